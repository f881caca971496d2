// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh::build: a from-scratch Delaunay triangulation into the flat arrays,
// with the input checks (doc/model.md, "Limits of the input").
//
// The triangulator inserts the points one at a time into a triangulation
// closed by the point at infinity (every hull edge has a triangle with it
// on the outside, so that the outside of the hull is triangles too):
//   * order: a biased randomized insertion order (Amenta, Choi and Rote
//     2003): the points shuffled, then in rounds of growing size (each
//     round the last 7/8 of what is left), each round sorted along a
//     Hilbert curve, so that each point is inserted near the previous one
//     while the triangulation already spans the whole set at a coarser
//     scale.  The coordinates are copied in that order, so that the
//     insertion reads memory nearly sequentially.
//   * location: a visibility walk from the last point's triangle, crossing
//     an edge that has the point strictly on its far side (the first edge
//     tried varies, which makes the walk terminate in any triangulation);
//     crossing a hull edge means the point is outside the hull.
//   * insertion: the triangle that holds the point (an infinite one when
//     it is outside the hull) is split in three, or the two triangles on an
//     edge that holds it in four, and Lawson flips of the edges opposite
//     the new point restore the Delaunay property: an edge between two
//     finite triangles is flipped when the far corner is inside the circle
//     (ties broken by the symbolic perturbation, below), an edge to the point
//     at infinity when the hull is not convex there.
// All tests are exact (filtered predicates, mesh_detail.h).
//
// Ties.  When four points are exactly co-circular, their in-circle test is
// decided as if every point's lifted coordinate x^2 + y^2 were raised by an
// infinitesimal that grows with the point's lexicographic order (x, then
// y), the larger point's raise infinitely larger than the smaller's: the
// in-circle determinant then takes the sign of the cofactor of the largest
// point whose cofactor (an orientation of the other three) is not zero.
// The perturbed points are in general position, so their Delaunay
// triangulation is unique: whatever the insertion order, and the same as
// CGAL's Delaunay_triangulation_2, which breaks ties by the same rule.  A
// multifold vertex (k co-circular points) thus becomes k - 2 triangles with
// one circumcentre, which the cells join by zero-length edges.

#include "mesh_detail.h"

#include <cstdint>
#include <numeric>

namespace tessera {

int detail::in_circle_tie(const double *a, const double *b, const double *c, const double *d) {
  const double *p[4] = {a, b, c, d};
  int order[4] = {0, 1, 2, 3};
  std::sort(order, order + 4, [&](int i, int j) {
    return p[i][0] > p[j][0] || (p[i][0] == p[j][0] && p[i][1] > p[j][1]);
  });
  // The cofactors of the lifted column of det[(x, y, x^2 + y^2, 1)] over
  // the rows a, b, c, d (which equals the in-circle determinant).
  for (const int i : order) {
    int s = 0;
    switch (i) {
    case 0:
      s = exact::orient2d(b, c, d);
      break;
    case 1:
      s = -exact::orient2d(a, c, d);
      break;
    case 2:
      s = exact::orient2d(a, b, d);
      break;
    default:
      s = -exact::orient2d(a, b, c);
      break;
    }
    if (s != 0)
      return s;
  }
  return 0;
}

namespace {

// Hilbert curve indices, four levels at a time.  The curve's orientation in
// a sub-square is one of four states (whether x and y are swapped, whether
// both are mirrored); one level reads a bit of x and of y in the current
// state's frame, appends the quadrant's place along the curve (0..3) and
// turns the frame for the quadrant.
struct HilbertTable {
  uint8_t digits[4][256]; // [state][x nibble << 4 | y nibble]: 4 levels' places
  uint8_t next[4][256];
  HilbertTable() {
    for (int state = 0; state < 4; ++state)
      for (int xy = 0; xy < 256; ++xy) {
        int swap = state & 1, mirror = state >> 1, d = 0;
        for (int level = 3; level >= 0; --level) {
          const int bx = (xy >> (4 + level)) & 1, by = (xy >> level) & 1;
          const int rx = (swap ? by : bx) ^ mirror, ry = (swap ? bx : by) ^ mirror;
          d = (d << 2) | ((3 * rx) ^ ry);
          if (ry == 0) {
            swap ^= 1;
            mirror ^= rx;
          }
        }
        digits[state][xy] = static_cast<uint8_t>(d);
        next[state][xy] = static_cast<uint8_t>(swap | (mirror << 1));
      }
  }
};

// The index along a Hilbert curve of order 16 of the cell (x, y), x and y
// in [0, 65536).
inline uint32_t hilbert_index(const HilbertTable &h, uint32_t x, uint32_t y) {
  uint32_t key = 0;
  int state = 0;
  for (int shift = 12; shift >= 0; shift -= 4) {
    const int xy = static_cast<int>((((x >> shift) & 15) << 4) | ((y >> shift) & 15));
    key = (key << 8) | h.digits[state][xy];
    state = h.next[state][xy];
  }
  return key;
}

// A small, fast generator for the shuffle and the walk (xorshift64).
struct XorShift {
  uint64_t s;
  uint64_t operator()() {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return s;
  }
};

// The Delaunay triangulation of points 0..n-1 (see the top of the file).
class Triangulator {
public:
  enum class Status { kOk, kCollinear, kDuplicate };

  Triangulator(const Points &pts, int n, bool filter) : pts_(pts), n_(n), filter_(filter) {}

  // On kOk, v and nb hold the triangles (3 per triangle, point indices of
  // pts, -1 for the point at infinity; nb[3 t + k] the triangle across the
  // edge opposite corner k), each with its smallest index first.  On
  // kDuplicate, duplicate[0] is in the triangulation and duplicate[1] is
  // at the same position.
  Status run();

  std::vector<int> v, nb;
  int duplicate[2] = {-1, -1};

private:
  const Points pts_;
  const int n_;
  const bool filter_;      // whether the in-circle filter may be used
  std::vector<int> order_; // insertion position -> point index
  std::vector<double> xy_; // coordinates in insertion order
  int nt_ = 0;             // triangles in use
  int last_ = 0;           // a triangle of the last point inserted
  std::vector<int> stack_;
  XorShift rng_{0x9E3779B97F4A7C15ull};

  const double *at(int p) const { return &xy_[2 * static_cast<size_t>(p)]; }
  int orient(int a, int b, int c) const {
    return orientation(at(a)[0], at(a)[1], at(b)[0], at(b)[1], at(c)[0], at(c)[1]);
  }
  bool infinite(int t) const { return v[3 * t] < 0 || v[3 * t + 1] < 0 || v[3 * t + 2] < 0; }
  void sort_points();
  bool first_triangle(int &a, int &b, int &c);
  Status collinear_or_duplicate();
  bool insert(int p);
  bool flip_needed(int p, int q, int r, int s) const;
  void flip(int t, int k, int u, int j);
  void legalize(int p);
  void set(int t, int a, int b, int c, int na, int nb_, int nc) {
    int *tv = &v[3 * t], *tn = &nb[3 * t];
    tv[0] = a, tv[1] = b, tv[2] = c;
    tn[0] = na, tn[1] = nb_, tn[2] = nc;
  }
  // In triangle t, the neighbour that was `from` becomes `to`.
  void relink(int t, int from, int to) {
    int *tn = &nb[3 * t];
    tn[(tn[1] == from) + 2 * (tn[2] == from)] = to;
  }
};

void Triangulator::sort_points() {
  const int n = n_;
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0);
  for (int i = n - 1; i > 0; --i)
    std::swap(order_[i], order_[static_cast<int>(rng_() % static_cast<uint64_t>(i + 1))]);
  double lo[2] = {pts_.x(0), pts_.y(0)}, hi[2] = {lo[0], lo[1]};
  for (int i = 1; i < n; ++i) {
    lo[0] = std::min(lo[0], pts_.x(i)), hi[0] = std::max(hi[0], pts_.x(i));
    lo[1] = std::min(lo[1], pts_.y(i)), hi[1] = std::max(hi[1], pts_.y(i));
  }
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  const double unit = extent > 0.0 ? 65535.0 / extent : 0.0;
  static const HilbertTable table;
  std::vector<uint32_t> key(n);
  std::vector<std::pair<uint32_t, int>> items;
  std::vector<uint32_t> key2;
  std::vector<int> idx2;
  std::vector<int> count(65536 + 1);
  // Rounds: [0, b_1), [b_1, b_2), ..., each the last 7/8 of what precedes
  // it ends; each sorted by its Hilbert index.
  std::vector<int> bounds = {n};
  while (bounds.back() > 64)
    bounds.push_back(bounds.back() / 8);
  bounds.push_back(0);
  std::reverse(bounds.begin(), bounds.end());
  for (size_t r = 0; r + 1 < bounds.size(); ++r) {
    const int b0 = bounds[r], b1 = bounds[r + 1], m = b1 - b0;
    if (m <= 1)
      continue;
    for (int i = b0; i < b1; ++i) {
      const int p = order_[i];
      const auto gx = static_cast<uint32_t>((pts_.x(p) - lo[0]) * unit);
      const auto gy = static_cast<uint32_t>((pts_.y(p) - lo[1]) * unit);
      key[i] = hilbert_index(table, std::min(gx, 65535u), std::min(gy, 65535u));
    }
    if (m < 4096) {
      items.resize(m);
      for (int i = 0; i < m; ++i)
        items[i] = {key[b0 + i], order_[b0 + i]};
      std::sort(items.begin(), items.end());
      for (int i = 0; i < m; ++i)
        order_[b0 + i] = items[i].second;
      continue;
    }
    // Radix sort by the two 16-bit halves of the key.
    key2.resize(m);
    idx2.resize(m);
    uint32_t *ka = &key[b0], *kb = key2.data();
    int *ia = &order_[b0], *ib = idx2.data();
    for (int shift = 0; shift < 32; shift += 16) {
      std::fill(count.begin(), count.end(), 0);
      for (int i = 0; i < m; ++i)
        ++count[((ka[i] >> shift) & 0xFFFF) + 1];
      for (int d = 0; d < 65536; ++d)
        count[d + 1] += count[d];
      for (int i = 0; i < m; ++i) {
        const int at = count[(ka[i] >> shift) & 0xFFFF]++;
        kb[at] = ka[i];
        ib[at] = ia[i];
      }
      std::swap(ka, kb);
      std::swap(ia, ib);
    }
    // (two passes: the result is back in key[b0..] and order_[b0..])
  }
  xy_.resize(2 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    xy_[2 * i] = pts_.x(order_[i]);
    xy_[2 * i + 1] = pts_.y(order_[i]);
  }
}

// Three points of the insertion order that are not collinear (a, b, c
// counter-clockwise), the first such: false when there are none, or when
// the first two positions differ only by a duplicate (duplicate[] set).
bool Triangulator::first_triangle(int &a, int &b, int &c) {
  a = 0;
  b = 1;
  while (b < n_ && at(b)[0] == at(0)[0] && at(b)[1] == at(0)[1]) {
    duplicate[0] = order_[0];
    duplicate[1] = order_[b];
    return false;
  }
  for (c = 2; c < n_; ++c) {
    const int o = orient(a, b, c);
    if (o < 0)
      std::swap(a, b);
    if (o != 0)
      return true;
  }
  return false;
}

// All points on one line (or fewer than 3): a duplicate if there is one,
// else collinear.
Triangulator::Status Triangulator::collinear_or_duplicate() {
  if (duplicate[0] >= 0)
    return Status::kDuplicate;
  std::vector<int> s(n_);
  std::iota(s.begin(), s.end(), 0);
  std::sort(s.begin(), s.end(), [&](int i, int j) {
    return at(i)[0] < at(j)[0] || (at(i)[0] == at(j)[0] && at(i)[1] < at(j)[1]);
  });
  for (int i = 1; i < n_; ++i)
    if (at(s[i])[0] == at(s[i - 1])[0] && at(s[i])[1] == at(s[i - 1])[1]) {
      duplicate[0] = order_[std::min(s[i], s[i - 1])];
      duplicate[1] = order_[std::max(s[i], s[i - 1])];
      return Status::kDuplicate;
    }
  return Status::kCollinear;
}

// Mesh::flip_needed with the new point r: edge (p, q) between t = (r, p, q)
// and u = (s, q, p).
bool Triangulator::flip_needed(int p, int q, int r, int s) const {
  if (s < 0)
    return false; // a hull edge
  if (p < 0)      // hull chain s -> q -> r must turn clockwise
    return orient(s, q, r) > 0;
  if (q < 0) // hull chain r -> p -> s
    return orient(r, p, s) > 0;
  return in_circle(at(p)[0], at(p)[1], at(q)[0], at(q)[1], at(r)[0], at(r)[1], at(s)[0], at(s)[1],
                   filter_) > 0;
}

// As Mesh::flip: t = (r, p, q) (r = corner k) and u = (s, q, p) (s = corner
// j) become t = (r, p, s) and u = (s, q, r).
void Triangulator::flip(int t, int k, int u, int j) {
  const int k1 = k == 2 ? 0 : k + 1, k2 = k1 == 2 ? 0 : k1 + 1;
  const int j1 = j == 2 ? 0 : j + 1, j2 = j1 == 2 ? 0 : j1 + 1;
  const int r = v[3 * t + k], p = v[3 * t + k1], q = v[3 * t + k2], s = v[3 * u + j];
  const int A = nb[3 * t + k1], B = nb[3 * t + k2], C = nb[3 * u + j1], D = nb[3 * u + j2];
  set(t, r, p, s, C, u, B);
  set(u, s, q, r, A, t, D);
  relink(A, t, u);
  relink(C, u, t);
}

// Lawson flips of the edges opposite the new point p, from those stacked.
void Triangulator::legalize(int p) {
  while (!stack_.empty()) {
    const int t = stack_.back();
    stack_.pop_back();
    const int k = (v[3 * t + 1] == p) + 2 * (v[3 * t + 2] == p);
    const int u = nb[3 * t + k];
    const int j = (nb[3 * u + 1] == t) + 2 * (nb[3 * u + 2] == t);
    const int k1 = k == 2 ? 0 : k + 1, k2 = k1 == 2 ? 0 : k1 + 1;
    if (!flip_needed(v[3 * t + k1], v[3 * t + k2], p, v[3 * u + j]))
      continue;
    flip(t, k, u, j); // t = (p, ., s), u = (s, ., p): both edges opposite p
    stack_.push_back(t);
    stack_.push_back(u);
  }
}

// Inserts point p; false when it lies on a point already inserted
// (duplicate[] set).
bool Triangulator::insert(int p) {
  // Locate: a walk from the last triangle.
  int t = last_;
  if (infinite(t)) {
    const int *tv = &v[3 * t];
    t = nb[3 * t + (tv[1] < 0) + 2 * (tv[2] < 0)];
  }
  int from = -1, o[3] = {0, 0, 0};
  long steps = 0;
  const long max_steps = 4L * nt_ + 64;
  bool outside = false;
  for (;;) {
    const int *tv = &v[3 * t];
    const int first = static_cast<int>(rng_() % 3);
    int cross = -1;
    for (int i = 0; i < 3; ++i) {
      const int k = first + i < 3 ? first + i : first + i - 3;
      const int across = nb[3 * t + k];
      if (across == from) {
        o[k] = 1; // the edge just crossed: p is strictly on this side
        continue;
      }
      const int k1 = k == 2 ? 0 : k + 1, k2 = k1 == 2 ? 0 : k1 + 1;
      o[k] = orient(tv[k1], tv[k2], p);
      if (o[k] < 0) {
        cross = k;
        break;
      }
    }
    if (cross < 0)
      break;
    from = t;
    t = nb[3 * t + cross];
    if (infinite(t)) {
      outside = true;
      break;
    }
    if (++steps > max_steps) {
      // Cannot happen in a Delaunay triangulation with exact tests; a scan
      // of every finite triangle keeps the insertion right anyway.
      t = -1;
      for (int m = 0; m < nt_ && t < 0; ++m) {
        if (infinite(m))
          continue;
        const int *mv = &v[3 * m];
        int mo[3];
        for (int k = 0; k < 3; ++k)
          mo[k] = orient(mv[(k + 1) % 3], mv[(k + 2) % 3], p);
        if (mo[0] >= 0 && mo[1] >= 0 && mo[2] >= 0) {
          t = m;
          o[0] = mo[0], o[1] = mo[1], o[2] = mo[2];
        }
      }
      if (t < 0) { // outside the hull: an infinite triangle that sees it
        for (int m = 0; m < nt_ && t < 0; ++m) {
          const int *mv = &v[3 * m];
          const int i = (mv[1] < 0) + 2 * (mv[2] < 0);
          if (mv[i] >= 0)
            continue;
          if (orient(mv[i == 2 ? 0 : i + 1], mv[i == 0 ? 2 : i - 1], p) > 0)
            t = m;
        }
        outside = true;
      }
      break;
    }
  }

  const int *tv = &v[3 * t];
  int onedge = -1;
  if (!outside) {
    const int zeros = (o[0] == 0) + (o[1] == 0) + (o[2] == 0);
    if (zeros >= 2) { // on a corner: the one whose opposite edge is not zero
      const int c = o[0] != 0 ? 0 : (o[1] != 0 ? 1 : 2);
      duplicate[0] = order_[tv[c]];
      duplicate[1] = order_[p];
      return false;
    }
    if (zeros == 1)
      onedge = o[0] == 0 ? 0 : (o[1] == 0 ? 1 : 2);
  }
  if (onedge < 0) {
    // Split t = (a, b, c) in three: (p, b, c), (a, p, c), (a, b, p).
    const int a = tv[0], b = tv[1], c = tv[2];
    const int na = nb[3 * t], nbb = nb[3 * t + 1], nc = nb[3 * t + 2];
    const int t1 = nt_++, t2 = nt_++;
    set(t, p, b, c, na, t1, t2);
    set(t1, a, p, c, t, nbb, t2);
    set(t2, a, b, p, t, t1, nc);
    relink(nbb, t, t1);
    relink(nc, t, t2);
    stack_.push_back(t);
    stack_.push_back(t1);
    stack_.push_back(t2);
  } else {
    // p on the edge opposite corner k of t = (a, b, c), shared with
    // u = (d, c, b): (a, b, p), (a, p, c), (d, c, p), (d, p, b).
    const int k = onedge, k1 = k == 2 ? 0 : k + 1, k2 = k1 == 2 ? 0 : k1 + 1;
    const int a = tv[k], b = tv[k1], c = tv[k2];
    const int u = nb[3 * t + k];
    const int j = (nb[3 * u + 1] == t) + 2 * (nb[3 * u + 2] == t);
    const int j1 = j == 2 ? 0 : j + 1, j2 = j1 == 2 ? 0 : j1 + 1;
    const int d = v[3 * u + j];
    const int tb = nb[3 * t + k1], tc = nb[3 * t + k2]; // across (c, a), (a, b)
    const int uc = nb[3 * u + j1], ub = nb[3 * u + j2]; // across (b, d), (d, c)
    const int t1 = nt_++, u1 = nt_++;
    set(t, a, b, p, u1, t1, tc);
    set(t1, a, p, c, u, tb, t);
    set(u, d, c, p, t1, u1, ub);
    set(u1, d, p, b, t, uc, u);
    relink(tb, t, t1);
    relink(uc, u, u1);
    stack_.push_back(t);
    stack_.push_back(t1);
    stack_.push_back(u);
    stack_.push_back(u1);
  }
  legalize(p);
  last_ = t;
  return true;
}

Triangulator::Status Triangulator::run() {
  const int n = n_;
  v.clear();
  nb.clear();
  if (n < 3) {
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0);
    xy_.resize(2 * static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
      xy_[2 * i] = pts_.x(i), xy_[2 * i + 1] = pts_.y(i);
    return collinear_or_duplicate();
  }
  sort_points();
  int a, b, c;
  if (!first_triangle(a, b, c))
    return collinear_or_duplicate();
  // A closed triangulation of n points has 2 n - 2 triangles.
  v.resize(3 * (2 * static_cast<size_t>(n) - 2));
  nb.resize(v.size());
  // (a, b, c) and the infinite triangles across its edges.
  set(0, a, b, c, 1, 2, 3);
  set(1, c, b, -1, 3, 2, 0);
  set(2, a, c, -1, 1, 3, 0);
  set(3, b, a, -1, 2, 1, 0);
  nt_ = 4;
  last_ = 0;
  for (int p = 1; p < n; ++p) {
    if (p == b || p == c || p == a)
      continue;
    if (!insert(p))
      return Status::kDuplicate;
  }
  // Back to the caller's point indices, each triangle smallest index first.
  for (int t = 0; t < nt_; ++t) {
    int *tv = &v[3 * t], *tn = &nb[3 * t];
    for (int k = 0; k < 3; ++k)
      tv[k] = tv[k] < 0 ? -1 : order_[tv[k]];
    const int k = tv[1] < tv[0] ? (tv[2] < tv[1] ? 2 : 1) : (tv[2] < tv[0] ? 2 : 0);
    std::rotate(tv, tv + k, tv + 3);
    std::rotate(tn, tn + k, tn + 3);
  }
  return Status::kOk;
}

} // namespace

void Mesh::throw_too_close(const Points &pts, int i, int j, double scale, const long *ids,
                           const int *report) {
  auto rep = [&](int k) { return report ? report[k] : k; };
  auto name = [&](int k) {
    std::ostringstream s;
    s.precision(17);
    s << point_name(rep(k), ids) << " at (" << pts.x(rep(k)) << ", " << pts.y(rep(k)) << ")";
    if (rep(k) != k)
      s << " (its periodic image at (" << pts.x(k) << ", " << pts.y(k) << "))";
    return s.str();
  };
  const double d = std::hypot(pts.x(i) - pts.x(j), pts.y(i) - pts.y(j));
  std::ostringstream s;
  s << "tessera: two cell centres nearly coincide: " << name(std::min(i, j)) << " and "
    << name(std::max(i, j)) << " are " << d << " apart, ";
  if (kMinSeparation * scale >= kMinLength)
    s << "closer than " << kMinSeparation << " times the largest coordinate magnitude " << scale
      << " (limit " << kMinSeparation * scale
      << "): double precision cannot resolve the cell boundary between them; move or delete "
         "one of them";
  else
    s << "closer than " << kMinLength
      << ": lengths this small underflow in double precision; rescale the length unit";
  throw Error(s.str());
}

void Mesh::build(const Points &pts, const long *ids, const int *report) {
  valid_ = false;
  collinear_ = false;
  const int n = pts.n;
  auto rep = [&](int i) { return report ? report[i] : i; };
  double scale = 0.0; // largest coordinate magnitude, for the separation limit
  bool tiny = false;
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(pts.x(i)) || !std::isfinite(pts.y(i))) {
      std::ostringstream s;
      s << "tessera: " << point_name(rep(i), ids) << " has a non-finite coordinate (" << pts.x(i)
        << ", " << pts.y(i) << ")";
      throw Error(s.str());
    }
    const double ax = std::fabs(pts.x(i)), ay = std::fabs(pts.y(i));
    const double m = std::max(ax, ay);
    if (m > kMaxCoordinate) {
      std::ostringstream s;
      s.precision(17);
      s << "tessera: " << point_name(rep(i), ids) << " at (" << pts.x(i) << ", " << pts.y(i)
        << ") is beyond " << kMaxCoordinate
        << " in magnitude: the geometry's squares and cubes would overflow double precision; "
           "rescale the length unit (and the box) so that coordinates stay below "
        << kMaxCoordinate;
      throw Error(s.str());
    }
    scale = std::max(scale, m);
    tiny |= (ax < kTinyCoordinate && ax != 0.0) | (ay < kTinyCoordinate && ay != 0.0);
  }
  if (n < 3) {
    std::ostringstream s;
    s << "tessera: need at least 3 non-collinear points to tessellate, got " << n;
    throw Error(s.str());
  }
  // The old arrays go first, and the triangulator's arrays become the
  // mesh's: the peak memory of a rebuild is what limits memory per cell.
  std::vector<int>().swap(v_);
  std::vector<int>().swap(nb_);
  std::vector<int>().swap(vt_);
  std::vector<char>().swap(frozen_);
  std::vector<int>().swap(spare_cv_);
  std::vector<int>().swap(spare_cn_);
  stamp_ = 0;
  tiny_ = tiny;
  {
    Triangulator tri(pts, n, !tiny);
    const Triangulator::Status status = tri.run();
    if (status == Triangulator::Status::kDuplicate) {
      const int j = tri.duplicate[0], i = tri.duplicate[1];
      std::ostringstream s;
      s << "tessera: two cell centres at the same position (" << pts.x(i) << ", " << pts.y(i)
        << "): " << point_name(rep(std::min(i, j)), ids) << " and "
        << point_name(rep(std::max(i, j)), ids) << "; move or delete one of them";
      throw Error(s.str());
    }
    if (status == Triangulator::Status::kCollinear) {
      collinear_ = true;
      std::ostringstream s;
      s << "tessera: need at least 3 non-collinear points to tessellate; all " << n
        << " points are on one line";
      throw Error(s.str());
    }
    v_.swap(tri.v);
    nb_.swap(tri.nb);
  }
  const int nf = static_cast<int>(v_.size() / 3);
  // Nearly coincident centres (the closest pair of points is always a
  // Delaunay edge, so checking the edges finds it).  One pass over the
  // edges, each once (from its triangle of lower number), cheap next to the
  // triangulation itself.
  const double sep2 = min_separation2(scale);
  for (int t = 0; t < nf; ++t)
    for (int k = 0; k < 3; ++k) {
      if (nb_[3 * t + k] < t)
        continue;
      const int i = v_[3 * t + (k + 1) % 3], j = v_[3 * t + (k + 2) % 3];
      if (i < 0 || j < 0)
        continue;
      const double dx = pts.x(i) - pts.x(j), dy = pts.y(i) - pts.y(j);
      if (dx * dx + dy * dy < sep2)
        throw_too_close(pts, i, j, scale, ids, report);
    }
  vt_.assign(n, -1);
  for (int t = 0; t < nf; ++t)
    for (int k = 0; k < 3; ++k)
      if (v_[3 * t + k] >= 0)
        vt_[v_[3 * t + k]] = t;

  // Renumber the triangles in the order the points' stars visit them, so
  // that reading cells point by point walks memory nearly sequentially (the
  // points themselves are spatially sorted by LAMMPS); the finite triangles
  // first, then those with the point at infinity (see nft_).
  std::vector<int> order(nf, -1);
  auto finite = [&](int m) {
    return v_[3 * m] != kInfinite && v_[3 * m + 1] != kInfinite && v_[3 * m + 2] != kInfinite;
  };
  int next = 0;
  for (int p = 0; p < n; ++p) {
    const int start = vt_[p];
    int m = start;
    do {
      if (order[m] < 0 && finite(m))
        order[m] = next++;
      const int *v = &v_[3 * m];
      const int i = (v[1] == p) + 2 * (v[2] == p);
      m = nb_[3 * m + (i == 2 ? 0 : i + 1)];
    } while (m != start);
  }
  for (int m = 0; m < nf; ++m)
    if (order[m] < 0 && finite(m))
      order[m] = next++;
  nft_ = next;
  for (int m = 0; m < nf; ++m)
    if (order[m] < 0)
      order[m] = next++;
  {
    std::vector<int> tmp(v_.size());
    for (int m = 0; m < nf; ++m)
      for (int k = 0; k < 3; ++k)
        tmp[3 * order[m] + k] = v_[3 * m + k];
    v_.swap(tmp);
    for (int m = 0; m < nf; ++m)
      for (int k = 0; k < 3; ++k)
        tmp[3 * order[m] + k] = order[nb_[3 * m + k]];
    nb_.swap(tmp);
  }
  for (int &t : vt_)
    t = order[t];

  n_points_ = n;
  flips_ = 0;
  dirty_.assign(n, 0);
  dirty_list_.clear();
  flipped_.clear();
  valid_ = true;
}

bool detail::delaunay_triangles(const Points &pts, std::vector<int> &tri) {
  bool tiny = false;
  for (int i = 0; i < pts.n; ++i) {
    const double ax = std::fabs(pts.x(i)), ay = std::fabs(pts.y(i));
    tiny |= (ax < kTinyCoordinate && ax != 0.0) | (ay < kTinyCoordinate && ay != 0.0);
  }
  Triangulator t(pts, pts.n, !tiny);
  if (t.run() != Triangulator::Status::kOk)
    return false;
  tri.swap(t.v);
  return true;
}

double time_plain_delaunay(const Points &pts, int n, long *faces) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  long finite = 0;
  std::vector<int> tri;
  if (n >= 3 && detail::delaunay_triangles(Points{pts.data, n, pts.stride}, tri))
    for (size_t t = 0; t < tri.size(); t += 3)
      finite += tri[t] >= 0; // the smallest corner first: -1 if infinite
  const double seconds = std::chrono::duration<double>(clock::now() - t0).count();
  if (faces)
    *faces = finite;
  return seconds;
}

} // namespace tessera
