// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh3::cells: the owned cells of the kept tetrahedra, as tessellate_local_3d
// builds them from CGAL's (see mesh3d.h).  Face f of cell i towards j is the
// ring of tetrahedra around the Delaunay edge i j, walked from a tetrahedron
// (i j a b) across the triangle (i j b) when (i j a b) is an even
// permutation of its positively oriented corners: the ring then runs
// counter-clockwise about x_j - x_i, as the Tessellation3 convention wants.
// Areas, volumes and surfaces by the formulas of voronoi3d.cpp.

#include "tessera/mesh3d.h"

#include "vec3_detail.h"

#include "point_name.h"

#include <cmath>
#include <utility>

namespace tessera {

namespace {

using namespace detail3;

}  // namespace

void Mesh3::next_stamp() const {
  const size_t nt = tv_.size() / 4;
  if (tmark_.size() < nt) tmark_.resize(nt, 0);
  if (tmap_.size() < nt) tmap_.resize(nt, -1);
  if (++stamp_ == 0) {
    std::fill(tmark_.begin(), tmark_.end(), 0u);
    std::fill(pmark_.begin(), pmark_.end(), 0u);
    stamp_ = 1;
  }
}

// The faces of owned cell i (neighbour, ring of mesh tetrahedra) appended to
// the next cache; false if the cell is unbounded.
bool Mesh3::walk_cell(int i, const long *ids) const {
  const int n = n_points_;
  next_stamp();
  const unsigned st = stamp_;
  // The star of i: every tetrahedron containing it.
  bfs_.clear();
  bfs_.push_back(vt_[i]);
  tmark_[vt_[i]] = st;
  for (size_t h = 0; h < bfs_.size(); ++h) {
    const int m = bfs_[h];
    if (skip_[m])
      throw Error("tessera: Mesh3::cells(): owned " + point_name(i, ids) +
                  " lies outside the region of interest of the last update()");
    for (int s = 0; s < 4; ++s) {
      const int v = tv_[4 * m + s];
      if (v >= n) return false;
      if (v == i) continue;
      const int nb = tn_[4 * m + s];
      if (nb >= 0 && tmark_[nb] != st) {
        tmark_[nb] = st;
        bfs_.push_back(nb);
      }
    }
  }
  for (const int m : bfs_) {
    int li = 0;
    while (tv_[4 * m + li] != i) ++li;
    for (int lj = 0; lj < 4; ++lj) {
      const int j = tv_[4 * m + lj];
      if (lj == li || pmark_[j] == st) continue;
      pmark_[j] = st;
      int la = -1, lb = -1;
      for (int q = 0; q < 4; ++q)
        if (q != li && q != lj) (la < 0 ? la : lb) = q;
      if (parity(li, lj, la, lb) < 0) std::swap(la, lb);
      // Walk around the edge i j: from a tetrahedron (i j a b), positively
      // oriented, cross the triangle (i j b); the ring is then
      // counter-clockwise about x_j - x_i.
      int cur = m, va = tv_[4 * m + la], vb = tv_[4 * m + lb];
      do {
        nx_tet_.push_back(cur);
        int sa = 0;
        while (tv_[4 * cur + sa] != va) ++sa;
        const int nx = tn_[4 * cur + sa];
        int vc = -1;
        for (int q = 0; q < 4; ++q) {
          const int v = tv_[4 * nx + q];
          if (v != i && v != j && v != vb) vc = v;
        }
        va = vb;
        vb = vc;
        cur = nx;
      } while (cur != m);
      nx_nb_.push_back(j);
      nx_foff_.push_back(static_cast<int>(nx_tet_.size()));
    }
  }
  return true;
}

void Mesh3::cells(const Points3 &pts, int n_owned, Tessellation3 &t, const long *ids,
                  bool throw_if_unbounded) const {
  if (!valid_) throw Error("tessera: Mesh3::cells() on an invalid mesh; call build() first");
  if (pts.n != n_points_) throw Error("tessera: Mesh3::cells() with a different number of points");
  if (n_owned < 0 || n_owned > n_points_) throw Error("tessera: n_owned out of range");
  const int n = n_points_;
  t.n_points = n;
  t.n_owned = n_owned;
  t.tets.clear();
  t.vertices.clear();
  t.radius.clear();
  t.cell_offset.assign(1, 0);
  t.face_neighbor.clear();
  t.face_area.clear();
  t.face_offset.assign(1, 0);
  t.face_vertex.clear();
  t.volume.assign(n_owned, 0.0);
  t.surface.assign(n_owned, 0.0);
  t.unbounded_cell = -1;
  t.origin.clear();
  t.position.clear();
  tused_.clear();
  next_stamp();
  // tmap_ is all -1 between calls, also when an Error leaves early.
  struct Reset {
    const Mesh3 &m;
    ~Reset() {
      for (const int k : m.tused_) m.tmap_[k] = -1;
    }
  } reset{*this};

  auto tet_of = [&](int m) {
    if (skip_[m])
      throw Error("tessera: Mesh3::cells(): a tetrahedron of an owned cell lies outside the "
                  "region of interest of the last update()");
    if (tmap_[m] >= 0) return tmap_[m];
    const int id = static_cast<int>(t.tets.size());
    tmap_[m] = id;
    tused_.push_back(m);
    const int *q = &tv_[4 * m];
    t.tets.push_back({q[0], q[1], q[2], q[3]});
    const V3 p0 = load(pts, q[0]);
    const V3 h = circumcentre(p0, load(pts, q[1]), load(pts, q[2]), load(pts, q[3]));
    t.vertices.push_back({h.x, h.y, h.z});
    const V3 dd = h - p0;
    t.radius.push_back(std::sqrt(dot(dd, dd)));
    return id;
  };

  // A cell whose star no flip touched since the last cells() keeps its
  // faces and rings (in mesh numbering); the others walk their star again.
  const bool reuse = cache_ok_ && cache_owned_ == n_owned;
  nx_off_.assign(1, 0);
  nx_nb_.clear();
  nx_foff_.assign(1, 0);
  nx_tet_.clear();
  for (int i = 0; i < n_owned; ++i) {
    bool bounded = true;
    if (reuse && !dirty_[i] && c_off_[i + 1] > c_off_[i]) {
      const int base = static_cast<int>(nx_tet_.size()) - c_foff_[c_off_[i]];
      for (int f = c_off_[i]; f < c_off_[i + 1]; ++f) {
        nx_nb_.push_back(c_nb_[f]);
        nx_foff_.push_back(c_foff_[f + 1] + base);
      }
      nx_tet_.insert(nx_tet_.end(), c_tet_.begin() + c_foff_[c_off_[i]],
                     c_tet_.begin() + c_foff_[c_off_[i + 1]]);
    } else {
      const size_t nf = nx_nb_.size(), nr = nx_tet_.size();
      bounded = walk_cell(i, ids);
      if (!bounded) {
        nx_nb_.resize(nf);
        nx_foff_.resize(nf + 1);
        nx_tet_.resize(nr);
      }
    }
    nx_off_.push_back(static_cast<int>(nx_nb_.size()));
    if (!bounded) {
      if (throw_if_unbounded) {
        throw Error("tessera: the cell of " + point_name(i, ids) +
                    " is unbounded (on the convex hull): the ghost shell is missing");
      }
      t.unbounded_cell = i;
      t.cell_offset.push_back(static_cast<int>(t.face_neighbor.size()));
      continue;
    }
    // Geometry of the cell's faces.
    const V3 xi = load(pts, i);
    double vol = 0.0, sur = 0.0;
    for (int f = nx_off_[i]; f < nx_off_[i + 1]; ++f) {
      const int j = nx_nb_[f];
      const int o = static_cast<int>(t.face_vertex.size());
      for (int r = nx_foff_[f]; r < nx_foff_[f + 1]; ++r) t.face_vertex.push_back(tet_of(nx_tet_[r]));
      t.face_offset.push_back(static_cast<int>(t.face_vertex.size()));
      t.face_neighbor.push_back(j);
      const int len = nx_foff_[f + 1] - nx_foff_[f];
      V3 av{0, 0, 0}, qs{0, 0, 0};
      for (int k = 0; k < len; ++k) {
        const V3 uu = vv(t.vertices[t.face_vertex[o + k]]) - xi;
        const V3 ww = vv(t.vertices[t.face_vertex[o + (k + 1) % len]]) - xi;
        av = av + 0.5 * cross(uu, ww);
        qs = qs + uu;
      }
      qs = (1.0 / len) * qs;
      const V3 dj = load(pts, j) - xi;
      const double area = dot(av, dj) / std::sqrt(dot(dj, dj));
      t.face_area.push_back(area);
      sur += area;
      vol += dot(av, qs) / 3.0;
    }
    t.volume[i] = vol;
    t.surface[i] = sur;
    t.cell_offset.push_back(static_cast<int>(t.face_neighbor.size()));
  }
  c_off_.swap(nx_off_);
  c_nb_.swap(nx_nb_);
  c_foff_.swap(nx_foff_);
  c_tet_.swap(nx_tet_);
  for (const int v : dirty_list_) dirty_[v] = 0;
  dirty_list_.clear();
  cache_ok_ = true;
  cache_owned_ = n_owned;
}

}  // namespace tessera
