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
ComputeStyle(vertex/tissue,ComputeVertexTissue);
// clang-format on
#else

#ifndef LMP_COMPUTE_VERTEX_TISSUE_H
#define LMP_COMPUTE_VERTEX_TISSUE_H

#include "compute.h"

#include <vector>

namespace LAMMPS_NS {

class ComputeVertexTissue : public Compute {
 public:
  ComputeVertexTissue(class LAMMPS *, int, char **);
  ~ComputeVertexTissue() override;
  void init() override;
  void compute_vector() override;
  void set_arrays(int) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double memory_usage() override;

  // Neighbour tags remembered per atom for counting neighbour exchanges.
  static constexpr int MAXNEIGH = 24;

 protected:
  char *id_fix;
  class Fix *fix;    // the internal store (tessera_compat::FixStorePerAtom)
  class CellSource *pair;
  int warned_overflow;

  void check_cells();
  double count_multifold();
  double rosette;    // > 0: count clusters of vertices joined by junctions shorter than this
  std::vector<int> cluster_offset, cluster_members;
  double count_new_neighbors();
  void junction_lengths(double &het, double &total);
  bigint vector_of = -1;    // pair's compute_count() of the last global vector
  void neighbor_tags(int, std::vector<tagint> &);

  // Forward communication: one flag per atom.
  std::vector<double> flag;    // per owned and ghost atom (see count_new_neighbors)
  void communicate_flags();
  std::vector<tagint> present;    // sorted tags of the owned and ghost cells with a memory
};

}    // namespace LAMMPS_NS

#endif
#endif
