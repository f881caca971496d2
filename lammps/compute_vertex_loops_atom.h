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

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(vertex/loops/atom,ComputeVertexLoopsAtom);
// clang-format on
#else

#ifndef LMP_COMPUTE_VERTEX_LOOPS_ATOM_H
#define LMP_COMPUTE_VERTEX_LOOPS_ATOM_H

#include "compute_vertex_loops.h"

namespace LAMMPS_NS {

class ComputeVertexLoopsAtom : public ComputeVertexLoops {
 public:
  ComputeVertexLoopsAtom(class LAMMPS *, int, char **);
  ~ComputeVertexLoopsAtom() override;
  void compute_peratom() override;
  double memory_usage() override;

 protected:
  int nmax_atom;
  double **values;    // per-atom output, nmax_atom x 3
};

}    // namespace LAMMPS_NS

#endif
#endif
