// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The fast paths of the polarity step (fix polarity) against their
// plain forms, bit for bit, on random and degenerate input: the torque from
// unit vectors, the rotation of the dipole moments, the tabulated 1/sqrt, the
// counter-based Gaussian numbers.  Plus the plain forms against independent
// formulas (std::sin/std::cos, the normal distribution's moments).
#include "test_util.h"
#include "tessera/counter_rng.h"
#include "tessera/overdamped.h"
#include "tessera/polarity.h"
#include "tessera/tessellation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace {

uint64_t bits(double x) {
  uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

double from_bits(uint64_t b) {
  double x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

// Same value bit for bit (NaN payloads included, -0.0 != +0.0).
#define EXPECT_SAME_BITS(a, b) EXPECT_EQ(bits(a), bits(b)) << (a) << " vs " << (b)

const double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

TEST(FastPaths, TorqueVecEqualsReferenceBitwise) {
  testutil::Rng rng(2024);
  const testutil::Config cfg = testutil::random_config(300, 0.0, 0.0, 17.0, 18.0, 2025, 0.3);
  tessera::Tessellation t = tessera::tessellate_periodic(cfg.box, cfg.points());
  // Degenerate input: zero-length edges (four-fold vertices), one of them in
  // front of a neighbour whose polarity is NaN, -0.0 components.
  int zeroed = 0;
  for (size_t k = 0; k < t.edge_length.size(); k += 7, ++zeroed) t.edge_length[k] = 0.0;
  ASSERT_GT(zeroed, 10);
  std::vector<double> u(2 * t.n_points), vhat(2 * t.n_owned);
  std::vector<unsigned char> has_v(t.n_owned);
  for (int i = 0; i < t.n_points; ++i) {
    const double th = rng.uniform(-4.0, 4.0);
    const double len = i % 11 == 0 ? 1.0 : rng.uniform(0.9, 1.1);
    u[2 * i] = len * std::cos(th);
    u[2 * i + 1] = len * std::sin(th);
    if (i % 13 == 5) u[2 * i + 1] = -0.0;
  }
  const int nan_point = t.cell_neighbor[0];
  u[2 * nan_point] = u[2 * nan_point + 1] = kNaN;  // behind the zero-length edge 0
  for (int c = 0; c < t.n_owned; ++c) {
    if (c == nan_point) continue;
    for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
      if (t.cell_neighbor[k] == nan_point) t.edge_length[k] = 0.0;
  }
  for (int c = 0; c < t.n_owned; ++c) {
    const double psi = rng.uniform(-3.2, 3.2);
    vhat[2 * c] = std::cos(psi);
    vhat[2 * c + 1] = std::sin(psi);
    has_v[c] = c % 4 != 1;
  }
  struct Case {
    double js, jg, phi, jv;
  };
  const Case cases[] = {{1.0, 0, 0, 0}, {0.7, 0.3, -0.4, 0.5}, {-2.0, 1.5, 2.0, 0.0},
                        {0, 1.0, 0.3, 1.0}};
  for (const Case &cs : cases) {
    tessera::PolarityParams p;
    p.J_S = cs.js;
    p.J_G = cs.jg;
    p.phi_G = cs.phi;
    p.J_V = cs.jv;
    std::vector<double> fast(t.n_owned, 7.0), ref(t.n_owned, 8.0);
    tessera::polarity_torque_vec(t, u.data(), 2, p, vhat.data(), has_v.data(), fast.data());
    tessera::polarity_torque_vec_reference(t, u.data(), 2, p, vhat.data(), has_v.data(),
                                           ref.data());
    int finite = 0;
    for (int c = 0; c < t.n_owned; ++c) {
      SCOPED_TRACE("cell " + std::to_string(c) + " J_S " + std::to_string(cs.js));
      EXPECT_SAME_BITS(fast[c], ref[c]);
      finite += std::isfinite(ref[c]);
    }
    // Only the NaN cell's own torque is NaN: the zero-length edges kept it out.
    EXPECT_GE(finite, t.n_owned - 1);
    // The reference is the sum it says it is.
    const int c = 3;
    double sx = 0, sy = 0;
    for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
      if (t.edge_length[k] > 0) {
        sx += u[2 * t.cell_neighbor[k]];
        sy += u[2 * t.cell_neighbor[k] + 1];
      }
    const double nx = u[2 * c], ny = u[2 * c + 1];
    const double th = std::atan2(ny, nx), len = std::hypot(nx, ny);
    double want = cs.js * (nx * sy - ny * sx) -
                  cs.jg * len * len * std::sin(th - cs.phi) * std::cos(th - cs.phi);
    if (has_v[c]) want -= cs.jv * (vhat[2 * c] * ny - vhat[2 * c + 1] * nx);
    EXPECT_NEAR(ref[c], want, 1e-12);
  }
}

TEST(FastPaths, SincosSmallMatchesLibrary) {
  testutil::Rng rng(31);
  for (int k = 0; k < 20000; ++k) {
    const double x = k < 10000 ? rng.uniform(-0.25, 0.25) : rng.uniform(-7.0, 7.0);
    double s, c;
    tessera::sincos_small(x, s, c);
    EXPECT_NEAR(s, std::sin(x), 2.3e-16);
    EXPECT_NEAR(c, std::cos(x), 2.3e-16);
  }
}

TEST(FastPaths, InverseSqrtEqualsDivisionBitwise) {
  // Every tabulated value and the first ones outside the table on both sides.
  for (int64_t k = -300; k <= 300; ++k) {
    const double q = from_bits(bits(1.0) + static_cast<uint64_t>(k));
    EXPECT_SAME_BITS(tessera::inverse_sqrt(q), 1.0 / std::sqrt(q));
  }
  testutil::Rng rng(5);
  for (int k = 0; k < 10000; ++k) {
    const double q = k % 2 ? rng.uniform(0.0, 4.0) : 1.0 + rng.uniform(-1e-13, 1e-13);
    EXPECT_SAME_BITS(tessera::inverse_sqrt(q), 1.0 / std::sqrt(q));
  }
  for (double q : {0.0, -0.0, 1e-300, 4.9e-324, 1e300, std::numeric_limits<double>::infinity()})
    EXPECT_SAME_BITS(tessera::inverse_sqrt(q), 1.0 / std::sqrt(q));
  EXPECT_TRUE(std::isnan(tessera::inverse_sqrt(kNaN)));
  EXPECT_TRUE(std::isnan(tessera::inverse_sqrt(-1.0)));
}

TEST(FastPaths, RotatePolaritiesEqualsReferenceBitwise) {
  testutil::Rng rng(77);
  for (int n : {0, 1, 2, 3, 1001}) {
    SCOPED_TRACE("n " + std::to_string(n));
    std::vector<double> u(2 * n), dth(n), mu(4 * n);
    std::vector<unsigned char> active(n);
    for (int i = 0; i < n; ++i) {
      const double th = rng.uniform(-4.0, 4.0);
      // Unit vectors to round-off, a few not unit at all.
      const double len = i % 17 == 3 ? rng.uniform(0.5, 2.0) : 1.0 + rng.uniform(-4e-16, 4e-16);
      u[2 * i] = len * std::cos(th);
      u[2 * i + 1] = len * std::sin(th);
      // Increments: mostly the noise of a step, some large, the branch edges,
      // zeros of both signs and NaN.
      const int kind = rng.below(20);
      dth[i] = kind < 14   ? 0.14 * rng.uniform(-2.0, 2.0)
               : kind < 17 ? rng.uniform(-6.0, 6.0)
               : kind == 17 ? (i % 2 ? 0.25 : -0.25)
               : kind == 18 ? (i % 2 ? 0.0 : -0.0)
                            : std::nextafter(0.25, 0.0);
      if (i == 7) dth[i] = kNaN;
      // |mu|: 1, other lengths, zero and negative (taken as 1).
      const int lk = rng.below(10);
      const double m = lk < 6 ? 1.0 : lk < 8 ? rng.uniform(0.1, 3.0) : lk == 8 ? 0.0 : -1.0;
      mu[4 * i] = m * u[2 * i];
      mu[4 * i + 1] = m * u[2 * i + 1];
      mu[4 * i + 2] = rng.uniform(-1, 1);
      mu[4 * i + 3] = m;
      active[i] = rng.below(5) != 0;
    }
    for (int with_mask = 0; with_mask < 2; ++with_mask) {
      std::vector<double> fast = mu, ref = mu;
      const unsigned char *act = with_mask ? active.data() : nullptr;
      tessera::rotate_polarities(n, u.data(), dth.data(), fast.data(), act);
      tessera::rotate_polarities_reference(n, u.data(), dth.data(), ref.data(), act);
      for (int k = 0; k < 4 * n; ++k) EXPECT_SAME_BITS(fast[k], ref[k]) << " entry " << k;
      for (int i = 0; i < n; ++i) {
        if (act && !act[i]) {  // untouched
          for (int d = 0; d < 4; ++d) EXPECT_SAME_BITS(ref[4 * i + d], mu[4 * i + d]);
          continue;
        }
        if (i == 7) continue;  // NaN increment
        // The reference against an independent rotation.
        const double m = mu[4 * i + 3] > 0 ? mu[4 * i + 3] : 1.0;
        const double th = std::atan2(u[2 * i + 1], u[2 * i]) + dth[i];
        EXPECT_NEAR(ref[4 * i], m * std::cos(th), 1e-14 * m) << "cell " << i;
        EXPECT_NEAR(ref[4 * i + 1], m * std::sin(th), 1e-14 * m) << "cell " << i;
        EXPECT_EQ(ref[4 * i + 2], 0.0);
        EXPECT_EQ(ref[4 * i + 3], m);
      }
    }
  }
}

TEST(FastPaths, GaussianEqualsReferenceBitwise) {
  // The inline first draw + out-of-line rest against the one-loop definition,
  // over enough (tag, step) pairs to take the wedge and the tail many times.
  namespace r = tessera::rng;
  int rest = 0, tail = 0;
  double sum = 0, sum2 = 0, sum4 = 0;
  long count = 0;
  for (uint64_t seed : {1ULL, 4821ULL, 0x5bd1e995ULL ^ 12345ULL}) {
    const uint64_t mixed = r::mix(seed);
    for (uint64_t tag = 1; tag <= 2000; ++tag)
      for (uint64_t step = 0; step < 300; step += (tag % 3) + 1) {
        const double want = r::gaussian_reference(seed, tag, step);
        EXPECT_SAME_BITS(r::gaussian_mixed(mixed, tag, step), want);
        EXPECT_SAME_BITS(r::gaussian(seed, tag, step), want);
        // Which path: the first draw's layer test.
        r::Stream s{r::mix(r::mix(mixed ^ tag) ^ step), 0};
        const int32_t hz = static_cast<int32_t>(static_cast<uint32_t>(s.next()));
        if (!(std::fabs(static_cast<double>(hz)) < r::ziggurat.kn[hz & 127])) {
          ++rest;
          tail += std::fabs(want) > 3.442619855899;
        }
        sum += want;
        sum2 += want * want;
        sum4 += want * want * want * want;
        ++count;
      }
  }
  EXPECT_GT(rest, 2000);
  EXPECT_GT(tail, 50);
  // Moments of N(0, 1): mean 0, variance 1, fourth moment 3 (about 1.2e6 draws).
  EXPECT_NEAR(sum / count, 0.0, 5 * std::sqrt(1.0 / count));
  EXPECT_NEAR(sum2 / count, 1.0, 5 * std::sqrt(2.0 / count));
  EXPECT_NEAR(sum4 / count, 3.0, 5 * std::sqrt(96.0 / count));
}

// Random positions, velocities and forces of n atoms (3 per atom) and a mask
// in which about three in four atoms are in the moved group (bit 4); with
// signed_zeros some forces are -0.0.
namespace {
struct StepInput {
  std::vector<double> x, v, f;
  std::vector<int> mask;
};
StepInput random_step_input(testutil::Rng &rng, int n, bool signed_zeros) {
  StepInput in{std::vector<double>(3 * n), std::vector<double>(3 * n), std::vector<double>(3 * n),
               std::vector<int>(n)};
  for (int k = 0; k < 3 * n; ++k) {
    in.x[k] = rng.uniform(-50.0, 50.0);
    in.v[k] = rng.uniform(-1.0, 1.0);
    in.f[k] = signed_zeros && k % 29 == 4 ? -0.0 : rng.uniform(-30.0, 30.0);
  }
  for (int i = 0; i < n; ++i) in.mask[i] = rng.below(4) ? 1 | 4 : 1;
  return in;
}
}  // namespace

TEST(FastPaths, OverdampedStepEqualsReferenceBitwise) {
  testutil::Rng rng(404);
  for (int n : {0, 1, 5, 500}) {
    const StepInput in = random_step_input(rng, n, true);
    const std::vector<double> &x = in.x, &v = in.v, &f = in.f;
    const std::vector<int> &mask = in.mask;
    for (int with_mask = 0; with_mask < 2; ++with_mask) {
      std::vector<double> xf = x, vf = v, xr = x, vr = v;
      const int *m = with_mask ? mask.data() : nullptr;
      tessera::overdamped_step_2d(n, xf.data(), vf.data(), f.data(), 0.013, 0.01, m, 4);
      tessera::overdamped_step_2d_reference(n, xr.data(), vr.data(), f.data(), 0.013, 0.01, m, 4);
      for (int k = 0; k < 3 * n; ++k) {
        EXPECT_SAME_BITS(xf[k], xr[k]) << " entry " << k;
        EXPECT_SAME_BITS(vf[k], vr[k]) << " entry " << k;
      }
      for (int i = 0; i < n; ++i) {
        const bool moved = !m || (m[i] & 4);
        for (int d = 0; d < 2; ++d) {
          const long k = 3 * i + d;
          EXPECT_NEAR(xr[k], moved ? x[k] + 0.013 * f[k] : x[k], 1e-12);
          EXPECT_NEAR(vr[k], moved ? 1.3 * f[k] : v[k], 1e-12);
        }
        EXPECT_EQ(vr[3 * i + 2], moved ? 0.0 : v[3 * i + 2]);
        EXPECT_EQ(xr[3 * i + 2], x[3 * i + 2]);
      }
    }
  }
}

// The chatter sums of the same pass (fix brownian's watch for period-two
// steps): against the sums of the analytic step, v_new = drift f / dt, and
// the v the arrays held before it, over the moved atoms; the positions and
// velocities stay those of the pass without sums, bit for bit.
TEST(FastPaths, OverdampedStepWatchSums) {
  testutil::Rng rng(405);
  for (int n : {0, 1, 5, 500}) {
    const StepInput in = random_step_input(rng, n, false);
    const std::vector<double> &x = in.x, &v = in.v, &f = in.f;
    const std::vector<int> &mask = in.mask;
    for (int with_mask = 0; with_mask < 2; ++with_mask) {
      const int *m = with_mask ? mask.data() : nullptr;
      double want[4] = {0.0, 0.0, 0.0, 0.0};
      for (int i = 0; i < n; ++i) {
        if (m && !(m[i] & 4)) continue;
        for (int d = 0; d < 2; ++d) {
          const double vn = 1.3 * f[3 * i + d], vo = v[3 * i + d];
          want[0] += vo * vn;
          want[1] += vo * vo;
          want[2] += vn * vn;
        }
        want[3] += 1.0;
      }
      for (int fast = 0; fast < 2; ++fast) {
        std::vector<double> xw = x, vw = v, xp = x, vp = v;
        double got[4] = {0.5, 0.25, 0.125, 2.0};    // added to, not overwritten
        if (fast) {
          tessera::overdamped_step_2d(n, xw.data(), vw.data(), f.data(), 0.013, 0.01, m, 4, got);
          tessera::overdamped_step_2d(n, xp.data(), vp.data(), f.data(), 0.013, 0.01, m, 4);
        } else {
          tessera::overdamped_step_2d_reference(n, xw.data(), vw.data(), f.data(), 0.013, 0.01,
                                                m, 4, got);
          tessera::overdamped_step_2d_reference(n, xp.data(), vp.data(), f.data(), 0.013, 0.01,
                                                m, 4);
        }
        const double start[4] = {0.5, 0.25, 0.125, 2.0};
        for (int s = 0; s < 4; ++s)
          EXPECT_NEAR(got[s] - start[s], want[s], 1e-11 * (1.0 + std::fabs(want[s])))
              << " sum " << s << " n " << n << " fast " << fast;
        for (int k = 0; k < 3 * n; ++k) {
          EXPECT_SAME_BITS(xw[k], xp[k]) << " entry " << k;
          EXPECT_SAME_BITS(vw[k], vp[k]) << " entry " << k;
        }
      }
    }
  }
}
