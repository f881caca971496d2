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
  // per_atom: the constructor of compute vertex/loops/atom (the same loops,
  // output per atom instead of the local array and global vector).
  ComputeVertexLoops(class LAMMPS *, int, char **, bool per_atom);
  int nmax;         // rows allocated
  double **rows;    // one row per loop (on rank 0)
  class CellSource *pair;
  bigint loops_of;    // pair's compute_count() of the loops found last
  int warned;
  double min_area;              // holes below this area are left out of the global values
  std::vector<double> table;    // the loops, 7 values each (every rank)
  // With want_chains: each loop's arcs in walking order, unwrapped, on
  // every rank: chain_arcs holds CHAIN_DOUBLES values per arc (cell ID,
  // centre x y, radius, phi, theta), loop l's from chain_begin[l].
  bool want_chains;
  std::vector<double> chain_arcs;
  std::vector<int> chain_begin;
  static constexpr int CHAIN_DOUBLES = 6;
  void find_loops();
  void sphere_error();    // stops: a sphere has no free boundary
};

}    // namespace LAMMPS_NS

#endif
#endif
