// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh::repair_folds: local repair of triangles that folded over (a point
// crossed an edge), so that a fold costs work in proportion to its size
// instead of a from-scratch rebuild of the whole mesh.
//
// For a folded triangle the cavity is the union of the stars of its corners
// (and of the corners of every other folded triangle met in it).  When the
// cavity is a topological disk whose boundary, at the new positions, is a
// simple counter-clockwise polygon with every inner point strictly inside
// it, the cavity is re-triangulated: the polygon by ear clipping, then the
// inner points inserted one by one (a triangle split in three, or two split
// in four when the point lies on an inner edge), all with exact orientation
// tests.  The new triangles are all counter-clockwise and fill the same
// polygon, so the mesh is a valid triangulation again; they take the
// cavity's slots (a disk with b boundary and i inner points always has
// b - 2 + 2 i triangles) and their edges go onto the flip stack, so that the
// Lawson flips of flip_pass() make the result Delaunay.  Where a check
// fails the cavity grows by one ring (the stars of all its points) and is
// tried again, up to kMaxRounds rings and kMaxCavity triangles; a cavity
// that reaches the point at infinity is not repaired.  Frozen triangles
// (folded outside the region of interest) met in a cavity are mended with
// it.
// Then the mesh is invalid and the caller rebuilds from scratch.

#include "mesh_detail.h"

#include <array>
#include <climits>

namespace tessera {

namespace {

constexpr int kMaxRounds = 4;     // rings added to a cavity before giving up
constexpr int kMaxCavity = 512;   // triangles in one cavity before giving up

// Whether the closed segments [a, b] and [c, d] meet (exact).
inline bool segments_meet(const Points &pts, int a, int b, int c, int d) {
  auto o = [&](int p, int q, int r) {
    return orientation(pts.x(p), pts.y(p), pts.x(q), pts.y(q), pts.x(r), pts.y(r));
  };
  const int o1 = o(a, b, c), o2 = o(a, b, d), o3 = o(c, d, a), o4 = o(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0)
    return true;
  // Touching or collinear overlap: an endpoint on the other segment.
  auto on = [&](int p, int q, int r) {  // r on closed [p, q], given collinear
    return std::min(pts.x(p), pts.x(q)) <= pts.x(r) && pts.x(r) <= std::max(pts.x(p), pts.x(q)) &&
           std::min(pts.y(p), pts.y(q)) <= pts.y(r) && pts.y(r) <= std::max(pts.y(p), pts.y(q));
  };
  return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) ||
         (o4 == 0 && on(c, d, b));
}

}  // namespace

bool Mesh::repair_folds(const Points &pts, double sep2) {
  for (const int f : folded_) {
    const int a = v_[3 * f], b = v_[3 * f + 1], c = v_[3 * f + 2];
    // Rewritten (and so counter-clockwise) by the repair of an earlier one.
    if (a != kInfinite && b != kInfinite && c != kInfinite &&
        orientation(pts.x(a), pts.y(a), pts.x(b), pts.y(b), pts.x(c), pts.y(c)) > 0)
      continue;
    if (!repair_one(pts, sep2, f)) {
      valid_ = false;
      return false;
    }
  }
  return true;
}

bool Mesh::repair_one(const Points &pts, double sep2, int f) {
  auto orient = [&](int p, int q, int r) {
    return orientation(pts.x(p), pts.y(p), pts.x(q), pts.y(q), pts.x(r), pts.y(r));
  };
  auto has = [](const std::vector<int> &sorted, int x) {
    return std::binary_search(sorted.begin(), sorted.end(), x);
  };
  std::vector<int> X(v_.begin() + 3 * f, v_.begin() + 3 * f + 3);  // points whose stars are taken
  std::vector<int> C;                                               // cavity triangles (sorted)
  std::vector<int> verts, B, inner, added;
  struct Outside {
    int p, q, tri, edge;  // boundary edge p -> q (cavity on its left), the triangle across
  };
  std::vector<Outside> bnd;
  std::vector<std::array<int, 3>> T;  // the new triangles
  for (int round = 0; round <= kMaxRounds; ++round) {
    std::sort(X.begin(), X.end());
    X.erase(std::unique(X.begin(), X.end()), X.end());
    // The cavity: the stars of X; folded triangles met in it bring their
    // corners in too.
    bool grew = true, bad = false;
    while (grew && !bad) {
      grew = false;
      C.clear();
      for (const int x : X) {
        if (x == kInfinite) {
          bad = true;
          break;
        }
        const int start = vt_[x];
        int m = start;
        int guard = 0;
        do {
          C.push_back(m);
          const int *v = &v_[3 * m];
          const int i = (v[1] == x) + 2 * (v[2] == x);
          m = nb_[3 * m + (i == 2 ? 0 : i + 1)];
          if (++guard > kMaxCavity) {
            bad = true;
            break;
          }
        } while (m != start);
        if (bad)
          break;
      }
      if (bad)
        break;
      std::sort(C.begin(), C.end());
      C.erase(std::unique(C.begin(), C.end()), C.end());
      if (static_cast<int>(C.size()) > kMaxCavity) {
        bad = true;
        break;
      }
      for (const int t : C) {
        const int *v = &v_[3 * t];
        if (v[0] == kInfinite || v[1] == kInfinite || v[2] == kInfinite) {
          bad = true;
          break;
        }
        // Folded (a frozen triangle too: it is mended with the rest).
        if (frozen_[t] || orient(v[0], v[1], v[2]) <= 0) {
          for (int k = 0; k < 3; ++k)
            if (!has(X, v[k])) added.push_back(v[k]);  // X stays sorted for has()
        }
      }
      if (!bad && !added.empty()) {
        X.insert(X.end(), added.begin(), added.end());
        added.clear();
        std::sort(X.begin(), X.end());
        X.erase(std::unique(X.begin(), X.end()), X.end());
        grew = true;
      }
    }
    if (bad)
      return false;  // the point at infinity, or too large: rebuild

    // The boundary: edges to triangles outside the cavity, each p -> q
    // counter-clockwise around the cavity.
    bnd.clear();
    verts.clear();
    for (const int t : C)
      for (int k = 0; k < 3; ++k) {
        verts.push_back(v_[3 * t + k]);
        const int u = nb_[3 * t + k];
        if (has(C, u))
          continue;
        const int p = v_[3 * t + (k + 1) % 3], q = v_[3 * t + (k + 2) % 3];
        int j = 0;
        while (j < 3 && !(nb_[3 * u + j] == t && v_[3 * u + (j + 1) % 3] == q &&
                          v_[3 * u + (j + 2) % 3] == p))
          ++j;
        if (j == 3)
          return false;  // inconsistent adjacency: cannot happen for a valid mesh
        bnd.push_back({p, q, u, j});
      }
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    // One loop through every boundary edge, each point on it once.
    bool ok = !bnd.empty();
    B.clear();
    if (ok) {
      std::vector<std::pair<int, int>> next;  // p -> q, sorted by p
      next.reserve(bnd.size());
      for (const auto &e : bnd) next.emplace_back(e.p, e.q);
      std::sort(next.begin(), next.end());
      for (size_t i = 1; i < next.size() && ok; ++i)
        if (next[i].first == next[i - 1].first) ok = false;  // a pinch point
      int p = next[0].first;
      while (ok) {
        B.push_back(p);
        const auto it = std::lower_bound(next.begin(), next.end(), std::make_pair(p, INT_MIN));
        if (it == next.end() || it->first != p) {
          ok = false;
          break;
        }
        p = it->second;
        if (p == B[0])
          break;
        if (B.size() > next.size()) ok = false;
      }
      if (ok && B.size() != next.size()) ok = false;  // more than one loop
    }
    inner.clear();
    if (ok) {
      std::vector<int> sb(B);
      std::sort(sb.begin(), sb.end());
      for (const int p : verts)
        if (!has(sb, p)) inner.push_back(p);
      // Euler: a disk with b boundary and i inner points has b - 2 + 2 i triangles.
      if (C.size() != B.size() - 2 + 2 * inner.size()) ok = false;
    }
    // The polygon at the new positions: simple and counter-clockwise.
    const int nb = static_cast<int>(B.size());
    if (ok) {
      for (int i = 0; i < nb && ok; ++i) {
        const int p0 = B[i], p1 = B[(i + 1) % nb], p2 = B[(i + 2) % nb];
        // Adjacent edges must not fold back onto each other.
        if (orient(p0, p1, p2) == 0 &&
            (pts.x(p2) - pts.x(p1)) * (pts.x(p1) - pts.x(p0)) +
                    (pts.y(p2) - pts.y(p1)) * (pts.y(p1) - pts.y(p0)) <
                0)
          ok = false;
        for (int j = i + 2; j < nb && ok; ++j) {
          if (i == 0 && j == nb - 1) continue;  // adjacent through the wrap
          if (segments_meet(pts, p0, p1, B[j], B[(j + 1) % nb])) ok = false;
        }
      }
    }
    if (ok) {
      double area2 = 0.0;  // only a sanity check of the orientation (simple polygon)
      const double ox = pts.x(B[0]), oy = pts.y(B[0]);
      for (int i = 0; i < nb; ++i) {
        const int p = B[i], q = B[(i + 1) % nb];
        area2 += (pts.x(p) - ox) * (pts.y(q) - oy) - (pts.x(q) - ox) * (pts.y(p) - oy);
      }
      if (!(area2 > 0.0)) ok = false;
    }
    // Ear clipping (exact orientation tests): an ear is a strictly convex
    // corner whose closed triangle holds no other point of the polygon.
    T.clear();
    if (ok) {
      std::vector<int> L(B);
      while (ok && L.size() > 3) {
        const int n = static_cast<int>(L.size());
        bool found = false;
        for (int i = 0; i < n && !found; ++i) {
          const int p = L[(i + n - 1) % n], q = L[i], r = L[(i + 1) % n];
          if (orient(p, q, r) <= 0) continue;
          bool empty = true;
          for (int k = 0; k < n && empty; ++k) {
            const int w = L[k];
            if (w == p || w == q || w == r) continue;
            if (orient(p, q, w) >= 0 && orient(q, r, w) >= 0 && orient(r, p, w) >= 0)
              empty = false;
          }
          if (!empty) continue;
          T.push_back({p, q, r});
          L.erase(L.begin() + i);
          found = true;
        }
        if (!found) ok = false;
      }
      if (ok) {
        if (orient(L[0], L[1], L[2]) > 0)
          T.push_back({L[0], L[1], L[2]});
        else
          ok = false;
      }
    }
    // The inner points, each strictly inside a triangle (split in three) or
    // on an edge between two (both split in two).
    for (size_t ii = 0; ii < inner.size() && ok; ++ii) {
      const int x = inner[ii];
      int hit = -1, zero = -1;
      for (int t = 0; t < static_cast<int>(T.size()); ++t) {
        const auto &tr = T[t];
        const int o0 = orient(tr[1], tr[2], x), o1 = orient(tr[2], tr[0], x),
                  o2 = orient(tr[0], tr[1], x);
        if (o0 < 0 || o1 < 0 || o2 < 0) continue;
        const int zeros = (o0 == 0) + (o1 == 0) + (o2 == 0);
        if (zeros > 1) {  // on a corner: coincident points; build() names them
          ok = false;
          break;
        }
        hit = t;
        zero = zeros == 0 ? -1 : (o0 == 0 ? 0 : (o1 == 0 ? 1 : 2));
        break;
      }
      if (!ok) break;
      if (hit < 0) {  // outside the polygon: grow
        ok = false;
        break;
      }
      const auto tr = T[hit];
      if (zero < 0) {
        T[hit] = {tr[0], tr[1], x};
        T.push_back({tr[1], tr[2], x});
        T.push_back({tr[2], tr[0], x});
        continue;
      }
      // On the edge opposite corner `zero`: (p, q), with the triangle (q, p, s) across.
      const int r = tr[zero], p = tr[(zero + 1) % 3], q = tr[(zero + 2) % 3];
      int other = -1, s = -1;
      for (int t = 0; t < static_cast<int>(T.size()) && other < 0; ++t)
        for (int k = 0; k < 3; ++k)
          if (T[t][(k + 1) % 3] == q && T[t][(k + 2) % 3] == p) {
            other = t;
            s = T[t][k];
            break;
          }
      if (other < 0) {  // on the polygon's boundary: grow
        ok = false;
        break;
      }
      T[hit] = {r, p, x};
      T.push_back({q, r, x});
      T[other] = {s, q, x};
      T.push_back({p, s, x});
    }
    if (ok && T.size() != C.size()) ok = false;  // cannot happen after the Euler check
    for (auto &tr : T)  // each with its smallest point first, as Mesh::canonical()
      std::rotate(tr.begin(), std::min_element(tr.begin(), tr.end()), tr.end());
    if (ok) {
      // New edges closer than the separation limit: build() names the points.
      for (const auto &tr : T)
        for (int k = 0; k < 3; ++k) {
          const int p = tr[k], q = tr[(k + 1) % 3];
          const double dx = pts.x(p) - pts.x(q), dy = pts.y(p) - pts.y(q);
          if (dx * dx + dy * dy < sep2) return false;
        }
      // Into the cavity's slots: corners, adjacency (inside, then across the
      // boundary), one triangle per point.
      const int nt = static_cast<int>(T.size());
      for (int i = 0; i < nt; ++i) {
        for (int k = 0; k < 3; ++k) v_[3 * C[i] + k] = T[i][k];
        frozen_[C[i]] = 0;
      }
      for (int i = 0; i < nt; ++i) {
        for (int k = 0; k < 3; ++k) {
          const int p = T[i][(k + 1) % 3], q = T[i][(k + 2) % 3];
          int across = -1;
          for (int j = 0; j < nt && across < 0; ++j) {
            if (j == i) continue;
            for (int e = 0; e < 3; ++e)
              if (T[j][(e + 1) % 3] == q && T[j][(e + 2) % 3] == p) {
                across = C[j];
                break;
              }
          }
          if (across < 0) {
            for (const auto &e : bnd)
              if (e.p == p && e.q == q) {
                across = e.tri;
                nb_[3 * e.tri + e.edge] = C[i];
                break;
              }
          }
          if (across < 0) return false;  // cannot happen: the polygon's edges are the boundary's
          nb_[3 * C[i] + k] = across;
        }
        for (int k = 0; k < 3; ++k) vt_[T[i][k]] = C[i];
      }
      for (const int p : verts) mark_dirty(p);
      for (int i = 0; i < nt; ++i) {
        flipped_.push_back(C[i]);
        for (int k = 0; k < 3; ++k) {
          stack_.push_back(C[i]);
          stack_.push_back(k);
        }
      }
      ++repairs_;
      repaired_triangles_ += nt;
      return true;
    }
    // Grow by one ring: the stars of every point of the cavity.
    X = verts;
  }
  return false;
}

}  // namespace tessera
