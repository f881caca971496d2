// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Shared by the two source files of the exact predicates: stage A, the
// filter every call goes through (exact_predicates.cpp), and stages B-D with
// the range check (exact_predicates_adapt.cpp): the error-bound coefficients
// (the adaptive stages repeat stage A on scaled input), the sign of a double
// or an expansion, and the slow path's entry points.  Internal to the core
// (not installed).
#pragma once

namespace tessera::exact {

// Half an ulp of 1: the largest relative error of one rounding.
constexpr double kEps = 0x1p-53;
// Error-bound coefficients (Shewchuk 1997, sections 4.2-4.3).
constexpr double kResultErr = (3.0 + 8.0 * kEps) * kEps;
constexpr double kO2A = (3.0 + 16.0 * kEps) * kEps;
constexpr double kO2B = (2.0 + 12.0 * kEps) * kEps;
constexpr double kO2C = (9.0 + 64.0 * kEps) * kEps * kEps;
constexpr double kICA = (10.0 + 96.0 * kEps) * kEps;
constexpr double kICB = (4.0 + 48.0 * kEps) * kEps;
constexpr double kICC = (44.0 + 576.0 * kEps) * kEps * kEps;
constexpr double kO3A = (7.0 + 56.0 * kEps) * kEps;
constexpr double kO3B = (3.0 + 28.0 * kEps) * kEps;
constexpr double kO3C = (26.0 + 288.0 * kEps) * kEps * kEps;
constexpr double kISA = (16.0 + 224.0 * kEps) * kEps;
constexpr double kISB = (5.0 + 72.0 * kEps) * kEps;
constexpr double kISC = 2.0 * (71.0 + 1408.0 * kEps) * kEps * kEps;

inline int sign_of(double x) {
  return (x > 0.0) - (x < 0.0);
}

inline int sign_of(int elen, const double *e) {
  return sign_of(e[elen - 1]);
}

// Stages B-D (exact_predicates_adapt.cpp), for what stage A left open, in
// the stages' conventions: orient3d_slow is the sign of det[a-d; b-d; c-d],
// insphere_slow that of the lifted determinant of rows p - e.
int orient2d_slow(const double *a, const double *b, const double *c);
int incircle_slow(const double *a, const double *b, const double *c, const double *d);
int orient3d_slow(const double *a, const double *b, const double *c, const double *d);
int insphere_slow(const double *a, const double *b, const double *c, const double *d,
                  const double *e);

} // namespace tessera::exact
