// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Cells on a sphere under tiny jitter and random input: a seeded table of
// polyhedra (cube, octahedron, icosahedron, random points) with jitters
// 1e-15 .. 1e-6, and a bounded fuzzer of random and near-degenerate point
// sets.  Independent checks: the adjacency is symmetric (a pair's edge is
// counted by both cells or by neither), the graph of counted edges has Euler
// characteristic 2 (vertices joined by uncounted edges merged), the areas
// sum to 4 pi R^2, the forces have no total torque about the centre, and the
// cells equal those of the convex-hull route (a different triangulation
// code).
#include "tessera/energy.h"
#include "tessera/sphere.h"
#include "sphere_test_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

namespace {

using tessera::Vec3;
using testutil::Rng;
using namespace spheretest;

std::vector<W> cube() {
  std::vector<W> v;
  for (int a : {-1, 1})
    for (int b : {-1, 1})
      for (int c : {-1, 1}) v.push_back({1.0 * a, 1.0 * b, 1.0 * c});
  return v;
}

std::vector<W> octahedron() {
  std::vector<W> v;
  for (int s : {-1, 1}) {
    v.push_back({1.0 * s, 0.0, 0.0});
    v.push_back({0.0, 1.0 * s, 0.0});
    v.push_back({0.0, 0.0, 1.0 * s});
  }
  return v;
}

std::vector<W> random_dirs(int n, Rng &rng) {
  std::vector<W> d;
  for (int i = 0; i < n; ++i) {
    const double z = rng.uniform(-1.0, 1.0), ph = rng.uniform(0.0, 2.0 * kPi);
    const double s = std::sqrt(1.0 - z * z);
    d.push_back({s * std::cos(ph), s * std::sin(ph), z});
  }
  return d;
}

// A random rotation: three random angles about the axes.
W turn(W v, const double a[3]) {
  v = {v.x, std::cos(a[0]) * v.y - std::sin(a[0]) * v.z, std::sin(a[0]) * v.y + std::cos(a[0]) * v.z};
  v = {std::cos(a[1]) * v.x + std::sin(a[1]) * v.z, v.y, -std::sin(a[1]) * v.x + std::cos(a[1]) * v.z};
  return {std::cos(a[2]) * v.x - std::sin(a[2]) * v.y, std::sin(a[2]) * v.x + std::cos(a[2]) * v.y, v.z};
}

// The checks of the file's header on one input; what names the case.
void check(const Vec3 &c, double R, const std::vector<double> &xyz, const std::string &what) {
  SCOPED_TRACE(what);
  const int n = static_cast<int>(xyz.size() / 3);
  const tessera::Points3 pts{xyz.data(), n, 3};
  tessera::SphereTessellation t, h;
  try {
    t = tessera::tessellate_sphere(c, R, pts);
    h = tessera::tessellate_sphere(c, R, pts, nullptr, true);
  } catch (const tessera::Error &e) {
    FAIL() << e.what();
  }

  // Symmetric adjacency: every counted edge i -> j is counted j -> i, with
  // the same length.
  auto counted = [&](int i, int k) {
    const int j = t.cell_neighbor[k];
    return t.edge_length[k] > 1e-9 * R * angle(w3(t.direction[i]), w3(t.direction[j]));
  };
  long z_total = 0;
  for (int i = 0; i < n; ++i) {
    int z = 0;
    for (int k = t.cell_offset[i]; k < t.cell_offset[i + 1]; ++k) {
      z += counted(i, k);
      const int j = t.cell_neighbor[k];
      int back = -1;
      for (int m = t.cell_offset[j]; m < t.cell_offset[j + 1]; ++m)
        if (t.cell_neighbor[m] == i) back = m;
      ASSERT_GE(back, 0) << "cell " << j << " does not list " << i;
      EXPECT_EQ(counted(i, k), counted(j, back)) << "cells " << i << " and " << j << " disagree";
      EXPECT_EQ(t.edge_length[k], t.edge_length[back]) << i << " " << j;
    }
    EXPECT_EQ(z, t.coordination_number(i)) << "cell " << i;
    z_total += z;
  }
  ASSERT_EQ(z_total % 2, 0);
  // Euler: poles joined by uncounted edges are one vertex.
  const int nt = static_cast<int>(t.triangles.size());
  std::vector<int> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (int i = 0; i < n; ++i)
    for (int k = t.cell_offset[i]; k < t.cell_offset[i + 1]; ++k)
      if (!counted(i, k)) {
        const int kn = k + 1 == t.cell_offset[i + 1] ? t.cell_offset[i] : k + 1;
        parent[root(t.cell_vertex[k])] = root(t.cell_vertex[kn]);
      }
  long vertices = 0;
  for (int x = 0; x < nt; ++x) vertices += root(x) == x;
  EXPECT_EQ(vertices - z_total / 2 + n, 2) << "Euler characteristic";

  // Conditioning: a pole of points a chord d apart is known to about
  // eps / d, and the direction of an edge theta long to eps / theta (the
  // tolerances scale with them, as in the planar fuzzer).
  double dmin = 2.0, theta_min = kPi;
  for (int i = 0; i < n; ++i)
    for (int k = t.cell_offset[i]; k < t.cell_offset[i + 1]; ++k) {
      dmin = std::min(dmin, norm(w3(t.direction[i]) - w3(t.direction[t.cell_neighbor[k]])));
      if (t.edge_length[k] > 0.0) theta_min = std::min(theta_min, t.edge_length[k] / R);
    }
  const double cond = std::max(1e-12, 4.0 * 2.2e-16 / std::min(dmin, theta_min));
  // Areas: 4 pi R^2; per cell the hull route's.
  double total = 0.0;
  for (int i = 0; i < n; ++i) {
    total += t.area[i];
    EXPECT_NEAR(t.area[i], h.area[i], cond * R * R) << "cell " << i;
    EXPECT_NEAR(t.perimeter[i], h.perimeter[i], 10.0 * cond * R) << "cell " << i;
  }
  EXPECT_NEAR(total, 4.0 * kPi * R * R, 1e-13 * 4.0 * kPi * R * R);

  // No total torque about the centre (rotating everything changes nothing).
  tessera::Model m(1);
  m.types[0] = {1.0, 1.1 * 4.0 * kPi * R * R / n, 0.3};
  m.set_lambda(0, 0, -0.4);
  std::vector<int> type(n, 0);
  std::vector<double> f(3 * n, 0.0);
  const double energy = tessera::sphere_forces(t, pts, type.data(), m, f.data(), 3).energy;
  W tau{0, 0, 0};
  double scale = 0.0;
  for (int p = 0; p < n; ++p) {
    const W r = R * w3(t.direction[p]), fp{f[3 * p], f[3 * p + 1], f[3 * p + 2]};
    tau = tau + cross(r, fp);
    scale += norm(r) * norm(fp);
  }
  // (scale: the forces' own, or the energy (a torque's units) where the
  // forces vanish by symmetry)
  EXPECT_LT(norm(tau), cond * (scale + energy)) << "torque " << tau.x << " " << tau.y << " " << tau.z;
}

std::vector<double> place(const Vec3 &c, double R, const std::vector<W> &dirs, double jitter,
                          Rng &rng) {
  const double a[3] = {rng.uniform(0.0, 6.3), rng.uniform(0.0, 6.3), rng.uniform(0.0, 6.3)};
  std::vector<double> xyz;
  for (const W &d : dirs) {
    W u = turn(unit(d), a);
    u = unit(u + W{rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter),
                   rng.uniform(-jitter, jitter)});
    const W p = w3(c) + R * u;
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  }
  return xyz;
}

TEST(SphereJitter, PolyhedraAgreeAcrossNeighboursAndTileTheSphere) {
  const Vec3 c{0.3, -0.2, 1.7};
  const double R = 2.3;
  const char *names[] = {"cube", "octahedron", "icosahedron", "random"};
  for (int shape = 0; shape < 4; ++shape)
    for (double jitter : {0.0, 1e-15, 1e-13, 1e-12, 1e-11, 1e-10, 3e-10, 1e-9, 1e-8, 1e-7, 1e-6})
      for (int seed = 1; seed <= 8; ++seed) {
        Rng rng(1000 * shape + seed);
        const std::vector<W> dirs = shape == 0   ? cube()
                                    : shape == 1 ? octahedron()
                                    : shape == 2 ? icosahedron()
                                                 : random_dirs(30, rng);
        char label[64];
        std::snprintf(label, sizeof label, "%s jitter %g seed %d", names[shape], jitter, seed);
        check(c, R, place(c, R, dirs, jitter, rng), label);
      }
}

// The configuration: a cube on the sphere, jitter 3e-10 (one
// neighbour pair used to disagree: sum(6 - z) came out odd).
TEST(SphereJitter, CubeAtThreeTenthsOfANanoHasEvenCoordination) {
  const Vec3 c{0.0, 0.0, 0.0};
  for (int seed = 1; seed <= 40; ++seed) {
    Rng rng(seed);
    const auto xyz = place(c, 1.0, cube(), 3e-10, rng);
    const auto t = tessera::tessellate_sphere(c, 1.0, {xyz.data(), 8, 3});
    int sum = 0;
    for (int i = 0; i < 8; ++i) sum += 6 - t.coordination_number(i);
    EXPECT_EQ(sum % 2, 0) << "seed " << seed;
  }
}

// A bounded fuzzer: random point sets, some with near-degenerate features
// (points pushed onto a common circle, near duplicates above the 2^-23 R
// precision limit, clusters), each checked as above.
TEST(SphereFuzz, RandomAndNearDegenerateInputs) {
  const double R = 1.3;
  const Vec3 c{-0.4, 0.9, 0.2};
  for (int seed = 1; seed <= 300; ++seed) {
    Rng rng(77000 + seed);
    const int n = 8 + rng.below(50);
    std::vector<W> dirs = random_dirs(n, rng);
    const int kind = seed % 4;
    if (kind == 1) {
      // Four points onto a small circle round a random axis (a four-fold
      // vertex), then jittered.
      const W axis = random_dirs(1, rng)[0];
      const W e1 = unit(cross(axis, W{0.3, 0.5, 0.8})), e2 = cross(axis, e1);
      const double h = rng.uniform(0.6, 0.95), s = std::sqrt(1.0 - h * h);
      for (int q = 0; q < 4; ++q) {
        const double ph = 0.5 * kPi * q + rng.uniform(-0.3, 0.3);
        dirs[q] = h * axis + s * std::cos(ph) * e1 + s * std::sin(ph) * e2;
      }
    } else if (kind == 2) {
      // A near duplicate (chord 1e-6 .. 1e-4 of R).
      const W d = dirs[0];
      const double eps = std::pow(10.0, rng.uniform(-6.0, -4.0));
      dirs[1] = unit(d + eps * unit(cross(d, W{0.1, 0.7, -0.4})));
    } else if (kind == 3) {
      // A tight cluster of five.
      const W d = dirs[0];
      for (int q = 1; q < 5; ++q)
        dirs[q] = unit(d + 1e-3 * W{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
    }
    const double jitter = std::pow(10.0, -rng.uniform(6.0, 15.0));
    check(c, R, place(c, R, dirs, jitter, rng), "seed " + std::to_string(seed));
  }
}

}  // namespace
