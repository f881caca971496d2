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

#ifndef LMP_PAIR_VERTEX_VORONOI_FINITE_H
#define LMP_PAIR_VERTEX_VORONOI_FINITE_H

#include "pair_vertex_voronoi_model.h"

#include "tessera/finite.h"
#include "tessera/tessellation.h"

namespace LAMMPS_NS {

// Finite 2D Voronoi cells ('radius r'): each owned cell is its Voronoi cell
// cut by the disc of radius r, bounded by contact edges and free arcs.
class VertexFinite : public VertexModel {
 public:
  VertexFinite(LAMMPS *lmp, PairVertexVoronoi *p) : VertexModel(lmp, p) {}
  const char *name() const override { return "finite 2d"; }
  void init() override;
  void compute(int eflag, int vflag) override;
  tessera::CellView &view() override { return cells_; }
  double memory_usage() const override;

 private:
  tessera::FiniteTessellation ftess;
  tessera::Tessellation contacts;    // the contact edges as neighbour lists
  tessera::FiniteCells cells_;
};

}    // namespace LAMMPS_NS

#endif
