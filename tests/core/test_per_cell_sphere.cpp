// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Per-cell stiffnesses and preferred perimeter (Model::cell_KA, cell_KP,
// cell_P0; LAMMPS's d_ka, d_kp, d_perim0) for cells on a sphere: each
// cell's energy against its quadratic form written out from the spherical
// areas and geodesic perimeters, the forces against central differences of
// the energy along geodesics, dE/dR against a central difference of the
// radius, per-cell values equal to the types' giving the types' forces, and
// bad values named.
#include "per_cell_test_util.h"
#include "test_util.h"
#include "tessera/energy.h"
#include "tessera/sphere.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using testutil::PerCell;
using testutil::Rng;
using testutil::two_types;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct D3 {
  double x, y, z;
};
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator*(double s, D3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 unit(D3 a) { return (1.0 / std::sqrt(dot(a, a))) * a; }

// n random cells on a sphere of mean cell area 1, off-centre, points off
// the sphere (they are projected), two types.
struct Cells {
  tessera::Vec3 c{0.3, -0.2, 0.5};
  double R = 1.0;
  int n = 0;
  std::vector<D3> dirs;
  std::vector<double> xyz;
  std::vector<int> type;
  Cells(int n_, uint64_t seed) : n(n_) {
    Rng rng(seed);
    R = std::sqrt(n / (4.0 * kPi));
    while (static_cast<int>(dirs.size()) < n) {
      const D3 d{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
      const double r2 = dot(d, d);
      if (r2 > 1.0 || r2 < 0.01) continue;
      dirs.push_back(unit(d));
    }
    for (const D3 &d : dirs) {
      const double r = R * rng.uniform(0.7, 1.4);
      xyz.insert(xyz.end(), {c.x + r * d.x, c.y + r * d.y, c.z + r * d.z});
      type.push_back(rng.below(2));
    }
  }
  tessera::SphereTessellation tess(const std::vector<double> &p, double radius) const {
    return tessera::tessellate_sphere(c, radius, tessera::Points3{p.data(), n, 3});
  }
  double energy(const std::vector<double> &p, const tessera::Model &m, double radius) const {
    return tessera::sphere_energy(tess(p, radius), type.data(), m);
  }
  std::vector<double> forces(const tessera::Model &m, double *energy = nullptr,
                             double *dE_dR = nullptr, std::vector<double> *ce = nullptr) const {
    const auto t = tess(xyz, R);
    std::vector<double> f(3 * static_cast<size_t>(n), 0.0);
    if (ce) ce->assign(n, 0.0);
    const auto out = tessera::sphere_forces(t, tessera::Points3{xyz.data(), n, 3}, type.data(), m,
                                            f.data(), 3, ce ? ce->data() : nullptr);
    if (energy) *energy = out.energy;
    if (dE_dR) *dE_dR = out.dE_dR;
    return f;
  }
};

PerCell random_values(Rng &rng, int n) {
  PerCell pc;
  pc.draw(rng, n, 3.3, 4.2);
  return pc;
}

const char *tname(tessera::Tension t) { return t == tessera::Tension::Edge ? "edge" : "cell"; }

}  // namespace

TEST(PerCellSphere, EnergyIsEachCellsQuadraticForm) {
  // With per-cell KA, KP, P0 and A0 every cell's energy is
  //   KA_c (A - A0_c)^2 + KP_c (P - P0_c)^2 - KP_c P0_c^2
  //     + w sum_k (Lambda_{t t_k} - Lambda_{t t}) l_k
  // with A the spherical area and P the geodesic perimeter, written here
  // from the tessellation's geometry, not through Model::cell_params.
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    SCOPED_TRACE(tname(tension));
    const Cells cells(30, 1001);
    tessera::Model m = two_types(1002, tension);
    Rng rng(1003);
    const PerCell pc = random_values(rng, cells.n);
    pc.bind(m, 15);
    std::vector<double> ce;
    double e = 0.0;
    cells.forces(m, &e, nullptr, &ce);
    const auto t = cells.tess(cells.xyz, cells.R);
    const double w = m.tension_weight();
    double sum = 0.0;
    for (int c = 0; c < cells.n; ++c) {
      const int tc = cells.type[c];
      const double A = t.area[c], P = t.perimeter[c];
      double het = 0.0;
      for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
        het += (m.lambda_of(tc, cells.type[t.cell_neighbor[k]]) - m.lambda_of(tc, tc)) *
               t.edge_length[k];
      const double ref = pc.ka[c] * (A - pc.a0[c]) * (A - pc.a0[c]) +
                         pc.kp[c] * (P - pc.p0[c]) * (P - pc.p0[c]) - pc.kp[c] * pc.p0[c] * pc.p0[c] +
                         w * het;
      EXPECT_NEAR(ce[c], ref, 1e-12 * (1.0 + std::abs(ref))) << "cell " << c;
      sum += ref;
    }
    EXPECT_NEAR(e, sum, 1e-11 * (1.0 + std::abs(sum)));
    EXPECT_NEAR(tessera::sphere_energy(t, cells.type.data(), m), e, 1e-12 * (1.0 + std::abs(e)));
  }
}

TEST(PerCellSphere, ForcesMatchCentralDifferencesAlongGeodesics) {
  // Random per-cell values, two types, both tension conventions, several
  // subsets of the per-cell arrays; each point moved along the great
  // circles through it in two tangent directions (fourth-order central
  // differences), and dE/dR against a central difference of the radius.
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    const Cells cells(24, 1011);
    tessera::Model m = two_types(1012, tension);
    Rng rng(1013);
    const PerCell pc = random_values(rng, cells.n);
    for (int which : {1, 2, 4, 7, 15}) {
      const std::string what = std::string(tname(tension)) + ", arrays " + std::to_string(which);
      pc.bind(m, which);
      double e = 0.0, dedr = 0.0;
      const std::vector<double> f = cells.forces(m, &e, &dedr);
      EXPECT_NEAR(e, cells.energy(cells.xyz, m, cells.R), 1e-12 * (1.0 + std::abs(e))) << what;
      double fmax = 0.0;
      for (double v : f) fmax = std::max(fmax, std::abs(v));
      ASSERT_GT(fmax, 1e-3) << what;
      const double R = cells.R, h = 1e-5 * R;
      double err = 0.0;
      for (int i = 0; i < cells.n; ++i) {
        const D3 u = cells.dirs[i];
        const D3 F{f[3 * i], f[3 * i + 1], f[3 * i + 2]};
        EXPECT_NEAR(dot(F, u), 0.0, 1e-13 * fmax) << what << ": force not tangent on " << i;
        const D3 e1 = unit(cross(u, std::abs(u.x) < 0.6 ? D3{1, 0, 0} : D3{0, 1, 0}));
        const D3 e2 = cross(u, e1);
        for (const D3 &dir : {e1, e2}) {
          auto at = [&](double eps) {
            std::vector<double> p = cells.xyz;
            const D3 q = D3{cells.c.x, cells.c.y, cells.c.z} +
                         R * (std::cos(eps / R) * u + std::sin(eps / R) * dir);
            p[3 * i] = q.x, p[3 * i + 1] = q.y, p[3 * i + 2] = q.z;
            return cells.energy(p, m, R);
          };
          const double fd = -(8.0 * (at(h) - at(-h)) - (at(2 * h) - at(-2 * h))) / (12.0 * h);
          err = std::max(err, std::abs(dot(F, dir) - fd));
        }
      }
      EXPECT_LT(err, 3e-7 * (fmax + 1.0)) << what << ": max |F - F_fd| = " << err
                                          << ", max |F| = " << fmax;
      const double hr = 1e-5 * R;
      const double fd_r =
          (cells.energy(cells.xyz, m, R + hr) - cells.energy(cells.xyz, m, R - hr)) / (2.0 * hr);
      EXPECT_NEAR(dedr, fd_r, 1e-6 * (std::abs(fd_r) + 1.0)) << what;
      // and the energy differs from the types' own
      tessera::Model plain = m;
      pc.bind(plain, 0);
      EXPECT_GT(std::abs(cells.energy(cells.xyz, plain, R) - e), 1e-4) << what;
    }
  }
}

TEST(PerCellSphere, ValuesEqualToTheTypesGiveTheTypesForces) {
  // KA = K/2, KP = Gamma/2 give the types' K and Gamma exactly (a factor
  // 2): the same bits; with P0 = -w Lambda_tt / Gamma_t and A0 = the
  // type's too, the same to round-off (1e-13).
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    SCOPED_TRACE(tname(tension));
    const Cells cells(40, 1021);
    tessera::Model m = two_types(1022, tension);
    const double w = m.tension_weight();
    PerCell pc;
    for (int i = 0; i < cells.n; ++i) {
      const int ti = cells.type[i];
      const auto &ct = m.types[ti];
      pc.ka.push_back(0.5 * ct.K);
      pc.kp.push_back(0.5 * ct.Gamma);
      pc.p0.push_back(-w * m.lambda_of(ti, ti) / ct.Gamma);
      pc.a0.push_back(ct.A0);
    }
    double e0 = 0.0, r0 = 0.0;
    const std::vector<double> f0 = cells.forces(m, &e0, &r0);
    double fmax = 0.0;
    for (double v : f0) fmax = std::max(fmax, std::abs(v));
    ASSERT_GT(fmax, 1e-3);
    pc.bind(m, 3);
    double e1 = 0.0, r1 = 0.0;
    const std::vector<double> f1 = cells.forces(m, &e1, &r1);
    EXPECT_EQ(e1, e0);
    EXPECT_EQ(r1, r0);
    for (size_t k = 0; k < f0.size(); ++k) ASSERT_EQ(f1[k], f0[k]) << "component " << k;
    for (int which : {4, 15}) {
      pc.bind(m, which);
      double e2 = 0.0, r2 = 0.0;
      const std::vector<double> f2 = cells.forces(m, &e2, &r2);
      EXPECT_NEAR(e2, e0, 1e-13 * std::abs(e0)) << which;
      EXPECT_NEAR(r2, r0, 1e-13 * std::abs(r0)) << which;
      for (size_t k = 0; k < f0.size(); ++k)
        ASSERT_NEAR(f2[k], f0[k], 1e-13 * fmax) << "arrays " << which << " component " << k;
      // The constant completing the square is the type's KP P0^2.
      for (int c = 0; c < cells.n; ++c)
        EXPECT_NEAR(m.quadratic_constant(c, cells.type[c]), pc.kp[c] * pc.p0[c] * pc.p0[c],
                    1e-13 * pc.kp[c] * pc.p0[c] * pc.p0[c]);
    }
    pc.bind(m, 0);
  }
}

TEST(PerCellSphere, BadValuesAreNamed) {
  // Every point is a cell: a bad value anywhere among the n_points is an
  // error naming the cell, not a NaN force.
  const Cells cells(12, 1031);
  tessera::Model m = two_types(1032, tessera::Tension::Edge);
  std::vector<double> ka(cells.n, 0.5), kp(cells.n, 0.1), p0(cells.n, 3.7);
  m.cell_KA = ka.data();
  m.cell_KP = kp.data();
  m.cell_P0 = p0.data();
  EXPECT_NO_THROW(cells.forces(m));
  ka[11] = 0.0;
  try {
    cells.forces(m);
    ADD_FAILURE() << "KA = 0 accepted on a sphere";
  } catch (const tessera::Error &e) {
    EXPECT_NE(std::string(e.what()).find("cell 11: per-cell area modulus KA must be > 0"),
              std::string::npos)
        << e.what();
  }
  ka[11] = 0.5;
  p0[3] = NAN;
  EXPECT_THROW(cells.forces(m), tessera::Error);
  const auto t = cells.tess(cells.xyz, cells.R);
  EXPECT_THROW(tessera::sphere_energy(t, cells.type.data(), m), tessera::Error);
}
