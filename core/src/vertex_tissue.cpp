// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The vertex model's tissue: geometry through the minimum image, energy and
// forces, the consistency and validity check, and the start from Voronoi
// polygons.

#include "tessera/vertex_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

namespace tessera {

bool VertexTissue::complete(int c) const {
  if (c < 0 || rings[c].empty())
    return false;
  for (int v : rings[c])
    if (!known(v))
      return false;
  return true;
}

Vec2 VertexTissue::image(double dx, double dy) const {
  if (periodic) {
    const double lx = box.length(0), ly = box.length(1);
    // Within a quarter period both shifts below are 0 (floor of a number in
    // [0.25, 0.75]): the same sums with 0, without the divisions and floors.
    if (std::fabs(dy) < 0.25 * ly && std::fabs(dx) < 0.25 * lx)
      return Vec2{dx - 0.0 * box.xy - 0.0 * lx, dy - 0.0 * ly};
  }
  return image_reference(dx, dy);
}

Vec2 VertexTissue::image_reference(double dx, double dy) const {
  if (periodic) {
    const double lx = box.length(0), ly = box.length(1);
    const double j = std::floor(dy / ly + 0.5);
    dx -= j * box.xy;
    dy -= j * ly;
    const double i = std::floor(dx / lx + 0.5);
    dx -= i * lx;
  }
  return Vec2{dx, dy};
}

void VertexTissue::polygon(int c, std::vector<double> &xy) const {
  const std::vector<int> &r = rings[c];
  const int n = static_cast<int>(r.size());
  xy.resize(2 * static_cast<size_t>(n));
  if (n == 0)
    return;
  double x = pos[r[0]].x, y = pos[r[0]].y;
  xy[0] = x;
  xy[1] = y;
  for (int k = 1; k < n; ++k) {
    const Vec2 d = delta(r[k - 1], r[k]);
    x += d.x;
    y += d.y;
    xy[2 * k] = x;
    xy[2 * k + 1] = y;
  }
}

PolygonMeasures VertexTissue::measures(int c) const {
  std::vector<double> xy;
  polygon(c, xy);
  return polygon_measures(xy.data(), static_cast<int>(rings[c].size()));
}

void EdgeMap::build(const VertexTissue &t) {
  dup_a = dup_b = -1;
  // (rings may name vertices beyond pos in a broken tissue: sized to hold them)
  int nv = t.n_vertices();
  for (const std::vector<int> &r : t.rings)
    for (int v : r)
      nv = std::max(nv, v + 1);
  first_.assign(static_cast<size_t>(nv) + 1, 0);
  for (const std::vector<int> &r : t.rings)
    for (int v : r)
      if (v >= 0)
        first_[v + 1]++;
  for (int v = 0; v < nv; ++v)
    first_[v + 1] += first_[v];
  to_.resize(first_[nv]);
  cell_.resize(first_[nv]);
  fill_.assign(first_.begin(), first_.end() - 1);
  // In the order of the cells: the first cell to hold an edge keeps it, and
  // the first repeated edge is the one reported.
  for (int c = 0; c < t.n_cells(); ++c) {
    const std::vector<int> &r = t.rings[c];
    const int n = static_cast<int>(r.size());
    for (int k = 0; k < n; ++k) {
      const int a = r[k], b = r[k + 1 == n ? 0 : k + 1];
      if (a < 0)
        continue;
      bool dup = false;
      for (int e = first_[a]; e < fill_[a] && !dup; ++e)
        dup = to_[e] == b;
      if (dup) {
        if (dup_a < 0) {
          dup_a = a;
          dup_b = b;
        }
        continue;
      }
      to_[fill_[a]] = b;
      cell_[fill_[a]++] = c;
    }
  }
  // Slots left by repeated edges: an edge to no vertex.
  for (int v = 0; v < nv; ++v)
    for (int e = fill_[v]; e < first_[v + 1]; ++e) {
      to_[e] = -2;
      cell_[e] = -1;
    }
}

int twin_cell(const VertexTissue &t, const EdgeMap &m, int c, int k) {
  const std::vector<int> &r = t.rings[c];
  const int n = static_cast<int>(r.size());
  return m.cell(r[k + 1 == n ? 0 : k + 1], r[k]);
}

namespace {

// Types across the edges of cell c (its own type where no cell is across).
void neighbour_types(const VertexTissue &t, const EdgeMap &m, int c, std::vector<int> &nt) {
  const int n = static_cast<int>(t.rings[c].size());
  nt.resize(n);
  for (int k = 0; k < n; ++k) {
    const int o = twin_cell(t, m, c, k);
    nt[k] = o >= 0 ? t.type[o] : t.type[c];
  }
}

} // namespace

double tissue_energy(const VertexTissue &t, const Model &model, std::vector<double> *cell_energy) {
  const EdgeMap m(t);
  std::vector<double> xy;
  std::vector<int> nt;
  double e = 0.0;
  if (cell_energy)
    cell_energy->assign(t.n_cells(), 0.0);
  for (int c = 0; c < t.n_cells(); ++c) {
    if (t.rings[c].empty())
      continue;
    t.polygon(c, xy);
    neighbour_types(t, m, c, nt);
    const double ec = polygon_energy(xy.data(), static_cast<int>(t.rings[c].size()), model, c,
                                     t.type[c], nt.data(), nullptr);
    if (cell_energy)
      (*cell_energy)[c] = ec;
    e += ec;
  }
  return e;
}

double tissue_forces(const VertexTissue &t, const Model &model, std::vector<double> &f,
                     double *virial) {
  const EdgeMap m(t);
  std::vector<double> xy, g;
  std::vector<int> nt;
  f.assign(2 * static_cast<size_t>(t.n_vertices()), 0.0);
  if (virial)
    virial[0] = virial[1] = virial[2] = virial[3] = 0.0;
  double e = 0.0;
  for (int c = 0; c < t.n_cells(); ++c) {
    const std::vector<int> &r = t.rings[c];
    const int n = static_cast<int>(r.size());
    if (n == 0)
      continue;
    t.polygon(c, xy);
    neighbour_types(t, m, c, nt);
    g.resize(2 * static_cast<size_t>(n));
    e += polygon_energy(xy.data(), n, model, c, t.type[c], nt.data(), g.data());
    for (int k = 0; k < n; ++k) {
      f[2 * r[k]] -= g[2 * k];
      f[2 * r[k] + 1] -= g[2 * k + 1];
      if (virial) {
        virial[0] -= xy[2 * k] * g[2 * k];
        virial[1] -= xy[2 * k + 1] * g[2 * k + 1];
        virial[2] -= xy[2 * k] * g[2 * k + 1];
        virial[3] -= xy[2 * k + 1] * g[2 * k];
      }
    }
  }
  return e;
}

void check_tissue(const VertexTissue &t) {
  auto fail = [](const std::string &s) { throw Error("tessera: vertex tissue: " + s); };
  std::vector<int> count(t.n_vertices(), 0);
  std::vector<double> xy;
  std::vector<long> ids;
  for (int c = 0; c < t.n_cells(); ++c) {
    const std::vector<int> &r = t.rings[c];
    if (r.empty())
      continue;
    if (r.size() < 3) {
      std::ostringstream s;
      s << "cell " << t.cid(c) << " has " << r.size() << " vertices (a cell needs three)";
      fail(s.str());
    }
    for (int v : r) {
      if (v < 0 || v >= t.n_vertices() || t.removed(v)) {
        std::ostringstream s;
        s << "cell " << t.cid(c) << " lists a vertex that does not exist or was removed";
        fail(s.str());
      }
      count[v]++;
    }
  }
  const EdgeMap m(t);
  if (m.dup_a >= 0) {
    std::ostringstream s;
    s << "the edge from vertex " << t.vid(m.dup_a) << " to vertex " << t.vid(m.dup_b)
      << " is in two cells in the same direction (a ring runs clockwise or two cells overlap)";
    fail(s.str());
  }
  for (int c = 0; c < t.n_cells(); ++c) {
    const std::vector<int> &r = t.rings[c];
    const int n = static_cast<int>(r.size());
    if (n == 0)
      continue;
    for (int k = 0; k < n; ++k)
      if (twin_cell(t, m, c, k) < 0) {
        std::ostringstream s;
        s << "the edge from vertex " << t.vid(r[k]) << " to vertex " << t.vid(r[(k + 1) % n])
          << " of cell " << t.cid(c) << " has no cell on its other side (the rings do not close)";
        fail(s.str());
      }
    t.polygon(c, xy);
    ids.resize(n);
    for (int k = 0; k < n; ++k)
      ids[k] = t.vid(r[k]);
    const PolygonDefect d = polygon_defect(xy.data(), n, ids.data());
    if (d != PolygonDefect::None) {
      std::ostringstream s;
      s << "cell " << t.cid(c) << " " << describe(d) << " (vertices";
      for (long id : ids)
        s << " " << id;
      s << ")";
      fail(s.str());
    }
  }
  for (int v = 0; v < t.n_vertices(); ++v)
    if (!t.removed(v) && count[v] != 3) {
      std::ostringstream s;
      s << "vertex " << t.vid(v) << " is in " << count[v] << " cells (every vertex is in three)";
      fail(s.str());
    }
  if (t.periodic) {
    double sum = 0.0;
    for (int c = 0; c < t.n_cells(); ++c)
      if (!t.rings[c].empty())
        sum += t.measures(c).area;
    if (!(std::fabs(sum - t.box.area()) <= 1e-9 * t.box.area())) {
      std::ostringstream s;
      s.precision(12);
      s << "the cells' areas add up to " << sum << ", not to the box's " << t.box.area()
        << " (the rings do not tile the periodic box once)";
      fail(s.str());
    }
  }
}

VertexTissue vertex_tissue_from_voronoi(const Box &box, const Points &pts, const int *type,
                                        const long *ids) {
  const Tessellation tess = tessellate_periodic(box, pts, ids);
  const int n = pts.n;
  const double lx = box.length(0), ly = box.length(1);
  // A Voronoi vertex is a Delaunay triangle up to a lattice translation: its
  // key is the sorted (point, image shift) triple with the shifts taken
  // relative to the smallest entry.
  using Entry = std::array<long, 3>;
  using Key = std::array<Entry, 3>;
  auto key_of = [&](int tri) {
    Key k;
    for (int i = 0; i < 3; ++i) {
      const int p = tess.triangles[tri][i];
      const int o = tess.origin[p];
      const double dy = tess.position[p].y - tess.position[o].y;
      const long sj = std::lround(dy / ly);
      const double dx = tess.position[p].x - tess.position[o].x - sj * box.xy;
      const long si = std::lround(dx / lx);
      k[i] = Entry{o, si, sj};
    }
    std::sort(k.begin(), k.end());
    const Entry base = k[0];
    for (Entry &e : k) {
      e[1] -= base[1];
      e[2] -= base[2];
    }
    return k;
  };
  VertexTissue t;
  t.box = box;
  t.periodic = true;
  t.rings.resize(n);
  t.type.assign(type, type + n);
  if (ids)
    t.cell_id.assign(ids, ids + n);
  // Vertices numbered in the order of their keys, which depends neither on
  // where a polygon's list starts nor on the order of the triangles.
  std::map<Key, int> index;
  std::map<Key, Vec2> where;
  std::vector<std::vector<Key>> ring_keys(n);
  for (int c = 0; c < n; ++c)
    for (int k = tess.cell_offset[c]; k < tess.cell_offset[c + 1]; ++k) {
      const int tri = tess.cell_vertex[k];
      const Key key = key_of(tri);
      ring_keys[c].push_back(key);
      if (where.emplace(key, tess.vertices[tri]).second)
        index.emplace(key, 0);
    }
  for (auto &kv : index) {
    kv.second = t.n_vertices();
    // Wrapped into the box (fractional coordinates in [0, 1)).
    const Vec2 v = where[kv.first];
    std::vector<double> p = {v.x, v.y};
    wrap_into_box(box, p);
    t.pos.push_back(Vec2{p[0], p[1]});
  }
  for (int c = 0; c < n; ++c)
    for (const Key &key : ring_keys[c])
      t.rings[c].push_back(index[key]);
  return t;
}

} // namespace tessera
