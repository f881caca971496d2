// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The convex hull of points near the unit sphere (sphere_hull.h): incremental, on
// flat arrays.  Each insertion finds one facet the new point q sees (strictly above
// its plane), grows the set of facets it sees from there (it is a disc: seen from q,
// the facets q is above cover the hull's silhouette once), and replaces them by the
// cone of triangles from q to the disc's boundary, the horizon.  A point that sees no
// facet lies in the hull of the points before it, hence in the final hull: no vertex.
//
// Finding the first facet, two ways.  Walk: with a point o strictly inside the first
// tetrahedron (so inside every later hull), the facets' cones from o partition space;
// walking across the edges whose plane through o separates the facet from q ends at
// the facet whose cone holds q, and q, outside the hull, is above that facet's plane
// or q is in the hull.  Points come along a Hilbert curve on the sphere, so walks are
// short.  Conflict: every point not yet inserted keeps one facet it sees; when that
// facet goes, the point sees one of the new facets or lies in the new hull (a segment
// from q to the inside of the removed facet leaves the new hull through a new facet),
// so only the new facets are tested.
//
// Every sign is exact: a floating-point filter, and exact::orient3d where it cannot
// decide.  Points on a common plane (co-circular points: cube faces) are never above
// one another's facets, so their face of the hull comes out as a triangulated polygon.

#include "sphere_hull.h"

#include "exact_predicates.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <utility>

namespace tessera {
namespace sphere_detail {

namespace {

// ------------------------------------------------------------------ predicates

// Sign of det[b-a; c-a; d-a] (exact::orient3d's).  In doubles, the determinant is
// off by less than 7u (1 + 8u) times its permanent (the same expansion with every
// product's absolute value; u = 2^-53, one rounding per operation on a chain of at
// most seven), plus what gradual underflow loses in its ~20 operations: 8u and
// DBL_MIN bound both.  Only signs closer to 0 than that are computed exactly.
inline int orient3(const double *a, const double *b, const double *c, const double *d) {
  const double bx = b[0] - a[0], by = b[1] - a[1], bz = b[2] - a[2];
  const double cx = c[0] - a[0], cy = c[1] - a[1], cz = c[2] - a[2];
  const double dx = d[0] - a[0], dy = d[1] - a[1], dz = d[2] - a[2];
  const double m1 = cy * dz, m2 = cz * dy, m3 = cz * dx, m4 = cx * dz, m5 = cx * dy, m6 = cy * dx;
  const double det = bx * (m1 - m2) + by * (m3 - m4) + bz * (m5 - m6);
  const double perm = std::fabs(bx) * (std::fabs(m1) + std::fabs(m2)) +
                      std::fabs(by) * (std::fabs(m3) + std::fabs(m4)) +
                      std::fabs(bz) * (std::fabs(m5) + std::fabs(m6));
  const double bound = 0x1p-50 * perm + DBL_MIN;
  if (det > bound)
    return 1;
  if (det < -bound)
    return -1;
  return exact::orient3d(a, b, c, d);
}

// Sign of det[b-a; c-a] for 2D points; the error is below 3u (1 + 4u) of the
// permanent, bounded by 4u.
inline int orient2(const double *a, const double *b, const double *c) {
  const double l = (b[0] - a[0]) * (c[1] - a[1]), r = (b[1] - a[1]) * (c[0] - a[0]);
  const double det = l - r, bound = 0x1p-51 * (std::fabs(l) + std::fabs(r)) + DBL_MIN;
  if (det > bound)
    return 1;
  if (det < -bound)
    return -1;
  return exact::orient2d(a, b, c);
}

// Three points of space are collinear iff their projections onto the three
// coordinate planes are (the cross product's components are those orientations).
bool collinear(const double *a, const double *b, const double *c) {
  for (int k = 0; k < 3; ++k) {
    const int x = k, y = (k + 1) % 3;
    const double pa[2] = {a[x], a[y]}, pb[2] = {b[x], b[y]}, pc[2] = {c[x], c[y]};
    if (orient2(pa, pb, pc) != 0)
      return false;
  }
  return true;
}

// ------------------------------------------------------------------ spatial order

// Position along a Hilbert curve through a 2^kBits x 2^kBits grid: at each scale,
// the quadrant's place along the curve, then the coordinates turned into the
// quadrant's own frame (the lower quadrants are transposed, the lower right one also
// mirrored, so that the curve enters and leaves them at the right corners).
constexpr int kBits = 16;

uint64_t hilbert_index(uint32_t x, uint32_t y) {
  uint64_t d = 0;
  for (uint32_t s = 1u << (kBits - 1); s > 0; s >>= 1) {
    const uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += static_cast<uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = s - 1 - x;
        y = s - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

// A point's place on the sphere: the cube face its direction goes through (the
// largest coordinate and its sign), then the Hilbert index of the central
// projection onto that face.
uint64_t sphere_key(const double *p) {
  const double ax = std::fabs(p[0]), ay = std::fabs(p[1]), az = std::fabs(p[2]);
  const int axis = ax >= ay && ax >= az ? 0 : ay >= az ? 1 : 2;
  const double m = std::fabs(p[axis]);
  const uint64_t face = 2 * axis + (p[axis] < 0.0 ? 1 : 0);
  const double side = static_cast<double>(1u << kBits);
  auto q = [&](double s) {
    const double x = (s / m + 1.0) * 0.5 * side;
    return x >= side ? (1u << kBits) - 1 : x > 0.0 ? static_cast<uint32_t>(x) : 0u;
  };
  return face << (2 * kBits) | hilbert_index(q(p[(axis + 1) % 3]), q(p[(axis + 2) % 3]));
}

struct KeyIndex {
  uint64_t key;
  int index;
};

// Stable least-significant-digit radix sort on the 2 kBits + 3 = 35 bits of the keys.
void radix_sort(std::vector<KeyIndex> &v) {
  constexpr int kDigit = 12;
  std::vector<KeyIndex> tmp(v.size());
  for (int shift = 0; shift < 2 * kBits + 3; shift += kDigit) {
    std::vector<size_t> start((1u << kDigit) + 1, 0);
    for (const KeyIndex &e : v)
      ++start[((e.key >> shift) & ((1u << kDigit) - 1)) + 1];
    for (size_t b = 1; b < start.size(); ++b)
      start[b] += start[b - 1];
    for (const KeyIndex &e : v)
      tmp[start[(e.key >> shift) & ((1u << kDigit) - 1)]++] = e;
    v.swap(tmp);
  }
}

// ------------------------------------------------------------------ the hull

// Facet f has corners fv[3f..3f+2], counter-clockwise seen from outside, and
// fn[3f+k] is the facet across its edge fv[3f+k] -> fv[3f+(k+1)%3].
class Hull {
public:
  Hull(const double *xyz, int n) : xyz_(xyz), start_of_(n, -1) {
    // A hull of n points has 2n - 4 facets; one insertion's removed facets wait
    // one insertion before their slots are reused.
    const size_t slots = 2 * static_cast<size_t>(n) + 64;
    fv.reserve(3 * slots);
    fn.reserve(3 * slots);
    alive.reserve(slots);
    mark_.reserve(slots);
  }

  const double *p(int i) const { return xyz_ + 3 * i; }
  bool sees(int f, int q) const {
    return orient3(p(fv[3 * f]), p(fv[3 * f + 1]), p(fv[3 * f + 2]), p(q)) > 0;
  }
  int facets() const { return static_cast<int>(alive.size()); }
  long live() const { return live_; }

  // The tetrahedron a b c d, its four facets turned outwards (orient3(a,b,c,d) != 0).
  void start(int a, int b, int c, int d) {
    if (orient3(p(a), p(b), p(c), p(d)) > 0)
      std::swap(b, c);
    // Each facet: the other three corners in an order that keeps the fourth below.
    const int f[4][3] = {{a, b, c}, {b, a, d}, {a, c, d}, {c, b, d}};
    for (const auto &t : f)
      make(t[0], t[1], t[2]);
    for (int g = 0; g < 4; ++g)
      for (int k = 0; k < 3; ++k) {
        const int u = fv[3 * g + k], v = fv[3 * g + (k + 1) % 3];
        for (int h = 0; h < 4; ++h)
          for (int m = 0; m < 3; ++m)
            if (fv[3 * h + m] == v && fv[3 * h + (m + 1) % 3] == u)
              fn[3 * g + k] = h;
      }
  }

  // Inserts q, which sees facet f.  Afterwards removed holds the facets it saw (their
  // slots are reused from the next insertion on) and created the new ones.
  void insert(int q, int f) {
    ++stamp_;
    for (const int h : removed)
      free_.push_back(h);
    removed.clear();
    created.clear();
    horizon_.clear();
    mark(f, true);
    stack_.assign(1, f);
    while (!stack_.empty()) {
      const int h = stack_.back();
      stack_.pop_back();
      removed.push_back(h);
      for (int k = 0; k < 3; ++k) {
        const int g = fn[3 * h + k];
        bool seen = mark_[g] == 2 * stamp_ + 1;
        if (mark_[g] < 2 * stamp_) {
          seen = sees(g, q);
          mark(g, seen);
          if (seen)
            stack_.push_back(g);
        }
        if (!seen) {
          int kg = 0;
          while (fn[3 * g + kg] != h)
            ++kg;
          horizon_.push_back({fv[3 * h + k], fv[3 * h + (k + 1) % 3], g, kg});
        }
      }
    }
    // The cone: one triangle (u, v, q) on each horizon edge u -> v, joined to the
    // facet outside the edge and to the triangles on the edges into u and out of v.
    for (const Edge &e : horizon_) {
      const int t = make(e.u, e.v, q);
      fn[3 * t] = e.out;
      fn[3 * e.out + e.k_out] = t;
      start_of_[e.u] = t;
      created.push_back(t);
    }
    for (const int t : created) {
      const int next = start_of_[fv[3 * t + 1]];
      fn[3 * t + 1] = next;
      fn[3 * next + 2] = t;
    }
    for (const int h : removed)
      alive[h] = 0;
    live_ += static_cast<long>(created.size()) - static_cast<long>(removed.size());
  }

  // From facet f, the facet whose cone from o holds q, or -1 after max_steps steps
  // (visibility walk: never back over the edge it came through, the first edge to
  // test chosen at random so that no fixed order can make it go round in circles).
  int walk(int f, int q, const double *o, long max_steps) {
    int prev = -1;
    for (long step = 0; step < max_steps; ++step) {
      rng_ ^= rng_ << 13;
      rng_ ^= rng_ >> 17;
      rng_ ^= rng_ << 5;
      const int k0 = static_cast<int>(rng_ % 3);
      int next = -1;
      for (int m = 0; m < 3 && next < 0; ++m) {
        const int k = (k0 + m) % 3, g = fn[3 * f + k];
        if (g != prev && orient3(o, p(fv[3 * f + k]), p(fv[3 * f + (k + 1) % 3]), p(q)) < 0)
          next = g;
      }
      if (next < 0)
        return f;
      prev = f;
      f = next;
    }
    return -1;
  }

  std::vector<int> fv, fn;
  std::vector<char> alive;
  std::vector<int> removed, created;

private:
  struct Edge {
    int u, v, out, k_out;
  };
  int make(int a, int b, int c) {
    int t;
    if (!free_.empty()) {
      t = free_.back();
      free_.pop_back();
      fv[3 * t] = a, fv[3 * t + 1] = b, fv[3 * t + 2] = c;
      alive[t] = 1;
      mark_[t] = 0;
    } else {
      t = facets();
      fv.push_back(a);
      fv.push_back(b);
      fv.push_back(c);
      for (int k = 0; k < 3; ++k)
        fn.push_back(-1);
      alive.push_back(1);
      mark_.push_back(0);
    }
    ++live_;
    return t;
  }
  void mark(int f, bool seen) { mark_[f] = 2 * stamp_ + (seen ? 1 : 0); }

  const double *xyz_;
  std::vector<int> start_of_; // per point: the cone triangle whose horizon edge leaves it
  std::vector<int> mark_;     // 2 stamp + 1 if q sees the facet, 2 stamp if not
  std::vector<int> stack_, free_;
  std::vector<Edge> horizon_;
  int stamp_ = 0;
  long live_ = 0;
  uint32_t rng_ = 2463534242u;
};

// ------------------------------------------------------------------ first tetrahedron

// Four points not on one plane, spread out (each the farthest, in doubles, from what
// the previous ones span) so that the walk's centre sits well inside; false if all
// points are on one plane.
bool first_tetrahedron(const double *P, int n, int t[4]) {
  auto at = [&](int i) { return P + 3 * i; };
  auto sub = [](const double *a, const double *b, double *d) {
    for (int k = 0; k < 3; ++k)
      d[k] = a[k] - b[k];
  };
  auto cross = [](const double *a, const double *b, double *c) {
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
  };
  int a = 0;
  for (int i = 1; i < n; ++i)
    if (at(i)[0] < at(a)[0])
      a = i;
  int b = a == 0 ? 1 : 0, c = -1, d = -1;
  double best = -1.0;
  for (int i = 0; i < n; ++i) {
    double e[3];
    sub(at(i), at(a), e);
    const double l = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    if (i != a && l > best)
      best = l, b = i;
  }
  double ab[3], nrm[3];
  sub(at(b), at(a), ab);
  best = -1.0;
  for (int i = 0; i < n; ++i) {
    double e[3], x[3];
    sub(at(i), at(a), e);
    cross(ab, e, x);
    const double l = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    if (i != a && i != b && l > best)
      best = l, c = i;
  }
  {
    double ac[3];
    sub(at(c), at(a), ac);
    cross(ab, ac, nrm);
  }
  best = -1.0;
  for (int i = 0; i < n; ++i) {
    double e[3];
    sub(at(i), at(a), e);
    const double h = std::fabs(nrm[0] * e[0] + nrm[1] * e[1] + nrm[2] * e[2]);
    if (i != a && i != b && i != c && h > best)
      best = h, d = i;
  }
  if (!collinear(at(a), at(b), at(c)) && orient3(at(a), at(b), at(c), at(d)) != 0) {
    t[0] = a, t[1] = b, t[2] = c, t[3] = d;
    return true;
  }
  // Flat to round-off: the exact search (points 0 and 1 differ, the caller checked).
  int i2 = -1, i3 = -1;
  for (int i = 2; i < n && i2 < 0; ++i)
    if (!collinear(at(0), at(1), at(i)))
      i2 = i;
  if (i2 < 0)
    return false;
  for (int i = 2; i < n && i3 < 0; ++i)
    if (i != i2 && orient3(at(0), at(1), at(i2), at(i)) != 0)
      i3 = i;
  if (i3 < 0)
    return false;
  t[0] = 0, t[1] = 1, t[2] = i2, t[3] = i3;
  return true;
}

void collect(const Hull &h, HullResult &r) {
  std::vector<int> index(h.facets(), -1);
  int m = 0;
  for (int f = 0; f < h.facets(); ++f)
    if (h.alive[f])
      index[f] = m++;
  r.triangles.resize(m);
  r.neighbors.resize(m);
  for (int f = 0; f < h.facets(); ++f)
    if (h.alive[f]) {
      const int t = index[f];
      r.triangles[t] = {h.fv[3 * f], h.fv[3 * f + 1], h.fv[3 * f + 2]};
      r.neighbors[t] = {index[h.fn[3 * f]], index[h.fn[3 * f + 1]], index[h.fn[3 * f + 2]]};
    }
}

// The conflict route (sphere_hull.h), in a seeded random order.
HullResult conflict_hull(const double *P, int n, const int t[4]) {
  HullResult r;
  r.route = HullRoute::Conflict;
  Hull h(P, n);
  h.start(t[0], t[1], t[2], t[3]);
  std::vector<int> order;
  order.reserve(n);
  for (int i = 0; i < n; ++i)
    if (i != t[0] && i != t[1] && i != t[2] && i != t[3])
      order.push_back(i);
  uint64_t s = 0x9E3779B97F4A7C15ull;
  for (size_t k = order.size(); k > 1; --k) {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    std::swap(order[k - 1], order[s % k]);
  }
  // Each point's facet, and each facet's points as a list through next.
  std::vector<int> facet_of(n, -1), next(n, -1), head(4, -1);
  auto assign = [&](int x, const std::vector<int> &candidates) {
    for (const int f : candidates)
      if (h.sees(f, x)) {
        if (static_cast<int>(head.size()) <= f)
          head.resize(h.facets(), -1);
        facet_of[x] = f;
        next[x] = head[f];
        head[f] = x;
        return true;
      }
    return false;
  };
  const std::vector<int> first = {0, 1, 2, 3};
  for (const int x : order)
    if (!assign(x, first)) {
      r.status = HullResult::Hidden, r.i = x;
      return r;
    }
  std::vector<int> moved;
  for (const int q : order) {
    h.insert(q, facet_of[q]);
    moved.clear();
    for (const int f : h.removed) {
      for (int x = head[f]; x >= 0; x = next[x])
        if (x != q)
          moved.push_back(x);
      head[f] = -1;
    }
    if (static_cast<int>(head.size()) < h.facets())
      head.resize(h.facets(), -1);
    for (const int x : moved)
      if (!assign(x, h.created)) {
        r.status = HullResult::Hidden, r.i = x;
        return r;
      }
  }
  collect(h, r);
  return r;
}

} // namespace

HullResult sphere_hull(const double *P, int n, HullRoute route) {
  HullResult r;
  // The Hilbert order, and in it equal points (equal keys, then equal coordinates).
  std::vector<KeyIndex> order(n);
  for (int i = 0; i < n; ++i)
    order[i] = {sphere_key(P + 3 * i), i};
  radix_sort(order);
  for (int k = 0; k < n;) {
    int e = k + 1;
    while (e < n && order[e].key == order[k].key)
      ++e;
    if (e - k > 1) {
      std::vector<int> run;
      for (int m = k; m < e; ++m)
        run.push_back(order[m].index);
      auto less = [&](int a, int b) {
        return std::lexicographical_compare(P + 3 * a, P + 3 * a + 3, P + 3 * b, P + 3 * b + 3) ||
               (std::equal(P + 3 * a, P + 3 * a + 3, P + 3 * b) && a < b);
      };
      std::sort(run.begin(), run.end(), less);
      for (size_t m = 1; m < run.size(); ++m)
        if (std::equal(P + 3 * run[m - 1], P + 3 * run[m - 1] + 3, P + 3 * run[m])) {
          r.status = HullResult::Equal;
          r.i = std::min(run[m - 1], run[m]);
          r.j = std::max(run[m - 1], run[m]);
          return r;
        }
    }
    k = e;
  }

  int t[4];
  if (!first_tetrahedron(P, n, t)) {
    r.status = HullResult::Flat;
    return r;
  }
  if (route == HullRoute::Conflict)
    return conflict_hull(P, n, t);

  // The walk's centre, the tetrahedron's centroid, must be strictly inside it.
  double o[3];
  for (int k = 0; k < 3; ++k)
    o[k] = 0.25 * ((P[3 * t[0] + k] + P[3 * t[1] + k]) + (P[3 * t[2] + k] + P[3 * t[3] + k]));
  Hull h(P, n);
  h.start(t[0], t[1], t[2], t[3]);
  for (int f = 0; f < 4; ++f)
    if (orient3(h.p(h.fv[3 * f]), h.p(h.fv[3 * f + 1]), h.p(h.fv[3 * f + 2]), o) >= 0)
      return conflict_hull(P, n, t);

  int last = 0;
  for (const KeyIndex &e : order) {
    const int q = e.index;
    if (q == t[0] || q == t[1] || q == t[2] || q == t[3])
      continue;
    // The walk ends (a visibility walk over the radial projection of a convex
    // polyhedron); its bound only turns a failure into the slower route, never a hang.
    const int f = h.walk(last, q, o, 2 * h.live() + 100);
    if (f < 0)
      return conflict_hull(P, n, t);
    if (!h.sees(f, q)) {
      r.status = HullResult::Hidden, r.i = q;
      return r;
    }
    h.insert(q, f);
    last = h.created[0];
  }
  collect(h, r);
  return r;
}

} // namespace sphere_detail
} // namespace tessera
