// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The cell view of cells on a sphere (tessera/sphere_cells.h): the owned
// cells' edges in compressed rows with the caller's neighbour indices, the
// multifold vertices (poles shared by several triangles, joined by edges of
// length 0), and the centroid and second moments of a spherical polygon.

#include "tessera/sphere_cells.h"

#include "sphere_vec.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tessera {

using namespace sphere_detail;

void SphereCells::bind(const SphereTessellation &t) {
  t_ = &t;
  owned_.resize(t.n_points);
  std::iota(owned_.begin(), owned_.end(), 0);
  n_points_ = t.n_points;
  own_points_ = true;
  pts_ = Points3();
  std::vector<int> index(t.n_points);
  std::iota(index.begin(), index.end(), 0);
  build(index);
}

void SphereCells::bind(const SphereTessellation &t, const std::vector<int> &owned,
                       const std::vector<int> &point_index, int n_points, const Points3 &pts) {
  t_ = &t;
  owned_ = owned;
  n_points_ = n_points;
  pts_ = pts;
  own_points_ = false;
  build(point_index);
}

void SphereCells::build(const std::vector<int> &index) {
  const SphereTessellation &t = *t_;
  index_ = index;
  const int n = static_cast<int>(owned_.size());
  missing_.clear();
  auto mapped = [&](int p) {
    const int q = index[p];
    if (q < 0) missing_.push_back(p);
    return q;
  };
  offset_.assign(1, 0);
  neighbor_.clear();
  v0_.clear();
  v1_.clear();
  size_.clear();
  for (int c = 0; c < n; ++c) {
    const int g = owned_[c], o = t.cell_offset[g], m = t.cell_size(g);
    for (int k = o; k < o + m; ++k) {
      neighbor_.push_back(mapped(t.cell_neighbor[k]));
      size_.push_back(t.edge_length[k]);
      v0_.push_back(t.cell_vertex[k]);
      v1_.push_back(t.cell_vertex[o + (k - o + 1) % m]);
    }
    offset_.push_back(static_cast<int>(neighbor_.size()));
  }
  // Multifold vertices: triangles joined by zero-length edges share a pole.
  std::vector<std::vector<int>> found;
  clusters(0.0, 2, found);
  ring_offset_.assign(1, 0);
  ring_.clear();
  for (const auto &mm : found) {
    if (mm.size() < 4) continue;
    for (int p : mm) ring_.push_back(mapped(p));
    ring_offset_.push_back(static_cast<int>(ring_.size()));
  }
  std::sort(missing_.begin(), missing_.end());
  missing_.erase(std::unique(missing_.begin(), missing_.end()), missing_.end());
}

void SphereCells::clusters(double below, int min_triangles,
                           std::vector<std::vector<int>> &out) const {
  const SphereTessellation &t = *t_;
  out.clear();
  const int nt = static_cast<int>(t.triangles.size());
  std::vector<int> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  bool any = false;
  for (int g = 0; g < t.n_points; ++g) {
    const int o = t.cell_offset[g], m = t.cell_size(g);
    for (int k = o; k < o + m; ++k) {
      const double l = t.edge_length[k];
      if (below > 0.0 ? !(l < below) : l != 0.0) continue;
      const int a = root(t.cell_vertex[k]), b = root(t.cell_vertex[o + (k - o + 1) % m]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
      any = true;
    }
  }
  if (!any) return;
  std::vector<char> wanted(nt, 0);
  for (size_t k = 0; k < v0_.size(); ++k) wanted[root(v0_[k])] = 1;
  std::vector<int> count(nt, 0);
  std::vector<std::vector<int>> members(nt);
  for (int tri = 0; tri < nt; ++tri) {
    const int r = root(tri);
    if (!wanted[r]) continue;
    ++count[r];
    for (int p : t.triangles[tri]) members[r].push_back(p);
  }
  for (int r = 0; r < nt; ++r) {
    if (count[r] < min_triangles) continue;
    std::vector<int> &mm = members[r];
    std::sort(mm.begin(), mm.end());
    mm.erase(std::unique(mm.begin(), mm.end()), mm.end());
    out.push_back(std::move(mm));
  }
}

bool SphereCells::short_edge_clusters(double min_length, std::vector<int> &offset,
                                      std::vector<int> &members) const {
  std::vector<std::vector<int>> found;
  clusters(min_length, 2, found);
  offset.assign(1, 0);
  members.clear();
  for (const auto &mm : found) {
    for (int p : mm)
      if (index_[p] >= 0) members.push_back(index_[p]);
    offset.push_back(static_cast<int>(members.size()));
  }
  return true;
}

int SphereCells::piece_corners(int k, std::vector<double> &xyz) const {
  const Vec3 a = t_->vertex(v0_[k]), b = t_->vertex(v1_[k]);
  xyz.insert(xyz.end(), {a.x, a.y, a.z, b.x, b.y, b.z});
  return 2;
}

void SphereCells::point(int i, double *x) const {
  const SphereTessellation &t = *t_;
  if (own_points_) {
    const Vec3 p = t.point(i);
    x[0] = p.x;
    x[1] = p.y;
    x[2] = p.z;
    return;
  }
  const double *p = pts_.p(i);
  const V d{p[0] - t.centre.x, p[1] - t.centre.y, p[2] - t.centre.z};
  const double l = norm(d);
  const double s = l > 0.0 ? t.R / l : 0.0;
  x[0] = t.centre.x + s * d.x;
  x[1] = t.centre.y + s * d.y;
  x[2] = t.centre.z + s * d.z;
}

Contacts SphereCells::contacts() const {
  Contacts c;
  if (!t_) return c;
  c.n_owned = n_owned();
  c.offset = offset_.data();
  c.neighbor = neighbor_.data();
  c.size = size_.data();
  return c;
}

int SphereCells::multifold_count() const {
  return t_ ? static_cast<int>(ring_offset_.size()) - 1 : 0;
}

void SphereCells::multifold_ring(int g, std::vector<int> &ring) const {
  ring.assign(ring_.begin() + ring_offset_[g], ring_.begin() + ring_offset_[g + 1]);
}

void SphereCells::centroid(int c, double *x) const {
  const SphereTessellation &t = *t_;
  V w{0.0, 0.0, 0.0};
  for (int k = offset_[c]; k < offset_[c + 1]; ++k) {
    const V a = vv(t.vertex_direction[v0_[k]]), b = vv(t.vertex_direction[v1_[k]]);
    const V m = cross(a, b);
    const double s = norm(m);
    if (!(s > 0.0)) continue;
    add_to(w, (std::atan2(s, dot(a, b)) / s) * m);
  }
  const double l = norm(w);
  const V u = l > 0.0 ? (1.0 / l) * w : vv(t.direction[owned_[c]]);
  x[0] = t.centre.x + t.R * u.x;
  x[1] = t.centre.y + t.R * u.y;
  x[2] = t.centre.z + t.R * u.z;
}

bool SphereCells::planar_moments(int c, double m2[3], double e1[3], double e2[3]) const {
  const SphereTessellation &t = *t_;
  const V u = vv(t.direction[owned_[c]]);
  // A tangent basis: e1 along the axis least aligned with u, made normal to it.
  const double au[3] = {std::fabs(u.x), std::fabs(u.y), std::fabs(u.z)};
  const int ax = au[0] <= au[1] && au[0] <= au[2] ? 0 : (au[1] <= au[2] ? 1 : 2);
  V a{ax == 0 ? 1.0 : 0.0, ax == 1 ? 1.0 : 0.0, ax == 2 ? 1.0 : 0.0};
  a = a - dot(a, u) * u;
  const V b1 = (1.0 / norm(a)) * a, b2 = cross(u, b1);
  e1[0] = b1.x, e1[1] = b1.y, e1[2] = b1.z;
  e2[0] = b2.x, e2[1] = b2.y, e2[2] = b2.z;
  auto image = [&](int vtx, double y[2]) {
    const V v = vv(t.vertex_direction[vtx]);
    const double h = dot(v, u);
    // Gnomonic (central) projection; a vertex 90 degrees or more away (only
    // in tessellations of a handful of points) falls back to the orthographic one.
    const double s = h > 1e-6 ? t.R / h : t.R;
    y[0] = s * dot(v, b1);
    y[1] = s * dot(v, b2);
  };
  double m0 = 0.0, mx = 0.0, my = 0.0, mxx = 0.0, myy = 0.0, mxy = 0.0;
  for (int k = offset_[c]; k < offset_[c + 1]; ++k) {
    double p[2], q[2];
    image(v0_[k], p);
    image(v1_[k], q);
    const double cr = p[0] * q[1] - q[0] * p[1];
    m0 += 0.5 * cr;
    mx += cr * (p[0] + q[0]) / 6.0;
    my += cr * (p[1] + q[1]) / 6.0;
    mxx += cr * (p[0] * p[0] + p[0] * q[0] + q[0] * q[0]) / 12.0;
    myy += cr * (p[1] * p[1] + p[1] * q[1] + q[1] * q[1]) / 12.0;
    mxy += cr * (2 * p[0] * p[1] + p[0] * q[1] + q[0] * p[1] + 2 * q[0] * q[1]) / 24.0;
  }
  if (!(m0 > 0.0)) {
    m2[0] = m2[1] = m2[2] = 0.0;
    return false;
  }
  m2[0] = mxx - mx * mx / m0;
  m2[1] = myy - my * my / m0;
  m2[2] = mxy - mx * my / m0;
  return true;
}

void SphereCells::second_moments(int c, double *out) const {
  double m[3], e1[3], e2[3];
  planar_moments(c, m, e1, e2);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      out[3 * a + b] = m[0] * e1[a] * e1[b] + m[1] * e2[a] * e2[b] +
                       m[2] * (e1[a] * e2[b] + e2[a] * e1[b]);
}

bool SphereCells::principal_axis(int c, bool longest, double *x) const {
  double m[3], e1[3], e2[3];
  if (!planar_moments(c, m, e1, e2)) return false;
  const double sxx = m[0], syy = m[1], sxy = m[2];
  if (!(sxx + syy > 0.0) || !(std::hypot(sxx - syy, 2.0 * sxy) > 1e-12 * (sxx + syy))) return false;
  double th = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  if (!longest) th += 0.5 * 3.14159265358979323846;
  for (int d = 0; d < 3; ++d) x[d] = std::cos(th) * e1[d] + std::sin(th) * e2[d];
  return true;
}

}  // namespace tessera
