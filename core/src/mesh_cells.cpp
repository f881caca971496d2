// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh::cells: the Voronoi cells read off the triangulation (polygons, edge
// lengths, areas, perimeters, multifold vertices).

#include "mesh_detail.h"

namespace tessera {

namespace detail {
unsigned long next_stamp() {
  static unsigned long counter = 0;
  return ++counter;
}
}  // namespace detail

void Mesh::cell_geometry(const Points &pts, const std::array<int, 3> *TRI, double cx, double cy,
                         const int *cv, int len, const Vec2 *H, const double *RAD, double *el,
                         double &area, double &perimeter) const {
  double area2 = 0.0, perim = 0.0;
  // In chunks: the squared lengths (and the area), then their square roots
  // two at a time, then the lengths.
  constexpr int kChunk = 32;
  double q[kChunk];
  for (int k0 = 0; k0 < len; k0 += kChunk) {
    const int k1 = std::min(len, k0 + kChunk);
    for (int k = k0; k < k1; ++k) {
      const Vec2 &h0 = H[cv[k]], &h1 = H[cv[k + 1 == len ? 0 : k + 1]];
      area2 += (h0.x - cx) * (h1.y - cy) - (h1.x - cx) * (h0.y - cy);
      const double dx = h1.x - h0.x, dy = h1.y - h0.y;
      q[k - k0] = dx * dx + dy * dy;
    }
    roots(q, k1 - k0);
    for (int k = k0; k < k1; ++k) {
      const int t0 = cv[k], t1 = cv[k + 1 == len ? 0 : k + 1];
      const double d = q[k - k0];
      const double l = zero_edge(d, t0, t1, RAD, pts, TRI) ? 0.0 : d;
      el[k] = l;
      perim += l;
      if (l == 0.0)
        seeds_.push_back(t0);
    }
  }
  area = 0.5 * area2;
  perimeter = perim;
}

void Mesh::cells(const Points &pts, int n_owned, Tessellation &t) const {
  const int nt = static_cast<int>(v_.size() / 3);
  t.n_points = n_points_;
  t.n_owned = n_owned;
  t.unbounded_cell = -1;

  // Finite triangles, numbered compactly, with their circumcentres.
  // Local, not members: only rebuilds (and callers outside a run) come here,
  // and a run's memory per cell is what it keeps between steps.
  std::vector<int> compact(nt), mesh_of(nt);
  t.triangles.resize(nt);
  t.vertices.resize(nt);
  t.radius.resize(nt);
  int nft = 0;
  for (int m = 0; m < nt; ++m) {
    const int a = v_[3 * m], b = v_[3 * m + 1], c = v_[3 * m + 2];
    if (a == kInfinite || b == kInfinite || c == kInfinite) {
      compact[m] = -1;
      continue;
    }
    compact[m] = nft;
    mesh_of[nft] = m;
    t.triangles[nft] = {a, b, c};
    circumcentre(pts.x(a), pts.y(a), pts.x(b), pts.y(b), pts.x(c), pts.y(c), t.vertices[nft],
                 t.radius[nft]);
    ++nft;
  }
  t.triangles.resize(nft);
  t.vertices.resize(nft);
  t.radius.resize(nft);
  mesh_of.resize(nft);

  auto same_vertex = [&](int a, int b) { return same_centre(pts, t, a, b); };
  // Multifold vertices (triangles sharing one circumcentre) are seeded while
  // the cells are read: a zero-length edge of an owned cell marks two such
  // triangles.  The one case an owned cell's polygon cannot show is the
  // Delaunay edge opposite the cell in its triangle (x, y): if x or y is
  // owned, its own polygon shows it; if both are ghosts it is checked here.
  seeds_.clear();

  t.cell_offset.resize(n_owned + 1);
  t.cell_offset[0] = 0;
  t.area.resize(n_owned);
  t.perimeter.resize(n_owned);
  // Written through raw pointers with room checked per triangle: push_back's
  // bookkeeping was a measurable part of a step.
  size_t cap = std::max<size_t>(t.cell_vertex.capacity(), 7 * static_cast<size_t>(n_owned) + 64);
  t.cell_vertex.resize(cap);
  t.cell_neighbor.resize(cap);
  t.edge_length.resize(cap);
  size_t used = 0;
  for (int c = 0; c < n_owned; ++c) {
    const size_t o = used;
    const int start = vt_[c];
    int m = start;
    bool unbounded = false;
    do {
      const int *v = &v_[3 * m];
      const int i = (v[1] == c) + 2 * (v[2] == c); // index of c, without branches
      const int cm = compact[m];
      if (cm < 0) {
        unbounded = true;
        break;
      }
      if (used == cap) {
        cap *= 2;
        t.cell_vertex.resize(cap);
        t.cell_neighbor.resize(cap);
        t.edge_length.resize(cap);
      }
      t.cell_vertex[used] = cm;
      // Counter-clockwise around c the next triangle shares the edge from c to
      // this triangle's vertex i+2; that point is across the Voronoi edge.
      const int i1 = i == 2 ? 0 : i + 1, i2 = i1 == 2 ? 0 : i1 + 1;
      t.cell_neighbor[used] = v[i2];
      ++used;
      if (v[i1] >= n_owned && v[i2] >= n_owned) {
        const int g = compact[nb_[3 * m + i]];
        if (g >= 0 && same_vertex(cm, g))
          seeds_.push_back(cm);
      }
      m = nb_[3 * m + i1];
    } while (m != start);
    if (unbounded) {
      if (t.unbounded_cell < 0)
        t.unbounded_cell = c;
      used = o;
    }
    const int len = static_cast<int>(used - o);
    canonical_ring(&t.cell_vertex[o], &t.cell_neighbor[o], len);
    t.cell_offset[c + 1] = static_cast<int>(used);
    cell_geometry(pts, t.triangles.data(), pts.x(c), pts.y(c), &t.cell_vertex[o], len,
                  t.vertices.data(), t.radius.data(), &t.edge_length[o], t.area[c], t.perimeter[c]);
  }
  t.cell_vertex.resize(used);
  t.cell_neighbor.resize(used);
  t.edge_length.resize(used);

  find_groups(pts, t, [&](int m) { return compact[m]; }, [&](int k) { return mesh_of[k]; });
  last_incremental_ = false;
  t.mesh_stamp = stamp_ = detail::next_stamp();
}


}  // namespace tessera
