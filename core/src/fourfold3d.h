// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Four-fold Voronoi edges in 3D (four coplanar, co-circular centres: every
// square of a simple cubic lattice): how the builders find them and how
// compute_forces_3d takes the mean of the two branches there (doc/model.md,
// "Four-fold edges (3D)").  Internal to the core (not installed).
#pragma once

#include "tessera/voronoi3d.h"

#include "vec3_detail.h"

#include <unordered_map>
#include <vector>

namespace tessera {
namespace detail3 {

// A point within this fraction of a sphere's radius counts as on it (the
// slivers' threshold of voronoi3d.cpp); plus the round-off of coordinates of
// magnitude |x| (a few ulps of it).
constexpr double kFourFoldTol = 1e-8;
constexpr double kFourFoldUlps = 1e-13;
// Tetrahedra flatter than this are slivers (voronoi3d.cpp, kSliver).
constexpr double kFourFoldSliver = 1e-6;

// The adjacency of a builder's tetrahedra (CGAL's cells, Mesh3's arrays),
// as opaque ids.  Tetrahedron v of the Tessellation3 has id(v).
class TetGraph {
public:
  virtual ~TetGraph() = default;
  virtual long id(int v) = 0;
  // The neighbour across the facet opposite corner k, or -1 (none, or a
  // tetrahedron with the point at infinity or a far point).
  virtual long neighbor(long g, int k) = 0;
  // The corners of g (-1 for the point at infinity or a far point).
  virtual void corners(long g, int q[4]) = 0;
  // The corner of the neighbour across facet k that is not in g, or -1.
  virtual int opposite(long g, int k) = 0;
  // The neighbour of t's tetrahedron v across the facet opposite corner k
  // as an index into t.tets; -1 if it is not one of them, -2 if there is
  // none (or it is CGAL's infinite cell).
  virtual int t_neighbor(int v, int k) = 0;
};

// Fills t.fourfold from the owned cells' face rings: a transition between
// consecutive ring tetrahedra with different circumcentres, where one of
// them has a facet neighbour on its circumsphere (a co-spherical cluster)
// or is a sliver, is a four-fold edge when exactly four points of the two
// tetrahedra's clusters lie on both circumspheres.  Generic configurations
// pay one distance per tetrahedron facet.
void find_fourfold_edges(Tessellation3 &t, const Points3 &pts, TetGraph &g);

// The four-fold edges seen from the owned cells: per ordered pair (owned
// cell, neighbour) the edges it is a side or a diagonal of.
class FourFoldIndex {
public:
  FourFoldIndex(const Tessellation3 &t, const Points3 &pts);
  bool empty() const { return roles_.empty(); }
  struct Role {
    int edge;      // index in t.fourfold
    int corner;    // the owned cell's corner (0..3)
    bool diagonal; // the pair is a diagonal (else a side)
  };
  // Roles of the pair (c, nb) (nullptr and n = 0 if none).
  const Role *roles(int c, int nb, int *n) const;
  // The edges owned cell c is a corner of.
  const Role *corners_of(int c, int *n) const;
  // Whether point h lies on the axis of edge e (equidistant from its four
  // corners).
  bool on_axis(int e, V3 h) const;
  // Whether tetrahedron v has the four corners of edge e.
  bool is_square_tet(int e, int v) const;
  double tol(int e) const { return tol_[e]; }

private:
  const Tessellation3 &t_;
  const Points3 &pts_;
  std::vector<double> tol_;
  std::unordered_map<long long, std::vector<Role>> roles_;
  std::unordered_map<int, std::vector<Role>> corners_;
};

// The gradient piece w (dE/dP, perpendicular to a Voronoi edge whose end P
// is the circumcentre of a tetrahedron with the triangle (i0, i1, i2)) sent
// to the triangle's three points through the in-plane motion of P, which
// depends on them alone: add(point, force) with weight times the force.
template <class Add>
void triangle_route(const Points3 &pts, V3 w, V3 P, int i0, int i1, int i2, double weight, Add add) {
  const V3 x0 = load(pts, i0), x1 = load(pts, i1), x2 = load(pts, i2);
  const V3 e1 = x1 - x0, e2 = x2 - x0;
  const V3 nt = cross(e1, e2);
  const double nn = dot(nt, nt);
  const V3 wp = w - (dot(w, nt) / nn) * nt;
  const double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
  const double b1 = dot(e1, wp), b2 = dot(e2, wp);
  const double det = g11 * g22 - g12 * g12;
  const double l1 = (g22 * b1 - g12 * b2) / det, l2 = (g11 * b2 - g12 * b1) / det;
  // (x_m - x0) . dP = (x_m - P) . dx_m - (x0 - P) . dx0, m = 1, 2.
  add(i1, (-weight * l1) * (x1 - P));
  add(i2, (-weight * l2) * (x2 - P));
  add(i0, (weight * (l1 + l2)) * (x0 - P));
}

}  // namespace detail3
}  // namespace tessera
