// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The periodic tessellation against the slow clipping reference, its
// invariances, owned+ghost coverage, and bad input.
#include "reference.h"
#include "test_util.h"
#include "tessera/energy.h"
#include "tessera/tessellation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

using testutil::Config;
using testutil::random_config;
using ::testing::AllOf;
using ::testing::AnyOf;
using ::testing::HasSubstr;

namespace {

struct EdgeKey {
  int nbr, sx, sy;
  double length;
  bool operator<(const EdgeKey &o) const {
    return std::tie(nbr, sx, sy) < std::tie(o.nbr, o.sx, o.sy);
  }
};

// Sides of owned cell c of a periodic tessellation longer than tol, as
// (owner of the neighbour, image shift in box lengths, length).
std::vector<EdgeKey> tess_edges(const tessera::Tessellation &t, const tessera::Box &box, int c,
                                double tol) {
  std::vector<EdgeKey> out;
  for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k) {
    if (t.edge_length[k] <= tol) continue;
    const int n = t.cell_neighbor[k];
    const int o = t.origin[n];
    const double sx = (t.position[n].x - t.position[o].x) / box.length(0);
    const double sy = (t.position[n].y - t.position[o].y) / box.length(1);
    EXPECT_NEAR(sx, std::round(sx), 1e-9) << "image is not a box-vector shift";
    EXPECT_NEAR(sy, std::round(sy), 1e-9) << "image is not a box-vector shift";
    out.push_back({o, static_cast<int>(std::lround(sx)), static_cast<int>(std::lround(sy)),
                   t.edge_length[k]});
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<EdgeKey> ref_edges(const reftess::RefCell &c, double tol) {
  std::vector<EdgeKey> out;
  for (const auto &e : c.edges)
    if (e.length > tol) out.push_back({e.nbr, e.sx, e.sy, e.length});
  std::sort(out.begin(), out.end());
  return out;
}

void expect_matches_reference(const Config &cfg, const tessera::Tessellation &t) {
  const int n = cfg.n();
  const auto ref = reftess::voronoi(cfg.refbox(), cfg.xy);
  ASSERT_EQ(t.n_owned, n);
  ASSERT_EQ(static_cast<int>(t.area.size()), n);
  ASSERT_EQ(static_cast<int>(t.perimeter.size()), n);
  ASSERT_EQ(static_cast<int>(t.cell_offset.size()), n + 1);
  ASSERT_EQ(static_cast<int>(t.origin.size()), t.n_points);
  ASSERT_EQ(static_cast<int>(t.position.size()), t.n_points);
  const double tol = 1e-8;  // absolute edge-length threshold (mean spacing ~1)
  // Round-off allowance: 1e-11 for well-separated points, more when two points
  // are so close that their bisector is ill-conditioned (see conditioning()).
  const double cond_tol = 1e-15 * testutil::conditioning(cfg);
  const double len_tol = 1e-10 + cond_tol, area_tol = 1e-11 + cond_tol;
  for (int i = 0; i < n; ++i) {
    SCOPED_TRACE("cell " + std::to_string(i));
    EXPECT_EQ(t.origin[i], i);
    EXPECT_EQ(t.position[i].x, cfg.xy[2 * i]);
    EXPECT_EQ(t.position[i].y, cfg.xy[2 * i + 1]);
    EXPECT_NEAR(t.area[i], ref[i].area, area_tol * std::max(1.0, ref[i].area));
    EXPECT_NEAR(t.perimeter[i], ref[i].perimeter, area_tol * std::max(1.0, ref[i].perimeter));
    const auto a = tess_edges(t, cfg.box, i, tol);
    const auto b = ref_edges(ref[i], tol);
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].nbr, b[k].nbr);
      EXPECT_EQ(a[k].sx, b[k].sx);
      EXPECT_EQ(a[k].sy, b[k].sy);
      EXPECT_NEAR(a[k].length, b[k].length, len_tol);
    }
    // Coordination: sides longer than 1e-9 of the mean side (tessera's rule).
    int z = 0;
    const double mean = ref[i].perimeter / static_cast<double>(ref[i].edges.size());
    for (const auto &e : ref[i].edges) z += e.length > 1e-9 * mean;
    EXPECT_EQ(t.coordination_number(i), z);
  }
}

tessera::Tessellation tess(const Config &c) {
  return tessera::tessellate_periodic(c.box, c.points());
}

}  // namespace

// ---------------------------------------------------------------------------
// Agreement with the reference

TEST(Tessellation, MatchesReferenceRandom) {
  struct Case {
    int n;
    double xlo, ylo, lx, ly;
    uint64_t seed;
    double dmin;
  };
  const Case cases[] = {
      {64, 0.0, 0.0, 8.0, 8.0, 1, 0.3},      {100, -3.5, 2.25, 12.5, 8.0, 2, 0.2},
      {200, 0.0, 0.0, 20.0, 10.0, 3, 0.0},   {150, 100.0, -50.0, 9.0, 16.0, 4, 0.1},
      {50, 0.0, 0.0, 5.0, 10.0, 5, 0.4},     {120, 0.0, 0.0, 0.011, 0.011, 6, 0.0002},
  };
  for (const Case &cs : cases) {
    SCOPED_TRACE("seed " + std::to_string(cs.seed));
    const Config cfg = random_config(cs.n, cs.xlo, cs.ylo, cs.lx, cs.ly, cs.seed, cs.dmin);
    ASSERT_EQ(cfg.n(), cs.n);
    if (cs.lx < 1) {
      // Small box: lengths scale with it; compare relative to the spacing.
      const auto ref = reftess::voronoi(cfg.refbox(), cfg.xy);
      const auto t = tess(cfg);
      double asum = 0;
      for (int i = 0; i < cfg.n(); ++i) {
        EXPECT_NEAR(t.area[i], ref[i].area, 1e-11 * cfg.box.area() / cfg.n());
        EXPECT_NEAR(t.perimeter[i], ref[i].perimeter, 1e-11 * cs.lx);
        asum += t.area[i];
      }
      EXPECT_NEAR(asum, cfg.box.area(), 1e-12 * cfg.box.area());
      continue;
    }
    expect_matches_reference(cfg, tess(cfg));
  }
}

TEST(Tessellation, MatchesReferenceClusteredAndSparse) {
  // Strongly inhomogeneous density: a dense cluster in a sparse background,
  // which makes long thin cells and needs far periodic images.
  testutil::Rng rng(77);
  Config cfg;
  cfg.box = tessera::Box::rect(0, 10, 0, 10);
  for (int i = 0; i < 60; ++i) {
    cfg.xy.push_back(4 + rng.uniform());
    cfg.xy.push_back(4 + rng.uniform());
  }
  for (int i = 0; i < 8; ++i) {
    cfg.xy.push_back(rng.uniform(0, 10));
    cfg.xy.push_back(rng.uniform(0, 10));
  }
  cfg.type.assign(cfg.n(), 0);
  expect_matches_reference(cfg, tess(cfg));
}

TEST(Tessellation, FewPointsInPeriodicBox) {
  // Very few points: cells neighbour several images of the same point.
  for (uint64_t seed = 10; seed < 14; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Config cfg = random_config(5, 0.0, 0.0, 3.0, 2.0, seed, 0.3, false);
    ASSERT_EQ(cfg.n(), 5);
    expect_matches_reference(cfg, tess(cfg));
  }
}

TEST(Tessellation, AreasSumToBoxArea) {
  for (uint64_t seed = 20; seed < 24; ++seed) {
    const Config cfg = random_config(180, -1.0, 3.0, 15.0, 12.0, seed, 0.0);
    const auto t = tess(cfg);
    const double s = std::accumulate(t.area.begin(), t.area.end(), 0.0);
    EXPECT_NEAR(s, cfg.box.area(), 1e-12 * cfg.box.area());
    for (double a : t.area) EXPECT_GT(a, 0.0);
  }
}

TEST(Tessellation, VerticesAreCircumcentresAndPolygonsAreConsistent) {
  const Config cfg = random_config(90, 0.0, 0.0, 10.0, 9.0, 31, 0.1);
  const auto t = tess(cfg);
  ASSERT_EQ(t.vertices.size(), t.triangles.size());
  ASSERT_EQ(t.radius.size(), t.triangles.size());
  for (size_t k = 0; k < t.triangles.size(); ++k) {
    const auto &tri = t.triangles[k];
    const tessera::Vec2 &a = t.position[tri[0]], &b = t.position[tri[1]], &c = t.position[tri[2]];
    // counter-clockwise
    EXPECT_GT((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x), 0.0) << "triangle " << k;
    const tessera::Vec2 h = t.vertices[k];
    for (const tessera::Vec2 *p : {&a, &b, &c}) {
      EXPECT_NEAR(std::hypot(h.x - p->x, h.y - p->y), t.radius[k], 1e-10) << "triangle " << k;
    }
  }
  for (int i = 0; i < t.n_owned; ++i) {
    // Polygon from the listed vertices: CCW, shoelace area and perimeter match.
    double a2 = 0, per = 0;
    const int m = t.cell_size(i);
    ASSERT_GE(m, 3);
    for (int v = 0; v < m; ++v) {
      const int k = t.cell_offset[i] + v;
      const int k1 = t.cell_offset[i] + (v + 1) % m;
      const tessera::Vec2 p = t.vertices[t.cell_vertex[k]], q = t.vertices[t.cell_vertex[k1]];
      a2 += p.x * q.y - p.y * q.x;
      const double l = std::hypot(q.x - p.x, q.y - p.y);
      EXPECT_NEAR(t.edge_length[k], l, 1e-12);
      per += l;
      // The side from v to v+1 lies on the bisector of i and its neighbour.
      const tessera::Vec2 r = t.position[i], s = t.position[t.cell_neighbor[k]];
      const double dp = std::hypot(p.x - r.x, p.y - r.y) - std::hypot(p.x - s.x, p.y - s.y);
      const double dq = std::hypot(q.x - r.x, q.y - r.y) - std::hypot(q.x - s.x, q.y - s.y);
      EXPECT_NEAR(dp, 0.0, 1e-10);
      EXPECT_NEAR(dq, 0.0, 1e-10);
      // Each vertex's triangle contains the cell's point.
      const auto &tri = t.triangles[t.cell_vertex[k]];
      EXPECT_TRUE(tri[0] == i || tri[1] == i || tri[2] == i);
    }
    EXPECT_NEAR(0.5 * a2, t.area[i], 1e-10);
    EXPECT_NEAR(per, t.perimeter[i], 1e-10);
  }
}

TEST(Tessellation, NeighboursAreMutual) {
  for (uint64_t seed = 40; seed < 43; ++seed) {
    const Config cfg = random_config(120, 0.0, 0.0, 11.0, 11.0, seed, 0.05);
    const auto t = tess(cfg);
    const double tol = 1e-8;
    for (int c = 0; c < t.n_owned; ++c) {
      for (const EdgeKey &e : tess_edges(t, cfg.box, c, tol)) {
        // Seen from e.nbr, c sits at the opposite shift with the same length.
        const auto back = tess_edges(t, cfg.box, e.nbr, tol);
        int found = 0;
        for (const EdgeKey &b : back) {
          if (b.nbr == c && b.sx == -e.sx && b.sy == -e.sy) {
            ++found;
            EXPECT_NEAR(b.length, e.length, 1e-12);
          }
        }
        EXPECT_EQ(found, 1) << "cell " << c << " -> " << e.nbr << " (" << e.sx << "," << e.sy
                            << ") not mirrored";
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Invariances: relabelling, translation by a box vector, translation with wrap

namespace {

struct Snapshot {
  std::vector<double> area, perimeter, force, cell_energy;
  std::vector<int> z;
  double energy = 0;
  double virial[4] = {0, 0, 0, 0};
};

Snapshot snapshot(const Config &cfg, const tessera::Model &model) {
  Snapshot s;
  const auto t = tess(cfg);
  s.area = t.area;
  s.perimeter = t.perimeter;
  for (int i = 0; i < cfg.n(); ++i) s.z.push_back(t.coordination_number(i));
  const auto out = tessera::periodic_forces(cfg.box, cfg.points(), cfg.type.data(), model,
                                            s.force, &s.cell_energy);
  s.energy = out.energy;
  std::copy(out.virial, out.virial + 4, s.virial);
  return s;
}

void expect_same(const Snapshot &a, const Snapshot &b, const std::vector<int> &perm) {
  // b's point k is a's point perm[k].
  const double ftol = 1e-10 * std::max(1.0, testutil::max_abs(a.force));
  for (size_t k = 0; k < perm.size(); ++k) {
    const int i = perm[k];
    EXPECT_NEAR(b.area[k], a.area[i], 1e-12);
    EXPECT_NEAR(b.perimeter[k], a.perimeter[i], 1e-12);
    EXPECT_EQ(b.z[k], a.z[i]);
    EXPECT_NEAR(b.cell_energy[k], a.cell_energy[i], 1e-11);
    EXPECT_NEAR(b.force[2 * k], a.force[2 * i], ftol);
    EXPECT_NEAR(b.force[2 * k + 1], a.force[2 * i + 1], ftol);
  }
  EXPECT_NEAR(b.energy, a.energy, 1e-11 * std::max(1.0, std::abs(a.energy)));
  const double vs = std::max({1.0, std::abs(a.virial[0]), std::abs(a.virial[1])});
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(b.virial[k], a.virial[k], 1e-10 * vs) << "virial " << k;
}

}  // namespace

TEST(Tessellation, InvariantUnderRelabelling) {
  const Config cfg = random_config(110, 0.0, 0.0, 10.0, 11.0, 50, 0.1);
  const tessera::Model model = testutil::to_model(testutil::random_params(50, false));
  const Snapshot a = snapshot(cfg, model);
  std::vector<int> perm(cfg.n());
  std::iota(perm.begin(), perm.end(), 0);
  testutil::Rng rng(5);
  for (int k = cfg.n() - 1; k > 0; --k) std::swap(perm[k], perm[rng.below(k + 1)]);
  Config p = cfg;
  for (int k = 0; k < cfg.n(); ++k) {
    p.xy[2 * k] = cfg.xy[2 * perm[k]];
    p.xy[2 * k + 1] = cfg.xy[2 * perm[k] + 1];
    p.type[k] = cfg.type[perm[k]];
  }
  expect_same(a, snapshot(p, model), perm);
}

TEST(Tessellation, InvariantUnderBoxVectorShift) {
  const Config cfg = random_config(100, 0.0, 0.0, 10.0, 10.0, 51, 0.1);
  const tessera::Model model = testutil::to_model(testutil::random_params(51, true));
  const Snapshot a = snapshot(cfg, model);
  std::vector<int> id(cfg.n());
  std::iota(id.begin(), id.end(), 0);
  // Shift box and points together by box vectors.
  const double shifts[][2] = {{10.0, 0.0}, {0.0, -10.0}, {-20.0, 30.0}, {-30.0, -20.0}};
  for (const auto &s : shifts) {
    SCOPED_TRACE("shift " + std::to_string(s[0]) + "," + std::to_string(s[1]));
    Config b = cfg;
    b.box = tessera::Box::rect(s[0], s[0] + 10.0, s[1], s[1] + 10.0);
    for (int i = 0; i < b.n(); ++i) {
      b.xy[2 * i] += s[0];
      b.xy[2 * i + 1] += s[1];
    }
    expect_same(a, snapshot(b, model), id);
  }
}

TEST(Tessellation, AccurateFarFromTheOrigin) {
  // A box far from the origin (a LAMMPS box of 1e6 cells at density 1 spans
  // 0..1000).  x + 1024 rounds the coordinates by at most 1.2e-13, which moves
  // areas and perimeters by ~1e-13; the geometry must not lose more than that
  // (e.g. a shoelace sum over absolute coordinates loses eps * |x|^2 ~ 1e-10).
  const Config cfg = random_config(100, 0.0, 0.0, 10.0, 10.0, 53, 0.1);
  const tessera::Model model = testutil::to_model(testutil::random_params(53, true));
  const Snapshot a = snapshot(cfg, model);
  std::vector<int> id(cfg.n());
  std::iota(id.begin(), id.end(), 0);
  Config b = cfg;
  b.box = tessera::Box::rect(1020.0, 1030.0, -510.0, -500.0);
  for (int i = 0; i < b.n(); ++i) {
    b.xy[2 * i] += 1020.0;
    b.xy[2 * i + 1] -= 510.0;
  }
  expect_same(a, snapshot(b, model), id);
}

TEST(Tessellation, InvariantUnderArbitraryShiftWithWrap) {
  const Config cfg = random_config(100, 0.0, 0.0, 10.0, 9.0, 52, 0.1);
  const tessera::Model model = testutil::to_model(testutil::random_params(52, false));
  const Snapshot a = snapshot(cfg, model);
  std::vector<int> id(cfg.n());
  std::iota(id.begin(), id.end(), 0);
  const double shifts[][2] = {{3.7, -1.3}, {-0.001, 0.0005}, {12.345, 27.1}, {5.0, 4.5}};
  for (const auto &s : shifts) {
    SCOPED_TRACE("shift " + std::to_string(s[0]) + "," + std::to_string(s[1]));
    Config b = cfg;
    for (int i = 0; i < b.n(); ++i) {
      b.xy[2 * i] += s[0];
      b.xy[2 * i + 1] += s[1];
    }
    tessera::wrap_into_box(b.box, b.xy);
    for (int i = 0; i < b.n(); ++i) {
      ASSERT_GE(b.xy[2 * i], 0.0);
      ASSERT_LT(b.xy[2 * i], 10.0);
      ASSERT_GE(b.xy[2 * i + 1], 0.0);
      ASSERT_LT(b.xy[2 * i + 1], 9.0);
    }
    const Snapshot sb = snapshot(b, model);
    // Same geometry; only the virial's reference point changes (sum F = 0 keeps it).
    expect_same(a, sb, id);
  }
}

TEST(Tessellation, WrapIntoBox) {
  const tessera::Box box = tessera::Box::rect(-1.0, 3.0, 2.0, 4.0);
  std::vector<double> xy{-1.0, 2.0, 3.0, 4.0, -5.5, 9.25, 2.5, 3.5, 100.0, -100.0, -1e-17, 2.0};
  tessera::wrap_into_box(box, xy);
  const double want[] = {-1.0, 2.0, -1.0, 2.0, 2.5, 3.25, 2.5, 3.5, 0.0, 2.0};
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(xy[k], want[k], 1e-12) << k;
  // A coordinate a hair below lo must end inside [lo, hi), not at hi.
  EXPECT_GE(xy[10], -1.0);
  EXPECT_LT(xy[10], 3.0);
  for (size_t k = 0; k < xy.size(); k += 2) {
    EXPECT_GE(xy[k], -1.0);
    EXPECT_LT(xy[k], 3.0);
    EXPECT_GE(xy[k + 1], 2.0);
    EXPECT_LT(xy[k + 1], 4.0);
  }
}

// ---------------------------------------------------------------------------
// Owned + ghost tessellation and its coverage check

namespace {

// Independent worst overshoot of the circumdisks of the owned cells' triangles
// beyond [lo - w, hi + w].
double worst_overshoot(const tessera::Tessellation &t, const std::vector<double> &xy,
                       const double lo[2], const double hi[2]) {
  double worst = -1e300;
  for (int c = 0; c < t.n_owned; ++c)
    for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k) {
      const auto &tri = t.triangles[t.cell_vertex[k]];
      const double ax = xy[2 * tri[0]], ay = xy[2 * tri[0] + 1];
      const double bx = xy[2 * tri[1]] - ax, by = xy[2 * tri[1] + 1] - ay;
      const double cx = xy[2 * tri[2]] - ax, cy = xy[2 * tri[2] + 1] - ay;
      const double d = 2 * (bx * cy - by * cx);
      const double ux = (cy * (bx * bx + by * by) - by * (cx * cx + cy * cy)) / d;
      const double uy = (bx * (cx * cx + cy * cy) - cx * (bx * bx + by * by)) / d;
      const double r = std::hypot(ux, uy);
      const double hx = ax + ux, hy = ay + uy;
      worst = std::max({worst, lo[0] - (hx - r), (hx + r) - hi[0], lo[1] - (hy - r),
                        (hy + r) - hi[1]});
    }
  return worst;
}

}  // namespace

TEST(Coverage, ThinShellFailsThickShellPassesAndMatchesPeriodic) {
  const Config cfg = random_config(100, 0.0, 0.0, 10.0, 10.0, 60, 0.2);
  const auto tp = tess(cfg);
  int n_fired = 0, n_ok = 0;
  bool was_ok = false;
  for (double w = 0.25; w <= 4.0; w += 0.25) {
    SCOPED_TRACE("margin " + std::to_string(w));
    const std::vector<double> xy = testutil::with_images(cfg, w);
    const tessera::Points pts{xy.data(), static_cast<int>(xy.size() / 2), 2};
    const double lo[2] = {-w, -w}, hi[2] = {10.0 + w, 10.0 + w};
    tessera::Tessellation t;
    try {
      t = tessera::tessellate_local(pts, cfg.n());
    } catch (const tessera::Error &) {
      // Allowed only while the shell is so thin that an owned cell is unbounded.
      EXPECT_FALSE(was_ok) << "tessellate_local threw although a thinner shell was fine";
      EXPECT_LT(w, 1.5);
      continue;
    }
    const tessera::Coverage cov = tessera::check_coverage(t, lo, hi);
    const double over = worst_overshoot(t, xy, lo, hi);
    if (cov.ok) {
      ++n_ok;
      was_ok = true;
      EXPECT_EQ(cov.needed_margin, 0.0);
      EXPECT_LE(over, 1e-9);
      for (int i = 0; i < cfg.n(); ++i) {
        EXPECT_NEAR(t.area[i], tp.area[i], 1e-11);
        EXPECT_NEAR(t.perimeter[i], tp.perimeter[i], 1e-11);
      }
    } else {
      ++n_fired;
      EXPECT_FALSE(was_ok) << "coverage must be monotone in the margin";
      EXPECT_GT(cov.needed_margin, 0.0);
      EXPECT_NEAR(cov.needed_margin, over, 1e-9);
      ASSERT_GE(cov.worst_cell, 0);
      ASSERT_LT(cov.worst_cell, cfg.n());
    }
  }
  EXPECT_GT(n_fired, 0) << "no margin was thin enough for the check to fire";
  EXPECT_GT(n_ok, 0);
}

TEST(Coverage, GrowingByNeededMarginConverges) {
  for (uint64_t seed = 61; seed < 64; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Config cfg = random_config(80, 0.0, 0.0, 8.0, 10.0, seed, 0.0);
    const auto tp = tess(cfg);
    double w = 1.0;
    bool ok = false;
    for (int iter = 0; iter < 6 && !ok; ++iter) {
      const std::vector<double> xy = testutil::with_images(cfg, w);
      const tessera::Points pts{xy.data(), static_cast<int>(xy.size() / 2), 2};
      const double lo[2] = {-w, -w}, hi[2] = {8.0 + w, 10.0 + w};
      tessera::Tessellation t;
      try {
        t = tessera::tessellate_local(pts, cfg.n());
      } catch (const tessera::Error &) {
        w *= 2;
        continue;
      }
      const tessera::Coverage cov = tessera::check_coverage(t, lo, hi);
      ok = cov.ok;
      if (ok) {
        const double tol = 1e-11 + 1e-15 * testutil::conditioning(cfg);
        for (int i = 0; i < cfg.n(); ++i) EXPECT_NEAR(t.area[i], tp.area[i], tol);
      } else {
        w += cov.needed_margin * (1 + 1e-9) + 1e-12;
      }
    }
    EXPECT_TRUE(ok) << "coverage did not pass after growing the shell, last margin " << w;
  }
}

TEST(Coverage, LocalTessellationThrowsWhenOwnedCellIsUnbounded) {
  const Config cfg = random_config(30, 0.0, 0.0, 5.0, 5.0, 65, 0.3, false);
  // No ghosts at all: the outer owned cells are unbounded.
  EXPECT_THROW(tessera::tessellate_local(cfg.points(), cfg.n()), tessera::Error);
  // Asked not to throw: the unbounded cell is reported and coverage fails
  // with an infinite margin.
  const tessera::Tessellation t =
      tessera::tessellate_local(cfg.points(), cfg.n(), nullptr, /*throw_if_unbounded=*/false);
  ASSERT_GE(t.unbounded_cell, 0);
  ASSERT_LT(t.unbounded_cell, cfg.n());
  const double lo[2] = {0, 0}, hi[2] = {5, 5};
  const tessera::Coverage cov = tessera::check_coverage(t, lo, hi);
  EXPECT_FALSE(cov.ok);
  EXPECT_TRUE(std::isinf(cov.needed_margin) && cov.needed_margin > 0);
  // A thin shell of 0.1 leaves most cells bounded, a few unbounded, or the
  // disks poke out: either way not ok, and no exception.
  const std::vector<double> xy = testutil::with_images(cfg, 0.1);
  const tessera::Points pts{xy.data(), static_cast<int>(xy.size() / 2), 2};
  const tessera::Tessellation t2 = tessera::tessellate_local(pts, cfg.n(), nullptr, false);
  const double lo2[2] = {-0.1, -0.1}, hi2[2] = {5.1, 5.1};
  const tessera::Coverage cov2 = tessera::check_coverage(t2, lo2, hi2);
  EXPECT_FALSE(cov2.ok);
  EXPECT_GT(cov2.needed_margin, 0.0);
}

// ---------------------------------------------------------------------------
// Bad input

namespace {

template <class F>
std::string error_message(F &&f) {
  try {
    f();
  } catch (const tessera::Error &e) {
    return e.what();
  } catch (const std::exception &e) {
    ADD_FAILURE() << "threw a non-tessera exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "did not throw";
  return "";
}

// Jittered 7x7 grid with spacing 1: the interior 5x5 points first (indices
// 0..24, to be owned), then the outer ring (25..48, ghosts).
std::vector<double> grid_points(uint64_t seed) {
  testutil::Rng rng(seed);
  std::vector<double> inner, outer;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) {
      const bool ring = i == 0 || j == 0 || i == 6 || j == 6;
      std::vector<double> &v = ring ? outer : inner;
      v.push_back(i + rng.uniform(-0.2, 0.2));
      v.push_back(j + rng.uniform(-0.2, 0.2));
    }
  inner.insert(inner.end(), outer.begin(), outer.end());
  return inner;
}

}  // namespace

TEST(BadInput, CoincidentPointsNameBothPoints) {
  // Periodic, by index.
  Config cfg = random_config(40, 0.0, 0.0, 7.0, 6.0, 70, 0.3);
  cfg.xy[2 * 27] = cfg.xy[2 * 13];
  cfg.xy[2 * 27 + 1] = cfg.xy[2 * 13 + 1];
  std::string msg = error_message([&] { tessera::tessellate_periodic(cfg.box, cfg.points()); });
  EXPECT_THAT(msg, AllOf(HasSubstr("13"), HasSubstr("27")));
  // Periodic, by id.
  std::vector<long> ids(cfg.n());
  for (int i = 0; i < cfg.n(); ++i) ids[i] = 5000 + 37 * i;
  msg = error_message(
      [&] { tessera::tessellate_periodic(cfg.box, cfg.points(), ids.data()); });
  EXPECT_THAT(msg, AllOf(HasSubstr(std::to_string(ids[13])), HasSubstr(std::to_string(ids[27]))));
  // Local: an owned point and a ghost at the same place.
  std::vector<double> xy = grid_points(71);
  const tessera::Points pts{xy.data(), 49, 2};
  EXPECT_NO_THROW(tessera::tessellate_local(pts, 25));
  xy[2 * 40] = xy[2 * 12];
  xy[2 * 40 + 1] = xy[2 * 12 + 1];
  std::vector<long> lids(49);
  for (int i = 0; i < 49; ++i) lids[i] = 900 + 11 * i;
  msg = error_message([&] { tessera::tessellate_local(pts, 25, lids.data()); });
  EXPECT_THAT(msg, AllOf(HasSubstr(std::to_string(lids[12])), HasSubstr(std::to_string(lids[40]))));
  // Two owned points, without ids: indices.
  xy = grid_points(71);
  xy[2 * 21] = xy[2 * 16];
  xy[2 * 21 + 1] = xy[2 * 16 + 1];
  const tessera::Points pts2{xy.data(), 49, 2};
  msg = error_message([&] { tessera::tessellate_local(pts2, 25); });
  EXPECT_THAT(msg, AllOf(HasSubstr("16"), HasSubstr("21")));
}

TEST(BadInput, FewerThanThreePoints) {
  const double two[] = {0.0, 0.0, 1.0, 0.5};
  const std::string msg =
      error_message([&] { tessera::tessellate_local(tessera::Points{two, 2, 2}, 2); });
  EXPECT_THAT(testutil::lower(msg), AnyOf(HasSubstr("3"), HasSubstr("three")));
  const double none[] = {0.0, 0.0};
  error_message([&] { tessera::tessellate_local(tessera::Points{none, 0, 2}, 0); });
  error_message([&] { tessera::tessellate_local(tessera::Points{none, 1, 2}, 1); });
}

TEST(BadInput, CollinearPoints) {
  std::vector<double> xy;
  for (int i = 0; i < 8; ++i) {
    xy.push_back(0.5 + 1.5 * i);
    xy.push_back(-2.0 + 0.75 * i);
  }
  const std::string msg =
      error_message([&] { tessera::tessellate_local(tessera::Points{xy.data(), 8, 2}, 8); });
  EXPECT_THAT(testutil::lower(msg), AnyOf(HasSubstr("collinear"), HasSubstr("colinear")));
  // Few owned points on a line among ghosts on the same line.
  error_message([&] { tessera::tessellate_local(tessera::Points{xy.data(), 8, 2}, 2); });
}

TEST(BadInput, NonFiniteCoordinateNamesThePoint) {
  for (double bad : {std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()}) {
    SCOPED_TRACE(bad);
    Config cfg = random_config(40, 0.0, 0.0, 7.0, 6.0, 72, 0.3);
    cfg.xy[2 * 17 + 1] = bad;
    std::string msg =
        error_message([&] { tessera::tessellate_periodic(cfg.box, cfg.points()); });
    EXPECT_THAT(msg, HasSubstr("17"));
    std::vector<long> ids(cfg.n());
    for (int i = 0; i < cfg.n(); ++i) ids[i] = 7000 + 3 * i;
    msg = error_message(
        [&] { tessera::tessellate_periodic(cfg.box, cfg.points(), ids.data()); });
    EXPECT_THAT(msg, HasSubstr("7051"));

    // Local: a ghost (index 30) and an owned point (index 7).
    std::vector<double> xy = grid_points(73);
    xy[2 * 30] = bad;
    std::vector<long> lids(49);
    for (int i = 0; i < 49; ++i) lids[i] = 300 + i;
    msg = error_message(
        [&] { tessera::tessellate_local(tessera::Points{xy.data(), 49, 2}, 25, lids.data()); });
    EXPECT_THAT(msg, HasSubstr("330"));
    xy = grid_points(73);
    xy[2 * 7 + 1] = bad;
    msg = error_message(
        [&] { tessera::tessellate_local(tessera::Points{xy.data(), 49, 2}, 25, lids.data()); });
    EXPECT_THAT(msg, HasSubstr("307"));
  }
}

TEST(BadInput, BoxWithNonPositiveOrNonFiniteLength) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const tessera::Box bad[] = {tessera::Box::rect(0, 0, 0, 1), tessera::Box::rect(0, 1, 2, 1),
                              tessera::Box::rect(0, -1, 0, 1), tessera::Box::rect(0, nan, 0, 1),
                              tessera::Box::rect(0, 1, 0, inf), tessera::Box::rect(-inf, 1, 0, 1)};
  for (const tessera::Box &b : bad) {
    const std::string msg = error_message([&] { b.validate(); });
    EXPECT_THAT(testutil::lower(msg), HasSubstr("box"));
    const Config cfg = random_config(20, 0.0, 0.0, 5.0, 5.0, 74, 0.3, false);
    error_message([&] { tessera::tessellate_periodic(b, cfg.points()); });
  }
  // Triclinic boxes are supported: a finite tilt is valid, a non-finite one not.
  tessera::Box tilted = tessera::Box::rect(0, 1, 0, 1);
  tilted.xy = 0.25;
  EXPECT_NO_THROW(tilted.validate());
  tilted.xy = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(testutil::lower(error_message([&] { tilted.validate(); })), HasSubstr("tilt"));
  EXPECT_NO_THROW(tessera::Box::rect(-2, 3, 1e-3, 2e-3).validate());
}

TEST(BadInput, ModelValidate) {
  {
    tessera::Model m(2);
    m.types[1].K = -2.5;
    const std::string msg = error_message([&] { m.validate(); });
    EXPECT_THAT(msg, AllOf(HasSubstr("K"), HasSubstr("-2.5")));
  }
  {
    tessera::Model m(2);
    m.types[0].K = 0.0;
    const std::string msg = error_message([&] { m.validate(); });
    EXPECT_THAT(msg, HasSubstr("K"));
  }
  {
    tessera::Model m(3);
    m.types[2].A0 = 0.0;
    const std::string msg = error_message([&] { m.validate(); });
    EXPECT_THAT(msg, HasSubstr("A0"));
  }
  {
    tessera::Model m(1);
    m.types[0].A0 = -0.75;
    const std::string msg = error_message([&] { m.validate(); });
    EXPECT_THAT(msg, AllOf(HasSubstr("A0"), HasSubstr("-0.75")));
  }
  {
    tessera::Model m(2);
    m.set_lambda(0, 1, std::numeric_limits<double>::quiet_NaN());
    error_message([&] { m.validate(); });
  }
  {
    tessera::Model m(2);
    m.types[1].Gamma = std::numeric_limits<double>::infinity();
    error_message([&] { m.validate(); });
  }
  {
    // Valid: Gamma zero, Lambda of either sign; set_lambda is symmetric.
    tessera::Model m(2);
    m.types[0].Gamma = 0.0;
    m.set_lambda(0, 1, -0.3);
    m.set_lambda(1, 1, 0.7);
    EXPECT_NO_THROW(m.validate());
    EXPECT_EQ(m.lambda_of(1, 0), -0.3);
    EXPECT_EQ(m.lambda_of(0, 1), -0.3);
    EXPECT_EQ(m.lambda_of(1, 1), 0.7);
    EXPECT_EQ(m.ntypes(), 2);
  }
}
