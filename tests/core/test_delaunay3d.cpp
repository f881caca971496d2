// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Tessera's 3D Delaunay tetrahedralisation (mesh3d_delaunay.h) against its
// definition, with exact predicates and no second builder: every
// tetrahedron positively oriented, neighbours consistent, the boundary the
// convex hull (no point beyond a hull triangle), the complex a ball (Euler
// characteristic 1) using every point, every interior triangle locally
// Delaunay for the perturbed in-sphere test (so the triangulation is the
// unique perturbed Delaunay one, whatever the insertion order) and, for the
// small sets, no point strictly inside any circumsphere (brute force).  The
// same tetrahedra for any order of the input points.  Bad input: duplicates
// named, coplanar sets refused.  oracle/test_delaunay3d_cgal.cpp compares
// the same cases with CGAL's Delaunay_triangulation_3 where CGAL is found.

#include "delaunay3d_cases.h"
#include "exact_predicates.h"
#include "mesh3d_delaunay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

namespace {

using delaunay3d_cases::Case;
using tessera::Points3;
using tessera::detail3::Delaunay3;
using tessera::detail3::Tetrahedra;

struct Input {
  std::vector<double> xyz;  // the case's points, then its far points
  int n = 0, n_extra = 0;
  double far[8][3] = {};
  const double *p(int i) const { return i < n ? &xyz[3 * i] : far[i - n]; }
};

Input input_of(const Case &c) {
  Input in;
  in.xyz = c.xyz;
  in.n = c.n();
  if (c.far) {
    delaunay3d_cases::far_points(c, in.far);
    in.n_extra = 8;
  }
  return in;
}

Tetrahedra triangulate(const Input &in) {
  Tetrahedra t;
  const Delaunay3 s =
      tessera::detail3::delaunay_3d(Points3{in.xyz.data(), in.n, 3}, in.n_extra ? in.far : nullptr,
                                    in.n_extra, t);
  EXPECT_EQ(static_cast<int>(s), static_cast<int>(Delaunay3::kOk));
  return t;
}

std::set<std::array<int, 4>> tet_set(const Tetrahedra &t, const std::vector<int> *relabel = nullptr) {
  std::set<std::array<int, 4>> s;
  for (int k = 0; k < t.n_tets; ++k) {
    std::array<int, 4> a;
    for (int q = 0; q < 4; ++q) {
      const int v = t.tv[4 * k + q];
      a[q] = relabel && v < static_cast<int>(relabel->size()) ? (*relabel)[v] : v;
    }
    std::sort(a.begin(), a.end());
    s.insert(a);
  }
  return s;
}

// The checks of the top of the file.
void expect_delaunay(const Input &in, const Tetrahedra &t, const std::string &name) {
  const int m = in.n + in.n_extra;
  long exact = 0;
  ASSERT_EQ(static_cast<int>(t.tv.size()), 4 * t.n_tets) << name;
  ASSERT_EQ(static_cast<int>(t.vt.size()), m) << name;
  int hull = 0, bad_orient = 0, bad_nb = 0, not_delaunay = 0, beyond = 0;
  std::set<std::pair<int, int>> edges;
  for (int k = 0; k < t.n_tets; ++k) {
    const int *q = &t.tv[4 * k];
    // Canonical order: the smallest corner first, then the smallest other.
    EXPECT_TRUE(q[0] < q[1] && q[1] < q[2] && q[1] < q[3]) << name << ": tetrahedron " << k;
    if (k > 0) EXPECT_LE(t.tv[4 * (k - 1)], q[0]) << name << ": numbering by smallest corner";
    if (tessera::exact::orient3d(in.p(q[0]), in.p(q[1]), in.p(q[2]), in.p(q[3])) <= 0) ++bad_orient;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) edges.insert({std::min(q[a], q[b]), std::max(q[a], q[b])});
    for (int s = 0; s < 4; ++s) {
      const int u = t.tn[4 * k + s];
      if (u < 0) {
        ++hull;
        // The hull triangle (the corners other than s): no point beyond it,
        // i.e. on the side opposite q[s] (by brute force up to 1000 points).
        int f[4] = {q[0], q[1], q[2], q[3]};
        for (int i = 0; i < (m <= 1000 ? m : 0); ++i) {
          f[s] = i;
          if (tessera::detail3::orient3d_filtered(in.p(f[0]), in.p(f[1]), in.p(f[2]), in.p(f[3]),
                                                  exact) < 0)
            ++beyond;
        }
        continue;
      }
      // u shares the three corners other than q[s], and points back.
      int shared = 0, apex = -1, back = 0;
      for (int r = 0; r < 4; ++r) {
        const int v = t.tv[4 * u + r];
        const bool in_face = v != q[s] && (v == q[0] || v == q[1] || v == q[2] || v == q[3]);
        shared += in_face;
        if (!in_face) apex = v;
        back += t.tn[4 * u + r] == k;
      }
      if (shared != 3 || back != 1 || apex == q[s]) ++bad_nb;
      const double *c[4] = {in.p(q[0]), in.p(q[1]), in.p(q[2]), in.p(q[3])};
      if (tessera::detail3::insphere_perturbed(c, in.p(apex), exact) > 0) ++not_delaunay;
    }
  }
  EXPECT_EQ(bad_orient, 0) << name;
  EXPECT_EQ(bad_nb, 0) << name;
  EXPECT_EQ(not_delaunay, 0) << name << ": interior triangles not locally Delaunay";
  EXPECT_EQ(beyond, 0) << name << ": points beyond hull triangles";
  // Every point a corner of its vt tetrahedron.
  int lost = 0;
  for (int i = 0; i < m; ++i) {
    const int k = t.vt[i];
    lost += k < 0 || !(t.tv[4 * k] == i || t.tv[4 * k + 1] == i || t.tv[4 * k + 2] == i ||
                       t.tv[4 * k + 3] == i);
  }
  EXPECT_EQ(lost, 0) << name;
  // A triangulated ball: V - E + F - T = 1, F = (4 T + hull) / 2.
  const long faces = (4L * t.n_tets + hull) / 2;
  EXPECT_EQ(m - static_cast<long>(edges.size()) + faces - t.n_tets, 1) << name;
  // Empty spheres (unperturbed), by brute force on the small sets (the
  // filtered predicates: exact, and tested against tessera::exact's by
  // Delaunay3.FiltersAgreeWithExactPredicates).
  if (static_cast<long>(m) * t.n_tets <= 200000) {
    int inside = 0;
    for (int k = 0; k < t.n_tets; ++k) {
      const int *q = &t.tv[4 * k];
      for (int i = 0; i < m; ++i)
        inside += tessera::detail3::insphere_filtered(in.p(q[0]), in.p(q[1]), in.p(q[2]),
                                                      in.p(q[3]), in.p(i), exact) > 0;
    }
    EXPECT_EQ(inside, 0) << name << ": points strictly inside circumspheres";
  }
}

TEST(Delaunay3, CasesAreDelaunay) {
  for (const Case &c : delaunay3d_cases::cases()) {
    const Input in = input_of(c);
    const Tetrahedra t = triangulate(in);
    expect_delaunay(in, t, c.name);
    std::printf("%-28s %5d points %6d tetrahedra, %ld exact predicate calls\n", c.name.c_str(),
                in.n + in.n_extra, t.n_tets, t.exact_calls);
  }
}

// The perturbation depends on the points, not their indices: a shuffled
// input gives the same tetrahedra (the builder's insertion order changes
// with it).
TEST(Delaunay3, SameTetrahedraForAnyInputOrder) {
  for (const Case &c : delaunay3d_cases::cases()) {
    const Input in = input_of(c);
    const Tetrahedra t = triangulate(in);
    testutil::Rng rng(7);
    std::vector<int> perm(in.n);  // new index -> old
    for (int i = 0; i < in.n; ++i) perm[i] = i;
    for (int i = in.n - 1; i > 0; --i) std::swap(perm[i], perm[rng.below(i + 1)]);
    Input sh = in;
    for (int i = 0; i < in.n; ++i)
      for (int d = 0; d < 3; ++d) sh.xyz[3 * i + d] = in.xyz[3 * perm[i] + d];
    std::vector<int> back(in.n + in.n_extra);
    for (int i = 0; i < in.n; ++i) back[i] = perm[i];
    for (int e = 0; e < in.n_extra; ++e) back[in.n + e] = in.n + e;
    EXPECT_EQ(tet_set(triangulate(sh), &back), tet_set(t)) << c.name;
  }
}

// Far points given as extra points or as ordinary ones: the same.
TEST(Delaunay3, ExtraPointsAreOrdinaryPoints) {
  for (const Case &c : delaunay3d_cases::cases()) {
    if (!c.far) continue;
    const Input in = input_of(c);
    Input flat;
    flat.xyz = in.xyz;
    for (auto &f : in.far) flat.xyz.insert(flat.xyz.end(), f, f + 3);
    flat.n = in.n + 8;
    EXPECT_EQ(tet_set(triangulate(flat)), tet_set(triangulate(in))) << c.name;
  }
}

// The unsorted export: the same tetrahedra and adjacency.
TEST(Delaunay3, UnsortedExportSameTetrahedra) {
  const Case c{"BCC", delaunay3d_cases::lattice(delaunay3d_cases::Kind::BCC, 3, 1.0)};
  const Input in = input_of(c);
  Tetrahedra u;
  ASSERT_EQ(static_cast<int>(tessera::detail3::delaunay_3d(Points3{in.xyz.data(), in.n, 3}, nullptr,
                                                           0, u, 0.0, false)),
            static_cast<int>(Delaunay3::kOk));
  EXPECT_EQ(tet_set(u), tet_set(triangulate(in)));
  for (int k = 0; k < u.n_tets; ++k)
    for (int s = 0; s < 4; ++s) {
      const int w = u.tn[4 * k + s];
      if (w >= 0) EXPECT_EQ(std::count(&u.tn[4 * w], &u.tn[4 * w] + 4, k), 1);
    }
}

TEST(Delaunay3, DuplicatesAndFlatInput) {
  std::vector<double> x = delaunay3d_cases::random_cube(50, 11);
  x.insert(x.end(), {x[3 * 17], x[3 * 17 + 1], x[3 * 17 + 2]});  // point 50 = point 17
  Tetrahedra t;
  EXPECT_EQ(static_cast<int>(tessera::detail3::delaunay_3d(Points3{x.data(), 51, 3}, nullptr, 0, t)),
            static_cast<int>(Delaunay3::kDuplicate));
  EXPECT_EQ(std::min(t.duplicate[0], t.duplicate[1]), 17);
  EXPECT_EQ(std::max(t.duplicate[0], t.duplicate[1]), 50);
  // Coplanar (a tilted plane with exactly representable points), collinear,
  // too few, coincident.
  std::vector<double> plane, line, three{0, 0, 0, 1, 0, 0, 0, 1, 0}, same(12, 0.25);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) plane.insert(plane.end(), {double(i), double(j), 0.5 * i + 0.25 * j});
  for (int i = 0; i < 10; ++i) line.insert(line.end(), {double(i), 2.0 * i, -0.5 * i});
  for (const auto *v : {&plane, &line, &three, &same}) {
    Tetrahedra f;
    const int n = static_cast<int>(v->size() / 3);
    const Delaunay3 s = tessera::detail3::delaunay_3d(Points3{v->data(), n, 3}, nullptr, 0, f);
    EXPECT_NE(static_cast<int>(s), static_cast<int>(Delaunay3::kOk)) << n << " points";
  }
  // Coplanar points plus one off the plane: a valid (flat-hulled) set.
  plane.insert(plane.end(), {2.0, 2.0, 7.0});
  const Input in{plane, static_cast<int>(plane.size() / 3)};
  expect_delaunay(in, triangulate(in), "plane and apex");
}

// A larger random set: the local checks only (the brute force is skipped).
TEST(Delaunay3, Random5000) {
  Input in;
  in.xyz = delaunay3d_cases::random_cube(5000, 12);
  in.n = 5000;
  expect_delaunay(in, triangulate(in), "random 5000");
}

// The filters decide as the exact predicates do, near ties included:
// points of a lattice moved by a few ulps, and far apart (large permanents).
TEST(Delaunay3, FiltersAgreeWithExactPredicates) {
  testutil::Rng rng(13);
  long exact = 0;
  int disagree = 0, zeros = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    double p[5][3];
    const double scale = trial % 3 == 0 ? 1e6 : 1.0;
    const bool moved = trial % 2 == 1;
    for (auto &q : p)
      for (double &v : q) {
        v = scale * rng.below(3);
        const int ulps = moved ? rng.below(5) - 2 : 0;
        for (int u = 0; u < std::abs(ulps); ++u) v = std::nextafter(v, ulps > 0 ? 1e300 : -1e300);
      }
    const int o = tessera::detail3::orient3d_filtered(p[0], p[1], p[2], p[3], exact);
    disagree += o != tessera::exact::orient3d(p[0], p[1], p[2], p[3]);
    const int s = tessera::detail3::insphere_filtered(p[0], p[1], p[2], p[3], p[4], exact);
    disagree += s != tessera::exact::insphere(p[0], p[1], p[2], p[3], p[4]);
    zeros += s == 0;
  }
  EXPECT_EQ(disagree, 0);
  EXPECT_GT(zeros, 100);  // exact ties were met
  EXPECT_GT(exact, 500);   // and near ties the filters left to the exact predicates
}

}  // namespace
