// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The adaptive-precision exact predicates (core/src/exact_predicates.h)
// against GMP rational arithmetic (exact_oracle.h), on seeded inputs of
// every kind the builders can pass: random points at any scale, points on a
// line / circle / plane / sphere rounded to doubles and moved by a few ulps
// (where the floating-point stages must hand over to the exact ones),
// integer grids and lattice points on circles and spheres (exact ties: the
// answer is 0), scaled by powers of two up to double's limits, far from the
// origin, at the input limits of doc/model.md (coordinates up to 1e100,
// separations down to 1e-100 and 1e-10 of the coordinates), and with
// coordinates whose exponents span hundreds of orders of magnitude.  One
// table of generators, one driver; about 1.2e6 cases.  The permutation rules
// (a transposition flips the sign) are checked on the way.

#include "exact_oracle.h"
#include "exact_predicates.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace {

using testutil::Rng;

enum Pred { O2, IC, O3, IS };
const int kPoints[] = {3, 4, 4, 5};
const int kDim[] = {2, 2, 3, 3};
const char *kName[] = {"orient2d", "incircle", "orient3d", "insphere"};

struct Pts {
  double p[5][3] = {};
};

int core(Pred k, const Pts &q) {
  switch (k) {
  case O2:
    return tessera::exact::orient2d(q.p[0], q.p[1], q.p[2]);
  case IC:
    return tessera::exact::incircle(q.p[0], q.p[1], q.p[2], q.p[3]);
  case O3:
    return tessera::exact::orient3d(q.p[0], q.p[1], q.p[2], q.p[3]);
  default:
    return tessera::exact::insphere(q.p[0], q.p[1], q.p[2], q.p[3], q.p[4]);
  }
}

int slow(Pred k, const Pts &q) {
  switch (k) {
  case O2:
    return oracle::orient2d(q.p[0], q.p[1], q.p[2]);
  case IC:
    return oracle::incircle(q.p[0], q.p[1], q.p[2], q.p[3]);
  case O3:
    return oracle::orient3d(q.p[0], q.p[1], q.p[2], q.p[3]);
  default:
    return oracle::insphere(q.p[0], q.p[1], q.p[2], q.p[3], q.p[4]);
  }
}

// x moved by k ulps.
double ulps(double x, int k) {
  for (; k > 0; --k)
    x = std::nextafter(x, HUGE_VAL);
  for (; k < 0; ++k)
    x = std::nextafter(x, -HUGE_VAL);
  return x;
}

// Every coordinate moved by up to `spread` ulps (none, sometimes).
void jitter(Rng &rng, Pred k, Pts &q, int spread) {
  if (rng.below(4) == 0)
    return;
  for (int i = 0; i < kPoints[k]; ++i)
    for (int d = 0; d < kDim[k]; ++d)
      if (rng.below(2))
        q.p[i][d] = ulps(q.p[i][d], rng.below(2 * spread + 1) - spread);
}

// A scale 2^e with e uniform in [lo, hi].
double pow2(Rng &rng, int lo, int hi) {
  return std::ldexp(1.0, lo + rng.below(hi - lo + 1));
}

// A random unit vector in dim dimensions.
void unit(Rng &rng, int dim, double *u) {
  double n = 0.0;
  do {
    n = 0.0;
    for (int d = 0; d < dim; ++d) {
      u[d] = rng.uniform(-1.0, 1.0);
      n += u[d] * u[d];
    }
  } while (n < 1e-4 || n > 1.0);
  for (int d = 0; d < dim; ++d)
    u[d] /= std::sqrt(n);
}

// A size and an offset from the origin: ordinary, far from the origin,
// huge, tiny, and at the input limits (coordinates up to 1e100, points
// 1e-10 of them apart; points 1e-100 apart).
void place(Rng &rng, double &size, double &offset) {
  switch (rng.below(6)) {
  case 0:
    size = 1.0;
    offset = 0.0;
    break;
  case 1:
    size = pow2(rng, -40, 40);
    offset = size * pow2(rng, 0, 40);
    break;
  case 2:
    size = pow2(rng, -300, 300);
    offset = size * rng.uniform(0.0, 4.0);
    break;
  case 3:
    size = 1e90;
    offset = 1e100;
    break;
  case 4:
    size = 1e-100;
    offset = rng.below(2) ? 0.0 : 1e-90;
    break;
  default:
    size = 1e-10 * 1e3;
    offset = 1e3;
    break;
  }
}

// Random points in a cube of side `size` at `offset`.
void gen_random(Rng &rng, Pred k, Pts &q) {
  double size, offset;
  place(rng, size, offset);
  for (int i = 0; i < kPoints[k]; ++i)
    for (int d = 0; d < kDim[k]; ++d)
      q.p[i][d] = offset + size * rng.uniform(-1.0, 1.0);
}

// Points on the degenerate set of the predicate (a line, a circle, a plane,
// a sphere), rounded to doubles and then moved by a few ulps: the cases the
// floating-point stages cannot decide.  For the in-circle and in-sphere
// tests the first points are on the circle or sphere and the last one on it
// too, or a point of the first ones moved by a few ulps.
void gen_near(Rng &rng, Pred k, Pts &q) {
  double size, offset;
  place(rng, size, offset);
  const int dim = kDim[k];
  double c[3], u[3], w[3];
  for (int d = 0; d < dim; ++d)
    c[d] = offset + size * rng.uniform(-1.0, 1.0);
  unit(rng, dim, u);
  unit(rng, dim, w);
  for (int i = 0; i < kPoints[k]; ++i) {
    if (k == O2 || k == O3) { // on the line c + s u, or the plane c + s u + t w
      const double s = size * rng.uniform(-2.0, 2.0), t = size * rng.uniform(-2.0, 2.0);
      for (int d = 0; d < dim; ++d)
        q.p[i][d] = c[d] + s * u[d] + (k == O3 ? t * w[d] : 0.0);
    } else { // on the circle or sphere of radius size round c
      double v[3];
      unit(rng, dim, v);
      for (int d = 0; d < dim; ++d)
        q.p[i][d] = c[d] + size * v[d];
    }
  }
  if (rng.below(3) == 0) { // one point a copy of another
    const int i = rng.below(kPoints[k]), j = rng.below(kPoints[k]);
    for (int d = 0; d < dim; ++d)
      q.p[i][d] = q.p[j][d];
  }
  jitter(rng, k, q, 3);
}

// Small integers (many exact ties), scaled by 2^s and shifted by an
// integer multiple of a power of two, both exact.
void gen_grid(Rng &rng, Pred k, Pts &q) {
  const double s = pow2(rng, -1000, 900), shift = std::ldexp(rng.below(5) - 2.0, rng.below(40));
  for (int i = 0; i < kPoints[k]; ++i)
    for (int d = 0; d < kDim[k]; ++d)
      q.p[i][d] = s * ((rng.below(9) - 4) + shift);
  jitter(rng, k, q, 1);
}

// Exactly degenerate: collinear / coplanar integer points, lattice points
// on one circle (x^2 + y^2 = 65) or one sphere (x^2 + y^2 + z^2 = 9, 29),
// round an integer centre, scaled by a power of two.  The answer is 0.
struct LatticeSet {
  std::vector<std::array<int, 3>> circle, sphere;
  LatticeSet() {
    for (int x = -9; x <= 9; ++x)
      for (int y = -9; y <= 9; ++y) {
        if (x * x + y * y == 65)
          circle.push_back({x, y, 0});
        for (int z = -9; z <= 9; ++z)
          if (x * x + y * y + z * z == 29)
            sphere.push_back({x, y, z});
      }
  }
};
const LatticeSet &lattice() {
  static const LatticeSet s;
  return s;
}

void gen_degenerate(Rng &rng, Pred k, Pts &q) {
  const double s = pow2(rng, -1000, 900);
  const int dim = kDim[k];
  int c[3], u[3], w[3];
  for (int d = 0; d < 3; ++d) {
    c[d] = rng.below(2001) - 1000;
    u[d] = rng.below(7) - 3;
    w[d] = rng.below(7) - 3;
  }
  for (int i = 0; i < kPoints[k]; ++i) {
    int v[3];
    if (k == O2 || k == O3) {
      const int a = rng.below(11) - 5, b = k == O3 ? rng.below(11) - 5 : 0;
      for (int d = 0; d < 3; ++d)
        v[d] = c[d] + a * u[d] + b * w[d];
    } else {
      const auto &set = k == IC ? lattice().circle : lattice().sphere;
      const auto &p = set[rng.below(static_cast<int>(set.size()))];
      for (int d = 0; d < 3; ++d)
        v[d] = c[d] + p[d];
    }
    for (int d = 0; d < dim; ++d)
      q.p[i][d] = s * v[d];
  }
}

// Coordinates of wildly different exponents in one call (a coordinate of
// 1e-300 next to ones of 1 or 1e100): beyond what scaled expansions hold,
// the big-integer path.  Sometimes near a degenerate set too.
void gen_wide(Rng &rng, Pred k, Pts &q) {
  if (rng.below(2))
    gen_near(rng, k, q);
  else
    gen_degenerate(rng, k, q);
  const int n = 1 + rng.below(3);
  for (int j = 0; j < n; ++j) {
    const int i = rng.below(kPoints[k]), d = rng.below(kDim[k]);
    const double tiny = pow2(rng, -1074, -700) * (rng.below(2) ? 1 : -1);
    switch (rng.below(3)) {
    case 0:
      q.p[i][d] = tiny;
      break;
    case 1:
      q.p[i][d] += tiny;
      break;
    default:
      q.p[i][d] = pow2(rng, 200, 1000) * rng.uniform(-1.0, 1.0);
      break;
    }
  }
}

std::string describe(Pred k, const Pts &q) {
  std::string s = kName[k];
  char buf[64];
  for (int i = 0; i < kPoints[k]; ++i) {
    s += " (";
    for (int d = 0; d < kDim[k]; ++d) {
      std::snprintf(buf, sizeof buf, "%s%a", d ? ", " : "", q.p[i][d]);
      s += buf;
    }
    s += ")";
  }
  return s;
}

struct Gen {
  const char *name;
  void (*make)(Rng &, Pred, Pts &);
  long count[4]; // per predicate
  bool all_zero; // the exact answer is 0
};

const Gen kGens[] = {
    {"random", gen_random, {60000, 60000, 40000, 20000}, false},
    {"near-degenerate", gen_near, {150000, 150000, 100000, 50000}, false},
    {"integer grid", gen_grid, {60000, 60000, 40000, 20000}, false},
    {"exactly degenerate", gen_degenerate, {30000, 30000, 20000, 10000}, true},
    {"wide exponents", gen_wide, {20000, 20000, 20000, 10000}, false},
};

TEST(ExactPredicates, AgreeWithRationalArithmetic) {
  for (const Gen &g : kGens) {
    for (Pred k : {O2, IC, O3, IS}) {
      Rng rng(1000 * (&g - kGens) + k + 1);
      long failures = 0, zeros = 0;
      for (long n = 0; n < g.count[k]; ++n) {
        Pts q;
        g.make(rng, k, q);
        const int want = slow(k, q), got = core(k, q);
        zeros += want == 0;
        if (got != want || (g.all_zero && want != 0)) {
          if (++failures <= 5)
            ADD_FAILURE() << g.name << ": " << describe(k, q) << ": core " << got << ", GMP "
                          << want;
          continue;
        }
        // A transposition of two points flips the sign.
        if (n % 8 == 0) {
          Pts r = q;
          const int i = rng.below(kPoints[k]), j = (i + 1 + rng.below(kPoints[k] - 1)) % kPoints[k];
          for (int d = 0; d < 3; ++d)
            std::swap(r.p[i][d], r.p[j][d]);
          if (core(k, r) != -want && ++failures <= 5)
            ADD_FAILURE() << g.name << ": swapping points " << i << " and " << j << " of "
                          << describe(k, q) << " gave " << core(k, r) << ", want " << -want;
        }
      }
      std::printf("%-20s %-9s %7ld cases, %6ld exactly degenerate\n", g.name, kName[k], g.count[k],
                  zeros);
      EXPECT_EQ(failures, 0) << g.name << " " << kName[k];
    }
  }
}

// The conventions of exact_predicates.h on hand-made cases.
TEST(ExactPredicates, Conventions) {
  const double a[2] = {0, 0}, b[2] = {1, 0}, c[2] = {0, 1}, in[2] = {0.5, 0.5}, on[2] = {1, 1},
               out[2] = {2, 2};
  EXPECT_EQ(tessera::exact::orient2d(a, b, c), 1);
  EXPECT_EQ(tessera::exact::orient2d(a, c, b), -1);
  EXPECT_EQ(tessera::exact::orient2d(a, b, out + 0), 1);
  const double l[2] = {3, 0};
  EXPECT_EQ(tessera::exact::orient2d(a, b, l), 0);
  EXPECT_EQ(tessera::exact::incircle(a, b, c, in), 1);
  EXPECT_EQ(tessera::exact::incircle(a, b, c, on), 0);
  EXPECT_EQ(tessera::exact::incircle(a, b, c, out), -1);
  EXPECT_EQ(tessera::exact::incircle(a, c, b, in), -1);
  const double A[3] = {0, 0, 0}, B[3] = {1, 0, 0}, C[3] = {0, 1, 0}, D[3] = {0, 0, 1};
  const double I[3] = {0.25, 0.25, 0.25}, O[3] = {2, 2, 2}, S[3] = {1, 1, 1};
  EXPECT_EQ(tessera::exact::orient3d(A, B, C, D), 1);
  EXPECT_EQ(tessera::exact::orient3d(A, C, B, D), -1);
  EXPECT_EQ(tessera::exact::orient3d(A, B, C, O + 0), 1);
  const double P[3] = {5, 7, 0};
  EXPECT_EQ(tessera::exact::orient3d(A, B, C, P), 0);
  EXPECT_EQ(tessera::exact::insphere(A, B, C, D, I), 1);
  EXPECT_EQ(tessera::exact::insphere(A, B, C, D, S), 0);
  EXPECT_EQ(tessera::exact::insphere(A, B, C, D, O), -1);
  EXPECT_EQ(tessera::exact::insphere(A, C, B, D, I), -1);
}

} // namespace
