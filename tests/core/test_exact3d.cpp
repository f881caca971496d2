// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The exact constructions of the 3D code (mesh3d_exact.cpp): a GMP rational
// rounded to the nearest double, ties to even (against IEEE 754 division,
// which rounds so, and against hand-made halfway cases and subnormals), and
// the circumcentre of a tetrahedron rounded so coordinate by coordinate
// (against the test's own rational solve of the bisector planes, on random
// tetrahedra and slivers).  oracle/test_delaunay3d_cgal.cpp compares the
// circumcentres with CGAL's exact construction as well.

#include "mesh3d_delaunay.h"
#include "mesh3d_exact.h"
#include "test_util.h"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using tessera::detail3::nearest_double;

double nearest(const mpq_class &q) { return nearest_double(q.get_mpq_t()); }

// Whether d is the double nearest q, ties to even: no neighbour of d is
// nearer, and at a tie d's significand is even.
bool is_nearest(double d, const mpq_class &q) {
  if (!std::isfinite(d)) return false;
  const mpq_class err = abs(mpq_class(d) - q);
  for (const double n : {std::nextafter(d, -1e308), std::nextafter(d, 1e308)}) {
    if (!std::isfinite(n)) continue;
    const mpq_class e = abs(mpq_class(n) - q);
    if (e < err) return false;
    if (e == err) {
      int ex;
      const double m = std::frexp(d, &ex);
      const long long sig = static_cast<long long>(std::ldexp(m, 53));
      if (d != 0.0 && (sig & 1)) return false;
    }
  }
  return true;
}

TEST(Exact3D, NearestDoubleMatchesIeeeDivision) {
  // a / b for doubles a, b is the correctly rounded quotient.
  testutil::Rng rng(21);
  for (int k = 0; k < 20000; ++k) {
    const double a = std::ldexp(rng.uniform(-1.0, 1.0), rng.below(200) - 100);
    const double b = std::ldexp(rng.uniform(0.5, 1.0), rng.below(200) - 100);
    ASSERT_EQ(nearest(mpq_class(a) / mpq_class(b)), a / b) << a << " / " << b;
  }
  // Subnormal quotients.
  for (int k = 0; k < 2000; ++k) {
    const double a = std::ldexp(rng.uniform(0.5, 1.0), -1000 - rng.below(60));
    const double b = std::ldexp(rng.uniform(0.5, 1.0), 20 + rng.below(40));
    ASSERT_EQ(nearest(mpq_class(a) / mpq_class(b)), a / b) << a << " / " << b;
  }
  EXPECT_EQ(nearest(mpq_class(1, 10)), 0.1);
  EXPECT_EQ(nearest(mpq_class(-1, 3)), -1.0 / 3.0);
  EXPECT_EQ(nearest(mpq_class(0)), 0.0);
}

TEST(Exact3D, NearestDoubleTiesAndLimits) {
  const mpz_class two53 = mpz_class(1) << 53;
  // Integers just above 2^53: spacing 2, ties to the even significand.
  EXPECT_EQ(nearest(mpq_class(two53 + 1)), 9007199254740992.0);
  EXPECT_EQ(nearest(mpq_class(two53 + 3)), 9007199254740996.0);
  EXPECT_EQ(nearest(mpq_class(-(two53 + 3))), -9007199254740996.0);
  // Just off the tie: rounds to the nearer one.
  EXPECT_EQ(nearest(mpq_class(mpz_class(2) * two53 + 3, 2)), 9007199254740994.0);
  // 1 + 2^-53 (a tie) to 1; 1 + 3 2^-54 to 1 + 2^-52 (nearer); 1 - 2^-54 (a
  // tie below 1, spacing 2^-53) to 1.
  EXPECT_EQ(nearest(mpq_class(two53 + 1, two53)), 1.0);
  EXPECT_EQ(nearest(mpq_class(2 * two53 + 3, 2 * two53)), 1.0 + std::ldexp(1.0, -52));
  EXPECT_EQ(nearest(mpq_class(2 * two53 - 1, 2 * two53)), 1.0);
  // The smallest subnormal and half of it (a tie to 0), 3/4 of it (to it).
  const double tiny = std::numeric_limits<double>::denorm_min();
  const mpz_class p1074 = mpz_class(1) << 1074;
  EXPECT_EQ(nearest(mpq_class(1, p1074)), tiny);
  EXPECT_EQ(nearest(mpq_class(1, 2 * p1074)), 0.0);
  EXPECT_EQ(nearest(mpq_class(3, 4 * p1074)), tiny);
  // The largest double, and beyond.
  const double big = std::numeric_limits<double>::max();
  EXPECT_EQ(nearest(mpq_class(big)), big);
  EXPECT_EQ(nearest(mpq_class(mpz_class(1) << 1024)), std::numeric_limits<double>::infinity());
  EXPECT_EQ(nearest(-mpq_class(mpz_class(1) << 1100)), -std::numeric_limits<double>::infinity());
  // mpq_get_d truncates, the reason for this function.
  const mpq_class third(1, 3);
  const mpq_class two_thirds(2, 3);
  EXPECT_TRUE(is_nearest(nearest(two_thirds), two_thirds));
  EXPECT_TRUE(is_nearest(nearest(third), third));
}

// The circumcentre in rationals, independently: c solves
// 2 (p_m - p0) . c = |p_m|^2 - |p0|^2 (m = 1..3), by Cramer's rule.
void rational_centre(const double p[4][3], mpq_class c[3]) {
  mpq_class a[3][3], r[3];
  for (int m = 0; m < 3; ++m) {
    r[m] = 0;
    for (int k = 0; k < 3; ++k) {
      a[m][k] = 2 * (mpq_class(p[m + 1][k]) - mpq_class(p[0][k]));
      r[m] += mpq_class(p[m + 1][k]) * p[m + 1][k] - mpq_class(p[0][k]) * p[0][k];
    }
  }
  auto det = [](const mpq_class x[3][3]) -> mpq_class {
    return x[0][0] * (x[1][1] * x[2][2] - x[1][2] * x[2][1]) -
           x[0][1] * (x[1][0] * x[2][2] - x[1][2] * x[2][0]) +
           x[0][2] * (x[1][0] * x[2][1] - x[1][1] * x[2][0]);
  };
  const mpq_class d = det(a);
  for (int k = 0; k < 3; ++k) {
    mpq_class b[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) b[i][j] = j == k ? r[i] : a[i][j];
    c[k] = det(b) / d;
  }
}

TEST(Exact3D, CircumcentreIsRoundedExactCentre) {
  testutil::Rng rng(22);
  int slivers = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    double p[4][3];
    if (trial % 2 == 0) {
      for (auto &q : p)
        for (double &v : q) v = rng.uniform(-3.0, 3.0);
    } else {
      // A sliver: four points near a circle of the plane z = 0.3 + small
      // slope, lifted off it by 1e-9..1e-14 (co-spherical points given
      // with round-off), at coordinates far from the origin in places.
      const double off = trial % 4 == 1 ? 0.0 : 1e3;
      const double eps = std::ldexp(1.0, -30 - rng.below(17));
      for (int m = 0; m < 4; ++m) {
        const double phi = 1.5707963 * m + rng.uniform(-0.3, 0.3);
        p[m][0] = off + std::cos(phi);
        p[m][1] = off + std::sin(phi);
        p[m][2] = 0.3 + 0.1 * p[m][0] + (m == 3 ? eps : 0.0);
      }
      ++slivers;
    }
    mpq_class exact[3];
    rational_centre(p, exact);
    double c[3];
    tessera::detail3::exact_circumcentre(p[0], p[1], p[2], p[3], c);
    for (int k = 0; k < 3; ++k)
      ASSERT_TRUE(is_nearest(c[k], exact[k])) << "trial " << trial << " coordinate " << k;
  }
  EXPECT_GT(slivers, 1000);
  // A flat tetrahedron has no circumcentre: NaN, not a crash.
  const double f[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  double c[3];
  tessera::detail3::exact_circumcentre(f[0], f[1], f[2], f[3], c);
  EXPECT_TRUE(std::isnan(c[0]) && std::isnan(c[1]) && std::isnan(c[2]));
}

}  // namespace
