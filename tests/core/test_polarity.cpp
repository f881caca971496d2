// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Polarity torque and velocity observables against direct computation on the
// reference tessellation.
#include "reference.h"
#include "test_util.h"
#include "tessera/polarity.h"
#include "tessera/tessellation.h"

#include <gtest/gtest.h>
#include <random>

#include <cmath>

using testutil::Config;

namespace {

const double kPi = 3.14159265358979323846;

struct PolaritySetup {
  Config cfg;
  tessera::Tessellation t;
  std::vector<reftess::RefCell> ref;
};

PolaritySetup make_setup(uint64_t seed, int n) {
  PolaritySetup s;
  s.cfg = testutil::random_config(n, 0.0, 0.0, 7.0, 6.0, seed, 0.3);
  s.t = tessera::tessellate_periodic(s.cfg.box, s.cfg.points());
  s.ref = reftess::voronoi(s.cfg.refbox(), s.cfg.xy);
  return s;
}

}  // namespace

TEST(Polarity, TorqueMatchesDirectSum) {
  const PolaritySetup s = make_setup(1000, 42);
  const int n = s.cfg.n();
  testutil::Rng rng(1001);
  std::vector<double> theta(n), psi(n);
  std::vector<unsigned char> has_psi(n);
  for (int i = 0; i < n; ++i) {
    theta[i] = rng.uniform(0, 2 * kPi);
    psi[i] = rng.uniform(-kPi, kPi);
    has_psi[i] = (i % 5 != 3);
  }
  std::vector<double> theta_all(s.t.n_points);
  for (int k = 0; k < s.t.n_points; ++k) theta_all[k] = theta[s.t.origin[k]];

  struct Case {
    double js, jg, phi, jv;
  };
  const Case cases[] = {{1.0, 0, 0, 0}, {0, 1.0, 0.0, 0}, {0, 0.8, 1.2, 0}, {0, 0, 0, 1.0},
                        {0.7, 0.3, -0.4, 0.5}};
  for (const Case &cs : cases) {
    SCOPED_TRACE("J_S " + std::to_string(cs.js) + " J_G " + std::to_string(cs.jg) + " phi " +
                 std::to_string(cs.phi) + " J_V " + std::to_string(cs.jv));
    tessera::PolarityParams p;
    p.J_S = cs.js;
    p.J_G = cs.jg;
    p.phi_G = cs.phi;
    p.J_V = cs.jv;
    std::vector<double> tau(n, 123.0), tau_nopsi(n, 123.0);
    tessera::polarity_torque(s.t, theta_all.data(), p, psi.data(), has_psi.data(), tau.data());
    tessera::polarity_torque(s.t, theta_all.data(), p, nullptr, nullptr, tau_nopsi.data());
    for (int i = 0; i < n; ++i) {
      double js = 0;
      for (const auto &e : s.ref[i].edges)
        if (e.length > 1e-9) js += std::sin(theta[e.nbr] - theta[i]);
      const double d = theta[i] - cs.phi;
      const double base = cs.js * js - cs.jg * std::sin(d) * std::cos(d);
      const double v = has_psi[i] ? -cs.jv * std::sin(theta[i] - psi[i]) : 0.0;
      EXPECT_NEAR(tau[i], base + v, 1e-12) << "cell " << i;
      EXPECT_NEAR(tau_nopsi[i], base, 1e-12) << "cell " << i << " (no psi)";
    }
  }
}

TEST(Polarity, TorqueHandPicked) {
  // Hexagonal lattice: every cell has 6 neighbours; uniform angle except one
  // cell rotated by 0.5: that cell's alignment torque is -6 J_S sin(0.5) and
  // each of its neighbours gets +J_S sin(0.5).
  Config c;
  const double a = 1.0, dy = std::sqrt(3.0) / 2;
  c.box = tessera::Box::rect(0, 6 * a, 0, 6 * dy);
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      c.xy.push_back((i + 0.5 * (j % 2) + 0.1) * a);
      c.xy.push_back((j + 0.2) * dy);
    }
  const auto t = tessera::tessellate_periodic(c.box, c.points());
  const int n = c.n();
  const int odd = 14;
  std::vector<double> theta_all(t.n_points, 0.3);
  for (int k = 0; k < t.n_points; ++k)
    if (t.origin[k] == odd) theta_all[k] = 0.8;
  tessera::PolarityParams p;
  p.J_S = 2.0;
  std::vector<double> tau(n);
  tessera::polarity_torque(t, theta_all.data(), p, nullptr, nullptr, tau.data());
  int touched = 0;
  for (int i = 0; i < n; ++i) {
    // Neighbours of the odd cell by minimum-image distance a.
    const double d2 = testutil::min_image_dist2(c.box, c.xy[2 * i], c.xy[2 * i + 1],
                                                c.xy[2 * odd], c.xy[2 * odd + 1]);
    double want = 0;
    if (i == odd) {
      want = -6 * 2.0 * std::sin(0.5);
    } else if (std::abs(d2 - a * a) < 1e-9) {
      want = 2.0 * std::sin(0.5);
      ++touched;
    }
    EXPECT_NEAR(tau[i], want, 1e-12) << "cell " << i;
  }
  EXPECT_EQ(touched, 6);
  // Groove only: theta = phi + pi/4 gives -J_G/2.
  tessera::PolarityParams g;
  g.J_G = 1.5;
  g.phi_G = 0.2;
  std::vector<double> th(t.n_points, 0.2 + kPi / 4);
  tessera::polarity_torque(t, th.data(), g, nullptr, nullptr, tau.data());
  for (int i = 0; i < n; ++i) EXPECT_NEAR(tau[i], -0.75, 1e-12);
}

TEST(Polarity, VelocityObservables) {
  const PolaritySetup s = make_setup(1100, 36);
  const int n = s.cfg.n();
  testutil::Rng rng(1101);
  std::vector<double> v(2 * n);
  for (double &x : v) x = rng.uniform(-1, 1);
  // Two cells at rest.
  const int rest[] = {4, 19};
  for (int i : rest) v[2 * i] = v[2 * i + 1] = 0.0;
  // One cell moving exactly along -x (orientation pi) and one along +x (0).
  v[2 * 7] = -0.3;
  v[2 * 7 + 1] = 0.0;
  v[2 * 8] = 2.0;
  v[2 * 8 + 1] = 0.0;
  const int stride = 3;
  std::vector<double> vel_all(stride * s.t.n_points, 99.0);
  for (int k = 0; k < s.t.n_points; ++k) {
    vel_all[stride * k] = v[2 * s.t.origin[k]];
    vel_all[stride * k + 1] = v[2 * s.t.origin[k] + 1];
  }
  std::vector<double> coord(n), orient(n);
  tessera::velocity_observables(s.t, vel_all.data(), stride, coord.data(), orient.data());
  for (int i = 0; i < n; ++i) {
    SCOPED_TRACE("cell " + std::to_string(i));
    const double vi = std::hypot(v[2 * i], v[2 * i + 1]);
    if (vi == 0) {
      EXPECT_EQ(coord[i], 0.0);
      EXPECT_EQ(orient[i], -1.0);
      continue;
    }
    double sum = 0;
    int cnt = 0;
    for (const auto &e : s.ref[i].edges) {
      if (e.length <= 1e-9) continue;
      const double vj = std::hypot(v[2 * e.nbr], v[2 * e.nbr + 1]);
      if (vj == 0) continue;
      sum += (v[2 * i] * v[2 * e.nbr] + v[2 * i + 1] * v[2 * e.nbr + 1]) / (vi * vj);
      ++cnt;
    }
    ASSERT_GT(cnt, 0);
    EXPECT_NEAR(coord[i], sum / cnt, 1e-12);
    EXPECT_GE(coord[i], -1.0);
    EXPECT_LE(coord[i], 1.0);
    EXPECT_NEAR(orient[i], std::acos(v[2 * i] / vi), 1e-12);
    EXPECT_GE(orient[i], 0.0);
    EXPECT_LE(orient[i], kPi);
  }
  EXPECT_NEAR(orient[7], kPi, 1e-15);
  EXPECT_NEAR(orient[8], 0.0, 1e-15);
}

TEST(Polarity, VelocityObservablesUniformFlow) {
  // All cells moving the same way: coordination 1 everywhere.
  const PolaritySetup s = make_setup(1200, 30);
  std::vector<double> vel(2 * s.t.n_points);
  for (int k = 0; k < s.t.n_points; ++k) {
    vel[2 * k] = 0.6;
    vel[2 * k + 1] = -0.8;
  }
  std::vector<double> coord(s.cfg.n()), orient(s.cfg.n());
  tessera::velocity_observables(s.t, vel.data(), 2, coord.data(), orient.data());
  for (int i = 0; i < s.cfg.n(); ++i) {
    EXPECT_NEAR(coord[i], 1.0, 1e-14);
    EXPECT_NEAR(orient[i], std::acos(0.6), 1e-14);
  }
}

namespace {

TEST(Polarity, VectorFormEqualsAngleForm) {
  // polarity_torque_vec (cross products) against polarity_torque (angles).
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(0.0, 6.0), ang(-3.14159, 3.14159);
  std::vector<double> xy;
  for (int i = 0; i < 40; ++i) {
    xy.push_back(u(rng));
    xy.push_back(u(rng));
  }
  const tessera::Tessellation t =
      tessera::tessellate_periodic(tessera::Box::rect(0, 6, 0, 6), tessera::Points{xy.data(), 40, 2});
  std::vector<double> theta(t.n_points), n(3 * t.n_points);
  std::vector<double> own(40);
  for (double &a : own) a = ang(rng);
  for (int p = 0; p < t.n_points; ++p) {
    theta[p] = own[t.origin[p]];
    n[3 * p] = std::cos(theta[p]);
    n[3 * p + 1] = std::sin(theta[p]);
  }
  std::vector<double> psi(40), vhat(80);
  std::vector<unsigned char> has(40, 1);
  for (int i = 0; i < 40; ++i) {
    psi[i] = ang(rng);
    vhat[2 * i] = std::cos(psi[i]);
    vhat[2 * i + 1] = std::sin(psi[i]);
  }
  has[3] = 0;
  const tessera::PolarityParams p{1.3, 0.7, 0.4, 0.9};
  std::vector<double> ta(40), tb(40);
  tessera::polarity_torque(t, theta.data(), p, psi.data(), has.data(), ta.data());
  tessera::polarity_torque_vec(t, n.data(), 3, p, vhat.data(), has.data(), tb.data());
  for (int i = 0; i < 40; ++i) EXPECT_NEAR(ta[i], tb[i], 1e-12) << i;
}

}  // namespace
