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

// ---------------------------------------------------------------------------
// Randomized generators.

namespace {

// Pair-local separation limit of the finite model (finite.h).
bool has_near_pair(const FiniteInput &in) {
  for (int i = 0; i < in.n(); ++i)
    for (int j = i + 1; j < in.n(); ++j) {
      const double dx = in.xy[2 * j] - in.xy[2 * i], dy = in.xy[2 * j + 1] - in.xy[2 * i + 1];
      const double mag = std::max({std::fabs(in.xy[2 * i]), std::fabs(in.xy[2 * i + 1]),
                                   std::fabs(in.xy[2 * j]), std::fabs(in.xy[2 * j + 1])});
      const double lim = std::max(1e-10 * mag, 1e-100);
      if (std::hypot(dx, dy) < 2 * in.r && std::hypot(dx, dy) < lim * (1 + 1e-12)) return true;
    }
  return false;
}

// The largest energy term the parameters can give (per cell, times n).
double energy_scale(const FiniteInput &in) {
  const double a = kPi * in.r * in.r, p = 2 * kPi * in.r;
  double e = 0.0;
  for (int t = 0; t < 2; ++t) {
    const auto &ct = in.model.types[t];
    e = std::max({e, ct.K * std::max(a, ct.A0) * std::max(a, ct.A0), ct.Gamma * p * p,
                  std::fabs(in.free_tension[t]) * p});
  }
  for (int a1 = 0; a1 < 2; ++a1)
    for (int b = 0; b < 2; ++b) e = std::max(e, std::fabs(in.model.lambda_of(a1, b)) * p);
  return e * in.n();
}

struct Stats {
  long inputs = 0, refused = 0, failures = 0, fd_checked = 0, fd_kink = 0;
  double worst_area = 0.0;
  std::map<std::string, long> reasons;
};

// "" if the input passes, else what is wrong.
std::string check(const FiniteInput &in, Rng &rng, Stats &st) {
  std::vector<double> f(2 * static_cast<size_t>(in.n()), 0.0);
  tessera::FiniteTessellation t;
  tessera::ForceOutput out;
  try {
    t = tessera::finite_tessellate(in.points(), in.n(), in.r);
    out = tessera::finite_forces(t, in.points(), in.type.data(), in.model,
                                 in.free_tension.data(), f.data(), 2);
  } catch (const tessera::Error &e) {
    const std::string m = e.what();
    std::string why;
    if (m.find("nearly coincide") != std::string::npos && has_near_pair(in))
      why = "nearly coincident centres";
    else if (m.find("far outside reduced units") != std::string::npos && energy_scale(in) > 1e280)
      why = "energy overflow";
    else if (m.find("radius") != std::string::npos && (in.r < 1e-100 || in.r > 1e100))
      why = "radius out of range";
    else if (m.find("beyond 1e+100") != std::string::npos &&
             std::any_of(in.xy.begin(), in.xy.end(), [](double v) { return std::fabs(v) > 1e100; }))
      why = "coordinate beyond 1e100";
    if (why.empty()) return "unexpected Error: " + m;
    ++st.refused;
    ++st.reasons[why];
    return "";
  }
  if (!std::isfinite(out.energy)) return "energy not finite";
  for (double v : out.virial)
    if (!std::isfinite(v)) return "virial not finite";
  double S = 0.0, fsum[2] = {0, 0}, fabs_sum = 0.0, fmax = 0.0;
  for (int i = 0; i < in.n(); ++i) {
    S = std::max({S, std::fabs(in.xy[2 * i]), std::fabs(in.xy[2 * i + 1])});
    for (int d = 0; d < 2; ++d) {
      if (!std::isfinite(f[2 * i + d])) return "force not finite";
      fsum[d] += f[2 * i + d];
      fabs_sum += std::fabs(f[2 * i + d]);
      fmax = std::max(fmax, std::fabs(f[2 * i + d]));
    }
  }
  // Areas tile the union of the discs.
  double asum = 0.0;
  for (int c = 0; c < in.n(); ++c) {
    if (!(t.area[c] >= 0.0)) return "negative cell area";
    asum += t.area[c];
  }
  const double disc = kPi * in.r * in.r;
  const double cond = 1.0 + S / in.r;
  const double atol = in.n() * disc * (1e-11 + 256 * kEps * cond);
  const double aerr = std::fabs(asum - union_area(in.xy, in.r));
  st.worst_area = std::max(st.worst_area, aerr / atol);
  if (aerr > atol) {
    std::ostringstream s;
    s << "cell areas sum to " << asum << ", the union of the discs is " << union_area(in.xy, in.r);
    return s.str();
  }
  // Translation invariance.  A corner between two centres d apart is known
  // to eps S / d of its distance from them (S the coordinates' magnitude).
  double dmin = 2 * in.r;
  for (int i = 0; i < in.n(); ++i)
    for (int j = i + 1; j < in.n(); ++j)
      dmin = std::min(dmin, std::hypot(in.xy[2 * j] - in.xy[2 * i], in.xy[2 * j + 1] - in.xy[2 * i + 1]));
  const double ftol = (1e-9 * cond + 1e4 * kEps * S / dmin) * fabs_sum + 1e-300;
  if (std::fabs(fsum[0]) > ftol || std::fabs(fsum[1]) > ftol) {
    std::ostringstream s;
    s << "forces sum to (" << fsum[0] << ", " << fsum[1] << "), sum |F| " << fabs_sum;
    return s.str();
  }
  // Central differences on two components, where the energy is smooth.
  if (cond > 1e6 || S / dmin > 1e8 || fmax < 1e-200 || energy_scale(in) > 1e200) return "";
  const double E0 = out.energy;
  for (int k = 0; k < 2; ++k) {
    const int q = rng.below(2 * in.n());
    const double h = std::min(1e-6 * in.r, 1e-3 * dmin);  // smooth within the step
    FiniteInput p = in, m = in;
    p.xy[q] += h;
    m.xy[q] -= h;
    FiniteInput p4 = in, m4 = in;
    p4.xy[q] += 0.25 * h;
    m4.xy[q] -= 0.25 * h;
    double Ep, Em, Ep4, Em4;
    try {
      Ep = energy(p);
      Em = energy(m);
      Ep4 = energy(p4);
      Em4 = energy(m4);
    } catch (const tessera::Error &) {
      continue;
    }
    const double right = (Ep - E0) / h, left = (E0 - Em) / h, central = (Ep - Em) / (2 * h);
    // The central difference of a quarter of the step: a square-root
    // singularity (a contact opening on both sides) can make the one-sided
    // differences agree by chance, not at two steps.
    const double central4 = (Ep4 - Em4) / (0.5 * h);
    // The smoothness test: at a kink (a contact appearing, the square-root
    // singularity of a nearly tangent pair) the one-sided differences
    // disagree and there is nothing to compare with.  Round-off of the energy: of its terms (coordinates rounded to eps S),
    // and of corners near two close centres (known to eps S / dmin times
    // their distance ~ r, moving the energy by the force times that).
    const double noise = 64 * kEps *
                         ((std::fabs(E0) + energy_scale(in) / in.n()) * cond +
                          fabs_sum / in.n() * S * in.r / dmin) / h;
    const double scale =
        std::max({std::fabs(right), std::fabs(left), 1e-9 * fabs_sum / in.n()});
    if (noise > 1e-3 * scale) {  // the differences are round-off
      ++st.fd_kink;
      continue;
    }
    if (std::fabs(right - left) > 1e-3 * scale + 4 * noise ||
        std::fabs(central4 - central) > 1e-4 * scale + 16 * noise) {
      ++st.fd_kink;
      continue;
    }
    ++st.fd_checked;
    if (std::fabs(-central - f[q]) > 1e-4 * scale + 4 * noise) {
      std::ostringstream s;
      s.precision(10);
      s << "force component " << q << " is " << f[q] << ", central difference " << -central
        << " (one-sided " << -right << ", " << -left << ")";
      return s.str();
    }
  }
  return "";
}

using Gen = void (*)(Rng &, FiniteInput &);

// A cluster of 2..25 cells in a square, at a random offset.
void gen_cluster(Rng &rng, FiniteInput &in) {
  in.r = std::pow(10.0, rng.uniform(-3, 3));
  const int n = 2 + rng.below(24);
  const double side = in.r * std::sqrt(n) * rng.uniform(0.5, 2.5);
  const double ox = in.r * std::pow(10.0, rng.uniform(0, 4)) * (rng.below(2) ? 1 : -1);
  for (int i = 0; i < n; ++i)
    in.xy.insert(in.xy.end(), {ox + side * rng.uniform(), side * rng.uniform() - 0.5 * side});
  set_model(rng, in);
}

// Chains of cells at 2r(1 + s 1e-12), s in {-1, 0, 1}: tangent within round-off.
void gen_tangent(Rng &rng, FiniteInput &in) {
  in.r = std::pow(10.0, rng.uniform(-2, 2));
  const int n = 2 + rng.below(7);
  double x = in.r * rng.uniform(-10, 10), y = in.r * rng.uniform(-10, 10);
  const bool straight = rng.below(2);
  double ang = rng.uniform(0, 2 * kPi);
  for (int i = 0; i < n; ++i) {
    in.xy.insert(in.xy.end(), {x, y});
    const double d = 2 * in.r * (1 + (rng.below(3) - 1) * 1e-12);
    if (!straight) ang += rng.uniform(-1.2, 1.2);
    if (rng.below(3) == 0) ang = 0.0;  // exact axis-aligned steps
    x += d * std::cos(ang);
    y += d * std::sin(ang);
  }
  set_model(rng, in);
}

// Rows of cells on one line (equal or random spacing, any angle).
void gen_row(Rng &rng, FiniteInput &in) {
  in.r = std::pow(10.0, rng.uniform(-2, 2));
  const int n = 3 + rng.below(18);
  const double ang = rng.below(2) ? 0.0 : rng.uniform(0, 2 * kPi);
  const bool equal = rng.below(2);
  const double step = in.r * rng.uniform(0.3, 2.2);
  double s = 0.0;
  const double ox = in.r * rng.uniform(-100, 100), oy = in.r * rng.uniform(-100, 100);
  for (int i = 0; i < n; ++i) {
    in.xy.insert(in.xy.end(), {ox + s * std::cos(ang), oy + s * std::sin(ang)});
    s += equal ? step : in.r * rng.uniform(0.3, 2.2);
  }
  set_model(rng, in);
}

// Small groups 1e4 .. 1e12 radii apart.
void gen_far(Rng &rng, FiniteInput &in) {
  in.r = std::pow(10.0, rng.uniform(-6, 2));
  const int groups = 2 + rng.below(3);
  for (int g = 0; g < groups; ++g) {
    const double gx = (g == 0 ? 0.0 : in.r * std::pow(10.0, rng.uniform(4, 10))) *
                      (rng.below(2) ? 1 : -1);
    const double gy = rng.below(2) ? 0.0 : in.r * std::pow(10.0, rng.uniform(0, 10));
    const int n = 1 + rng.below(5);
    for (int i = 0; i < n; ++i)
      in.xy.insert(in.xy.end(), {gx + in.r * rng.uniform(0, 3), gy + in.r * rng.uniform(0, 3)});
  }
  set_model(rng, in);
}

// Radii over the whole supported range (and a little beyond: an Error),
// parameters of order 1 in absolute units, so energies underflow or
// overflow at the extremes.
void gen_extreme(Rng &rng, FiniteInput &in) {
  in.r = std::pow(10.0, rng.uniform(-105, 105));
  const int n = 2 + rng.below(8);
  for (int i = 0; i < n; ++i)
    in.xy.insert(in.xy.end(), {in.r * rng.uniform(0, 4), in.r * rng.uniform(0, 4)});
  set_model(rng, in);
  for (auto &t : in.model.types) {
    t.K = rng.uniform(0.5, 1.5);
    t.A0 = rng.uniform(0.5, 1.5);
    t.Gamma = rng.uniform(0.0, 0.2);
  }
  in.model.set_lambda(0, 0, -0.5);
  in.model.set_lambda(1, 1, -0.3);
  in.model.set_lambda(0, 1, 0.2);
  for (double &f : in.free_tension) f = 0.1;
}

// Near-duplicates: pairs 1e-13 .. 1e-6 of their magnitude apart.
void gen_near_duplicate(Rng &rng, FiniteInput &in) {
  in.r = 1.0;
  const double ox = std::pow(10.0, rng.uniform(-3, 8));
  const int n = 2 + rng.below(6);
  for (int i = 0; i < n; ++i) {
    const double x = ox + rng.uniform(0, 3), y = rng.uniform(0, 3);
    in.xy.insert(in.xy.end(), {x, y});
    if (rng.below(2)) {
      const double d = std::max(std::fabs(x), std::fabs(y)) * std::pow(10.0, rng.uniform(-13, -6));
      in.xy.insert(in.xy.end(), {x + d, y});
    }
  }
  set_model(rng, in);
}

long count(long n) {
  const char *s = std::getenv("TESSERA_FUZZ_SCALE");
  return s ? std::max(1L, static_cast<long>(n * std::atof(s))) : n;
}
uint64_t seed(uint64_t s) {
  const char *e = std::getenv("TESSERA_FUZZ_SEED");
  return e ? s + 1000 * std::strtoull(e, nullptr, 10) : s;
}

void run(const char *name, Gen gen, long n, uint64_t seed0) {
  Stats st;
  for (long k = 0; k < n; ++k) {
    Rng rng(seed0 * 1000003 + k);
    FiniteInput in;
    gen(rng, in);
    ++st.inputs;
    const std::string why = check(in, rng, st);
    if (!why.empty()) {
      ++st.failures;
      if (st.failures <= 3)
        ADD_FAILURE() << name << " input " << k << " (seed " << seed0 << "): " << why
                      << "\nreproducer: " << reproducer(in);
    }
  }
  std::printf("%s: %ld inputs, %ld refused with an Error, %ld failures; %ld finite-difference "
              "checks (%ld skipped at kinks or round-off); worst area-sum error %.3g of its tolerance\n",
              name, st.inputs, st.refused, st.failures, st.fd_checked, st.fd_kink, st.worst_area);
  for (const auto &r : st.reasons) std::printf("  refused %6ld x  %s\n", r.second, r.first.c_str());
  EXPECT_EQ(st.failures, 0);
}

}  // namespace

TEST(FiniteFuzz, Clusters) { run("finite clusters", gen_cluster, count(3000), seed(101)); }
TEST(FiniteFuzz, TangentPairs) { run("finite tangent", gen_tangent, count(4000), seed(102)); }
TEST(FiniteFuzz, CollinearRows) { run("finite rows", gen_row, count(3000), seed(103)); }
TEST(FiniteFuzz, FarApart) { run("finite far apart", gen_far, count(3000), seed(104)); }
TEST(FiniteFuzz, ExtremeRadii) { run("finite extreme r", gen_extreme, count(4000), seed(105)); }
TEST(FiniteFuzz, NearDuplicates) { run("finite near-duplicates", gen_near_duplicate, count(4000), seed(106)); }
