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

#ifndef LMP_PAIR_VERTEX_VORONOI_3D_H
#define LMP_PAIR_VERTEX_VORONOI_3D_H

#include "pair_vertex_voronoi_model.h"

#include "tessera/mesh3d.h"
#include "tessera/voronoi3d.h"

namespace LAMMPS_NS {

// 3D Voronoi polyhedra ('dimension 3'): the tetrahedralisation of owned and
// ghost atoms, kept between neighbor-list builds and repaired by flips.
class Vertex3d : public VertexModel {
 public:
  Vertex3d(LAMMPS *lmp, PairVertexVoronoi *p) : VertexModel(lmp, p) {}
  const char *name() const override { return "3d"; }
  void init() override;
  void compute(int eflag, int vflag) override;
  tessera::CellView &view() override { return cells_; }
  double memory_usage() const override;

 private:
  tessera::Tessellation3 tess3;
  tessera::Mesh3 mesh;        // kept between neighbor-list builds, repaired by flips
  bigint mesh_ncalls = -1;    // neighbor->ncalls when the mesh was built
  bigint mesh_cells = -1;     // the pair style's list of cell atoms then
  tessera::Cells3 cells_;
  bool tessellate();    // true if the ghost shell had to grow
  tessera::Region3 subdomain() const;
  void check_against_scratch(const tessera::Points3 &, const tessera::Region3 &, double);
};

}    // namespace LAMMPS_NS

#endif
