// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh3::cells: the owned cells of the kept tetrahedra, as tessellate_local_3d
// builds them from a fresh triangulation (see mesh3d.h).  Face f of cell i towards j is the
// ring of tetrahedra around the Delaunay edge i j, walked from a tetrahedron
// (i j a b) across the triangle (i j b) when (i j a b) is an even
// permutation of its positively oriented corners: the ring then runs
// counter-clockwise about x_j - x_i, as the Tessellation3 convention wants.
// Areas, volumes and surfaces by the formulas of voronoi3d.cpp.
//
// Slivers (tetrahedra flatter than 1e-6: four nearly co-spherical, nearly
// coplanar points, as round-off makes of a lattice in a tilted box) are
// treated as tessellate_local_3d treats them: their circumcentres are
// computed exactly, and a sliver whose four points lie on the circumsphere
// of a well-shaped facet neighbour (one of the owned cells' tetrahedra)
// with the same centre is dropped from the face polygons (voronoi3d.cpp,
// drop_slivers).  Both are rare; the common path only measures flatness.
// Four-fold edges are found by the same routine as tessellate_local_3d's
// (fourfold3d.cpp), through the mesh's adjacency.

#include "tessera/mesh3d.h"

#include "fourfold3d.h"
#include "mesh3d_delaunay.h"
#include "vec3_detail.h"

#include "point_name.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace tessera {

namespace {

using namespace detail3;

// The thresholds of voronoi3d.cpp: tetrahedra flatter than kSliver (|det|
// of the edge vectors from the first corner over the cube of their largest
// component) get exact circumcentres; kCoSpherical: a point within this
// fraction of a sphere's radius counts as on it.
constexpr double kSliver = 1e-6;
constexpr double kCoSpherical = 1e-8;

// The circumcentre of a sliver to the nearest double (computed in
// rationals, mesh3d_exact.cpp; the formula of vec3_detail.h loses about
// eps/q of the radius at flatness q).
V3 exact_circumcentre(V3 p0, V3 p1, V3 p2, V3 p3) {
  const double a[3] = {p0.x, p0.y, p0.z}, b[3] = {p1.x, p1.y, p1.z}, c[3] = {p2.x, p2.y, p2.z},
               d[3] = {p3.x, p3.y, p3.z};
  double h[3];
  detail3::exact_circumcentre(a, b, c, d, h);
  return {h[0], h[1], h[2]};
}

// Circumcentre of tetrahedron p0..p3 (exact for a sliver); *sliver says
// which.  The same flatness as voronoi3d.cpp's.
V3 centre_of(V3 p0, V3 p1, V3 p2, V3 p3, bool *sliver) {
  const V3 e1 = p1 - p0, e2 = p2 - p0, e3 = p3 - p0;
  const V3 c23 = cross(e2, e3), c31 = cross(e3, e1), c12 = cross(e1, e2);
  const double det = dot(e1, c23);
  double l = std::max({std::fabs(e1.x), std::fabs(e1.y), std::fabs(e1.z), std::fabs(e2.x),
                       std::fabs(e2.y), std::fabs(e2.z), std::fabs(e3.x), std::fabs(e3.y),
                       std::fabs(e3.z)});
  const double q = l > 0.0 ? std::fabs(det) / (l * l * l) : 0.0;
  if (!(q >= kSliver)) {
    *sliver = true;
    return exact_circumcentre(p0, p1, p2, p3);
  }
  *sliver = false;
  const double s = 0.5 / det;
  return p0 + s * (dot(e1, e1) * c23 + dot(e2, e2) * c31 + dot(e3, e3) * c12);
}

// Storage for n elements, grown by a small margin rather than the library's
// doubling (the arrays are kept from step to step and their sizes change by
// a few per cent at most); fit also resizes v to n.
template <class Vec>
void room(Vec &v, size_t n) {
  if (v.capacity() < n) v.reserve(n + n / 32);
}
template <class Vec>
void fit(Vec &v, size_t n) {
  room(v, n);
  v.resize(n);
}

// Releases the storage of v beyond a quarter above its size (after the first
// call, whose arrays grew by doubling).
template <class Vec>
void trim(Vec &v) {
  if (v.capacity() > v.size() + v.size() / 4 + 64) v.shrink_to_fit();
}

// Which cells() filled a Tessellation3 (Tessellation3::mesh_stamp).
unsigned long stamp_counter = 0;

// Face areas, volume and surface of owned cell i from t.vertices (the
// formulas of voronoi3d.cpp's measure()).  Returns the smallest squared
// distance to a neighbour across a face (for check_separation_3d).
double measure_cell(Tessellation3 &t, const Points3 &pts, int i) {
  const V3 xi = load(pts, i);
  double vol = 0.0, sur = 0.0, d2min = std::numeric_limits<double>::infinity();
  for (int f = t.cell_offset[i]; f < t.cell_offset[i + 1]; ++f) {
    const int o = t.face_offset[f], len = t.face_offset[f + 1] - o;
    const int *ring = t.face_vertex.data() + o;
    V3 av{0, 0, 0}, qs{0, 0, 0};
    V3 uu = vv(t.vertices[ring[len - 1]]) - xi;
    for (int k = 0; k < len; ++k) {
      // Summed from the last corner round: the same terms as voronoi3d.cpp's
      // measure(), in a rotated order (round-off only).
      const V3 ww = vv(t.vertices[ring[k]]) - xi;
      av = av + cross(uu, ww);
      qs = qs + ww;
      uu = ww;
    }
    av = 0.5 * av;
    qs = (1.0 / len) * qs;
    const V3 dj = load(pts, t.face_neighbor[f]) - xi;
    const double d2 = dot(dj, dj);
    d2min = std::min(d2min, d2);
    const double area = dot(av, dj) / std::sqrt(d2);
    t.face_area[f] = area;
    sur += area;
    vol += dot(av, qs) / 3.0;
  }
  t.volume[i] = vol;
  t.surface[i] = sur;
  return d2min;
}

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
// nbs and ring, with each face's end in ring appended to offs (the rings in
// mesh numbering until cells() renumbers them); false, with nothing
// appended, if the cell is unbounded (its star is walked before any face).
bool Mesh3::walk_cell(int i, const long *ids, std::vector<int> &nbs, std::vector<int> &offs,
                      std::vector<int> &ring) const {
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
        ring.push_back(cur);
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
      nbs.push_back(j);
      offs.push_back(static_cast<int>(ring.size()));
    }
  }
  return true;
}

// Owned cell i is unbounded (on the convex hull): an Error, or, if the caller
// asked not to throw, t.unbounded_cell (the cell has no faces).
void Mesh3::unbounded(int i, const long *ids, bool throw_if_unbounded, Tessellation3 &t) const {
  if (throw_if_unbounded) {
    throw Error("tessera: the cell of " + point_name(i, ids) +
                " is unbounded (on the convex hull): the ghost shell is missing");
  }
  t.unbounded_cell = i;
}

// Pass 1 of cells() when t holds the topology of the last call (rings in
// t's numbering, tused_ mapping them to mesh tetrahedra): the clean cells'
// faces and rings stay, moved in place to their new offsets, and the cells
// whose star a flip touched (or that had no faces) are walked again into
// side buffers, copied in last.  Clean cells that move towards the front are
// moved in increasing order and those that move towards the back in
// decreasing order: a cell's destination then only covers storage already
// moved or belonging to walked cells.
void Mesh3::keep_topology(int n_owned, const long *ids, bool throw_if_unbounded,
                          Tessellation3 &t) const {
  std::vector<int> &off = t.cell_offset, &nb = t.face_neighbor, &fo = t.face_offset,
                   &fv = t.face_vertex;
  for (int &v : fv) v = tused_[v];
  const size_t cells = static_cast<size_t>(n_owned) + 1;
  fit(k_ring0_, cells);
  fit(k_fstart_, cells);
  fit(k_rstart_, cells);
  for (size_t i = 0; i < cells; ++i) k_ring0_[i] = fo[off[i]];
  auto clean = [&](int i) { return !dirty_[i] && off[i + 1] > off[i]; };
  k_cells_.clear();
  k_first_.clear();
  k_nb_.clear();
  k_fo_.assign(1, 0);
  k_fv_.clear();
  int nfaces = 0, nring = 0;
  for (int i = 0; i < n_owned; ++i) {
    k_fstart_[i] = nfaces;
    k_rstart_[i] = nring;
    if (clean(i)) {
      nfaces += off[i + 1] - off[i];
      nring += k_ring0_[i + 1] - k_ring0_[i];
      continue;
    }
    const size_t nf = k_nb_.size(), nr = k_fv_.size();
    k_cells_.push_back(i);
    k_first_.push_back(static_cast<int>(nf));
    if (!walk_cell(i, ids, k_nb_, k_fo_, k_fv_)) unbounded(i, ids, throw_if_unbounded, t);
    nfaces += static_cast<int>(k_nb_.size() - nf);
    nring += static_cast<int>(k_fv_.size() - nr);
  }
  k_fstart_[n_owned] = nfaces;
  k_rstart_[n_owned] = nring;
  k_first_.push_back(static_cast<int>(k_nb_.size()));
  if (static_cast<size_t>(nfaces) > nb.size()) {
    fit(nb, nfaces);
    fit(fo, static_cast<size_t>(nfaces) + 1);
  }
  if (static_cast<size_t>(nring) > fv.size()) fit(fv, nring);

  auto move_faces = [&](int i) {
    const int o = off[i], n = k_fstart_[i], len = off[i + 1] - o;
    const int dr = k_rstart_[i] - k_ring0_[i];
    if (n <= o) {
      for (int f = 0; f < len; ++f) {
        nb[n + f] = nb[o + f];
        fo[n + f + 1] = fo[o + f + 1] + dr;
      }
    } else {
      for (int f = len - 1; f >= 0; --f) {
        nb[n + f] = nb[o + f];
        fo[n + f + 1] = fo[o + f + 1] + dr;
      }
    }
  };
  auto move_ring = [&](int i) {
    const int o = k_ring0_[i], n = k_rstart_[i], len = k_ring0_[i + 1] - o;
    if (n < o)
      std::copy(fv.begin() + o, fv.begin() + o + len, fv.begin() + n);
    else if (n > o)
      std::copy_backward(fv.begin() + o, fv.begin() + o + len, fv.begin() + n + len);
  };
  for (int i = 0; i < n_owned; ++i) {
    if (!clean(i)) continue;
    if (k_fstart_[i] <= off[i]) move_faces(i);
    if (k_rstart_[i] < k_ring0_[i]) move_ring(i);
  }
  for (int i = n_owned - 1; i >= 0; --i) {
    if (!clean(i)) continue;
    if (k_fstart_[i] > off[i]) move_faces(i);
    if (k_rstart_[i] > k_ring0_[i]) move_ring(i);
  }
  for (size_t c = 0; c + 1 < k_first_.size(); ++c) {
    const int i = k_cells_[c], f0 = k_first_[c], f1 = k_first_[c + 1];
    const int n = k_fstart_[i], r = k_rstart_[i], r0 = k_fo_[f0];
    for (int f = f0; f < f1; ++f) {
      nb[n + (f - f0)] = k_nb_[f];
      fo[n + (f - f0) + 1] = r + (k_fo_[f + 1] - r0);
    }
    std::copy(k_fv_.begin() + r0, k_fv_.begin() + k_fo_[f1], fv.begin() + r);
  }
  nb.resize(nfaces);
  fo.resize(static_cast<size_t>(nfaces) + 1);
  fv.resize(nring);
  std::copy(k_fstart_.begin(), k_fstart_.end(), off.begin());
}

void Mesh3::cells(const Points3 &pts, int n_owned, Tessellation3 &t, const long *ids,
                  bool throw_if_unbounded) const {
  if (!valid_) throw Error("tessera: Mesh3::cells() on an invalid mesh; call build() first");
  if (pts.n != n_points_) throw Error("tessera: Mesh3::cells() with a different number of points");
  if (n_owned < 0 || n_owned > n_points_) throw Error("tessera: n_owned out of range");
  const int n = n_points_;
  t.n_points = n;
  t.n_owned = n_owned;
  t.unbounded_cell = -1;
  t.origin.clear();
  t.position.clear();
  next_stamp();
  // tmap_ is all -1 between calls, also when an Error leaves early.
  struct Reset {
    const Mesh3 &m;
    ~Reset() {
      for (const int k : m.tused_) m.tmap_[k] = -1;
    }
  } reset{*this};

  // Pass 1, topology: the faces and rings of every owned cell, written into
  // t with the rings in mesh numbering.  When t is the tessellation the last
  // cells() filled (its stamp), a cell whose star no flip touched since
  // keeps its faces and rings, moved in place; the others walk their star
  // again.  There is no second copy of the topology.
  const bool reuse = cache_ok_ && cache_owned_ == n_owned && t.mesh_stamp != 0 &&
                     t.mesh_stamp == cache_stamp_ &&
                     t.cell_offset.size() == static_cast<size_t>(n_owned) + 1 &&
                     t.tets.size() == tused_.size();
  t.mesh_stamp = 0;
  if (reuse) {
    keep_topology(n_owned, ids, throw_if_unbounded, t);
  } else {
    t.cell_offset.assign(1, 0);
    t.face_neighbor.clear();
    t.face_offset.assign(1, 0);
    t.face_vertex.clear();
    room(t.cell_offset, static_cast<size_t>(n_owned) + 1);
    const size_t cap_nb = t.face_neighbor.capacity(), cap_fo = t.face_offset.capacity(),
                 cap_fv = t.face_vertex.capacity();
    for (int i = 0; i < n_owned; ++i) {
      if (!walk_cell(i, ids, t.face_neighbor, t.face_offset, t.face_vertex))
        unbounded(i, ids, throw_if_unbounded, t);
      t.cell_offset.push_back(static_cast<int>(t.face_neighbor.size()));
    }
    // Arrays that grew by doubling here (the first call) give the slack back;
    // storage the caller gave t stays.
    if (t.face_neighbor.capacity() != cap_nb) trim(t.face_neighbor);
    if (t.face_offset.capacity() != cap_fo) trim(t.face_offset);
    if (t.face_vertex.capacity() != cap_fv) trim(t.face_vertex);
  }
  // An Error below leaves the topology unusable for the next call.
  cache_ok_ = false;
  tused_.clear();

  // Pass 2: number the tetrahedra of the rings in order of first use (the
  // Tessellation3's numbering), and the polygons in that numbering, in place.
  const size_t n_faces = t.face_neighbor.size(), n_ring = t.face_vertex.size();
  fit(t.face_area, n_faces);
  int *fv = t.face_vertex.data();
  int n_tet = 0;
  for (size_t r = 0; r < n_ring; ++r) {
    const int m = fv[r];
    int id = tmap_[m];
    if (id < 0) {
      if (skip_[m])
        throw Error("tessera: Mesh3::cells(): a tetrahedron of an owned cell lies outside the "
                    "region of interest of the last update()");
      id = tmap_[m] = n_tet++;
      tused_.push_back(m);
    }
    fv[r] = id;
  }

  // Pass 3: the tetrahedra's corners, circumcentres and radii.
  fit(t.tets, n_tet);
  fit(t.vertices, n_tet);
  fit(t.radius, n_tet);
  std::vector<int> slivers;  // mesh tetrahedra (rare: no allocation without)
  bool dropped = false;
  for (int id = 0; id < n_tet; ++id) {
    const int m = tused_[id];
    const int *q = &tv_[4 * m];
    t.tets[id] = {q[0], q[1], q[2], q[3]};
    const V3 p0 = load(pts, q[0]);
    bool sliver;
    const V3 h = centre_of(p0, load(pts, q[1]), load(pts, q[2]), load(pts, q[3]), &sliver);
    if (sliver) slivers.push_back(m);
    t.vertices[id] = {h.x, h.y, h.z};
    const V3 dd = h - p0;
    t.radius[id] = std::sqrt(dot(dd, dd));
  }

  // Pass 4: areas, volumes, surfaces.
  t.volume.assign(n_owned, 0.0);
  t.surface.assign(n_owned, 0.0);
  double d2min = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n_owned; ++i) d2min = std::min(d2min, measure_cell(t, pts, i));
  if (!slivers.empty()) {
    // As voronoi3d.cpp's drop_slivers: a sliver is dropped from the
    // polygons when a well-shaped facet neighbour among t's tetrahedra has
    // its four points on its circumsphere and the same centre (a sliver
    // inside a cluster of co-spherical points); it takes that neighbour's
    // centre and radius.
    std::vector<char> drop(t.tets.size(), 0);
    std::vector<char> is_sliver(t.tets.size(), 0);
    for (const int m : slivers) is_sliver[tmap_[m]] = 1;
    bool any = false;
    for (const int m : slivers) {
      const int v = tmap_[m];
      for (int k = 0; k < 4; ++k) {
        const int nb = tn_[4 * m + k];
        if (nb < 0 || tmap_[nb] < 0) continue;
        const int w = tmap_[nb];
        if (is_sliver[w]) continue;
        const V3 h = vv(t.vertices[w]);
        const double r = t.radius[w];
        if (!std::isfinite(r)) continue;
        bool on = true;
        for (int c = 0; c < 4 && on; ++c) {
          const V3 d = load(pts, t.tets[v][c]) - h;
          on = std::fabs(std::sqrt(dot(d, d)) - r) <= kCoSpherical * r;
        }
        if (!on) continue;
        const V3 dh = vv(t.vertices[v]) - h;
        if (!(std::sqrt(dot(dh, dh)) <= kCoSpherical * r)) continue;
        t.vertices[v] = t.vertices[w];
        t.radius[v] = t.radius[w];
        drop[v] = 1;
        any = true;
        break;
      }
    }
    dropped = any;
    if (any) {
      // Rewrite the polygons without the dropped slivers (a face of
      // slivers only keeps them: an area-0 face) and measure the cells
      // that had one again.
      std::vector<int> fv, fo(1, 0);
      fv.reserve(t.face_vertex.size());
      const int nf = static_cast<int>(t.face_offset.size()) - 1;
      for (int f = 0; f < nf; ++f) {
        const size_t start = fv.size();
        for (int k = t.face_offset[f]; k < t.face_offset[f + 1]; ++k)
          if (!drop[t.face_vertex[k]]) fv.push_back(t.face_vertex[k]);
        if (fv.size() == start)
          for (int k = t.face_offset[f]; k < t.face_offset[f + 1]; ++k) fv.push_back(t.face_vertex[k]);
        fo.push_back(static_cast<int>(fv.size()));
      }
      std::vector<char> touched(n_owned, 0);
      for (int i = 0; i < n_owned; ++i)
        for (int f = t.cell_offset[i]; f < t.cell_offset[i + 1] && !touched[i]; ++f)
          touched[i] = fo[f + 1] - fo[f] != t.face_offset[f + 1] - t.face_offset[f];
      t.face_vertex.swap(fv);
      t.face_offset.swap(fo);
      for (int i = 0; i < n_owned; ++i)
        if (touched[i]) measure_cell(t, pts, i);
    }
  }
  check_separation_3d(t, pts, ids, d2min);
  {
    // Four-fold edges, found through the mesh's adjacency (far points and
    // their tetrahedra count as absent, as the hull's in
    // tessellate_local_3d).
    class MeshGraph : public detail3::TetGraph {
    public:
      MeshGraph(const std::vector<int> &tv, const std::vector<int> &tn, const std::vector<int> &used,
                const std::vector<int> &tmap, int n)
          : tv_(tv), tn_(tn), used_(used), tmap_(tmap), n_(n) {}
      long id(int v) override { return used_[v]; }
      long neighbor(long g, int k) override {
        const int nb = tn_[4 * g + k];
        if (nb < 0) return -1;
        for (int s = 0; s < 4; ++s)
          if (tv_[4 * nb + s] >= n_) return -1;
        return nb;
      }
      void corners(long g, int q[4]) override {
        for (int s = 0; s < 4; ++s) q[s] = tv_[4 * g + s] < n_ ? tv_[4 * g + s] : -1;
      }
      int t_neighbor(int v, int k) override {
        const int nb = tn_[4 * used_[v] + k];
        if (nb < 0) return -2;
        return tmap_[nb] >= 0 ? tmap_[nb] : -1;
      }
      int opposite(long g, int k) override {
        const int nb = tn_[4 * g + k];
        if (nb < 0) return -1;
        const int *a = &tv_[4 * g], *b = &tv_[4 * nb];
        for (int s = 0; s < 4; ++s)
          if (b[s] != a[0] && b[s] != a[1] && b[s] != a[2] && b[s] != a[3])
            return b[s] < n_ ? b[s] : -1;
        return -1;
      }

    private:
      const std::vector<int> &tv_, &tn_, &used_, &tmap_;
      int n_;
    } graph(tv_, tn_, tused_, tmap_, n);
    detail3::find_fourfold_edges(t, pts, graph);
  }
  for (const int v : dirty_list_) dirty_[v] = 0;
  dirty_list_.clear();
  // The next call may keep this topology (rings through tused_) unless
  // slivers were dropped from it.
  cache_ok_ = !dropped;
  cache_owned_ = n_owned;
  t.mesh_stamp = cache_stamp_ = ++stamp_counter;
}

}  // namespace tessera
