/* ----------------------------------------------------------------------
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

   The pair style that makes cells, for the computes and fixes that read
   them (see cell_source.h).
------------------------------------------------------------------------- */

#include "cell_source.h"

#include "force.h"
#include "lammps.h"
#include "pair.h"
#include "pair_vertex_polygon.h"
#include "pair_vertex_voronoi.h"

using namespace LAMMPS_NS;

CellSource *CellSource::find(LAMMPS *lmp)
{
  for (const char *style : {"vertex/voronoi", "vertex/polygon"}) {
    Pair *p = lmp->force->pair_match(style, 1);
    if (p) {
      int dim = 0;
      return static_cast<CellSource *>(p->extract(extract_name, dim));
    }
  }
  return nullptr;
}

/* Each pair style's side of the interface, forwarding to its public members.
   One virtual call per query, as when the pair styles derived from CellSource
   themselves (they no longer do, so that their headers need no Tessera type). */

namespace {

// What both pair styles answer alike.
template <class Pair> class Forward : public CellSource {
 public:
  explicit Forward(Pair &pair) : p(pair) {}
  const tessera::CellView &cells() const override { return p.cells(); }
  bigint cells_step() const override { return p.cells_step(); }
  void require_current_cells(const std::string &who) override { p.require_current_cells(who); }
  tessera::Contacts force_contacts() const override { return p.force_contacts(); }
  double force_boundary(int c) const override { return p.force_boundary(c); }
  bigint force_count() const override { return p.force_count(); }
  bigint compute_count() const override { return p.compute_count(); }
  bool is_cell_type(int type) const override { return p.is_cell_type(type); }

 protected:
  Pair &p;
};

class VoronoiSource final : public Forward<PairVertexVoronoi> {
 public:
  using Forward::Forward;
  double finite_radius() const override { return p.finite_radius(); }
  bool on_sphere() const override { return p.on_sphere(); }
  const double *sphere_centre() const override { return p.sphere_centre(); }
};

class PolygonSource final : public Forward<PairVertexPolygon> {
 public:
  using Forward::Forward;
  bool cells_are_vertices() const override { return true; }
};

}    // namespace

std::unique_ptr<CellSource> CellSource::of(PairVertexVoronoi &pair)
{
  return std::unique_ptr<CellSource>(new VoronoiSource(pair));
}

std::unique_ptr<CellSource> CellSource::of(PairVertexPolygon &pair)
{
  return std::unique_ptr<CellSource>(new PolygonSource(pair));
}
