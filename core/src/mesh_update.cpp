// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh::update: the triangulation kept Delaunay across steps by Lawson flips
// with filtered exact predicates (ties of co-circular points broken as
// build() breaks them, so that the two give the same triangles).

#include "mesh_detail.h"

namespace tessera {

bool Mesh::flip_needed(const Points &pts, int p, int q, int r, int s) const {
  if (r == kInfinite || s == kInfinite)
    return false;     // a hull edge
  if (p == kInfinite) // hull chain s -> q -> r must turn clockwise
    return orientation(pts.x(s), pts.y(s), pts.x(q), pts.y(q), pts.x(r), pts.y(r)) > 0;
  if (q == kInfinite) // hull chain r -> p -> s
    return orientation(pts.x(r), pts.y(r), pts.x(p), pts.y(p), pts.x(s), pts.y(s)) > 0;
  return in_circle(pts.x(p), pts.y(p), pts.x(q), pts.y(q), pts.x(r), pts.y(r), pts.x(s), pts.y(s),
                   !tiny_) > 0;
}

void Mesh::canonical(int t) {
  int *v = &v_[3 * t], *n = &nb_[3 * t];
  const int k = v[1] < v[0] ? (v[2] < v[1] ? 2 : 1) : (v[2] < v[0] ? 2 : 0);
  if (k == 0)
    return;
  const int v0 = v[0], v1 = v[1], v2 = v[2], n0 = n[0], n1 = n[1], n2 = n[2];
  if (k == 1) {
    v[0] = v1, v[1] = v2, v[2] = v0;
    n[0] = n1, n[1] = n2, n[2] = n0;
  } else {
    v[0] = v2, v[1] = v0, v[2] = v1;
    n[0] = n2, n[1] = n0, n[2] = n1;
  }
}

// Flips the edge between triangle t = (r, p, q) (r = vertex k) and
// u = (s, q, p) (s = vertex j) into t = (r, p, s), u = (s, q, r), each then
// rotated to its canonical order.
void Mesh::flip(int t, int k, int u, int j) {
  const int r = v_[3 * t + k], p = v_[3 * t + (k + 1) % 3], q = v_[3 * t + (k + 2) % 3];
  const int s = v_[3 * u + j];
  const int A = nb_[3 * t + (k + 1) % 3]; // across (q, r)
  const int B = nb_[3 * t + (k + 2) % 3]; // across (r, p)
  const int C = nb_[3 * u + (j + 1) % 3]; // across (p, s)
  const int D = nb_[3 * u + (j + 2) % 3]; // across (s, q)
  v_[3 * t] = r;
  v_[3 * t + 1] = p;
  v_[3 * t + 2] = s;
  nb_[3 * t] = C;
  nb_[3 * t + 1] = u;
  nb_[3 * t + 2] = B;
  v_[3 * u] = s;
  v_[3 * u + 1] = q;
  v_[3 * u + 2] = r;
  nb_[3 * u] = A;
  nb_[3 * u + 1] = t;
  nb_[3 * u + 2] = D;
  for (int e = 0; e < 3; ++e) {
    if (nb_[3 * A + e] == t)
      nb_[3 * A + e] = u;
    if (nb_[3 * C + e] == u)
      nb_[3 * C + e] = t;
  }
  if (r != kInfinite)
    vt_[r] = t;
  if (p != kInfinite)
    vt_[p] = t;
  if (s != kInfinite)
    vt_[s] = u;
  if (q != kInfinite)
    vt_[q] = u;
  canonical(t);
  canonical(u);
  flipped_.push_back(t);
  flipped_.push_back(u);
  mark_dirty(r);
  mark_dirty(p);
  mark_dirty(s);
  mark_dirty(q);
}

// Exchanges the numbers of triangles a and b (the references to them in
// their neighbours and in vt_ follow); the corners of both are marked dirty.
void Mesh::swap_slots(int a, int b) {
  if (a == b)
    return;
  int rows[8];
  int nr = 0;
  auto add = [&](int x) {
    for (int i = 0; i < nr; ++i)
      if (rows[i] == x)
        return;
    rows[nr++] = x;
  };
  add(a);
  add(b);
  for (int k = 0; k < 3; ++k) {
    add(nb_[3 * a + k]);
    add(nb_[3 * b + k]);
  }
  auto remap = [a, b](int x) { return x == a ? b : (x == b ? a : x); };
  for (int i = 0; i < nr; ++i)
    for (int k = 0; k < 3; ++k)
      nb_[3 * rows[i] + k] = remap(nb_[3 * rows[i] + k]);
  for (int k = 0; k < 3; ++k) {
    std::swap(v_[3 * a + k], v_[3 * b + k]);
    std::swap(nb_[3 * a + k], nb_[3 * b + k]);
  }
  for (int k = 0; k < 3; ++k) {
    for (const int p : {v_[3 * a + k], v_[3 * b + k]}) {
      if (p == kInfinite)
        continue;
      vt_[p] = remap(vt_[p]);
      mark_dirty(p);
    }
  }
}

// Flips only turn triangles with the point at infinity into finite ones
// (both triangles of a flipped edge (p, q) with p or q infinite had that
// corner; afterwards one of them has none): those are moved to slot nft_.
void Mesh::restore_partition() {
  const int *v = v_.data();
  for (size_t i = 0; i < flipped_.size(); ++i) {
    const int x = flipped_[i];
    if (x < nft_ || v[3 * x] == kInfinite || v[3 * x + 1] == kInfinite || v[3 * x + 2] == kInfinite)
      continue;
    swap_slots(x, nft_);
    v = v_.data();
    flipped_.push_back(nft_);
    // What was at nft_ is now at x: it may have turned finite too.
    if (x != nft_)
      flipped_.push_back(x);
    ++nft_;
  }
}

// The start of update() and advance(): the bookkeeping of the last update
// cleared, the input checked (bad input invalidates the mesh: build() names
// it), the separation limit for it in sep2, frozen_ and stack_ reset.
bool Mesh::start_update(const Points &pts, double &sep2) {
  flips_ = 0;
  repairs_ = 0;
  repaired_triangles_ = 0;
  stamp_ = 0;
  flipped_.clear();
  folded_.clear();
  for (const int p : dirty_list_)
    dirty_[p] = 0;
  dirty_list_.clear();
  if (!valid_ || pts.n != n_points_) {
    valid_ = false;
    return false;
  }
  double scale = 0.0;
  bool tiny = false;
  for (int i = 0; i < pts.n; ++i) {
    if (!std::isfinite(pts.x(i)) || !std::isfinite(pts.y(i))) { // build() names it
      valid_ = false;
      return false;
    }
    const double ax = std::fabs(pts.x(i)), ay = std::fabs(pts.y(i));
    scale = std::max({scale, ax, ay});
    tiny |= (ax < kTinyCoordinate && ax != 0.0) | (ay < kTinyCoordinate && ay != 0.0);
  }
  tiny_ = tiny;
  if (scale > kMaxCoordinate) { // build() names it
    valid_ = false;
    return false;
  }
  // Points that came too close are left to build(), which names them: every
  // edge is checked in the pass over the triangles and every edge a flip
  // creates.
  sep2 = min_separation2(scale);
  frozen_.assign(v_.size() / 3, 0);
  stack_.clear();
  return true;
}

// The edges of triangle t to triangles of higher number (so each edge once):
// those that need a flip are stacked.  False (the mesh invalid) when an
// edge joins two points closer than the separation limit.
bool Mesh::stack_edges(const Points &pts, int t, double sep2) {
  for (int k = 0; k < 3; ++k) {
    const int u = nb_[3 * t + k];
    if (u < t)
      continue;
    const int r = v_[3 * t + k], p = v_[3 * t + (k + 1) % 3], q = v_[3 * t + (k + 2) % 3];
    if (p != kInfinite && q != kInfinite) {
      const double dx = pts.x(p) - pts.x(q), dy = pts.y(p) - pts.y(q);
      if (dx * dx + dy * dy < sep2) {
        valid_ = false;
        return false;
      }
    }
    int j = (nb_[3 * u + 1] == t) + 2 * (nb_[3 * u + 2] == t);
    if (j == 3) {
      // u shares its other two edges with t (a folded pair; see advance())
      j = detail::slot_across(v_.data(), nb_.data(), u, t, p, q);
      if (j < 0) {
        valid_ = false;
        return false;
      }
    }
    if (flip_needed(pts, p, q, r, v_[3 * u + j])) {
      stack_.push_back(t);
      stack_.push_back(k);
    }
  }
  return true;
}

bool Mesh::update(const Points &pts, const double *roi_lo, const double *roi_hi) {
  double sep2;
  if (!start_update(pts, sep2))
    return false;
  const int nt = static_cast<int>(v_.size() / 3);
  // One pass over the triangles: a finite triangle that is no longer
  // counter-clockwise has folded over, which flips cannot repair: its region
  // is re-triangulated after the pass (outside the region of interest it is
  // frozen instead); every edge is tested once, and the ones to flip are
  // stacked (edges of frozen triangles are dropped when popped, as
  // frozenness of the far side is not known yet here; entries of triangles
  // that a repair rewrites are tested again when popped).
  for (int t = 0; t < nt; ++t) {
    const int a = v_[3 * t], b = v_[3 * t + 1], c = v_[3 * t + 2];
    if (a != kInfinite && b != kInfinite && c != kInfinite) {
      const double ax = pts.x(a), ay = pts.y(a), bx = pts.x(b), by = pts.y(b), cx = pts.x(c),
                   cy = pts.y(c);
      if (orientation(ax, ay, bx, by, cx, cy) <= 0) {
        if (!outside_region(ax, ay, bx, by, cx, cy, roi_lo, roi_hi)) {
          if (!fold_repair_) {
            valid_ = false;
            return false;
          }
          folded_.push_back(t);
          continue;
        }
        frozen_[t] = 1;
        continue;
      }
    }
    if (!stack_edges(pts, t, sep2))
      return false;
  }
  if (!folded_.empty() && !repair_folds(pts, sep2))
    return false;
  return flip_pass(pts, sep2);
}

// The Lawson flips of the edges on stack_, then the finite-first numbering.
bool Mesh::flip_pass(const Points &pts, double sep2) {
  auto too_close = [&](int a, int b) {
    if (a == kInfinite || b == kInfinite)
      return false;
    const double dx = pts.x(a) - pts.x(b), dy = pts.y(a) - pts.y(b);
    return dx * dx + dy * dy < sep2;
  };
  const int nt = static_cast<int>(v_.size() / 3);
  const long max_flips = 20L * nt + 1000;
  while (!stack_.empty()) {
    const int k = stack_.back();
    stack_.pop_back();
    const int t = stack_.back();
    stack_.pop_back();
    const int u = nb_[3 * t + k];
    if (frozen_[t] || frozen_[u])
      continue;
    int j = 0;
    while (j < 3 && nb_[3 * u + j] != t)
      ++j;
    if (j == 3)
      continue;
    const int r = v_[3 * t + k], p = v_[3 * t + (k + 1) % 3], q = v_[3 * t + (k + 2) % 3];
    if ((j == 0 && (nb_[3 * u + 1] == t || nb_[3 * u + 2] == t)) ||
        (j == 1 && nb_[3 * u + 2] == t)) {
      // u shares two edges with t (a folded pair): the slot by its corners
      j = detail::slot_across(v_.data(), nb_.data(), u, t, p, q);
      if (j < 0)
        continue;
    }
    if (!flip_needed(pts, p, q, r, v_[3 * u + j]))
      continue;
    if (too_close(r, v_[3 * u + j])) { // the edge the flip would create
      valid_ = false;
      return false;
    }
    const int s = v_[3 * u + j];
    flip(t, k, u, j);
    if (++flips_ > max_flips) { // cannot happen for a valid mesh; be safe
      valid_ = false;
      return false;
    }
    // The four outer edges of the new pair (r, p, s) in t and (s, q, r) in
    // u: those opposite r and s.
    const int edges[4][2] = {{t, r}, {t, s}, {u, s}, {u, r}};
    for (const auto &e : edges) {
      stack_.push_back(e[0]);
      stack_.push_back(corner(e[0], e[1]));
    }
  }
  restore_partition();
  return true;
}


}  // namespace tessera
