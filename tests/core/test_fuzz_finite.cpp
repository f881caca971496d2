// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The finite Voronoi model (cells cut by discs of radius r) on degenerate and
// extreme input: first the reproducers of specific failures (the neighbour
// grid at extreme length ratios, nearly coincident centres, energy
// overflow), then seeded randomized generators (FiniteFuzz.*) in the style
// of test_fuzz.cpp: clusters, tangent pairs at 2r(1 +- 1e-12), collinear
// rows, far-apart groups, extreme radii.
//
// The rule checked: every input gives finite results that are right, or a
// tessera::Error with a message whose reason the input really has.
// "Right" is checked against properties of the exact answer, computed
// independently:
//   * energy, virial and forces finite;
//   * the cells tile the union of the discs: the sum of the cell areas
//     equals the area of the union, computed here from the uncovered arcs of
//     every circle (Green's theorem; no clipping, no Voronoi cells);
//   * forces sum to zero (translation invariance);
//   * on a sample, forces equal central differences of the energy where the
//     energy is smooth within the step (both one-sided differences agree).
// On failure the input is printed (generator, seed, radius, points).

#include "test_util.h"
#include "tessera/energy.h"
#include "tessera/finite.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

using testutil::Rng;
constexpr double kPi = 3.141592653589793238462643383279502884;
constexpr double kEps = 2.220446049250313e-16;

// Area of the union of discs of radius r around the points, from the arcs of
// each circle that no other disc covers: area = 1/2 oint (x dy - y dx).
// Coordinates relative to the first point (keeps far-away groups exact).
double union_area(const std::vector<double> &xy, double r) {
  const int n = static_cast<int>(xy.size() / 2);
  if (n == 0) return 0.0;
  const double ox = xy[0], oy = xy[1];
  double twice = 0.0;
  std::vector<std::pair<double, double>> cov;
  for (int i = 0; i < n; ++i) {
    const double cx = xy[2 * i] - ox, cy = xy[2 * i + 1] - oy;
    cov.clear();
    bool inside_other = false;
    for (int j = 0; j < n && !inside_other; ++j) {
      if (j == i) continue;
      const double dx = xy[2 * j] - xy[2 * i], dy = xy[2 * j + 1] - xy[2 * i + 1];
      const double d = std::hypot(dx, dy);
      if (d >= 2 * r) continue;
      if (d == 0.0) {
        inside_other = j < i;  // a duplicate: only the first one counts
        continue;
      }
      const double phi = std::atan2(dy, dx), a = std::acos(d / (2 * r));
      double lo = phi - a, hi = phi + a;
      // to [0, 2 pi)
      while (lo < 0) {
        lo += 2 * kPi;
        hi += 2 * kPi;
      }
      while (lo >= 2 * kPi) {
        lo -= 2 * kPi;
        hi -= 2 * kPi;
      }
      if (hi > 2 * kPi) {
        cov.push_back({lo, 2 * kPi});
        cov.push_back({0.0, hi - 2 * kPi});
      } else {
        cov.push_back({lo, hi});
      }
    }
    if (inside_other) continue;
    std::sort(cov.begin(), cov.end());
    // Uncovered arcs between merged covered intervals.
    double at = 0.0;
    auto arc = [&](double a, double b) {
      if (b <= a) return;
      twice += r * cx * (std::sin(b) - std::sin(a)) - r * cy * (std::cos(b) - std::cos(a)) +
               r * r * (b - a);
    };
    for (const auto &iv : cov) {
      if (iv.first > at) arc(at, iv.first);
      at = std::max(at, iv.second);
    }
    arc(at, 2 * kPi);
  }
  return 0.5 * twice;
}

struct FiniteInput {
  double r = 1.0;
  std::vector<double> xy;
  std::vector<int> type;
  tessera::Model model{2};
  std::vector<double> free_tension{0.0, 0.0};
  int n() const { return static_cast<int>(xy.size() / 2); }
  tessera::Points points() const { return tessera::Points{xy.data(), n(), 2}; }
};

std::string reproducer(const FiniteInput &in) {
  std::ostringstream s;
  s.precision(17);
  s << "r " << in.r << ", " << in.n() << " points (x y type):\n";
  for (int i = 0; i < in.n(); ++i)
    s << "  " << in.xy[2 * i] << ' ' << in.xy[2 * i + 1] << ' ' << in.type[i] << '\n';
  s << "types (K A0 Gamma F):";
  for (int t = 0; t < 2; ++t)
    s << " (" << in.model.types[t].K << ' ' << in.model.types[t].A0 << ' '
      << in.model.types[t].Gamma << ' ' << in.free_tension[t] << ')';
  s << " lambda " << in.model.lambda_of(0, 0) << ' ' << in.model.lambda_of(0, 1) << ' '
    << in.model.lambda_of(1, 1) << '\n';
  return s.str();
}

double energy(const FiniteInput &in) {
  const tessera::FiniteTessellation t = tessera::finite_tessellate(in.points(), in.n(), in.r);
  return tessera::finite_energy(t, in.type.data(), in.model, in.free_tension.data());
}

// Parameters in units of r (so that energies are of order 1 for r ~ 1).
void set_model(Rng &rng, FiniteInput &in) {
  const double a = kPi * in.r * in.r;
  for (auto &t : in.model.types) {
    t.K = rng.uniform(0.5, 1.5) / (a * a);
    t.A0 = a * rng.uniform(0.5, 1.0);
    t.Gamma = rng.uniform(0.0, 0.2) / (in.r * in.r);
  }
  in.model.set_lambda(0, 0, -rng.uniform(0.0, 1.0) / in.r);
  in.model.set_lambda(1, 1, -rng.uniform(0.0, 1.0) / in.r);
  in.model.set_lambda(0, 1, rng.uniform(0.0, 0.5) / in.r);
  for (double &f : in.free_tension) f = rng.uniform(0.0, 0.5) / in.r;
  in.type.resize(in.n());
  for (int &t : in.type) t = rng.below(2);
}

}  // namespace

// ---------------------------------------------------------------------------
// Reproducers.

// Cells at 0 and 1e-14 with r = 1e-14 and a third cell 1e6 away: the grid
// of spacing 2 r had 5e19 bins along x, beyond long long (the conversion is
// undefined; in practice the first two cells lost their contact).  Each of
// the pair is the disc less the cap beyond their bisector.
TEST(FiniteReliability, ExtremeLengthRatioKeepsContacts) {
  for (double far : {1e6, -1e6, 1e300, -1e100}) {
    const double r = 1e-14, d = 1e-14;
    std::vector<double> xy = {0.0, 0.0, d, 0.0, far, 0.5 * far};
    if (std::fabs(far) > 1e100) continue;  // beyond the coordinate limit: refused, below
    const tessera::FiniteTessellation t =
        tessera::finite_tessellate(tessera::Points{xy.data(), 3, 2}, 3, r);
    const double ca = d / (2 * r), alpha = std::acos(ca);
    const double area = r * r * (kPi - alpha + ca * std::sqrt(1 - ca * ca));
    for (int c = 0; c < 2; ++c) {
      EXPECT_NEAR(t.area[c], area, 1e-12 * area) << "far " << far << " cell " << c;
      ASSERT_EQ(t.cell_size(c), 2) << "far " << far;
    }
    EXPECT_NEAR(t.area[2], kPi * r * r, 1e-14 * r * r);
  }
  std::vector<double> xy = {0.0, 0.0, 1e-14, 0.0, 1e300, 0.0};
  EXPECT_THROW(tessera::finite_tessellate(tessera::Points{xy.data(), 3, 2}, 3, 1e-14),
               tessera::Error);
  // Points spread over the whole range allowed (41 on a diagonal 4.9e98
  // apart) and one at (1.5, 0): every bin index is clamped, and the pair at
  // the origin keeps its contact.
  std::vector<double> many;
  for (int k = -20; k <= 20; ++k) many.insert(many.end(), {k * 4.9e98, -k * 4.9e98});
  many.insert(many.end(), {1.5, 0.0});
  const tessera::FiniteTessellation t =
      tessera::finite_tessellate(tessera::Points{many.data(), 42, 2}, 42, 1.0);
  EXPECT_EQ(t.cell_size(20), 2);
  EXPECT_EQ(t.cell_size(41), 2);
  EXPECT_EQ(t.cell_size(0), 1);
}

// Nearly coincident centres are refused as in the confluent model, with
// both points named; the threshold scales with the pair's own magnitude.
TEST(FiniteReliability, NearlyCoincidentCentresAreRefused) {
  for (double x0 : {0.0, 1.0, 1e7}) {
    const double mag = std::max(std::fabs(x0), 1e-100);
    const double lim = std::max(1e-10 * mag, 1e-100);
    std::vector<double> xy = {x0, 0.5, x0 + 0.3 * lim, 0.5, x0 + 1.0, 0.5};
    const long ids[3] = {11, 12, 13};
    if (x0 == 0.0) {
      xy = {0.0, 0.0, 3e-101, 0.0, 1.0, 0.0};
    }
    try {
      tessera::finite_tessellate(tessera::Points{xy.data(), 3, 2}, 3, 1.0, ids);
      ADD_FAILURE() << "accepted centres " << xy[0] << " and " << xy[2];
    } catch (const tessera::Error &e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("nearly coincide"), std::string::npos) << m;
      EXPECT_NE(m.find("id 11"), std::string::npos) << m;
      EXPECT_NE(m.find("id 12"), std::string::npos) << m;
    }
  }
  // Just above the limit (and a pair at 0 and 1e-14, r = 1e-14): accepted.
  std::vector<double> ok = {1e7, 0.0, 1e7 + 3e-3, 0.0};
  EXPECT_NO_THROW(tessera::finite_tessellate(tessera::Points{ok.data(), 2, 2}, 2, 1.0));
  ok = {0.0, 0.0, 1e-14, 0.0};
  EXPECT_NO_THROW(tessera::finite_tessellate(tessera::Points{ok.data(), 2, 2}, 2, 1e-14));
  // Out-of-range radii.
  EXPECT_THROW(tessera::finite_tessellate(tessera::Points{ok.data(), 2, 2}, 2, 1e-150),
               tessera::Error);
  EXPECT_THROW(tessera::finite_tessellate(tessera::Points{ok.data(), 2, 2}, 2, 1e150),
               tessera::Error);
}

// Energies beyond double's range: an Error that names the cell and the
// value, not inf or NaN.
TEST(FiniteReliability, EnergyOverflowIsAnError) {
  std::vector<double> xy = {0.0, 0.0, 1.2, 0.0, 5.0, 0.0};
  const int type[3] = {0, 0, 0};
  tessera::Model m(1);
  m.types[0].K = 1e308;
  m.types[0].A0 = 1.0;
  m.types[0].Gamma = 0.1;
  m.set_lambda(0, 0, 0.0);
  const tessera::Points p{xy.data(), 3, 2};
  const tessera::FiniteTessellation t = tessera::finite_tessellate(p, 3, 1.0);
  std::vector<double> f(6, 0.0);
  for (int which = 0; which < 2; ++which) {
    try {
      if (which == 0)
        tessera::finite_forces(t, p, type, m, nullptr, f.data(), 2);
      else
        tessera::finite_energy(t, type, m, nullptr);
      ADD_FAILURE() << "no error";
    } catch (const tessera::Error &e) {
      const std::string s = e.what();
      // the forces of cell 0 overflow first (K dA ~ 2e308); the energy of
      // cell 2 (area pi: K/2 (pi - 1)^2) is the first energy to
      EXPECT_NE(s.find(which == 0 ? "cell of point 0" : "cell of point 2"), std::string::npos) << s;
      EXPECT_NE(s.find("inf"), std::string::npos) << s;
      EXPECT_NE(s.find("far outside reduced units"), std::string::npos) << s;
    }
  }
  // Each cell finite, the total not (free tension times free length).
  m.types[0].K = 1.0;
  m.types[0].Gamma = 0.0;
  const double free_tension[1] = {2.7e307};
  EXPECT_TRUE(std::isfinite(2.7e307 * 2 * kPi));
  EXPECT_THROW(tessera::finite_energy(t, type, m, free_tension), tessera::Error);
  EXPECT_THROW(tessera::finite_forces(t, p, type, m, free_tension, f.data(), 2), tessera::Error);
}
