// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The 2D triangulator (Mesh::build) and its rule for ties (doc/model.md,
// "Exact geometry"): the Delaunay triangulation of the points with every
// lifted coordinate x^2 + y^2 raised by an infinitesimal that grows with
// the point's lexicographic order, which is unique.  Checked against
//   * a brute force on small sets: every triangle of three points whose
//     perturbed circumcircle holds none of the others, and only those
//     (O(n^4), with the perturbation written out again here);
//   * itself under relabelling (the result may not depend on the order);
//   * CGAL's Delaunay_triangulation_2, which breaks ties by the same
//     perturbation, on random, clustered and degenerate input of up to 2e4
//     points (when CGAL is installed: TESSERA_CGAL_ORACLE);
// and Mesh::update() must reach the same triangles as a rebuild when the
// points move onto a tie (a lattice).

#include "exact_predicates.h"
#include "mesh_detail.h"
#include "test_util.h"
#include "tessera/mesh.h"
#include "tessera/tessellation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#ifdef TESSERA_CGAL_ORACLE
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#endif

namespace {

using testutil::Rng;
using Tri = std::array<int, 3>;

// A triangle as its corners rotated to start at the smallest (orientation kept).
Tri rotated(Tri t) {
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

// The finite triangles of a mesh built on the points.
std::set<Tri> mesh_triangles(const std::vector<double> &xy) {
  const tessera::Points pts{xy.data(), static_cast<int>(xy.size() / 2), 2};
  tessera::Mesh m;
  m.build(pts);
  tessera::Tessellation t;
  m.cells(pts, 0, t);
  std::set<Tri> s;
  for (const auto &tri : t.triangles)
    s.insert(rotated(tri));
  return s;
}

// The perturbed in-circle test, written out independently of the core's:
// sign of det[(x, y, x^2 + y^2 + e_i, 1)] over rows a, b, c, d, where the
// e_i are infinitesimals with e_i >> e_j when point i is lexicographically
// larger than point j.
int perturbed_incircle(const double *a, const double *b, const double *c, const double *d) {
  const int s = tessera::exact::incircle(a, b, c, d);
  if (s != 0)
    return s;
  const double *row[4] = {a, b, c, d};
  std::array<int, 4> by_size = {0, 1, 2, 3};
  std::sort(by_size.begin(), by_size.end(), [&](int i, int j) {
    return std::make_pair(row[i][0], row[i][1]) > std::make_pair(row[j][0], row[j][1]);
  });
  for (const int i : by_size) {
    // The cofactor of row i's lifted entry (column 2, counting from 0):
    // (-1)^(i + 2) times the determinant of the other rows' (x, y, 1),
    // i.e. their orientation.
    const double *o[3];
    for (int r = 0, k = 0; r < 4; ++r)
      if (r != i)
        o[k++] = row[r];
    const int cof = (i % 2 == 0 ? 1 : -1) * tessera::exact::orient2d(o[0], o[1], o[2]);
    if (cof != 0)
      return cof;
  }
  return 0;
}

std::set<Tri> brute_force(const std::vector<double> &xy) {
  const int n = static_cast<int>(xy.size() / 2);
  auto P = [&](int i) { return &xy[2 * i]; };
  std::set<Tri> s;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        const int o = tessera::exact::orient2d(P(i), P(j), P(k));
        if (o == 0)
          continue;
        const Tri t = o > 0 ? Tri{i, j, k} : Tri{i, k, j};
        bool empty = true;
        for (int l = 0; l < n && empty; ++l)
          if (l != i && l != j && l != k && perturbed_incircle(P(t[0]), P(t[1]), P(t[2]), P(l)) > 0)
            empty = false;
        if (empty)
          s.insert(rotated(t));
      }
  return s;
}

// Small degenerate point sets: subsets of a small grid (co-circular and
// collinear everywhere), lattice points of one circle with a few others,
// a regular polygon with its centre, random points; scaled and shifted.
std::vector<double> small_set(Rng &rng) {
  std::vector<double> xy;
  std::set<std::pair<int, int>> used;
  const int kind = rng.below(4);
  const int n = 3 + rng.below(10);
  auto add = [&](double x, double y) {
    xy.push_back(x);
    xy.push_back(y);
  };
  if (kind == 0 || kind == 1) {
    const int side = kind == 0 ? 4 : 6;
    while (static_cast<int>(used.size()) < std::min(n, side * side)) {
      const int i = rng.below(side), j = rng.below(side);
      if (used.insert({i, j}).second)
        add(i, j);
    }
  } else if (kind == 2) {
    for (int x = -8; x <= 8; ++x)
      for (int y = -8; y <= 8; ++y)
        if (x * x + y * y == 65 && rng.below(3))
          add(x, y);
    for (int k = rng.below(3); k > 0; --k)
      add(rng.below(11) - 5, rng.below(11) - 5);
  } else {
    const int k = 3 + rng.below(9);
    for (int j = 0; j < k; ++j)
      add(std::cos(6.283185307179586 * j / k), std::sin(6.283185307179586 * j / k));
    if (rng.below(2))
      add(0.0, 0.0);
  }
  // Drop duplicates (the generators above can make some), then scale/shift.
  std::set<std::pair<double, double>> seen;
  std::vector<double> out;
  const double s = std::ldexp(1.0, rng.below(40) - 20), sh = rng.below(2) ? 1e3 : 0.0;
  for (size_t i = 0; i + 1 < xy.size(); i += 2)
    if (seen.insert({xy[i], xy[i + 1]}).second) {
      out.push_back(sh + s * xy[i]);
      out.push_back(sh + s * xy[i + 1]);
    }
  return out;
}

bool collinear(const std::vector<double> &xy) {
  const int n = static_cast<int>(xy.size() / 2);
  for (int k = 2; k < n; ++k)
    if (tessera::exact::orient2d(&xy[0], &xy[2], &xy[2 * k]) != 0)
      return false;
  return true;
}

TEST(Delaunay2D, SmallDegenerateSetsMatchBruteForce) {
  Rng rng(41);
  int checked = 0;
  for (int c = 0; c < 1500; ++c) {
    const std::vector<double> xy = small_set(rng);
    if (xy.size() < 6 || collinear(xy))
      continue;
    const std::set<Tri> want = brute_force(xy), got = mesh_triangles(xy);
    ASSERT_EQ(got, want) << "case " << c << " with " << xy.size() / 2 << " points";
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

// A random relabelling gives the same triangles (relabelled).
TEST(Delaunay2D, IndependentOfTheOrderOfThePoints) {
  Rng rng(42);
  for (int c = 0; c < 60; ++c) {
    std::vector<double> xy;
    const int side = 5 + rng.below(20);
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) {
        const bool hex = c % 3 == 0;
        xy.push_back(i + (hex && j % 2 ? 0.5 : 0.0) + (c % 3 == 2 ? 1e-3 * rng.uniform() : 0.0));
        xy.push_back(hex ? j * std::sqrt(0.75) : j);
      }
    const int n = static_cast<int>(xy.size() / 2);
    std::vector<int> perm(n);
    std::iota(perm.begin(), perm.end(), 0);
    for (int i = n - 1; i > 0; --i)
      std::swap(perm[i], perm[rng.below(i + 1)]);
    std::vector<double> shuffled(xy.size());
    for (int i = 0; i < n; ++i) {
      shuffled[2 * perm[i]] = xy[2 * i];
      shuffled[2 * perm[i] + 1] = xy[2 * i + 1];
    }
    std::set<Tri> a;
    for (Tri t : mesh_triangles(xy))
      a.insert(rotated({perm[t[0]], perm[t[1]], perm[t[2]]}));
    ASSERT_EQ(a, mesh_triangles(shuffled)) << "case " << c;
  }
}

// Points that leave a square lattice and come back onto it: the flips of
// update() break the ties as build() does.
TEST(Delaunay2D, UpdateOntoATieGivesTheRebuildsTriangles) {
  Rng rng(43);
  const int side = 12;
  std::vector<double> lattice;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      lattice.push_back(0.25 * i);
      lattice.push_back(0.25 * j);
    }
  const int n = side * side;
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<double> xy = lattice;
    for (int p = 0; p < n; ++p) { // the hull stays where it is: only inner points move
      const int i = p / side, j = p % side;
      if (i == 0 || j == 0 || i == side - 1 || j == side - 1)
        continue;
      xy[2 * p] += 0.05 * rng.uniform(-1.0, 1.0);
      xy[2 * p + 1] += 0.05 * rng.uniform(-1.0, 1.0);
    }
    const tessera::Points pts{xy.data(), n, 2};
    tessera::Mesh m;
    m.build(pts);
    xy = lattice; // back onto the tie
    ASSERT_TRUE(m.update(pts));
    tessera::Tessellation t;
    m.cells(pts, 0, t);
    std::set<Tri> got;
    for (const auto &tri : t.triangles)
      got.insert(rotated(tri));
    ASSERT_EQ(got, mesh_triangles(xy)) << "trial " << trial;
  }
}

#ifdef TESSERA_CGAL_ORACLE

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using CgalDelaunay = CGAL::Delaunay_triangulation_2<K, Tds>;

std::set<Tri> cgal_triangles(const std::vector<double> &xy) {
  std::vector<std::pair<K::Point_2, int>> in;
  for (size_t i = 0; i + 1 < xy.size(); i += 2)
    in.emplace_back(K::Point_2(xy[i], xy[i + 1]), i / 2);
  CgalDelaunay dt(in.begin(), in.end());
  std::set<Tri> s;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
    s.insert(rotated({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()}));
  return s;
}

// Random, clustered and degenerate (lattices, rings, rows) point sets of up
// to 2e4 points: the same triangles as CGAL's.
TEST(Delaunay2D, SameTrianglesAsCgal) {
  Rng rng(44);
  for (int c = 0; c < 120; ++c) {
    std::vector<double> xy;
    const int kind = c % 6;
    const int n = c < 6 ? 20000 : 10 + rng.below(2000);
    auto add = [&](double x, double y) {
      xy.push_back(x);
      xy.push_back(y);
    };
    if (kind == 0) { // uniform
      for (int i = 0; i < n; ++i)
        add(rng.uniform(), rng.uniform());
    } else if (kind == 1) { // square lattice (every vertex four-fold), far from the origin
      const int side = static_cast<int>(std::sqrt(n)) + 2;
      for (int i = 0; i < side * side; ++i)
        add(1e4 + 0.1 * (i % side), 0.1 * (i / side));
    } else if (kind == 2) { // hexagonal lattice, rounded
      const int side = static_cast<int>(std::sqrt(n)) + 2;
      for (int i = 0; i < side * side; ++i)
        add((i % side) + 0.5 * ((i / side) % 2), (i / side) * std::sqrt(0.75));
    } else if (kind == 3) { // concentric rings of regular polygons
      for (int r = 1; static_cast<int>(xy.size() / 2) < n; ++r)
        for (int j = 0; j < 6 * r; ++j)
          add(r * std::cos(6.283185307179586 * j / (6 * r)),
              r * std::sin(6.283185307179586 * j / (6 * r)));
    } else if (kind == 4) { // clusters a few ulps to 1e-6 wide
      for (int i = 0; i < n; ++i) {
        const double cx = rng.below(20), cy = rng.below(20);
        const double w = std::ldexp(1.0, -20 - rng.below(30));
        add(cx + w * rng.below(5), cy + w * rng.below(5));
      }
    } else { // collinear rows, crossing, on a grid
      for (int i = 0; i < n; ++i) {
        const int t = rng.below(200);
        switch (rng.below(3)) {
        case 0:
          add(t, 3.0);
          break;
        case 1:
          add(7.0, t);
          break;
        default:
          add(t, t);
          break;
        }
      }
    }
    // Without duplicates (those are refused, not triangulated).
    std::set<std::pair<double, double>> seen;
    std::vector<double> unique;
    for (size_t i = 0; i + 1 < xy.size(); i += 2)
      if (seen.insert({xy[i], xy[i + 1]}).second) {
        unique.push_back(xy[i]);
        unique.push_back(xy[i + 1]);
      }
    if (collinear(unique))
      continue;
    // The triangulator alone: Mesh::build would refuse the tightest clusters.
    std::vector<int> tri;
    ASSERT_TRUE(tessera::detail::delaunay_triangles(
        tessera::Points{unique.data(), static_cast<int>(unique.size() / 2), 2}, tri));
    std::set<Tri> got;
    for (size_t t = 0; t < tri.size(); t += 3)
      if (tri[t] >= 0)
        got.insert({tri[t], tri[t + 1], tri[t + 2]});
    ASSERT_EQ(got, cgal_triangles(unique)) << "case " << c << " kind " << kind;
    if (kind != 4)
      EXPECT_EQ(mesh_triangles(unique), got) << "case " << c << " kind " << kind;
  }
}

#endif // TESSERA_CGAL_ORACLE

} // namespace
