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
ComputeStyle(vertex/local,ComputeVertexLocal);
// clang-format on
#else

#ifndef LMP_COMPUTE_VERTEX_LOCAL_H
#define LMP_COMPUTE_VERTEX_LOCAL_H

#include "compute.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeVertexLocal : public Compute {
 public:
  ComputeVertexLocal(class LAMMPS *, int, char **);
  ~ComputeVertexLocal() override;
  void init() override;
  void compute_local() override;
  double memory_usage() override;

 protected:
  int nmax;         // rows allocated
  double **rows;    // nmax x 7: cell ID, neighbour ID, x1 y1 x2 y2, length
  class CellSource *pair;
  std::vector<double> flat;    // the rows of this step, row-major
};

}    // namespace LAMMPS_NS

#endif
#endif
