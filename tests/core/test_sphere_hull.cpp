// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The sphere's own convex hull (core/src/sphere_hull.cpp), both routes, on the table
// of sphere_hull_cases.h, against brute force in exact arithmetic: the triangles form
// a closed surface (each directed edge once and its reverse once, 2n - 4 triangles,
// every point a corner), and no point lies above any triangle's plane (exact
// orientation, decided here without the hull's floating-point filter).  A closed
// surface with every point on or below each of its triangles' planes is the
// boundary of the hull.  And the errors: equal points, all points on one plane, a
// point that round-off put inside the hull of the others.
#include "exact_predicates.h"
#include "sphere_hull.h"
#include "sphere_hull_cases.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <utility>
#include <vector>

namespace {

using tessera::sphere_detail::HullResult;
using tessera::sphere_detail::HullRoute;
using tessera::sphere_detail::sphere_hull;

// Sign of det[b-a; c-a; d-a]: in doubles where it is far from 0 (the determinant of
// unit vectors is off by far less than 1e-12), else the exact predicate.
int orientation(const double *a, const double *b, const double *c, const double *d) {
  double m[3][3];
  for (int k = 0; k < 3; ++k)
    m[0][k] = b[k] - a[k], m[1][k] = c[k] - a[k], m[2][k] = d[k] - a[k];
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  if (det > 1e-12)
    return 1;
  if (det < -1e-12)
    return -1;
  return tessera::exact::orient3d(a, b, c, d);
}

// The checks of the file's header; the number of co-planar (orientation 0) pairs of
// a triangle and a fourth point, i.e. how degenerate the case was.
int check_hull(const std::vector<double> &dir, const HullResult &r, const std::string &what) {
  SCOPED_TRACE(what);
  const int n = static_cast<int>(dir.size() / 3);
  EXPECT_EQ(r.status, HullResult::Ok);
  if (r.status != HullResult::Ok)
    return 0;
  EXPECT_EQ(static_cast<int>(r.triangles.size()), 2 * n - 4);
  std::map<std::pair<int, int>, int> edges;
  std::vector<int> corner(n, 0);
  for (const auto &t : r.triangles)
    for (int k = 0; k < 3; ++k) {
      ++edges[{t[k], t[(k + 1) % 3]}];
      ++corner[t[k]];
    }
  for (const auto &e : edges) {
    EXPECT_EQ(e.second, 1) << "edge " << e.first.first << " " << e.first.second;
    const auto back = edges.find({e.first.second, e.first.first});
    EXPECT_TRUE(back != edges.end() && back->second == 1)
        << "edge " << e.first.first << " " << e.first.second << " has no twin";
  }
  for (int i = 0; i < n; ++i)
    EXPECT_GE(corner[i], 3) << "point " << i << " is no corner";
  int coplanar = 0;
  for (const auto &t : r.triangles)
    for (int p = 0; p < n; ++p) {
      if (p == t[0] || p == t[1] || p == t[2])
        continue;
      const int o = orientation(&dir[3 * t[0]], &dir[3 * t[1]], &dir[3 * t[2]], &dir[3 * p]);
      EXPECT_LE(o, 0) << "point " << p << " above " << t[0] << " " << t[1] << " " << t[2];
      coplanar += o == 0;
    }
  return coplanar;
}

TEST(SphereHull, TableOfCasesGivesTheExactHullOnBothRoutes) {
  int degenerate = 0, fallbacks = 0;
  for (const spherehull::HullCase &c : spherehull::hull_cases())
    for (HullRoute route : {HullRoute::Walk, HullRoute::Conflict}) {
      const HullResult r = sphere_hull(c.dir.data(), c.n(), route);
      if (c.may_be_flat && r.status == HullResult::Flat) {
        for (int p = 3; p < c.n(); ++p)
          EXPECT_EQ(orientation(&c.dir[0], &c.dir[3], &c.dir[6], &c.dir[3 * p]), 0) << c.name;
        continue;
      }
      const int k =
          check_hull(c.dir, r, c.name + (route == HullRoute::Walk ? " (walk)" : " (conflict)"));
      degenerate += k > 0;
      fallbacks += route == HullRoute::Walk && r.route == HullRoute::Conflict;
    }
  // The axis-aligned cube and cuboctahedron and the drums have exactly co-planar
  // faces; some near-flat circles leave the walk no centre (the fallback is tested).
  EXPECT_GE(degenerate, 8);
  EXPECT_GE(fallbacks, 1);
}

// In general position the hull is unique: both routes give the same triangles, also
// where the walk crosses many facets (twenty thousand points).
TEST(SphereHull, RoutesAgreeOnManyRandomPoints) {
  testutil::Rng rng(99);
  for (double zmin : {-1.0, 0.5}) {
    std::vector<spheretest::W> v;
    for (int i = 0; i < 20000; ++i)
      v.push_back(spherehull::random_dir(rng, zmin));
    const double none[3] = {0.0, 0.0, 0.0};
    const std::vector<double> dir = spherehull::directions(v, none, 0.0, rng);
    const int n = static_cast<int>(v.size());
    auto canonical = [](HullResult r) {
      for (auto &f : r.triangles)
        while (f[0] > f[1] || f[0] > f[2])
          f = {f[1], f[2], f[0]};
      std::sort(r.triangles.begin(), r.triangles.end());
      return r.triangles;
    };
    const auto walk = canonical(sphere_hull(dir.data(), n, HullRoute::Walk));
    ASSERT_EQ(static_cast<int>(walk.size()), 2 * n - 4);
    EXPECT_EQ(walk, canonical(sphere_hull(dir.data(), n, HullRoute::Conflict))) << zmin;
  }
}

TEST(SphereHull, EqualFlatAndHiddenPointsAreReported) {
  testutil::Rng rng(5);
  const double none[3] = {0.0, 0.0, 0.0};
  std::vector<double> dir = spherehull::directions(spheretest::icosahedron(), none, 0.0, rng);
  const int n = static_cast<int>(dir.size() / 3);
  for (HullRoute route : {HullRoute::Walk, HullRoute::Conflict}) {
    // Point 12 equal to point 7.
    std::vector<double> d = dir;
    d.insert(d.end(), dir.begin() + 21, dir.begin() + 24);
    HullResult r = sphere_hull(d.data(), n + 1, route);
    EXPECT_EQ(r.status, HullResult::Equal);
    EXPECT_EQ(r.i, 7);
    EXPECT_EQ(r.j, 12);
    // All on the great circle z = 0 (exactly one plane), and on a small circle.
    for (double h : {0.0, 0.6}) {
      d.clear();
      for (int m = 0; m < 9; ++m) {
        const double s = std::sqrt(1.0 - h * h);
        d.insert(d.end(), {s * std::cos(0.6 * m), s * std::sin(0.6 * m), h});
      }
      EXPECT_EQ(sphere_hull(d.data(), 9, route).status, HullResult::Flat) << h;
    }
    // A point halfway between the centre and point 0: inside the hull of the others.
    d = dir;
    const double mid[3] = {0.5 * dir[0], 0.5 * dir[1], 0.5 * dir[2]};
    d.insert(d.end(), mid, mid + 3);
    r = sphere_hull(d.data(), n + 1, route);
    EXPECT_EQ(r.status, HullResult::Hidden);
    EXPECT_EQ(r.i, n);
  }
}

} // namespace
