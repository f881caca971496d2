// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The four-fold edge rule (doc/model.md, "Four-fold edges (3D)"): at an
// isolated four-fold Voronoi edge (four coplanar, co-circular centres; at
// each end of the edge a fifth centre in general position) the energy has a
// kink, and its central difference is the mean of the two branch gradients
// (the triangulations with one diagonal of the square or the other).  The
// branches are taken from the Delaunay triangulations of the configuration
// moved a little either way, remeasured at the unmoved points
// (remeasure_3d: a branch, no four-fold edges).  The force is that mean.

#include "test_util.h"

#include "tessera/energy.h"
#include "tessera/mesh3d.h"
#include "tessera/voronoi3d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace tessera;

namespace {

struct Config3 {
  Box3 box;
  std::vector<double> xyz;
  std::vector<int> type;
  int n() const { return static_cast<int>(xyz.size() / 3); }
  Points3 points() const { return Points3{xyz.data(), n(), 3}; }
};

// A square of side 0.5 in the plane y = 1 around (1, 1, 1) (dyadic
// coordinates: exactly coplanar and co-circular), and random centres at
// least 0.6 from its centre (so that the spheres through its circle with
// radius up to 0.6 are empty: the square's Voronoi edge exists) and 0.25
// from each other, in the periodic box [0, 2]^3.
Config3 square_and_random(uint64_t seed) {
  testutil::Rng rng(seed);
  Config3 c;
  for (int d = 0; d < 3; ++d) c.box.hi[d] = 2.0;
  const double sq[4][3] = {{0.75, 1.0, 0.75}, {1.25, 1.0, 0.75}, {1.25, 1.0, 1.25}, {0.75, 1.0, 1.25}};
  for (const auto &p : sq) c.xyz.insert(c.xyz.end(), p, p + 3);
  auto dist2 = [](const double *a, const double *b) {
    double s = 0.0;
    for (int d = 0; d < 3; ++d) {
      double x = a[d] - b[d];
      x -= 2.0 * std::round(x / 2.0);
      s += x * x;
    }
    return s;
  };
  const double centre[3] = {1.0, 1.0, 1.0};
  for (int tries = 0; c.n() < 24 && tries < 100000; ++tries) {
    const double p[3] = {rng.uniform(0.0, 2.0), rng.uniform(0.0, 2.0), rng.uniform(0.0, 2.0)};
    if (dist2(p, centre) < 0.36) continue;
    bool ok = true;
    for (int j = 0; j < c.n() && ok; ++j) ok = dist2(p, &c.xyz[3 * j]) >= 0.0625;
    if (ok) c.xyz.insert(c.xyz.end(), p, p + 3);
  }
  for (int i = 0; i < c.n(); ++i) c.type.push_back(rng.below(2));
  return c;
}

// The gradient of the branch that is Delaunay at c with coordinate q moved
// by delta, evaluated at c (forces folded onto the owners).
std::vector<double> branch_forces(const Config3 &c, const Model &m, int q, double delta) {
  Config3 moved = c;
  moved.xyz[q] += delta;
  Tessellation3 t = tessellate_periodic_3d(moved.box, moved.points());
  std::vector<double> pos = t.position;
  for (int p = 0; p < t.n_points; ++p)
    if (t.origin[p] == q / 3) pos[3 * p + q % 3] -= delta;
  const Points3 all{pos.data(), t.n_points, 3};
  remeasure_3d(t, all);
  std::vector<int> ty(t.n_points);
  for (int p = 0; p < t.n_points; ++p) ty[p] = c.type[t.origin[p]];
  std::vector<double> fall(3 * static_cast<size_t>(t.n_points), 0.0), f(3 * c.n(), 0.0);
  compute_forces_3d(t, all, ty.data(), m, fall.data(), 3);
  for (int p = 0; p < t.n_points; ++p)
    for (int d = 0; d < 3; ++d) f[3 * t.origin[p] + d] += fall[3 * p + d];
  return f;
}

double energy_at(const Config3 &c, const Model &m, int q, double h) {
  Config3 moved = c;
  moved.xyz[q] += h;
  std::vector<double> f;
  return periodic_forces_3d(moved.box, moved.points(), moved.type.data(), m, f).energy;
}

}  // namespace

TEST(FourFold3D, CentralDifferenceIsTheMeanOfTheTwoBranchGradients) {
  const Model m = testutil::two_types_fixed(0.3, 0.35);
  int kinks = 0, checked = 0;
  for (uint64_t seed : {1u, 2u, 3u}) {
    const Config3 c = square_and_random(seed);
    ASSERT_EQ(c.n(), 24);
    std::vector<double> f0;
    periodic_forces_3d(c.box, c.points(), c.type.data(), m, f0);
    // The forces sum to zero (each branch's do, and so does their mean).
    double sum[3] = {0, 0, 0}, sabs = 0.0;
    for (int i = 0; i < c.n(); ++i)
      for (int d = 0; d < 3; ++d) {
        sum[d] += f0[3 * i + d];
        sabs += std::fabs(f0[3 * i + d]);
      }
    for (int d = 0; d < 3; ++d) EXPECT_LT(std::fabs(sum[d]), 1e-12 * sabs) << "seed " << seed;
    {
      // Mesh3 (the pair style's per-step path) finds the same edge and
      // gives the same forces.
      const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
      EXPECT_EQ(t.fourfold.size(), 1u) << "seed " << seed;
      const Points3 all{t.position.data(), t.n_points, 3};
      Mesh3 mesh;
      mesh.build(all);
      Tessellation3 tm;
      mesh.cells(all, c.n(), tm);
      EXPECT_EQ(tm.fourfold.size(), 1u) << "seed " << seed;
      std::vector<int> ty(t.n_points);
      for (int p = 0; p < t.n_points; ++p) ty[p] = c.type[t.origin[p]];
      std::vector<double> fall(3 * static_cast<size_t>(t.n_points), 0.0), fm(3 * c.n(), 0.0);
      compute_forces_3d(tm, all, ty.data(), m, fall.data(), 3);
      for (int p = 0; p < t.n_points; ++p)
        for (int d = 0; d < 3; ++d) fm[3 * t.origin[p] + d] += fall[3 * p + d];
      for (size_t q = 0; q < fm.size(); ++q) EXPECT_NEAR(fm[q], f0[q], 1e-10 * sabs) << "seed " << seed;
    }
    // In-plane coordinates (x, z) of the square's corners move them off
    // the circle: one sign opens a face between one diagonal pair, the
    // other between the other.
    for (int corner = 0; corner < 4; ++corner)
      for (int d : {0, 2}) {
        const int q = 3 * corner + d;
        const std::vector<double> fp = branch_forces(c, m, q, 1e-7);
        const std::vector<double> fm = branch_forces(c, m, q, -1e-7);
        const double h = 1e-6;
        const double cd = -(energy_at(c, m, q, h) - energy_at(c, m, q, -h)) / (2 * h);
        const double jump = std::fabs(fp[q] - fm[q]);
        kinks += jump > 1e-3;
        ++checked;
        const double scale = testutil::max_abs(f0) + 1.0;
        EXPECT_NEAR(0.5 * (fp[q] + fm[q]), cd, 1e-6 * scale)
            << "seed " << seed << ", coordinate " << q << ": branches " << fp[q] << ", "
            << fm[q];
        // Each one-sided derivative is one branch's gradient.
        const double right = -(energy_at(c, m, q, h) - energy_at(c, m, q, 0.0)) / h;
        const double left = -(energy_at(c, m, q, 0.0) - energy_at(c, m, q, -h)) / h;
        EXPECT_NEAR(right, fp[q], 1e-5 * scale) << "seed " << seed << ", coordinate " << q;
        EXPECT_NEAR(left, fm[q], 1e-5 * scale) << "seed " << seed << ", coordinate " << q;
        // The force is the mean of the two branches' gradients: the
        // central difference (before the four-fold rule it was one of
        // the two branches', 0.2 away).
        EXPECT_NEAR(f0[q], cd, 1e-6 * scale) << "seed " << seed << ", coordinate " << q;
        EXPECT_NEAR(f0[q], 0.5 * (fp[q] + fm[q]), 1e-9 * scale)
            << "seed " << seed << ", coordinate " << q;
      }
  }
  EXPECT_EQ(kinks, checked);  // every such move crosses the kink
}

// Five co-circular, coplanar centres (a regular pentagon, radius 0.3, in the
// plane y = 1) among random centres: a five-fold Voronoi edge, which the
// rule leaves alone (doc/model.md, "Four-fold edges (3D)"): no four-fold
// edge is recorded, so the forces are the gradient of the branch the
// triangulation chose (the remeasured tessellation's, exactly).
TEST(FourFold3D, FiveFoldEdgesAreLeftAlone) {
  const Model m = testutil::two_types_fixed(0.3, 0.35);
  Config3 c = square_and_random(4);
  const double pi = 3.141592653589793;
  // Replace the square by a pentagon (one more centre: the last random one
  // goes).
  c.xyz.resize(3 * 23);
  c.type.resize(23);
  std::vector<double> pent;
  for (int k = 0; k < 5; ++k) {
    pent.push_back(1.0 + 0.3 * std::cos(2 * pi * k / 5));
    pent.push_back(1.0);
    pent.push_back(1.0 + 0.3 * std::sin(2 * pi * k / 5));
  }
  c.xyz.erase(c.xyz.begin(), c.xyz.begin() + 12);
  c.xyz.insert(c.xyz.begin(), pent.begin(), pent.end());
  c.type.push_back(0);
  ASSERT_EQ(c.n(), 24);
  const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
  EXPECT_TRUE(t.fourfold.empty());
  // The edge is there: the energy has a kink at the pentagon (moving a
  // corner in its plane gives different one-sided derivatives).
  const double h = 1e-6, e0 = energy_at(c, m, 0, 0.0);
  const double right = (energy_at(c, m, 0, h) - e0) / h, left = (e0 - energy_at(c, m, 0, -h)) / h;
  EXPECT_GT(std::fabs(right - left), 1e-3);
  std::vector<double> f;
  periodic_forces_3d(c.box, c.points(), c.type.data(), m, f);
  for (double x : f) EXPECT_TRUE(std::isfinite(x));
  Tessellation3 b = t;
  const Points3 all{t.position.data(), t.n_points, 3};
  remeasure_3d(b, all);
  std::vector<int> ty(t.n_points);
  for (int p = 0; p < t.n_points; ++p) ty[p] = c.type[t.origin[p]];
  std::vector<double> fa(3 * static_cast<size_t>(t.n_points), 0.0), fb = fa;
  compute_forces_3d(t, all, ty.data(), m, fa.data(), 3);
  compute_forces_3d(b, all, ty.data(), m, fb.data(), 3);
  for (size_t q = 0; q < fa.size(); ++q) EXPECT_NEAR(fa[q], fb[q], 1e-12 * (1.0 + std::fabs(fb[q])));
}
