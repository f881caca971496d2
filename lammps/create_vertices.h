/* -*- c++ -*- ----------------------------------------------------------
   TESSERA package for LAMMPS: vertex models of cell tissues
   LAMMPS: https://www.lammps.org/

   Copyright (2026) the Tessera developers.  This software is distributed
   under the GNU General Public License, version 2 or (at your option) any
   later version.
   SPDX-License-Identifier: GPL-2.0-or-later

   See the README file in the package's directory (src/TESSERA).
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing authors: the Tessera developers
------------------------------------------------------------------------- */

#ifdef COMMAND_CLASS
// clang-format off
CommandStyle(create_vertices,CreateVertices);
// clang-format on
#else

#ifndef LMP_CREATE_VERTICES_H
#define LMP_CREATE_VERTICES_H

#include "command.h"

namespace LAMMPS_NS {

/* create_vertices group-ID vertex-type [maxsides W]: turns a tissue of cell
   centres (the group's atoms) into a vertex tissue for pair_style
   vertex/polygon.  The Voronoi polygons of the centres in the periodic box
   become the cells' rings (i_vring of fix vring, defined here if it is not),
   and one vertex atom of vertex-type is created per Voronoi vertex, with IDs
   after the largest one in an order that does not depend on the number of
   ranks. */

class CreateVertices : public Command {
 public:
  CreateVertices(class LAMMPS *lmp) : Command(lmp) {}
  void command(int, char **) override;
};

}    // namespace LAMMPS_NS

#endif
#endif
