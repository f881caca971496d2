// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The vertex model's single polygon: measures, the cell's energy and its exact
// gradient with respect to the corners, and the validity test.

#include "tessera/vertex_model.h"

#include <cmath>
#include <vector>

namespace tessera {

namespace {

// A polygon's edge: sqrt of the sum of squares, not std::hypot (several times
// dearer), since a cell's corners are nowhere near 1e154 apart; non-finite
// corners give a non-finite length either way.
inline double edge_length(double dx, double dy) {
  return std::sqrt(dx * dx + dy * dy);
}

// The centroid from the shoelace sums relative to the first corner (x0, y0):
// a2 twice the area, (cx, cy) the first moments times 6; a polygon of no
// area gets the mean of its corners ((mx, my) their sum relative to x0, y0).
inline Vec2 centroid_of(double x0, double y0, double a2, double cx, double cy, double mx,
                        double my, int n) {
  if (a2 != 0.0)
    return {x0 + cx / (3.0 * a2), y0 + cy / (3.0 * a2)};
  return {x0 + mx / n, y0 + my / n};
}

} // namespace

PolygonMeasures polygon_measures(const double *xy, int n) {
  PolygonMeasures m;
  if (n <= 0)
    return m;
  // Relative to the first corner: the shoelace sums then cancel less.
  const double x0 = xy[0], y0 = xy[1];
  double a2 = 0.0, cx = 0.0, cy = 0.0, mx = 0.0, my = 0.0;
  for (int k = 0; k < n; ++k) {
    const int k1 = k + 1 == n ? 0 : k + 1;
    const double xa = xy[2 * k] - x0, ya = xy[2 * k + 1] - y0;
    const double xb = xy[2 * k1] - x0, yb = xy[2 * k1 + 1] - y0;
    const double cr = xa * yb - xb * ya;
    a2 += cr;
    cx += (xa + xb) * cr;
    cy += (ya + yb) * cr;
    mx += xa;
    my += ya;
    m.perimeter += edge_length(xb - xa, yb - ya);
  }
  m.area = 0.5 * a2;
  m.centroid = centroid_of(x0, y0, a2, cx, cy, mx, my, n);
  return m;
}

double polygon_energy(const double *xy, int n, const Model &model, int c, int tc,
                      const int *nbr_type, double *grad, PolygonMeasures *measures) {
  // Each edge's vector, length and junction tension once, for the energy
  // and the gradient.
  constexpr int kStack = 32;
  double stack[4 * kStack];
  std::vector<double> heap;
  double *edge = stack;
  if (n > kStack) {
    heap.resize(4 * static_cast<size_t>(n));
    edge = heap.data();
  }
  const double x0 = xy[0], y0 = xy[1];
  double a2 = 0.0, P = 0.0, tension = 0.0, cx = 0.0, cy = 0.0, mx = 0.0, my = 0.0;
  const double w = model.tension_weight();
  for (int k = 0; k < n; ++k) {
    const int k1 = k + 1 == n ? 0 : k + 1;
    const double xa = xy[2 * k] - x0, ya = xy[2 * k + 1] - y0;
    const double xb = xy[2 * k1] - x0, yb = xy[2 * k1 + 1] - y0;
    const double cr = xa * yb - xb * ya;
    a2 += cr;
    // (polygon_measures' sums, as it makes them)
    cx += (xa + xb) * cr;
    cy += (ya + yb) * cr;
    mx += xa;
    my += ya;
    const double dx = xy[2 * k1] - xy[2 * k], dy = xy[2 * k1 + 1] - xy[2 * k + 1];
    const double l = edge_length(dx, dy);
    const double lam = model.lambda_of(tc, nbr_type ? nbr_type[k] : tc);
    edge[4 * k] = dx;
    edge[4 * k + 1] = dy;
    edge[4 * k + 2] = l;
    edge[4 * k + 3] = lam;
    P += l;
    tension += lam * l;
  }
  const double A = 0.5 * a2;
  if (measures) {
    measures->area = A;
    measures->perimeter = P;
    measures->centroid = centroid_of(x0, y0, a2, cx, cy, mx, my, n);
  }
  const Model::CellParams p = model.cell_params(c, tc);
  const double dA = A - p.A0;
  const double e = 0.5 * p.K * dA * dA + 0.5 * p.Gamma * P * P + p.shift * P + w * tension;
  if (!grad)
    return e;
  const double eA = p.K * dA, eP = p.Gamma * P + p.shift;
  // Edge k's coefficient t_k = dE/dl_k times its unit vector u_k (in place
  // of the edge vector); corner k gets t_{k-1} u_{k-1} - t_k u_k from the
  // lengths.  A zero-length edge has no direction: nothing.
  for (int k = 0; k < n; ++k) {
    const double l = edge[4 * k + 2];
    const double t = eP + w * edge[4 * k + 3];
    const double s = l > 0.0 ? t / l : 0.0;
    edge[4 * k] *= s;
    edge[4 * k + 1] *= s;
  }
  for (int k = 0; k < n; ++k) {
    const int k1 = k + 1 == n ? 0 : k + 1;
    const int km = k == 0 ? n - 1 : k - 1;
    grad[2 * k] = eA * 0.5 * (xy[2 * k1 + 1] - xy[2 * km + 1]) + edge[4 * km] - edge[4 * k];
    grad[2 * k + 1] = eA * 0.5 * (xy[2 * km] - xy[2 * k1]) + edge[4 * km + 1] - edge[4 * k + 1];
  }
  return e;
}

const char *describe(PolygonDefect d) {
  switch (d) {
  case PolygonDefect::None:
    return "valid";
  case PolygonDefect::TooFewSides:
    return "has fewer than three vertices";
  case PolygonDefect::RepeatedVertex:
    return "lists a vertex twice";
  case PolygonDefect::NotFinite:
    return "has a vertex at a non-finite position";
  case PolygonDefect::NotPositive:
    return "has zero or negative area (clockwise: inverted)";
  case PolygonDefect::SelfIntersecting:
    return "crosses itself";
  }
  return "?";
}

namespace {

inline double orient(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

// Whether c lies strictly inside segment ab, given that a, b, c are collinear.
inline bool strictly_between(double ax, double ay, double bx, double by, double cx, double cy) {
  const double d = (cx - ax) * (bx - ax) + (cy - ay) * (by - ay);
  const double l2 = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
  const bool at_end = (cx == ax && cy == ay) || (cx == bx && cy == by);
  return !at_end && d > 0.0 && d < l2;
}

// Segments pq and rs cross at interior points, or one's end lies inside the
// other (collinear overlap); ends that coincide do not count.
bool segments_meet(const double *p, const double *q, const double *r, const double *s) {
  const double o1 = orient(p[0], p[1], q[0], q[1], r[0], r[1]);
  const double o2 = orient(p[0], p[1], q[0], q[1], s[0], s[1]);
  const double o3 = orient(r[0], r[1], s[0], s[1], p[0], p[1]);
  const double o4 = orient(r[0], r[1], s[0], s[1], q[0], q[1]);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
    return true;
  if (o1 == 0 && strictly_between(p[0], p[1], q[0], q[1], r[0], r[1]))
    return true;
  if (o2 == 0 && strictly_between(p[0], p[1], q[0], q[1], s[0], s[1]))
    return true;
  if (o3 == 0 && strictly_between(r[0], r[1], s[0], s[1], p[0], p[1]))
    return true;
  if (o4 == 0 && strictly_between(r[0], r[1], s[0], s[1], q[0], q[1]))
    return true;
  return false;
}

// Whether the polygon is convex beyond rounding and winds once: every corner
// a left turn whose sine exceeds 1e-6 (no rounding of the differences can
// flip it) and the edges' directions passing the +x direction exactly once
// (the turns, each in (0, pi), add up to 2 pi).  Such a polygon is simple
// with positive area, so the pairwise test has nothing to find.  Zero-length
// edges, straight or reflex corners and windings other than one answer
// false (the pairwise test decides).
bool surely_convex(const double *xy, int n) {
  double ux = xy[0] - xy[2 * n - 2], uy = xy[1] - xy[2 * n - 1];
  double lu2 = ux * ux + uy * uy; // (each edge's square length once: w's is the next u's)
  int wraps = 0;
  for (int k = 0; k < n; ++k) {
    const int k1 = k + 1 == n ? 0 : k + 1;
    const double wx = xy[2 * k1] - xy[2 * k], wy = xy[2 * k1 + 1] - xy[2 * k + 1];
    const double lw2 = wx * wx + wy * wy;
    const double cr = ux * wy - uy * wx;
    if (!(cr > 0.0) || !(cr * cr > 1e-12 * lu2 * lw2))
      return false;
    // (the sign of a rounded difference is exact)
    if (uy < 0.0 && wy >= 0.0)
      ++wraps;
    ux = wx;
    uy = wy;
    lu2 = lw2;
  }
  return wraps == 1;
}

PolygonDefect basic_defect(const double *xy, int n, const long *ids) {
  if (n < 3)
    return PolygonDefect::TooFewSides;
  for (int k = 0; k < 2 * n; ++k)
    if (!std::isfinite(xy[k]))
      return PolygonDefect::NotFinite;
  if (ids)
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (ids[i] == ids[j])
          return PolygonDefect::RepeatedVertex;
  return PolygonDefect::None;
}

} // namespace

PolygonDefect polygon_defect(const double *xy, int n, const long *ids) {
  // (a non-finite corner fails surely_convex: its edges' products are
  // infinite or NaN; so a convex polygon needs only the repeated-ID test)
  if (n >= 3 && surely_convex(xy, n)) {
    if (ids)
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
          if (ids[i] == ids[j])
            return PolygonDefect::RepeatedVertex;
    return PolygonDefect::None;
  }
  return polygon_defect_pairwise(xy, n, ids);
}

PolygonDefect polygon_defect_pairwise(const double *xy, int n, const long *ids) {
  const PolygonDefect d = basic_defect(xy, n, ids);
  if (d != PolygonDefect::None)
    return d;
  if (!(polygon_measures(xy, n).area > 0.0))
    return PolygonDefect::NotPositive;
  // Adjacent edges that fold back onto each other (a spike of zero width).
  for (int k = 0; k < n; ++k) {
    const int km = k == 0 ? n - 1 : k - 1, k1 = k + 1 == n ? 0 : k + 1;
    const double *a = &xy[2 * km], *b = &xy[2 * k], *c = &xy[2 * k1];
    if (orient(a[0], a[1], b[0], b[1], c[0], c[1]) == 0.0 &&
        (strictly_between(a[0], a[1], b[0], b[1], c[0], c[1]) ||
         strictly_between(b[0], b[1], c[0], c[1], a[0], a[1])))
      return PolygonDefect::SelfIntersecting;
  }
  // Non-adjacent edge pairs (i, j), j > i + 1, not the pair (0, n-1).
  for (int i = 0; i < n; ++i) {
    const int i1 = i + 1 == n ? 0 : i + 1;
    // Bounding box of edge i, to skip most pairs cheaply.
    const double ax = xy[2 * i], ay = xy[2 * i + 1], bx = xy[2 * i1], by = xy[2 * i1 + 1];
    const double xlo = std::fmin(ax, bx), xhi = std::fmax(ax, bx);
    const double ylo = std::fmin(ay, by), yhi = std::fmax(ay, by);
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1)
        continue;
      const int j1 = j + 1 == n ? 0 : j + 1;
      const double cx = xy[2 * j], cy = xy[2 * j + 1], dx = xy[2 * j1], dy = xy[2 * j1 + 1];
      if (std::fmax(cx, dx) < xlo || std::fmin(cx, dx) > xhi || std::fmax(cy, dy) < ylo ||
          std::fmin(cy, dy) > yhi)
        continue;
      if (segments_meet(&xy[2 * i], &xy[2 * i1], &xy[2 * j], &xy[2 * j1]))
        return PolygonDefect::SelfIntersecting;
    }
  }
  return PolygonDefect::None;
}

} // namespace tessera
