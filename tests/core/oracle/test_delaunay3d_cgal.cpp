// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// CGAL as an oracle (built only with -D TESSERA_CGAL_ORACLE=ON, the default
// where CGAL is found; nothing of it is linked into the library): Tessera's
// 3D Delaunay tetrahedralisation has exactly the tetrahedra of CGAL's
// Delaunay_triangulation_3 on the cases of delaunay3d_cases.h (random,
// co-spherical lattices exact, rounded, rotated and jittered, points on a
// sphere, coplanar hulls, Mesh3's far points), on larger random and
// jittered BCC sets, and its exactly rounded circumcentres are CGAL's exact
// constructions rounded to the nearest double (CGAL's own conversion
// truncates: within one ulp of ours, never nearer the exact value).

#include "delaunay3d_cases.h"
#include "mesh3d_delaunay.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using DT = CGAL::Delaunay_triangulation_3<K, Tds>;
using Tets = std::set<std::array<int, 4>>;

Tets cgal_tets(const std::vector<double> &xyz) {
  std::vector<std::pair<K::Point_3, int>> in;
  for (size_t i = 0; i < xyz.size() / 3; ++i)
    in.push_back({K::Point_3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]), static_cast<int>(i)});
  const DT dt(in.begin(), in.end());
  Tets s;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    std::array<int, 4> a;
    for (int k = 0; k < 4; ++k) a[k] = c->vertex(k)->info();
    std::sort(a.begin(), a.end());
    s.insert(a);
  }
  return s;
}

Tets own_tets(const std::vector<double> &xyz, const double (*far)[3], int n_far) {
  tessera::detail3::Tetrahedra t;
  const int n = static_cast<int>(xyz.size() / 3);
  EXPECT_EQ(static_cast<int>(tessera::detail3::delaunay_3d(tessera::Points3{xyz.data(), n, 3}, far,
                                                           n_far, t)),
            static_cast<int>(tessera::detail3::Delaunay3::kOk));
  Tets s;
  for (int k = 0; k < t.n_tets; ++k) {
    std::array<int, 4> a{t.tv[4 * k], t.tv[4 * k + 1], t.tv[4 * k + 2], t.tv[4 * k + 3]};
    std::sort(a.begin(), a.end());
    s.insert(a);
  }
  return s;
}

void expect_same(const delaunay3d_cases::Case &c) {
  std::vector<double> all = c.xyz;
  double far[8][3];
  if (c.far) {
    delaunay3d_cases::far_points(c, far);
    for (auto &f : far) all.insert(all.end(), f, f + 3);
  }
  const Tets ours = own_tets(c.xyz, c.far ? far : nullptr, c.far ? 8 : 0);
  const Tets theirs = cgal_tets(all);
  EXPECT_EQ(ours.size(), theirs.size()) << c.name;
  EXPECT_TRUE(ours == theirs) << c.name << ": the tetrahedra differ from CGAL's";
}

TEST(Delaunay3Cgal, SameTetrahedraAsCgal) {
  for (const auto &c : delaunay3d_cases::cases()) expect_same(c);
}

TEST(Delaunay3Cgal, SameTetrahedraOnLargerSets) {
  using namespace delaunay3d_cases;
  expect_same({"random 20000", random_cube(20000, 31)});
  expect_same({"BCC 10 jittered 0.1", jitter(lattice(Kind::BCC, 10, 1.0), 0.1, 32)});
  expect_same({"BCC 10 jittered 0.1 with far points", jitter(lattice(Kind::BCC, 10, 1.0), 0.1, 33),
               true});
  expect_same({"SC 8", lattice(Kind::SC, 8, 1.0)});
  expect_same({"FCC 5 spacing 1.1 at 0.3", lattice(Kind::FCC, 5, 1.1, 0.3)});
  for (uint64_t seed = 40; seed < 60; ++seed)
    expect_same({"random 40 seed " + std::to_string(seed), random_cube(40, seed)});
}

TEST(Delaunay3Cgal, CircumcentresAreCgalsRoundedToNearest) {
  using E = CGAL::Exact_predicates_exact_constructions_kernel;
  testutil::Rng rng(34);
  int differ = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    double p[4][3];
    const double eps = trial % 2 ? std::ldexp(1.0, -30 - rng.below(17)) : 0.5;
    for (int m = 0; m < 4; ++m) {
      const double phi = 1.5707963 * m + rng.uniform(-0.3, 0.3);
      p[m][0] = 10.0 + std::cos(phi);
      p[m][1] = -3.0 + std::sin(phi);
      p[m][2] = 0.7 - 0.2 * p[m][1] + (m == 3 ? eps : 0.0);
    }
    double c[3];
    tessera::detail3::exact_circumcentre(p[0], p[1], p[2], p[3], c);
    const E::Point_3 h =
        CGAL::circumcenter(E::Point_3(p[0][0], p[0][1], p[0][2]), E::Point_3(p[1][0], p[1][1], p[1][2]),
                           E::Point_3(p[2][0], p[2][1], p[2][2]), E::Point_3(p[3][0], p[3][1], p[3][2]));
    const E::FT x[3] = {h.x(), h.y(), h.z()};
    for (int k = 0; k < 3; ++k) {
      const auto ex = CGAL::exact(x[k]);
      const double theirs = CGAL::to_double(ex);
      // Within one ulp of CGAL's conversion, and no farther from the exact
      // value than it.
      EXPECT_TRUE(c[k] == theirs || std::nextafter(c[k], theirs) == theirs) << trial;
      EXPECT_LE(CGAL::abs(decltype(ex)(c[k]) - ex), CGAL::abs(decltype(ex)(theirs) - ex)) << trial;
      differ += c[k] != theirs;
    }
  }
  // CGAL truncates: about half of the coordinates differ by an ulp.
  EXPECT_GT(differ, 100);
}

}  // namespace
