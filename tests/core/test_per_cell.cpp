// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Per-cell stiffnesses and preferred perimeter (Model::cell_KA, cell_KP,
// cell_P0; LAMMPS's d_ka, d_kp, d_perim0) in every model: the energy against
// the quadratic form written out per cell, the forces against central
// differences of the energy (confluent 2D on the lean and the general path,
// finite 2D cells, 3D polyhedra; the sphere in test_per_cell_sphere.cpp),
// the Hessian against central differences of the forces, and per-cell
// values equal to the types' giving the types' forces.
#include "per_cell_test_util.h"
#include "test_util.h"
#include "tessera/energy.h"
#include "tessera/finite.h"
#include "tessera/hessian.h"
#include "tessera/tessellation.h"
#include "tessera/voronoi3d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using testutil::Config;
using testutil::PerCell;
using testutil::Rng;
using testutil::two_types;

namespace {

void wrap2(const tessera::Box &box, double &x, double &y) {
  const double lx = box.length(0), ly = box.length(1);
  x -= lx * std::floor((x - box.lo[0]) / lx);
  y -= ly * std::floor((y - box.lo[1]) / ly);
  if (x >= box.hi[0]) x -= lx;
  if (y >= box.hi[1]) y -= ly;
}

double periodic_energy(const Config &c, const tessera::Model &m, std::vector<double> *ce = nullptr) {
  const tessera::Tessellation t = tessera::tessellate_periodic(c.box, c.points());
  std::vector<int> ty(t.n_points);
  for (int p = 0; p < t.n_points; ++p) ty[p] = c.type[t.origin[p]];
  if (ce) ce->assign(t.n_owned, 0.0);
  return tessera::compute_energy(t, ty.data(), m, ce ? ce->data() : nullptr);
}

// The forces on the owned points (images folded), by the lean path
// (cell_virial == nullptr) or the general one.
std::vector<double> periodic_forces(const Config &c, const tessera::Model &m, bool general,
                                    double *energy = nullptr) {
  const tessera::Tessellation t = tessera::tessellate_periodic(c.box, c.points());
  const std::vector<double> xy = tessera::positions_of(t);
  std::vector<int> ty(t.n_points);
  for (int p = 0; p < t.n_points; ++p) ty[p] = c.type[t.origin[p]];
  std::vector<double> fall(2 * static_cast<size_t>(t.n_points), 0.0), w(4 * t.n_owned);
  const auto out = tessera::compute_forces(t, tessera::Points{xy.data(), t.n_points, 2},
                                           ty.data(), m, fall.data(), 2, nullptr,
                                           general ? w.data() : nullptr);
  if (energy) *energy = out.energy;
  std::vector<double> f(2 * static_cast<size_t>(c.n()), 0.0);
  for (int p = 0; p < t.n_points; ++p) {
    f[2 * t.origin[p]] += fall[2 * p];
    f[2 * t.origin[p] + 1] += fall[2 * p + 1];
  }
  return f;
}

void expect_fd_2d(const Config &c, const tessera::Model &m, const std::vector<double> &f,
                  const std::string &what) {
  const double h = 1e-6;
  double fmax = 0.0, err = 0.0;
  for (double v : f) fmax = std::max(fmax, std::abs(v));
  ASSERT_GT(fmax, 1e-3) << what;
  for (int i = 0; i < c.n(); ++i)
    for (int d = 0; d < 2; ++d) {
      Config cp = c, cm = c;
      cp.xy[2 * i + d] += h;
      cm.xy[2 * i + d] -= h;
      wrap2(c.box, cp.xy[2 * i], cp.xy[2 * i + 1]);
      wrap2(c.box, cm.xy[2 * i], cm.xy[2 * i + 1]);
      const double fd = -(periodic_energy(cp, m) - periodic_energy(cm, m)) / (2 * h);
      err = std::max(err, std::abs(fd - f[2 * i + d]));
    }
  EXPECT_LT(err, 1e-6 * fmax) << what << ": max |F - F_fd| = " << err << ", max |F| = " << fmax;
}

const char *tname(tessera::Tension t) { return t == tessera::Tension::Edge ? "edge" : "cell"; }

}  // namespace

TEST(PerCell, ConfluentEnergyIsEachCellsQuadraticForm) {
  // With per-cell KA, KP, P0 and A0 every cell's energy is
  //   KA_c (A - A0_c)^2 + KP_c (P - P0_c)^2 - KP_c P0_c^2
  //     + w sum_k (Lambda_{t t_k} - Lambda_{t t}) l_k
  // (the heterotypic excess of the junction tensions stays per type pair),
  // written here from the cells' geometry, not through Model::cell_params.
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    SCOPED_TRACE(tname(tension));
    const Config cfg = testutil::random_config(40, 0.0, 0.0, 7.0, 6.0, 901, 0.3, false);
    tessera::Model m = two_types(902, tension);
    Rng rng(903);
    PerCell pc;
    pc.draw(rng, cfg.n(), 3.3, 4.2);
    pc.bind(m, 15);
    std::vector<double> ce;
    const double e = periodic_energy(cfg, m, &ce);
    const tessera::Tessellation t = tessera::tessellate_periodic(cfg.box, cfg.points());
    const double w = m.tension_weight();
    double sum = 0.0;
    for (int c = 0; c < t.n_owned; ++c) {
      const int tc = cfg.type[c];
      const double A = t.area[c], P = t.perimeter[c];
      double het = 0.0;
      for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
        het += (m.lambda_of(tc, cfg.type[t.origin[t.cell_neighbor[k]]]) - m.lambda_of(tc, tc)) *
               t.edge_length[k];
      const double ref = pc.ka[c] * (A - pc.a0[c]) * (A - pc.a0[c]) +
                         pc.kp[c] * (P - pc.p0[c]) * (P - pc.p0[c]) - pc.kp[c] * pc.p0[c] * pc.p0[c] +
                         w * het;
      EXPECT_NEAR(ce[c], ref, 1e-12 * (1.0 + std::abs(ref))) << "cell " << c;
      // The constant that completes the square.
      EXPECT_NEAR(m.quadratic_constant(c, tc), pc.kp[c] * pc.p0[c] * pc.p0[c],
                  1e-14 * pc.kp[c] * pc.p0[c] * pc.p0[c]);
      sum += ref;
    }
    EXPECT_NEAR(e, sum, 1e-11 * std::abs(sum));
  }
}

TEST(PerCell, ConfluentForcesMatchCentralDifferences) {
  // Random per-cell values, two types, both tension conventions, every
  // subset of the three per-cell arrays (with and without per-cell A0),
  // on the lean path and the general one (which agree to round-off).
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    const Config cfg = testutil::random_config(30, 0.0, 0.0, 6.0, 5.0, 911, 0.3, false);
    tessera::Model m = two_types(912, tension);
    Rng rng(913);
    PerCell pc;
    pc.draw(rng, cfg.n(), 3.0, 4.4);
    for (int which : {1, 2, 4, 6, 7, 15}) {
      const std::string what = std::string(tname(tension)) + ", arrays " + std::to_string(which);
      pc.bind(m, which);
      double el = 0.0, eg = 0.0;
      const std::vector<double> lean = periodic_forces(cfg, m, false, &el);
      const std::vector<double> general = periodic_forces(cfg, m, true, &eg);
      EXPECT_NEAR(el, eg, 1e-12 * std::abs(el)) << what;
      for (size_t k = 0; k < lean.size(); ++k)
        ASSERT_NEAR(lean[k], general[k], 1e-11) << what << " component " << k;
      expect_fd_2d(cfg, m, lean, what);
      // and the energy differs from the types' own
      tessera::Model plain = m;
      pc.bind(plain, 0);
      EXPECT_GT(std::abs(periodic_energy(cfg, plain) - el), 1e-4) << what;
    }
  }
}

TEST(PerCell, ValuesEqualToTheTypesGiveTheTypesForces) {
  // KA = K/2, KP = Gamma/2 give the types' K and Gamma exactly (a factor
  // 2), so with them alone the forces are the same bits; with P0 =
  // -w Lambda_tt / Gamma_t too they agree to round-off (1e-13).
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    SCOPED_TRACE(tname(tension));
    const Config cfg = testutil::random_config(40, 0.0, 0.0, 7.0, 6.0, 921, 0.3, false);
    tessera::Model m = two_types(922, tension);
    const double w = m.tension_weight();
    PerCell pc;
    for (int i = 0; i < cfg.n(); ++i) {
      const auto &ct = m.types[cfg.type[i]];
      pc.ka.push_back(0.5 * ct.K);
      pc.kp.push_back(0.5 * ct.Gamma);
      pc.p0.push_back(-w * m.lambda_of(cfg.type[i], cfg.type[i]) / ct.Gamma);
      pc.a0.push_back(ct.A0);
    }
    double e0 = 0.0;
    const std::vector<double> f0 = periodic_forces(cfg, m, false, &e0);
    for (bool general : {false, true}) {
      pc.bind(m, 3);
      double e1 = 0.0;
      const std::vector<double> f1 = periodic_forces(cfg, m, general, &e1);
      if (!general) {
        EXPECT_EQ(e1, e0);
        for (size_t k = 0; k < f0.size(); ++k) ASSERT_EQ(f1[k], f0[k]) << "component " << k;
      }
      pc.bind(m, 15);
      double e2 = 0.0;
      const std::vector<double> f2 = periodic_forces(cfg, m, general, &e2);
      double fmax = 0.0;
      for (double v : f0) fmax = std::max(fmax, std::abs(v));
      EXPECT_NEAR(e2, e0, 1e-13 * std::abs(e0));
      for (size_t k = 0; k < f0.size(); ++k)
        ASSERT_NEAR(f2[k], f0[k], 1e-13 * fmax) << "component " << k;
      pc.bind(m, 0);
    }
  }
}

TEST(PerCell, TypeWithoutPerimeterModulusKeepsItsTension) {
  // Gamma_t = 0 defines no preferred perimeter: a per-cell KP without P0
  // leaves the cell's own tension w Lambda_tt (shift 0); with P0 the
  // cell's linear coefficient is -2 KP P0.
  tessera::Model m(1);
  m.types[0] = tessera::CellType{1.0, 1.0, 0.0};
  m.set_lambda(0, 0, -0.6);
  const double kp[1] = {0.2}, p0[1] = {3.5};
  m.cell_KP = kp;
  auto p = m.cell_params(0, 0);
  EXPECT_EQ(p.Gamma, 0.4);
  EXPECT_EQ(p.shift, 0.0);
  m.cell_P0 = p0;
  p = m.cell_params(0, 0);
  EXPECT_DOUBLE_EQ(m.tension_weight() * m.lambda_of(0, 0) + p.shift, -0.4 * 3.5);
  EXPECT_DOUBLE_EQ(m.quadratic_constant(0, 0), 0.2 * 3.5 * 3.5);
}

TEST(PerCell, BadValuesAreNamed) {
  tessera::Model m(1);
  const double good[2] = {1.0, 1.0}, zero[2] = {1.0, 0.0}, neg[2] = {1.0, -0.5},
               inf[2] = {1.0, INFINITY};
  m.cell_KA = good;
  m.cell_KP = zero;
  m.cell_P0 = neg;
  EXPECT_NO_THROW(m.validate_cells(2));  // KP 0 and P0 < 0 have a meaning
  m.cell_KA = zero;
  try {
    m.validate_cells(2);
    ADD_FAILURE() << "KA = 0 accepted";
  } catch (const tessera::Error &e) {
    EXPECT_NE(std::string(e.what()).find("cell 1: per-cell area modulus KA must be > 0"),
              std::string::npos)
        << e.what();
  }
  m.cell_KA = good;
  m.cell_KP = neg;
  EXPECT_THROW(m.validate_cells(2), tessera::Error);
  m.cell_KP = good;
  m.cell_P0 = inf;
  EXPECT_THROW(m.validate_cells(2), tessera::Error);
  EXPECT_NO_THROW(m.validate_cells(1));  // only the owned cells are read
}

TEST(PerCell, FiniteForcesMatchCentralDifferences) {
  // An open cluster of finite cells (edges, arcs): the per-cell shift acts
  // on the whole perimeter, so contact edges and free arcs both feel P0_c.
  Rng rng(931);
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    const int n = 16;
    std::vector<double> xy;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        xy.push_back(i + 0.5 * j + rng.uniform(-0.15, 0.15));
        xy.push_back(0.85 * j + rng.uniform(-0.15, 0.15));
      }
    std::vector<int> type(n);
    for (int i = 0; i < n; ++i) type[i] = rng.below(2);
    tessera::Model m = two_types(932, tension);
    const std::vector<double> free_t = {0.2, -0.1};
    const double r = 0.7;
    PerCell pc;
    pc.draw(rng, n, 3.0, 4.4);
    for (int which : {2, 4, 15}) {
      const std::string what = std::string(tname(tension)) + ", arrays " + std::to_string(which);
      pc.bind(m, which);
      auto energy = [&](const std::vector<double> &p) {
        const auto t = tessera::finite_tessellate(tessera::Points{p.data(), n, 2}, n, r);
        return tessera::finite_energy(t, type.data(), m, free_t.data());
      };
      const auto t = tessera::finite_tessellate(tessera::Points{xy.data(), n, 2}, n, r);
      std::vector<double> f(2 * n, 0.0);
      const auto out = tessera::finite_forces(t, tessera::Points{xy.data(), n, 2}, type.data(), m,
                                              free_t.data(), f.data(), 2);
      EXPECT_NEAR(out.energy, energy(xy), 1e-12 * std::abs(out.energy));
      double fmax = 0.0, err = 0.0;
      for (double v : f) fmax = std::max(fmax, std::abs(v));
      const double h = 1e-6;
      for (int k = 0; k < 2 * n; ++k) {
        std::vector<double> p = xy, q = xy;
        p[k] += h;
        q[k] -= h;
        err = std::max(err, std::abs(-(energy(p) - energy(q)) / (2 * h) - f[k]));
      }
      EXPECT_GT(fmax, 1e-3) << what;
      EXPECT_LT(err, 1e-6 * fmax) << what << ": max |F - F_fd| = " << err;
      // The energy with these values, written out per cell: the cell's own
      // linear coefficient s_c on the whole perimeter, the heterotypic excess
      // on contacts, and on the free arcs F_t less the w Lambda_tt that s_c
      // includes (arcs carry no junction tension).
      std::vector<double> ce(n);
      tessera::finite_energy(t, type.data(), m, free_t.data(), ce.data());
      const double w = m.tension_weight();
      for (int c = 0; c < n; ++c) {
        const int tc = type[c];
        const double k_c = (which & 1) ? 2.0 * pc.ka[c] : m.types[tc].K;
        const double a0_c = (which & 8) ? pc.a0[c] : m.types[tc].A0;
        const double gamma_c = (which & 2) ? 2.0 * pc.kp[c] : m.types[tc].Gamma;
        const double s = (which & 4) ? -gamma_c * pc.p0[c]
                                     : gamma_c * (w * m.lambda_of(tc, tc) / m.types[tc].Gamma);
        double contacts = 0.0;
        for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k) {
          const auto &piece = t.pieces[k];
          if (piece.neighbor >= 0)
            contacts += (m.lambda_of(type[c], type[piece.neighbor]) - m.lambda_of(type[c], type[c])) *
                        piece.length;
        }
        const double A = t.area[c], P = t.perimeter[c];
        const double ref = 0.5 * k_c * (A - a0_c) * (A - a0_c) + 0.5 * gamma_c * P * P + s * P +
                           w * contacts + (free_t[tc] - w * m.lambda_of(tc, tc)) * t.free_length[c];
        EXPECT_NEAR(ce[c], ref, 1e-12 * (1.0 + std::abs(ref))) << what << " cell " << c;
      }
    }
  }
}

TEST(PerCell, Forces3DMatchCentralDifferences) {
  // A jittered BCC lattice of two types; per-cell KV, KS, S0 (and V0).
  Rng rng(941);
  const int nc = 2;
  const double a = 1.26;
  tessera::Box3 box;
  for (int d = 0; d < 3; ++d) {
    box.lo[d] = 0.0;
    box.hi[d] = nc * a;
  }
  std::vector<double> xyz;
  std::vector<int> type;
  for (int i = 0; i < nc; ++i)
    for (int j = 0; j < nc; ++j)
      for (int k = 0; k < nc; ++k)
        for (double b : {0.0, 0.5}) {
          xyz.push_back((i + b + 0.25) * a + rng.uniform(-0.06, 0.06));
          xyz.push_back((j + b + 0.25) * a + rng.uniform(-0.06, 0.06));
          xyz.push_back((k + b + 0.25) * a + rng.uniform(-0.06, 0.06));
          type.push_back(rng.below(2));
        }
  const int n = static_cast<int>(type.size());
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    tessera::Model m = two_types(942, tension);
    PerCell pc;
    pc.draw(rng, n, 5.0, 6.0);
    for (int which : {2, 4, 15}) {
      const std::string what = std::string(tname(tension)) + ", arrays " + std::to_string(which);
      pc.bind(m, which);
      auto energy = [&](const std::vector<double> &p) {
        const auto t = tessera::tessellate_periodic_3d(box, tessera::Points3{p.data(), n, 3});
        std::vector<int> ty(t.n_points);
        for (int q = 0; q < t.n_points; ++q) ty[q] = type[t.origin[q]];
        return tessera::compute_energy_3d(t, ty.data(), m);
      };
      std::vector<double> f;
      const auto out = tessera::periodic_forces_3d(box, tessera::Points3{xyz.data(), n, 3},
                                                   type.data(), m, f);
      EXPECT_NEAR(out.energy, energy(xyz), 1e-12 * std::abs(out.energy));
      double fmax = 0.0, err = 0.0;
      for (double v : f) fmax = std::max(fmax, std::abs(v));
      const double h = 1e-6;
      for (int k = 0; k < 3 * n; ++k) {
        std::vector<double> p = xyz, q = xyz;
        p[k] += h;
        q[k] -= h;
        err = std::max(err, std::abs(-(energy(p) - energy(q)) / (2 * h) - f[k]));
      }
      EXPECT_GT(fmax, 1e-3) << what;
      EXPECT_LT(err, 1e-6 * fmax) << what << ": max |F - F_fd| = " << err;
      tessera::Model plain = m;
      pc.bind(plain, 0);
      EXPECT_GT(std::abs(energy(xyz) - [&] {
                  const auto t = tessera::tessellate_periodic_3d(box, tessera::Points3{xyz.data(), n, 3});
                  std::vector<int> ty(t.n_points);
                  for (int q = 0; q < t.n_points; ++q) ty[q] = type[t.origin[q]];
                  return tessera::compute_energy_3d(t, ty.data(), plain);
                }()),
                1e-4)
          << what;
    }
  }
}

TEST(PerCell, HessianEqualsFiniteDifferencesOfForces) {
  // The exact Hessian (tessera::periodic_hessian) with per-cell KA, KP, P0
  // and A0 against central differences of the exact forces.
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    SCOPED_TRACE(tname(tension));
    const Config cfg = testutil::random_config(20, 0.0, 0.0, 5.0, 4.0, 951, 0.35, false);
    tessera::Model m = two_types(952, tension);
    Rng rng(953);
    PerCell pc;
    pc.draw(rng, cfg.n(), 3.0, 4.4);
    pc.bind(m, 15);
    const auto ph = tessera::periodic_hessian(cfg.box, cfg.points(), cfg.type.data(), m);
    const int n2 = 2 * cfg.n();
    std::vector<double> H(static_cast<size_t>(n2) * n2, 0.0);
    for (size_t k = 0; k < ph.hessian.val.size(); ++k)
      H[static_cast<size_t>(ph.hessian.row[k]) * n2 + ph.hessian.col[k]] += ph.hessian.val[k];
    double scale = 0.0, worst = 0.0;
    for (double v : H) scale = std::max(scale, std::abs(v));
    ASSERT_GT(scale, 0.0);
    const double h = 1e-6;
    for (int j = 0; j < n2; ++j) {
      Config cp = cfg, cm = cfg;
      cp.xy[j] += h;
      cm.xy[j] -= h;
      const std::vector<double> fp = periodic_forces(cp, m, false);
      const std::vector<double> fm = periodic_forces(cm, m, false);
      for (int i = 0; i < n2; ++i)
        worst = std::max(worst, std::abs(H[static_cast<size_t>(i) * n2 + j] + (fp[i] - fm[i]) / (2 * h)));
    }
    EXPECT_LT(worst / scale, 1e-6) << "max |H - H_fd| = " << worst << ", max |H| = " << scale;
  }
}
