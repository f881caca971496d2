/* -*- c++ -*- ----------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later
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
