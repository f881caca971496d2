// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Degenerate input that once gave NaN forces or negative areas without an
// error (the first three tests are those reproducers, their numbers copied
// in), and the input limits of doc/model.md ("Limits of the input"): finite
// and right results on one side of each limit, a tessera::Error naming the
// points and the cause on the other.

#include "reference.h"
#include "test_util.h"
#include "tessera/energy.h"
#include "tessera/mesh.h"
#include "tessera/tessellation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

struct Case {
  tessera::Box box;
  tessera::Model model{1};
  std::vector<double> xy;
  std::vector<int> type;  // 0-based
  int n() const { return static_cast<int>(xy.size() / 2); }
  tessera::Points points() const { return tessera::Points{xy.data(), n(), 2}; }
};

// The points named in an error message ("point 7 at (x, y)"), in order.
std::vector<int> named_points(const std::string &msg) {
  std::vector<int> out;
  const std::regex re("point ([0-9]+) at \\(");
  for (auto it = std::sregex_iterator(msg.begin(), msg.end(), re); it != std::sregex_iterator();
       ++it)
    out.push_back(std::stoi((*it)[1]));
  return out;
}

// The message of the tessera::Error that periodic_forces throws, or "" if
// it throws none.
std::string error_of(const Case &c) {
  std::vector<double> f;
  try {
    tessera::periodic_forces(c.box, c.points(), c.type.data(), c.model, f);
  } catch (const tessera::Error &e) {
    return e.what();
  }
  return "";
}

double energy_at(const Case &c, const std::vector<double> &xy) {
  std::vector<double> f;
  return tessera::periodic_forces(c.box, tessera::Points{xy.data(), c.n(), 2}, c.type.data(),
                                  c.model, f)
      .energy;
}

}  // namespace

// 8 points on one slanted row in a 2 x 2 box tilted by -1.6: the row runs
// along the box's second edge vector (-1.6, 2), so the points and their
// images form the lattice spanned by u = (-0.2, 0.25) and a = (2, 0).  The
// images' hull holds nearly flat triangles of infinite circumradius, whose
// multifold-vertex tolerance (a fraction of the radius) was infinite: a
// group centre at -inf and NaN forces.
TEST(Degenerate, SlantedRowInTiltedBox) {
  Case c;
  c.box = tessera::Box::rect(0, 2, 0, 2);
  c.box.xy = -1.6000685329303517;
  c.model.types[0] = {1.0, 0.5, 0.10000000000000001};
  c.model.set_lambda(0, 0, -0.35355339059327379);
  const double row[8][2] = {{0, 0},
                            {-0.20000856661629396, 0.25},
                            {-0.40001713323258792, 0.5},
                            {-0.60002569984888188, 0.75},
                            {-0.80003426646517584, 1},
                            {-1.0000428330814697, 1.25},
                            {-1.2000513996977638, 1.5},
                            {-1.4000599663140578, 1.75}};
  for (const auto &p : row) {
    c.xy.push_back(p[0]);
    c.xy.push_back(p[1]);
  }
  c.type.assign(8, 0);
  std::vector<double> f;
  const auto out = tessera::periodic_forces(c.box, c.points(), c.type.data(), c.model, f);
  const auto t = tessera::tessellate_periodic(c.box, c.points());
  // All cells are translates of one lattice cell: area = box area / 8.  The
  // lattice (u = (-0.2000085..., 0.25), a = (2, 0)) repeats in no small
  // orthogonal box (u's x is not a round number), so the reference is the
  // cell of one point clipped by the bisectors of the lattice vectors
  // i u + j a, built here independently of the core.
  const double ux = row[1][0], uy = row[1][1];
  std::vector<std::array<double, 2>> poly = {{-10, -10}, {10, -10}, {10, 10}, {-10, 10}};
  for (int i = -12; i <= 12; ++i)
    for (int j = -3; j <= 3; ++j) {
      if (i == 0 && j == 0) continue;
      const double vx = i * ux + j * 2.0, vy = i * uy;
      const double h = 0.5 * (vx * vx + vy * vy);  // keep x . v <= |v|^2 / 2
      std::vector<std::array<double, 2>> next;
      for (size_t k = 0; k < poly.size(); ++k) {
        const auto &p = poly[k], &q = poly[(k + 1) % poly.size()];
        const double sp = p[0] * vx + p[1] * vy - h, sq = q[0] * vx + q[1] * vy - h;
        if (sp <= 0) next.push_back(p);
        if ((sp < 0) != (sq < 0) && sp != 0 && sq != 0) {
          const double s = sp / (sp - sq);
          next.push_back({p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])});
        }
      }
      poly = next;
    }
  double area = 0, perim = 0;
  for (size_t k = 0; k < poly.size(); ++k) {
    const auto &p = poly[k], &q = poly[(k + 1) % poly.size()];
    area += 0.5 * (p[0] * q[1] - q[0] * p[1]);
    perim += std::hypot(q[0] - p[0], q[1] - p[1]);
  }
  ASSERT_NEAR(area, 0.5, 1e-12);  // the clipping itself is right
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(t.area[i], 0.5, 1e-12) << "cell " << i;
    EXPECT_NEAR(t.perimeter[i], perim, 1e-12) << "cell " << i;
    // Every lattice point is a centre of inversion symmetry: no force.
    ASSERT_TRUE(std::isfinite(f[2 * i]) && std::isfinite(f[2 * i + 1])) << "cell " << i;
    EXPECT_NEAR(f[2 * i], 0.0, 1e-12) << "cell " << i;
    EXPECT_NEAR(f[2 * i + 1], 0.0, 1e-12) << "cell " << i;
  }
  const double lam = -0.35355339059327379, gamma = 0.10000000000000001;
  const double per_cell = 0.5 * gamma * perim * perim + 0.5 * lam * perim;  // A = A0
  EXPECT_NEAR(out.energy, 8 * per_cell, 1e-12);
  for (double v : out.virial) EXPECT_TRUE(std::isfinite(v));
}

// Five points within a few ulps of each other near (2.3e5, -2.2e6) in a
// 9 x 9 box: the whole cluster was taken for one multifold vertex whose fan
// triangles were flat (division by zero, NaN forces).  The points are
// closer than the separation limit: an Error naming two of them.
TEST(Degenerate, ClusterOfAFewUlps) {
  Case c;
  c.box = tessera::Box::rect(230688.18757292919, 230697.18757292919, -2152394.3107358883,
                             -2152385.3107358883);
  c.model = tessera::Model(2);
  c.model.types[0] = {1, 16.199999999999999, 0.10000000000000001};
  c.model.types[1] = {1.5, 17.82, 0.15000000000000002};
  c.model.set_lambda(0, 0, -2.0124611797498106);
  c.model.set_lambda(0, 1, -2.4149534156997725);
  c.model.set_lambda(1, 1, -2.8174456516497348);
  c.xy = {230693.03966939219, -2152388.9401803371, 230693.03966939228, -2152388.9401803371,
          230693.03966939211, -2152388.9401803371, 230693.03966939176, -2152388.9401803366,
          230693.03966939184, -2152388.9401803366};
  c.type = {0, 0, 1, 1, 0};
  const std::string msg = error_of(c);
  ASSERT_FALSE(msg.empty()) << "no error for five points a few ulps apart";
  EXPECT_NE(msg.find("nearly coincide"), std::string::npos) << msg;
  const auto pts = named_points(msg);
  ASSERT_EQ(pts.size(), 2u) << msg;
  EXPECT_NE(pts[0], pts[1]) << msg;
  for (int p : pts) EXPECT_LT(p, 5) << msg;
  EXPECT_NE(msg.find("(230693.0396693"), std::string::npos) << "coordinates: " << msg;
}

// A 4 x 3 grid in a tilted box with three more points about 1e-15 from two
// grid points: a cell area of -0.207 and an area sum of 35.966 in a box of
// 36, without an error.  Now an Error naming a pair of the near-duplicates.
TEST(Degenerate, NearDuplicatesInTiltedGrid) {
  Case c;
  c.box = tessera::Box::rect(0, 12, 0, 3);
  c.box.xy = -8.0542871754527194;
  c.model = tessera::Model(2);
  c.model.types[0] = {1, 2.3999999999999999, 0.10000000000000001};
  c.model.types[1] = {1.5, 2.6400000000000001, 0.15000000000000002};
  c.model.set_lambda(0, 0, -0.7745966692414834);
  c.model.set_lambda(0, 1, -0.92951600308978);
  c.model.set_lambda(1, 1, -1.0844353369380766);
  c.xy = {0, 0, -1.3423811959087866, 0.5, -2.6847623918175731, 1, -4.0271435877263597, 1.5,
          -5.3695247836351463, 2, -6.7119059795439329, 2.5, 6, 0, 4.6576188040912134, 0.5,
          3.3152376081824269, 1, 1.9728564122736403, 1.5, 0.63047521636485371, 2,
          -0.71190597954393287, 2.5, 4.6576188040912143, 0.49999999999999972, 4.657618804091217,
          0.49999999999999972, 6.0000000000000009, -1.1238308759431283e-16};
  c.type = {0, 0, 0, 0, 1, 1, 1, 1, 0, 0, 1, 1, 1, 1, 0};
  const std::string msg = error_of(c);
  ASSERT_FALSE(msg.empty()) << "no error for points 1e-15 apart";
  EXPECT_NE(msg.find("nearly coincide"), std::string::npos) << msg;
  const auto pts = named_points(msg);
  ASSERT_EQ(pts.size(), 2u) << msg;
  // The near-duplicate groups: {7, 12, 13} and {6, 14}.
  const std::set<std::set<int>> allowed = {{7, 12}, {7, 13}, {12, 13}, {6, 14}};
  EXPECT_TRUE(allowed.count({pts[0], pts[1]})) << msg;
}

// Four points in a 6000 x 5000 box, two of them 2.1e-6 apart (3.5e-10 of
// the box, above the separation limit): the mesh moved there by flips from
// a nearby configuration gave cell 2 an area of 4689763.777 where a rebuild
// gave 4689763.010.  Each path rounded the circumcentres of the triangles
// at the near pair (which amplify the images' rounding by the box over the
// pair's distance, about 3e9) from different corners, and a tie could
// leave the two with different triangles.  Now a triangle's corners are in
// one order however it was made and ties are broken by one rule, so the
// paths agree to round-off; and the areas tile the box to the tolerance the
// pair's conditioning allows (doc/model.md, "Limits of the input").
TEST(Degenerate, NearPairFlipsAgreeWithARebuild) {
  const tessera::Box box = tessera::Box::rect(0, 6000, 0, 5000);
  const std::vector<double> own = {4652.4518680999436, 1643.4423125614326, 2107.3553041936675,
                                   947.77082098780556, 4069.546937896801,  2159.2004208769245,
                                   4069.5469358690693, 2159.2004214445533};
  const int n = 4;
  const tessera::Tessellation t = tessera::tessellate_periodic(box, {own.data(), n, 2});
  double sum = 0.0;
  for (int c = 0; c < n; ++c) sum += t.area[c];
  const double dmin = std::hypot(own[4] - own[6], own[5] - own[7]);
  const double cond = 6000.0 / dmin;
  EXPECT_NEAR(sum, box.area(), (1e-12 + 4.0 * 2.220446049250313e-16 * cond) * box.area());
  // The periodic images, rigidly attached to their owners.
  const int m = t.n_points;
  std::vector<double> shift(2 * m);
  for (int p = 0; p < m; ++p) {
    shift[2 * p] = t.position[p].x - own[2 * t.origin[p]];
    shift[2 * p + 1] = t.position[p].y - own[2 * t.origin[p] + 1];
  }
  auto images = [&](const std::vector<double> &o) {
    std::vector<double> xy(2 * m);
    for (int p = 0; p < m; ++p) {
      xy[2 * p] = o[2 * t.origin[p]] + shift[2 * p];
      xy[2 * p + 1] = o[2 * t.origin[p] + 1] + shift[2 * p + 1];
    }
    return xy;
  };
  const std::vector<double> here = images(own);
  const tessera::Points pts{here.data(), m, 2};
  tessera::Mesh fresh;
  fresh.build(pts);
  tessera::Tessellation b;
  fresh.cells(pts, n, b);
  testutil::Rng rng(5020819);
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> near = own;
    const double step = std::pow(10.0, -3 - trial % 8);
    for (double &v : near) v += step * rng.uniform(-1.0, 1.0);
    const std::vector<double> there = images(near);
    tessera::Mesh inc;
    try {
      inc.build({there.data(), m, 2});
    } catch (const tessera::Error &) {
      continue;  // the nearby configuration broke the separation limit
    }
    tessera::Tessellation a;
    inc.cells({there.data(), m, 2}, n, a);
    const double lo[2] = {-1e5, -1e5}, hi[2] = {1e5, 1e5};
    if (!inc.advance(pts, n, lo, hi, a)) continue;  // a fold: a rebuild, nothing to compare
    ++compared;
    for (int c = 0; c < n; ++c) {
      ASSERT_NEAR(a.area[c], b.area[c], 1e-12 * b.area[c]) << "trial " << trial << " cell " << c;
      ASSERT_NEAR(a.perimeter[c], b.perimeter[c], 1e-12 * b.perimeter[c])
          << "trial " << trial << " cell " << c;
    }
  }
  EXPECT_GT(compared, 50);
}

// Just above the separation limit the results are finite and right (areas
// fill the box, forces are the finite differences of the energy); below it
// an Error names both points.
TEST(Degenerate, SeparationLimit) {
  testutil::Config cfg = testutil::random_config(30, 0.0, 0.0, 6.0, 5.0, 11, 0.4, false);
  Case c;
  c.box = cfg.box;
  c.model = testutil::to_model(testutil::random_params(3, false));
  c.xy = cfg.xy;
  c.type = cfg.type;
  const int n0 = c.n();
  // S, the largest coordinate the periodic tessellation sees, is at most
  // about 6 + its margin; 1e-8 is safely above 1e-10 S, 1e-12 below.
  for (double d : {1e-6, 1e-8, 1e-12}) {
    SCOPED_TRACE("distance " + std::to_string(d));
    Case k = c;
    k.xy.push_back(c.xy[6] + 0.6 * d);
    k.xy.push_back(c.xy[7] + 0.8 * d);
    k.type.push_back(1);
    if (d < 1e-10) {
      const std::string msg = error_of(k);
      EXPECT_NE(msg.find("nearly coincide"), std::string::npos) << msg;
      const auto pts = named_points(msg);
      ASSERT_EQ(pts.size(), 2u) << msg;
      EXPECT_EQ(std::min(pts[0], pts[1]), 3) << msg;
      EXPECT_EQ(std::max(pts[0], pts[1]), n0) << msg;
      continue;
    }
    std::vector<double> f;
    tessera::periodic_forces(k.box, k.points(), k.type.data(), k.model, f);
    const auto t = tessera::tessellate_periodic(k.box, k.points());
    const double asum = std::accumulate(t.area.begin(), t.area.end(), 0.0);
    EXPECT_NEAR(asum, 30.0, 1e-9);
    for (double a : t.area) EXPECT_GT(a, 0.0);
    // The pair's forces against central differences with a step well below
    // d.  The energy is only defined to about eps S / d of itself (the
    // rounded images, see doc/model.md), which limits the differences to
    // d >= 1e-6 here.
    if (d < 1e-7) continue;
    for (int p : {3, n0})
      for (int dim = 0; dim < 2; ++dim) {
        const double h = 1e-3 * d;
        std::vector<double> xp = k.xy, xm = k.xy;
        xp[2 * p + dim] += h;
        xm[2 * p + dim] -= h;
        const double fd = -(energy_at(k, xp) - energy_at(k, xm)) / (2 * h);
        ASSERT_TRUE(std::isfinite(f[2 * p + dim]));
        EXPECT_NEAR(f[2 * p + dim], fd, 2e-5 * std::abs(fd))
            << "point " << p << " component " << dim;
      }
  }
}

// One and two cells in a periodic box are a valid tiling (each cell meets
// its own images); so are cells on one line whose images across the box
// are beyond the first margin.
TEST(Degenerate, OneTwoAndARowOfCells) {
  const reftess::RefParams p = testutil::random_params(5, true);
  const tessera::Model m = testutil::to_model(p);
  for (int n : {1, 2, 3}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    testutil::Config cfg = testutil::random_config(n, 0.0, 0.0, 3.0, 2.0, 40 + n, 0.3, false);
    ASSERT_EQ(cfg.n(), n);
    const auto t = tessera::tessellate_periodic(cfg.box, cfg.points());
    const auto ref = reftess::voronoi(cfg.refbox(), cfg.xy);
    std::vector<double> f;
    const auto out = tessera::periodic_forces(cfg.box, cfg.points(), cfg.type.data(), m, f);
    EXPECT_NEAR(out.energy, reftess::total_energy(ref, cfg.type, p), 1e-12);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(t.area[i], ref[i].area, 1e-12);
      EXPECT_NEAR(t.perimeter[i], ref[i].perimeter, 1e-12);
    }
    if (n == 1) EXPECT_NEAR(std::hypot(f[0], f[1]), 0.0, 1e-12);
  }
  // A row of 4 cells along x in a box 40 high: the first margin (about
  // 2 sqrt(A / n) = 20) does not reach the images above and below.
  testutil::Config row;
  row.box = tessera::Box::rect(0, 4, 0, 40);
  for (int i = 0; i < 4; ++i) {
    row.xy.push_back(0.5 + i);
    row.xy.push_back(3.0);
  }
  row.type.assign(4, 0);
  const auto t = tessera::tessellate_periodic(row.box, row.points());
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(t.area[i], 40.0, 1e-12);
}

// Lengths beyond the range where squares and cubes stay in double's range
// are refused with a message that says to rescale; so is an energy that
// overflows.  Just inside the range, results are right.
TEST(Degenerate, LengthScales) {
  const testutil::Config base = testutil::random_config(20, 0.0, 0.0, 5.0, 4.0, 21, 0.4, false);
  const auto t1 = tessera::tessellate_periodic(base.box, base.points());
  for (double s : {1e-95, 1e-60, 1e60, 1e95, 1e-110, 1e110}) {
    SCOPED_TRACE("scale " + std::to_string(std::log10(s)));
    testutil::Config c = base;
    c.box = tessera::Box::rect(0, 5 * s, 0, 4 * s);
    for (double &v : c.xy) v *= s;
    std::string msg;
    try {
      const auto t = tessera::tessellate_periodic(c.box, c.points());
      for (int i = 0; i < c.n(); ++i)
        EXPECT_NEAR(t.area[i] / (s * s), t1.area[i], 1e-12) << "cell " << i;
    } catch (const tessera::Error &e) {
      msg = e.what();
    }
    if (s > 1e-100 && s < 1e100) {
      EXPECT_EQ(msg, "");
    } else {
      EXPECT_NE(msg.find("rescale"), std::string::npos) << msg;
      EXPECT_EQ(named_points(msg).size(), s < 1 ? 2u : 1u) << msg;
    }
  }
  // Energy overflow: moduli of order one at lengths of 1e90.
  Case c;
  c.box = tessera::Box::rect(0, 5e90, 0, 4e90);
  c.xy = base.xy;
  for (double &v : c.xy) v *= 1e90;
  c.type.assign(c.n(), 0);
  const std::string msg = error_of(c);
  EXPECT_NE(msg.find("not finite"), std::string::npos) << msg;
  EXPECT_NE(msg.find("rescale"), std::string::npos) << msg;
}

// The incremental mesh (Mesh::update, used every step by the pair style)
// does not follow points that came closer than the limit: it asks for a
// rebuild, and the rebuild names them.
TEST(Degenerate, MeshUpdateRefusesCollision) {
  testutil::Config cfg = testutil::random_config(40, 0.0, 0.0, 6.0, 6.0, 31, 0.4, false);
  std::vector<double> xy = testutil::with_images(cfg, 2.0);
  const int n = static_cast<int>(xy.size() / 2);
  tessera::Mesh mesh;
  mesh.build(tessera::Points{xy.data(), n, 2});
  // Move point 5 onto point 9 up to 1e-13 (S is below 10 here).
  xy[10] = xy[18] + 1e-13;
  xy[11] = xy[19];
  EXPECT_FALSE(mesh.update(tessera::Points{xy.data(), n, 2}));
  std::vector<long> ids(n);
  std::iota(ids.begin(), ids.end(), 100L);
  try {
    mesh.build(tessera::Points{xy.data(), n, 2}, ids.data());
    ADD_FAILURE() << "no error";
  } catch (const tessera::Error &e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("id 105 at ("), std::string::npos) << msg;
    EXPECT_NE(msg.find("id 109 at ("), std::string::npos) << msg;
  }
}
