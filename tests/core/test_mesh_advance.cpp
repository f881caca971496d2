// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh::advance (the per-step fast path: circumcentres in the fold pass,
// in-circle tests from them with a floating-point filter, cell lists copied
// where no flip touched them) against its slow oracle, Mesh::update followed
// by Mesh::cells, which must give the same tessellation bit for bit; on
// fluid runs with images and a region of interest, on an open plane whose
// convex hull changes (flips that turn triangles finite), and on points
// jittered by 1e-15..1e-9 around an exact square lattice (in-circle tests at
// round-off level, multifold vertices).

#include "tessera/energy.h"
#include "tessera/mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <cstdio>
#include <algorithm>
#include <random>
#include <vector>

namespace {

using tessera::Mesh;
using tessera::Points;
using tessera::Tessellation;

template <class T>
bool same_bits(const std::vector<T> &a, const std::vector<T> &b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Everything but the stamp.
void expect_identical(const Tessellation &a, const Tessellation &b, int step) {
  ASSERT_EQ(a.n_points, b.n_points) << "step " << step;
  ASSERT_EQ(a.n_owned, b.n_owned) << "step " << step;
  ASSERT_EQ(a.unbounded_cell, b.unbounded_cell) << "step " << step;
  EXPECT_TRUE(same_bits(a.triangles, b.triangles)) << "triangles, step " << step;
  EXPECT_TRUE(same_bits(a.vertices, b.vertices)) << "vertices, step " << step;
  EXPECT_TRUE(same_bits(a.radius, b.radius)) << "radius, step " << step;
  EXPECT_TRUE(same_bits(a.cell_offset, b.cell_offset)) << "cell_offset, step " << step;
  EXPECT_TRUE(same_bits(a.cell_vertex, b.cell_vertex)) << "cell_vertex, step " << step;
  EXPECT_TRUE(same_bits(a.cell_neighbor, b.cell_neighbor)) << "cell_neighbor, step " << step;
  EXPECT_TRUE(same_bits(a.edge_length, b.edge_length)) << "edge_length, step " << step;
  EXPECT_TRUE(same_bits(a.area, b.area)) << "area, step " << step;
  EXPECT_TRUE(same_bits(a.perimeter, b.perimeter)) << "perimeter, step " << step;
  EXPECT_TRUE(same_bits(a.triangle_group, b.triangle_group)) << "groups, step " << step;
  EXPECT_TRUE(same_bits(a.group_offset, b.group_offset)) << "group_offset, step " << step;
  EXPECT_TRUE(same_bits(a.group_point, b.group_point)) << "group_point, step " << step;
  EXPECT_TRUE(same_bits(a.group_centre, b.group_centre)) << "group_centre, step " << step;
}

// Runs both paths side by side over the positions produced by next(step, xy)
// and compares after every step.  Returns the number of steps that took the
// fast path (Mesh::incremental()).
template <class Next>
int compare_paths(std::vector<double> xy, int n_owned, int steps, const double *lo,
                  const double *hi, Next next, long *flips = nullptr, int *groups = nullptr,
                  int *grew = nullptr) {
  const int n = static_cast<int>(xy.size() / 2);
  Mesh fast, slow;
  Tessellation tf, ts;
  fast.build(Points{xy.data(), n, 2});
  slow.build(Points{xy.data(), n, 2});
  fast.cells(Points{xy.data(), n, 2}, n_owned, tf);
  slow.cells(Points{xy.data(), n, 2}, n_owned, ts);
  int fast_steps = 0;
  size_t last_nft = tf.triangles.size();
  for (int step = 0; step < steps; ++step) {
    next(step, xy);
    const Points pts{xy.data(), n, 2};
    const bool ok_fast = fast.advance(pts, n_owned, lo, hi, tf);
    const bool ok_slow = slow.update(pts, lo, hi);
    EXPECT_EQ(ok_fast, ok_slow) << "step " << step;
    if (!ok_fast || !ok_slow) {
      fast.build(pts);
      slow.build(pts);
      fast.cells(pts, n_owned, tf);
      slow.cells(pts, n_owned, ts);
      last_nft = tf.triangles.size();
      continue;
    }
    EXPECT_EQ(fast.flips_last_update(), slow.flips_last_update()) << "step " << step;
    if (flips) *flips += slow.flips_last_update();
    slow.cells(pts, n_owned, ts);
    if (fast.incremental()) {
      ++fast_steps;
      if (grew && tf.triangles.size() > last_nft) ++*grew;  // flips made triangles finite
    }
    last_nft = tf.triangles.size();
    expect_identical(tf, ts, step);
    if (groups) *groups += static_cast<int>(ts.group_centre.size());
    if (::testing::Test::HasFailure()) return fast_steps;
  }
  return fast_steps;
}

// n points of a periodic square box of side L (owned) plus their images
// within margin.
struct Images {
  double L;
  int n;
  std::vector<int> origin;
  std::vector<double> shift;
  Images(const std::vector<double> &own, double L_, double margin, double o = 0.0)
      : L(L_), n(own.size() / 2) {
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int p = 0; p < n; ++p) {
          if (i == 0 && j == 0) continue;
          const double x = own[2 * p] + i * L - o, y = own[2 * p + 1] + j * L - o;
          if (x < -margin || x > L + margin || y < -margin || y > L + margin) continue;
          origin.push_back(p);
          shift.push_back(i * L);
          shift.push_back(j * L);
        }
  }
  std::vector<double> all(const std::vector<double> &own) const {
    std::vector<double> xy(own);
    for (size_t k = 0; k < origin.size(); ++k) {
      xy.push_back(own[2 * origin[k]] + shift[2 * k]);
      xy.push_back(own[2 * origin[k] + 1] + shift[2 * k + 1]);
    }
    return xy;
  }
};

TEST(MeshAdvance, ActiveFluidWithImagesIsIdenticalToUpdateThenCells) {
  // Overdamped vertex-model forces at p0 = 3.9 plus strong noise: many flips
  // per step; the images follow their owners; the region of interest stops
  // short of the images' hull, where thin triangles fold and are frozen.
  tessera::Model model(1);
  const tessera::QuadraticParams q{1.0, 1.0, 1.0, 3.9};
  model.types[0] = tessera::cell_type_from_quadratic(q);
  model.set_lambda(0, 0, tessera::lambda_from_quadratic(q, tessera::Tension::Edge));
  for (unsigned seed : {21u, 22u}) {
    std::mt19937 rng(seed);
    const int n = 400;
    const double L = 20.0;
    std::uniform_real_distribution<double> u(0.0, L);
    std::vector<double> own(2 * n);
    for (double &c : own) c = u(rng);
    const Images im(own, L, 3.0);
    std::vector<int> type(n, 0);
    const tessera::Box box = tessera::Box::rect(0, L, 0, L);
    std::normal_distribution<double> g(0.0, 1.0);
    const double lo[2] = {-2.0, -2.0}, hi[2] = {L + 2.0, L + 2.0};
    long flips = 0;
    auto next = [&](int, std::vector<double> &xy) {
      std::vector<double> f;
      tessera::periodic_forces(box, Points{own.data(), n, 2}, type.data(), model, f);
      for (size_t k = 0; k < own.size(); ++k)
        own[k] += 0.01 * f[k] + std::sqrt(2.0 * 0.05 * 0.01) * g(rng);
      xy = im.all(own);  // the same images, rigidly attached to their owners
    };
    const int fast = compare_paths(im.all(own), n, 200, lo, hi, next, &flips);
    if (::testing::Test::HasFailure()) return;
    EXPECT_GT(flips, 500) << "seed " << seed;
    EXPECT_GT(fast, 100) << "seed " << seed;  // the fast path really ran
  }
}

TEST(MeshAdvance, OpenPlaneWithAMovingHullIsIdentical) {
  // No images: hull points move, so flips of edges to the point at infinity
  // turn triangles finite and advance() renumbers them.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  std::normal_distribution<double> g(0.0, 0.004);
  std::uniform_real_distribution<double> inner(3.5, 6.5);
  std::vector<double> xy;
  // Owned: 60 points well inside (their cells stay bounded), then 160 that
  // fill the square and make its hull.
  for (int i = 0; i < 220; ++i) {
    xy.push_back(i < 60 ? inner(rng) : u(rng));
    xy.push_back(i < 60 ? inner(rng) : u(rng));
  }
  long flips = 0;
  auto next = [&](int, std::vector<double> &p) {
    for (double &c : p) c += g(rng);
  };
  int grew = 0;
  const int fast = compare_paths(xy, 60, 300, nullptr, nullptr, next, &flips, nullptr, &grew);
  EXPECT_GT(flips, 200);
  EXPECT_GT(fast, 200);
  EXPECT_GT(grew, 5);  // the renumbering of triangles turned finite was exercised
  std::printf("%ld flips, %d fast steps, %d with more finite triangles\n", flips, fast, grew);
}

TEST(MeshAdvance, RoundOffJitterAroundASquareLatticeIsIdentical) {
  // Every in-circle test of an exact square lattice is zero: jitter of
  // 1e-15..1e-9 puts them at round-off level, where the filter must hand
  // them to the exact predicate; some steps sit exactly on the lattice
  // (four-fold vertices: groups).
  // Also far from the origin (offset 1e6, where a coordinate's rounding is
  // 1e-10, far above the cells' own round-off).
  for (double offset : {0.0, 1e6})
  for (double amp : {1e-15, 1e-12, 1e-9}) {
    const int side = 10, n = side * side;
    std::vector<double> base;
    for (int j = 0; j < side; ++j)
      for (int i = 0; i < side; ++i) {
        base.push_back(offset + i + 0.5);
        base.push_back(offset + j + 0.5);
      }
    const Images im(base, side, 2.5, offset);
    std::mt19937 rng(static_cast<unsigned>(std::lround(-std::log10(amp))));
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int groups = 0;
    auto next = [&](int step, std::vector<double> &xy) {
      std::vector<double> own(base);
      if (step % 7 != 0)
        for (double &c : own) c += amp * u(rng);
      xy = im.all(own);
    };
    const double lo[2] = {offset - 1.5, offset - 1.5}, hi[2] = {offset + side + 1.5, offset + side + 1.5};
    compare_paths(im.all(base), n, 40, lo, hi, next, nullptr, &groups);
    if (::testing::Test::HasFailure()) return;
    EXPECT_GT(groups, 0) << "amp " << amp;  // the exact lattice steps had multifold vertices
  }
}

TEST(MeshAdvance, ATessellationItDidNotFillTakesTheFullPath) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  std::vector<double> xy;
  for (int i = 0; i < 100; ++i) {
    xy.push_back(u(rng));
    xy.push_back(u(rng));
  }
  const Points pts{xy.data(), 100, 2};
  Mesh a, b;
  a.build(pts);
  b.build(pts);
  Tessellation first, other, ref;
  a.cells(pts, 0, first);
  for (double &c : xy) c += 1e-4 * u(rng);
  ASSERT_TRUE(a.advance(pts, 0, nullptr, nullptr, other));  // other: never filled
  EXPECT_FALSE(a.incremental());                            // so the full path ran
  ASSERT_TRUE(b.update(pts));
  b.cells(pts, 0, ref);
  expect_identical(other, ref, 0);
  // first is stale now (the mesh filled other since): the full path again.
  for (double &c : xy) c += 1e-4 * u(rng);
  ASSERT_TRUE(a.advance(pts, 0, nullptr, nullptr, first));
  EXPECT_FALSE(a.incremental());
}

}  // namespace

namespace {

// compute_forces' lean loop (no multifold vertex, no per-cell virial)
// against its general loop, which per-cell virials select: the same
// arithmetic in the same order, so the same bits, on random periodic
// tissues with two cell types.
TEST(ForcesLean, SameBitsAsTheGeneralLoop) {
  tessera::Model model(2);
  model.types[0] = {1.0, 1.0, 0.4};
  model.types[1] = {1.7, 0.8, 0.2};
  model.set_lambda(0, 0, -1.5);
  model.set_lambda(0, 1, 0.3);
  model.set_lambda(1, 1, -0.9);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    std::mt19937 rng(seed);
    const int n = 300;
    const double L = std::sqrt(double(n));
    std::uniform_real_distribution<double> u(0.0, L);
    std::vector<double> own(2 * n);
    for (double &c : own) c = u(rng);
    const tessera::Box box = tessera::Box::rect(0, L, 0, L);
    const Tessellation t = tessera::tessellate_periodic(box, Points{own.data(), n, 2});
    ASSERT_TRUE(t.group_centre.empty());
    const std::vector<double> xy = tessera::positions_of(t);
    std::vector<int> type(t.n_points);
    for (int p = 0; p < t.n_points; ++p) type[p] = t.origin[p] % 3 == 0;
    const Points pts{xy.data(), t.n_points, 2};
    std::vector<double> fa(2 * t.n_points, 0.0), fb(2 * t.n_points, 0.0), ea(n), eb(n), w(4 * n);
    const auto a = tessera::compute_forces(t, pts, type.data(), model, fa.data(), 2, ea.data());
    const auto b =
        tessera::compute_forces(t, pts, type.data(), model, fb.data(), 2, eb.data(), w.data());
    EXPECT_EQ(a.energy, b.energy) << "seed " << seed;
    for (int k = 0; k < 4; ++k) EXPECT_EQ(a.virial[k], b.virial[k]) << "seed " << seed;
    EXPECT_TRUE(same_bits(fa, fb)) << "seed " << seed;
    EXPECT_TRUE(same_bits(ea, eb)) << "seed " << seed;
    // Without the virial: the same forces; and the closest pair of Voronoi
    // neighbours against a plain search.
    std::vector<double> fc(2 * t.n_points, 0.0);
    const auto c = tessera::compute_forces(t, pts, type.data(), model, fc.data(), 2, nullptr,
                                           nullptr, false);
    EXPECT_TRUE(same_bits(fa, fc)) << "seed " << seed;
    EXPECT_EQ(a.energy, c.energy);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(c.virial[k], 0.0);
    double best = -1.0;
    for (int cell = 0; cell < n; ++cell)
      for (int k = t.cell_offset[cell]; k < t.cell_offset[cell + 1]; ++k) {
        const int q = t.cell_neighbor[k];
        const double d2 = std::pow(xy[2 * q] - xy[2 * cell], 2) + std::pow(xy[2 * q + 1] - xy[2 * cell + 1], 2);
        if (best < 0.0 || d2 < best) best = d2;
      }
    for (const auto *o : {&a, &b, &c}) {
      EXPECT_NEAR(o->closest_distance2, best, 1e-15 * best);
      const int p = o->closest_cell, q = o->closest_neighbor;
      ASSERT_GE(p, 0);
      EXPECT_NEAR(std::pow(xy[2 * q] - xy[2 * p], 2) + std::pow(xy[2 * q + 1] - xy[2 * p + 1], 2), best,
                  1e-15 * best);
    }
  }
}

}  // namespace

namespace {

// The forces' per-cell half run by Mesh::advance (CellPass) against
// compute_forces doing everything itself: the same bits, on a fluid run with
// images; and a pass from another step or another tessellation is ignored.
TEST(CellPass, FusedIntoAdvanceGivesTheSameForces) {
  tessera::Model model(2);
  model.types[0] = {2.0, 1.0, 2.0};
  model.types[1] = {2.0, 1.2, 1.6};
  model.set_lambda(0, 0, -7.8);
  model.set_lambda(0, 1, -6.0);
  model.set_lambda(1, 1, -7.0);
  std::mt19937 rng(31);
  const int n = 300;
  const double L = std::sqrt(double(n));
  std::uniform_real_distribution<double> u(0.0, L);
  std::normal_distribution<double> g(0.0, 0.01);
  std::vector<double> own(2 * n);
  for (double &c : own) c = u(rng);
  const Images im(own, L, 3.0);
  std::vector<double> xy = im.all(own);
  const int nall = static_cast<int>(xy.size() / 2);
  std::vector<int> type(nall);
  for (int p = 0; p < nall; ++p) type[p] = (p < n ? p : im.origin[p - n]) % 3 == 0;
  const double lo[2] = {-2.0, -2.0}, hi[2] = {L + 2.0, L + 2.0};
  Mesh mesh;
  Tessellation t;
  mesh.build(Points{xy.data(), nall, 2});
  mesh.cells(Points{xy.data(), nall, 2}, n, t);
  std::vector<double> ea(n), eb(n);
  tessera::CellPass pass;
  int fused = 0;
  for (int step = 0; step < 60; ++step) {
    for (double &c : own) c += g(rng);
    xy = im.all(own);
    const Points pts{xy.data(), nall, 2};
    pass.set(pts, type.data(), model, ea.data());
    if (!mesh.advance(pts, n, lo, hi, t, &pass)) {
      mesh.build(pts);
      mesh.cells(pts, n, t);
    }
    if (pass.covers(t)) ++fused;
    std::vector<double> fa(2 * nall, 0.0), fb(2 * nall, 0.0);
    const auto a = tessera::compute_forces(t, pts, type.data(), model, fa.data(), 2, ea.data(),
                                           nullptr, true, &pass);
    const auto b = tessera::compute_forces(t, pts, type.data(), model, fb.data(), 2, eb.data());
    ASSERT_TRUE(same_bits(fa, fb)) << "step " << step;
    ASSERT_TRUE(same_bits(ea, eb)) << "step " << step;
    ASSERT_EQ(a.energy, b.energy) << "step " << step;
    ASSERT_EQ(a.closest_cell, b.closest_cell);
    ASSERT_EQ(a.closest_neighbor, b.closest_neighbor);
    for (int k = 0; k < 4; ++k) ASSERT_EQ(a.virial[k], b.virial[k]);
  }
  EXPECT_GT(fused, 50);
  // A tessellation the pass did not see: not covered.
  Tessellation other = tessera::tessellate_local(Points{xy.data(), nall, 2}, n);
  EXPECT_FALSE(pass.covers(other));
  // The same tessellation after another advance without the pass: not covered.
  for (double &c : own) c += g(rng);
  xy = im.all(own);
  ASSERT_TRUE(mesh.advance(Points{xy.data(), nall, 2}, n, lo, hi, t));
  EXPECT_FALSE(pass.covers(t));
}

}  // namespace
