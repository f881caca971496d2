// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Delaunay triangulation (CGAL, exact predicates) of owned + ghost points and
// the owned cells' Voronoi polygons read off it.

#include "tessera/tessellation.h"

#include "tessera/mesh.h"

#include "point_name.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <utility>

namespace tessera {

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
  if (n_owned < 0 || n_owned > pts.n) throw Error("tessera: n_owned must be in [0, number of points]");
  Mesh mesh;
  mesh.build(pts, ids);
  Tessellation t;
  mesh.cells(pts, n_owned, t);
  if (t.unbounded_cell >= 0 && throw_if_unbounded) {
    std::ostringstream s;
    s << "tessera: the cell of " << point_name(t.unbounded_cell, ids)
      << " is unbounded (it lies on the convex hull of the points given): the ghost shell "
         "around the owned points is missing or far too thin";
    throw Error(s.str());
  }
  return t;
}

Coverage check_coverage(const Tessellation &t, const double lo[2], const double hi[2]) {
  Coverage cov;
  if (t.unbounded_cell >= 0) {
    cov.ok = false;
    cov.needed_margin = std::numeric_limits<double>::infinity();
    cov.worst_cell = t.unbounded_cell;
    return cov;
  }
  // The triangles used by owned cells are those with an owned corner; one
  // sequential pass over the triangles visits each once.
  int worst = -1;
  for (size_t k = 0; k < t.triangles.size(); ++k) {
    const auto &tri = t.triangles[k];
    if (tri[0] >= t.n_owned && tri[1] >= t.n_owned && tri[2] >= t.n_owned) continue;
    const Vec2 &h = t.vertices[k];
    const double r = t.radius[k];
    const double need = std::max(std::max(lo[0] - (h.x - r), (h.x + r) - hi[0]),
                                 std::max(lo[1] - (h.y - r), (h.y + r) - hi[1]));
    if (need > cov.needed_margin) {
      cov.ok = false;
      cov.needed_margin = need;
      worst = static_cast<int>(k);
    }
  }
  if (worst >= 0) {
    const auto &tri = t.triangles[worst];
    cov.worst_cell = std::min({tri[0], tri[1], tri[2]});
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
    Mesh mesh;
    mesh.build(ext, ids, origin.data());
    Tessellation t;
    mesh.cells(ext, n, t);
    double grow = 0.0;
    if (t.unbounded_cell >= 0) {
      grow = margin;
    } else {
      const Coverage cov = check_coverage(t, lo, hi);
      if (cov.ok) {
        t.origin = std::move(origin);
        t.position.resize(t.n_points);
        for (int p = 0; p < t.n_points; ++p) t.position[p] = Vec2{all[2 * p], all[2 * p + 1]};
        return t;
      }
      grow = std::max(0.5 * margin, 1.25 * cov.needed_margin);
    }
    if (margin >= max_margin)
      throw Error("tessera: periodic tessellation did not converge (are all points on one line?)");
    margin = std::min(margin + grow, max_margin);
  }
}

}  // namespace tessera
