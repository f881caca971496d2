// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Local fold repair (Mesh::update / Mesh::advance re-triangulate the region
// of a folded triangle instead of asking for a rebuild) against the
// from-scratch oracle, Mesh::build (CGAL): folds forced by large random
// displacements of a few points, and disordered starts (random sequential
// addition) relaxing under vertex-model forces, where triangles fold on
// almost every step.  Every step the repaired mesh must have the Delaunay
// triangulation's triangles (points in general position: the triangulation is
// unique) or, with images and a region of interest, the same owned cells;
// advance() must give update() + cells() bit for bit.

#include "test_util.h"
#include "tessera/energy.h"
#include "tessera/mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <set>
#include <vector>

namespace {

using tessera::Mesh;
using tessera::Points;
using tessera::Tessellation;
using testutil::triangle_set;

// Folded triangles (clockwise or flat at pts), counting only those with a
// corner below `below` (default: all).
int folded_triangles(const Tessellation &t, const Points &pts, int below = -1) {
  int n = 0;
  for (const auto &tri : t.triangles) {
    if (below >= 0 && std::min({tri[0], tri[1], tri[2]}) >= below) continue;
    const double ax = pts.x(tri[0]), ay = pts.y(tri[0]);
    const double d = (pts.x(tri[1]) - ax) * (pts.y(tri[2]) - ay) -
                     (pts.y(tri[1]) - ay) * (pts.x(tri[2]) - ax);
    n += d <= 0.0;
  }
  return n;
}

// Random sequential addition in [0, L)^2: uniform candidates, kept when no
// kept point is closer than dmin (periodic distance).  O(n^2): small n only.
std::vector<double> rsa(int n, double L, double dmin, std::mt19937 &rng) {
  std::uniform_real_distribution<double> u(0.0, L);
  std::vector<double> xy;
  while (static_cast<int>(xy.size()) < 2 * n) {
    const double x = u(rng), y = u(rng);
    bool ok = true;
    for (size_t k = 0; k < xy.size() && ok; k += 2) {
      double dx = std::fabs(x - xy[k]), dy = std::fabs(y - xy[k + 1]);
      dx = std::min(dx, L - dx);
      dy = std::min(dy, L - dy);
      ok = dx * dx + dy * dy >= dmin * dmin;
    }
    if (ok) {
      xy.push_back(x);
      xy.push_back(y);
    }
  }
  return xy;
}

// A few points jump by up to `jump` while the others stay: the mesh of the
// old positions has folded triangles around each jumper.  Free points (no
// images), so the triangulation must equal the from-scratch one exactly.
TEST(MeshRepair, LargeJumpsOfAFewPointsMatchFromScratch) {
  std::mt19937 rng(2024);
  const int n = 400;
  const double L = 20.0;
  std::vector<double> xy = rsa(n, L, 0.5, rng);
  const Points pts{xy.data(), n, 2};
  Mesh inc;
  inc.build(pts);
  // Movers are drawn from points at least 4 from the box's edges, so that
  // the folds stay off the convex hull (a fold there asks for a rebuild).
  std::vector<int> inside;
  for (int p = 0; p < n; ++p)
    if (std::min({xy[2 * p], xy[2 * p + 1], L - xy[2 * p], L - xy[2 * p + 1]}) > 4.0)
      inside.push_back(p);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(inside.size()) - 1);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  long repairs = 0, folded_steps = 0, rebuilds = 0;
  for (int step = 0; step < 200; ++step) {
    const int movers = 1 + step % 4;
    const double jump = 0.5 + 1.5 * (step % 5) / 4.0;  // 0.5 .. 2 (points ~1 apart)
    std::vector<double> old(xy);
    for (int m = 0; m < movers; ++m) {
      const int p = inside[pick(rng)];
      xy[2 * p] += jump * d(rng);
      xy[2 * p + 1] += jump * d(rng);
    }
    // Whether the old mesh has a fold at the new positions (the test really
    // exercises the repair).
    {
      Tessellation before;
      inc.cells(pts, 0, before);
      folded_steps += folded_triangles(before, pts) > 0;
    }
    bool ok = true;
    try {
      ok = inc.update(pts);
    } catch (...) {
      ok = false;
    }
    if (!ok) {
      // Only a fold on the hull or points too close may ask for a rebuild.
      ++rebuilds;
      try {
        inc.build(pts);
      } catch (const tessera::Error &) {  // two points too close: undo the move
        xy = old;
        inc.build(pts);
        continue;
      }
    }
    repairs += inc.repairs_last_update();
    Mesh fresh;
    fresh.build(pts);
    Tessellation a, b;
    inc.cells(pts, 0, a);
    fresh.cells(pts, 0, b);
    ASSERT_EQ(folded_triangles(a, pts), 0) << "step " << step;
    ASSERT_EQ(triangle_set(a), triangle_set(b)) << "step " << step;
  }
  std::printf("%ld steps with folds, %ld repairs, %ld rebuilds\n", folded_steps, repairs,
              rebuilds);
  EXPECT_GT(folded_steps, 100);
  EXPECT_GT(repairs, 100);
  EXPECT_LT(rebuilds, folded_steps / 4);  // most folds are mended locally
}

// Fold repair off: a fold makes update() return false, as before; on, the
// same fold is mended in place.
TEST(MeshRepair, OffAsksForARebuild) {
  // A jittered 7 x 7 grid; the centre point jumps past its right neighbour
  // (the corners of the folded triangles stay off the hull).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-0.1, 0.1);
  std::vector<double> xy;
  for (int j = 0; j < 7; ++j)
    for (int i = 0; i < 7; ++i) {
      xy.push_back(i + d(rng));
      xy.push_back(j + d(rng));
    }
  const int n = 49, centre = 3 * 7 + 3;
  for (const bool on : {false, true}) {
    std::vector<double> p(xy);
    Mesh m;
    m.set_fold_repair(on);
    EXPECT_EQ(m.fold_repair(), on);
    m.build(Points{p.data(), n, 2});
    p[2 * centre] += 1.35;
    p[2 * centre + 1] += 0.2;
    {
      Tessellation before;
      m.cells(Points{p.data(), n, 2}, 0, before);
      ASSERT_GT(folded_triangles(before, Points{p.data(), n, 2}), 0);
    }
    const bool ok = m.update(Points{p.data(), n, 2});
    EXPECT_EQ(ok, on);
    EXPECT_EQ(m.valid(), on);
    if (on) {
      EXPECT_GE(m.repairs_last_update(), 1);
      EXPECT_GT(m.repaired_triangles_last_update(), 6);
      Mesh fresh;
      fresh.build(Points{p.data(), n, 2});
      Tessellation a, b;
      m.cells(Points{p.data(), n, 2}, 0, a);
      fresh.cells(Points{p.data(), n, 2}, 0, b);
      EXPECT_EQ(triangle_set(a), triangle_set(b));
    }
  }
}

// Owned points of a periodic box and their images within 4.5 (the region
// of interest, 3, stops 1.5 short of the images' hull: the voids of a
// disordered start make large circumdisks).
struct Periodic : testutil::PeriodicPatch {
  Periodic(std::vector<double> own_, double L_) {
    L = L_;
    n = static_cast<int>(own_.size() / 2);
    own = std::move(own_);
    images(6.0);
    fill();
  }
};

template <class T>
bool same_bits(const std::vector<T> &a, const std::vector<T> &b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// A disordered start (random sequential addition, minimum distance 0.5,
// density 1) relaxing under the vertex-model forces at p0 = 3.9 with noise
// and a large time step: the start transient folds triangles on most steps.
// Three meshes follow it: advance() (fast path, with repair), update() +
// cells() (its slow oracle, with repair) and a from-scratch build (the
// Delaunay oracle).
TEST(MeshRepair, DisorderedStartMatchesFromScratch) {
  tessera::Model model(1);
  const tessera::QuadraticParams q{1.0, 1.0, 1.0, 3.9};
  model.types[0] = tessera::cell_type_from_quadratic(q);
  model.set_lambda(0, 0, tessera::lambda_from_quadratic(q, tessera::Tension::Edge));
  long repairs_total = 0, rebuilds_total = 0, fold_steps = 0;
  for (unsigned seed : {7u, 8u}) {
    std::mt19937 rng(seed);
    const int n = 400;
    const double L = 20.0;
    Periodic patch(rsa(n, L, 0.5, rng), L);
    std::vector<int> type(n, 0);
    const tessera::Box box = tessera::Box::rect(0, L, 0, L);
    std::normal_distribution<double> g(0.0, 1.0);
    const double lo[2] = {-3.0, -3.0}, hi[2] = {L + 3.0, L + 3.0};
    Mesh fast, slow;
    Tessellation tf, ts;
    fast.build(patch.points());
    slow.build(patch.points());
    fast.cells(patch.points(), n, tf);
    int compared = 0;
    for (int step = 0; step < 120; ++step) {
      std::vector<double> f;
      tessera::periodic_forces(box, Points{patch.own.data(), n, 2}, type.data(), model, f);
      const double dt = 0.04, D = 0.1;  // large: neighbours cross edges
      for (size_t k = 0; k < patch.own.size(); ++k)
        patch.own[k] += dt * f[k] + std::sqrt(2.0 * D * dt) * g(rng);
      // The images follow their owners (unwrapped, as between two
      // neighbour-list builds of a run).
      patch.fill();
      const Points pts = patch.points();
      {
        Tessellation before;
        slow.cells(pts, 0, before);
        fold_steps += folded_triangles(before, pts, n) > 0;  // a fold at an owned point
      }
      const bool ok_fast = fast.advance(pts, n, lo, hi, tf);
      const bool ok_slow = slow.update(pts, lo, hi);
      EXPECT_EQ(ok_fast, ok_slow) << "step " << step;
      EXPECT_EQ(fast.repairs_last_update(), slow.repairs_last_update()) << "step " << step;
      EXPECT_EQ(fast.flips_last_update(), slow.flips_last_update()) << "step " << step;
      repairs_total += slow.repairs_last_update();
      if (!ok_fast || !ok_slow) {
        ++rebuilds_total;
        fast.build(pts);
        slow.build(pts);
        fast.cells(pts, n, tf);
      }
      slow.cells(pts, n, ts);
      if (ok_fast && ok_slow) {
        EXPECT_TRUE(same_bits(tf.triangles, ts.triangles)) << "step " << step;
        EXPECT_TRUE(same_bits(tf.cell_vertex, ts.cell_vertex)) << "step " << step;
        EXPECT_TRUE(same_bits(tf.area, ts.area)) << "step " << step;
        EXPECT_TRUE(same_bits(tf.perimeter, ts.perimeter)) << "step " << step;
      }
      Mesh fresh;
      fresh.build(pts);
      Tessellation b;
      fresh.cells(pts, n, b);
      if (!tessera::check_coverage(b, lo, hi).ok) continue;
      ++compared;
      ASSERT_EQ(ts.unbounded_cell, b.unbounded_cell);
      for (int c = 0; c < n; ++c) {
        ASSERT_EQ(ts.cell_size(c), b.cell_size(c)) << "step " << step << " cell " << c;
        EXPECT_NEAR(ts.area[c], b.area[c], 1e-12) << "step " << step << " cell " << c;
        EXPECT_NEAR(ts.perimeter[c], b.perimeter[c], 1e-12) << "step " << step << " cell " << c;
        std::multiset<int> na(ts.cell_neighbor.begin() + ts.cell_offset[c],
                              ts.cell_neighbor.begin() + ts.cell_offset[c + 1]);
        std::multiset<int> nb(b.cell_neighbor.begin() + b.cell_offset[c],
                              b.cell_neighbor.begin() + b.cell_offset[c + 1]);
        EXPECT_EQ(na, nb) << "step " << step << " cell " << c;
      }
      if (::testing::Test::HasFailure()) return;
    }
    EXPECT_GT(compared, 100);
  }
  std::printf("%ld steps with folds, %ld repairs, %ld rebuilds\n", fold_steps, repairs_total,
              rebuilds_total);
  EXPECT_GT(fold_steps, 20);
  EXPECT_GT(repairs_total, 20);
  EXPECT_LT(rebuilds_total, fold_steps / 10);  // folds that reach the images' hull
}

}  // namespace
