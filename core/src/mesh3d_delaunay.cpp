// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The 3D Delaunay tetrahedralisation (mesh3d_delaunay.h): Bowyer-Watson
// insertion on flat arrays.
//
// Order (mesh3d_order.h).  The points are copied in a biased randomised
// insertion order (rounds of 1/2, 1/4, ... of the points chosen at random,
// each round along a Hilbert curve through the bounding box): consecutive
// points are close, so the walk to the next one is short and the arrays are
// used in order, while the rounds keep the triangulation well shaped as it
// grows.  Extra points (Mesh3's far points) go first: the convex hull is then
// theirs from the start.  The result does not depend on the order
// (mesh3d_delaunay.h).
//
// Structure.  Four corners and four neighbours per tetrahedron; the convex
// hull is closed by tetrahedra with a point at infinity (index m, the
// number of points), oriented as if that point lay beyond the hull triangle,
// so that every triangle has a tetrahedron on each side.
//
// Insertion of p.  A visibility walk from the last new tetrahedron (across a
// triangle that p lies strictly beyond, in a random order of the four) ends
// in the tetrahedron containing p, or at the hull in a tetrahedron with the
// point at infinity whose triangle p lies beyond.  The conflict region
// grows from there across triangles, a tetrahedron belonging to it when p
// fails its perturbed in-sphere test (a hull tetrahedron: when p lies beyond
// its hull triangle, or in its plane inside the perturbed circle).  Every
// triangle between the region and the rest is joined to p; the new
// tetrahedra's other neighbours are found by turning about the triangle's
// edges inside the region until its boundary.

#include "mesh3d_delaunay.h"

#include "mesh3d_detail.h"
#include "mesh3d_filters.h"
#include "mesh3d_order.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tessera {
namespace detail3 {

namespace {

// A point off the plane of the non-collinear a, b, c (by about their extent
// along the axis closest to its normal): orientations against it orient the
// plane, and the sphere through a, b, c and it cuts the plane in their
// circle.
void off_plane(const double *a, const double *b, const double *c, double *d, long &exact_calls) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                       u[0] * v[1] - u[1] * v[0]};
  int axis[3] = {0, 1, 2};
  std::sort(axis, axis + 3, [&](int x, int y) { return std::fabs(n[x]) > std::fabs(n[y]); });
  double len = 0.0;
  for (int k = 0; k < 3; ++k)
    len = std::max({len, std::fabs(u[k]), std::fabs(v[k])});
  // The first offset that leaves the plane for sure (exactly checked): a
  // larger one when a tiny offset is lost in a large coordinate.
  for (double scale = 1.0; scale < 1e300; scale *= 1e8)
    for (const int k : axis) {
      d[0] = a[0];
      d[1] = a[1];
      d[2] = a[2];
      d[k] += scale * len + (scale > 1.0 ? scale * std::fabs(a[k]) : 0.0);
      if (orient3d_filtered(a, b, c, d, exact_calls) != 0)
        return;
    }
}

// Whether p, coplanar with the hull triangle a b c, is in conflict with it:
// inside their circle, exact zeros broken by the perturbation (see the
// header).
bool coplanar_in_circle(const double *a, const double *b, const double *c, const double *p,
                        long &exact_calls) {
  double d[3];
  off_plane(a, b, c, d, exact_calls);
  const int local = orient3d_filtered(a, b, c, d, exact_calls);
  const int s = insphere_filtered(a, b, c, d, p, exact_calls) * local;
  if (s != 0)
    return s > 0;
  const double *q[4] = {a, b, c, p};
  int slot[4] = {0, 1, 2, 3};
  std::sort(slot, slot + 4, [&](int x, int y) { return less_xyz(q[x], q[y]); });
  for (int r = 3; r > 0; --r) {
    const int k = slot[r];
    if (k == 3)
      return false;
    const double *w[3] = {a, b, c};
    w[k] = p;
    const int o = orient3d_filtered(w[0], w[1], w[2], d, exact_calls);
    if (o != 0)
      return o * local > 0;
  }
  return local < 0;
}

// The two slots other than j and k (j != k).
constexpr int kOther[4][4][2] = {{{-1, -1}, {2, 3}, {1, 3}, {1, 2}},
                                 {{2, 3}, {-1, -1}, {0, 3}, {0, 2}},
                                 {{1, 3}, {0, 3}, {-1, -1}, {0, 1}},
                                 {{1, 2}, {0, 2}, {0, 1}, {-1, -1}}};

// Size at least n (the scratch arrays of an insertion never shrink).
template <class Vec>
inline void grow(Vec &v, size_t n) {
  if (v.size() < n)
    v.resize(n + n / 2);
}

class Builder {
public:
  Builder(const Points3 &pts, const double (*extra)[3], int n_extra) {
    const int n = pts.n;
    m_ = n + n_extra;
    inf_ = m_;
    std::vector<int> order;
    insertion_order(pts, order);
    orig_.resize(m_);
    xyz_.resize(3 * static_cast<size_t>(m_));
    vmark_.assign(m_ + 1, 0);
    int k = 0;
    for (int e = 0; e < n_extra; ++e) {
      orig_[k] = n + e;
      for (int d = 0; d < 3; ++d)
        xyz_[3 * k + d] = extra[e][d];
      ++k;
    }
    for (const int i : order) {
      orig_[k] = i;
      for (int d = 0; d < 3; ++d)
        xyz_[3 * k + d] = pts.p(i)[d];
      ++k;
    }
  }

  Delaunay3 run(Tetrahedra &out, double slack, bool sorted);

private:
  int m_ = 0, inf_ = 0;
  std::vector<double> xyz_; // the points in insertion order
  std::vector<int> orig_;   // insertion order -> caller's index
  // Per tetrahedron: 4 corners, then the neighbours across the triangle
  // opposite each (one cache line holds two tetrahedra).
  // Per tetrahedron, one cache line: 4 corners, the neighbours across the
  // triangle opposite each, and the circumsphere (centre relative to
  // corner 0, squared radius; NaN where the filter is not claimed: flat
  // tetrahedra and those with the point at infinity).
  struct alignas(64) Tet {
    int v[4];
    int n[4];
    double c[3];
    double r2;
  };
  std::vector<Tet> tet_;
  int n_tet_ = 0;
  void sphere(int t) {
    Tet &x = tet_[t];
    if (has_inf(x.v) || !circumsphere(pt(x.v[0]), pt(x.v[1]), pt(x.v[2]), pt(x.v[3]), x.c, x.r2))
      x.r2 = std::numeric_limits<double>::quiet_NaN();
  }
  std::vector<int> free_;
  uint32_t stamp_ = 0;
  long exact_ = 0;
  uint64_t rng_ = 0x3D3D3D3Dull;
  int last_ = 0;
  // Scratch of one insertion: the conflict region, its boundary triangles
  // (conflict tetrahedron, slot; outside neighbour, its slot), new ids.
  std::vector<int> conflict_;
  struct Facet {
    int t, k, u, j;
  };
  std::vector<Facet> boundary_;
  std::vector<int> new_id_;
  std::vector<int> new_tn_;  // per new tetrahedron: neighbours (boundary indices)
  std::vector<int> corners_; // per new tetrahedron: corners
  // Local numbers of the boundary's corners (stamp << 7 | number), the
  // edge table (zero between insertions), each (triangle, slot) code's cell
  // and the corners' local numbers, and the sorted edges of a large region.
  static constexpr int kLocal = 64;
  std::vector<uint32_t> vmark_;
  std::vector<uint32_t> edge_sum_ = std::vector<uint32_t>(kLocal * kLocal, 0);
  std::vector<int> edge_code_, local_;
  std::vector<std::array<int, 3>> edges_;

  const double *pt(int v) const { return &xyz_[3 * static_cast<size_t>(v)]; }
  int orient(int a, int b, int c, int d) {
    return orient_impl(pt(a), pt(b), pt(c), pt(d), exact_);
  }
  bool has_inf(const int *q) const {
    return std::max(std::max(q[0], q[1]), std::max(q[2], q[3])) == inf_;
  }
  int inf_slot(int t) const {
    const int *q = tet_[t].v;
    for (int s = 0; s < 4; ++s)
      if (q[s] == inf_)
        return s;
    return -1;
  }
  bool in_conflict(int t, int p);
  int new_tet();
  bool init(int &first);
  int locate(int p, int &dup);
  void insert(int p, int start);
  void export_to(Tetrahedra &out, double slack, bool sorted);
};

bool Builder::in_conflict(int t, int p) {
  const Tet &x = tet_[t];
  const int *q = x.v;
  if (!has_inf(q)) {
    // The kept circumsphere decides unless p is within 1e-8 of it
    // (relative; the centre's error is far below, see circumsphere()).
    const double *e = pt(p), *p0 = pt(q[0]);
    const double w[3] = {e[0] - p0[0] - x.c[0], e[1] - p0[1] - x.c[1], e[2] - p0[2] - x.c[2]};
    const double d2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    const double margin = 1e-8 * (x.r2 + d2);
    if (d2 - x.r2 > margin)
      return false;
    if (x.r2 - d2 > margin)
      return true;
    const double *c[4] = {p0, pt(q[1]), pt(q[2]), pt(q[3])};
    return insphere_perturbed_impl(c, pt(p), exact_) > 0;
  }
  const int s = inf_slot(t);
  int r[4] = {q[0], q[1], q[2], q[3]};
  r[s] = p;
  const int o = orient(r[0], r[1], r[2], r[3]);
  if (o != 0)
    return o > 0;
  const int a = q[(s + 1) & 3], b = q[(s + 2) & 3], c = q[(s + 3) & 3];
  return coplanar_in_circle(pt(a), pt(b), pt(c), pt(p), exact_);
}

int Builder::new_tet() {
  if (!free_.empty()) {
    const int t = free_.back();
    free_.pop_back();
    return t;
  }
  // tet_ is kept at its capacity; n_tet_ of its records are in use.
  if (static_cast<size_t>(n_tet_) == tet_.size())
    tet_.resize(2 * tet_.size());
  return n_tet_++;
}

// The first tetrahedron: four non-coplanar points (the first in insertion
// order that are), and the four hull tetrahedra around it.  first: the
// position of its last corner in insertion order.
bool Builder::init(int &first) {
  if (m_ < 4)
    return false;
  int i0 = 0, i1 = -1, i2 = -1, i3 = -1;
  for (int i = 1; i < m_ && i1 < 0; ++i) {
    const double *p = pt(i0), *q = pt(i);
    if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2])
      i1 = i;
  }
  for (int i = i1 + 1; i1 > 0 && i < m_ && i2 < 0; ++i)
    if (!collinear3(pt(i0), pt(i1), pt(i)))
      i2 = i;
  for (int i = i2 + 1; i2 > 0 && i < m_ && i3 < 0; ++i)
    if (orient(i0, i1, i2, i) != 0)
      i3 = i;
  if (i3 < 0)
    return false;
  first = i3;
  int q[4] = {i0, i1, i2, i3};
  if (orient(q[0], q[1], q[2], q[3]) < 0)
    std::swap(q[2], q[3]);
  // Tetrahedron 0 and, for each slot k, hull tetrahedron k + 1: slot k
  // replaced by the point at infinity and two other corners swapped (a
  // point beyond the triangle is then on the positive side).
  // Room for about 6.5 tetrahedra per point.
  tet_.resize(7 * static_cast<size_t>(m_) + 64);
  for (int t = 0; t < 5; ++t)
    for (int s = 0; s < 4; ++s)
      tet_[t].v[s] = tet_[t].n[s] = -1;
  n_tet_ = 5;
  for (int s = 0; s < 4; ++s)
    tet_[0].v[s] = q[s];
  for (int k = 0; k < 4; ++k) {
    int *h = tet_[k + 1].v;
    for (int s = 0; s < 4; ++s)
      h[s] = q[s];
    h[k] = inf_;
    std::swap(h[(k + 1) & 3], h[(k + 2) & 3]);
  }
  // Neighbours: the two tetrahedra sharing the three corners other than
  // slot s's.
  for (int t = 0; t < 5; ++t)
    for (int s = 0; s < 4; ++s) {
      for (int u = 0; u < 5 && tet_[t].n[s] < 0; ++u) {
        if (u == t)
          continue;
        int shared = 0;
        for (int a = 0; a < 4; ++a) {
          if (a == s)
            continue;
          for (int b = 0; b < 4; ++b)
            shared += tet_[t].v[a] == tet_[u].v[b];
        }
        if (shared == 3)
          tet_[t].n[s] = u;
      }
    }
  for (int t = 0; t < 5; ++t)
    sphere(t);
  last_ = 0;
  return true;
}

// A tetrahedron in conflict with p: the one containing it, or a hull
// tetrahedron whose triangle p lies beyond.  dup: a point equal to p, or -1.
int Builder::locate(int p, int &dup) {
  dup = -1;
  int t = last_;
  if (t < 0 || tet_[t].v[0] < 0)
    t = 0;
  while (tet_[t].v[0] < 0)
    ++t;
  {
    const int s = inf_slot(t);
    if (s >= 0)
      t = tet_[t].n[s];
  }
  int prev = -1;
  for (;;) {
    const int *q = tet_[t].v;
    const int start = static_cast<int>(splitmix64(rng_) & 3);
    int next = -1;
    for (int i = 0; i < 4; ++i) {
      const int k = (start + i) & 3;
      const int u = tet_[t].n[k];
      if (u == prev)
        continue;
      int r[4] = {q[0], q[1], q[2], q[3]};
      r[k] = p;
      if (orient(r[0], r[1], r[2], r[3]) < 0) {
        next = u;
        break;
      }
    }
    if (next < 0) {
      // p lies in t (closed), or beyond the triangle shared with prev
      // (checked when t was left: impossible).  A corner equal to p?
      for (int s = 0; s < 4; ++s) {
        const double *a = pt(q[s]), *b = pt(p);
        if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2])
          dup = q[s];
      }
      return t;
    }
    prev = t;
    t = next;
    if (inf_slot(t) >= 0)
      return t;
  }
}

void Builder::insert(int p, int start) {
  // Marks live in the tetrahedra themselves (one cache line with the
  // corners the test reads): corner 3 complemented for the conflict region,
  // corner 2 for a tetrahedron found outside it (restored below).
  auto in_region = [&](int t) { return tet_[t].v[3] < 0; };
  auto outside = [&](int t) { return tet_[t].v[2] < 0; };
  auto flip = [&](int t, int s) {
    int &v = tet_[t].v[s];
    v = ~v;
  };
  conflict_.clear();
  boundary_.clear();
  conflict_.push_back(start);
  flip(start, 3);
  for (size_t h = 0; h < conflict_.size(); ++h) {
    const int t = conflict_[h];
    const int *tn = tet_[t].n;
    for (int k = 0; k < 4; ++k)
      __builtin_prefetch(tet_[tn[k]].v);
    for (int k = 0; k < 4; ++k) {
      const int u = tet_[t].n[k];
      if (in_region(u))
        continue;
      if (!outside(u)) {
        if (in_conflict(u, p)) {
          flip(u, 3);
          conflict_.push_back(u);
          continue;
        }
        flip(u, 2);
      }
      const int *un = tet_[u].n;
      boundary_.push_back({t, k, u, un[0] == t ? 0 : un[1] == t ? 1 : un[2] == t ? 2 : 3});
    }
  }
  const int nb = static_cast<int>(boundary_.size());
  const int nc = static_cast<int>(conflict_.size());
  // The region's corners as they were.
  for (const int t : conflict_)
    flip(t, 3);
  // Each boundary triangle becomes a tetrahedron with p: its corners, and
  // the outside neighbour's slot towards the region.
  grow(corners_, 4 * static_cast<size_t>(nb));
  for (int b = 0; b < nb; ++b) {
    const Facet &f = boundary_[b];
    const int *q = tet_[f.t].v;
    for (int s = 0; s < 4; ++s)
      corners_[4 * b + s] = q[s];
    corners_[4 * b + f.k] = p;
  }
  for (int b = 0; b < nb; ++b) {
    const int u = boundary_[b].u;
    if (outside(u))
      flip(u, 2);
  }
  // Neighbours of the new tetrahedra: slot k (p's) the outside one; slot
  // j != k (opposite corner v of the triangle, edge {e0, e1} the other two)
  // the new tetrahedron on the other boundary triangle with the edge
  // {e0, e1}: exactly one, the boundary being a closed surface.  The
  // boundary's corners get local numbers, an edge a cell of a small table
  // that sums the two (triangle, slot) codes meeting there; each code's
  // partner is the sum less itself (no branch on whether an edge was met).
  grow(new_tn_, 4 * static_cast<size_t>(nb));
  if (++stamp_ >= (1u << 25)) {
    std::fill(vmark_.begin(), vmark_.end(), 0u);
    stamp_ = 1;
  }
  const uint32_t st = stamp_ << 7;
  int n_local = 0;
  grow(edge_code_, 4 * static_cast<size_t>(nb));
  grow(local_, 4 * static_cast<size_t>(nb));
  for (int b = 0; b < nb && n_local <= kLocal; ++b) {
    const int k = boundary_[b].k;
    for (int s = 0; s < 4; ++s) {
      if (s == k)
        continue;
      uint32_t &mk = vmark_[corners_[4 * b + s]];
      if ((mk & ~127u) != st)
        mk = st | static_cast<uint32_t>(n_local++ & 127);
      local_[4 * b + s] = static_cast<int>(mk & 127);
    }
  }
  if (n_local <= kLocal) {
    for (int b = 0; b < nb; ++b) {
      const int k = boundary_[b].k;
      const int *q = &local_[4 * b];
      for (int j = 0; j < 4; ++j) {
        if (j == k)
          continue;
        const int l0 = q[kOther[j][k][0]], l1 = q[kOther[j][k][1]];
        const int cell = std::min(l0, l1) * kLocal + std::max(l0, l1);
        edge_code_[4 * b + j] = cell;
        edge_sum_[cell] += static_cast<uint32_t>(4 * b + j + 1);
      }
    }
    for (int b = 0; b < nb; ++b) {
      const int k = boundary_[b].k;
      for (int j = 0; j < 4; ++j) {
        if (j == k)
          continue;
        const int code = 4 * b + j;
        new_tn_[code] = static_cast<int>(edge_sum_[edge_code_[code]] - (code + 1) - 1) >> 2;
      }
    }
    for (int b = 0; b < nb; ++b) {
      const int k = boundary_[b].k;
      for (int j = 0; j < 4; ++j)
        if (j != k)
          edge_sum_[edge_code_[4 * b + j]] = 0;
    }
  } else {
    // A large region (a hull point, or a far one): the edges sorted.
    edges_.clear();
    for (int b = 0; b < nb; ++b) {
      const int k = boundary_[b].k;
      const int *q = &corners_[4 * b];
      for (int j = 0; j < 4; ++j) {
        if (j == k)
          continue;
        const int e0 = q[kOther[j][k][0]], e1 = q[kOther[j][k][1]];
        edges_.push_back({std::min(e0, e1), std::max(e0, e1), 4 * b + j});
      }
    }
    std::sort(edges_.begin(), edges_.end());
    for (size_t e = 0; e + 1 < edges_.size(); e += 2) {
      new_tn_[edges_[e][2]] = edges_[e + 1][2] >> 2;
      new_tn_[edges_[e + 1][2]] = edges_[e][2] >> 2;
    }
  }
  // Ids: the region's tetrahedra first, then free slots or new ones.
  grow(new_id_, static_cast<size_t>(nb));
  for (int b = 0; b < nb; ++b)
    new_id_[b] = b < nc ? conflict_[b] : new_tet();
  for (int c = nb; c < nc; ++c) {
    tet_[conflict_[c]].v[0] = -1;
    free_.push_back(conflict_[c]);
  }
  for (int b = 0; b < nb; ++b) {
    const Facet &f = boundary_[b];
    const int t = new_id_[b];
    Tet &r = tet_[t];
    for (int s = 0; s < 4; ++s) {
      r.v[s] = corners_[4 * b + s];
      if (s != f.k)
        r.n[s] = new_id_[new_tn_[4 * b + s]];
    }
    r.n[f.k] = f.u;
    tet_[f.u].n[f.j] = t;
    sphere(t);
  }
  last_ = new_id_[0];
  for (int b = 0; b < nb; ++b)
    if (inf_slot(new_id_[b]) < 0) {
      last_ = new_id_[b];
      break;
    }
}

Delaunay3 Builder::run(Tetrahedra &out, double slack, bool sorted) {
  int first = 0;
  if (!init(first))
    return Delaunay3::kFlat;
  // The points before `first` that are not corners of tetrahedron 0 come
  // next, then the rest.
  const int *q0 = tet_[0].v;
  auto corner = [&](int v) { return v == q0[0] || v == q0[1] || v == q0[2] || v == q0[3]; };
  std::vector<int> late;
  for (int v = 0; v < first; ++v)
    if (!corner(v))
      late.push_back(v);
  auto add = [&](int p) {
    int dup;
    const int t = locate(p, dup);
    if (dup >= 0) {
      out.duplicate[0] = orig_[dup];
      out.duplicate[1] = orig_[p];
      return false;
    }
    insert(p, t);
    return true;
  };
  for (const int p : late)
    if (!add(p))
      return Delaunay3::kDuplicate;
  for (int p = first + 1; p < m_; ++p)
    if (!add(p))
      return Delaunay3::kDuplicate;
  export_to(out, slack, sorted);
  return Delaunay3::kOk;
}

// The finite tetrahedra in the caller's numbering, sorted (see the header).
// Read in memory order; written where their number puts them.
void Builder::export_to(Tetrahedra &out, double slack, bool sorted) {
  const int n_all = n_tet_;
  // Even permutations of the slots: the smallest corner first (pairs of
  // swaps), then the smallest of the other three (a rotation of three).
  static constexpr int kEven[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
  auto canonical = [&](const int *q, int *slot) {
    int v[4] = {orig_[q[0]], orig_[q[1]], orig_[q[2]], orig_[q[3]]};
    int s = 0;
    for (int r = 1; r < 4; ++r)
      if (v[r] < v[s])
        s = r;
    const int *e = kEven[s];
    int r = 1;
    if (v[e[2]] < v[e[r]])
      r = 2;
    if (v[e[3]] < v[e[r]])
      r = 3;
    slot[0] = e[0];
    slot[1] = e[r];
    slot[2] = e[r == 3 ? 1 : r + 1];
    slot[3] = e[r == 1 ? 3 : r - 1];
  };
  auto finite = [&](int t) {
    const int *q = tet_[t].v;
    return q[0] >= 0 && q[0] != inf_ && q[1] != inf_ && q[2] != inf_ && q[3] != inf_;
  };
  // Counting sort by the smallest corner (or memory order).
  std::vector<int> id(n_all, -1);
  if (!sorted) {
    int k = 0;
    for (int t = 0; t < n_all; ++t)
      if (finite(t))
        id[t] = k++;
    out.n_tets = k;
  } else {
    std::vector<int> start(m_ + 1, 0);
    for (int t = 0; t < n_all; ++t) {
      if (!finite(t))
        continue;
      const int *q = tet_[t].v;
      ++start[std::min({orig_[q[0]], orig_[q[1]], orig_[q[2]], orig_[q[3]]}) + 1];
    }
    for (int i = 0; i < m_; ++i)
      start[i + 1] += start[i];
    for (int t = 0; t < n_all; ++t) {
      if (!finite(t))
        continue;
      const int *q = tet_[t].v;
      id[t] = start[std::min({orig_[q[0]], orig_[q[1]], orig_[q[2]], orig_[q[3]]})]++;
    }
    out.n_tets = 0;
    for (int t = 0; t < n_all; ++t)
      out.n_tets += id[t] >= 0;
  }
  const int nt = out.n_tets;
  const size_t cap = 4 * static_cast<size_t>(nt);
  const size_t room = cap + static_cast<size_t>(slack * cap) + 256;
  out.tv.clear();
  out.tn.clear();
  out.tv.reserve(room);
  out.tn.reserve(room);
  out.tv.resize(cap);
  out.tn.resize(cap);
  // Corners in canonical order; tn holds the internal number for now.
  for (int t = 0; t < n_all; ++t) {
    if (id[t] < 0)
      continue;
    const int *q = tet_[t].v;
    int slot[4];
    canonical(q, slot);
    int *c = &out.tv[4 * static_cast<size_t>(id[t])];
    for (int s = 0; s < 4; ++s)
      c[s] = orig_[q[slot[s]]];
    out.tn[4 * static_cast<size_t>(id[t])] = t;
  }
  // Within one smallest corner (a few tetrahedra), by the other corners.
  if (sorted) {
    std::vector<std::array<int, 5>> group;
    for (int lo = 0; lo < nt;) {
      int hi = lo + 1;
      while (hi < nt && out.tv[4 * static_cast<size_t>(hi)] == out.tv[4 * static_cast<size_t>(lo)])
        ++hi;
      if (hi - lo > 1) {
        group.clear();
        for (int k = lo; k < hi; ++k) {
          const int *c = &out.tv[4 * static_cast<size_t>(k)];
          group.push_back({c[0], c[1], c[2], c[3], out.tn[4 * static_cast<size_t>(k)]});
        }
        std::sort(group.begin(), group.end());
        for (int k = lo; k < hi; ++k) {
          const auto &g = group[k - lo];
          for (int s = 0; s < 4; ++s)
            out.tv[4 * static_cast<size_t>(k) + s] = g[s];
          id[g[4]] = k;
        }
      }
      lo = hi;
    }
  }
  // Neighbours.
  for (int t = 0; t < n_all; ++t) {
    const int k = id[t];
    if (k < 0)
      continue;
    const int *q = tet_[t].v;
    int slot[4];
    canonical(q, slot);
    for (int s = 0; s < 4; ++s)
      out.tn[4 * static_cast<size_t>(k) + s] = id[tet_[t].n[slot[s]]];
  }
  out.vt.assign(m_, -1);
  for (int k = nt - 1; k >= 0; --k)
    for (int s = 0; s < 4; ++s)
      out.vt[out.tv[4 * static_cast<size_t>(k) + s]] = k;
  out.exact_calls = exact_;
}

} // namespace

Delaunay3 delaunay_3d(const Points3 &pts, const double (*extra)[3], int n_extra, Tetrahedra &out,
                      double slack, bool sorted) {
  out.duplicate[0] = out.duplicate[1] = -1;
  Delaunay3 status;
  {
    Builder b(pts, extra, n_extra);
    status = b.run(out, slack, sorted);
  }
  return status;
}

} // namespace detail3
} // namespace tessera
