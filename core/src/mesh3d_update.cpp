// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh3::update and advance: the region of interest, the scan for
// tetrahedra that are inverted or not locally Delaunay, and their repair by
// flips (with substeps when the flips get stuck).

#include "tessera/mesh3d.h"

#include "mesh3d_detail.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tessera {

// Outcodes of the points against the region of interest: bit 2d (2d+1) set
// when coordinate d lies below (above) the region grown by the buffer, bits
// 6 + 2d (7 + 2d) the same for the region itself.  Points whose outcodes
// share a bit are separated from the (grown) region by one of its faces'
// planes, and so is their convex hull.
void Mesh3::outcodes(const Points3 &pts) {
  const int n = n_points_;
  code_.resize(n + 8);
  for (int i = 0; i < n + 8; ++i) {
    const double *p = pos(pts, i);
    unsigned c = 0;
    for (int d = 0; d < 3; ++d) {
      c |= (p[d] < roi_lo_[d] - buffer_) << (2 * d);
      c |= (p[d] > roi_hi_[d] + buffer_) << (2 * d + 1);
      c |= (p[d] < roi_lo_[d]) << (6 + 2 * d);
      c |= (p[d] > roi_hi_[d]) << (7 + 2 * d);
    }
    code_[i] = static_cast<unsigned short>(c);
  }
}

// Whether the points v[0..m) are separated from the region of interest
// (grown by the buffer if grown).
bool Mesh3::outside(const int *v, int m, bool grown) const {
  if (!roi_lo_) return false;
  unsigned c = code_[v[0]];
  for (int s = 1; s < m; ++s) c &= code_[v[s]];
  return (grown ? c & 0x3f : c >> 6) != 0;
}

// Marks the tetrahedra to leave alone (free slots, outside the region) and
// lists the others that are inverted or flat in pending_; returns how many.
int Mesh3::scan(const Points3 &pts) {
  const int nt = static_cast<int>(tv_.size() / 4);
  if (roi_lo_) outcodes(pts);
  pending_.clear();
  if (skip_.size() < static_cast<size_t>(nt)) skip_.resize(nt);
  for (int t = 0; t < nt; ++t) {
    const int *q = &tv_[4 * t];
    skip_[t] = q[0] < 0 || outside(q, 4, true);
    if (skip_[t]) continue;
    if (orient(pts, q[0], q[1], q[2], q[3]) <= 0) pending_.push_back(t);
  }
  return static_cast<int>(pending_.size());
}

// After scan(pts): untangles pending_, then restores the Delaunay property.
bool Mesh3::repair(const Points3 &pts) {
  const int nt = static_cast<int>(tv_.size() / 4);
  stack_.clear();
  // Untangle inverted or flat tetrahedra first (the in-sphere test needs
  // positive ones): rounds over them while some flip succeeds.
  while (!pending_.empty()) {
    bool progress = false;
    for (size_t i = 0; i < pending_.size(); ++i) {
      const int t = pending_[i];
      const int *q = &tv_[4 * t];
      if (q[0] < 0 || orient(pts, q[0], q[1], q[2], q[3]) > 0) {
        pending_[i--] = pending_.back();
        pending_.pop_back();
        continue;
      }
      if (untangle(pts, t)) {
        progress = true;
        ++untangled_;
        pending_[i--] = pending_.back();
        pending_.pop_back();
      }
    }
    if (progress) continue;
    // Left as they are outside the region itself (in the buffer around it).
    for (const int t : pending_) {
      if (!outside(&tv_[4 * t], 4, false)) {
        failure_ = "an inverted or flat tetrahedron no flip repairs";
        return false;
      }
      skip_[t] = 1;
    }
    pending_.clear();
  }
  const long limit = flips_ + 1000 + n_tets();
  bool flipped_this_round = false;
  // One interior triangle (4 t + k): flipped if it is not locally Delaunay;
  // false when the flips exceed the limit.
  auto visit = [&](int code) {
    const int t = code >> 2, k = code & 3;
    if (tv_[4 * t] < 0) return true;
    const int u = tn_[4 * t + k];
    if (u < 0 || skip_[t] || skip_[u]) return true;
    if (roi_lo_) {
      const int f[3] = {tv_[4 * t + kFace[k][0]], tv_[4 * t + kFace[k][1]], tv_[4 * t + kFace[k][2]]};
      if (outside(f, 3, true)) return true;
    }
    if (insphere(pts, &tv_[4 * t], tv_[4 * u + slot_of_nb(u, t)]) <= 0) return true;
    if (!flip_face(pts, t, k)) {
      pending_.push_back(code);
      return true;
    }
    flipped_this_round = true;
    if (++flips_ > limit) {
      failure_ = "more flips than tetrahedra";
      return false;
    }
    return true;
  };
  // The triangles made by a flip (stack_), depth first.
  auto drain = [&]() {
    while (!stack_.empty()) {
      const int code = stack_.back();
      stack_.pop_back();
      if (!visit(code)) return false;
    }
    return true;
  };
  // Every interior triangle of the region once, in a sweep over the
  // tetrahedra (a stack of them all would hold two ints per tetrahedron);
  // the triangles of a flip are checked before the sweep goes on.  Most
  // triangles are decided from the circumsphere of the tetrahedron on their
  // lower-numbered side, computed once for its triangles (clearly_outside:
  // the opposite point lies well outside, so the triangle is Delaunay, as
  // the predicate would say); the rest, near ties and flat tetrahedra,
  // take the in-sphere predicate in visit().
  for (int t = 0; t < nt; ++t) {
    if (skip_[t] || tv_[4 * t] < 0) continue;
    double v[3], r2 = 0.0;
    bool sphere = false;
    long sphere_at = -1;  // flips_ when the sphere was computed (a flip may change t)
    for (int k = 0; k < 4; ++k) {
      const int *q = &tv_[4 * t];
      if (q[0] < 0) break;
      const int u = tn_[4 * t + k];
      if (!(u > t || (u >= 0 && skip_[u]))) continue;
      if (u >= 0 && !skip_[u]) {
        const double *p0 = pos(pts, q[0]);
        if (sphere_at != flips_) {
          sphere = detail3::circumsphere(p0, pos(pts, q[1]), pos(pts, q[2]), pos(pts, q[3]), v, r2);
          sphere_at = flips_;
        }
        const double *e = pos(pts, tv_[4 * u + slot_of_nb(u, t)]);
        if (sphere && detail3::clearly_outside(p0, v, r2, e)) continue;
      }
      if (!visit(4 * t + k) || !drain()) return false;
    }
  }
  for (;;) {
    if (!drain()) return false;
    if (pending_.empty()) break;
    if (!flipped_this_round) {
      // A round over the waiting triangles changed nothing: if one of them
      // is still not locally Delaunay, no flip sequence found it.
      for (const int code : pending_) {
        const int t = code >> 2, k = code & 3;
        if (tv_[4 * t] < 0) continue;
        const int u = tn_[4 * t + k];
        if (u < 0) continue;
        const int f[3] = {tv_[4 * t + kFace[k][0]], tv_[4 * t + kFace[k][1]], tv_[4 * t + kFace[k][2]]};
        if (insphere(pts, &tv_[4 * t], tv_[4 * u + slot_of_nb(u, t)]) > 0 && !outside(f, 3, false)) {
          failure_ = "a non-Delaunay triangle no flip repairs";
          return false;
        }
      }
      pending_.clear();
      break;
    }
    flipped_this_round = false;
    // Another round over the waiting triangles.
    stack_.swap(pending_);
    pending_.clear();
  }
  return true;
}

bool Mesh3::update(const Points3 &pts, const double *roi_lo, const double *roi_hi) {
  flips_ = f23_ = f32_ = f44_ = exact_ = untangled_ = substeps_ = 0;
  failure_ = nullptr;
  if (!valid_ || pts.n != n_points_) {
    failure_ = valid_ ? "the number of points changed" : "the mesh is invalid (call build())";
    valid_ = false;
    return false;
  }
  const int n = n_points_;
  for (int i = 0; i < n; ++i) {
    const double *p = pts.p(i);
    if (!std::isfinite(p[0] + p[1] + p[2])) {
      failure_ = "non-finite coordinates";
      valid_ = false;
      return false;
    }
  }
  roi_lo_ = roi_hi_ = nullptr;
  if (roi_lo && roi_hi) {
    std::copy(roi_lo, roi_lo + 3, roi_box_);
    std::copy(roi_hi, roi_hi + 3, roi_box_ + 3);
    roi_lo_ = roi_box_;
    roi_hi_ = roi_box_ + 3;
  }
  // First in one go; if the flips get stuck (several events of a continuous
  // motion merged into one step can leave no flippable triangle), back to
  // the mesh as it was and again in 2, 4, 8 substeps from the previous
  // positions, each one repaired before the next.
  undo_.clear();
  bool ok = false;
  for (int nsub = 1; nsub <= 8 && !ok; nsub *= 2) {
    if (nsub > 1) {
      rollback();
      f23_ = f32_ = f44_ = untangled_ = 0;
    }
    substeps_ = nsub;
    ok = true;
    for (int k = 1; k <= nsub && ok; ++k) {
      const Points3 at = k == nsub ? pts : interpolate(pts, static_cast<double>(k) / nsub);
      scan(at);
      ok = repair(at);
    }
  }
  flips_ = f23_ + f32_ + f44_;
  if (!ok) {
    valid_ = false;
    return false;
  }
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) prev_[3 * i + d] = pts.p(i)[d];
  return true;
}

Points3 Mesh3::interpolate(const Points3 &pts, double s) {
  const int n = n_points_;
  mid_.resize(3 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) mid_[3 * i + d] = prev_[3 * i + d] + s * (pts.p(i)[d] - prev_[3 * i + d]);
  return Points3{mid_.data(), n, 3};
}

bool Mesh3::advance(const Points3 &pts, int n_owned, const double *roi_lo, const double *roi_hi,
                    Tessellation3 &t) {
  incremental_ = false;
  if (!update(pts, roi_lo, roi_hi)) return false;
  try {
    cells(pts, n_owned, t);
  } catch (const Error &) {
    // (nearly coincident centres, an owned cell outside the region or on
    // the hull): build() and cells() again report it, naming the points
    valid_ = false;
    return false;
  }
  incremental_ = true;
  return true;
}

}  // namespace tessera
