// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The exact Hessian against finite differences of the exact forces, the affine
// (Born) terms against finite differences of energy and forces under box
// strain, and the hexagonal lattice's shear and bulk moduli against the
// second derivatives of the closed-form energy of a regular hexagon.
#include "test_util.h"
#include "tessera/energy.h"
#include "tessera/hessian.h"
#include "tessera/tessellation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using testutil::Config;
using testutil::random_config;

namespace {

std::vector<double> dense(const tessera::SparseMatrix &h) {
  std::vector<double> d(static_cast<size_t>(h.n) * h.n, 0.0);
  for (size_t k = 0; k < h.val.size(); ++k)
    d[static_cast<size_t>(h.row[k]) * h.n + h.col[k]] += h.val[k];
  return d;
}

std::vector<double> forces(const tessera::Box &box, const std::vector<double> &xy,
                           const std::vector<int> &type, const tessera::Model &m,
                           double *energy = nullptr) {
  std::vector<double> f;
  const auto out = tessera::periodic_forces(box, tessera::Points{xy.data(), (int)xy.size() / 2, 2},
                                            type.data(), m, f);
  if (energy) *energy = out.energy;
  return f;
}

tessera::Model quadratic_model(double p0, tessera::Tension tension) {
  tessera::Model m(1);
  const tessera::QuadraticParams q{1.0, 1.0, 1.0, p0};
  m.types[0] = tessera::cell_type_from_quadratic(q);
  m.set_lambda(0, 0, tessera::lambda_from_quadratic(q, tension));
  m.tension = tension;
  return m;
}

class HessianRandom : public ::testing::TestWithParam<int> {};

TEST_P(HessianRandom, EqualsFiniteDifferencesOfForces) {
  const int seed = GetParam();
  const bool cell = seed % 2 == 0;
  const Config cfg = random_config(24, -1.0, 0.5, 5.0, 4.5, 100 + seed, 0.35, false, 2);
  const tessera::Model m = testutil::to_model(testutil::random_params(seed, cell));
  const auto ph = tessera::periodic_hessian(cfg.box, cfg.points(), cfg.type.data(), m);
  const int n2 = 2 * cfg.n();
  ASSERT_EQ(ph.hessian.n, n2);
  const std::vector<double> H = dense(ph.hessian);
  // The forces it reports are periodic_forces'.
  const std::vector<double> f0 = forces(cfg.box, cfg.xy, cfg.type, m);
  for (int i = 0; i < n2; ++i) EXPECT_NEAR(ph.force[i], f0[i], 1e-12 * (1 + std::abs(f0[i])));
  const double h = 1e-6;
  double scale = 0.0, worst = 0.0, asym = 0.0;
  for (double v : H) scale = std::max(scale, std::abs(v));
  ASSERT_GT(scale, 0.0);
  int wi = -1, wj = -1;
  double wfd = 0.0;
  for (int j = 0; j < n2; ++j) {
    std::vector<double> xp = cfg.xy, xm = cfg.xy;
    xp[j] += h;
    xm[j] -= h;
    const std::vector<double> fp = forces(cfg.box, xp, cfg.type, m);
    const std::vector<double> fm = forces(cfg.box, xm, cfg.type, m);
    for (int i = 0; i < n2; ++i) {
      const double fd = -(fp[i] - fm[i]) / (2 * h);
      const double e = std::abs(H[static_cast<size_t>(i) * n2 + j] - fd);
      if (e > worst) {
        worst = e;
        wi = i;
        wj = j;
        wfd = fd;
      }
      asym = std::max(asym, std::abs(H[static_cast<size_t>(i) * n2 + j] -
                                     H[static_cast<size_t>(j) * n2 + i]));
    }
  }
  EXPECT_LT(worst / scale, 1e-6) << "worst entry (" << wi << ", " << wj << "): Hessian "
                                 << H[static_cast<size_t>(wi) * n2 + wj]
                                 << ", finite difference " << wfd << " (max |H| " << scale << ")";
  EXPECT_LT(asym / scale, 1e-12);
}

// Affine strain of box and points: D = shear (x += g y) or dilation.
struct Strained {
  tessera::Box box;
  std::vector<double> xy;
};
Strained strain(const Config &cfg, bool shear, double g) {
  Strained s{cfg.box, cfg.xy};
  // Affine about the box's lower corner, which stays put (the energy is
  // translation invariant, so the reference point does not matter).
  const double ox = cfg.box.lo[0], oy = cfg.box.lo[1];
  if (shear) {
    s.box.xy = g * cfg.box.length(1);
    for (size_t i = 0; i < s.xy.size(); i += 2) s.xy[i] += g * (s.xy[i + 1] - oy);
  } else {
    s.box.hi[0] = ox + (1 + g) * cfg.box.length(0);
    s.box.hi[1] = oy + (1 + g) * cfg.box.length(1);
    for (size_t i = 0; i < s.xy.size(); i += 2) {
      s.xy[i] = ox + (1 + g) * (s.xy[i] - ox);
      s.xy[i + 1] = oy + (1 + g) * (s.xy[i + 1] - oy);
    }
  }
  return s;
}

TEST_P(HessianRandom, AffineTermsAreFiniteDifferences) {
  const int seed = GetParam();
  const bool cell = seed % 2 == 1;
  const Config cfg = random_config(24, 0.3, -0.7, 5.0, 4.5, 200 + seed, 0.35, false, 2);
  const tessera::Model m = testutil::to_model(testutil::random_params(seed + 7, cell));
  const auto ph = tessera::periodic_hessian(cfg.box, cfg.points(), cfg.type.data(), m);
  for (bool shear : {true, false}) {
    SCOPED_TRACE(shear ? "shear" : "dilation");
    const double g = 1e-4;
    const Strained sp = strain(cfg, shear, g), sm = strain(cfg, shear, -g);
    double ep, em, e0;
    const auto fp = forces(sp.box, sp.xy, cfg.type, m, &ep);
    const auto fm = forces(sm.box, sm.xy, cfg.type, m, &em);
    forces(cfg.box, cfg.xy, cfg.type, m, &e0);
    const double born_fd = (ep - 2 * e0 + em) / (g * g);
    const double born = shear ? ph.born_shear : ph.born_dilation;
    EXPECT_NEAR(born, born_fd, 1e-5 * std::max(1.0, std::abs(born_fd)));
    // First derivative: the virial (dE/dgamma = -W_xy, dE/deps = -(W_xx + W_yy)).
    const double d1 = (ep - em) / (2 * g);
    const double w = shear ? -ph.virial[2] : -(ph.virial[0] + ph.virial[1]);
    EXPECT_NEAR(w, d1, 1e-6 * std::max(1.0, std::abs(d1)));
    const std::vector<double> &xi = shear ? ph.xi_shear : ph.xi_dilation;
    ASSERT_EQ(xi.size(), cfg.xy.size());
    double scale = testutil::max_abs(xi), worst = 0.0, sx = 0.0, sy = 0.0;
    ASSERT_GT(scale, 0.0);
    for (size_t i = 0; i < xi.size(); ++i) {
      const double fd = -(fp[i] - fm[i]) / (2 * g);
      worst = std::max(worst, std::abs(xi[i] - fd));
      (i % 2 ? sy : sx) += xi[i];
    }
    EXPECT_LT(worst / scale, 1e-6);
    // Xi is orthogonal to the translations (no net force under affine strain).
    EXPECT_NEAR(sx, 0.0, 1e-10 * scale * cfg.n());
    EXPECT_NEAR(sy, 0.0, 1e-10 * scale * cfg.n());
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, HessianRandom, ::testing::Values(1, 2, 3, 4));

// Hexagonal lattice of unit-area cells (nearest neighbours along x, as
// LAMMPS's `lattice hex 1.0`), nx x ny rectangular unit cells of two points.
Config hex_lattice(int nx, int ny) {
  const double a = std::sqrt(2.0 / std::sqrt(3.0)), b = a * std::sqrt(3.0);
  Config c;
  c.box = tessera::Box::rect(0.0, nx * a, 0.0, ny * b);
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const double x = (i + 0.2) * a, y = (j + 0.1) * b;
      c.xy.insert(c.xy.end(), {x, y, x + 0.5 * a, y + 0.5 * b});
    }
  c.type.assign(c.n(), 0);
  return c;
}

// Closed form, for E = sum KA (A - 1)^2 + KP (P - p0)^2 with KA = KP = 1 and
// regular hexagons of area 1 (perimeter Ph = sqrt(8 sqrt 3)):
//  dilation: P = Ph sqrt(A), so B = A d2e/dA2 = 2 KA + KP Ph p0 / 2;
//  shear x += g y: A fixed, P(g) = Ph + (3/8) Ph g^2 + O(g^4) (each edge of
//  the Voronoi hexagon of the sheared lattice on the bisector of its
//  neighbour), so G = d2e/dg2 / A = 2 KP (Ph - p0) (3/8) Ph = (3/4) KP Ph (Ph - p0).
TEST(HessianHexagon, ModuliAreTheClosedFormSecondDerivatives) {
  const double Ph = std::sqrt(8.0 * std::sqrt(3.0));
  const Config cfg = hex_lattice(6, 4);
  for (double p0 : {3.5, 3.7, 3.9}) {
    for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
      SCOPED_TRACE("p0 = " + std::to_string(p0));
      const auto ph = tessera::periodic_hessian(cfg.box, cfg.points(), cfg.type.data(),
                                                quadratic_model(p0, tension));
      EXPECT_NEAR(ph.area, cfg.n(), 1e-12 * cfg.n());
      // A Bravais lattice: every centre is a centre of inversion, so no
      // non-affine relaxation (Xi = 0) and G, B are the Born terms alone.
      EXPECT_LT(testutil::max_abs(ph.xi_shear), 1e-10);
      EXPECT_LT(testutil::max_abs(ph.xi_dilation), 1e-10);
      EXPECT_LT(testutil::max_abs(ph.force), 1e-10);
      const double G = ph.born_shear / ph.area;
      const double pressure = (ph.virial[0] + ph.virial[1]) / (2 * ph.area);
      const double B = (ph.born_dilation / ph.area + 2 * pressure) / 4;
      EXPECT_NEAR(G, 0.75 * Ph * (Ph - p0), 1e-10);
      EXPECT_NEAR(B, 2.0 + Ph * p0 / 2, 1e-10);
      // Pressure -de/dA = -2 KP (Ph - p0) Ph / 2.
      EXPECT_NEAR(pressure, -(Ph - p0) * Ph, 1e-10);
    }
  }
}

TEST(HessianMultifold, SquareLatticeThrowsNamingTheVertex) {
  Config c;
  c.box = tessera::Box::rect(0.0, 4.0, 0.0, 4.0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) c.xy.insert(c.xy.end(), {i + 0.5, j + 0.5});
  c.type.assign(c.n(), 0);
  try {
    tessera::periodic_hessian(c.box, c.points(), c.type.data(),
                              quadratic_model(3.8, tessera::Tension::Edge));
    FAIL() << "no error at four-fold vertices";
  } catch (const tessera::Error &e) {
    EXPECT_NE(std::string(e.what()).find("multifold vertex"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("shared by 4 cells"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

// Nearly four-fold vertices (a square lattice jittered by 1e-3: Voronoi edges
// of length ~1e-3): the Hessian is still the derivative of the forces.
TEST(HessianNearlyMultifold, ShortEdgesStillFiniteDifferences) {
  testutil::Rng rng(11);
  Config c;
  c.box = tessera::Box::rect(0.0, 4.0, 0.0, 4.0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      c.xy.insert(c.xy.end(), {i + 0.5 + 1e-3 * rng.uniform(-1, 1), j + 0.5 + 1e-3 * rng.uniform(-1, 1)});
  c.type.assign(c.n(), 0);
  const tessera::Model m = quadratic_model(3.8, tessera::Tension::Edge);
  const auto t = tessera::tessellate_periodic(c.box, c.points());
  double shortest = 1e300;
  for (double l : t.edge_length) shortest = std::min(shortest, l);
  ASSERT_LT(shortest, 3e-3);
  ASSERT_GT(shortest, 0.0);
  const auto ph = tessera::periodic_hessian(c.box, c.points(), c.type.data(), m);
  const std::vector<double> H = dense(ph.hessian);
  const int n2 = 2 * c.n();
  const double h = 1e-7;
  double scale = 0.0, worst = 0.0;
  for (double v : H) scale = std::max(scale, std::abs(v));
  for (int j = 0; j < n2; ++j) {
    std::vector<double> xp = c.xy, xm = c.xy;
    xp[j] += h;
    xm[j] -= h;
    const auto fp = forces(c.box, xp, c.type, m), fm = forces(c.box, xm, c.type, m);
    for (int i = 0; i < n2; ++i)
      worst = std::max(worst, std::abs(H[static_cast<size_t>(i) * n2 + j] + (fp[i] - fm[i]) / (2 * h)));
  }
  EXPECT_LT(worst / scale, 1e-5) << "max |H| " << scale << ", shortest edge " << shortest;
}

}  // namespace
