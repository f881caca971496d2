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
      // (each site is a corner of 12 squares)
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
      double vsum_m = 0.0;
      for (int i = 0; i < c.n(); ++i) vsum_m += tm.volume[i];
      EXPECT_NEAR(vsum_m, c.box.volume(), 1e-10 * c.box.volume());
      const std::vector<double> fm = folded(tm, all, t.origin, c.n(), m);
      EXPECT_LT(testutil::max_abs(fm), 1e-10)
          << "Mesh3: lo " << cs[0] << " tilts " << cs[1] << " " << cs[2] << " a " << a;
    }
  EXPECT_EQ(with_edges, 14);
}

namespace {

// Forces of the periodic configuration c (types ty), folded; both builders.
std::vector<double> forces(const Lattice &c, const std::vector<int> &type, const Model &m,
                           bool mesh3, size_t *edges = nullptr) {
  Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
  const Points3 all{t.position.data(), t.n_points, 3};
  if (mesh3) {
    Mesh3 mesh;
    mesh.build(all);
    Tessellation3 tm;
    mesh.cells(all, c.n(), tm);
    tm.origin = t.origin;
    t = tm;
  }
  if (edges) *edges = t.fourfold.size();
  std::vector<int> ty(t.n_points);
  for (int p = 0; p < t.n_points; ++p) ty[p] = type[t.origin[p]];
  std::vector<double> fall(3 * static_cast<size_t>(t.n_points), 0.0), f(3 * c.n(), 0.0);
  compute_forces_3d(t, all, ty.data(), m, fall.data(), 3);
  for (int p = 0; p < t.n_points; ++p)
    for (int d = 0; d < 3; ++d) f[3 * t.origin[p] + d] += fall[3 * p + d];
  return f;
}

double energy(const Lattice &c, const std::vector<int> &type, const Model &m) {
  std::vector<double> f;
  return periodic_forces_3d(c.box, c.points(), type.data(), m, f).energy;
}

// Coordinate q of c moved by h, wrapped back into the box.
Lattice moved(const Lattice &c, int q, double h) {
  Lattice p = c;
  p.xyz[q] += h;
  double *x = &p.xyz[q - q % 3];
  const Region3 r = p.box.region();
  const double *e[3] = {r.a, r.b, r.c};
  for (int pass = 0; pass < 6; ++pass) {
    double s[3];
    p.box.fractional(x, s);
    int k = 0;
    while (k < 3 && s[k] >= 0.0 && s[k] < 1.0) ++k;
    if (k == 3) break;
    const double sg = s[k] < 0.0 ? 1.0 : -1.0;
    for (int d = 0; d < 3; ++d) x[d] += sg * e[k][d];
  }
  return p;
}

double sum_abs(const std::vector<double> &f) {
  double s = 0.0;
  for (double x : f) s += std::fabs(x);
  return s;
}

}  // namespace

// Two cell types on a simple cubic lattice in a tilted box with rounded
// coordinates: the forces are not zero, but at every square the mean of
// the branches, so moving a site along a coordinate (which takes every
// square it is a corner of from one branch to the other) gives one-sided
// derivatives whose mean is the force; the forces sum to zero; CGAL and
// Mesh3 (which break the ties differently) give the same forces.
TEST(FourFold3D, TwoTypeTiltedSimpleCubicForcesAreTheMeanOfTheOneSidedDerivatives) {
  const Model m = testutil::two_types_fixed(0.9, 1.1);
  const Lattice c = sc(3, 1.0, 0.3, 1.0, 0.0);
  testutil::Rng rng(5);
  std::vector<int> type(c.n());
  for (int &ty : type) ty = rng.below(2);
  size_t edges = 0;
  const std::vector<double> f = forces(c, type, m, false, &edges);
  const std::vector<double> fm = forces(c, type, m, true);
  EXPECT_GT(edges, 0u);
  const double fmax = testutil::max_abs(f);
  ASSERT_GT(fmax, 1e-2);
  double sx[3] = {0, 0, 0};
  for (int i = 0; i < c.n(); ++i)
    for (int d = 0; d < 3; ++d) sx[d] += f[3 * i + d];
  for (int d = 0; d < 3; ++d) EXPECT_LT(std::fabs(sx[d]), 1e-12 * sum_abs(f));
  for (size_t q = 0; q < f.size(); ++q) ASSERT_NEAR(fm[q], f[q], 1e-10 * fmax) << "coordinate " << q;
  const double h = 1e-6, e0 = energy(c, type, m);
  double err = 0.0, jump = 0.0;
  for (int k = 0; k < 16; ++k) {
    const int q = rng.below(3 * c.n());
    const double right = -(energy(moved(c, q, h), type, m) - e0) / h;
    const double left = -(e0 - energy(moved(c, q, -h), type, m)) / h;
    jump = std::max(jump, std::fabs(right - left));
    err = std::max(err, std::fabs(0.5 * (right + left) - f[q]));
  }
  EXPECT_GT(jump, 1e-2);  // the kinks are there
  EXPECT_LT(err, 1e-6 * fmax) << "one-sided derivatives differ by up to " << jump;
}

// Jittered simple cubic lattices.  By 1e-3 (generic: no four-fold edge is
// found) the forces are the central differences of the energy.  By 1e-12
// (within the rule's tolerance: every square is treated as one) CGAL and
// Mesh3 give the same forces, which sum to zero (before the rule the
// slivers there made them differ by up to the forces' own size).
TEST(FourFold3D, JitteredSimpleCubic) {
  const Model m = testutil::two_types_fixed(0.9, 1.1);
  testutil::Rng rng(9);
  Lattice c = sc(3, 1.0, 0.3, 1.0, 0.0);
  std::vector<int> type(c.n());
  for (int &ty : type) ty = rng.below(2);
  for (const double jit : {1e-3, 1e-12}) {
    Lattice j = c;
    for (int q = 0; q < 3 * j.n(); ++q) j = moved(j, q, jit * rng.uniform(-1.0, 1.0));
    size_t edges = 0, edges_m = 0;
    const std::vector<double> f = forces(j, type, m, false, &edges);
    const std::vector<double> fm = forces(j, type, m, true, &edges_m);
    EXPECT_EQ(edges, edges_m);
    const double fmax = testutil::max_abs(f);
    for (size_t q = 0; q < f.size(); ++q) ASSERT_NEAR(fm[q], f[q], 1e-9 * fmax) << "jitter " << jit;
    double sx[3] = {0, 0, 0};
    for (int i = 0; i < j.n(); ++i)
      for (int d = 0; d < 3; ++d) sx[d] += f[3 * i + d];
    for (int d = 0; d < 3; ++d) EXPECT_LT(std::fabs(sx[d]), 1e-12 * sum_abs(f)) << "jitter " << jit;
    if (jit == 1e-3) {
      EXPECT_EQ(edges, 0u);
      const double h = 1e-7;
      double err = 0.0;
      for (int k = 0; k < 16; ++k) {
        const int q = rng.below(3 * j.n());
        const double cd = -(energy(moved(j, q, h), type, m) - energy(moved(j, q, -h), type, m)) / (2 * h);
        err = std::max(err, std::fabs(cd - f[q]));
      }
      EXPECT_LT(err, 1e-6 * fmax);
    } else {
      EXPECT_GT(edges, 0u);
    }
  }
}

// The per-cell virials (each cell's forces, the four-fold edges' direct
// routes included, about its centre) add up to the total virial on a
// two-type tilted simple cubic lattice.
TEST(FourFold3D, CellVirialsAddUpAtFourFoldEdges) {
  const Model m = testutil::two_types_fixed(0.9, 1.1);
  const Lattice c = sc(3, 1.0, 0.3, 1.0, 0.0);
  testutil::Rng rng(8);
  std::vector<int> type(c.n());
  for (int &ty : type) ty = rng.below(2);
  const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
  ASSERT_FALSE(t.fourfold.empty());
  const Points3 all{t.position.data(), t.n_points, 3};
  std::vector<int> ty(t.n_points);
  for (int p = 0; p < t.n_points; ++p) ty[p] = type[t.origin[p]];
  std::vector<double> f(3 * static_cast<size_t>(t.n_points), 0.0), cv(9 * c.n(), 0.0);
  const ForceOutput3 out = compute_forces_3d(t, all, ty.data(), m, f.data(), 3, nullptr, cv.data());
  double scale = 0.0;
  for (double v : out.virial) scale = std::max(scale, std::fabs(v));
  for (int a = 0; a < 9; ++a) {
    double s = 0.0;
    for (int i = 0; i < c.n(); ++i) s += cv[9 * i + a];
    EXPECT_NEAR(s, out.virial[a], 1e-10 * scale) << "component " << a;
  }
}
