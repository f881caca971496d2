// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The Voronoi model on a sphere (sphere.h, doc/sphere.md).
//
// Triangulation.  The spherical Delaunay triangulation of points on a sphere
// is the convex hull of the points (a circle on the sphere is the sphere cut
// by a plane; a triangle's circumcircle cap is empty iff no point lies
// beyond its facet plane).  It is built from the unit directions u_i as
// rounded to doubles, with exact predicates, by CGAL's Delaunay
// triangulation on the sphere (Caroli et al., SEA 2010: the predicates are
// 3D orientations, so the result is the hull of the rounded directions), or
// by CGAL's convex hull when the points lie in one hemisphere.  The rounded
// directions are not exactly on the sphere, but a point can only fall
// inside the hull of the others if it is within about sqrt(eps) of another
// one (the sagitta of a cap of angular size d is d^2/2, against round-off
// of order eps), whatever the co-circularity; pairs closer than 2^-23 (the
// bound of CGAL's triangulation on the sphere) are refused, naming them.
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
#include "sphere_vec.h"

#include <CGAL/Delaunay_triangulation_on_sphere_2.h>
#include <CGAL/Delaunay_triangulation_on_sphere_traits_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_on_sphere_face_base_2.h>
#include <CGAL/Triangulation_on_sphere_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/hilbert_sort_on_sphere.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace tessera {

using namespace sphere_detail;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = K::Point_3;

// Closest two directions may be (chord on the unit sphere), the bound under
// which CGAL's triangulation on the sphere guarantees that no point rounded
// to doubles near the sphere is hidden by round-off: 2^-23.
constexpr double kMinChord = 0x1p-23;

std::array<double, 3> key_of(const P3 &p) { return {p.x(), p.y(), p.z()}; }
struct KeyHash {
  static uint64_t mix(uint64_t z) {  // splitmix64's finaliser
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  size_t operator()(const std::array<double, 3> &a) const {
    uint64_t b[3];
    std::memcpy(b, a.data(), sizeof b);
    return mix(b[0] + mix(b[1] + mix(b[2])));
  }
};
using IndexMap = std::unordered_map<std::array<double, 3>, int, KeyHash>;

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

// CGAL's Delaunay triangulation on the sphere (Caroli et al.'s predicates,
// points inserted along a Hilbert curve on the sphere: about eight times
// faster than the hull at N = 1e5).  Returns false, leaving the work to the
// hull, when it does not give a full triangulation of the sphere: points all in one
// hemisphere (CGAL then fills the rest with "ghost" faces, which are not
// hull facets) or a direction CGAL finds too far off the sphere.
struct VertexIndex {
  int i = -1;
};
using SphereTraits = CGAL::Delaunay_triangulation_on_sphere_traits_2<K>;
using SVb = CGAL::Triangulation_vertex_base_with_info_2<VertexIndex, SphereTraits,
                                                        CGAL::Triangulation_on_sphere_vertex_base_2<SphereTraits>>;
using SFb = CGAL::Triangulation_on_sphere_face_base_2<SphereTraits>;
using STds = CGAL::Triangulation_data_structure_2<SVb, SFb>;
using SDT = CGAL::Delaunay_triangulation_on_sphere_2<SphereTraits, STds>;

bool delaunay_on_sphere(const std::vector<P3> &P, const IndexMap &index_of,
                        const std::vector<Vec3> &dir, const long *ids,
                        std::vector<std::array<int, 3>> &faces) {
  std::vector<P3> order(P);
  CGAL::hilbert_sort_on_sphere(order.begin(), order.end(), 1.0, P3(0.0, 0.0, 0.0));
  SDT dt(SphereTraits(P3(0.0, 0.0, 0.0), 1.0));
  SDT::Face_handle hint;
  for (const P3 &p : order) {
    const int i = index_of.at(key_of(p));
    const SDT::Vertex_handle v = dt.insert(p, hint);
    if (v == SDT::Vertex_handle()) return false;
    if (v->info().i >= 0) {
      // CGAL took the point for an existing vertex: a pair closer than the
      // precision limit is named; otherwise (CGAL's own criterion, on points
      // that are not close) the hull decides.
      const int j = v->info().i;
      if (norm(vv(dir[i]) - vv(dir[j])) < kMinChord) throw_too_close(std::min(i, j), std::max(i, j), dir, ids);
      return false;
    }
    v->info().i = i;
    hint = v->face();
  }
  if (dt.dimension() != 2 || static_cast<int>(dt.number_of_vertices()) != static_cast<int>(P.size()))
    return false;
  faces.clear();
  for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f) {
    if (dt.is_ghost(f)) return false;
    faces.push_back({f->vertex(0)->info().i, f->vertex(1)->info().i, f->vertex(2)->info().i});
  }
  return true;
}

// The convex hull (CGAL's quickhull, exact predicates): right for any
// points, also all in one hemisphere.  A point the rounding of directions
// put inside the hull of the others is named with its nearest point.
void convex_hull(const std::vector<P3> &P, const IndexMap &index_of, const std::vector<Vec3> &dir,
                 const long *ids, std::vector<std::array<int, 3>> &faces) {
  const int n = static_cast<int>(P.size());
  // Into a Surface_mesh: the polygon-soup overload of convex_hull_3 drops an
  // extreme point of some exactly convex inputs (12 icosahedron directions
  // gave 11 hull points), which the mesh output keeps.
  CGAL::Surface_mesh<P3> sm;
  CGAL::convex_hull_3(P.begin(), P.end(), sm);
  std::vector<int> hull_index(sm.number_of_vertices() + sm.number_of_removed_vertices(), -1);
  std::vector<char> on_hull(n, 0);
  for (const auto v : sm.vertices()) {
    const auto it = index_of.find(key_of(sm.point(v)));
    if (it == index_of.end()) throw Error("tessera: internal error: a hull vertex is no input point");
    hull_index[v.idx()] = it->second;
    on_hull[it->second] = 1;
  }
  for (int i = 0; i < n; ++i)
    if (!on_hull[i]) {
      const int j = nearest(i, dir);
      throw_too_close(std::min(i, j), std::max(i, j), dir, ids);
    }
  faces.clear();
  for (const auto f : sm.faces()) {
    std::array<int, 3> tri{{-1, -1, -1}};
    int m = 0;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (m == 3) throw Error("tessera: internal error: a hull facet is not a triangle");
      tri[m++] = hull_index[v.idx()];
    }
    if (m != 3) throw Error("tessera: internal error: a hull facet is not a triangle");
    faces.push_back(tri);
  }
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

  // Two points with one projection.
  {
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    auto key = [&](int i) {
      const Vec3 &u = t.direction[i];
      return std::array<double, 3>{u.x, u.y, u.z};
    };
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const auto ka = key(a), kb = key(b);
      return ka != kb ? ka < kb : a < b;
    });
    for (int k = 1; k < n; ++k)
      if (key(order[k]) == key(order[k - 1])) {
        const int a = std::min(order[k], order[k - 1]), b = std::max(order[k], order[k - 1]);
        throw Error("tessera: " + point_name(a, ids) + " and " + point_name(b, ids) +
                    " project to the same point of the sphere");
      }
  }

  std::vector<P3> P(n);
  for (int i = 0; i < n; ++i) P[i] = P3(t.direction[i].x, t.direction[i].y, t.direction[i].z);

  // Not all on one plane (one circle of the sphere).  Three distinct points
  // of a sphere are never collinear, but their roundings could be.
  int i2 = -1, i3 = -1;
  for (int i = 2; i < n && i2 < 0; ++i)
    if (!CGAL::collinear(P[0], P[1], P[i])) i2 = i;
  if (i2 >= 0)
    for (int i = 2; i < n && i3 < 0; ++i)
      if (i != i2 && CGAL::orientation(P[0], P[1], P[i2], P[i]) != CGAL::COPLANAR) i3 = i;
  if (i3 < 0) {
    std::ostringstream s;
    s << "tessera: all " << n
      << " points lie on one circle of the sphere (one plane; a great circle if it passes"
         " through the centre): their tessellation is degenerate";
    throw Error(s.str());
  }

  // Point indices by their (rounded) directions, which are distinct now.
  std::unordered_map<std::array<double, 3>, int, KeyHash> index_of;
  index_of.reserve(2 * n);
  for (int i = 0; i < n; ++i) index_of.emplace(key_of(P[i]), i);

  std::vector<std::array<int, 3>> faces;
  if (reference_hull || !delaunay_on_sphere(P, index_of, t.direction, ids, faces))
    convex_hull(P, index_of, t.direction, ids, faces);
  if (static_cast<long>(faces.size()) != 2L * n - 4)
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

  t.triangles = std::move(faces);
  // Orientation: counter-clockwise seen from outside, i.e. every other point
  // below the facet.  CGAL's faces are consistently oriented; test one.
  // The point farthest from the facet's plane decides (a point on the plane
  // to round-off, as the fourth corner of a cube's face, may lie on either
  // side of it and would turn every triangle the wrong way).
  {
    const auto &f0 = t.triangles[0];
    const V a = vv(t.direction[f0[0]]);
    const V nrm = cross(vv(t.direction[f0[1]]) - a, vv(t.direction[f0[2]]) - a);
    int far = -1;
    double best = -1.0;
    for (int i = 0; i < n; ++i)
      if (i != f0[0] && i != f0[1] && i != f0[2]) {
        const double h = std::fabs(dot(nrm, vv(t.direction[i]) - a));
        if (h > best) best = h, far = i;
      }
    const CGAL::Orientation o = CGAL::orientation(P[f0[0]], P[f0[1]], P[f0[2]], P[far]);
    if (o == CGAL::POSITIVE)
      for (auto &tri : t.triangles) std::swap(tri[1], tri[2]);
  }

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

  // Cells: around point i, triangle (i, x, y) leads from neighbour x to y.
  std::vector<int> count(n + 1, 0);
  for (const auto &tri : t.triangles)
    for (int m = 0; m < 3; ++m) ++count[tri[m] + 1];
  for (int i = 0; i < n; ++i) count[i + 1] += count[i];
  t.cell_offset = count;
  const int total = count[n];
  std::vector<int> ex(total), ey(total), etri(total);
  {
    std::vector<int> fill(count.begin(), count.end() - 1);
    for (int f = 0; f < nt; ++f)
      for (int m = 0; m < 3; ++m) {
        const int i = t.triangles[f][m];
        const int k = fill[i]++;
        ex[k] = t.triangles[f][(m + 1) % 3];
        ey[k] = t.triangles[f][(m + 2) % 3];
        etri[k] = f;
      }
  }
  t.cell_vertex.resize(total);
  t.cell_neighbor.resize(total);
  t.edge_length.resize(total);
  t.area.assign(n, 0.0);
  t.perimeter.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const int k0 = count[i], k1 = count[i + 1];
    // Chain the triangles: the next one starts where this one ends.
    int cur = k0;
    for (int k = k0; k < k1; ++k) {
      t.cell_vertex[k] = etri[cur];
      t.cell_neighbor[k] = ey[cur];
      if (k + 1 == k1) break;
      int next = -1;
      for (int q = k0; q < k1; ++q)
        if (ex[q] == ey[cur]) {
          next = q;
          break;
        }
      if (next < 0) throw Error("tessera: internal error: open ring of triangles around " +
                                point_name(i, ids));
      cur = next;
    }
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
        const double th = angle(vv(t.vertex_direction[ta]), vv(t.vertex_direction[tb]));
        const double r = std::min(rho[ta], rho[tb]);
        if (th < 1e-10 * r + 8.0 * DBL_EPSILON / r) {
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
  for (int i = 0; i < n; ++i) {
    const int k0 = count[i], k1 = count[i + 1];
    const V u = vv(t.direction[i]);
    double area = 0.0, perim = 0.0;
    for (int k = k0; k < k1; ++k) {
      const int kn = k + 1 == k1 ? k0 : k + 1;
      const int ta = t.cell_vertex[k], tb = t.cell_vertex[kn];
      const V va = vv(t.vertex_direction[ta]), vb = vv(t.vertex_direction[tb]);
      const double l = zero[k] ? 0.0 : R * angle(va, vb);
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
    if (t.coordination_number(i, 0.0) < 3) {
      std::ostringstream s;
      s << "tessera: all " << n
        << " points lie on one circle of the sphere (to round-off; a great circle if its plane"
           " passes through the centre): their tessellation is degenerate";
      throw Error(s.str());
    }
  return t;
}

}  // namespace tessera
