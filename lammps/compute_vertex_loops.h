/* -*- c++ -*- ----------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(vertex/loops,ComputeVertexLoops);
// clang-format on
#else

#ifndef LMP_COMPUTE_VERTEX_LOOPS_H
#define LMP_COMPUTE_VERTEX_LOOPS_H

#include "compute.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeVertexLoops : public Compute {
 public:
  ComputeVertexLoops(class LAMMPS *, int, char **);
  ~ComputeVertexLoops() override;
  void init() override;
  void compute_vector() override;
  void compute_local() override;
  double memory_usage() override;

 protected:
  int nmax;          // rows allocated
  double **rows;     // one row per loop (on rank 0)
  class CellSource *pair;
  bigint loops_of;   // pair's compute_count() of the loops found last
  int warned;
  double min_area;    // holes below this area are left out of the global values
  std::vector<double> table;    // the loops, 7 values each (every rank)
  void find_loops();
  void sphere_error();    // stops: a sphere has no free boundary
};

}    // namespace LAMMPS_NS

#endif
#endif
