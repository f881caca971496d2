// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// 3D Voronoi cells from Tessera's Delaunay tetrahedralisation (exact
// predicates, mesh3d_delaunay.h), their volumes and surfaces, and the
// energy's exact gradient.
//
// Geometry of the gradient.  Face f of cell i (towards j) is the polygon of
// the circumcentres h_k of the tetrahedra around the Delaunay edge i-j; all of
// them lie on the bisector plane of i and j, whatever the triangulation, so
// the face is planar with unit normal n = (x_j - x_i)/|x_j - x_i|.  With
// u_k = h_k - x_i:
//   vector area  a_f = 1/2 sum_k u_k x u_{k+1},   face area S_f = a_f . n,
//   volume       V   = 1/3 sum_f a_f . q_f,       q_f = mean of the face's u_k,
//   dS_f/dh_k = 1/2 (u_{k+1} - u_{k-1}) x n,
//   dV/dh_k   = sum_f 1/3 [ 1/2 (u_{k+1} - u_{k-1}) x q_f + a_f / m_f ].
// S_f also depends on x_i, x_j through n, but a_f is parallel to n, so that
// derivative (a_f . dn) vanishes; V does not depend on x_i (sum_f a_f = 0).
// The circumcentre c of p0..p3, with e_m = p_m - p0 and A the matrix of rows
// e_m, has dc/dp_m = A^{-1}[:, m] (p_m - c)^T (m = 1..3) and
// dc/dp0 = I - sum_m dc/dp_m.
//
// Co-spherical points.  Several tetrahedra then share a circumcentre and the
// symbolic perturbation picks one of the triangulations.  Every triangulation of the points near
// such a configuration gives planar faces on the right bisector planes; a
// non-Delaunay one differs from the true cells only inside a ball of the size
// e of the perturbation, by O(e^2) in face areas and O(e^3) in volumes.  So V
// and S (unlike the 2D perimeter, which has |edge| terms) are continuously
// differentiable there and the gradient through the chosen triangulation is
// the true gradient, whichever way the tie was broken.

#include "tessera/voronoi3d.h"

#include "fourfold3d.h"
#include "mesh3d_delaunay.h"
#include "vec3_detail.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <utility>

namespace tessera {

namespace {

using namespace detail3;

std::string point_name(int i, const long *ids) {
  std::ostringstream s;
  if (ids)
    s << "id " << ids[i];
  else
    s << "point " << i;
  return s.str();
}

// The circumcentre of a flat tetrahedron (sliver) to the nearest double
// (in rationals, mesh3d_exact.cpp): the formula above loses about eps/q of
// its radius (q its flatness), all of it for the slivers of co-spherical
// points that round-off creates.
V3 exact_circumcentre(V3 p0, V3 p1, V3 p2, V3 p3) {
  const double a[3] = {p0.x, p0.y, p0.z}, b[3] = {p1.x, p1.y, p1.z}, c[3] = {p2.x, p2.y, p2.z},
               d[3] = {p3.x, p3.y, p3.z};
  double h[3];
  detail3::exact_circumcentre(a, b, c, d, h);
  return {h[0], h[1], h[2]};
}

}  // namespace

void Box3::validate() const {
  for (int d = 0; d < 3; ++d)
    if (!std::isfinite(lo[d]) || !std::isfinite(hi[d]) || !(hi[d] > lo[d])) {
      std::ostringstream s;
      s << "tessera: box length in " << "xyz"[d] << " must be positive and finite, got [" << lo[d]
        << ", " << hi[d] << "]";
      throw Error(s.str());
    }
  if (!std::isfinite(xy) || !std::isfinite(xz) || !std::isfinite(yz))
    throw Error("tessera: box tilts xy, xz, yz must be finite");
}

Region3 Box3::region() const {
  Region3 r;
  for (int d = 0; d < 3; ++d) r.o[d] = lo[d];
  r.a[0] = length(0);
  r.a[1] = r.a[2] = 0.0;
  r.b[0] = xy;
  r.b[1] = length(1);
  r.b[2] = 0.0;
  r.c[0] = xz;
  r.c[1] = yz;
  r.c[2] = length(2);
  return r;
}

void Box3::fractional(const double x[3], double s[3]) const {
  s[2] = (x[2] - lo[2]) / length(2);
  s[1] = (x[1] - lo[1] - yz * s[2]) / length(1);
  s[0] = (x[0] - lo[0] - xy * s[1] - xz * s[2]) / length(0);
}

namespace {

// Unit normals of the three pairs of faces of a parallelepiped (normal k is
// perpendicular to the two edges other than k, pointing along edge k) and
// the widths along them.
void slabs(const Region3 &r, V3 n[3], double width[3]) {
  const V3 e[3] = {{r.a[0], r.a[1], r.a[2]}, {r.b[0], r.b[1], r.b[2]}, {r.c[0], r.c[1], r.c[2]}};
  for (int k = 0; k < 3; ++k) {
    V3 m = cross(e[(k + 1) % 3], e[(k + 2) % 3]);
    m = (1.0 / std::sqrt(dot(m, m))) * m;
    if (dot(m, e[k]) < 0) m = -1.0 * m;
    n[k] = m;
    width[k] = dot(m, e[k]);
  }
}

}  // namespace

int Tessellation3::face_count(int c, double rel_tol) const {
  int z = 0;
  for (int f = cell_offset[c]; f < cell_offset[c + 1]; ++f) z += face_area[f] > rel_tol * surface[c];
  return z;
}

double Tessellation3::shape_index(int c) const { return surface[c] / std::cbrt(volume[c] * volume[c]); }

namespace {

// Tetrahedra flatter than this (|det| of the edge vectors over the cube of
// the longest edge component) have an ill-conditioned circumcentre.
constexpr double kSliver = 1e-6;
// A point within this fraction of the radius of a sphere counts as on it.
constexpr double kCoSpherical = 1e-8;

// Slivers of co-spherical points.  Near-co-spherical points given with
// round-off (a lattice in a tilted box, coordinates not exact in binary)
// may be triangulated with a flat tetrahedron whose four points are nearly
// on one circle.  Its circumcentre is then round-off (or 0/0), and so is its
// gradient, though the Voronoi vertex it stands for is well defined: the
// centre of the sphere through the cluster, which the well-shaped
// tetrahedra of the cluster give.  Such a sliver is dropped from the face
// polygons when a facet-adjacent well-shaped tetrahedron's circumsphere
// holds its four points (kCoSpherical): every face then has only
// well-conditioned vertices, all on the face's bisector plane, and the
// polygon loses a corner within the cluster, which changes areas and
// volumes only at second order in the distance from the co-spherical
// configuration (doc/model.md, "Reliability of the finite and 3D paths").
// The sliver keeps the neighbour's circumcentre and radius (unused).  A
// sliver without such a neighbour (not co-spherical) keeps its own.
void drop_slivers(Tessellation3 &t, const detail3::Tetrahedra &dt, const std::vector<int> &handle,
                  const std::vector<int> &tmap, const Points3 &pts) {
  auto quality = [&](int v) {
    const auto &q = t.tets[v];
    return flatness(load(pts, q[0]), load(pts, q[1]), load(pts, q[2]), load(pts, q[3]));
  };
  std::vector<int> slivers;
  const int n_tets = static_cast<int>(t.tets.size());
  for (int v = 0; v < n_tets; ++v)
    if (!(quality(v) >= kSliver)) slivers.push_back(v);
  if (slivers.empty()) return;
  auto on_sphere = [&](int v, int w) {  // the points of v on w's circumsphere
    const V3 h = vv(t.vertices[w]);
    const double r = t.radius[w];
    if (!std::isfinite(r)) return false;
    for (int k = 0; k < 4; ++k) {
      const V3 d = load(pts, t.tets[v][k]) - h;
      if (!(std::fabs(std::sqrt(dot(d, d)) - r) <= kCoSpherical * r)) return false;
    }
    return true;
  };
  std::vector<char> drop(n_tets, 0);
  bool any = false;
  for (int v : slivers)
    for (int k = 0; k < 4; ++k) {
      const int nb = dt.tn[4 * static_cast<size_t>(handle[v]) + k];
      // Only tetrahedra already in the faces: the tetrahedra of t stay those
      // of the owned cells' faces (as an incremental mesh reproduces them).
      if (nb < 0 || tmap[nb] < 0) continue;
      const int w = tmap[nb];
      if (!(quality(w) >= kSliver) || !on_sphere(v, w)) continue;
      // Co-spherical is not enough: four points of a square shared by two
      // cubes of co-spherical points (a four-fold Voronoi edge, SC) lie on
      // both cubes' spheres, and the sliver's circumcentre is a real vertex
      // anywhere on the edge between their centres.  Only a sliver whose
      // (exactly computed) circumcentre is at w's is dropped.
      const V3 dh = vv(t.vertices[v]) - vv(t.vertices[w]);
      if (!(std::sqrt(dot(dh, dh)) <= kCoSpherical * t.radius[w])) continue;
      t.vertices[v] = t.vertices[w];
      t.radius[v] = t.radius[w];
      drop[v] = 1;
      any = true;
      break;
    }
  if (!any) return;
  std::vector<int> fv, fo(1, 0);
  fv.reserve(t.face_vertex.size());
  for (size_t f = 0; f + 1 < t.face_offset.size(); ++f) {
    const size_t start = fv.size();
    for (int k = t.face_offset[f]; k < t.face_offset[f + 1]; ++k)
      if (!drop[t.face_vertex[k]]) fv.push_back(t.face_vertex[k]);
    if (fv.size() == start)  // only slivers: keep them (an area-0 face)
      for (int k = t.face_offset[f]; k < t.face_offset[f + 1]; ++k) fv.push_back(t.face_vertex[k]);
    fo.push_back(static_cast<int>(fv.size()));
  }
  t.face_vertex.swap(fv);
  t.face_offset.swap(fo);
}

// The triangulation's adjacency for find_fourfold_edges: ids are its
// tetrahedra's numbers (handle: of t's tetrahedra, tmap the inverse, -1 for
// the others); the hull's outside counts as absent.
class FlatGraph : public detail3::TetGraph {
public:
  FlatGraph(const detail3::Tetrahedra &dt, const std::vector<int> &handle,
            const std::vector<int> &tmap)
      : dt_(dt), handle_(handle), tmap_(tmap) {}
  long id(int v) override { return handle_[v]; }
  long neighbor(long g, int k) override { return dt_.tn[4 * g + k]; }
  void corners(long g, int q[4]) override {
    for (int k = 0; k < 4; ++k) q[k] = dt_.tv[4 * g + k];
  }
  int t_neighbor(int v, int k) override {
    const int nb = dt_.tn[4 * static_cast<size_t>(handle_[v]) + k];
    if (nb < 0) return -2;
    return tmap_[nb];
  }
  int opposite(long g, int k) override {
    const int nb = dt_.tn[4 * g + k];
    if (nb < 0) return -1;
    const int *a = &dt_.tv[4 * g], *b = &dt_.tv[4 * static_cast<size_t>(nb)];
    for (int s = 0; s < 4; ++s)
      if (b[s] != a[0] && b[s] != a[1] && b[s] != a[2] && b[s] != a[3]) return b[s];
    return -1;
  }

private:
  const detail3::Tetrahedra &dt_;
  const std::vector<int> &handle_, &tmap_;
};

// Face areas, volumes and surfaces of the owned cells from t.vertices.
void measure(Tessellation3 &t, const Points3 &pts) {
  for (int i = 0; i < t.n_owned; ++i) {
    const V3 xi = load(pts, i);
    double vol = 0.0, sur = 0.0;
    for (int f = t.cell_offset[i]; f < t.cell_offset[i + 1]; ++f) {
      const int o = t.face_offset[f], m = t.face_offset[f + 1] - o;
      V3 av{0, 0, 0}, q{0, 0, 0};
      for (int k = 0; k < m; ++k) {
        const V3 u = vv(t.vertices[t.face_vertex[o + k]]) - xi;
        const V3 w = vv(t.vertices[t.face_vertex[o + (k + 1) % m]]) - xi;
        av = av + 0.5 * cross(u, w);
        q = q + u;
      }
      q = (1.0 / m) * q;
      const V3 d = load(pts, t.face_neighbor[f]) - xi;
      const double area = dot(av, d) / std::sqrt(dot(d, d));
      t.face_area[f] = area;
      sur += area;
      vol += dot(av, q) / 3.0;
    }
    t.volume[i] = vol;
    t.surface[i] = sur;
  }
}

}  // namespace

Tessellation3 tessellate_local_3d(const Points3 &pts, int n_owned, const long *ids,
                                  bool throw_if_unbounded) {
  const int n = pts.n;
  if (n_owned < 0 || n_owned > n) throw Error("tessera: n_owned out of range");
  if (n_owned == 0) {
    // No cells wanted (e.g. an MPI rank without atoms): nothing to triangulate.
    Tessellation3 empty;
    empty.n_points = n;
    empty.cell_offset.assign(1, 0);
    empty.face_offset.assign(1, 0);
    return empty;
  }
  for (int i = 0; i < n; ++i) {
    const double *p = pts.p(i);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw Error("tessera: non-finite coordinates for " + point_name(i, ids));
  }
  detail3::Tetrahedra dt;
  const detail3::Delaunay3 status = detail3::delaunay_3d(pts, nullptr, 0, dt, 0.0, false);
  if (status != detail3::Delaunay3::kOk) {
    // Coincident points: name a pair.
    std::vector<int> order(n);
    for (int i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const double *p = pts.p(a), *q = pts.p(b);
      return std::lexicographical_compare(p, p + 3, q, q + 3);
    });
    for (int k = 0; k + 1 < n; ++k) {
      const double *p = pts.p(order[k]), *q = pts.p(order[k + 1]);
      if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2])
        throw Error("tessera: two cell centres at the same position (" + point_name(order[k], ids) +
                    " and " + point_name(order[k + 1], ids) + ")");
    }
    if (status == detail3::Delaunay3::kFlat)
      throw Error("tessera: the points are coplanar; need a 3D configuration");
    throw Error("tessera: points were lost by the triangulation");
  }

  Tessellation3 t;
  t.n_points = n;
  t.n_owned = n_owned;
  t.cell_offset.assign(1, 0);
  t.face_offset.assign(1, 0);
  t.volume.assign(n_owned, 0.0);
  t.surface.assign(n_owned, 0.0);

  const int *tv = dt.tv.data(), *tn = dt.tn.data();
  std::vector<int> handle;                // of each tetrahedron in t.tets
  std::vector<int> tmap(dt.n_tets, -1);  // and back
  auto tet_of = [&](int c) {
    if (tmap[c] >= 0) return tmap[c];
    const int id = static_cast<int>(t.tets.size());
    tmap[c] = id;
    handle.push_back(c);
    const int *q = tv + 4 * static_cast<size_t>(c);
    t.tets.push_back({q[0], q[1], q[2], q[3]});
    const V3 p0 = load(pts, q[0]), p1 = load(pts, q[1]), p2 = load(pts, q[2]), p3 = load(pts, q[3]);
    const V3 h = flatness(p0, p1, p2, p3) >= kSliver ? circumcentre(p0, p1, p2, p3)
                                                     : exact_circumcentre(p0, p1, p2, p3);
    t.vertices.push_back({h.x, h.y, h.z});
    const V3 d = h - load(pts, q[0]);
    t.radius.push_back(std::sqrt(dot(d, d)));
    return id;
  };

  // Per tetrahedron and per point: the owned cell that last met it.
  std::vector<int> tseen(dt.n_tets, -1), pseen(n, -1), star;
  for (int i = 0; i < n_owned; ++i) {
    // The star of i, every tetrahedron containing it; on the hull if a
    // triangle through i has no tetrahedron beyond it.
    star.clear();
    star.push_back(dt.vt[i]);
    tseen[dt.vt[i]] = i;
    bool unbounded = false;
    for (size_t h = 0; h < star.size() && !unbounded; ++h) {
      const int m = star[h];
      for (int s = 0; s < 4; ++s) {
        if (tv[4 * m + s] == i) continue;
        const int nb = tn[4 * m + s];
        if (nb < 0) {
          unbounded = true;
          break;
        }
        if (tseen[nb] != i) {
          tseen[nb] = i;
          star.push_back(nb);
        }
      }
    }
    if (unbounded) {
      if (throw_if_unbounded)
        throw Error("tessera: the cell of " + point_name(i, ids) +
                    " is unbounded (on the convex hull): the ghost shell is missing");
      t.unbounded_cell = i;
      t.cell_offset.push_back(static_cast<int>(t.face_neighbor.size()));
      continue;
    }
    for (const int m : star) {
      int li = 0;
      while (tv[4 * m + li] != i) ++li;
      for (int lj = 0; lj < 4; ++lj) {
        const int j = tv[4 * m + lj];
        if (lj == li || pseen[j] == i) continue;
        pseen[j] = i;
        int la = -1, lb = -1;
        for (int q = 0; q < 4; ++q)
          if (q != li && q != lj) (la < 0 ? la : lb) = q;
        if (parity(li, lj, la, lb) < 0) std::swap(la, lb);
        // Around the edge i j: from a tetrahedron (i j a b), positively
        // oriented, across the triangle (i j b); the ring then runs
        // counter-clockwise about x_j - x_i.
        int cur = m, va = tv[4 * m + la], vb = tv[4 * m + lb];
        do {
          t.face_vertex.push_back(tet_of(cur));
          int sa = 0;
          while (tv[4 * cur + sa] != va) ++sa;
          const int nx = tn[4 * cur + sa];
          int vc = -1;
          for (int q = 0; q < 4; ++q) {
            const int v = tv[4 * nx + q];
            if (v != i && v != j && v != vb) vc = v;
          }
          va = vb;
          vb = vc;
          cur = nx;
        } while (cur != m);
        t.face_offset.push_back(static_cast<int>(t.face_vertex.size()));
        t.face_neighbor.push_back(j);
        t.face_area.push_back(0.0);  // measured below, after drop_slivers
      }
    }
    t.cell_offset.push_back(static_cast<int>(t.face_neighbor.size()));
  }
  drop_slivers(t, dt, handle, tmap, pts);
  measure(t, pts);
  check_separation_3d(t, pts, ids);
  FlatGraph graph(dt, handle, tmap);
  detail3::find_fourfold_edges(t, pts, graph);
  return t;
}

namespace detail3 {

void check_separation_3d(const Tessellation3 &t, const Points3 &pts, const long *ids,
                         double d2min) {
  // A first filter with one bound for all faces (the largest radius, and
  // the largest owned coordinate plus a diameter: a neighbour across a face
  // lies within 2 r of the cell's centre), then the pair's own limit.
  double rmax = 0.0, xmax = 0.0;
  for (const double r : t.radius)
    if (!(r <= rmax)) rmax = r;  // (NaN propagates: every face is then looked at)
  for (int i = 0; i < t.n_owned; ++i) {
    const double *p = pts.p(i);
    xmax = std::max({xmax, std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])});
  }
  const double bound = std::max(
      {kMinSeparation3 * rmax, kMinSeparation3Coord * (xmax + 2.0 * rmax), kMinLength3});
  const double bound2 = std::isfinite(bound) ? bound * bound : std::numeric_limits<double>::infinity();
  if (d2min >= 0.0 && d2min >= bound2) return;
  int bi = -1, bj = -1;
  double bd = 0.0, blim = 0.0;
  for (int i = 0; i < t.n_owned; ++i) {
    const V3 xi = load(pts, i);
    for (int f = t.cell_offset[i]; f < t.cell_offset[i + 1]; ++f) {
      const int j = t.face_neighbor[f];
      const V3 dj = load(pts, j) - xi;
      const double d2 = dot(dj, dj);
      if (!(d2 < bound2)) continue;
      double rmin = std::numeric_limits<double>::infinity();
      for (int k = t.face_offset[f]; k < t.face_offset[f + 1]; ++k) {
        const double r = t.radius[t.face_vertex[k]];
        if (!(r >= rmin)) rmin = r;
      }
      const double mag = std::max({std::fabs(xi.x), std::fabs(xi.y), std::fabs(xi.z),
                                   std::fabs(xi.x + dj.x), std::fabs(xi.y + dj.y),
                                   std::fabs(xi.z + dj.z)});
      const double lim = std::max({kMinSeparation3 * rmin, kMinSeparation3Coord * mag, kMinLength3});
      const double d = std::sqrt(d2);
      if (!(d >= lim) && (bi < 0 || d < bd)) bi = i, bj = j, bd = d, blim = lim;
    }
  }
  if (bi < 0) return;
  auto name = [&](int k) {
    std::ostringstream s;
    s.precision(17);
    const double *p = pts.p(k);
    s << point_name(k, ids) << " at (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
    return s.str();
  };
  // The pair in ID order (index order without ids), whichever cell found it.
  const bool swap = ids ? ids[bj] < ids[bi] : bj < bi;
  std::ostringstream s;
  s << "tessera: two cell centres nearly coincide: " << name(swap ? bj : bi) << " and "
    << name(swap ? bi : bj) << " are " << bd << " apart, closer than " << blim
    << " (1e-6 of the radius of the Voronoi vertices between them, or 1e-10 of their "
       "coordinates): the 3D cells cannot resolve the face between them; move or delete one "
       "of them";
  throw Error(s.str());
}

}  // namespace detail3

void remeasure_3d(Tessellation3 &t, const Points3 &pts) {
  t.fourfold.clear();
  for (size_t v = 0; v < t.tets.size(); ++v) {
    const auto &q = t.tets[v];
    const V3 p0 = load(pts, q[0]), p1 = load(pts, q[1]), p2 = load(pts, q[2]), p3 = load(pts, q[3]);
    const V3 h = flatness(p0, p1, p2, p3) >= kSliver ? circumcentre(p0, p1, p2, p3)
                                                     : exact_circumcentre(p0, p1, p2, p3);
    t.vertices[v] = {h.x, h.y, h.z};
    const V3 d = h - p0;
    t.radius[v] = std::sqrt(dot(d, d));
  }
  measure(t, pts);
}

Coverage check_coverage_3d(const Tessellation3 &t, const double lo[3], const double hi[3],
                           double margin) {
  Coverage cov;
  if (t.unbounded_cell >= 0) {
    cov.ok = false;
    cov.needed_margin = std::numeric_limits<double>::infinity();
    cov.worst_cell = t.unbounded_cell;
    return cov;
  }
  for (int c = 0; c < t.n_owned; ++c)
    for (int f = t.cell_offset[c]; f < t.cell_offset[c + 1]; ++f)
      for (int k = t.face_offset[f]; k < t.face_offset[f + 1]; ++k) {
        const int v = t.face_vertex[k];
        const double h[3] = {t.vertices[v].x, t.vertices[v].y, t.vertices[v].z};
        const double r = t.radius[v];
        for (int d = 0; d < 3; ++d) {
          const double need = std::max(lo[d] - margin - (h[d] - r), (h[d] + r) - (hi[d] + margin));
          if (need > cov.needed_margin) {
            cov.ok = false;
            cov.needed_margin = need;
            cov.worst_cell = c;
          }
        }
      }
  return cov;
}

Coverage check_coverage_3d(const Tessellation3 &t, const Region3 &region, double margin) {
  Coverage cov;
  if (t.unbounded_cell >= 0) {
    cov.ok = false;
    cov.needed_margin = std::numeric_limits<double>::infinity();
    cov.worst_cell = t.unbounded_cell;
    return cov;
  }
  V3 n[3];
  double width[3];
  slabs(region, n, width);
  const V3 o{region.o[0], region.o[1], region.o[2]};
  for (int c = 0; c < t.n_owned; ++c)
    for (int f = t.cell_offset[c]; f < t.cell_offset[c + 1]; ++f)
      for (int k = t.face_offset[f]; k < t.face_offset[f + 1]; ++k) {
        const int v = t.face_vertex[k];
        const V3 h = vv(t.vertices[v]) - o;
        const double r = t.radius[v];
        for (int d = 0; d < 3; ++d) {
          const double u = dot(n[d], h);
          const double need = std::max(-margin - (u - r), (u + r) - (width[d] + margin));
          if (need > cov.needed_margin) {
            cov.ok = false;
            cov.needed_margin = need;
            cov.worst_cell = c;
          }
        }
      }
  return cov;
}

Tessellation3 tessellate_periodic_3d(const Box3 &box, const Points3 &pts, const long *ids) {
  box.validate();
  const int n = pts.n;
  if (n < 1) throw Error("tessera: no points");
  for (int i = 0; i < n; ++i) {
    double s[3];
    box.fractional(pts.p(i), s);
    for (int d = 0; d < 3; ++d)
      if (!(s[d] >= 0.0 && s[d] < 1.0))
        throw Error("tessera: " + point_name(i, ids) + " lies outside the box; wrap it first");
  }
  const Region3 reg = box.region();
  V3 nrm[3];
  double width[3];
  slabs(reg, nrm, width);
  const V3 edge[3] = {{reg.a[0], reg.a[1], reg.a[2]}, {reg.b[0], reg.b[1], reg.b[2]},
                      {reg.c[0], reg.c[1], reg.c[2]}};
  const V3 origin0{reg.o[0], reg.o[1], reg.o[2]};
  const double lmax = std::max({width[0], width[1], width[2]});
  double margin = 2.0 * std::cbrt(box.volume() / n);
  for (int attempt = 0; attempt < 40; ++attempt) {
    std::vector<double> xyz;
    std::vector<int> origin;
    std::vector<long> pid;
    xyz.reserve(3 * n);
    for (int i = 0; i < n; ++i) {
      const double *p = pts.p(i);
      xyz.insert(xyz.end(), p, p + 3);
      origin.push_back(i);
      if (ids) pid.push_back(ids[i]);
    }
    int range[3];
    for (int d = 0; d < 3; ++d) range[d] = static_cast<int>(std::ceil(margin / width[d]));
    for (int a = -range[0]; a <= range[0]; ++a)
      for (int b = -range[1]; b <= range[1]; ++b)
        for (int c = -range[2]; c <= range[2]; ++c) {
          if (a == 0 && b == 0 && c == 0) continue;
          const V3 shift = (1.0 * a) * edge[0] + (1.0 * b) * edge[1] + (1.0 * c) * edge[2];
          const double s[3] = {shift.x, shift.y, shift.z};
          for (int i = 0; i < n; ++i) {
            const double *p = pts.p(i);
            double q[3];
            for (int d = 0; d < 3; ++d) q[d] = p[d] + s[d];
            const V3 rel = V3{q[0], q[1], q[2]} - origin0;
            bool in = true;
            for (int d = 0; d < 3; ++d) {
              const double u = dot(nrm[d], rel);
              if (u < -margin || u > width[d] + margin) in = false;
            }
            if (!in) continue;
            xyz.insert(xyz.end(), q, q + 3);
            origin.push_back(i);
            if (ids) pid.push_back(ids[i]);
          }
        }
    const Points3 all{xyz.data(), static_cast<int>(origin.size()), 3};
    Tessellation3 t = tessellate_local_3d(all, n, ids ? pid.data() : nullptr, false);
    const Coverage cov = check_coverage_3d(t, reg, margin);
    if (cov.ok) {
      t.origin = std::move(origin);
      t.position = std::move(xyz);
      return t;
    }
    margin = std::isinf(cov.needed_margin) ? 2.0 * margin
                                           : std::max(1.5 * margin, margin + 1.1 * cov.needed_margin);
    if (margin > 3.0 * lmax) margin = 3.0 * lmax;
  }
  throw Error("tessera: the periodic 3D tessellation did not converge");
}

}  // namespace tessera
