// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The incremental mesh (Mesh::update, Lawson flips) against the from-scratch
// triangulation (Mesh::build, CGAL) on long random walks with many neighbour
// exchanges, on moving convex hulls, and through degenerate lattices.

#include "test_util.h"
#include "tessera/energy.h"
#include "tessera/mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <vector>

namespace {

using tessera::Mesh;
using tessera::Points;
using tessera::Tessellation;
using testutil::triangle_set;

// Points in a periodic box plus their images within a margin; move() keeps
// images rigidly attached to their owners.
struct Patch : testutil::PeriodicPatch {
  // n_ = side^2 points on a square grid jittered by +-jitter (jitter >= 0.5:
  // uniformly random).
  Patch(int n_, double margin, std::mt19937 &rng, double jitter = 1.0) {
    L = std::sqrt(double(n_));
    n = n_;
    std::uniform_real_distribution<double> u(0.0, L), d(-jitter, jitter);
    const int side = static_cast<int>(std::lround(L));
    for (int i = 0; i < n; ++i) {
      if (jitter >= 0.5) {
        own.push_back(u(rng));
        own.push_back(u(rng));
      } else {
        own.push_back(i % side + 0.5 + d(rng));
        own.push_back(i / side + 0.5 + d(rng));
      }
    }
    images(margin);
    fill();
  }
  void move(double step, std::mt19937 &rng) {
    std::normal_distribution<double> g(0.0, step);
    for (double &c : own) c += g(rng);
    fill();
  }
};

void expect_same_cells(const Tessellation &a, const Tessellation &b) {
  ASSERT_EQ(a.n_owned, b.n_owned);
  for (int c = 0; c < a.n_owned; ++c) {
    ASSERT_EQ(a.cell_size(c), b.cell_size(c)) << "cell " << c;
    EXPECT_NEAR(a.area[c], b.area[c], 1e-12) << "cell " << c;
    EXPECT_NEAR(a.perimeter[c], b.perimeter[c], 1e-12) << "cell " << c;
    std::multiset<int> na(a.cell_neighbor.begin() + a.cell_offset[c],
                          a.cell_neighbor.begin() + a.cell_offset[c + 1]);
    std::multiset<int> nb(b.cell_neighbor.begin() + b.cell_offset[c],
                          b.cell_neighbor.begin() + b.cell_offset[c + 1]);
    EXPECT_EQ(na, nb) << "cell " << c;
  }
}

TEST(Mesh, FluidTissueMatchesFromScratch) {
  // An active-fluid-like run: overdamped vertex-model forces (p0 = 3.9, above
  // the rigidity transition) plus strong noise, so that neighbours change
  // every step somewhere; the images follow their owners.
  tessera::Model model(1);
  const tessera::QuadraticParams q{1.0, 1.0, 1.0, 3.9};
  model.types[0] = tessera::cell_type_from_quadratic(q);
  model.set_lambda(0, 0, tessera::lambda_from_quadratic(q, tessera::Tension::Edge));
  for (unsigned seed : {11u, 12u}) {
    std::mt19937 rng(seed);
    Patch patch(400, 3.0, rng, 0.3);
    std::vector<int> type(patch.n, 0);
    const tessera::Box box = tessera::Box::rect(0, patch.L, 0, patch.L);
    std::normal_distribution<double> g(0.0, 1.0);
    Mesh inc;
    inc.build(patch.points());
    long flips = 0, rebuilds = 0;
    // The images reach 3 beyond the box; the region of interest stops 1
    // short of the hull, where thin triangles fold and are frozen.
    const double lo[2] = {-2.0, -2.0}, hi[2] = {patch.L + 2.0, patch.L + 2.0};
    int compared = 0;
    for (int step = 0; step < 300; ++step) {
      std::vector<double> f;
      tessera::periodic_forces(box, Points{patch.own.data(), patch.n, 2}, type.data(), model, f);
      const double dt = 0.01;
      for (size_t k = 0; k < patch.own.size(); ++k)
        patch.own[k] += dt * f[k] + std::sqrt(2.0 * 0.05 * dt) * g(rng);
      patch.fill();
      if (!inc.update(patch.points(), lo, hi)) {
        ++rebuilds;
        inc.build(patch.points());
      }
      flips += inc.flips_last_update();
      Mesh fresh;
      fresh.build(patch.points());
      Tessellation a, b;
      inc.cells(patch.points(), patch.n, a);
      fresh.cells(patch.points(), patch.n, b);
      ASSERT_EQ(a.unbounded_cell, b.unbounded_cell);
      if (!tessera::check_coverage(b, lo, hi).ok) continue;  // owned cells not certified
      ++compared;
      expect_same_cells(a, b);
      if (::testing::Test::HasFailure()) return;
    }
    EXPECT_GT(compared, 200);
    EXPECT_GT(flips, 1000);  // the run really exercised the flips
    EXPECT_LT(rebuilds, 30);
    std::printf("seed %u: %ld flips, %ld rebuilds in 300 steps\n", seed, flips, rebuilds);
  }
}

TEST(Mesh, MovingConvexHull) {
  // Free points in the plane (no images): hull points move too, so the hull
  // changes through flips of edges to the point at infinity.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  std::normal_distribution<double> g(0.0, 0.08);
  std::vector<double> xy;
  for (int i = 0; i < 150; ++i) {
    xy.push_back(u(rng));
    xy.push_back(u(rng));
  }
  Mesh inc;
  inc.build(Points{xy.data(), 150, 2});
  for (int step = 0; step < 200; ++step) {
    for (double &c : xy) c += g(rng);
    const Points pts{xy.data(), 150, 2};
    if (!inc.update(pts)) inc.build(pts);
    Mesh fresh;
    fresh.build(pts);
    Tessellation a, b;
    inc.cells(pts, 0, a);
    fresh.cells(pts, 0, b);
    ASSERT_EQ(triangle_set(a), triangle_set(b)) << "step " << step;
  }
}

TEST(Mesh, ThroughDegenerateSquareLattice) {
  // Points oscillate through an exact square lattice (every vertex 4-fold),
  // crossing the degeneracy in both directions: the incremental mesh and a
  // fresh one may pick different diagonals there, but cells and forces agree.
  const int side = 8;
  const double L = side;
  std::vector<double> base;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      base.push_back(i + 0.5);
      base.push_back(j + 0.5);
    }
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> dir(base.size());
  for (double &d : dir) d = g(rng);
  const int n = side * side;
  std::vector<int> type(9 * n, 0);
  tessera::Model model(1);
  model.types[0] = {1.0, 1.0, 0.3};
  model.set_lambda(0, 0, -0.7);
  Mesh inc;
  for (int step = 0; step <= 40; ++step) {
    const double amp = 0.02 * std::cos(0.4 * step) * (step % 10 == 0 ? 0.0 : 1.0);
    std::vector<double> xy;
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int p = 0; p < n; ++p) {
          if (i == 0 && j == 0) continue;
        }
    // owned first, then the 8 image blocks
    for (int p = 0; p < n; ++p) {
      xy.push_back(base[2 * p] + amp * dir[2 * p]);
      xy.push_back(base[2 * p + 1] + amp * dir[2 * p + 1]);
    }
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j) {
        if (i == 0 && j == 0) continue;
        for (int p = 0; p < n; ++p) {
          xy.push_back(xy[2 * p] + i * L);
          xy.push_back(xy[2 * p + 1] + j * L);
        }
      }
    const Points pts{xy.data(), 9 * n, 2};
    if (step == 0 || !inc.update(pts)) inc.build(pts);
    Mesh fresh;
    fresh.build(pts);
    Tessellation a, b;
    inc.cells(pts, n, a);
    fresh.cells(pts, n, b);
    ASSERT_LT(a.unbounded_cell, 0);
    std::vector<double> fa(2 * 9 * n, 0.0), fb(2 * 9 * n, 0.0);
    const double ea = tessera::compute_forces(a, pts, type.data(), model, fa.data(), 2).energy;
    const double eb = tessera::compute_forces(b, pts, type.data(), model, fb.data(), 2).energy;
    EXPECT_NEAR(ea, eb, 1e-10 * std::fabs(eb)) << "step " << step;
    for (size_t k = 0; k < 2 * static_cast<size_t>(n); ++k)
      ASSERT_NEAR(fa[k], fb[k], 1e-9) << "step " << step << " component " << k;
    for (int c = 0; c < n; ++c) {
      EXPECT_NEAR(a.area[c], b.area[c], 1e-12);
      EXPECT_NEAR(a.perimeter[c], b.perimeter[c], 1e-12);
    }
    EXPECT_EQ(a.count_multifold_vertices(), b.count_multifold_vertices()) << "step " << step;
  }
}

TEST(Mesh, UpdateRefusesADifferentPointCount) {
  std::vector<double> xy = {0, 0, 1, 0, 0, 1, 1, 1, 0.5, 0.4};
  Mesh m;
  m.build(Points{xy.data(), 5, 2});
  EXPECT_FALSE(m.update(Points{xy.data(), 4, 2}));
  EXPECT_FALSE(m.valid());
}

TEST(Mesh, FoldOverAsksForRebuild) {
  // Move a point across its neighbours' edge: a triangle turns clockwise.
  std::vector<double> xy = {0, 0, 4, 0, 0, 4, 4, 4, 1, 1, 3, 3};
  Mesh m;
  m.build(Points{xy.data(), 6, 2});
  xy[8] = 3.5;  // point 4 jumps past point 5
  xy[9] = 3.6;
  const bool ok = m.update(Points{xy.data(), 6, 2});
  if (!ok) {
    EXPECT_FALSE(m.valid());
    m.build(Points{xy.data(), 6, 2});
  }
  Mesh fresh;
  fresh.build(Points{xy.data(), 6, 2});
  Tessellation a, b;
  m.cells(Points{xy.data(), 6, 2}, 0, a);
  fresh.cells(Points{xy.data(), 6, 2}, 0, b);
  EXPECT_EQ(triangle_set(a), triangle_set(b));
}

}  // namespace

namespace {

TEST(Clusters, NearlyFourFoldVerticesOfAJitteredSquareLattice) {
  // A square lattice jittered by 1e-6: no vertex is exactly four-fold, but
  // every lattice vertex is two triangles joined by an edge far shorter
  // than 1e-3; counted once each (by the copy whose lowest point is owned).
  const int side = 6, n = side * side;
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1e-6, 1e-6);
  std::vector<double> xy;
  for (int i = 0; i < n; ++i) {
    xy.push_back(i % side + 0.5 + u(rng));
    xy.push_back(i / side + 0.5 + u(rng));
  }
  const tessera::Tessellation t = tessera::tessellate_periodic(
      tessera::Box::rect(0, side, 0, side), Points{xy.data(), n, 2});
  EXPECT_EQ(t.count_multifold_vertices(), 0);
  auto count = [&](double length) {
    std::vector<int> offset, members;
    t.short_edge_clusters(length, offset, members);
    int counted = 0;
    for (size_t c = 0; c + 1 < offset.size(); ++c) {
      int lowest = -1;
      for (int k = offset[c]; k < offset[c + 1]; ++k) {
        const int p = members[k];
        if (lowest < 0 || t.origin[p] < t.origin[lowest] ||
            (t.origin[p] == t.origin[lowest] && p < lowest))
          lowest = p;
      }
      if (offset[c + 1] - offset[c] >= 4 && lowest < n) ++counted;
    }
    return counted;
  };
  EXPECT_EQ(count(1e-3), n);
  EXPECT_EQ(count(1e-9), 0);  // shorter than every junction
}

}  // namespace

// The benchmarks' plain CGAL yardstick triangulates exactly the points it is
// given: n points with h on the convex hull have 2 n - 2 - h triangles
// (Euler), here random points strictly inside a triangle plus its 3 corners.
TEST(Mesh, PlainDelaunayYardstickTriangulatesTheOwnedPoints) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> xyz = {0.0, 0.0, 7.0, 10.0, 0.0, 7.0, 0.0, 10.0, 7.0};
  const int n = 503;
  while (static_cast<int>(xyz.size()) < 3 * n) {
    const double a = u(rng), b = u(rng);
    if (a + b > 0.98 || a < 0.01 || b < 0.01) continue;
    xyz.insert(xyz.end(), {10.0 * a, 10.0 * b, 7.0});
  }
  // 20 more points far away (ghosts in the pair style): not triangulated
  for (int k = 0; k < 20; k++) xyz.insert(xyz.end(), {-50.0 - k, 3.0 * k, 7.0});
  const Points pts{xyz.data(), n + 20, 3};
  long faces = -1;
  const double seconds = tessera::time_plain_delaunay(pts, n, &faces);
  EXPECT_EQ(faces, 2L * n - 2 - 3);
  EXPECT_GE(seconds, 0.0);
  tessera::time_plain_delaunay(pts, 0, &faces);
  EXPECT_EQ(faces, 0);
}
