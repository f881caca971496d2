// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh::advance: the per-step path (flips and cells in one pass, bit for bit
// the cells of update() + cells()).

#include "mesh_detail.h"

namespace tessera {

bool Mesh::advance(const Points &pts, int n_owned, const double *roi_lo, const double *roi_hi,
                   Tessellation &t, CellObserver *observer) {
  if (!valid_ || pts.n != n_points_ || stamp_ == 0 || t.mesh_stamp != stamp_ ||
      t.n_owned != n_owned || t.unbounded_cell >= 0 ||
      static_cast<int>(t.cell_offset.size()) != n_owned + 1 || n_owned > n_points_) {
    if (!update(pts, roi_lo, roi_hi))
      return false;
    cells(pts, n_owned, t);
    return true;
  }
  double sep2;
  if (!start_update(pts, sep2))
    return false;
  if (tiny_) { // no floating-point filters: the full path
    if (!update(pts, roi_lo, roi_hi))
      return false;
    cells(pts, n_owned, t);
    return true;
  }
  const int nt = static_cast<int>(v_.size() / 3);
  const int nft0 = nft_;
  t.triangles.resize(nft0);
  t.vertices.resize(nft0);
  t.radius.resize(nft0);
  const int *V = v_.data();
  const int *NB = nb_.data();
  Vec2 *h_out = t.vertices.data();
  double *r_out = t.radius.data();
  constexpr double eps = 2.220446049250313e-16;
  // Finite triangles: the fold check, the circumcentre (written into t; the
  // same arithmetic as cells()), and the in-circle test of each edge to a
  // finite triangle of higher number (each edge once, as in update()).
  for (int m = 0; m < nft0; ++m) {
    const int a = V[3 * m], b = V[3 * m + 1], c = V[3 * m + 2];
    // t.triangles[m] is still {a, b, c}: t matched the mesh after the last
    // call, and the triangles the flips change are rewritten below.
    const double ax = pts.x(a), ay = pts.y(a), bx = pts.x(b), by = pts.y(b), cx = pts.x(c),
                 cy = pts.y(c);
    // circumcentre(), written out to keep 1/D for the error bound below
    // (the same operations in the same order, so the same bits).
    const double bpx = bx - ax, bpy = by - ay, cpx = cx - ax, cpy = cy - ay;
    const double id = 0.5 / (bpx * cpy - bpy * cpx);
    const double b2 = bpx * bpx + bpy * bpy, c2 = cpx * cpx + cpy * cpy;
    // u = h - a, before a is added (h - a recomputed would carry the
    // rounding of a's magnitude, which the bound below does not cover).
    const double ux = (cpy * b2 - bpy * c2) * id;
    const double uy = (bpx * c2 - cpx * b2) * id;
    h_out[m].x = ax + ux;
    h_out[m].y = ay + uy;
    r_out[m] = root(ux * ux + uy * uy);
    const double l = bpx * cpy, r = bpy * cpx;
    const double D = l - r;
    const double sum_lr = std::fabs(l) + std::fabs(r);
    const bool certain = D > 3.3306690738754716e-16 * sum_lr;  // the sign of D is exact
    if (!certain && orientation(ax, ay, bx, by, cx, cy) <= 0) {
      if (!outside_region(ax, ay, bx, by, cx, cy, roi_lo, roi_hi)) {
        if (!fold_repair_) {
          valid_ = false;
          return false;
        }
        folded_.push_back(m);  // repaired after the pass, as update() does
        continue;
      }
      frozen_[m] = 1;
      continue;
    }
    // A bound on the error of u.
    const double R1 = std::fabs(ux) + std::fabs(uy);
    // (A triangle whose orientation needed the exact predicate gets no
    // bound: all its tests go to the exact predicate.)
    const double err_u =
        !certain ? std::numeric_limits<double>::infinity() :
        32.0 * eps *
            ((std::fabs(cpx) + std::fabs(cpy)) * b2 + (std::fabs(bpx) + std::fabs(bpy)) * c2 +
             R1 * sum_lr) *
            (2.0 * id) +
        8.0 * eps * R1;
    for (int k = 0; k < 3; ++k) {
      const int u = NB[3 * m + k];
      if (u < m)
        continue;
      const int p = V[3 * m + (k == 2 ? 0 : k + 1)], q = V[3 * m + (k == 0 ? 2 : k - 1)];
      {
        const double dx = pts.x(p) - pts.x(q), dy = pts.y(p) - pts.y(q);
        if (dx * dx + dy * dy < sep2) {
          valid_ = false;
          return false;
        }
      }
      if (u >= nft0)
        continue;  // a hull edge (the far triangle has the point at infinity)
      int j = (NB[3 * u + 1] == m) + 2 * (NB[3 * u + 2] == m);
      if (j == 3) {
        // u shares its other two edges with m (a folded pair beside a point
        // of degree two): the formula gave 3, and the read past u's corners
        // a wrong or no point; the slot across (p, q) is found by its corners.
        // (A pair that shares edges 0 and 1 or 0 and 2 reads one of u's own
        // corners; u is folded and repaired when the pass reaches it, and
        // flip_pass() finds the slot by its corners.)
        j = detail::slot_across(V, NB, u, m, p, q);
        if (j < 0) {
          valid_ = false;
          return false;
        }
      }
      const int s = V[3 * u + j];
      // s inside the circumcircle iff |s - h|^2 < |a - h|^2, i.e.
      // F = |d|^2 - 2 d.u < 0 with d = s - a.
      const double dx = pts.x(s) - ax, dy = pts.y(s) - ay;
      const double dd = dx * dx + dy * dy, du = dx * ux + dy * uy;
      const double F = dd - 2.0 * du;
      const double bound = 2.0 * (std::fabs(dx) + std::fabs(dy)) * err_u +
                           8.0 * eps * (dd + 2.0 * (std::fabs(dx * ux) + std::fabs(dy * uy)));
      bool inside;
      if (F < -bound)
        inside = true;
      else if (F > bound)
        inside = false;
      else
        inside = flip_needed(pts, p, q, V[3 * m + k], s);
      if (inside) {
        stack_.push_back(m);
        stack_.push_back(k);
      }
    }
  }
  // Triangles with the point at infinity: the hull chain tests, as update().
  for (int m = nft0; m < nt; ++m)
    if (!stack_edges(pts, m, sep2))
      return false;
  // Folded regions re-triangulated (their triangles join flipped_, their
  // points dirty_, so that they are read again below).
  if (!folded_.empty() && !repair_folds(pts, sep2))
    return false;
  if (!flip_pass(pts, sep2))
    return false;

  // The triangles the flips changed (and those moved into the finite range).
  const int nft = nft_;
  t.triangles.resize(nft);
  t.vertices.resize(nft);
  t.radius.resize(nft);
  for (const int m : flipped_) {
    if (m >= nft)
      continue;
    const int a = v_[3 * m], b = v_[3 * m + 1], c = v_[3 * m + 2];
    t.triangles[m] = {a, b, c};
    circumcentre(pts.x(a), pts.y(a), pts.x(b), pts.y(b), pts.x(c), pts.y(c), t.vertices[m],
                 t.radius[m]);
  }
  t.n_points = n_points_;

  // The cell lists: copied where no flip touched the cell's star (runs of
  // such cells at once), walked again (as cells() does) where one did.
  const size_t old_used = t.cell_vertex.size();
  size_t cap = std::max(spare_cv_.size(), old_used + old_used / 32 + 64);
  if (spare_cv_.size() < cap) {
    spare_cv_.resize(cap);
    spare_cn_.resize(cap);
  }
  int *off = t.cell_offset.data();
  const int *old_cv = t.cell_vertex.data(), *old_cn = t.cell_neighbor.data();
  size_t used = 0;
  int c = 0;
  while (c < n_owned) {
    if (!dirty_[c]) {
      int c1 = c + 1;
      while (c1 < n_owned && !dirty_[c1])
        ++c1;
      const int b0 = off[c], b1 = off[c1];
      const size_t len = static_cast<size_t>(b1 - b0);
      if (used + len > cap) {
        cap = 2 * (used + len);
        spare_cv_.resize(cap);
        spare_cn_.resize(cap);
      }
      std::copy(old_cv + b0, old_cv + b1, spare_cv_.data() + used);
      std::copy(old_cn + b0, old_cn + b1, spare_cn_.data() + used);
      const int shift = static_cast<int>(used) - b0;
      for (int cc = c; cc < c1; ++cc)
        off[cc] += shift;
      used += len;
      c = c1;
      continue;
    }
    off[c] = static_cast<int>(used);
    const int start = vt_[c];
    int m = start;
    do {
      const int *v = &v_[3 * m];
      const int i = (v[1] == c) + 2 * (v[2] == c);
      if (m >= nft) {  // unbounded: cells() reports it; let it
        stamp_ = 0;
        t.mesh_stamp = 0;
        cells(pts, n_owned, t);
        return true;
      }
      if (used == cap) {
        cap *= 2;
        spare_cv_.resize(cap);
        spare_cn_.resize(cap);
      }
      spare_cv_[used] = m;
      const int i1 = i == 2 ? 0 : i + 1, i2 = i1 == 2 ? 0 : i1 + 1;
      spare_cn_[used] = v[i2];
      ++used;
      m = nb_[3 * m + i1];
    } while (m != start);
    canonical_ring(spare_cv_.data() + off[c], spare_cn_.data() + off[c],
                   static_cast<int>(used) - off[c]);
    ++c;
  }
  off[n_owned] = static_cast<int>(used);
  // Swap the buffers: t gets the new lists; the old ones are the next spare
  // (kept at full size, so that resizing them costs nothing).
  spare_cv_.resize(used);
  spare_cn_.resize(used);
  t.cell_vertex.swap(spare_cv_);
  t.cell_neighbor.swap(spare_cn_);
  spare_cv_.resize(spare_cv_.capacity());
  spare_cn_.resize(spare_cn_.capacity());

  // Lengths, areas, perimeters and the seeds of multifold vertices, in the
  // order cells() finds them.
  auto same_vertex = [&](int a, int b) { return same_centre(pts, t, a, b); };
  seeds_.clear();
  t.edge_length.resize(used);
  t.area.resize(n_owned);
  t.perimeter.resize(n_owned);
  const Vec2 *H = t.vertices.data();
  const double *RAD = t.radius.data();
  const int *CV = t.cell_vertex.data(), *CN = t.cell_neighbor.data();
  double *EL = t.edge_length.data();
  if (observer) observer->begin(t);
  constexpr int kBlock = 64;  // cells per observer call (their data still in L1/L2)
  int block_start = 0;
  for (int cc = 0; cc < n_owned; ++cc) {
    const int o = off[cc], len = off[cc + 1] - o;
    const int *cv = CV + o, *cn = CN + o;
    for (int k = 0; k < len; ++k) {
      // The triangle at vertex k is (cc, cn[k-1], cn[k]): if both are ghosts
      // no owned cell shows the Voronoi edge opposite cc.
      if (cn[k] >= n_owned && cn[k == 0 ? len - 1 : k - 1] >= n_owned) {
        const int m = cv[k];
        const int *v = &v_[3 * m];
        const int i = (v[1] == cc) + 2 * (v[2] == cc);
        const int g = nb_[3 * m + i];
        if (g < nft && same_vertex(m, g))
          seeds_.push_back(m);
      }
    }
    cell_geometry(pts, t.triangles.data(), pts.x(cc), pts.y(cc), cv, len, H, RAD, EL + o,
                  t.area[cc], t.perimeter[cc]);
    if (observer && (cc + 1 - block_start == kBlock || cc + 1 == n_owned)) {
      observer->cells(t, block_start, cc + 1);
      block_start = cc + 1;
    }
  }
  find_groups(pts, t, [nft](int m) { return m < nft ? m : -1; }, [](int k) { return k; });
  t.unbounded_cell = -1;
  t.mesh_stamp = stamp_ = detail::next_stamp();
  last_incremental_ = true;
  if (observer) observer->end(t);
  return true;
}


}  // namespace tessera
