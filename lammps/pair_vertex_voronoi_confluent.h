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

#ifndef LMP_PAIR_VERTEX_VORONOI_CONFLUENT_H
#define LMP_PAIR_VERTEX_VORONOI_CONFLUENT_H

#include "pair_vertex_voronoi_model.h"

#include "tessera/energy.h"
#include "tessera/mesh.h"
#include "tessera/tessellation.h"

namespace LAMMPS_NS {

// Confluent 2D Voronoi cells: the Delaunay mesh of owned and ghost atoms,
// kept between neighbor-list builds and updated by flips (Mesh::advance).
class VertexConfluent : public VertexModel {
 public:
  VertexConfluent(LAMMPS *lmp, PairVertexVoronoi *p) : VertexModel(lmp, p) {}
  const char *name() const override { return "confluent 2d"; }
  void init() override;
  void compute(int eflag, int vflag) override;
  tessera::CellView &view() override { return cells_; }
  double memory_usage() const override;

 private:
  tessera::Tessellation tess;
  tessera::ConfluentCells cells_;
  tessera::Mesh mesh;
  tessera::CellPass cell_pass;    // the forces' per-cell half, run by Mesh::advance
  bool fuse_cells = false;        // hand cell_pass to the next Mesh::advance
  bigint mesh_ncalls = -1;        // neighbor->ncalls when the mesh was built
  bigint mesh_cells = -1;         // the pair style's list of cell atoms then
  void prepare();
  bool tessellate();    // true if the ghost shell had to grow
  void check_against_scratch(const tessera::Points &, const tessera::Region &, double);
  tessera::Region subdomain() const;
};

}    // namespace LAMMPS_NS

#endif
