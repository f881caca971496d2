// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The exact predicates of exact_predicates.h in adaptive-precision
// floating-point arithmetic, after J. R. Shewchuk, "Adaptive precision
// floating-point arithmetic and fast robust geometric predicates", Discrete
// Comput. Geom. 18, 305-363 (1997).
//
// A number is held exactly as an expansion: a sum of doubles, each
// component smaller than the next and without overlapping bits.  The sum of
// two doubles and the product of two doubles are both exactly a two-component
// expansion (Two-Sum, Two-Product), and expansions add and scale exactly.
// Each predicate goes through stages, stopping at the first that can tell
// the sign:
//   A  the determinant in plain double arithmetic of the coordinate
//      differences, with an error bound proportional to its permanent (the
//      same sum with every term made positive);
//   B  the determinant of the rounded differences computed exactly (an
//      expansion), whose only error is the rounding of the differences; when
//      the differences were exact this is the answer;
//   C  B plus the first-order terms in the differences' rounding errors
//      (their "tails", which Two-Diff gives exactly), with a bound on what the
//      higher-order terms and the rounding of the correction can add;
//   D  the determinant of the exact differences, exactly.
// The bounds' coefficients are the paper's (for orient2d, incircle, orient3d
// the stages evaluate the same expressions); insphere's stage C is this
// file's own first-order sum, given twice the paper's coefficient.
//
// Expansion arithmetic is exact only while nothing overflows or underflows.
// Stage A therefore runs only on differences whose magnitudes keep every
// product in double's normal range, and before stage B the coordinates are
// checked: when all are integer multiples of 2^m with d m >= -1074 (d the
// predicate's degree: every exact intermediate is then a multiple of
// 2^-1074, which double holds exactly even below its normal range) and
// below 2^E with d (E + 1) <= 983 (nothing reaches 2^990, so neither the
// sums nor the splitting of factors overflow), stages B-D run as they are.
// Otherwise the coordinates are scaled by a power of two that satisfies both
// (exact, and the sign of a homogeneous determinant does not change), or,
// when their exponents span too wide a range for any (a coordinate of 1e-300
// next to one of 1, say), the determinant is evaluated in plain big-integer
// arithmetic.  So the sign is exact for every finite input.
//
// This file is stage A; the rest is exact_predicates_adapt.cpp (with
// exact_bigint.h and the shared exact_predicates_detail.h).

#include "exact_predicates.h"
#include "exact_predicates_detail.h"

#include <cmath>

namespace tessera::exact {

namespace {

// Stage A runs only when every coordinate difference is 0 or within
// [2^-200, 2^190]: products of up to five of them stay within double's
// normal range, where each rounding is relative.
constexpr double kSafeLow = 0x1p-200;
constexpr double kSafeHigh = 0x1p190;

inline bool safe(double d) {
  const double a = std::fabs(d);
  return a == 0.0 || (a >= kSafeLow && a <= kSafeHigh);
}

} // namespace

// Stage A in front of each: the differences within the safe range, the
// determinant decided by its error bound.

int orient2d(const double *a, const double *b, const double *c) {
  const double acx = a[0] - c[0], bcx = b[0] - c[0], acy = a[1] - c[1], bcy = b[1] - c[1];
  if (safe(acx) && safe(bcx) && safe(acy) && safe(bcy)) {
    const double l = acx * bcy, r = acy * bcx;
    const double det = l - r;
    const double bound = kO2A * (std::fabs(l) + std::fabs(r));
    if (det > bound || -det > bound)
      return sign_of(det);
  }
  return orient2d_slow(a, b, c);
}

int incircle(const double *a, const double *b, const double *c, const double *d) {
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  if (safe(adx) && safe(bdx) && safe(cdx) && safe(ady) && safe(bdy) && safe(cdy)) {
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy, cdxady = cdx * ady, adxcdy = adx * cdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady;
    const double alift = adx * adx + ady * ady, blift = bdx * bdx + bdy * bdy;
    const double clift = cdx * cdx + cdy * cdy;
    const double det =
        alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                             (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                             (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
    const double bound = kICA * permanent;
    if (det > bound || -det > bound)
      return sign_of(det);
  }
  return incircle_slow(a, b, c, d);
}

int orient3d(const double *a, const double *b, const double *c, const double *d) {
  // det[b-a; c-a; d-a] = -det[a-d; b-d; c-d]
  const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
  const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
  const double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
  if (safe(adx) && safe(bdx) && safe(cdx) && safe(ady) && safe(bdy) && safe(cdy) && safe(adz) &&
      safe(bdz) && safe(cdz)) {
    const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy, cdxady = cdx * ady, adxcdy = adx * cdy;
    const double adxbdy = adx * bdy, bdxady = bdx * ady;
    const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                             (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                             (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
    const double bound = kO3A * permanent;
    if (det > bound || -det > bound)
      return -sign_of(det);
  }
  return -orient3d_slow(a, b, c, d);
}

int insphere(const double *a, const double *b, const double *c, const double *d, const double *e) {
  // The stages compute the lifted determinant, positive when e is inside the
  // sphere of a tetrahedron with det[b-a; c-a; d-a] < 0: hence the sign flip.
  bool ok = true;
  for (int k = 0; k < 3; ++k)
    ok = ok && safe(a[k] - e[k]) && safe(b[k] - e[k]) && safe(c[k] - e[k]) && safe(d[k] - e[k]);
  if (ok) {
    const double *P[4] = {a, b, c, d};
    double h[4][3], L[4];
    for (int i = 0; i < 4; ++i) {
      for (int k = 0; k < 3; ++k)
        h[i][k] = P[i][k] - e[k];
      L[i] = h[i][0] * h[i][0] + h[i][1] * h[i][1] + h[i][2] * h[i][2];
    }
    double det = 0.0, permanent = 0.0;
    // -L_a |b c d| + L_b |a c d| - L_c |a b d| + L_d |a b c|, grouped as in the stages
    const int rows[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
    double m[4], pm[4];
    for (int r = 0; r < 4; ++r) {
      const int i = rows[r][0], j = rows[r][1], k = rows[r][2];
      const double xjk = h[j][0] * h[k][1], yjk = h[k][0] * h[j][1];
      const double xik = h[i][0] * h[k][1], yik = h[k][0] * h[i][1];
      const double xij = h[i][0] * h[j][1], yij = h[j][0] * h[i][1];
      m[r] = h[i][2] * (xjk - yjk) - h[j][2] * (xik - yik) + h[k][2] * (xij - yij);
      pm[r] = std::fabs(h[i][2]) * (std::fabs(xjk) + std::fabs(yjk)) +
              std::fabs(h[j][2]) * (std::fabs(xik) + std::fabs(yik)) +
              std::fabs(h[k][2]) * (std::fabs(xij) + std::fabs(yij));
    }
    det = (L[3] * m[0] - L[2] * m[1]) + (L[1] * m[2] - L[0] * m[3]);
    permanent = L[3] * pm[0] + L[2] * pm[1] + L[1] * pm[2] + L[0] * pm[3];
    const double bound = kISA * permanent;
    if (det > bound || -det > bound)
      return -sign_of(det);
  }
  return -insphere_slow(a, b, c, d, e);
}

} // namespace tessera::exact
