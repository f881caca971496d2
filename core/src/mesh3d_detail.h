// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Shared by the 3D mesh's sources (mesh3d, mesh3d_update): the slots of a
// tetrahedron's triangles, and the circumsphere test of the flip sweep
// (tested on its own in tests/core).  Internal to the core (not installed).
#pragma once

#include <algorithm>
#include <cmath>

namespace tessera {
namespace {

// Slots of the triangle opposite slot k, ordered so that (f0 f1 f2 k) is an
// even permutation: the apex k sees it positively.
constexpr int kFace[4][3] = {{1, 3, 2}, {0, 2, 3}, {1, 0, 3}, {0, 1, 2}};

}  // namespace
namespace detail3 {

// The circumsphere of the tetrahedron p0 p1 p2 p3, relative to p0: centre
// p0 + v, squared radius r2.  False when the tetrahedron is flatter than
// |det| >= 1e-3 L^3 (L its longest edge from p0), beyond which the error
// bound of clearly_outside() is not claimed.
inline bool circumsphere(const double *p0, const double *p1, const double *p2, const double *p3,
                         double *v, double &r2) {
  const double a[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double b[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  const double d[3] = {p3[0] - p0[0], p3[1] - p0[1], p3[2] - p0[2]};
  const double la = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  const double lb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
  const double ld = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double bxd[3] = {b[1] * d[2] - b[2] * d[1], b[2] * d[0] - b[0] * d[2],
                         b[0] * d[1] - b[1] * d[0]};
  const double dxa[3] = {d[1] * a[2] - d[2] * a[1], d[2] * a[0] - d[0] * a[2],
                         d[0] * a[1] - d[1] * a[0]};
  const double axb[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]};
  const double det = a[0] * bxd[0] + a[1] * bxd[1] + a[2] * bxd[2];
  const double l2 = std::max({la, lb, ld});
  if (!(std::fabs(det) >= 1e-3 * l2 * std::sqrt(l2)))
    return false;
  const double s = 0.5 / det;
  for (int k = 0; k < 3; ++k)
    v[k] = (la * bxd[k] + lb * dxa[k] + ld * axb[k]) * s;
  r2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  return std::isfinite(r2);
}

// Whether e lies outside the circumsphere (p0 + v, r2) by more than
// 1e-8 (r^2 + |e - c|^2).  For a tetrahedron circumsphere() accepts, the
// rounding error of v is below about 1e4 machine epsilons of r (relative
// error of the 3x3 solve: about 10 eps / flatness, flatness >= 1e-3, times
// r + L <= 3 r), so the error of |e - c|^2 - r^2 is below 1e-11 (r^2 +
// |e - c|^2): a point this far outside is outside for the exact in-sphere
// predicate too, with or without its symbolic perturbation (which only
// breaks exact ties).  Everything is relative to p0, so large coordinates do
// not enter the rounding.
inline bool clearly_outside(const double *p0, const double *v, double r2, const double *e) {
  const double w[3] = {e[0] - p0[0] - v[0], e[1] - p0[1] - v[1], e[2] - p0[2] - v[2]};
  const double d2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  return d2 - r2 > 1e-8 * (r2 + d2);
}

}  // namespace detail3
}  // namespace tessera
