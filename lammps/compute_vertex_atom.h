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
ComputeStyle(vertex/atom,ComputeVertexAtom);
// clang-format on
#else

#ifndef LMP_COMPUTE_VERTEX_ATOM_H
#define LMP_COMPUTE_VERTEX_ATOM_H

#include "compute.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeVertexAtom : public Compute {
 public:
  ComputeVertexAtom(class LAMMPS *, int, char **);
  ~ComputeVertexAtom() override;
  void init() override;
  void compute_peratom() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double memory_usage() override;

 protected:
  int nmax;
  double **values;            // per-atom output, nmax x NCOLS
  std::vector<double> vel;    // stride-3 velocities of owned and ghost atoms
  std::vector<double> coordination, orientation;
  class CellSource *pair;

  void check_cells();
  void communicate_velocities();
};

}    // namespace LAMMPS_NS

#endif
#endif
