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
// Gradient.  A and P are functions of the Voronoi vertices only (the fan's
// apex does not change the area), so dE/du_p comes from dE/dv only.  The
// formulas above extend off the unit sphere; only tangent derivatives are
// used, the extension does not matter:
//   dOmega/db = 2 [S (c x a) - D (a + c)] / (S^2 + D^2),
//   dOmega/dc = 2 [S (a x b) - D (a + b)] / (S^2 + D^2),
//   dtheta/da = -(b - (a.b) a) / |a x b|   (theta = angle(a, b)),
// then through v = n/|n|: g_n = (I - v v^T) g_v / |n|, and since
// dn = du_a x (u_b - u_c) + du_b x (u_c - u_a) + du_c x (u_a - u_b),
//   dE/du_a = (u_b - u_c) x g_n  (and cyclically),
// and finally F_p = -(I - u_p u_p^T) dE/du_p / R.
//
// Multifold vertices: the mean over the fan triangulations of the ring, as
// in the plane (energy.cpp), with two changes for the sphere: a zero-length
// edge's direction at V, for the neighbour q, is V x (u_q - u_c) normalised
// (along the bisecting great circle), and the zero-area fan triangles
// (u, V, V) between two poles at V keep their solid angle's derivative
// (+-2 (u x V) / (2 + 2 u.V)), which cancels only between two inner poles.

#include "tessera/sphere.h"

#include "point_name.h"

#include <CGAL/Delaunay_triangulation_on_sphere_2.h>
#include <CGAL/Delaunay_triangulation_on_sphere_traits_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_on_sphere_face_base_2.h>
#include <CGAL/Triangulation_on_sphere_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
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

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = K::Point_3;

struct V {
  double x, y, z;
};
inline V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V cross(V a, V b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(V a) { return std::sqrt(dot(a, a)); }
inline V vv(const Vec3 &a) { return {a.x, a.y, a.z}; }
inline Vec3 to3(V a) { return Vec3{a.x, a.y, a.z}; }
inline void add_to(V &a, V b) { a = a + b; }

// Angle between two (unit or not) vectors, accurate also near 0 and pi.
inline double angle(V a, V b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }

// Solid angle of the geodesic triangle of unit vectors a, b, c (signed:
// positive when counter-clockwise seen from outside).
inline double solid_angle(V a, V b, V c) {
  const double D = dot(a, cross(b, c));
  const double S = 1.0 + dot(a, b) + dot(b, c) + dot(c, a);
  return 2.0 * std::atan2(D, S);
}

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
// points inserted along a Hilbert curve on the sphere: about ten times
// faster than the hull).  Returns false, leaving the work to the hull, when
// it does not give a full triangulation of the sphere: points all in one
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
    if (v->info().i >= 0) throw_too_close(std::min(i, v->info().i), std::max(i, v->info().i), dir, ids);
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
  std::vector<P3> hull_points;
  std::vector<std::array<int, 3>> hf;
  CGAL::convex_hull_3(P.begin(), P.end(), hull_points, hf);
  std::vector<int> hull_index(hull_points.size());
  std::vector<char> on_hull(n, 0);
  for (size_t h = 0; h < hull_points.size(); ++h) {
    const auto it = index_of.find(key_of(hull_points[h]));
    if (it == index_of.end()) throw Error("tessera: internal error: a hull vertex is no input point");
    hull_index[h] = it->second;
    on_hull[it->second] = 1;
  }
  for (int i = 0; i < n; ++i)
    if (!on_hull[i]) {
      const int j = nearest(i, dir);
      throw_too_close(std::min(i, j), std::max(i, j), dir, ids);
    }
  faces.resize(hf.size());
  for (size_t f = 0; f < hf.size(); ++f)
    for (int m = 0; m < 3; ++m) faces[f][m] = hull_index[hf[f][m]];
}

bool finite3(const double *p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

double cell_energy_of(const SphereTessellation &t, int c, const int *type, const Model &m) {
  const int tc = type[c];
  const CellType &ct = m.types[tc];
  const double dA = t.area[c] - m.area0_of(c, tc);
  double e = 0.5 * ct.K * dA * dA + 0.5 * ct.Gamma * t.perimeter[c] * t.perimeter[c];
  double lsum = 0.0;
  for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
    lsum += m.lambda_of(tc, type[t.cell_neighbor[k]]) * t.edge_length[k];
  return e + m.tension_weight() * lsum;
}

void check_types(const SphereTessellation &t, const int *type, const Model &model) {
  model.validate();
  for (int p = 0; p < t.n_points; ++p)
    if (type[p] < 0 || type[p] >= model.ntypes()) {
      std::ostringstream s;
      s << "tessera: point " << p << " has type " << type[p] << ", outside [0, "
        << model.ntypes() << ")";
      throw Error(s.str());
    }
}

// dE/dv at the pole of the counter-clockwise triangle (A, B, C) of unit
// directions, moved onto the three points as forces (appended to fc, fp).
void push_pole(const SphereTessellation &t, int A, int B, int C, V g, std::vector<V> &fc,
               std::vector<int> &fp) {
  const V ua = vv(t.direction[A]), ub = vv(t.direction[B]), uc = vv(t.direction[C]);
  const V nn = cross(ub - ua, uc - ua);
  const double nlen = norm(nn);
  const V v = (1.0 / nlen) * nn;
  const V gn = (1.0 / nlen) * (g - dot(g, v) * v);
  const V du[3] = {cross(ub - uc, gn), cross(uc - ua, gn), cross(ua - ub, gn)};
  const int pq[3] = {A, B, C};
  for (int q = 0; q < 3; ++q) {
    const V up = vv(t.direction[pq[q]]);
    fc.push_back((-1.0 / t.R) * (du[q] - dot(du[q], up) * up));
    fp.push_back(pq[q]);
  }
}

// Multifold vertices: groups of triangles joined by zero-length edges, and
// the ring of points around each, counter-clockwise seen from outside.
struct Multifold {
  std::vector<int> group;   // per triangle: its group, or -1 (alone)
  std::vector<int> offset;  // per group: ring[offset[g] .. offset[g+1])
  std::vector<int> ring;
};

Multifold find_multifold(const SphereTessellation &t) {
  Multifold mf;
  const int nt = static_cast<int>(t.triangles.size());
  std::vector<int> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  bool any = false;
  for (int c = 0; c < t.n_points; ++c)
    for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
      if (t.edge_length[k] == 0.0) {
        const int kn = k + 1 == t.cell_offset[c + 1] ? t.cell_offset[c] : k + 1;
        const int a = root(t.cell_vertex[k]), b = root(t.cell_vertex[kn]);
        if (a != b) parent[a] = b;
        any = true;
      }
  mf.group.assign(nt, -1);
  if (!any) return mf;
  std::vector<int> size(nt, 0), gid(nt, -1);
  for (int x = 0; x < nt; ++x) ++size[root(x)];
  std::vector<std::vector<int>> members;
  for (int x = 0; x < nt; ++x) {
    const int r = root(x);
    if (size[r] < 2) continue;
    if (gid[r] < 0) {
      gid[r] = static_cast<int>(members.size());
      members.emplace_back();
    }
    mf.group[x] = gid[r];
    members[gid[r]].push_back(x);
  }
  mf.offset.assign(1, 0);
  for (const auto &tris : members) {
    std::vector<int> pts;
    for (int x : tris)
      for (int q : t.triangles[x]) pts.push_back(q);
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    // Counter-clockwise about the pole: angles in the tangent plane.
    const V v = vv(t.vertex_direction[tris[0]]);
    const V d0 = vv(t.direction[pts[0]]);
    const V e1 = (1.0 / norm(d0 - dot(d0, v) * v)) * (d0 - dot(d0, v) * v);
    const V e2 = cross(v, e1);
    std::vector<std::pair<double, int>> by_angle;
    for (int q : pts) {
      const V d = vv(t.direction[q]);
      by_angle.emplace_back(std::atan2(dot(d, e2), dot(d, e1)), q);
    }
    std::sort(by_angle.begin(), by_angle.end());
    for (const auto &aq : by_angle) mf.ring.push_back(aq.second);
    mf.offset.push_back(static_cast<int>(mf.ring.size()));
  }
  return mf;
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
  const double mean = perimeter[c] / (k1 - k0);
  int z = 0;
  for (int k = k0; k < k1; ++k)
    if (edge_length[k] > rel_tol * mean) ++z;
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
  {
    const auto &f0 = t.triangles[0];
    CGAL::Orientation o = CGAL::COPLANAR;
    for (int i = 0; i < n && o == CGAL::COPLANAR; ++i)
      if (i != f0[0] && i != f0[1] && i != f0[2]) o = CGAL::orientation(P[f0[0]], P[f0[1]], P[f0[2]], P[i]);
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
    const V u = vv(t.direction[i]);
    double area = 0.0, perim = 0.0;
    for (int k = k0; k < k1; ++k) {
      const int kn = k + 1 == k1 ? k0 : k + 1;
      const int ta = t.cell_vertex[k], tb = t.cell_vertex[kn];
      const V va = vv(t.vertex_direction[ta]), vb = vv(t.vertex_direction[tb]);
      const double th = angle(va, vb);
      const double r = std::min(rho[ta], rho[tb]);
      const double l = th < 1e-10 * r + 8.0 * DBL_EPSILON / r ? 0.0 : R * th;
      t.edge_length[k] = l;
      perim += l;
      if (l > 0.0) area += solid_angle(u, va, vb);
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

double sphere_energy(const SphereTessellation &t, const int *type, const Model &model,
                     double *cell_energy) {
  check_types(t, type, model);
  double e = 0.0;
  for (int c = 0; c < t.n_points; ++c) {
    const double ec = cell_energy_of(t, c, type, model);
    if (cell_energy) cell_energy[c] = ec;
    e += ec;
  }
  return e;
}

SphereForceOutput sphere_forces(const SphereTessellation &t, const Points3 &pts, const int *type,
                                const Model &model, double *f, int f_stride, double *cell_energy,
                                double *cell_virial) {
  if (pts.n != t.n_points) {
    std::ostringstream s;
    s << "tessera: sphere_forces got " << pts.n << " points for a tessellation of " << t.n_points;
    throw Error(s.str());
  }
  const V c = vv(t.centre);
  for (int i = 0; i < t.n_points; ++i) {
    const double *p = pts.p(i);
    const V d = V{p[0], p[1], p[2]} - c;
    const double r = norm(d);
    if (!(r > 0.0) || norm((1.0 / r) * d - vv(t.direction[i])) > 1e-12)
      throw Error("tessera: sphere_forces: " + point_name(i, nullptr) +
                  " is not where it was when the sphere was tessellated");
  }
  check_types(t, type, model);

  const double R = t.R;
  const double w = model.tension_weight();
  SphereForceOutput out;
  double rdedr = 0.0;
  std::vector<V> G;    // dE_c/dv per vertex of the cell
  std::vector<V> fc;   // this cell's forces on the points it moves
  std::vector<int> fp;  // and which points
  std::vector<int> spokes;
  const Multifold mf = find_multifold(t);
  for (int cell = 0; cell < t.n_points; ++cell) {
    const int k0 = t.cell_offset[cell], k1 = t.cell_offset[cell + 1], m = k1 - k0;
    const int tc = type[cell];
    const CellType &ct = model.types[tc];
    const double A = t.area[cell], P = t.perimeter[cell];
    const double dEdA = ct.K * (A - model.area0_of(cell, tc));
    const double dEdP = ct.Gamma * P;
    const double ec = cell_energy_of(t, cell, type, model);
    if (cell_energy) cell_energy[cell] = ec;
    out.energy += ec;
    double tension = 0.0;

    G.assign(m, V{0.0, 0.0, 0.0});
    const V u = vv(t.direction[cell]);
    for (int j = 0; j < m; ++j) {
      const int jn = j + 1 == m ? 0 : j + 1;
      const V a = vv(t.vertex_direction[t.cell_vertex[k0 + j]]);
      const V b = vv(t.vertex_direction[t.cell_vertex[k0 + jn]]);
      const double l = t.edge_length[k0 + j];
      if (l <= 0.0) continue;  // zero-length edge: no area, no length gradient
      // Area of the fan triangle (u, a, b).
      const double D = dot(u, cross(a, b));
      const double S = 1.0 + dot(u, a) + dot(a, b) + dot(b, u);
      const double s = 2.0 * dEdA * R * R / (S * S + D * D);
      add_to(G[j], s * (S * cross(b, u) - D * (u + b)));
      add_to(G[jn], s * (S * cross(u, a) - D * (u + a)));
      // Length of the edge a-b.
      const double lam = model.lambda_of(tc, type[t.cell_neighbor[k0 + j]]);
      tension += w * lam * l;
      const double coef = R * (dEdP + w * lam);
      const double ab = dot(a, b);
      const double sn = norm(cross(a, b));
      add_to(G[j], (-coef / sn) * (b - ab * a));
      add_to(G[jn], (-coef / sn) * (a - ab * b));
    }
    rdedr += 2.0 * dEdA * A + dEdP * P + tension;

    // Through the poles to the points.
    fc.clear();
    fp.clear();
    for (int j = 0; j < m; ++j) {
      const int tri = t.cell_vertex[k0 + j];
      const int g = mf.group[tri];
      if (g < 0) {
        const std::array<int, 3> &pq = t.triangles[tri];
        push_pole(t, pq[0], pq[1], pq[2], G[j], fc, fp);
        continue;
      }
      const int jp = j == 0 ? m - 1 : j - 1;
      if (mf.group[t.cell_vertex[k0 + jp]] == g) continue;  // not the run's first vertex
      // A multifold vertex V shared by the kk >= 4 cells of its ring
      // w_0..w_{kk-1}, of which this cell is w_i.  Each way of triangulating
      // the ring is one smooth branch of the energy; as in the plane
      // (model.md, Geometry) we take the mean of the branch gradients over
      // the kk fan triangulations (from each w_j): for a four-fold vertex
      // the mean of the two one-sided derivatives.  In a branch, the edges
      // at V have length zero and the direction they take on that branch's
      // side: along the bisector of the cell and the neighbour q, at V,
      // V x (u_q - u_c) normalised.
      int run_end = j;
      while (run_end - j + 1 < m && mf.group[t.cell_vertex[k0 + (run_end + 1) % m]] == g) ++run_end;
      const int *ring = &mf.ring[mf.offset[g]];
      const int kk = mf.offset[g + 1] - mf.offset[g];
      int i = 0;
      while (i < kk && ring[i] != cell) ++i;
      const int w_in = ring[(i + 1) % kk], w_out = ring[(i + kk - 1) % kk];
      if (i == kk || t.cell_neighbor[k0 + jp] != w_in || t.cell_neighbor[k0 + run_end % m] != w_out)
        throw Error("tessera: internal error: the ring of a multifold vertex on the sphere does not"
                    " match the cell of " + point_name(cell, nullptr));
      const V hp = vv(t.vertex_direction[t.cell_vertex[k0 + jp]]);
      const V hn = vv(t.vertex_direction[t.cell_vertex[k0 + (run_end + 1) % m]]);
      const V Vp = vv(t.vertex_direction[tri]);
      // Area terms of the two real edges (fan triangles (u, hp, V) and (u, V, hn)).
      V area_in{0, 0, 0}, area_out{0, 0, 0};
      {
        const double D = dot(u, cross(hp, Vp)), S = 1.0 + dot(u, hp) + dot(hp, Vp) + dot(Vp, u);
        area_in = (2.0 * dEdA * R * R / (S * S + D * D)) * (S * cross(u, hp) - D * (u + hp));
      }
      {
        const double D = dot(u, cross(Vp, hn)), S = 1.0 + dot(u, Vp) + dot(Vp, hn) + dot(hn, u);
        area_out = (2.0 * dEdA * R * R / (S * S + D * D)) * (S * cross(hn, u) - D * (u + hn));
      }
      const V zero_in = (2.0 * dEdA * R * R / (2.0 + 2.0 * dot(u, Vp))) * cross(u, Vp);
      auto spoke_dir = [&](int q) {
        const V d = cross(Vp, vv(t.direction[q]) - u);
        return (1.0 / norm(d)) * d;
      };
      auto spoke_coef = [&](int q) { return R * (dEdP + w * model.lambda_of(tc, type[q])); };
      const double inv_k = 1.0 / kk;
      for (int b = 0; b < kk; ++b) {
        spokes.assign(1, w_in);
        if (b == i) {
          for (int q = 2; q <= kk - 2; ++q) spokes.push_back(ring[(i + q) % kk]);
        } else if (b != (i + 1) % kk && b != (i + kk - 1) % kk) {
          spokes.push_back(ring[b]);
        }
        spokes.push_back(w_out);
        const int M = static_cast<int>(spokes.size()) - 1;
        for (int sp = 1; sp <= M; ++sp) {
          V gs = spoke_coef(spokes[sp - 1]) * spoke_dir(spokes[sp - 1]) -
                 spoke_coef(spokes[sp]) * spoke_dir(spokes[sp]);
          // The fan triangles on either side of this pole: the real ones at
          // the ends, else the zero-area (u, V, V), whose solid angle still
          // has a derivative (2 (u x V) / S in its third argument, the
          // opposite in its second); they cancel for inner spokes.
          gs = gs + (sp == 1 ? area_in : zero_in) + (sp == M ? area_out : (-1.0) * zero_in);
          push_pole(t, cell, spokes[sp - 1], spokes[sp], inv_k * gs, fc, fp);
        }
      }
    }
    const V rc = R * u;
    double *cv = cell_virial ? cell_virial + 9L * cell : nullptr;
    if (cv) std::fill(cv, cv + 9, 0.0);
    for (size_t q = 0; q < fc.size(); ++q) {
      const int p = fp[q];
      const V F = fc[q];
      double *fo = f + static_cast<long>(p) * f_stride;
      fo[0] += F.x;
      fo[1] += F.y;
      fo[2] += F.z;
      const V r = R * vv(t.direction[p]);
      const double ra[3] = {r.x, r.y, r.z}, Fb[3] = {F.x, F.y, F.z};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) out.virial[3 * a + b] += ra[a] * Fb[b];
      if (cv) {
        const V d = r - rc;
        const double da[3] = {d.x, d.y, d.z};
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) cv[3 * a + b] += da[a] * Fb[b];
      }
    }
  }
  out.dE_dR = rdedr / R;
  for (int p = 0; p < t.n_points; ++p) {
    const double *fo = f + static_cast<long>(p) * f_stride;
    if (!finite3(fo))
      throw Error("tessera: the force on " + point_name(p, nullptr) +
                  " on the sphere is not finite");
  }
  return out;
}

Vec3 sphere_tangent(const Vec3 &centre, const Vec3 &p, const Vec3 &v) {
  const V d = vv(p) - vv(centre);
  const double r = norm(d);
  if (!(r > 0.0)) throw Error("tessera: sphere_tangent: the point is at the centre of the sphere");
  const V u = (1.0 / r) * d;
  const V x = vv(v);
  return to3(x - dot(x, u) * u);
}

Vec3 sphere_transport(const Vec3 &centre, const Vec3 &a, const Vec3 &b, const Vec3 &v) {
  const V da = vv(a) - vv(centre), db = vv(b) - vv(centre);
  const double ra = norm(da), rb = norm(db);
  if (!(ra > 0.0 && rb > 0.0))
    throw Error("tessera: sphere_transport: a point is at the centre of the sphere");
  const V ua = (1.0 / ra) * da, ub = (1.0 / rb) * db;
  const double cab = dot(ua, ub);
  if (!(1.0 + cab > 1e-12))
    throw Error("tessera: sphere_transport: the two points are antipodal (no unique great-circle"
                " arc between them)");
  V x = vv(v);
  x = x - dot(x, ua) * ua;
  return to3(x - (dot(ub, x) / (1.0 + cab)) * (ua + ub));
}

Vec3 sphere_rotate_tangent(const Vec3 &centre, const Vec3 &p, const Vec3 &v, double angle_rad) {
  const V d = vv(p) - vv(centre);
  const double r = norm(d);
  if (!(r > 0.0))
    throw Error("tessera: sphere_rotate_tangent: the point is at the centre of the sphere");
  const V u = (1.0 / r) * d;
  V x = vv(v);
  x = x - dot(x, u) * u;
  const double cs = std::cos(angle_rad), sn = std::sin(angle_rad);
  return to3(cs * x + sn * cross(u, x));
}

}  // namespace tessera
