// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The flip sweep's circumsphere shortcut (mesh3d_detail.h): when it says a
// point lies clearly outside a tetrahedron's circumsphere, the exact
// answer must say outside too.  The oracle is exact integer arithmetic:
// points on an integer grid (scaled by a power of two and shifted by a large
// power of two, so the doubles are exact), where |e - c|^2 - r^2 has the sign
// of D |w|^2 - w . N (c = p0 + N / (2 D), w = e - p0) in 128-bit integers.
// Grids give many exact ties (co-spherical points): the shortcut must never
// decide them.
#include "mesh3d_detail.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

namespace {

using I = __int128;

// Sign of |e - c|^2 - r^2 for the circumsphere of p0..p3 (integer points).
int exact_side(const std::array<long, 3> *p, const std::array<long, 3> &e) {
  I a[3], b[3], d[3], w[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = p[1][k] - p[0][k];
    b[k] = p[2][k] - p[0][k];
    d[k] = p[3][k] - p[0][k];
    w[k] = e[k] - p[0][k];
  }
  const I la = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  const I lb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
  const I ld = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const I bxd[3] = {b[1] * d[2] - b[2] * d[1], b[2] * d[0] - b[0] * d[2],
                    b[0] * d[1] - b[1] * d[0]};
  const I dxa[3] = {d[1] * a[2] - d[2] * a[1], d[2] * a[0] - d[0] * a[2],
                    d[0] * a[1] - d[1] * a[0]};
  const I axb[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0]};
  const I det = a[0] * bxd[0] + a[1] * bxd[1] + a[2] * bxd[2];
  I wn = 0;
  for (int k = 0; k < 3; ++k)
    wn += w[k] * (la * bxd[k] + lb * dxa[k] + ld * axb[k]);
  const I s = det * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) - wn; // times det
  const int sign = s > 0 ? 1 : (s < 0 ? -1 : 0);
  return det > 0 ? sign : -sign;
}

struct Counts {
  long decided = 0, outside = 0, ties = 0, samples = 0;
};

// m random tetrahedra and points on a grid of side 2 range + 1, scaled by
// `scale` and shifted by `shift`.
Counts check(unsigned seed, long range, double scale, double shift, int m) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<long> g(-range, range);
  Counts c;
  for (int s = 0; s < m; ++s) {
    std::array<long, 3> p[4], e;
    for (auto &q : p)
      for (long &x : q)
        x = g(rng);
    for (long &x : e)
      x = g(rng);
    // Every fourth sample: e = p0 + p1 - p2, the fourth corner of the
    // parallelogram on p2, p0, p1, which on a grid often lies on the sphere.
    if (s % 4 == 3)
      for (int k = 0; k < 3; ++k)
        e[k] = p[0][k] + p[1][k] - p[2][k];
    double x[4][3], xe[3];
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k)
        x[i][k] = shift + scale * static_cast<double>(p[i][k]);
    for (int k = 0; k < 3; ++k)
      xe[k] = shift + scale * static_cast<double>(e[k]);
    double v[3], r2;
    if (!tessera::detail3::circumsphere(x[0], x[1], x[2], x[3], v, r2))
      continue;
    ++c.samples;
    const int side = exact_side(p, e);
    c.outside += side > 0;
    c.ties += side == 0;
    if (tessera::detail3::clearly_outside(x[0], v, r2, xe)) {
      ++c.decided;
      EXPECT_GT(side, 0) << "seed " << seed << " sample " << s << ": decided outside, exact "
                         << side;
    }
  }
  return c;
}

TEST(Mesh3Sphere, ClearlyOutsideAgreesWithExactArithmetic) {
  // Coarse grids (many ties and near-ties), fine grids, tiny and large
  // scales, coordinates near 2^20 and 2^30.
  const struct {
    long range;
    double scale, shift;
  } cases[] = {{2, 1.0, 0.0},           {3, 0.5, 0.0},           {8, 1.0, 1048576.0},
               {64, 1.0 / 64, 0.0},     {1024, 1.0 / 1024, 0.0}, {1024, 1.0 / 1024, 1073741824.0},
               {5, 1.0 / 4096, 1024.0}, {200, 0.125, -65536.0}};
  long decided = 0, outside = 0, ties = 0;
  unsigned seed = 1;
  for (const auto &k : cases) {
    const Counts c = check(seed++, k.range, k.scale, k.shift, 20000);
    decided += c.decided;
    outside += c.outside;
    ties += c.ties;
  }
  // Not vacuous: most points outside are decided, and there were ties.
  EXPECT_GT(ties, 100);
  EXPECT_GT(decided, outside / 2);
  std::printf("%ld outside (%ld decided by the shortcut), %ld exact ties\n", outside, decided,
              ties);
}

} // namespace
