// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The oracle of the exact predicates (core/src/exact_predicates.h): the same
// four determinants in GMP rationals.  Every double is a rational, so they
// are computed without rounding; slow, and sharing no code with the core's
// adaptive floating-point version.  Same conventions as the core's.
#pragma once

namespace oracle {

int orient2d(const double *a, const double *b, const double *c);
int incircle(const double *a, const double *b, const double *c, const double *d);
int orient3d(const double *a, const double *b, const double *c, const double *d);
int insphere(const double *a, const double *b, const double *c, const double *d, const double *e);

} // namespace oracle
