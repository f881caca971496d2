// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The four-fold edge rule on simple cubic lattices (doc/model.md,
// "Four-fold edges (3D)"): every square of the lattice is a Voronoi edge
// shared by four cells, and the force takes the mean of its two branches.
// In a box tilted by a lattice vector every cell is the same cube, so the
// forces are exactly zero (the lattice has inversion symmetry about every
// site) and each volume is the box's over N, whatever the round-off of the
// coordinates and however CGAL or Mesh3 broke the ties (before the rule the
// forces were of order 1 there).

#include "test_util.h"

#include "tessera/energy.h"
#include "tessera/mesh3d.h"
#include "tessera/voronoi3d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace tessera;

namespace {

struct Lattice {
  Box3 box;
  std::vector<double> xyz;
  int n() const { return static_cast<int>(xyz.size() / 3); }
  Points3 points() const { return Points3{xyz.data(), n(), 3}; }
};

// m^3 sites of spacing a from lo (+ 0.25 a), in a box tilted by xy = tx a,
// xz = tz a (lattice vectors), wrapped into it by whole box vectors.
Lattice sc(int m, double a, double lo, double tx, double tz) {
  Lattice c;
  for (int d = 0; d < 3; ++d) {
    c.box.lo[d] = lo;
    c.box.hi[d] = lo + m * a;
  }
  c.box.xy = tx * a;
  c.box.xz = tz * a;
  const Region3 r = c.box.region();
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        double x[3] = {lo + (i + 0.25) * a, lo + (j + 0.25) * a, lo + (k + 0.25) * a};
        for (int pass = 0; pass < 4; ++pass) {
          double s[3];
          c.box.fractional(x, s);
          if (s[0] < 0.0)
            for (int d = 0; d < 3; ++d) x[d] += r.a[d];
          else if (s[0] >= 1.0)
            for (int d = 0; d < 3; ++d) x[d] -= r.a[d];
          else
            break;
        }
        c.xyz.insert(c.xyz.end(), x, x + 3);
      }
  return c;
}

Model one_type() {
  Model m(1);
  m.types[0].K = 1.0;
  m.types[0].A0 = 0.9;
  m.types[0].Gamma = 0.2;
  m.set_lambda(0, 0, -0.5);
  return m;
}

// Forces of t (points pts, all of type 0) folded onto the owners.
std::vector<double> folded(const Tessellation3 &t, const Points3 &pts, const std::vector<int> &origin,
                           int n, const Model &m) {
  std::vector<int> ty(t.n_points, 0);
  std::vector<double> fall(3 * static_cast<size_t>(t.n_points), 0.0), f(3 * n, 0.0);
  compute_forces_3d(t, pts, ty.data(), m, fall.data(), 3);
  for (int p = 0; p < t.n_points; ++p)
    for (int d = 0; d < 3; ++d) f[3 * origin[p] + d] += fall[3 * p + d];
  return f;
}

}  // namespace

TEST(FourFold3D, TiltedSimpleCubicHasZeroForcesBothBuilders) {
  const Model m = one_type();
  const double cases[][4] = {{0.0, 0.0, 0.0}, {0.3, 1.0, 0.0}, {0.3, 2.0, 0.0}, {0.3, 1.0, 1.0},
                             {-1.7, -1.0, 2.0}, {100.1, 1.0, 0.0}, {0.1, 1.0, -1.0}};
  int with_edges = 0;
  for (const auto &cs : cases)
    for (double a : {1.0, 0.7}) {
      const Lattice c = sc(3, a, cs[0], cs[1], cs[2]);
      const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
      const Points3 all{t.position.data(), t.n_points, 3};
      // Every site's three squares with it at a corner... and more: each
      // owned site is a corner of 12 squares.
      with_edges += !t.fourfold.empty();
      double vsum = 0.0;
      const double v0 = a * a * a;
      for (int i = 0; i < c.n(); ++i) {
        vsum += t.volume[i];
        EXPECT_NEAR(t.volume[i], v0, 1e-12 * v0) << "cell " << i;
      }
      EXPECT_NEAR(vsum, c.box.volume(), 1e-10 * c.box.volume());
      const std::vector<double> f = folded(t, all, t.origin, c.n(), m);
      EXPECT_LT(testutil::max_abs(f), 1e-10)
          << "lo " << cs[0] << " tilts " << cs[1] << " " << cs[2] << " a " << a;
      // Mesh3 on the same points (the pair style's per-step path).
      Mesh3 mesh;
      mesh.build(all);
      Tessellation3 tm;
      mesh.cells(all, c.n(), tm);
      EXPECT_EQ(tm.fourfold.size(), t.fourfold.size());
      const std::vector<double> fm = folded(tm, all, t.origin, c.n(), m);
      EXPECT_LT(testutil::max_abs(fm), 1e-10)
          << "Mesh3: lo " << cs[0] << " tilts " << cs[1] << " " << cs[2] << " a " << a;
    }
  EXPECT_EQ(with_edges, 14);
}
