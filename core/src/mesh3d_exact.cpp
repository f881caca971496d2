// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Exact constructions of the 3D code: the circumcentre of a tetrahedron in
// GMP rationals, each coordinate rounded to the nearest double.  Only the
// slivers need it (tetrahedra flatter than 1e-6, whose floating-point
// circumcentre loses about eps/flatness of the radius): they are rare, so
// the rationals' cost does not matter.

#include "mesh3d_delaunay.h"
#include "mesh3d_exact.h"

#include <gmpxx.h>

#include <cmath>
#include <limits>

namespace tessera {
namespace detail3 {

double nearest_double(mpq_srcptr q) {
  const int sign = mpq_sgn(q);
  if (sign == 0)
    return 0.0;
  mpz_class num(mpq_numref(q)), den(mpq_denref(q));
  mpz_abs(num.get_mpz_t(), num.get_mpz_t());
  // |q| = num / den with num in [2^(nb-1), 2^nb), den in [2^(db-1), 2^db):
  // |q| / 2^e lies in [2^52, 2^54) for e = nb - db - 53; at most one more
  // halving brings it into [2^52, 2^53), 53 significant bits.  Below the
  // normal range the scale stays at 2^-1074 (the subnormals' spacing) and
  // the quotient has fewer bits.
  const long nb = static_cast<long>(mpz_sizeinbase(num.get_mpz_t(), 2));
  const long db = static_cast<long>(mpz_sizeinbase(den.get_mpz_t(), 2));
  if (nb - db > 1100)
    return sign * std::numeric_limits<double>::infinity();
  long e = nb - db - 53;
  if (e < -1074)
    e = -1074;
  mpz_class quo, rem, div;
  for (int pass = 0; pass < 2; ++pass) {
    mpz_class a = num;
    div = den;
    if (e < 0)
      a <<= static_cast<mp_bitcnt_t>(-e);
    else
      div <<= static_cast<mp_bitcnt_t>(e);
    mpz_fdiv_qr(quo.get_mpz_t(), rem.get_mpz_t(), a.get_mpz_t(), div.get_mpz_t());
    if (mpz_sizeinbase(quo.get_mpz_t(), 2) <= 53)
      break;
    ++e;
  }
  // Round half to even: the remainder against half the divisor.
  rem <<= 1;
  const int c = cmp(rem, div);
  if (c > 0 || (c == 0 && mpz_odd_p(quo.get_mpz_t())))
    ++quo;
  // quo <= 2^53 is a double exactly; the scaling by 2^e is exact unless it
  // overflows (then infinity, as rounding to nearest gives).
  return sign * std::ldexp(quo.get_d(), static_cast<int>(e));
}

void exact_circumcentre(const double *p0, const double *p1, const double *p2, const double *p3,
                        double *c) {
  // c = p0 + (|e1|^2 e2 x e3 + |e2|^2 e3 x e1 + |e3|^2 e1 x e2) / (2 e1 . e2 x e3)
  // with e_m = p_m - p0, every operation exact.
  mpq_class e[3][3];
  const double *p[3] = {p1, p2, p3};
  for (int m = 0; m < 3; ++m)
    for (int k = 0; k < 3; ++k)
      e[m][k] = mpq_class(p[m][k]) - mpq_class(p0[k]);
  auto cross = [](const mpq_class *a, const mpq_class *b, mpq_class *out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
  };
  mpq_class c23[3], c31[3], c12[3];
  cross(e[1], e[2], c23);
  cross(e[2], e[0], c31);
  cross(e[0], e[1], c12);
  const mpq_class det = e[0][0] * c23[0] + e[0][1] * c23[1] + e[0][2] * c23[2];
  if (sgn(det) == 0) {
    for (int k = 0; k < 3; ++k)
      c[k] = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  mpq_class len[3];
  for (int m = 0; m < 3; ++m)
    len[m] = e[m][0] * e[m][0] + e[m][1] * e[m][1] + e[m][2] * e[m][2];
  const mpq_class inv = 1 / (2 * det);
  for (int k = 0; k < 3; ++k) {
    const mpq_class x =
        mpq_class(p0[k]) + (len[0] * c23[k] + len[1] * c31[k] + len[2] * c12[k]) * inv;
    c[k] = nearest_double(x.get_mpq_t());
  }
}

} // namespace detail3
} // namespace tessera
