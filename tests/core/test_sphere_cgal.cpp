// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// CGAL as the oracle of the sphere's own triangulation (built only where CGAL is
// found, with TESSERA_CGAL_ORACLE; the library never links it).  On the table of
// sphere_hull_cases.h and on random points (to twenty thousand, on the sphere and on
// a cap), the hull that tessellate_sphere's triangles come from equals CGAL's
// convex_hull_3 of the same rounded directions: the same triangles in general
// position; where co-planar points make a face a polygon, which both split into
// triangles as they please, the same faces (each triangle taken with every point
// on its plane, by CGAL's exact orientation).
#ifdef TESSERA_CGAL_ORACLE

#include "sphere_hull.h"
#include "sphere_hull_cases.h"
#include "tessera/sphere.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = K::Point_3;
using Tri = std::array<int, 3>;
using tessera::sphere_detail::HullResult;
using tessera::sphere_detail::HullRoute;

std::vector<P3> points(const std::vector<double> &dir) {
  std::vector<P3> P;
  for (size_t i = 0; i < dir.size(); i += 3)
    P.emplace_back(dir[i], dir[i + 1], dir[i + 2]);
  return P;
}

// CGAL's hull as triangles of point indices (into a Surface_mesh: its polygon-soup
// output has been seen to drop a corner of exactly convex input).
std::vector<Tri> cgal_hull(const std::vector<P3> &P) {
  CGAL::Surface_mesh<P3> sm;
  CGAL::convex_hull_3(P.begin(), P.end(), sm);
  std::map<std::array<double, 3>, int> index;
  for (size_t i = 0; i < P.size(); ++i)
    index[{P[i].x(), P[i].y(), P[i].z()}] = static_cast<int>(i);
  std::vector<Tri> t;
  for (const auto f : sm.faces()) {
    Tri tri{{-1, -1, -1}};
    int m = 0;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      const P3 &p = sm.point(v);
      if (m < 3)
        tri[m] = index.at({p.x(), p.y(), p.z()});
      ++m;
    }
    EXPECT_EQ(m, 3) << "CGAL's hull has a facet that is no triangle";
    t.push_back(tri);
  }
  return t;
}

std::vector<Tri> canonical(std::vector<Tri> v) {
  for (Tri &f : v)
    while (f[0] > f[1] || f[0] > f[2])
      f = {f[1], f[2], f[0]};
  std::sort(v.begin(), v.end());
  return v;
}

// The faces: each triangle with every point on its plane (a sorted index set),
// and whether any triangle had a fourth point on its plane.
std::set<std::vector<int>> faces(const std::vector<Tri> &t, const std::vector<P3> &P, bool *flat) {
  std::set<std::vector<int>> s;
  for (const Tri &f : t) {
    std::vector<int> face;
    for (int p = 0; p < static_cast<int>(P.size()); ++p)
      if (p == f[0] || p == f[1] || p == f[2] ||
          CGAL::orientation(P[f[0]], P[f[1]], P[f[2]], P[p]) == CGAL::COPLANAR)
        face.push_back(p);
    if (face.size() > 3)
      *flat = true;
    s.insert(face);
  }
  return s;
}

TEST(SphereCgal, HullCasesGiveCgalsFaces) {
  int polygons = 0;
  for (const spherehull::HullCase &c : spherehull::hull_cases()) {
    const std::vector<P3> P = points(c.dir);
    for (HullRoute route : {HullRoute::Walk, HullRoute::Conflict}) {
      SCOPED_TRACE(c.name + (route == HullRoute::Walk ? " (walk)" : " (conflict)"));
      const HullResult r = tessera::sphere_detail::sphere_hull(c.dir.data(), c.n(), route);
      if (c.may_be_flat && r.status == HullResult::Flat) {
        // CGAL's hull of coplanar points is flat too: no facet has a point off its plane.
        for (const Tri &f : cgal_hull(P))
          for (const P3 &p : P)
            EXPECT_EQ(CGAL::orientation(P[f[0]], P[f[1]], P[f[2]], p), CGAL::COPLANAR);
        continue;
      }
      ASSERT_EQ(r.status, HullResult::Ok);
      bool flat_mine = false, flat_cgal = false;
      const std::vector<Tri> theirs = cgal_hull(P);
      EXPECT_EQ(faces(r.triangles, P, &flat_mine), faces(theirs, P, &flat_cgal));
      EXPECT_EQ(flat_mine, flat_cgal);
      if (!flat_mine)
        EXPECT_EQ(canonical(r.triangles), canonical(theirs));
      polygons += flat_mine;
    }
  }
  EXPECT_GE(polygons, 8); // the co-planar cases were co-planar
}

// tessellate_sphere's triangles are CGAL's hull of its rounded directions, on the
// sphere and on a cap (the centre outside the hull), to twenty thousand points.
TEST(SphereCgal, RandomPointsGiveCgalsTriangles) {
  testutil::Rng rng(31);
  for (int n : {4, 50, 1000, 20000})
    for (double zmin : {-1.0, 0.4}) {
      const tessera::Vec3 c{0.3, -1.2, 0.5};
      const double R = 3.7;
      std::vector<double> xyz;
      for (int i = 0; i < n; ++i) {
        const spheretest::W d = spherehull::random_dir(rng, zmin);
        xyz.insert(xyz.end(), {c.x + R * d.x, c.y + R * d.y, c.z + R * d.z});
      }
      const tessera::SphereTessellation t = tessera::tessellate_sphere(c, R, {xyz.data(), n, 3});
      std::vector<P3> P;
      for (const tessera::Vec3 &u : t.direction)
        P.emplace_back(u.x, u.y, u.z);
      EXPECT_EQ(canonical(t.triangles), canonical(cgal_hull(P))) << n << " " << zmin;
    }
}

} // namespace

#endif // TESSERA_CGAL_ORACLE
