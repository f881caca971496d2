// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Delaunay triangulation (Mesh, exact predicates) of owned + ghost points and
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
  if (!std::isfinite(xy)) throw Error("tessera: box tilt xy must be finite");
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

void Tessellation::short_edge_clusters(double min_length, std::vector<int> &offset,
                                       std::vector<int> &members) const {
  offset.assign(1, 0);
  members.clear();
  const int nt = static_cast<int>(triangles.size());
  std::vector<char> seen(nt, 0);
  std::vector<int> stack, tris, pts;
  const double l2 = min_length * min_length;
  // The triangles' neighbours, from their edges (each interior edge is
  // shared by two triangles); not kept in the Tessellation, whose memory per
  // cell a run keeps between steps.
  std::vector<std::array<int, 3>> own_neighbor;
  const std::vector<std::array<int, 3>> *nbr = &own_neighbor;
  {
    std::vector<std::array<long, 3>> edges;  // (min point, max point, triangle * 3 + side)
    edges.reserve(3 * static_cast<size_t>(nt));
    for (int k = 0; k < nt; ++k)
      for (int e = 0; e < 3; ++e) {
        const int a = triangles[k][(e + 1) % 3], b = triangles[k][(e + 2) % 3];
        edges.push_back({std::min(a, b), std::max(a, b), 3L * k + e});
      }
    std::sort(edges.begin(), edges.end());
    own_neighbor.assign(nt, {-1, -1, -1});
    for (size_t i = 0; i + 1 < edges.size(); ++i)
      if (edges[i][0] == edges[i + 1][0] && edges[i][1] == edges[i + 1][1]) {
        own_neighbor[edges[i][2] / 3][edges[i][2] % 3] = static_cast<int>(edges[i + 1][2] / 3);
        own_neighbor[edges[i + 1][2] / 3][edges[i + 1][2] % 3] = static_cast<int>(edges[i][2] / 3);
        ++i;
      }
  }
  auto close = [&](int a, int b) {
    const double dx = vertices[a].x - vertices[b].x, dy = vertices[a].y - vertices[b].y;
    return dx * dx + dy * dy < l2;
  };
  for (int c = 0; c < n_owned; ++c) {
    for (int k = cell_offset[c]; k < cell_offset[c + 1]; ++k) {
      const int seed = cell_vertex[k];
      if (seen[seed]) continue;
      seen[seed] = 1;
      tris.assign(1, seed);
      stack.assign(1, seed);
      while (!stack.empty()) {
        const int cur = stack.back();
        stack.pop_back();
        for (int e = 0; e < 3; ++e) {
          const int nb = (*nbr)[cur][e];
          if (nb < 0 || seen[nb] || !close(cur, nb)) continue;
          seen[nb] = 1;
          tris.push_back(nb);
          stack.push_back(nb);
        }
      }
      if (tris.size() < 2) continue;
      pts.clear();
      for (int q : tris)
        for (int p : triangles[q]) pts.push_back(p);
      std::sort(pts.begin(), pts.end());
      pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
      members.insert(members.end(), pts.begin(), pts.end());
      offset.push_back(static_cast<int>(members.size()));
    }
  }
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

void Region::bounding_box(double margin, double lo[2], double hi[2]) const {
  // The slanted sides move sideways by margin |b| / by when grown by margin.
  const double side = margin * std::hypot(bx, by) / by;
  lo[0] = o[0] + std::min(0.0, bx) - side;
  hi[0] = o[0] + ax + std::max(0.0, bx) + side;
  lo[1] = o[1] - margin;
  hi[1] = o[1] + by + margin;
}

Coverage check_coverage(const Tessellation &t, const double lo[2], const double hi[2]) {
  return check_coverage(t, Region::rect(lo, hi), 0.0);
}

Coverage check_coverage(const Tessellation &t, const Region &region, double margin) {
  Coverage cov;
  if (t.unbounded_cell >= 0) {
    cov.ok = false;
    cov.needed_margin = std::numeric_limits<double>::infinity();
    cov.worst_cell = t.unbounded_cell;
    return cov;
  }
  // Inward unit normal of the left side (along b through o); the right side
  // (through o + a) has the opposite one.
  const double blen = std::hypot(region.bx, region.by);
  const double nx = region.by / blen, ny = -region.bx / blen;
  const double ox = region.o[0], oy = region.o[1];
  // The triangles used by owned cells are those with an owned corner; one
  // sequential pass over the triangles visits each once.
  int worst = -1;
  for (size_t k = 0; k < t.triangles.size(); ++k) {
    const auto &tri = t.triangles[k];
    if (tri[0] >= t.n_owned && tri[1] >= t.n_owned && tri[2] >= t.n_owned) continue;
    const Vec2 &h = t.vertices[k];
    const double r = t.radius[k] - margin;
    const double dx = h.x - ox, dy = h.y - oy;
    const double left = nx * dx + ny * dy;
    const double right = -(nx * (dx - region.ax) + ny * dy);
    const double need = r - std::min(std::min(dy, region.by - dy), std::min(left, right));
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
  const double lx = box.length(0), ly = box.length(1);
  auto wrap01 = [](double s) {
    s -= std::floor(s);
    return s >= 1.0 ? 0.0 : s;  // floor of a value just below 1 can round up
  };
  for (size_t i = 0; i + 1 < xy.size(); i += 2) {
    const double sy = wrap01((xy[i + 1] - box.lo[1]) / ly);
    const double shift = std::floor((xy[i + 1] - box.lo[1]) / ly);
    // x relative to the box's left side at this height, after the y wrap
    const double x = xy[i] - shift * box.xy - box.lo[0] - sy * box.xy;
    const double sx = wrap01(x / lx);
    xy[i] = box.lo[0] + sx * lx + sy * box.xy;
    xy[i + 1] = box.lo[1] + sy * ly;
  }
}

Tessellation tessellate_periodic(const Box &box, const Points &pts, const long *ids) {
  box.validate();
  const int n = pts.n;
  // One or two cells, or cells on one line, are a valid periodic tiling:
  // their images complete it (the margin grows below until they do).
  if (n < 1) throw Error("tessera: no points to tessellate in the periodic box");
  std::vector<double> own(2 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    own[2 * i] = pts.x(i);
    own[2 * i + 1] = pts.y(i);
  }
  wrap_into_box(box, own);

  const double lx = box.length(0), ly = box.length(1);
  const Region region = box.region();
  double margin = 2.0 * std::sqrt(box.area() / n);
  const double max_margin = 4.0 * std::max(lx + std::fabs(box.xy), ly) + margin;
  std::vector<double> all;
  std::vector<int> origin;
  while (true) {
    all.assign(own.begin(), own.end());
    origin.resize(n);
    std::iota(origin.begin(), origin.end(), 0);
    // Images p + i (lx, 0) + j (xy, ly) inside the box grown by margin.
    double blo[2], bhi[2];
    region.bounding_box(margin, blo, bhi);
    const int sy = static_cast<int>(std::ceil(margin / ly)) + 1;
    const int sx = static_cast<int>(std::ceil((margin + sy * std::fabs(box.xy)) / lx)) + 1;
    const double blen = std::hypot(box.xy, ly);
    for (int j = -sy; j <= sy; ++j) {
      for (int i = -sx; i <= sx; ++i) {
        if (i == 0 && j == 0) continue;
        for (int p = 0; p < n; ++p) {
          const double x = own[2 * p] + i * lx + j * box.xy, y = own[2 * p + 1] + j * ly;
          if (x < blo[0] || x > bhi[0] || y < blo[1] || y > bhi[1]) continue;
          // inside the parallelogram grown by margin
          const double dx = x - region.o[0], dy = y - region.o[1];
          const double left = (ly * dx - box.xy * dy) / blen;
          const double right = -(ly * (dx - lx) - box.xy * dy) / blen;
          if (left < -margin || right < -margin) continue;
          all.push_back(x);
          all.push_back(y);
          origin.push_back(p);
        }
      }
    }
    Points ext{all.data(), static_cast<int>(origin.size()), 2};
    Mesh mesh;
    try {
      mesh.build(ext, ids, origin.data());
    } catch (const Error &) {
      // Fewer than 3 points, or all on one line, within this margin (a
      // single cell, or a row of cells whose images across the box are
      // still outside it): images further out make the set two-dimensional.
      // Any other error (coincident points, ...) stands.
      if (!(origin.size() < 3 || mesh.collinear()) || margin >= max_margin) throw;
      margin = std::min(2.0 * margin, max_margin);
      continue;
    }
    Tessellation t;
    mesh.cells(ext, n, t);
    double grow = 0.0;
    if (t.unbounded_cell >= 0) {
      grow = margin;
    } else {
      const Coverage cov = check_coverage(t, region, margin);
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
