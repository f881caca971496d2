// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The exact predicates in GMP arithmetic (exact_oracle.h), written as the
// core's first implementation was (the determinants of the differences,
// expanded by hand) but in integers: the coordinates of one call are all
// integer multiples of 2^m, m the lowest bit set in any of them, so in units
// of 2^m they are GMP integers and the determinants (homogeneous, so their
// sign does not depend on the unit) are computed without rounding, and
// without the rationals' greatest common divisors, which made the oracle the
// slowest part of the test.

#include "exact_oracle.h"

#include <gmpxx.h>

#include <algorithm>
#include <climits>
#include <cmath>

namespace oracle {

namespace {

// The exponent of the lowest set bit of x (x != 0).
int low_bit(double x) {
  int e;
  const double f = std::frexp(std::fabs(x), &e);
  long long mant = static_cast<long long>(std::ldexp(f, 53));
  int low = e - 53;
  while ((mant & 1) == 0) {
    mant >>= 1;
    ++low;
  }
  return low;
}

// x in units of 2^m, for x a multiple of 2^m, into z.
void in_units(double x, int m, mpz_t z) {
  if (x == 0.0) {
    mpz_set_ui(z, 0);
    return;
  }
  int e;
  const double f = std::frexp(x, &e); // x = f 2^e, |f| in [0.5, 1)
  mpz_set_d(z, std::ldexp(f, 53));    // an integer of at most 53 bits
  const int shift = e - 53 - m;
  if (shift >= 0)
    mpz_mul_2exp(z, z, shift);
  else
    mpz_tdiv_q_2exp(z, z, -shift); // only zero bits go
}

// GMP integers reused from call to call (their allocation was most of the
// time): the coordinates in one unit, the matrix, and scratch.
struct Work {
  mpz_t z[5][3], m[4][4], t[8];
  Work() {
    for (auto &r : z)
      for (auto &x : r)
        mpz_init(x);
    for (auto &r : m)
      for (auto &x : r)
        mpz_init(x);
    for (auto &x : t)
      mpz_init(x);
  }
  ~Work() {
    for (auto &r : z)
      for (auto &x : r)
        mpz_clear(x);
    for (auto &r : m)
      for (auto &x : r)
        mpz_clear(x);
    for (auto &x : t)
      mpz_clear(x);
  }
  // The coordinates of the points p[0..np) (dim each) in one unit, into z.
  void convert(const double *const *p, int np, int dim) {
    int low = INT_MAX;
    for (int i = 0; i < np; ++i)
      for (int k = 0; k < dim; ++k)
        if (p[i][k] != 0.0)
          low = std::min(low, low_bit(p[i][k]));
    for (int i = 0; i < np; ++i)
      for (int k = 0; k < dim; ++k)
        in_units(p[i][k], low == INT_MAX ? 0 : low, z[i][k]);
  }
  // out = a d - b c
  void cross(mpz_t out, const mpz_t a, const mpz_t d, const mpz_t b, const mpz_t c) {
    mpz_mul(t[0], a, d);
    mpz_mul(t[1], b, c);
    mpz_sub(out, t[0], t[1]);
  }
  // det of rows r0, r1, r2 of m, columns c0, c1, c2, into out (uses t[2..5]).
  void det3(mpz_t out, int r0, int r1, int r2, int c0, int c1, int c2) {
    cross(t[2], m[r1][c1], m[r2][c2], m[r1][c2], m[r2][c1]);
    mpz_mul(t[3], m[r0][c0], t[2]);
    cross(t[2], m[r1][c0], m[r2][c2], m[r1][c2], m[r2][c0]);
    mpz_mul(t[4], m[r0][c1], t[2]);
    mpz_sub(t[3], t[3], t[4]);
    cross(t[2], m[r1][c0], m[r2][c1], m[r1][c1], m[r2][c0]);
    mpz_mul(t[4], m[r0][c2], t[2]);
    mpz_add(out, t[3], t[4]);
  }
};

Work &work() {
  static thread_local Work w;
  return w;
}

} // namespace

int orient2d(const double *a, const double *b, const double *c) {
  Work &w = work();
  const double *p[3] = {a, b, c};
  w.convert(p, 3, 2);
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k)
      mpz_sub(w.m[i][k], w.z[i + 1][k], w.z[0][k]);
  w.cross(w.t[5], w.m[0][0], w.m[1][1], w.m[0][1], w.m[1][0]);
  return mpz_sgn(w.t[5]);
}

int incircle(const double *a, const double *b, const double *c, const double *d) {
  Work &w = work();
  const double *p[4] = {a, b, c, d};
  w.convert(p, 4, 2);
  for (int i = 0; i < 3; ++i) {
    mpz_sub(w.m[i][0], w.z[i][0], w.z[3][0]);
    mpz_sub(w.m[i][1], w.z[i][1], w.z[3][1]);
    mpz_mul(w.t[0], w.m[i][0], w.m[i][0]);
    mpz_mul(w.t[1], w.m[i][1], w.m[i][1]);
    mpz_add(w.m[i][2], w.t[0], w.t[1]);
  }
  w.det3(w.t[5], 0, 1, 2, 0, 1, 2);
  return mpz_sgn(w.t[5]);
}

int orient3d(const double *a, const double *b, const double *c, const double *d) {
  Work &w = work();
  const double *p[4] = {a, b, c, d};
  w.convert(p, 4, 3);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      mpz_sub(w.m[i][k], w.z[i + 1][k], w.z[0][k]);
  w.det3(w.t[5], 0, 1, 2, 0, 1, 2);
  return mpz_sgn(w.t[5]);
}

int insphere(const double *a, const double *b, const double *c, const double *d, const double *e) {
  // Rows p - e (p = a, b, c, d) with |p - e|^2 as the fourth column; its
  // determinant is positive when e is inside the sphere of a tetrahedron
  // whose det[b-a; c-a; d-a] is negative, so the sign is flipped.
  Work &w = work();
  const double *p[5] = {a, b, c, d, e};
  w.convert(p, 5, 3);
  for (int i = 0; i < 4; ++i) {
    mpz_set_ui(w.m[i][3], 0);
    for (int k = 0; k < 3; ++k) {
      mpz_sub(w.m[i][k], w.z[i][k], w.z[4][k]);
      mpz_addmul(w.m[i][3], w.m[i][k], w.m[i][k]);
    }
  }
  // Along the first row: sum_j (-1)^j m[0][j] minor_j.
  mpz_set_ui(w.t[6], 0);
  for (int j = 0; j < 4; ++j) {
    int c[3], n = 0;
    for (int k = 0; k < 4; ++k)
      if (k != j)
        c[n++] = k;
    w.det3(w.t[5], 1, 2, 3, c[0], c[1], c[2]);
    mpz_mul(w.t[7], w.m[0][j], w.t[5]);
    if (j % 2 == 0)
      mpz_add(w.t[6], w.t[6], w.t[7]);
    else
      mpz_sub(w.t[6], w.t[6], w.t[7]);
  }
  return -mpz_sgn(w.t[6]);
}

} // namespace oracle
