// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Delaunay triangulation (CGAL, exact predicates) of owned + ghost points and
// the owned cells' Voronoi polygons read off it.

#include "tessera/tessellation.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_map>
#include <utility>

namespace tessera {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using Fb = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using CPoint = Kernel::Point_2;

// Voronoi edges shorter than this fraction of the adjacent circumradius are
// the zero-length edges of a multifold vertex whose circumcentres differ only
// by round-off; they get length exactly 0 (and no direction).
constexpr double kZeroEdge = 1e-10;

std::string point_name(int i, const long *ids) {
  std::ostringstream s;
  if (ids)
    s << "id " << ids[i];
  else
    s << "point " << i;
  return s.str();
}

void check_finite(const Points &pts, const long *ids) {
  for (int i = 0; i < pts.n; ++i) {
    if (!std::isfinite(pts.x(i)) || !std::isfinite(pts.y(i))) {
      std::ostringstream s;
      s << "tessera: " << point_name(i, ids) << " has a non-finite coordinate (" << pts.x(i)
        << ", " << pts.y(i) << ")";
      throw Error(s.str());
    }
  }
}

// Circumcentre and circumradius of (a, b, c), relative to a for accuracy.
inline void circumcentre(double ax, double ay, double bx, double by, double cx, double cy,
                         Vec2 &h, double &r) {
  const double bpx = bx - ax, bpy = by - ay, cpx = cx - ax, cpy = cy - ay;
  const double d = 2.0 * (bpx * cpy - bpy * cpx);
  const double b2 = bpx * bpx + bpy * bpy, c2 = cpx * cpx + cpy * cpy;
  const double ux = (cpy * b2 - bpy * c2) / d;
  const double uy = (bpx * c2 - cpx * b2) / d;
  h.x = ax + ux;
  h.y = ay + uy;
  r = std::sqrt(ux * ux + uy * uy);
}

struct Built {
  Tessellation t;
  int unbounded_cell = -1;  // an owned cell on the convex hull, if any
};

// Triangulates and reads off the owned cells.  name_of maps a point index to
// the index used in messages (periodic images report their owner).
template <class NameOf>
Built build(const Points &pts, int n_owned, const long *ids, NameOf name_of) {
  const int n = pts.n;
  if (n_owned < 0 || n_owned > n) throw Error("tessera: n_owned must be in [0, number of points]");
  if (n < 3) {
    std::ostringstream s;
    s << "tessera: need at least 3 non-collinear points to tessellate, got " << n;
    throw Error(s.str());
  }

  std::vector<std::pair<CPoint, int>> input;
  input.reserve(n);
  for (int i = 0; i < n; ++i) input.emplace_back(CPoint(pts.x(i), pts.y(i)), i);

  Delaunay dt;
  dt.insert(input.begin(), input.end());

  std::vector<Delaunay::Vertex_handle> vh(n, Delaunay::Vertex_handle());
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
    vh[v->info()] = v;
  if (static_cast<int>(dt.number_of_vertices()) != n) {
    for (int i = 0; i < n; ++i) {
      if (vh[i] != Delaunay::Vertex_handle()) continue;
      const int j = dt.nearest_vertex(input[i].first)->info();
      std::ostringstream s;
      s << "tessera: two cell centres at the same position (" << pts.x(i) << ", " << pts.y(i)
        << "): " << point_name(name_of(j), ids) << " and " << point_name(name_of(i), ids)
        << "; move or delete one of them";
      throw Error(s.str());
    }
  }
  if (dt.dimension() < 2) {
    std::ostringstream s;
    s << "tessera: need at least 3 non-collinear points to tessellate; all " << n
      << " points are on one line";
    throw Error(s.str());
  }

  Built out;
  Tessellation &t = out.t;
  t.n_points = n;
  t.n_owned = n_owned;
  t.cell_offset.assign(n_owned + 1, 0);
  t.area.assign(n_owned, 0.0);
  t.perimeter.assign(n_owned, 0.0);
  t.cell_vertex.reserve(static_cast<size_t>(6.2 * n_owned));
  t.cell_neighbor.reserve(static_cast<size_t>(6.2 * n_owned));
  t.triangles.reserve(static_cast<size_t>(2.2 * n_owned));
  t.vertices.reserve(static_cast<size_t>(2.2 * n_owned));
  t.radius.reserve(static_cast<size_t>(2.2 * n_owned));

  for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f) f->info() = -1;
  std::vector<Delaunay::Face_handle> face_of;
  face_of.reserve(static_cast<size_t>(2.2 * n_owned));
  // Gives face f a triangle index (and its circumcentre) on first sight.
  auto index_of = [&](Delaunay::Face_handle f) {
    if (f->info() < 0) {
      f->info() = static_cast<int>(t.triangles.size());
      const int a = f->vertex(0)->info(), b = f->vertex(1)->info(), d = f->vertex(2)->info();
      t.triangles.push_back({a, b, d});
      Vec2 h;
      double r;
      circumcentre(pts.x(a), pts.y(a), pts.x(b), pts.y(b), pts.x(d), pts.y(d), h, r);
      t.vertices.push_back(h);
      t.radius.push_back(r);
      face_of.push_back(f);
    }
    return f->info();
  };

  for (int c = 0; c < n_owned; ++c) {
    const auto v = vh[c];
    auto fc = dt.incident_faces(v), done = fc;
    bool unbounded = false;
    do {
      if (dt.is_infinite(fc)) {
        unbounded = true;
        break;
      }
      const int i = fc->index(v);
      t.cell_vertex.push_back(index_of(fc));
      // Going counter-clockwise around v, the next face shares the edge from v
      // to this face's vertex cw(i): that point is across the Voronoi edge.
      t.cell_neighbor.push_back(fc->vertex(Delaunay::cw(i))->info());
    } while (++fc != done);
    if (unbounded) {
      if (out.unbounded_cell < 0) out.unbounded_cell = c;
      t.cell_vertex.resize(t.cell_offset[c]);
      t.cell_neighbor.resize(t.cell_offset[c]);
    }
    t.cell_offset[c + 1] = static_cast<int>(t.cell_vertex.size());
  }

  t.edge_length.assign(t.cell_vertex.size(), 0.0);
  for (int c = 0; c < n_owned; ++c) {
    const int o = t.cell_offset[c], m = t.cell_size(c);
    double area2 = 0.0, perim = 0.0;
    // Shoelace relative to the cell centre: absolute coordinates far from the
    // origin would cancel catastrophically.
    const double cx = pts.x(c), cy = pts.y(c);
    for (int k = 0; k < m; ++k) {
      const int t0 = t.cell_vertex[o + k], t1 = t.cell_vertex[o + (k + 1) % m];
      const Vec2 &h0 = t.vertices[t0], &h1 = t.vertices[t1];
      area2 += (h0.x - cx) * (h1.y - cy) - (h1.x - cx) * (h0.y - cy);
      const double len = std::hypot(h1.x - h0.x, h1.y - h0.y);
      const double tol = kZeroEdge * std::max(t.radius[t0], t.radius[t1]);
      const double l = len > tol ? len : 0.0;
      t.edge_length[o + k] = l;
      perim += l;
    }
    t.area[c] = 0.5 * area2;
    t.perimeter[c] = perim;
  }

  // Multifold vertices: Delaunay triangles sharing one circumcentre (within
  // the zero-edge tolerance).  Every triangle of an owned cell is compared
  // with its three neighbours; a match seeds a search for all the triangles
  // at that vertex, so that its complete ring of cells is known even where
  // some of them are not owned here.
  auto same_vertex = [&](int a, int b) {
    const double d = std::hypot(t.vertices[a].x - t.vertices[b].x, t.vertices[a].y - t.vertices[b].y);
    return d <= kZeroEdge * std::max(t.radius[a], t.radius[b]);
  };
  t.triangle_group.assign(t.triangles.size(), -1);
  t.group_offset.assign(1, 0);
  const int n_cell_triangles = static_cast<int>(t.triangles.size());
  std::vector<int> stack, members;
  for (int seed = 0; seed < n_cell_triangles; ++seed) {
    if (t.triangle_group[seed] >= 0) continue;
    bool multifold = false;
    for (int e = 0; e < 3 && !multifold; ++e) {
      const auto g = face_of[seed]->neighbor(e);
      if (dt.is_infinite(g)) continue;
      const int gi = index_of(g);
      if (t.triangle_group.size() < t.triangles.size()) t.triangle_group.resize(t.triangles.size(), -1);
      multifold = same_vertex(seed, gi);
    }
    if (!multifold) continue;
    const int group = static_cast<int>(t.group_centre.size());
    members.assign(1, seed);
    stack.assign(1, seed);
    t.triangle_group[seed] = group;
    while (!stack.empty()) {
      const int cur = stack.back();
      stack.pop_back();
      for (int e = 0; e < 3; ++e) {
        const auto g = face_of[cur]->neighbor(e);
        if (dt.is_infinite(g)) continue;
        const int gi = index_of(g);
        if (t.triangle_group.size() < t.triangles.size()) t.triangle_group.resize(t.triangles.size(), -1);
        if (t.triangle_group[gi] >= 0 || !same_vertex(seed, gi)) continue;
        t.triangle_group[gi] = group;
        members.push_back(gi);
        stack.push_back(gi);
      }
    }
    Vec2 centre;
    for (int m : members) {
      centre.x += t.vertices[m].x / members.size();
      centre.y += t.vertices[m].y / members.size();
    }
    // The ring of cells around the vertex, counter-clockwise.
    std::vector<int> ring;
    for (int m : members)
      for (int p : t.triangles[m]) ring.push_back(p);
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    std::vector<std::pair<double, int>> by_angle;
    for (int p : ring) by_angle.emplace_back(std::atan2(pts.y(p) - centre.y, pts.x(p) - centre.x), p);
    std::sort(by_angle.begin(), by_angle.end());
    for (const auto &ap : by_angle) t.group_point.push_back(ap.second);
    t.group_offset.push_back(static_cast<int>(t.group_point.size()));
    t.group_centre.push_back(centre);
  }
  t.triangle_group.resize(t.triangles.size(), -1);
  return out;
}

}  // namespace

void Box::validate() const {
  for (int d = 0; d < 2; ++d) {
    if (!std::isfinite(lo[d]) || !std::isfinite(hi[d]) || !(hi[d] > lo[d])) {
      std::ostringstream s;
      s << "tessera: box length in " << (d == 0 ? "x" : "y") << " must be positive and finite, got ["
        << lo[d] << ", " << hi[d] << "]";
      throw Error(s.str());
    }
  }
  if (xy != 0.0)
    throw Error("tessera: triclinic (tilted) boxes are not supported yet; use a box with xy = 0");
}

int Tessellation::coordination_number(int c, double rel_tol) const {
  const int o = cell_offset[c], m = cell_size(c);
  if (m == 0) return 0;
  double mean = 0.0;
  for (int k = 0; k < m; ++k) mean += edge_length[o + k];
  mean /= m;
  int z = 0;
  for (int k = 0; k < m; ++k) z += edge_length[o + k] > rel_tol * mean;
  return z;
}

double Tessellation::multifold_vertex_share() const {
  // A vertex shared by k cells is seen once from each of them; each owned
  // cell contributes 1/k, so copies (periodic images, MPI ranks) add up to one.
  double share = 0.0;
  for (int g = 0; g + 1 < static_cast<int>(group_offset.size()); ++g) {
    const int k = group_offset[g + 1] - group_offset[g];
    int owned = 0;
    for (int j = group_offset[g]; j < group_offset[g + 1]; ++j) owned += group_point[j] < n_owned;
    share += static_cast<double>(owned) / k;
  }
  return share;
}

int Tessellation::count_multifold_vertices() const {
  return static_cast<int>(std::lround(multifold_vertex_share()));
}

Tessellation tessellate_local(const Points &pts, int n_owned, const long *ids,
                              bool throw_if_unbounded) {
  check_finite(pts, ids);
  Built b = build(pts, n_owned, ids, [](int i) { return i; });
  b.t.unbounded_cell = b.unbounded_cell;
  if (b.unbounded_cell >= 0 && throw_if_unbounded) {
    std::ostringstream s;
    s << "tessera: the cell of " << point_name(b.unbounded_cell, ids)
      << " is unbounded (it lies on the convex hull of the points given): the ghost shell "
         "around the owned points is missing or far too thin";
    throw Error(s.str());
  }
  return std::move(b.t);
}

Coverage check_coverage(const Tessellation &t, const double lo[2], const double hi[2]) {
  Coverage cov;
  if (t.unbounded_cell >= 0) {
    cov.ok = false;
    cov.needed_margin = std::numeric_limits<double>::infinity();
    cov.worst_cell = t.unbounded_cell;
    return cov;
  }
  for (int c = 0; c < t.n_owned; ++c) {
    for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k) {
      const int tri = t.cell_vertex[k];
      const Vec2 &h = t.vertices[tri];
      const double r = t.radius[tri];
      const double need = std::max({lo[0] - (h.x - r), (h.x + r) - hi[0], lo[1] - (h.y - r),
                                    (h.y + r) - hi[1]});
      if (need > cov.needed_margin) {
        cov.ok = false;
        cov.needed_margin = need;
        cov.worst_cell = c;
      }
    }
  }
  return cov;
}

void wrap_into_box(const Box &box, std::vector<double> &xy) {
  for (size_t i = 0; i < xy.size(); ++i) {
    const int d = static_cast<int>(i % 2);
    const double L = box.length(d);
    double v = xy[i] - box.lo[d];
    v -= L * std::floor(v / L);
    if (v >= L) v -= L;  // floor of a value just below L can round up
    xy[i] = box.lo[d] + v;
  }
}

Tessellation tessellate_periodic(const Box &box, const Points &pts, const long *ids) {
  box.validate();
  check_finite(pts, ids);
  const int n = pts.n;
  if (n < 3) {
    std::ostringstream s;
    s << "tessera: need at least 3 non-collinear points to tessellate, got " << n;
    throw Error(s.str());
  }
  std::vector<double> own(2 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    own[2 * i] = pts.x(i);
    own[2 * i + 1] = pts.y(i);
  }
  wrap_into_box(box, own);

  const double L[2] = {box.length(0), box.length(1)};
  double margin = 2.0 * std::sqrt(box.area() / n);
  const double max_margin = 4.0 * std::max(L[0], L[1]) + margin;
  std::vector<double> all;
  std::vector<int> origin;
  while (true) {
    const double lo[2] = {box.lo[0] - margin, box.lo[1] - margin};
    const double hi[2] = {box.hi[0] + margin, box.hi[1] + margin};
    all.assign(own.begin(), own.end());
    origin.resize(n);
    std::iota(origin.begin(), origin.end(), 0);
    const int sx = static_cast<int>(std::ceil(margin / L[0]));
    const int sy = static_cast<int>(std::ceil(margin / L[1]));
    for (int i = -sx; i <= sx; ++i) {
      for (int j = -sy; j <= sy; ++j) {
        if (i == 0 && j == 0) continue;
        for (int p = 0; p < n; ++p) {
          const double x = own[2 * p] + i * L[0], y = own[2 * p + 1] + j * L[1];
          if (x < lo[0] || x > hi[0] || y < lo[1] || y > hi[1]) continue;
          all.push_back(x);
          all.push_back(y);
          origin.push_back(p);
        }
      }
    }
    Points ext{all.data(), static_cast<int>(origin.size()), 2};
    Built b = build(ext, n, ids, [&](int i) { return origin[i]; });
    double grow = 0.0;
    if (b.unbounded_cell >= 0) {
      grow = margin;
    } else {
      const Coverage cov = check_coverage(b.t, lo, hi);
      if (cov.ok) {
        b.t.origin = std::move(origin);
        b.t.position.resize(b.t.n_points);
        for (int p = 0; p < b.t.n_points; ++p) b.t.position[p] = Vec2{all[2 * p], all[2 * p + 1]};
        return std::move(b.t);
      }
      grow = std::max(0.5 * margin, 1.25 * cov.needed_margin);
    }
    if (margin >= max_margin)
      throw Error("tessera: periodic tessellation did not converge (are all points on one line?)");
    margin = std::min(margin + grow, max_margin);
  }
}

}  // namespace tessera
