// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The cell view of cells on a sphere (tessera/sphere_cells.h): measures and
// neighbours of exact solids, the centroid against a slow oracle (the
// geodesic fan subdivided into small triangles), second moments and
// principal axes against a rectangle in the flat limit, multifold rings of
// the cube, and the caller's index map with missing points.
#include "tessera/sphere.h"
#include "tessera/sphere_cells.h"
#include "sphere_test_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

using tessera::Vec3;
using testutil::Rng;

using namespace spheretest;

std::vector<double> on_sphere(const Vec3 &c, double R, const std::vector<W> &dirs) {
  std::vector<double> xyz;
  for (const W &d : dirs) {
    const W p = w3(c) + R * unit(d);
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  }
  return xyz;
}

// Slow oracle: integral of the unit direction over the geodesic triangle
// (a, b, c), by splitting it 4^level times (midpoints pushed onto the
// sphere) and summing solid angle x centroid direction of the pieces.
W direction_integral(W a, W b, W c, int level) {
  if (level == 0) {
    const double D = dot(a, cross(b, c)), S = 1.0 + dot(a, b) + dot(b, c) + dot(c, a);
    return (2.0 * std::atan2(D, S)) * unit(a + b + c);
  }
  const W ab = unit(a + b), bc = unit(b + c), ca = unit(c + a);
  return direction_integral(a, ab, ca, level - 1) + direction_integral(ab, b, bc, level - 1) +
         direction_integral(ca, bc, c, level - 1) + direction_integral(ab, bc, ca, level - 1);
}

TEST(SphereCells, IcosahedronViewGivesRegularPentagons) {
  const Vec3 c{0.3, -0.2, 1.1};
  const double R = 2.5;
  const auto xyz = on_sphere(c, R, icosahedron());
  const tessera::SphereTessellation t = tessera::tessellate_sphere(c, R, {xyz.data(), 12, 3});
  tessera::SphereCells v;
  v.bind(t);
  EXPECT_EQ(v.dimension(), 2);
  EXPECT_EQ(v.space_dimension(), 3);
  ASSERT_EQ(v.n_owned(), 12);
  for (int i = 0; i < 12; ++i) {
    EXPECT_NEAR(v.measure(i), 4.0 * kPi * R * R / 12.0, 1e-12);
    EXPECT_EQ(v.coordination_number(i), 5);
    EXPECT_NEAR(v.shape_index(i), v.boundary(i) / std::sqrt(v.measure(i)), 1e-14);
    double x[3], p[3], ax[3];
    v.centroid(i, x);
    v.point(i, p);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(x[d], p[d], 1e-12);
    EXPECT_FALSE(v.principal_axis(i, true, ax));  // a regular pentagon is isotropic
    // Corners: the pieces close into the polygon, each on the sphere.
    std::vector<double> corners;
    for (int k = v.piece_begin(i); k < v.piece_end(i); ++k) {
      corners.clear();
      ASSERT_EQ(v.piece_corners(k, corners), 2);
      const W a{corners[0] - c.x, corners[1] - c.y, corners[2] - c.z};
      EXPECT_NEAR(norm(a), R, 1e-12);
      const int next = k + 1 < v.piece_end(i) ? k + 1 : v.piece_begin(i);
      std::vector<double> nc;
      v.piece_corners(next, nc);
      for (int d = 0; d < 3; ++d) EXPECT_EQ(corners[3 + d], nc[d]);
    }
  }
  EXPECT_EQ(v.multifold_count(), 0);
  const tessera::Contacts ct = v.contacts();
  EXPECT_EQ(ct.n_owned, 12);
  EXPECT_EQ(ct.offset[12], 60);
}

TEST(SphereCells, CentroidMatchesASubdividedFan) {
  Rng rng(71);
  const Vec3 c{1.0, 2.0, -0.5};
  const double R = 3.0;
  std::vector<W> dirs;
  for (int i = 0; i < 40; ++i) {
    const double z = rng.uniform(-1.0, 1.0), ph = rng.uniform(0.0, 2.0 * kPi);
    const double s = std::sqrt(1.0 - z * z);
    dirs.push_back({s * std::cos(ph), s * std::sin(ph), z});
  }
  const auto xyz = on_sphere(c, R, dirs);
  const tessera::SphereTessellation t = tessera::tessellate_sphere(c, R, {xyz.data(), 40, 3});
  tessera::SphereCells v;
  v.bind(t);
  double worst = 0.0;
  for (int i = 0; i < 40; ++i) {
    const W u = w3(t.direction[i]);
    W sum{0, 0, 0};
    const int o = t.cell_offset[i], m = t.cell_size(i);
    for (int k = 0; k < m; ++k)
      sum = sum + direction_integral(u, w3(t.vertex_direction[t.cell_vertex[o + k]]),
                                     w3(t.vertex_direction[t.cell_vertex[o + (k + 1) % m]]), 6);
    const W want = w3(c) + R * unit(sum);
    double x[3];
    v.centroid(i, x);
    worst = std::max(worst, norm(W{x[0], x[1], x[2]} - want));
    // The centroid lies in the cell: it is closer to this cell's point than
    // to any neighbour's.
    const W xu = unit(W{x[0], x[1], x[2]} - w3(c));
    for (int k = o; k < o + m; ++k)
      EXPECT_GE(dot(xu, u), dot(xu, w3(t.direction[t.cell_neighbor[k]])) - 1e-12);
  }
  EXPECT_LT(worst, 1e-4 * R);  // the oracle's own error is O(4^-6)
}

// In the flat limit the cell of the origin among (+-2, 0), (0, +-1) is the
// rectangle [-1, 1] x [-1/2, 1/2]: area 2, moments 8/12 and 2/12.
TEST(SphereCells, SecondMomentsOfARectangleInTheFlatLimit) {
  const double R = 1000.0;
  const Vec3 c{0, 0, 0};
  std::vector<W> dirs = {{0, 0, R}, {2, 0, R}, {-2, 0, R}, {0, 1, R}, {0, -1, R}, {0, 0, -1}};
  const auto xyz = on_sphere(c, R, dirs);
  const tessera::SphereTessellation t = tessera::tessellate_sphere(c, R, {xyz.data(), 6, 3});
  tessera::SphereCells v;
  v.bind(t);
  EXPECT_NEAR(v.measure(0), 2.0, 1e-4);
  EXPECT_EQ(v.coordination_number(0), 4);
  double m[9];
  v.second_moments(0, m);
  EXPECT_NEAR(m[0], 8.0 / 12.0, 1e-4);  // xx
  EXPECT_NEAR(m[4], 2.0 / 12.0, 1e-4);  // yy
  EXPECT_NEAR(m[1], 0.0, 1e-8);
  EXPECT_NEAR(m[8], 0.0, 1e-8);  // nothing along the normal
  double a[3];
  ASSERT_TRUE(v.principal_axis(0, true, a));
  EXPECT_NEAR(std::fabs(a[0]), 1.0, 1e-8);
  ASSERT_TRUE(v.principal_axis(0, false, a));
  EXPECT_NEAR(std::fabs(a[1]), 1.0, 1e-8);
  double x[3];
  v.centroid(0, x);
  EXPECT_NEAR(x[0], 0.0, 1e-9);
  EXPECT_NEAR(x[1], 0.0, 1e-9);
  EXPECT_NEAR(x[2], R, 1e-9);
}

// The cube's six four-fold vertices: each a ring of four points.
TEST(SphereCells, CubeHasSixFourfoldRings) {
  std::vector<W> dirs;
  for (int a : {-1, 1})
    for (int b : {-1, 1})
      for (int d : {-1, 1}) dirs.push_back({1.0 * a, 1.0 * b, 1.0 * d});
  const Vec3 c{0, 0, 0};
  const auto xyz = on_sphere(c, 1.0, dirs);
  const tessera::SphereTessellation t = tessera::tessellate_sphere(c, 1.0, {xyz.data(), 8, 3});
  tessera::SphereCells v;
  v.bind(t);
  ASSERT_EQ(v.multifold_count(), 6);
  std::vector<int> ring;
  for (int g = 0; g < 6; ++g) {
    v.multifold_ring(g, ring);
    ASSERT_EQ(ring.size(), 4u);
    // The four points of one face of the cube: one coordinate in common.
    int common = 0;
    for (int d = 0; d < 3; ++d) {
      bool same = true;
      for (int p : ring) same = same && xyz[3 * p + d] == xyz[3 * ring[0] + d];
      common += same;
    }
    EXPECT_EQ(common, 1);
  }
  for (int i = 0; i < 8; ++i) EXPECT_EQ(v.coordination_number(i), 3);
}

// Rosettes: clusters of vertices joined by edges shorter than L.
TEST(SphereCells, ShortEdgeClusters) {
  const Vec3 c{0, 0, 0};
  const auto xyz = on_sphere(c, 1.0, icosahedron());
  const tessera::SphereTessellation t = tessera::tessellate_sphere(c, 1.0, {xyz.data(), 12, 3});
  tessera::SphereCells v;
  v.bind(t);
  std::vector<int> offset, members;
  const double edge = t.edge_length[0];
  ASSERT_TRUE(v.short_edge_clusters(0.99 * edge, offset, members));
  EXPECT_EQ(offset.size(), 1u);  // no edge is shorter: no cluster
  ASSERT_TRUE(v.short_edge_clusters(1.01 * edge, offset, members));
  ASSERT_EQ(offset.size(), 2u);  // every vertex joined: one cluster of all 12 points
  EXPECT_EQ(offset[1], 12);
}

// A caller that owns some cells and lacks some points: indices translated,
// the lacking ones reported.
TEST(SphereCells, CallersIndicesAndMissingPoints) {
  const Vec3 c{0, 0, 0};
  const auto xyz = on_sphere(c, 1.0, icosahedron());
  const tessera::SphereTessellation t = tessera::tessellate_sphere(c, 1.0, {xyz.data(), 12, 3});
  // The caller's points: 0 -> 100 + ..., owned cells are t's points 3 and 7.
  std::vector<int> index(12);
  for (int p = 0; p < 12; ++p) index[p] = 11 - p;
  index[5] = -1;
  tessera::SphereCells v;
  std::vector<double> mine(3 * 12);
  for (int p = 0; p < 12; ++p)
    for (int d = 0; d < 3; ++d) mine[3 * (11 - p) + d] = 2.0 * xyz[3 * p + d];  // off the sphere
  v.bind(t, {3, 7}, index, 12, {mine.data(), 12, 3});
  ASSERT_EQ(v.n_owned(), 2);
  EXPECT_EQ(v.tess_index(1), 7);
  for (int cc = 0; cc < 2; ++cc) {
    const int g = v.tess_index(cc);
    ASSERT_EQ(v.piece_end(cc) - v.piece_begin(cc), t.cell_size(g));
    for (int k = 0; k < t.cell_size(g); ++k) {
      const int q = t.cell_neighbor[t.cell_offset[g] + k];
      EXPECT_EQ(v.piece_neighbor(v.piece_begin(cc) + k), q == 5 ? -1 : 11 - q);
    }
  }
  const bool five_is_near = std::count(t.cell_neighbor.begin() + t.cell_offset[3],
                                       t.cell_neighbor.begin() + t.cell_offset[4], 5) +
                                std::count(t.cell_neighbor.begin() + t.cell_offset[7],
                                           t.cell_neighbor.begin() + t.cell_offset[8], 5) > 0;
  EXPECT_EQ(v.missing().size(), five_is_near ? 1u : 0u);
  double p[3];
  v.point(11 - 3, p);  // projected back onto the sphere
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(p[d], xyz[3 * 3 + d], 1e-15);
}

}  // namespace
