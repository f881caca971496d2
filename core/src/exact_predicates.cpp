// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The exact predicates of exact_predicates.h in GMP rationals: every double
// is a rational, so the determinants are computed without rounding.  Slow
// (a few microseconds a call), and called only where a builder's filter
// cannot decide.  (A placeholder for adaptive-precision floating point.)

#include "exact_predicates.h"

#include <gmpxx.h>

namespace tessera::exact {

namespace {

int sign(const mpq_class &q) { return sgn(q); }

mpq_class det3(const mpq_class m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

} // namespace

int orient2d(const double *a, const double *b, const double *c) {
  const mpq_class ax(a[0]), ay(a[1]);
  const mpq_class bx = mpq_class(b[0]) - ax, by = mpq_class(b[1]) - ay;
  const mpq_class cx = mpq_class(c[0]) - ax, cy = mpq_class(c[1]) - ay;
  return sign(bx * cy - by * cx);
}

int incircle(const double *a, const double *b, const double *c, const double *d) {
  const mpq_class dx(d[0]), dy(d[1]);
  const double *p[3] = {a, b, c};
  mpq_class m[3][3];
  for (int i = 0; i < 3; ++i) {
    m[i][0] = mpq_class(p[i][0]) - dx;
    m[i][1] = mpq_class(p[i][1]) - dy;
    m[i][2] = m[i][0] * m[i][0] + m[i][1] * m[i][1];
  }
  return sign(det3(m));
}

int orient3d(const double *a, const double *b, const double *c, const double *d) {
  const double *p[3] = {b, c, d};
  mpq_class m[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) m[i][k] = mpq_class(p[i][k]) - mpq_class(a[k]);
  return sign(det3(m));
}

int insphere(const double *a, const double *b, const double *c, const double *d, const double *e) {
  // Rows p - e (p = a, b, c, d) with |p - e|^2 as the fourth column; its
  // determinant is positive when e is inside the sphere of a tetrahedron
  // whose det[b-a; c-a; d-a] is negative, so the sign is flipped.
  const double *p[4] = {a, b, c, d};
  mpq_class m[4][4];
  for (int i = 0; i < 4; ++i) {
    m[i][3] = 0;
    for (int k = 0; k < 3; ++k) {
      m[i][k] = mpq_class(p[i][k]) - mpq_class(e[k]);
      m[i][3] += m[i][k] * m[i][k];
    }
  }
  mpq_class det = 0;
  for (int j = 0; j < 4; ++j) {
    mpq_class minor[3][3];
    for (int i = 1; i < 4; ++i)
      for (int k = 0, kk = 0; k < 4; ++k)
        if (k != j) minor[i - 1][kk++] = m[i][k];
    const mpq_class term = m[0][j] * det3(minor);
    if (j % 2 == 0)
      det += term;
    else
      det -= term;
  }
  return -sign(det);
}

} // namespace tessera::exact
