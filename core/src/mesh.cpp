// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Flat-array Delaunay triangulation: built by CGAL, kept Delaunay across
// steps by Lawson flips with filtered exact predicates, and read off into
// Voronoi cells.

#include "tessera/mesh.h"

#include "point_name.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace tessera {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using Fb = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
using CPoint = Kernel::Point_2;

// Voronoi edges shorter than this fraction of the adjacent circumradius are
// the zero-length edges of a multifold vertex whose circumcentres differ only
// by round-off; they get length exactly 0.
constexpr double kZeroEdge = 1e-10;

// Input limits (doc/model.md, "Limits of the input").  Two centres closer
// than kMinSeparation times the largest coordinate magnitude S are refused:
// a periodic image or ghost is a rounded translate, off by up to ulp(S), so
// the bisector of two points d apart is only known to an angle ~ eps S / d
// and the vertices on it to eps S / d of their distance; at the limit that
// is ~2e-6, and below it the cell boundary between them is round-off.
// Lengths are kept within [kMinLength, kMaxCoordinate] so that the cubes of
// lengths in the circumcentre formula neither overflow nor underflow
// (double's range is 2e-308 .. 2e308; (1e100)^3 keeps a factor 1e8 to spare).
constexpr double kMinSeparation = 1e-10;
constexpr double kMinLength = 1e-100;
constexpr double kMaxCoordinate = 1e100;

// The squared distance below which two points are refused, for points whose
// largest coordinate magnitude is S.
inline double min_separation2(double S) {
  const double d = std::max(kMinSeparation * S, kMinLength);
  return d * d;
}

// Orientation of (a, b, c): > 0 counter-clockwise.  Shewchuk's static error
// bound decides almost every case in double precision; the rest go to CGAL's
// exact predicate.
inline int orientation(double ax, double ay, double bx, double by, double cx, double cy) {
  const double l = (ax - cx) * (by - cy), r = (ay - cy) * (bx - cx);
  const double det = l - r;
  const double bound = 3.3306690738754716e-16 * (std::fabs(l) + std::fabs(r));
  if (det > bound)
    return 1;
  if (-det > bound)
    return -1;
  return static_cast<int>(CGAL::orientation(CPoint(ax, ay), CPoint(bx, by), CPoint(cx, cy)));
}

// > 0 when d is strictly inside the circle through the counter-clockwise a, b, c.
inline int in_circle(double ax, double ay, double bx, double by, double cx, double cy, double dx,
                     double dy) {
  const double adx = ax - dx, ady = ay - dy, bdx = bx - dx, bdy = by - dy, cdx = cx - dx,
               cdy = cy - dy;
  const double bc = bdx * cdy, cb = cdx * bdy, ca = cdx * ady, ac = adx * cdy, ab = adx * bdy,
               ba = bdx * ady;
  const double al = adx * adx + ady * ady, bl = bdx * bdx + bdy * bdy, cl = cdx * cdx + cdy * cdy;
  const double det = al * (bc - cb) + bl * (ca - ac) + cl * (ab - ba);
  const double perm = (std::fabs(bc) + std::fabs(cb)) * al + (std::fabs(ca) + std::fabs(ac)) * bl +
                      (std::fabs(ab) + std::fabs(ba)) * cl;
  const double bound = 1.1102230246251577e-15 * perm;
  if (det > bound)
    return 1;
  if (-det > bound)
    return -1;
  return static_cast<int>(CGAL::side_of_oriented_circle(CPoint(ax, ay), CPoint(bx, by),
                                                        CPoint(cx, cy), CPoint(dx, dy)));
}

// The correctly rounded square root (as std::sqrt) without the errno path:
// with CGAL's -frounding-math GCC turned std::sqrt in advance() into a call
// into libm, 5 % of a step.
#if defined(__SSE2__)
#define TESSERA_ALWAYS_INLINE inline __attribute__((always_inline))
TESSERA_ALWAYS_INLINE double root(double x) { return _mm_cvtsd_f64(_mm_sqrt_sd(_mm_set_sd(x), _mm_set_sd(x))); }
// q[0..n) := sqrt(q[0..n)); q has room for n rounded up to even.
TESSERA_ALWAYS_INLINE void roots(double *q, int n) {
  for (int k = 0; k < n; k += 2) _mm_storeu_pd(q + k, _mm_sqrt_pd(_mm_loadu_pd(q + k)));
}
#else
#define TESSERA_ALWAYS_INLINE inline
inline double root(double x) { return std::sqrt(x); }
inline void roots(double *q, int n) {
  for (int k = 0; k < n; ++k) q[k] = std::sqrt(q[k]);
}
#endif

TESSERA_ALWAYS_INLINE void circumcentre(double ax, double ay, double bx, double by, double cx,
                                        double cy, Vec2 &h, double &r) {
  const double bpx = bx - ax, bpy = by - ay, cpx = cx - ax, cpy = cy - ay;
  const double id = 0.5 / (bpx * cpy - bpy * cpx);
  const double b2 = bpx * bpx + bpy * bpy, c2 = cpx * cpx + cpy * cpy;
  const double ux = (cpy * b2 - bpy * c2) * id;
  const double uy = (bpx * c2 - cpx * b2) * id;
  h.x = ax + ux;
  h.y = ay + uy;
  r = root(ux * ux + uy * uy);
}

// Whether the triangle (a, b, c) lies entirely outside the region of
// interest [roi_lo, roi_hi] (false without one): a fold there is frozen.
inline bool outside_region(double ax, double ay, double bx, double by, double cx, double cy,
                           const double *roi_lo, const double *roi_hi) {
  return roi_lo && (std::max({ax, bx, cx}) < roi_lo[0] || std::min({ax, bx, cx}) > roi_hi[0] ||
                    std::max({ay, by, cy}) < roi_lo[1] || std::min({ay, by, cy}) > roi_hi[1]);
}

// Whether triangles a and b of t have one circumcentre (a multifold
// vertex): closer than kZeroEdge times the smaller circumradius.  The
// tolerance is a fraction of the smaller one: a nearly flat triangle (on the
// hull of a ghost shell, or a row of collinear images) has a huge or
// infinite radius, and with the larger one its tolerance would swallow its
// neighbours into one "vertex" with an infinite centre.  A vertex that is not
// finite is never the same as another (the comparisons are false for NaN).
inline bool same_centre(const Tessellation &t, int a, int b) {
  const double dx = t.vertices[a].x - t.vertices[b].x, dy = t.vertices[a].y - t.vertices[b].y;
  const double tol = kZeroEdge * std::min(t.radius[a], t.radius[b]);
  return dx * dx + dy * dy <= tol * tol;
}

} // namespace

void Mesh::throw_too_close(const Points &pts, int i, int j, double scale, const long *ids,
                           const int *report) {
  auto rep = [&](int k) { return report ? report[k] : k; };
  auto name = [&](int k) {
    std::ostringstream s;
    s.precision(17);
    s << point_name(rep(k), ids) << " at (" << pts.x(rep(k)) << ", " << pts.y(rep(k)) << ")";
    if (rep(k) != k) s << " (its periodic image at (" << pts.x(k) << ", " << pts.y(k) << "))";
    return s.str();
  };
  const double d = std::hypot(pts.x(i) - pts.x(j), pts.y(i) - pts.y(j));
  std::ostringstream s;
  s << "tessera: two cell centres nearly coincide: " << name(std::min(i, j)) << " and "
    << name(std::max(i, j)) << " are " << d << " apart, ";
  if (kMinSeparation * scale >= kMinLength)
    s << "closer than " << kMinSeparation << " times the largest coordinate magnitude "
      << scale << " (limit " << kMinSeparation * scale
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
  double scale = 0.0;  // largest coordinate magnitude, for the separation limit
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(pts.x(i)) || !std::isfinite(pts.y(i))) {
      std::ostringstream s;
      s << "tessera: " << point_name(rep(i), ids) << " has a non-finite coordinate (" << pts.x(i)
        << ", " << pts.y(i) << ")";
      throw Error(s.str());
    }
    const double m = std::max(std::fabs(pts.x(i)), std::fabs(pts.y(i)));
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
  }
  if (n < 3) {
    std::ostringstream s;
    s << "tessera: need at least 3 non-collinear points to tessellate, got " << n;
    throw Error(s.str());
  }
  // The old arrays go first and CGAL's triangulation lives only until it is
  // exported: the peak memory of a rebuild is what limits memory per cell.
  std::vector<int>().swap(v_);
  std::vector<int>().swap(nb_);
  std::vector<int>().swap(vt_);
  std::vector<char>().swap(frozen_);
  std::vector<int>().swap(spare_cv_);
  std::vector<int>().swap(spare_cn_);
  stamp_ = 0;
  int nf = 0;
  {
    Delaunay dt;
    {
      std::vector<std::pair<CPoint, int>> input;
      input.reserve(n);
      for (int i = 0; i < n; ++i)
        input.emplace_back(CPoint(pts.x(i), pts.y(i)), i);
      dt.insert(input.begin(), input.end());
    }

    if (static_cast<int>(dt.number_of_vertices()) != n) {
      std::vector<char> seen(n, 0);
      for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
        seen[v->info()] = 1;
      for (int i = 0; i < n; ++i) {
        if (seen[i])
          continue;
        const int j = dt.nearest_vertex(CPoint(pts.x(i), pts.y(i)))->info();
        std::ostringstream s;
        s << "tessera: two cell centres at the same position (" << pts.x(i) << ", " << pts.y(i)
          << "): " << point_name(rep(j), ids) << " and " << point_name(rep(i), ids)
          << "; move or delete one of them";
        throw Error(s.str());
      }
    }
    if (dt.dimension() < 2) {
      collinear_ = true;
      std::ostringstream s;
      s << "tessera: need at least 3 non-collinear points to tessellate; all " << n
        << " points are on one line";
      throw Error(s.str());
    }
    // Nearly coincident centres (the closest pair of points is always a
    // Delaunay edge, so checking the edges finds it).  One pass over the
    // edges, cheap next to the triangulation itself.
    const double sep2 = min_separation2(scale);
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
      const int i = e->first->vertex(Delaunay::cw(e->second))->info();
      const int j = e->first->vertex(Delaunay::ccw(e->second))->info();
      const double dx = pts.x(i) - pts.x(j), dy = pts.y(i) - pts.y(j);
      if (dx * dx + dy * dy < sep2) throw_too_close(pts, i, j, scale, ids, report);
    }

    // Export, with the infinite vertex as -1 (faces in CGAL's order; they
    // are renumbered below).
    for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f)
      f->info() = nf++;
    v_.assign(3 * static_cast<size_t>(nf), kInfinite);
    nb_.assign(3 * static_cast<size_t>(nf), -1);
    vt_.assign(n, -1);
    const auto inf = dt.infinite_vertex();
    for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f) {
      const int id = f->info();
      for (int k = 0; k < 3; ++k) {
        const auto vk = f->vertex(k);
        v_[3 * id + k] = vk == inf ? kInfinite : vk->info();
        nb_[3 * id + k] = f->neighbor(k)->info();
        if (vk != inf)
          vt_[vk->info()] = id;
      }
    }
  } // CGAL's triangulation is freed here

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

bool Mesh::flip_needed(const Points &pts, int p, int q, int r, int s) const {
  if (r == kInfinite || s == kInfinite)
    return false;     // a hull edge
  if (p == kInfinite) // hull chain s -> q -> r must turn clockwise
    return orientation(pts.x(s), pts.y(s), pts.x(q), pts.y(q), pts.x(r), pts.y(r)) > 0;
  if (q == kInfinite) // hull chain r -> p -> s
    return orientation(pts.x(r), pts.y(r), pts.x(p), pts.y(p), pts.x(s), pts.y(s)) > 0;
  return in_circle(pts.x(p), pts.y(p), pts.x(q), pts.y(q), pts.x(r), pts.y(r), pts.x(s), pts.y(s)) >
         0;
}

// Flips the edge between triangle t = (r, p, q) (r = vertex k) and
// u = (s, q, p) (s = vertex j) into t = (r, p, s), u = (s, q, r).
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
  stamp_ = 0;
  flipped_.clear();
  for (const int p : dirty_list_)
    dirty_[p] = 0;
  dirty_list_.clear();
  if (!valid_ || pts.n != n_points_) {
    valid_ = false;
    return false;
  }
  double scale = 0.0;
  for (int i = 0; i < pts.n; ++i) {
    if (!std::isfinite(pts.x(i)) || !std::isfinite(pts.y(i))) { // build() names it
      valid_ = false;
      return false;
    }
    scale = std::max({scale, std::fabs(pts.x(i)), std::fabs(pts.y(i))});
  }
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
    const int j = (nb_[3 * u + 1] == t) + 2 * (nb_[3 * u + 2] == t);
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
  // counter-clockwise has folded over, which flips cannot repair (outside the
  // region of interest it is frozen instead); every edge is tested once, and
  // the ones to flip are stacked (edges of frozen triangles are dropped when
  // popped, as frozenness of the far side is not known yet here).
  for (int t = 0; t < nt; ++t) {
    const int a = v_[3 * t], b = v_[3 * t + 1], c = v_[3 * t + 2];
    if (a != kInfinite && b != kInfinite && c != kInfinite) {
      const double ax = pts.x(a), ay = pts.y(a), bx = pts.x(b), by = pts.y(b), cx = pts.x(c),
                   cy = pts.y(c);
      if (orientation(ax, ay, bx, by, cx, cy) <= 0) {
        if (!outside_region(ax, ay, bx, by, cx, cy, roi_lo, roi_hi)) {
          valid_ = false;
          return false;
        }
        frozen_[t] = 1;
        continue;
      }
    }
    if (!stack_edges(pts, t, sep2))
      return false;
  }
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
    if (!flip_needed(pts, p, q, r, v_[3 * u + j]))
      continue;
    if (too_close(r, v_[3 * u + j])) { // the edge the flip would create
      valid_ = false;
      return false;
    }
    flip(t, k, u, j);
    if (++flips_ > max_flips) { // cannot happen for a valid mesh; be safe
      valid_ = false;
      return false;
    }
    // The four outer edges of the new pair (r,p,s) in t and (s,q,r) in u.
    const int edges[4][2] = {{t, 0}, {t, 2}, {u, 0}, {u, 2}};
    for (const auto &e : edges) {
      stack_.push_back(e[0]);
      stack_.push_back(e[1]);
    }
  }
  restore_partition();
  return true;
}

namespace {
// A fresh stamp for each filled Tessellation (see Mesh::stamp_).
unsigned long next_stamp() {
  static unsigned long counter = 0;
  return ++counter;
}
}  // namespace

// Multifold vertices from the seeds (triangles found at a zero-length edge):
// each seed starts a search over all triangles at that vertex, so that its
// whole ring of cells is known even where some are not owned here.
// compact(m) is the finite number of mesh triangle m (or -1), mesh_of(k) the
// inverse.
template <class Compact, class MeshOf>
void Mesh::find_groups(const Points &pts, Tessellation &t, Compact compact, MeshOf mesh_of) const {
  const int nft = static_cast<int>(t.triangles.size());
  auto same_vertex = [&](int a, int b) { return same_centre(t, a, b); };
  t.triangle_group.assign(nft, -1);
  t.group_offset.assign(1, 0);
  t.group_point.clear();
  t.group_centre.clear();
  if (seeds_.empty())
    return;
  std::vector<int> members, ring;
  for (const int seed : seeds_) {
    if (t.triangle_group[seed] >= 0)
      continue;
    const int ms = mesh_of(seed);
    const int group = static_cast<int>(t.group_centre.size());
    members.assign(1, seed);
    stack_.assign(1, ms);
    t.triangle_group[seed] = group;
    while (!stack_.empty()) {
      const int cur = stack_.back();
      stack_.pop_back();
      for (int e = 0; e < 3; ++e) {
        const int nm = nb_[3 * cur + e];
        const int g = compact(nm);
        if (g < 0 || t.triangle_group[g] >= 0 || !same_vertex(seed, g))
          continue;
        t.triangle_group[g] = group;
        members.push_back(g);
        stack_.push_back(nm);
      }
    }
    if (members.size() < 2) { // a tolerance edge case: no partner after all
      t.triangle_group[seed] = -1;
      continue;
    }
    Vec2 centre;
    for (int mm : members) {
      centre.x += t.vertices[mm].x / members.size();
      centre.y += t.vertices[mm].y / members.size();
    }
    ring.clear();
    for (int mm : members)
      for (int p : t.triangles[mm])
        ring.push_back(p);
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    std::vector<std::pair<double, int>> by_angle;
    by_angle.reserve(ring.size());
    for (int p : ring)
      by_angle.emplace_back(std::atan2(pts.y(p) - centre.y, pts.x(p) - centre.x), p);
    std::sort(by_angle.begin(), by_angle.end());
    for (const auto &ap : by_angle)
      t.group_point.push_back(ap.second);
    t.group_offset.push_back(static_cast<int>(t.group_point.size()));
    t.group_centre.push_back(centre);
  }
}

// One cell's edge lengths (into el), area and perimeter from its polygon
// (cv: len triangles, H: circumcentres, RAD: circumradii; (cx, cy) its
// centre), and the seeds of multifold vertices at its zero-length edges.
// Shared by cells() and advance().  The shoelace is taken relative to the
// cell centre: absolute coordinates far from the origin would cancel
// catastrophically.
void Mesh::cell_geometry(double cx, double cy, const int *cv, int len, const Vec2 *H,
                         const double *RAD, double *el, double &area, double &perimeter) const {
  double area2 = 0.0, perim = 0.0;
  // In chunks: the squared lengths (and the area), then their square roots
  // two at a time, then the lengths.
  constexpr int kChunk = 32;
  double q[kChunk];
  for (int k0 = 0; k0 < len; k0 += kChunk) {
    const int k1 = std::min(len, k0 + kChunk);
    for (int k = k0; k < k1; ++k) {
      const Vec2 &h0 = H[cv[k]], &h1 = H[cv[k + 1 == len ? 0 : k + 1]];
      area2 += (h0.x - cx) * (h1.y - cy) - (h1.x - cx) * (h0.y - cy);
      const double dx = h1.x - h0.x, dy = h1.y - h0.y;
      q[k - k0] = dx * dx + dy * dy;
    }
    roots(q, k1 - k0);
    for (int k = k0; k < k1; ++k) {
      const int t0 = cv[k], t1 = cv[k + 1 == len ? 0 : k + 1];
      const double d = q[k - k0];
      const double l = d > kZeroEdge * std::min(RAD[t0], RAD[t1]) ? d : 0.0;
      el[k] = l;
      perim += l;
      if (l == 0.0)
        seeds_.push_back(t0);
    }
  }
  area = 0.5 * area2;
  perimeter = perim;
}

void Mesh::cells(const Points &pts, int n_owned, Tessellation &t) const {
  const int nt = static_cast<int>(v_.size() / 3);
  t.n_points = n_points_;
  t.n_owned = n_owned;
  t.unbounded_cell = -1;

  // Finite triangles, numbered compactly, with their circumcentres.
  // Local, not members: only rebuilds (and callers outside a run) come here,
  // and a run's memory per cell is what it keeps between steps.
  std::vector<int> compact(nt), mesh_of(nt);
  t.triangles.resize(nt);
  t.vertices.resize(nt);
  t.radius.resize(nt);
  int nft = 0;
  for (int m = 0; m < nt; ++m) {
    const int a = v_[3 * m], b = v_[3 * m + 1], c = v_[3 * m + 2];
    if (a == kInfinite || b == kInfinite || c == kInfinite) {
      compact[m] = -1;
      continue;
    }
    compact[m] = nft;
    mesh_of[nft] = m;
    t.triangles[nft] = {a, b, c};
    circumcentre(pts.x(a), pts.y(a), pts.x(b), pts.y(b), pts.x(c), pts.y(c), t.vertices[nft],
                 t.radius[nft]);
    ++nft;
  }
  t.triangles.resize(nft);
  t.vertices.resize(nft);
  t.radius.resize(nft);
  mesh_of.resize(nft);

  auto same_vertex = [&](int a, int b) { return same_centre(t, a, b); };
  // Multifold vertices (triangles sharing one circumcentre) are seeded while
  // the cells are read: a zero-length edge of an owned cell marks two such
  // triangles.  The one case an owned cell's polygon cannot show is the
  // Delaunay edge opposite the cell in its triangle (x, y): if x or y is
  // owned, its own polygon shows it; if both are ghosts it is checked here.
  seeds_.clear();

  t.cell_offset.resize(n_owned + 1);
  t.cell_offset[0] = 0;
  t.area.resize(n_owned);
  t.perimeter.resize(n_owned);
  // Written through raw pointers with room checked per triangle: push_back's
  // bookkeeping was a measurable part of a step.
  size_t cap = std::max<size_t>(t.cell_vertex.capacity(), 7 * static_cast<size_t>(n_owned) + 64);
  t.cell_vertex.resize(cap);
  t.cell_neighbor.resize(cap);
  t.edge_length.resize(cap);
  size_t used = 0;
  for (int c = 0; c < n_owned; ++c) {
    const size_t o = used;
    const int start = vt_[c];
    int m = start;
    bool unbounded = false;
    do {
      const int *v = &v_[3 * m];
      const int i = (v[1] == c) + 2 * (v[2] == c); // index of c, without branches
      const int cm = compact[m];
      if (cm < 0) {
        unbounded = true;
        break;
      }
      if (used == cap) {
        cap *= 2;
        t.cell_vertex.resize(cap);
        t.cell_neighbor.resize(cap);
        t.edge_length.resize(cap);
      }
      t.cell_vertex[used] = cm;
      // Counter-clockwise around c the next triangle shares the edge from c to
      // this triangle's vertex i+2; that point is across the Voronoi edge.
      const int i1 = i == 2 ? 0 : i + 1, i2 = i1 == 2 ? 0 : i1 + 1;
      t.cell_neighbor[used] = v[i2];
      ++used;
      if (v[i1] >= n_owned && v[i2] >= n_owned) {
        const int g = compact[nb_[3 * m + i]];
        if (g >= 0 && same_vertex(cm, g))
          seeds_.push_back(cm);
      }
      m = nb_[3 * m + i1];
    } while (m != start);
    if (unbounded) {
      if (t.unbounded_cell < 0)
        t.unbounded_cell = c;
      used = o;
    }
    const int len = static_cast<int>(used - o);
    t.cell_offset[c + 1] = static_cast<int>(used);
    cell_geometry(pts.x(c), pts.y(c), &t.cell_vertex[o], len, t.vertices.data(),
                  t.radius.data(), &t.edge_length[o], t.area[c], t.perimeter[c]);
  }
  t.cell_vertex.resize(used);
  t.cell_neighbor.resize(used);
  t.edge_length.resize(used);

  find_groups(pts, t, [&](int m) { return compact[m]; }, [&](int k) { return mesh_of[k]; });
  last_incremental_ = false;
  t.mesh_stamp = stamp_ = next_stamp();
}

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
        valid_ = false;
        return false;
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
      const int j = (NB[3 * u + 1] == m) + 2 * (NB[3 * u + 2] == m);
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
  auto same_vertex = [&](int a, int b) { return same_centre(t, a, b); };
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
    cell_geometry(pts.x(cc), pts.y(cc), cv, len, H, RAD, EL + o, t.area[cc], t.perimeter[cc]);
    if (observer && (cc + 1 - block_start == kBlock || cc + 1 == n_owned)) {
      observer->cells(t, block_start, cc + 1);
      block_start = cc + 1;
    }
  }
  find_groups(pts, t, [nft](int m) { return m < nft ? m : -1; }, [](int k) { return k; });
  t.unbounded_cell = -1;
  t.mesh_stamp = stamp_ = next_stamp();
  last_incremental_ = true;
  if (observer) observer->end(t);
  return true;
}

double time_plain_delaunay(const Points &pts, int n, long *faces)
{
  using PlainDelaunay = CGAL::Delaunay_triangulation_2<Kernel>;
  std::vector<PlainDelaunay::Point> cp;
  cp.reserve(static_cast<size_t>(n > 0 ? n : 0));
  for (int i = 0; i < n; i++) cp.emplace_back(pts.x(i), pts.y(i));
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  PlainDelaunay dt;
  dt.insert(cp.begin(), cp.end());
  const double seconds = std::chrono::duration<double>(clock::now() - t0).count();
  if (faces) *faces = static_cast<long>(dt.number_of_faces());
  return seconds;
}

} // namespace tessera
