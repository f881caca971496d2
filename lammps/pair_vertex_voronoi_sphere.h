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

#ifndef LMP_PAIR_VERTEX_VORONOI_SPHERE_H
#define LMP_PAIR_VERTEX_VORONOI_SPHERE_H

#include "pair_vertex_voronoi_model.h"

#include "tessera/sphere.h"
#include "tessera/sphere_cells.h"

#include <vector>

namespace LAMMPS_NS {

// Cells on a sphere ('surface sphere cx cy cz R' in 'dimension 3'): every
// rank gathers all cell centres, sorted by atom ID, tessellates the whole
// sphere and applies the forces of its owned atoms.
class VertexSphere : public VertexModel {
 public:
  VertexSphere(LAMMPS *lmp, PairVertexVoronoi *p) : VertexModel(lmp, p) {}
  const char *name() const override { return "sphere"; }
  void init() override;
  void compute(int eflag, int vflag) override;
  tessera::CellView &view() override { return cells_; }
  double memory_usage() const override;

 private:
  tessera::SphereTessellation tess;
  tessera::SphereCells cells_;
  double centre[3] = {0.0, 0.0, 0.0};
  double R = 1.0;
  // All cells, by ascending atom ID: positions, 0-based types, per-cell A0,
  // KA, KP, P0 (pcall[0..3], when d_area0, d_ka, d_kp, d_perim0 exist), IDs;
  // each owned atom's index among them, and each one's local index (-1: not
  // on this rank).
  static constexpr int NPC = 4;
  std::vector<double> xall, fall, eall;
  std::vector<double> pcall[NPC];
  bool has_pc[NPC] = {false, false, false, false};
  std::vector<int> typeall, owned, local;
  std::vector<long> ids;
  std::vector<tagint> tags;
  void gather();
  bool tessellate();    // true if the ghost shell had to grow
};

}    // namespace LAMMPS_NS

#endif
