// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Tilted (triclinic) periodic boxes: the same lattice described with a tilt
// of a whole box length is the same tessellation; areas fill the box; forces
// are the finite differences of the energy; the shear component of the
// virial is the derivative of the energy under simple shear.

#include "tessera/energy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

using tessera::Box;
using tessera::Points;

struct TiltedCase {
  Box box;
  std::vector<double> xy;
  std::vector<int> type;
  tessera::Model model{2};
};

TiltedCase random_setup(double tilt, unsigned seed, int n = 60) {
  TiltedCase s;
  s.box = Box::rect(0.0, 8.0, 0.0, 7.5);
  s.box.xy = tilt;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    const double fx = u(rng), fy = u(rng);
    s.xy.push_back(fx * 8.0 + fy * tilt);
    s.xy.push_back(fy * 7.5);
    s.type.push_back(i % 2);
  }
  s.model.types[0] = {1.0, 1.0, 0.12};
  s.model.types[1] = {1.3, 0.9, 0.2};
  s.model.set_lambda(0, 0, -0.45);
  s.model.set_lambda(1, 1, -0.6);
  s.model.set_lambda(0, 1, 0.1);
  return s;
}

double energy(const TiltedCase &s, const std::vector<double> &xy, const Box &box) {
  std::vector<double> f;
  return tessera::periodic_forces(box, Points{xy.data(), static_cast<int>(xy.size() / 2), 2},
                                  s.type.data(), s.model, f)
      .energy;
}

TEST(Triclinic, AreasFillTheBox) {
  for (double tilt : {-3.0, 2.5, 7.9}) {
    const TiltedCase s = random_setup(tilt, 3);
    const auto t = tessera::tessellate_periodic(s.box, Points{s.xy.data(), 60, 2});
    double area = 0.0;
    for (double a : t.area) area += a;
    EXPECT_NEAR(area, s.box.area(), 1e-9) << "tilt " << tilt;
  }
}

TEST(Triclinic, WholeBoxTiltIsTheSameLattice) {
  // Tilts differing by the box length describe the same periodic tiling.
  TiltedCase a = random_setup(1.5, 9), b = a;
  b.box.xy = 1.5 - 8.0;
  std::vector<double> fa, fb;
  const double ea = tessera::periodic_forces(a.box, Points{a.xy.data(), 60, 2}, a.type.data(),
                                             a.model, fa)
                        .energy;
  const double eb = tessera::periodic_forces(b.box, Points{b.xy.data(), 60, 2}, b.type.data(),
                                             b.model, fb)
                        .energy;
  EXPECT_NEAR(ea, eb, 1e-10 * std::fabs(ea));
  for (size_t k = 0; k < fa.size(); ++k) EXPECT_NEAR(fa[k], fb[k], 1e-9) << k;
}

TEST(Triclinic, ForcesAreFiniteDifferences) {
  for (unsigned seed : {4u, 5u}) {
    const TiltedCase s = random_setup(2.7, seed);
    std::vector<double> f;
    tessera::periodic_forces(s.box, Points{s.xy.data(), 60, 2}, s.type.data(), s.model, f);
    const double h = 1e-6;
    for (size_t k = 0; k < s.xy.size(); ++k) {
      std::vector<double> p = s.xy, m = s.xy;
      p[k] += h;
      m[k] -= h;
      const double fd = -(energy(s, p, s.box) - energy(s, m, s.box)) / (2 * h);
      EXPECT_NEAR(f[k], fd, 1e-6 * std::max(1.0, std::fabs(fd))) << "component " << k;
    }
  }
}

TEST(Triclinic, ShearVirialIsTheShearDerivative) {
  // Simple shear x -> x + g (y - ylo), tilt xy -> xy + g ly: dE/dg = -W_yx.
  const TiltedCase s = random_setup(1.1, 7);
  std::vector<double> f;
  const auto out =
      tessera::periodic_forces(s.box, Points{s.xy.data(), 60, 2}, s.type.data(), s.model, f);
  auto sheared = [&](double g) {
    std::vector<double> q = s.xy;
    for (size_t p = 0; p < q.size() / 2; ++p) q[2 * p] += g * (q[2 * p + 1] - s.box.lo[1]);
    Box b = s.box;
    b.xy += g * s.box.length(1);
    return energy(s, q, b);
  };
  const double h = 1e-6;
  const double dE = (sheared(h) - sheared(-h)) / (2 * h);
  EXPECT_NEAR(dE, -out.virial[3], 1e-6 * std::max(1.0, std::fabs(dE)));
  EXPECT_NEAR(out.virial[2], out.virial[3], 1e-9 * std::max(1.0, std::fabs(out.virial[2])));
}

TEST(Triclinic, WrapIntoTiltedBox) {
  Box box = Box::rect(1.0, 5.0, -1.0, 2.0);
  box.xy = 1.5;
  std::vector<double> xy = {0.0, 2.5, 9.0, -4.0, 2.0, 0.5};
  const std::vector<double> before = xy;
  tessera::wrap_into_box(box, xy);
  for (size_t p = 0; p < xy.size() / 2; ++p) {
    const double sy = (xy[2 * p + 1] - box.lo[1]) / box.length(1);
    const double sx = (xy[2 * p] - box.lo[0] - sy * box.xy) / box.length(0);
    EXPECT_GE(sy, 0.0);
    EXPECT_LT(sy, 1.0);
    EXPECT_GE(sx, 0.0);
    EXPECT_LT(sx, 1.0);
    // moved by whole lattice vectors
    const double jy = (before[2 * p + 1] - xy[2 * p + 1]) / box.length(1);
    EXPECT_NEAR(jy, std::round(jy), 1e-12);
    const double ix = (before[2 * p] - xy[2 * p] - std::round(jy) * box.xy) / box.length(0);
    EXPECT_NEAR(ix, std::round(ix), 1e-12);
  }
}

}  // namespace
