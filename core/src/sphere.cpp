// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The Voronoi model on a sphere (sphere.h, doc/sphere.md).
//
// Triangulation.  The spherical Delaunay triangulation of points on a sphere
// is the convex hull of the points (a circle on the sphere is the sphere cut
// by a plane; a triangle's circumcircle cap is empty iff no point lies
// beyond its facet plane).  It is built by sphere_hull.cpp from the unit
// directions u_i as rounded to doubles, with exact predicates: the exact
// convex hull of the rounded directions, which is the spherical Delaunay
// triangulation of the directions they round.  The rounded directions are
// not exactly on the sphere, but a point can only fall inside the hull of
// the others if it is within about sqrt(eps) of another one (the sagitta of
// a cap of angular size d is d^2/2, against round-off of order eps),
// whatever the co-circularity; pairs closer than 2^-23 (a margin of 8 over
// sqrt(eps) = 2^-26) are refused, naming them.  Four or more co-circular
// points make one face of the hull, a polygon, which the hull splits into
// triangles in an order that depends on the insertion order; their poles
// coincide up to round-off and are merged below.
//
// Geometry.  Voronoi vertex of facet (a, b, c), counter-clockwise from
// outside: v = n/|n|, n = (u_b - u_a) x (u_c - u_a), its outward normal.  A
// cell's area is the fan of geodesic triangles (u_i, v_k, v_{k+1}) (a cell is
// spherically convex and contains its centre), each of solid angle
//   Omega = 2 atan2(D, S),  D = a . (b x c),  S = 1 + a.b + b.c + c.a
// (exact for unit vectors whose geodesic triangle has sides below pi); an
// edge's length is R atan2(|a x b|, a . b).
//
// Energy and forces: sphere_forces.cpp.

#include "tessera/sphere.h"

#include "point_name.h"
#include "sphere_hull.h"
#include "sphere_vec.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <numeric>
#include <sstream>

namespace tessera {

using namespace sphere_detail;

namespace {

// Closest two directions may be (chord on the unit sphere): 2^-23, eight
// times the sqrt(eps) under which round-off can hide a point inside the hull
// of the others (the file's header).
constexpr double kMinChord = 0x1p-23;

[[noreturn]] void throw_too_close(int i, int j, const std::vector<Vec3> &dir, const long *ids) {
  std::ostringstream s;
  s << "tessera: " << point_name(i, ids) << " and " << point_name(j, ids)
    << " project to the same point of the sphere to double precision (angular distance "
    << angle(vv(dir[i]), vv(dir[j])) << "; points closer than 2^-23 R = 1.2e-7 R cannot be"
       " triangulated)";
  throw Error(s.str());
}

// The nearest other point of i (brute force; for error messages only).
int nearest(int i, const std::vector<Vec3> &dir) {
  int best = -1;
  double best_angle = 10.0;
  for (int j = 0; j < static_cast<int>(dir.size()); ++j)
    if (j != i) {
      const double a = angle(vv(dir[i]), vv(dir[j]));
      if (a < best_angle) best_angle = a, best = j;
    }
  return best;
}

}  // namespace

Vec3 SphereTessellation::point(int i) const {
  const Vec3 &u = direction[i];
  return Vec3{centre.x + R * u.x, centre.y + R * u.y, centre.z + R * u.z};
}

Vec3 SphereTessellation::vertex(int t) const {
  const Vec3 &u = vertex_direction[t];
  return Vec3{centre.x + R * u.x, centre.y + R * u.y, centre.z + R * u.z};
}

int SphereTessellation::coordination_number(int c, double rel_tol) const {
  const int k0 = cell_offset[c], k1 = cell_offset[c + 1];
  if (k1 == k0) return 0;
  // The pair's own threshold (rel_tol times the geodesic distance of the
  // two centres), so that both cells of a pair agree.
  int z = 0;
  for (int k = k0; k < k1; ++k)
    if (edge_length[k] > rel_tol * R * angle(vv(direction[c]), vv(direction[cell_neighbor[k]]))) ++z;
  return z;
}

SphereTessellation tessellate_sphere(const Vec3 &centre, double R, const Points3 &pts,
                                     const long *ids, bool reference_hull) {
  if (!(std::isfinite(R) && R > 0.0)) {
    std::ostringstream s;
    s << "tessera: sphere radius must be positive and finite, got " << R;
    throw Error(s.str());
  }
  if (!(std::isfinite(centre.x) && std::isfinite(centre.y) && std::isfinite(centre.z)))
    throw Error("tessera: sphere centre must be finite");
  const int n = pts.n;
  if (n < 4) {
    std::ostringstream s;
    s << "tessera: a tessellation of the sphere needs at least 4 points, got " << n;
    throw Error(s.str());
  }

  SphereTessellation t;
  t.n_points = n;
  t.centre = centre;
  t.R = R;
  t.direction.resize(n);
  const V c = vv(centre);
  for (int i = 0; i < n; ++i) {
    const double *p = pts.p(i);
    if (!finite3(p)) throw Error("tessera: " + point_name(i, ids) + " has a non-finite coordinate");
    const V d = V{p[0], p[1], p[2]} - c;
    const double r = norm(d);
    if (!(r > 0.0))
      throw Error("tessera: " + point_name(i, ids) +
                  " is at the centre of the sphere: it has no direction to be projected along");
    t.direction[i] = to3((1.0 / r) * d);
  }

  // The hull of the rounded directions (sphere_hull.h): its errors are the
  // input's.
  std::vector<double> xyz(3 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    xyz[3 * i] = t.direction[i].x;
    xyz[3 * i + 1] = t.direction[i].y;
    xyz[3 * i + 2] = t.direction[i].z;
  }
  HullResult hull =
      sphere_hull(xyz.data(), n, reference_hull ? HullRoute::Conflict : HullRoute::Walk);
  switch (hull.status) {
  case HullResult::Equal:
    throw Error("tessera: " + point_name(hull.i, ids) + " and " + point_name(hull.j, ids) +
                " project to the same point of the sphere");
  case HullResult::Flat: {
    // Three distinct points of a sphere are never collinear, but their
    // roundings could be: all collinear counts as one plane too.
    std::ostringstream s;
    s << "tessera: all " << n
      << " points lie on one circle of the sphere (one plane; a great circle if it passes"
         " through the centre): their tessellation is degenerate";
    throw Error(s.str());
  }
  case HullResult::Hidden: {
    // Round-off put the point inside the hull of the others: it is within
    // about sqrt(eps) of its nearest point.
    const int i = hull.i, j = nearest(i, t.direction);
    throw_too_close(std::min(i, j), std::max(i, j), t.direction, ids);
  }
  case HullResult::Ok:
    break;
  }
  std::vector<std::array<int, 3>> &faces = hull.triangles;
  if (static_cast<long>(faces.size()) != 2L * n - 4 || hull.neighbors.size() != faces.size())
    throw Error("tessera: internal error: the triangulation of the points on the sphere is not a"
                " triangulated sphere");
  // Pairs closer than the precision bound (the nearest point is always a
  // Delaunay neighbour), so that both routes refuse the same inputs.
  for (const auto &f : faces)
    for (int m = 0; m < 3; ++m) {
      const int i = f[m], j = f[(m + 1) % 3];
      if (i < j && norm(vv(t.direction[i]) - vv(t.direction[j])) < kMinChord)
        throw_too_close(std::min(i, j), std::max(i, j), t.direction, ids);
    }
  // Counter-clockwise seen from outside, every point below or on each
  // triangle's plane (exactly: the hull turns its facets outwards).
  t.triangles = std::move(faces);

  const int nt = static_cast<int>(t.triangles.size());
  t.vertex_direction.resize(nt);
  t.circumradius.resize(nt);
  std::vector<double> rho(nt);
  for (int f = 0; f < nt; ++f) {
    const V a = vv(t.direction[t.triangles[f][0]]), b = vv(t.direction[t.triangles[f][1]]),
            cc = vv(t.direction[t.triangles[f][2]]);
    const V nn = cross(b - a, cc - a);
    const V v = (1.0 / norm(nn)) * nn;
    t.vertex_direction[f] = to3(v);
    rho[f] = angle(v, a);
    t.circumradius[f] = R * rho[f];
  }

  // Cells: around point i, triangle (i, x, y) leads from neighbour x to y,
  // and its neighbour across the edge y -> i is the next, (i, y, z).  Each
  // ring starts at the first triangle that has i as a corner.
  std::vector<int> count(n + 1, 0), first(n, -1);
  for (int f = 0; f < nt; ++f)
    for (int m = 0; m < 3; ++m) {
      const int i = t.triangles[f][m];
      ++count[i + 1];
      if (first[i] < 0) first[i] = f;
    }
  for (int i = 0; i < n; ++i) count[i + 1] += count[i];
  t.cell_offset = count;
  const int total = count[n];
  t.cell_vertex.resize(total);
  t.cell_neighbor.resize(total);
  t.edge_length.resize(total);
  t.area.assign(n, 0.0);
  t.perimeter.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    int f = first[i];
    for (int k = count[i]; k < count[i + 1]; ++k) {
      const auto &tri = t.triangles[f];
      const int m = tri[0] == i ? 0 : tri[1] == i ? 1 : 2;
      t.cell_vertex[k] = f;
      t.cell_neighbor[k] = tri[(m + 2) % 3];
      f = hull.neighbors[f][(m + 2) % 3];
    }
    if (f != first[i])
      throw Error("tessera: internal error: open ring of triangles around " + point_name(i, ids));
  }
  // Zero-length edges: the poles of nearly co-circular points (a multifold
  // vertex split by round-off or a tiny jitter), closer than 1e-10 of their
  // circumradius (or a few ulps).  The decision is the edge's own (both
  // cells see the same two poles), and the poles it joins become one: every
  // pole of such a cluster is moved onto their normalised mean, so that all
  // cells around it share one vertex.  Then the cells tile the sphere (areas
  // sum to 4 pi R^2 to round-off, no sliver between two cells left out of
  // both), and the geometry is the one the forces differentiate (the
  // cluster is one vertex there, sphere_forces.cpp).
  std::vector<char> zero(total, 0);
  {
    PoleSets poles(nt);
    auto root = [&](int x) { return poles.root(x); };
    bool any = false;
    for (int i = 0; i < n; ++i) {
      const int k0 = count[i], k1 = count[i + 1];
      for (int k = k0; k < k1; ++k) {
        const int ta = t.cell_vertex[k], tb = t.cell_vertex[k + 1 == k1 ? k0 : k + 1];
        const V va = vv(t.vertex_direction[ta]), vb = vv(t.vertex_direction[tb]);
        const double r = std::min(rho[ta], rho[tb]), limit = 1e-10 * r + 8.0 * DBL_EPSILON / r;
        // The angle is at least the chord, less round-off far below 1e-14:
        // a chord beyond twice the limit decides without the arc tangent.
        const V d = va - vb;
        if (dot(d, d) > (2.0 * limit + 1e-14) * (2.0 * limit + 1e-14)) continue;
        if (angle(va, vb) < limit) {
          zero[k] = 1;
          poles.join(ta, tb);
          any = true;
        }
      }
    }
    if (any) {
      std::vector<V> sum(nt, V{0.0, 0.0, 0.0});
      std::vector<int> members(nt, 0);
      for (int f = 0; f < nt; ++f) {
        add_to(sum[root(f)], vv(t.vertex_direction[f]));
        ++members[root(f)];
      }
      for (int f = 0; f < nt; ++f) {
        const int r = root(f);
        if (members[r] > 1) t.vertex_direction[f] = to3((1.0 / norm(sum[r])) * sum[r]);
      }
    }
  }
  // Each edge's arc once, for the first of its two cells (angle(a, b) and
  // angle(b, a) are the same double); by the triangulation's edge it crosses.
  std::vector<double> arc(3 * static_cast<size_t>(nt), -1.0);
  for (int i = 0; i < n; ++i) {
    const int k0 = count[i], k1 = count[i + 1];
    const V u = vv(t.direction[i]);
    double area = 0.0, perim = 0.0;
    for (int k = k0; k < k1; ++k) {
      const int kn = k + 1 == k1 ? k0 : k + 1;
      const int ta = t.cell_vertex[k], tb = t.cell_vertex[kn];
      const V va = vv(t.vertex_direction[ta]), vb = vv(t.vertex_direction[tb]);
      double l = 0.0;
      if (!zero[k]) {
        const auto &na = hull.neighbors[ta], &nb = hull.neighbors[tb];
        double &a = arc[3 * ta + (na[0] == tb ? 0 : na[1] == tb ? 1 : 2)];
        if (a < 0.0) {
          a = angle(va, vb);
          arc[3 * tb + (nb[0] == ta ? 0 : nb[1] == ta ? 1 : 2)] = a;
        }
        l = R * a;
      }
      t.edge_length[k] = l;
      perim += l;
      area += solid_angle(u, va, vb);  // (exactly 0 for a zero edge: va == vb)
    }
    t.area[i] = R * R * area;
    t.perimeter[i] = perim;
  }
  // Points on one circle that the rounding of their directions has lifted
  // off a common plane: the hull is flat to round-off, every pole is one of
  // the circle's two poles, and the cells are lunes of two edges.  A cell
  // with fewer than three edges of non-zero length exists only then.
  for (int i = 0; i < n; ++i)
    if (std::count_if(t.edge_length.begin() + count[i], t.edge_length.begin() + count[i + 1],
                      [](double l) { return l > 0.0; }) < 3) {
      std::ostringstream s;
      s << "tessera: all " << n
        << " points lie on one circle of the sphere (to round-off; a great circle if its plane"
           " passes through the centre): their tessellation is degenerate";
      throw Error(s.str());
    }
  return t;
}

}  // namespace tessera
