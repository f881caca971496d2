// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Energy, forces and virial against the reference energy, finite differences
// and analytic lattices.
#include "reference.h"
#include "test_util.h"
#include "tessera/energy.h"
#include "tessera/tessellation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>

using testutil::Config;
using testutil::random_config;

namespace {

const char *name(bool cell) { return cell ? "tension cell" : "tension edge"; }

struct Result {
  std::vector<double> f, cell_energy;
  tessera::ForceOutput out;
};

Result forces(const Config &cfg, const tessera::Model &m) {
  Result r;
  r.out = tessera::periodic_forces(cfg.box, cfg.points(), cfg.type.data(), m, r.f, &r.cell_energy);
  return r;
}

// -dE/dr by central differences of the reference energy of the cells that
// can depend on each point.
std::vector<double> fd_forces(const Config &cfg, const reftess::RefParams &p, double h) {
  const auto ref = reftess::voronoi(cfg.refbox(), cfg.xy);
  std::vector<double> fd(cfg.xy.size());
  for (int i = 0; i < cfg.n(); ++i) {
    const std::vector<int> cells = reftess::affected_cells(ref, i);
    for (int d = 0; d < 2; ++d) {
      std::vector<double> xp = cfg.xy, xm = cfg.xy;
      xp[2 * i + d] += h;
      xm[2 * i + d] -= h;
      const double ep = reftess::partial_energy(cfg.refbox(), xp, cfg.type, p, cells);
      const double em = reftess::partial_energy(cfg.refbox(), xm, cfg.type, p, cells);
      fd[2 * i + d] = -(ep - em) / (2 * h);
    }
  }
  return fd;
}

void expect_forces_match(const std::vector<double> &f, const std::vector<double> &fd,
                         double rtol) {
  ASSERT_EQ(f.size(), fd.size());
  const double scale = testutil::max_abs(fd);
  ASSERT_GT(scale, 0.0);
  double worst = 0;
  int worst_k = -1;
  for (size_t k = 0; k < f.size(); ++k) {
    ASSERT_TRUE(std::isfinite(f[k])) << "component " << k;
    const double e = std::abs(f[k] - fd[k]);
    if (e > worst) {
      worst = e;
      worst_k = static_cast<int>(k);
    }
  }
  EXPECT_LT(worst / scale, rtol) << "worst: point " << worst_k / 2 << " component "
                                 << worst_k % 2 << ": force " << f[worst_k] << ", finite difference "
                                 << fd[worst_k] << " (max |F| " << scale << ")";
}

void expect_sum_zero(const std::vector<double> &f) {
  double sx = 0, sy = 0;
  for (size_t k = 0; k < f.size(); k += 2) {
    sx += f[k];
    sy += f[k + 1];
  }
  const double tol = 1e-13 * static_cast<double>(f.size()) * std::max(1.0, testutil::max_abs(f));
  EXPECT_NEAR(sx, 0.0, tol);
  EXPECT_NEAR(sy, 0.0, tol);
}

// A random configuration whose shortest Voronoi edge is at least min_edge, so
// that central differences with step ~1e-6 see a smooth energy.
Config nondegenerate_config(int n, double lx, double ly, uint64_t seed, double dmin,
                            double min_edge) {
  for (uint64_t s = seed;; s += 1000) {
    Config c = random_config(n, 0.0, 0.0, lx, ly, s, dmin);
    if (c.n() == n && testutil::shortest_edge(reftess::voronoi(c.refbox(), c.xy)) > min_edge)
      return c;
  }
}

}  // namespace

// ---------------------------------------------------------------------------

TEST(Energy, MatchesReferenceEnergy) {
  for (bool cell : {false, true}) {
    for (uint64_t seed = 100; seed < 103; ++seed) {
      SCOPED_TRACE(std::string(name(cell)) + ", seed " + std::to_string(seed));
      const Config cfg = random_config(80, 0.0, 0.0, 10.0, 8.0, seed, 0.1);
      const reftess::RefParams p = testutil::random_params(seed, cell);
      const tessera::Model m = testutil::to_model(p);
      const auto ref = reftess::voronoi(cfg.refbox(), cfg.xy);
      const double eref = reftess::total_energy(ref, cfg.type, p);
      const Result r = forces(cfg, m);
      EXPECT_NEAR(r.out.energy, eref, 1e-11 * std::max(1.0, std::abs(eref)));
      ASSERT_EQ(static_cast<int>(r.cell_energy.size()), cfg.n());
      for (int i = 0; i < cfg.n(); ++i) {
        EXPECT_NEAR(r.cell_energy[i], reftess::cell_energy(ref[i], i, cfg.type, p), 1e-11)
            << "cell " << i;
      }
      // compute_energy on the periodic tessellation agrees too.
      const tessera::Tessellation t = tessera::tessellate_periodic(cfg.box, cfg.points());
      std::vector<int> type_all(t.n_points);
      for (int k = 0; k < t.n_points; ++k) type_all[k] = cfg.type[t.origin[k]];
      std::vector<double> ce(cfg.n());
      EXPECT_NEAR(tessera::compute_energy(t, type_all.data(), m, ce.data()), eref,
                  1e-11 * std::max(1.0, std::abs(eref)));
      for (int i = 0; i < cfg.n(); ++i) EXPECT_NEAR(ce[i], r.cell_energy[i], 1e-12);
    }
  }
}

TEST(Forces, MatchFiniteDifferencesRandom) {
  for (bool cell : {false, true}) {
    for (uint64_t seed = 200; seed < 203; ++seed) {
      SCOPED_TRACE(std::string(name(cell)) + ", seed " + std::to_string(seed));
      const Config cfg = nondegenerate_config(56, 8.0, 7.0, seed, 0.3, 2e-3);
      const reftess::RefParams p = testutil::random_params(seed, cell);
      const Result r = forces(cfg, testutil::to_model(p));
      ASSERT_EQ(r.f.size(), cfg.xy.size());
      expect_forces_match(r.f, fd_forces(cfg, p, 1e-6), 1e-6);
      expect_sum_zero(r.f);
    }
  }
}

TEST(Forces, MatchFiniteDifferencesInhomogeneous) {
  // Unequal densities in a non-square box, no minimum distance; three types.
  for (bool cell : {false, true}) {
    SCOPED_TRACE(name(cell));
    Config cfg;
    for (uint64_t s = 300;; s += 1000) {
      testutil::Rng rng(s);
      cfg = Config();
      cfg.box = tessera::Box::rect(-2.0, 4.0, 1.0, 10.0);
      for (int i = 0; i < 60; ++i) {
        const double u = rng.uniform();
        cfg.xy.push_back(-2.0 + 6.0 * u * u);  // denser near x = -2
        cfg.xy.push_back(1.0 + 9.0 * rng.uniform());
        cfg.type.push_back(rng.below(3));
      }
      if (testutil::shortest_edge(reftess::voronoi(cfg.refbox(), cfg.xy)) > 2e-3) break;
    }
    const reftess::RefParams p = testutil::random_params(301, cell, 3);
    const Result r = forces(cfg, testutil::to_model(p));
    expect_forces_match(r.f, fd_forces(cfg, p, 1e-6), 1e-6);
    expect_sum_zero(r.f);
  }
}

TEST(Forces, PerCellPreferredAreaMatchesFiniteDifferences) {
  // Model::cell_area0 gives every cell its own A0.  The reference knows only
  // per-type parameters, so it gets one type per cell: the cell's base-type
  // K, Gamma and Lambdas with the cell's own A0.
  for (bool cell : {false, true}) {
    SCOPED_TRACE(name(cell));
    const Config cfg = nondegenerate_config(40, 7.0, 6.0, 410, 0.3, 2e-3);
    const reftess::RefParams base = testutil::random_params(411, cell);
    testutil::Rng rng(412);
    std::vector<double> a0(cfg.n());
    for (double &a : a0) a = rng.uniform(0.5, 2.0);
    const int n = cfg.n(), nt = base.ntypes();
    reftess::RefParams p;
    p.cell_tension = cell;
    p.Lambda.assign(static_cast<size_t>(n) * n, 0.0);
    Config per_cell = cfg;
    for (int i = 0; i < n; ++i) {
      const int t = cfg.type[i];
      p.K.push_back(base.K[t]);
      p.A0.push_back(a0[i]);
      p.Gamma.push_back(base.Gamma[t]);
      per_cell.type[i] = i;
      for (int j = 0; j < n; ++j) p.Lambda[i * n + j] = base.Lambda[t * nt + cfg.type[j]];
    }
    tessera::Model m = testutil::to_model(base);
    m.cell_area0 = a0.data();
    const Result r = forces(cfg, m);
    expect_forces_match(r.f, fd_forces(per_cell, p, 1e-6), 1e-6);
    expect_sum_zero(r.f);
    const double eref = reftess::total_energy(reftess::voronoi(cfg.refbox(), cfg.xy), per_cell.type, p);
    EXPECT_NEAR(r.out.energy, eref, 1e-11 * std::max(1.0, std::abs(eref)));
    // Without the per-cell array the energy is the types' (a different value).
    const Result r0 = forces(cfg, testutil::to_model(base));
    EXPECT_GT(std::abs(r0.out.energy - r.out.energy), 1e-3);
  }
}

TEST(Forces, SumToZero) {
  for (bool cell : {false, true}) {
    for (uint64_t seed = 400; seed < 404; ++seed) {
      SCOPED_TRACE(std::string(name(cell)) + ", seed " + std::to_string(seed));
      const Config cfg = random_config(500, 0.0, 0.0, 25.0, 20.0, seed, 0.0);
      const Result r = forces(cfg, testutil::to_model(testutil::random_params(seed, cell)));
      expect_sum_zero(r.f);
    }
  }
}

TEST(Forces, ComputeForcesAddsAndFoldsLikePeriodicForces) {
  const Config cfg = random_config(70, 0.0, 0.0, 9.0, 8.0, 500, 0.2);
  const tessera::Model m = testutil::to_model(testutil::random_params(500, false));
  const Result r = forces(cfg, m);
  const tessera::Tessellation t = tessera::tessellate_periodic(cfg.box, cfg.points());
  const std::vector<double> pos = tessera::positions_of(t);
  ASSERT_EQ(static_cast<int>(pos.size()), 2 * t.n_points);
  for (int k = 0; k < t.n_points; ++k) {
    EXPECT_EQ(pos[2 * k], t.position[k].x);
    EXPECT_EQ(pos[2 * k + 1], t.position[k].y);
  }
  std::vector<int> type_all(t.n_points);
  for (int k = 0; k < t.n_points; ++k) type_all[k] = cfg.type[t.origin[k]];
  // Stride 3 with a preloaded value: forces must be added.
  std::vector<double> f(3 * t.n_points, 1.5);
  std::vector<double> ce(cfg.n(), -99.0);
  const tessera::Points pts{pos.data(), t.n_points, 2};
  const tessera::ForceOutput out =
      tessera::compute_forces(t, pts, type_all.data(), m, f.data(), 3, ce.data());
  EXPECT_NEAR(out.energy, r.out.energy, 1e-12 * std::abs(r.out.energy));
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(out.virial[k], r.out.virial[k], 1e-10);
  std::vector<double> folded(2 * cfg.n(), 0.0);
  for (int k = 0; k < t.n_points; ++k) {
    EXPECT_EQ(f[3 * k + 2], 1.5) << "third column touched";
    folded[2 * t.origin[k]] += f[3 * k] - 1.5;
    folded[2 * t.origin[k] + 1] += f[3 * k + 1] - 1.5;
  }
  for (int i = 0; i < cfg.n(); ++i) {
    EXPECT_NEAR(folded[2 * i], r.f[2 * i], 1e-12);
    EXPECT_NEAR(folded[2 * i + 1], r.f[2 * i + 1], 1e-12);
    EXPECT_NEAR(ce[i], r.cell_energy[i], 1e-13);
  }
}

// ---------------------------------------------------------------------------
// Lattices

namespace {

Config hex_lattice(int nx, int ny, double a, double xlo, double ylo) {
  Config c;
  const double dy = a * std::sqrt(3.0) / 2;
  c.box = tessera::Box::rect(xlo, xlo + nx * a, ylo, ylo + ny * dy);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      c.xy.push_back(xlo + (i + 0.5 * (j % 2) + 0.25) * a);
      c.xy.push_back(ylo + (j + 0.3) * dy);
    }
  c.type.assign(c.n(), 0);
  return c;
}

Config square_lattice(int nx, int ny, double xlo, double ylo) {
  Config c;
  c.box = tessera::Box::rect(xlo, xlo + nx, ylo, ylo + ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      c.xy.push_back(xlo + i + 0.5);
      c.xy.push_back(ylo + j + 0.5);
    }
  c.type.assign(c.n(), 0);
  return c;
}

}  // namespace

TEST(Lattice, HexagonalZeroForceAndAnalyticEnergy) {
  const double a = 1.1;
  const double area = a * a * std::sqrt(3.0) / 2;
  const double perim = std::sqrt(8 * std::sqrt(3.0) * area);
  EXPECT_NEAR(perim, 2 * std::sqrt(3.0) * a, 1e-14);
  for (bool cell : {false, true}) {
    for (double a0 : {area, 0.8 * area}) {
      SCOPED_TRACE(std::string(name(cell)) + ", A0 " + std::to_string(a0));
      const Config cfg = hex_lattice(8, 8, a, -3.0, 2.5);
      const int n = cfg.n();
      tessera::Model m(1);
      m.types[0].K = 1.3;
      m.types[0].A0 = a0;
      m.types[0].Gamma = 0.23;
      m.set_lambda(0, 0, -0.41);
      m.tension = cell ? tessera::Tension::Cell : tessera::Tension::Edge;
      const Result r = forces(cfg, m);
      for (int k = 0; k < 2 * n; ++k) EXPECT_LT(std::abs(r.f[k]), 1e-12) << "component " << k;
      const double per_cell = 0.5 * 1.3 * (area - a0) * (area - a0) + 0.5 * 0.23 * perim * perim +
                              (cell ? 1.0 : 0.5) * -0.41 * perim;
      EXPECT_NEAR(r.out.energy, n * per_cell, 1e-12 * n);
      for (int i = 0; i < n; ++i) EXPECT_NEAR(r.cell_energy[i], per_cell, 1e-12);

      const tessera::Tessellation t = tessera::tessellate_periodic(cfg.box, cfg.points());
      EXPECT_EQ(t.count_multifold_vertices(), 0);
      for (int i = 0; i < n; ++i) {
        EXPECT_NEAR(t.area[i], area, 1e-13);
        EXPECT_NEAR(t.perimeter[i], perim, 1e-13);
        EXPECT_EQ(t.coordination_number(i), 6);
      }
      // Isotropic virial: W_xx = W_yy = -dE/d(strain) = -(N K (A - A0) A) - ...,
      // analytic for a uniform dilation of the lattice: E(s) per cell with
      // A -> A (1+s)^2, P -> P (1+s): dE/ds = K (A - A0) 2A + Gamma P^2 + w Lambda P.
      const double dEds = n * (1.3 * (area - a0) * 2 * area + 0.23 * perim * perim +
                               (cell ? 1.0 : 0.5) * -0.41 * perim);
      EXPECT_NEAR(r.out.virial[0] + r.out.virial[1], -dEds, 1e-10 * std::abs(dEds) + 1e-10);
      EXPECT_NEAR(r.out.virial[0], r.out.virial[1], 1e-10 * std::abs(dEds) + 1e-10);
      EXPECT_NEAR(r.out.virial[2], 0.0, 1e-10 * std::abs(dEds) + 1e-10);
      EXPECT_NEAR(r.out.virial[3], 0.0, 1e-10 * std::abs(dEds) + 1e-10);
    }
  }
}

TEST(Lattice, SquareUniformIsForceFree) {
  for (bool cell : {false, true}) {
    SCOPED_TRACE(name(cell));
    const Config cfg = square_lattice(8, 8, 0.0, 0.0);
    tessera::Model m(1);
    m.types[0].K = 1.0;
    m.types[0].A0 = 0.9;
    m.types[0].Gamma = 0.3;
    m.set_lambda(0, 0, -0.7);
    m.tension = cell ? tessera::Tension::Cell : tessera::Tension::Edge;
    const Result r = forces(cfg, m);
    for (double f : r.f) EXPECT_LT(std::abs(f), 1e-12);
    const double per_cell = 0.5 * 0.01 + 0.5 * 0.3 * 16 + (cell ? 1.0 : 0.5) * -0.7 * 4;
    EXPECT_NEAR(r.out.energy, 64 * per_cell, 1e-11);
    const tessera::Tessellation t = tessera::tessellate_periodic(cfg.box, cfg.points());
    for (int i = 0; i < 64; ++i) {
      EXPECT_NEAR(t.area[i], 1.0, 1e-13);
      EXPECT_NEAR(t.perimeter[i], 4.0, 1e-13);
      EXPECT_EQ(t.coordination_number(i), 4);
    }
  }
}

TEST(Lattice, SquareMultifoldVertexCount) {
  // An n x n periodic square lattice has n^2 Voronoi vertices, all 4-fold,
  // wherever the box puts them (the global number of multifold vertices).
  for (double off : {0.0, 0.25}) {
    SCOPED_TRACE("offset " + std::to_string(off));
    Config cfg = square_lattice(8, 8, 0.0, 0.0);
    for (double &x : cfg.xy) x += off;
    tessera::wrap_into_box(cfg.box, cfg.xy);
    const tessera::Tessellation t = tessera::tessellate_periodic(cfg.box, cfg.points());
    EXPECT_EQ(t.count_multifold_vertices(), 64);
  }
  // 6 x 4 rectangular lattice in a 6 x 4 box: 24 vertices.
  Config r = square_lattice(6, 4, -2.0, 1.0);
  const tessera::Tessellation t = tessera::tessellate_periodic(r.box, r.points());
  EXPECT_EQ(t.count_multifold_vertices(), 24);
}

namespace {

Config typed_square_lattice(uint64_t seed) {
  Config cfg = square_lattice(8, 8, -1.0, 3.0);
  testutil::Rng rng(seed);
  for (int &t : cfg.type) t = rng.below(2);
  return cfg;
}

}  // namespace

TEST(Lattice, SquareMultifoldMatchesCentralDifferences) {
  // The requirement of the test plan: at exactly 4-fold vertices the forces
  // equal the central difference of the true energy (the average of the
  // one-sided derivatives across the kinks).  A fixed triangulation with
  // zero-length edges ignored does not give this (its derivative can lie
  // outside both one-sided ones); averaging the branches does.

  for (bool cell : {false, true}) {
    for (uint64_t seed = 600; seed < 602; ++seed) {
      SCOPED_TRACE(std::string(name(cell)) + ", seed " + std::to_string(seed));
      const Config cfg = typed_square_lattice(seed);
      const reftess::RefParams p = testutil::random_params(seed, cell);
      const Result r = forces(cfg, testutil::to_model(p));
      expect_forces_match(r.f, fd_forces(cfg, p, 1e-7), 1e-6);
      expect_sum_zero(r.f);
    }
  }
}

TEST(Lattice, SquareMultifoldForceWithinOneSidedDerivatives) {
  // Energy of a single cell's perimeter, E = Gamma/2 P_a^2 (other cells have
  // Gamma = 0 and sit at A = A0), on a square lattice.  Along any coordinate
  // of any point, E(s) is piecewise smooth with a kink at s = 0; any sensible
  // force (a generalised gradient) has -F between the left and the right
  // derivative.  The central difference is their mean.
  Config c;
  c.box = tessera::Box::rect(0, 6, 0, 6);
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      c.xy.push_back(i + 0.5);
      c.xy.push_back(j + 0.5);
    }
  c.type.assign(36, 1);
  c.type[14] = 0;
  reftess::RefParams p;
  p.K = {1e-9, 1e-9};
  p.A0 = {1.0, 1.0};
  p.Gamma = {1.0, 0.0};
  p.Lambda = {0.0, 0.0, 0.0, 0.0};
  const Result r = forces(c, testutil::to_model(p));
  const auto ref = reftess::voronoi(c.refbox(), c.xy);
  const double h = 1e-7;
  for (int i = 0; i < 36; ++i) {
    const std::vector<int> cells = reftess::affected_cells(ref, i);
    const double e0 = reftess::partial_energy(c.refbox(), c.xy, c.type, p, cells);
    for (int d = 0; d < 2; ++d) {
      std::vector<double> xp = c.xy, xm = c.xy;
      xp[2 * i + d] += h;
      xm[2 * i + d] -= h;
      const double right = (reftess::partial_energy(c.refbox(), xp, c.type, p, cells) - e0) / h;
      const double left = (e0 - reftess::partial_energy(c.refbox(), xm, c.type, p, cells)) / h;
      const double g = -r.f[2 * i + d];
      EXPECT_GE(g, std::min(left, right) - 1e-5)
          << "point " << i << " component " << d << ": left " << left << " right " << right;
      EXPECT_LE(g, std::max(left, right) + 1e-5)
          << "point " << i << " component " << d << ": left " << left << " right " << right;
    }
  }
}

TEST(Lattice, PerturbedSquareMatchesFiniteDifferences) {
  for (bool cell : {false, true}) {
    SCOPED_TRACE(name(cell));
    Config cfg = square_lattice(8, 8, 0.0, 0.0);
    testutil::Rng rng(610);
    for (double &x : cfg.xy) x += rng.uniform(-1e-3, 1e-3);
    tessera::wrap_into_box(cfg.box, cfg.xy);
    for (int &t : cfg.type) t = rng.below(2);
    const reftess::RefParams p = testutil::random_params(610, cell);
    const Result r = forces(cfg, testutil::to_model(p));
    expect_forces_match(r.f, fd_forces(cfg, p, 1e-7), 1e-6);
    const tessera::Tessellation t = tessera::tessellate_periodic(cfg.box, cfg.points());
    EXPECT_EQ(t.count_multifold_vertices(), 0);
  }
}

// ---------------------------------------------------------------------------
// Quadratic-form parameters

TEST(Energy, QuadraticFormDiffersByConstant) {
  const tessera::QuadraticParams q{0.7, 1.1, 0.2, 3.9};
  const tessera::CellType ct = tessera::cell_type_from_quadratic(q);
  EXPECT_DOUBLE_EQ(ct.K, 1.4);
  EXPECT_DOUBLE_EQ(ct.A0, 1.1);
  EXPECT_DOUBLE_EQ(ct.Gamma, 0.4);
  EXPECT_DOUBLE_EQ(tessera::lambda_from_quadratic(q, tessera::Tension::Edge), -2 * 0.4 * 3.9);
  EXPECT_DOUBLE_EQ(tessera::lambda_from_quadratic(q, tessera::Tension::Cell), -0.4 * 3.9);
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    tessera::Model m(1);
    m.types[0] = ct;
    m.set_lambda(0, 0, tessera::lambda_from_quadratic(q, tension));
    m.tension = tension;
    for (uint64_t seed = 700; seed < 703; ++seed) {
      const Config cfg = random_config(60, 0.0, 0.0, 7.0, 9.0, seed, 0.2);
      const auto ref = reftess::voronoi(cfg.refbox(), cfg.xy);
      double equad = 0;
      for (const auto &c : ref) {
        equad += q.KA * (c.area - q.A0) * (c.area - q.A0) +
                 q.KP * (c.perimeter - q.P0) * (c.perimeter - q.P0);
      }
      std::vector<int> type(cfg.n(), 0);
      std::vector<double> f;
      const auto out = tessera::periodic_forces(cfg.box, cfg.points(), type.data(), m, f);
      EXPECT_NEAR(out.energy, equad - cfg.n() * q.KP * q.P0 * q.P0, 1e-10);
    }
  }
}

// ---------------------------------------------------------------------------
// Virial

TEST(Virial, DiagonalMatchesAffineStretch) {
  for (bool cell : {false, true}) {
    for (uint64_t seed = 800; seed < 802; ++seed) {
      SCOPED_TRACE(std::string(name(cell)) + ", seed " + std::to_string(seed));
      Config cfg = random_config(64, 0.5, -1.0, 8.0, 9.0, seed, 0.2);
      reftess::RefParams p = testutil::random_params(seed, cell);
      const Result r = forces(cfg, testutil::to_model(p));
      const double eps = 1e-6;
      for (int d = 0; d < 2; ++d) {
        double e[2];
        for (int s = 0; s < 2; ++s) {
          const double g = 1 + (s == 0 ? eps : -eps);
          reftess::RefBox b = cfg.refbox();
          std::vector<double> xy = cfg.xy;
          for (int i = 0; i < cfg.n(); ++i) xy[2 * i + d] *= g;
          if (d == 0) {
            b.xlo *= g;
            b.lx *= g;
          } else {
            b.ylo *= g;
            b.ly *= g;
          }
          e[s] = reftess::total_energy(reftess::voronoi(b, xy), cfg.type, p);
        }
        const double dE = (e[0] - e[1]) / (2 * eps);
        const double w = r.out.virial[d];
        EXPECT_NEAR(-w, dE, 1e-6 * std::max({1.0, std::abs(r.out.virial[0]),
                                             std::abs(r.out.virial[1])}))
            << (d == 0 ? "xx" : "yy");
      }
      EXPECT_NEAR(r.out.virial[2], r.out.virial[3],
                  1e-12 * std::max({1.0, std::abs(r.out.virial[0]), std::abs(r.out.virial[1])}))
          << "W_xy != W_yx";
    }
  }
}

TEST(Virial, ShearMatchesLocalPatchDerivative) {
  // Affine shear of the periodic system, evaluated on an explicit patch of
  // periodic images with tessellate_local (a sheared box is not supported yet).
  for (bool cell : {false, true}) {
    SCOPED_TRACE(name(cell));
    const Config cfg = random_config(64, 0.0, 0.0, 8.0, 8.0, 900 + cell, 0.2);
    const reftess::RefParams p = testutil::random_params(900, cell);
    const tessera::Model m = testutil::to_model(p);
    const Result r = forces(cfg, m);
    std::vector<int> origin;
    const double w = 3.0;
    const std::vector<double> patch = testutil::with_images(cfg, w, &origin);
    const int np = static_cast<int>(patch.size() / 2);
    std::vector<int> type_all(np);
    for (int k = 0; k < np; ++k) type_all[k] = cfg.type[origin[k]];
    {
      // The patch is thick enough, and its forces fold onto the periodic ones.
      const tessera::Tessellation t = tessera::tessellate_local({patch.data(), np, 2}, cfg.n());
      const double lo[2] = {-w, -w}, hi[2] = {8 + w, 8 + w};
      ASSERT_TRUE(tessera::check_coverage(t, lo, hi).ok);
      std::vector<double> f(2 * np, 0.0);
      const auto out = tessera::compute_forces(t, {patch.data(), np, 2}, type_all.data(), m,
                                               f.data(), 2);
      EXPECT_NEAR(out.energy, r.out.energy, 1e-11 * std::abs(r.out.energy));
      std::vector<double> folded(2 * cfg.n(), 0.0);
      for (int k = 0; k < np; ++k) {
        folded[2 * origin[k]] += f[2 * k];
        folded[2 * origin[k] + 1] += f[2 * k + 1];
      }
      for (int k = 0; k < 2 * cfg.n(); ++k) EXPECT_NEAR(folded[k], r.f[k], 1e-11);
      for (int k = 0; k < 4; ++k) EXPECT_NEAR(out.virial[k], r.out.virial[k], 1e-9) << k;
    }
    auto energy = [&](int a, int b, double eps) {
      // r_a += eps * r_b for every point
      std::vector<double> xy = patch;
      for (int k = 0; k < np; ++k) xy[2 * k + a] += eps * patch[2 * k + b];
      const tessera::Tessellation t = tessera::tessellate_local({xy.data(), np, 2}, cfg.n());
      return tessera::compute_energy(t, type_all.data(), m);
    };
    const double eps = 1e-6;
    const double scale =
        std::max({1.0, std::abs(r.out.virial[0]), std::abs(r.out.virial[1])});
    // x += eps y: dE/deps = sum dE/dx_i y_i = -sum y_i F_x,i = -W_yx
    const double d_xy = (energy(0, 1, eps) - energy(0, 1, -eps)) / (2 * eps);
    EXPECT_NEAR(-r.out.virial[3], d_xy, 1e-6 * scale) << "W_yx";
    // y += eps x: -W_xy
    const double d_yx = (energy(1, 0, eps) - energy(1, 0, -eps)) / (2 * eps);
    EXPECT_NEAR(-r.out.virial[2], d_yx, 1e-6 * scale) << "W_xy";
    // x += eps x: -W_xx (same as the periodic stretch)
    const double d_xx = (energy(0, 0, eps) - energy(0, 0, -eps)) / (2 * eps);
    EXPECT_NEAR(-r.out.virial[0], d_xx, 1e-6 * scale) << "W_xx";
    EXPECT_NEAR(r.out.virial[2], r.out.virial[3], 1e-12 * scale);
    // The shear response is not trivially zero in this configuration.
    EXPECT_GT(std::abs(d_xy), 1e-3);
  }
}
