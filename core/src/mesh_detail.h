// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Shared by the mesh's source files (mesh_build, mesh_update, mesh_cells,
// mesh_advance, mesh_repair): the input limits, the filtered predicates and
// the tie-break of co-circular points, the circumcentre, and the search for
// multifold vertices.  Internal to the core (not installed).
#pragma once

#include "tessera/mesh.h"

#include "exact_predicates.h"
#include "point_name.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace tessera {

namespace detail {
// The sign of the in-circle determinant of exactly co-circular a, b, c, d
// under the symbolic perturbation that breaks their tie (mesh_build.cpp;
// doc/model.md, "Exact geometry"): never 0 for four distinct points with
// a, b, c not collinear.
int in_circle_tie(const double *a, const double *b, const double *c, const double *d);

// The triangulator of Mesh::build alone (mesh_build.cpp), on points
// 0..pts.n-1 without the input checks: the triangles into tri (three
// corners each, counter-clockwise, the smallest first; -1 is the point at
// infinity).  False when all points are on one line or two coincide.
bool delaunay_triangles(const Points &pts, std::vector<int> &tri);
}  // namespace detail

namespace {

// Voronoi edges shorter than this fraction of the adjacent circumradius (or
// than the circumcentres' error bounds, see zero_edge) are the zero-length
// edges of a multifold vertex whose circumcentres differ only by round-off;
// they get length exactly 0.
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

// Coordinates below this magnitude (other than 0) let products of four
// coordinate differences underflow, where the floating-point filters'
// relative error bounds no longer hold.  A point set with one (build() and
// update() look) takes the exact predicates without the in-circle filters:
// all nonzero differences of coordinates of at least 2^-200 are at least
// 2^-252, and products of four of those stay normal.
constexpr double kTinyCoordinate = 0x1p-200;

// Orientation of (a, b, c): > 0 counter-clockwise.  Shewchuk's static error
// bound (plus 2^-1060 for products that underflow) decides almost every
// case in double precision; the rest go to the exact predicate.
inline int orientation(double ax, double ay, double bx, double by, double cx, double cy) {
  const double l = (ax - cx) * (by - cy), r = (ay - cy) * (bx - cx);
  const double det = l - r;
  const double bound = 3.3306690738754716e-16 * (std::fabs(l) + std::fabs(r)) + 0x1p-1060;
  if (det > bound)
    return 1;
  if (-det > bound)
    return -1;
  const double a[2] = {ax, ay}, b[2] = {bx, by}, c[2] = {cx, cy};
  return exact::orient2d(a, b, c);
}

// > 0 when d is strictly inside the circle through the counter-clockwise
// a, b, c, ties broken by the symbolic perturbation: the same side as
// CGAL's perturbed side_of_oriented_circle, so that the Delaunay
// triangulation is unique.  Shewchuk's static filter first (valid when no
// coordinate is tiny, see kTinyCoordinate; with filter false it is skipped),
// then the exact predicate.
inline int in_circle(double ax, double ay, double bx, double by, double cx, double cy, double dx,
                     double dy, bool filter = true) {
  if (filter) {
    const double adx = ax - dx, ady = ay - dy, bdx = bx - dx, bdy = by - dy, cdx = cx - dx,
                 cdy = cy - dy;
    const double bc = bdx * cdy, cb = cdx * bdy, ca = cdx * ady, ac = adx * cdy, ab = adx * bdy,
                 ba = bdx * ady;
    const double al = adx * adx + ady * ady, bl = bdx * bdx + bdy * bdy,
                 cl = cdx * cdx + cdy * cdy;
    const double det = al * (bc - cb) + bl * (ca - ac) + cl * (ab - ba);
    const double perm = (std::fabs(bc) + std::fabs(cb)) * al +
                        (std::fabs(ca) + std::fabs(ac)) * bl + (std::fabs(ab) + std::fabs(ba)) * cl;
    const double bound = 1.1102230246251577e-15 * perm;
    if (det > bound)
      return 1;
    if (-det > bound)
      return -1;
  }
  const double a[2] = {ax, ay}, b[2] = {bx, by}, c[2] = {cx, cy}, d[2] = {dx, dy};
  const int s = exact::incircle(a, b, c, d);
  return s != 0 ? s : detail::in_circle_tie(a, b, c, d);
}

// The correctly rounded square root (as std::sqrt) without the errno path:
// with -frounding-math (which CGAL's build flags brought in) GCC turned
// std::sqrt in advance() into a call into libm, 5 % of a step.
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

// A cell's ring (its Voronoi vertices cv and the neighbours cn across the
// edges that follow them) rotated to start at its smallest neighbour index.
// The walk starts wherever the triangulation's history left the point's
// triangle, so a mesh repaired by flips and one built afresh (a restart, a
// rebuild) would read the same polygon from different corners and sum its
// area, lengths and exchanges in another order (a last-place difference
// that an active tissue amplifies).  From one corner the two agree bit for bit.
inline void canonical_ring(int *cv, int *cn, int len) {
  int k0 = 0;
  for (int k = 1; k < len; ++k)
    if (cn[k] < cn[k0])
      k0 = k;
  if (k0 == 0)
    return;
  std::rotate(cv, cv + k0, cv + len);
  std::rotate(cn, cn + k0, cn + len);
}

// Whether the triangle (a, b, c) lies entirely outside the region of
// interest [roi_lo, roi_hi] (false without one): a fold there is frozen.
inline bool outside_region(double ax, double ay, double bx, double by, double cx, double cy,
                           const double *roi_lo, const double *roi_hi) {
  return roi_lo && (std::max({ax, bx, cx}) < roi_lo[0] || std::min({ax, bx, cx}) > roi_hi[0] ||
                    std::max({ay, by, cy}) < roi_lo[1] || std::min({ay, by, cy}) > roi_hi[1]);
}

// A bound on the error of the computed circumcentre of (a, b, c) (r: its
// computed radius), counting the input as known only to eps times its
// largest coordinate magnitude S: a periodic image or a ghost is a rounded
// translate, and coordinates far from the origin carry that rounding (see
// kMinSeparation).  With b' = b - a, c' = c - a, u = N / D the circumcentre
// relative to a (N = (c'y |b'|^2 - b'y |c'|^2, b'x |c'|^2 - c'x |b'|^2),
// D = 2 b' x c'), moving every corner coordinate by at most e moves u to
// first order by at most (in the 1-norm)
//   4 e (|b'|^2 + |c'|^2 + 2 |b'|_1 |c'|_1 + |u|_1 (|b'|_1 + |c'|_1)) / |D|,
// which grows with S and with 1 / flatness (|D| is twice the area).  The
// bound takes twice that with e = eps (S + 8 (|b'|_1 + |c'|_1)) (the second
// term covers the rounding of the arithmetic itself), plus the rounding of
// h = a + u.  |u|_1 <= sqrt(2) r.
inline double centre_error(double ax, double ay, double bx, double by, double cx, double cy,
                           double r) {
  constexpr double eps = 2.220446049250313e-16;
  const double bpx = bx - ax, bpy = by - ay, cpx = cx - ax, cpy = cy - ay;
  const double b1 = std::fabs(bpx) + std::fabs(bpy), c1 = std::fabs(cpx) + std::fabs(cpy);
  const double b2 = bpx * bpx + bpy * bpy, c2 = cpx * cpx + cpy * cpy;
  const double iD = std::fabs(0.5 / (bpx * cpy - bpy * cpx));
  const double S = std::max({std::fabs(ax), std::fabs(ay), std::fabs(bx), std::fabs(by),
                             std::fabs(cx), std::fabs(cy)});
  const double R1 = 1.5 * r;
  const double e = eps * (S + 8.0 * (b1 + c1));
  return 8.0 * e * (b2 + c2 + 2.0 * b1 * c1 + R1 * (b1 + c1)) * iD + 4.0 * eps * (S + R1);
}

// A circumcentre whose error bound exceeds this fraction of its radius (half
// of it, for rounding) is not trusted to be grouped by that bound (only by
// kZeroEdge).  Such a triangle is flat at the round-off level (the hull of a
// ghost shell, a row of collinear images): its centre is far away and
// undetermined, and its bound would swallow its neighbours.  With trusted
// bounds two triangles sharing an edge are grouped only if their radii agree
// to about kTrust, i.e. they lie on nearly one circle.  It also bounds the
// tolerance: err_a + err_b <= kTrust max(r_a, r_b), which lets the common
// case (an edge longer than that) skip the bounds.
constexpr double kTrust = 1e-3;

inline double trusted_error(const Points &pts, const std::array<int, 3> &tri, double r) {
  const int a = tri[0], b = tri[1], c = tri[2];
  const double err = centre_error(pts.x(a), pts.y(a), pts.x(b), pts.y(b), pts.x(c), pts.y(c), r);
  // false for NaN and infinity (r infinite: a triangle flat in floating point)
  return err <= 0.5 * kTrust * r && err <= std::numeric_limits<double>::max() ? err : 0.0;
}

// Whether the Voronoi edge of length d between the circumcentres of
// triangles t0 and t1 (RAD: radii, TRI: corners) is a zero-length edge of a
// multifold vertex, i.e. the two circumcentres are one point within what
// floating point can tell: d <= kZeroEdge times the smaller radius (round-off
// of well-placed points near the origin), or d <= err_0 + err_1, the sum of
// the two circumcentres' error bounds (coordinates far from the origin,
// nearly flat triangles).  The tolerance is a fraction of the smaller radius:
// a nearly flat triangle (on the hull of a ghost shell, or a row of collinear
// images) has a huge or infinite radius, and with the larger one its
// tolerance would swallow its neighbours into one "vertex" with an infinite
// centre (kTrust keeps the error bounds from doing the same).  A NaN length
// is zero (as the comparison d > tol is false).  The one predicate of both
// the cells' edge lengths and the grouping, so that the two agree.
TESSERA_ALWAYS_INLINE bool zero_edge(double d, int t0, int t1, const double *RAD,
                                     const Points &pts, const std::array<int, 3> *TRI) {
  const double r0 = RAD[t0], r1 = RAD[t1];
  if (!(d > kZeroEdge * std::min(r0, r1)))
    return true;
  if (d > kTrust * std::max(r0, r1))
    return false;  // the common case: longer than any trusted bound
  return d <= trusted_error(pts, TRI[t0], r0) + trusted_error(pts, TRI[t1], r1);
}

// Whether triangles a and b of t have one circumcentre (a multifold vertex):
// zero_edge() of the distance between them.  A vertex that is not finite is
// never the same as another.
inline bool same_centre(const Points &pts, const Tessellation &t, int a, int b) {
  const double dx = t.vertices[a].x - t.vertices[b].x, dy = t.vertices[a].y - t.vertices[b].y;
  const double d = root(dx * dx + dy * dy);
  return std::isfinite(d) && zero_edge(d, a, b, t.radius.data(), pts, t.triangles.data());
}

} // namespace

namespace detail {
// A fresh stamp for each filled Tessellation (see Mesh::stamp_).
unsigned long next_stamp();

// The slot j of triangle u (corners v, neighbours nb, three per triangle)
// whose edge is (q, p) and whose neighbour is t, i.e. the corner of u across
// t's edge (p, q); -1 if none (inconsistent adjacency).  For the rare pair of
// triangles that share two edges, where the quick formula from the
// neighbours alone is ambiguous.
[[gnu::noinline, gnu::cold]] inline int slot_across(const int *v, const int *nb, int u, int t,
                                                    int p, int q) {
  for (int j = 0; j < 3; ++j)
    if (nb[3 * u + j] == t && v[3 * u + (j + 1) % 3] == q && v[3 * u + (j + 2) % 3] == p)
      return j;
  return -1;
}
}  // namespace detail

// Multifold vertices from the seeds (triangles found at a zero-length edge):
// each seed starts a search over all triangles at that vertex, so that its
// whole ring of cells is known even where some are not owned here.
// compact(m) is the finite number of mesh triangle m (or -1), mesh_of(k) the
// inverse.
template <class Compact, class MeshOf>
void Mesh::find_groups(const Points &pts, Tessellation &t, Compact compact, MeshOf mesh_of) const {
  const int nft = static_cast<int>(t.triangles.size());
  auto same_vertex = [&](int a, int b) { return same_centre(pts, t, a, b); };
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
    // The members' circumcentres differ by round-off: they all become the
    // one vertex, so that every cell at it sees one position.
    for (int mm : members) t.vertices[mm] = centre;
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

}  // namespace tessera
