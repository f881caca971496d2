// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh3: a 3D Delaunay tetrahedralisation repaired by flips (see mesh3d.h).
//
// Build.  Tessera's own Delaunay tetrahedralisation of the points and the
// far points (mesh3d_delaunay.h), its tetrahedra numbered by their smallest
// point index.
//
// Predicates (mesh3d_delaunay.h).  orient(a, b, c, d) is the sign of
// det[b-a; c-a; d-a] (positive when the tetrahedron a b c d is positively
// oriented, CGAL's convention).  The in-sphere test of a positively
// oriented tetrahedron against e is positive when e lies inside its
// circumsphere (CGAL's side_of_oriented_sphere).  Both are evaluated in
// floating point with static error bounds (multiples of the permanent, the
// determinant with every product replaced by its magnitude, ten times and
// more above the classical bounds); only inside the bound do they call
// tessera::exact's predicates.  An exact zero of the in-sphere test is
// broken by the symbolic perturbation of Devillers and Teillaud
// ("Perturbations for Delaunay and weighted Delaunay 3D triangulations",
// 2011), the one CGAL's Delaunay_triangulation_3 uses: the five points
// ranked by lexicographic xyz order, the two highest ranked decide through
// orientation tests with the point replaced.  The builder uses the same
// predicate, so the repaired triangulation is the unique one a rebuild
// gives.
//
// Flips.  A triangle a b c between tetrahedra (a b c p) and (a b c d) that
// fails the in-sphere test is flipped 2-3 when the segment p d crosses the
// triangle's interior (new tetrahedra a b d p, b c d p, c a d p), 3-2 when it
// passes beyond an edge a b of degree 3 (the edge disappears: a c p d and
// b c p d), 4-4 when it meets or passes beyond an edge a b of degree 4 (the
// octahedron around a b gets p d as its axis; when p, d, a, b are not
// coplanar only if its four inner triangles then pass the in-sphere test, so
// that no 4-4 flip is undone by the next).  Otherwise the triangle waits
// until other flips have changed its surroundings; if a whole round over the
// waiting triangles flips nothing, the repair fails.  A flip of the five or
// six points of its cavity preserves the signed volume covered, so a flip
// whose new tetrahedra are all positive also repairs an inverted one.  Every triangle of the new tetrahedra is tested
// again, so at the end every interior triangle is locally Delaunay (for the
// perturbed predicate), hence the triangulation is Delaunay.

#include "tessera/mesh3d.h"

#include "exact_predicates.h"
#include "mesh3d_delaunay.h"
#include "mesh3d_detail.h"
#include "point_name.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace tessera {

namespace {

// Capacity for `size` elements plus 1/32 (and `unit` whole elements' worth
// of 64 more), on an empty vector (after Mesh3::release()).
template <class Vec>
void reserve_with_margin(Vec &v, std::size_t size, std::size_t unit) {
  v.reserve(size + size / 32 + 64 * unit);
}

template <class Vec>
void release_vec(Vec &v) {
  Vec().swap(v);
}

inline void sort3(int *f) {
  if (f[0] > f[1]) std::swap(f[0], f[1]);
  if (f[1] > f[2]) std::swap(f[1], f[2]);
  if (f[0] > f[1]) std::swap(f[0], f[1]);
}

}  // namespace

int Mesh3::orient(const Points3 &pts, int a, int b, int c, int d) const {
  return detail3::orient3d_filtered(pos(pts, a), pos(pts, b), pos(pts, c), pos(pts, d), exact_);
}

bool Mesh3::less_xyz(const Points3 &pts, int a, int b) const {
  return detail3::less_xyz(pos(pts, a), pos(pts, b));
}

// Perturbed in-sphere test of point e against the positively oriented
// tetrahedron t[0..3]: +1 inside, -1 outside, never 0.
int Mesh3::insphere(const Points3 &pts, const int *t, int e) const {
  const double *c[4] = {pos(pts, t[0]), pos(pts, t[1]), pos(pts, t[2]), pos(pts, t[3])};
  return detail3::insphere_perturbed(c, pos(pts, e), exact_);
}

// The Delaunay tetrahedralisation of the points and the far points into
// tv_, tn_ and vt_; returns the number of tetrahedra.  Tetrahedra are
// numbered by their smallest point index: callers keep points in spatial
// order (LAMMPS sorts atoms), so a point's star lies in a few cache lines;
// the owned points' tetrahedra come first.  Room for a few per cent more
// tetrahedra (2-3 flips add one) is reserved, so that the first flips do
// not double the arrays (as push_back would).
int Mesh3::triangulate(const Points3 &pts, const long *ids, const int *report) {
  const int n = pts.n;
  auto name = [&](int i) { return point_name(report ? report[i] : i, ids); };
  detail3::Tetrahedra out;
  const detail3::Delaunay3 status = detail3::delaunay_3d(pts, far_, 8, out, 1.0 / 32);
  if (status != detail3::Delaunay3::kOk) {
    std::vector<int> order(n);
    for (int i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const double *p = pts.p(a), *q = pts.p(b);
      return std::lexicographical_compare(p, p + 3, q, q + 3);
    });
    for (int k = 0; k + 1 < n; ++k) {
      const double *p = pts.p(order[k]), *q = pts.p(order[k + 1]);
      if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2])
        throw Error("tessera: two cell centres at the same position (" + name(order[k]) + " and " +
                    name(order[k + 1]) + ")");
    }
    throw Error("tessera: points were lost by the 3D triangulation");
  }
  tv_.swap(out.tv);
  tn_.swap(out.tn);
  vt_.swap(out.vt);
  return out.n_tets;
}

void Mesh3::build(const Points3 &pts, const long *ids, const int *report) {
  valid_ = false;
  const int n = pts.n;
  auto name = [&](int i) { return point_name(report ? report[i] : i, ids); };
  for (int i = 0; i < n; ++i) {
    const double *p = pts.p(i);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw Error("tessera: non-finite coordinates for " + name(i));
  }
  // Four non-coplanar points.
  int i1 = -1, i2 = -1, i3 = -1;
  for (int i = 1; i < n && i1 < 0; ++i) {
    const double *p = pts.p(0), *q = pts.p(i);
    if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2]) i1 = i;
  }
  for (int i = i1 + 1; i1 > 0 && i < n && i2 < 0; ++i)
    if (!detail3::collinear3(pts.p(0), pts.p(i1), pts.p(i))) i2 = i;
  for (int i = i2 + 1; i2 > 0 && i < n && i3 < 0; ++i)
    if (exact::orient3d(pts.p(0), pts.p(i1), pts.p(i2), pts.p(i)) != 0) i3 = i;
  if (i3 < 0)
    throw Error("tessera: fewer than 4 non-coplanar points; the 3D mesh needs a 3D configuration");

  n_points_ = n;
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) lo[d] = hi[d] = pts.p(0)[d];
  for (int i = 1; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], pts.p(i)[d]);
      hi[d] = std::max(hi[d], pts.p(i)[d]);
    }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  // The buffer kept Delaunay around a region of interest: about one spacing.
  buffer_ = std::cbrt(std::max(hi[0] - lo[0], 1e-3 * extent) * std::max(hi[1] - lo[1], 1e-3 * extent) *
                      std::max(hi[2] - lo[2], 1e-3 * extent) / n);
  for (int k = 0; k < 8; ++k)
    for (int d = 0; d < 3; ++d)
      far_[k][d] = 0.5 * (lo[d] + hi[d]) + ((k >> d) & 1 ? 32.0 : -32.0) * extent;

  // The previous mesh is not needed: its arrays are released before the
  // triangulation is built, so that the two never coexist (the peak memory
  // of a rebuild is the builder's arrays and those exported from them).
  release();
  const int nt = triangulate(pts, ids, report);
  reserve_with_margin(skip_, nt, 1);
  reserve_with_margin(tmark_, nt, 1);
  reserve_with_margin(tmap_, nt, 1);
  skip_.assign(nt, 0);
  dirty_.assign(n + 8, 0);
  prev_.resize(3 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) prev_[3 * i + d] = pts.p(i)[d];
  tmark_.assign(nt, 0);
  pmark_.assign(n + 8, 0);
  tmap_.assign(nt, -1);
  stamp_ = 0;
  flips_ = f23_ = f32_ = f44_ = exact_ = 0;
  valid_ = true;
}

void Mesh3::release() {
  valid_ = false;
  cache_ok_ = false;
  for (auto *v : {&tv_, &tn_, &free_, &vt_, &stack_, &pending_, &tmap_, &tused_, &bfs_,
                  &dirty_list_, &k_ring0_, &k_fstart_, &k_rstart_, &k_cells_, &k_first_, &k_nb_,
                  &k_fo_, &k_fv_})
    release_vec(*v);
  for (auto *v : {&prev_, &mid_}) release_vec(*v);
  for (auto *v : {&tmark_, &pmark_}) release_vec(*v);
  release_vec(undo_);
  release_vec(skip_);
  release_vec(dirty_);
  release_vec(code_);
}

std::size_t Mesh3::memory_bytes() const {
  const std::size_t ints = tv_.capacity() + tn_.capacity() + free_.capacity() + vt_.capacity() +
                           stack_.capacity() + pending_.capacity() + tmap_.capacity() +
                           tused_.capacity() + bfs_.capacity() +
                           3 * undo_.capacity() + dirty_list_.capacity() + k_ring0_.capacity() +
                           k_fstart_.capacity() + k_rstart_.capacity() + k_cells_.capacity() +
                           k_first_.capacity() + k_nb_.capacity() + k_fo_.capacity() +
                           k_fv_.capacity();
  return ints * sizeof(int) + skip_.capacity() + dirty_.capacity() + code_.capacity() * sizeof(unsigned short) +
         (prev_.capacity() + mid_.capacity()) * sizeof(double) +
         (tmark_.capacity() + pmark_.capacity()) * sizeof(unsigned);
}

int Mesh3::new_tet() {
  if (!free_.empty()) {
    const int t = free_.back();
    free_.pop_back();
    undo_.push_back({kUndoFreePop, 0, t});
    return t;
  }
  const int t = static_cast<int>(tv_.size() / 4);
  undo_.push_back({kUndoGrow, 0, static_cast<int>(tv_.size())});
  for (int k = 0; k < 4; ++k) {
    tv_.push_back(-1);
    tn_.push_back(-1);
  }
  return t;
}

// Undoes the flips since undo_ was last cleared (in reverse order).
void Mesh3::rollback() {
  for (size_t k = undo_.size(); k-- > 0;) {
    const auto &u = undo_[k];
    switch (u[0]) {
      case kUndoTv: tv_[u[1]] = u[2]; break;
      case kUndoTn: tn_[u[1]] = u[2]; break;
      case kUndoVt: vt_[u[1]] = u[2]; break;
      case kUndoFreePop: free_.push_back(u[2]); break;
      case kUndoFreePush: free_.pop_back(); break;
      case kUndoGrow:
        tv_.resize(u[2]);
        tn_.resize(u[2]);
        break;
    }
  }
  undo_.clear();
}

// Replaces the tetrahedra old_tets (a flip's cavity) by the n_new
// tetrahedra nv, if all of these are positively oriented; reconnects them to
// each other and to the cavity's outside and queues all their triangles.
bool Mesh3::replace(const Points3 &pts, const int *old_tets, int n_old, int (*nv)[4], int n_new) {
  for (int i = 0; i < n_new; ++i)
    if (orient(pts, nv[i][0], nv[i][1], nv[i][2], nv[i][3]) <= 0) return false;
  // The cavity's boundary: triangle (sorted) and the tetrahedron outside.
  int ext_face[16][3], ext_nb[16], n_ext = 0;
  for (int i = 0; i < n_old; ++i) {
    const int o = old_tets[i];
    for (int s = 0; s < 4; ++s) {
      const int nb = tn_[4 * o + s];
      if (std::find(old_tets, old_tets + n_old, nb) != old_tets + n_old) continue;
      int m = 0;
      for (int q = 0; q < 4; ++q)
        if (q != s) ext_face[n_ext][m++] = tv_[4 * o + q];
      sort3(ext_face[n_ext]);
      ext_nb[n_ext++] = nb;
    }
  }
  int id[4];
  for (int i = 0; i < n_new; ++i) id[i] = i < n_old ? old_tets[i] : new_tet();
  if (skip_.size() < tv_.size() / 4) skip_.resize(tv_.size() / 4, 0);
  for (int i = 0; i < n_new; ++i) skip_[id[i]] = 0;
  auto set_tv = [&](int k, int v) {
    undo_.push_back({kUndoTv, k, tv_[k]});
    tv_[k] = v;
  };
  auto set_tn = [&](int k, int v) {
    undo_.push_back({kUndoTn, k, tn_[k]});
    tn_[k] = v;
  };
  for (int i = n_new; i < n_old; ++i) {
    set_tv(4 * old_tets[i], -1);
    free_.push_back(old_tets[i]);
    undo_.push_back({kUndoFreePush, 0, 0});
  }
  for (int i = 0; i < n_new; ++i) {
    const int t = id[i];
    for (int s = 0; s < 4; ++s) set_tv(4 * t + s, nv[i][s]);
    for (int s = 0; s < 4; ++s) {
      int f[3], m = 0;
      for (int q = 0; q < 4; ++q)
        if (q != s) f[m++] = nv[i][q];
      sort3(f);
      int nb = -2;
      for (int j = 0; j < n_new && nb == -2; ++j) {
        if (j == i) continue;
        int hit = 0;
        for (int q = 0; q < 4; ++q) hit += nv[j][q] == f[0] || nv[j][q] == f[1] || nv[j][q] == f[2];
        if (hit == 3) nb = id[j];
      }
      if (nb == -2) {
        for (int e = 0; e < n_ext; ++e)
          if (ext_face[e][0] == f[0] && ext_face[e][1] == f[1] && ext_face[e][2] == f[2]) {
            nb = ext_nb[e];
            if (nb >= 0)
              for (int q = 0; q < 4; ++q) {
                const int v = tv_[4 * nb + q];
                if (v != f[0] && v != f[1] && v != f[2]) set_tn(4 * nb + q, t);
              }
            break;
          }
      }
      if (nb == -2) throw Error("tessera: internal error in a 3D flip (cavity boundary mismatch)");
      set_tn(4 * t + s, nb);
    }
  }
  for (int i = 0; i < n_new; ++i)
    for (int s = 0; s < 4; ++s) {
      const int v = nv[i][s];
      if (!dirty_[v]) {
        dirty_[v] = 1;
        dirty_list_.push_back(v);
      }
      undo_.push_back({kUndoVt, v, vt_[v]});
      vt_[v] = id[i];
      if (tn_[4 * id[i] + s] >= 0) stack_.push_back(4 * id[i] + s);
    }
  return true;
}

int Mesh3::slot_of_nb(int tet, int nb) const {
  int j = 0;
  while (tn_[4 * tet + j] != nb) ++j;
  return j;
}

int Mesh3::slot_of(int tet, int v) const {
  for (int q = 0; q < 4; ++q)
    if (tv_[4 * tet + q] == v) return q;
  return -1;
}

// The flips across triangle k of tetrahedron t = (a b c p), towards its
// neighbour u = (a b c d).  edge: 0, 1, 2 for the edges a b, b c, c a of
// the triangle; each flip checks that its new tetrahedra are positively
// oriented and that the cavity has the right shape, and returns false (the
// mesh unchanged) otherwise.
bool Mesh3::flip23(const Points3 &pts, int t, int k) {
  const int u = tn_[4 * t + k];
  if (u < 0) return false;
  const int p = tv_[4 * t + k], d = tv_[4 * u + slot_of_nb(u, t)];
  const int a = tv_[4 * t + kFace[k][0]], b = tv_[4 * t + kFace[k][1]], c = tv_[4 * t + kFace[k][2]];
  int nv[3][4] = {{a, b, d, p}, {b, c, d, p}, {c, a, d, p}};
  const int old[2] = {t, u};
  if (!replace(pts, old, 2, nv, 3)) return false;
  ++f23_;
  return true;
}

bool Mesh3::flip32(const Points3 &pts, int t, int k, int edge) {
  const int u = tn_[4 * t + k];
  if (u < 0) return false;
  const int p = tv_[4 * t + k], d = tv_[4 * u + slot_of_nb(u, t)];
  const int x = tv_[4 * t + kFace[k][edge]], y = tv_[4 * t + kFace[k][(edge + 1) % 3]],
            z = tv_[4 * t + kFace[k][(edge + 2) % 3]];
  // The edge x y must have degree 3, its third tetrahedron x y p d.
  const int w = tn_[4 * t + slot_of(t, z)];
  if (w < 0 || slot_of(w, d) < 0 || tn_[4 * u + slot_of(u, z)] != w) return false;
  int nv[2][4] = {{x, d, z, p}, {d, y, z, p}};
  const int old[3] = {t, u, w};
  if (!replace(pts, old, 3, nv, 2)) return false;
  ++f32_;
  return true;
}

bool Mesh3::flip44(const Points3 &pts, int t, int k, int edge, bool delaunay) {
  const int u = tn_[4 * t + k];
  if (u < 0) return false;
  const int p = tv_[4 * t + k], d = tv_[4 * u + slot_of_nb(u, t)];
  const int x = tv_[4 * t + kFace[k][edge]], y = tv_[4 * t + kFace[k][(edge + 1) % 3]],
            z = tv_[4 * t + kFace[k][(edge + 2) % 3]];
  // The edge x y of degree 4: t, u, w1 = x y d e, w = x y p e.
  const int w = tn_[4 * t + slot_of(t, z)];
  if (w < 0) return false;
  int e = -1;
  for (int q = 0; q < 4; ++q) {
    const int v = tv_[4 * w + q];
    if (v != x && v != y && v != p) e = v;
  }
  const int w1 = tn_[4 * u + slot_of(u, z)];
  if (w1 < 0 || w1 == w || slot_of(w1, e) < 0 || tn_[4 * w + slot_of(w, p)] != w1) return false;
  int nv[4][4] = {{x, d, z, p}, {d, y, z, p}, {d, x, e, p}, {y, d, e, p}};
  if (delaunay) {
    // Unless p, d, x, y are coplanar the new axis need not be better for
    // both halves: flip only to an octahedron whose four inner triangles
    // pass the in-sphere test (no flip back and forth).
    for (auto &q : nv)
      if (orient(pts, q[0], q[1], q[2], q[3]) <= 0) return false;
    if (insphere(pts, nv[0], y) > 0 || insphere(pts, nv[0], e) > 0 || insphere(pts, nv[1], e) > 0 ||
        insphere(pts, nv[2], y) > 0)
      return false;
  }
  const int old[4] = {t, u, w1, w};
  if (!replace(pts, old, 4, nv, 4)) return false;
  ++f44_;
  return true;
}

// A triangle that fails the in-sphere test: the flip the position of the
// segment p d relative to the triangle calls for.
bool Mesh3::flip_face(const Points3 &pts, int t, int k) {
  const int u = tn_[4 * t + k];
  const int p = tv_[4 * t + k], d = tv_[4 * u + slot_of_nb(u, t)];
  const int f[3] = {tv_[4 * t + kFace[k][0]], tv_[4 * t + kFace[k][1]], tv_[4 * t + kFace[k][2]]};
  int o[3], bad = 0;
  for (int e = 0; e < 3; ++e) {
    o[e] = orient(pts, f[e], f[(e + 1) % 3], d, p);
    bad += o[e] <= 0;
  }
  if (bad == 0) return flip23(pts, t, k);
  // p d passes beyond (or through) an edge: remove it by 3-2 if it has
  // degree 3, else by 4-4 if it has degree 4 (the octahedron around it gets
  // p d as its axis; p, d and the edge need not be coplanar).
  for (int e = 0; e < 3; ++e)
    if (o[e] <= 0 && (flip32(pts, t, k, e) || flip44(pts, t, k, e, true))) return true;
  return false;
}

// An inverted or flat tetrahedron t: any flip with a neighbour that leaves
// only positively oriented tetrahedra (flips preserve the signed covering,
// so the mesh is a triangulation again once no tetrahedron is negative).
bool Mesh3::untangle(const Points3 &pts, int t) {
  for (int k = 0; k < 4; ++k) {
    if (tn_[4 * t + k] < 0) continue;
    if (flip23(pts, t, k)) return true;
    for (int e = 0; e < 3; ++e)
      if (flip32(pts, t, k, e) || flip44(pts, t, k, e, false)) return true;
  }
  // As the neighbour of a triangle: the same flips seen from the other side.
  for (int k = 0; k < 4; ++k) {
    const int u = tn_[4 * t + k];
    if (u < 0) continue;
    const int j = slot_of_nb(u, t);
    if (flip23(pts, u, j)) return true;
    for (int e = 0; e < 3; ++e)
      if (flip32(pts, u, j, e) || flip44(pts, u, j, e, false)) return true;
  }
  return false;
}

double time_plain_delaunay_3d(const Points3 &pts, int n, long *cells) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  detail3::Tetrahedra out;
  const Points3 own{pts.data, n > 0 ? n : 0, pts.stride};
  detail3::delaunay_3d(own, nullptr, 0, out, 0.0, false);
  const double seconds = std::chrono::duration<double>(clock::now() - t0).count();
  if (cells) *cells = out.n_tets;
  return seconds;
}

}  // namespace tessera
