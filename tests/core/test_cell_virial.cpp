// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Per-cell virial (compute_forces' cell_virial): the cells' virials add up to
// the total, which is the strain derivative of the energy; identical cells of
// a hexagonal lattice carry equal shares; the forces are unchanged.

#include "tessera/energy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

using tessera::Points;

TEST(CellVirial, SumsToTheTotalAndLeavesForcesAlone) {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(0.0, 8.0);
  std::vector<double> xy;
  for (int i = 0; i < 64; ++i) {
    xy.push_back(u(rng));
    xy.push_back(u(rng));
  }
  const tessera::Box box = tessera::Box::rect(0, 8, 0, 8);
  const tessera::Tessellation t = tessera::tessellate_periodic(box, Points{xy.data(), 64, 2});
  const std::vector<double> pos = tessera::positions_of(t);
  std::vector<int> type(t.n_points);
  for (int p = 0; p < t.n_points; ++p) type[p] = t.origin[p] % 2;
  tessera::Model model(2);
  model.types[0] = {1.0, 1.0, 0.15};
  model.types[1] = {1.3, 0.9, 0.25};
  model.set_lambda(0, 0, -0.5);
  model.set_lambda(1, 1, -0.7);
  model.set_lambda(0, 1, 0.2);
  const Points pts{pos.data(), t.n_points, 2};
  std::vector<double> f1(2 * t.n_points, 0.0), f2(2 * t.n_points, 0.0), w(4 * 64);
  const auto plain = tessera::compute_forces(t, pts, type.data(), model, f1.data(), 2);
  const auto with = tessera::compute_forces(t, pts, type.data(), model, f2.data(), 2, nullptr, w.data());
  for (size_t k = 0; k < f1.size(); ++k) EXPECT_EQ(f1[k], f2[k]);
  double sum[4] = {0, 0, 0, 0};
  for (int c = 0; c < 64; ++c)
    for (int a = 0; a < 4; ++a) sum[a] += w[4 * c + a];
  for (int a = 0; a < 4; ++a)
    EXPECT_NEAR(sum[a], plain.virial[a], 1e-10 * (1.0 + std::fabs(plain.virial[a]))) << a;
}

TEST(CellVirial, EqualSharesOnAStrainedHexagonalLattice) {
  // A hexagonal lattice stretched along x: every cell is the same hexagon,
  // so every cell carries 1/N of the total virial, and the total is the
  // strain derivative of the energy.
  const int nx = 6, ny = 4;
  const double a = std::sqrt(2.0 / std::sqrt(3.0)), s = 1.07;  // area 1 per cell, then stretched
  const double lx = nx * a * s, ly = ny * a * std::sqrt(3.0);
  std::vector<double> xy;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      xy.push_back((i + 0.25) * a * s);
      xy.push_back((j + 0.25) * a * std::sqrt(3.0));
      xy.push_back((i + 0.75) * a * s);
      xy.push_back((j + 0.75) * a * std::sqrt(3.0));
    }
  const int n = static_cast<int>(xy.size() / 2);
  const tessera::Box box = tessera::Box::rect(0, lx, 0, ly);
  const tessera::Tessellation t = tessera::tessellate_periodic(box, Points{xy.data(), n, 2});
  const std::vector<double> pos = tessera::positions_of(t);
  std::vector<int> type(t.n_points, 0);
  tessera::Model model(1);
  model.types[0] = {1.0, 1.0, 0.2};
  model.set_lambda(0, 0, -0.6);
  std::vector<double> f(2 * t.n_points, 0.0), w(4 * n);
  const auto out = tessera::compute_forces(t, Points{pos.data(), t.n_points, 2}, type.data(), model,
                                           f.data(), 2, nullptr, w.data());
  for (int c = 0; c < n; ++c)
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR(w[4 * c + k], out.virial[k] / n, 1e-10) << "cell " << c << " component " << k;
  // dE/d(strain_xx) = -W_xx
  auto energy = [&](double e) {
    std::vector<double> q(xy);
    for (int p = 0; p < n; ++p) q[2 * p] *= 1.0 + e;
    std::vector<double> ff;
    std::vector<int> ty(n, 0);
    return tessera::periodic_forces(tessera::Box::rect(0, lx * (1.0 + e), 0, ly),
                                    Points{q.data(), n, 2}, ty.data(), model, ff)
        .energy;
  };
  const double h = 1e-6;
  EXPECT_NEAR(-(energy(h) - energy(-h)) / (2 * h), out.virial[0], 1e-6);
}

}  // namespace
