// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Free-boundary loops (tessera/loops.h) against analytic shapes: an isolated
// disc, the union of two overlapping discs (two discs less their lens), four
// discs at the corners of a square around a hole (a square of the arcs'
// corners less four circular segments), and a periodic row of discs, whose
// two edges wrap around the box and enclose no area.  Which loop encloses a
// point (loop_winding, LoopLocator) against the discs themselves: summed
// over all loops the winding number is 1 on the union of the discs and 0
// off it, for random discs and points; the locator's innermost loop is the
// smallest of those a brute-force scan finds winding about the point, and
// it finds a hole across a periodic box's corner through the point's image.

#include "tessera/loops.h"

#include "tessera/finite.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace tessera;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<FreeLoop> loops_of(const std::vector<double> &xy, double r, int *unmatched,
                               std::vector<FreeArc> *arcs_out = nullptr)
{
  const int n = static_cast<int>(xy.size() / 2);
  Points pts{xy.data(), n, 2};
  FiniteTessellation ft = finite_tessellate(pts, n, r);
  Tessellation con;
  finite_contacts(ft, con);
  FiniteCells v;
  v.bind(ft, con, pts);
  std::vector<FreeArc> arcs;
  append_free_arcs(v, nullptr, nullptr, arcs);
  if (arcs_out) *arcs_out = arcs;
  return free_loops(arcs, MinimumImage(), 1e-9 * r, unmatched);
}

bool covered(const std::vector<double> &xy, double r, const double *p)
{
  for (size_t i = 0; i < xy.size(); i += 2)
    if (std::hypot(p[0] - xy[i], p[1] - xy[i + 1]) < r) return true;
  return false;
}

}  // namespace

TEST(FreeLoops, IsolatedDisc) {
  const double r = 0.7;
  int bad = -1;
  auto loops = loops_of({1.3, -0.4}, r, &bad);
  EXPECT_EQ(bad, 0);
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].kind, LoopKind::Outer);
  EXPECT_NEAR(loops[0].area, kPi * r * r, 1e-13);
  EXPECT_NEAR(loops[0].length, 2 * kPi * r, 1e-13);
  EXPECT_NEAR(loops[0].cx, 1.3, 1e-13);
  EXPECT_NEAR(loops[0].cy, -0.4, 1e-13);
  EXPECT_EQ(loops[0].n_cells, 1);
}

TEST(FreeLoops, TwoDiscsAreTheirUnion) {
  const double r = 0.8, d = 1.1;
  int bad = -1;
  auto loops = loops_of({0.2, 0.1, 0.2 + d, 0.1}, r, &bad);
  EXPECT_EQ(bad, 0);
  ASSERT_EQ(loops.size(), 1u);
  const double lens = 2 * r * r * std::acos(d / (2 * r)) - 0.5 * d * std::sqrt(4 * r * r - d * d);
  EXPECT_EQ(loops[0].kind, LoopKind::Outer);
  EXPECT_NEAR(loops[0].area, 2 * kPi * r * r - lens, 1e-12);
  EXPECT_NEAR(loops[0].length, 2 * r * (2 * kPi - 2 * std::acos(d / (2 * r))), 1e-12);
  EXPECT_NEAR(loops[0].cx, 0.2 + d / 2, 1e-12);
  EXPECT_NEAR(loops[0].cy, 0.1, 1e-12);
  EXPECT_EQ(loops[0].n_cells, 2);
}

TEST(FreeLoops, FourDiscsAroundAHole) {
  // Corners of a square of side d around (x0, y0), r < d / sqrt(2): the
  // hole's corners are on the square's midlines at distance q from the
  // centre, joined by arcs that bulge into the hole.
  const double r = 0.62, d = 1.0, x0 = 0.3, y0 = 0.7;
  int bad = -1;
  auto loops = loops_of({x0 - d / 2, y0 - d / 2, x0 + d / 2, y0 - d / 2, x0 + d / 2, y0 + d / 2,
                         x0 - d / 2, y0 + d / 2},
                        r, &bad);
  EXPECT_EQ(bad, 0);
  ASSERT_EQ(loops.size(), 2u);
  const FreeLoop &hole = loops[0].kind == LoopKind::Hole ? loops[0] : loops[1];
  const FreeLoop &outer = loops[0].kind == LoopKind::Hole ? loops[1] : loops[0];
  ASSERT_EQ(hole.kind, LoopKind::Hole);
  ASSERT_EQ(outer.kind, LoopKind::Outer);
  const double q = d / 2 - std::sqrt(r * r - d * d / 4);
  const double alpha = std::asin(q * std::sqrt(2.0) / (2 * r));    // half the arc angle
  const double segment = 0.5 * r * r * (2 * alpha - std::sin(2 * alpha));
  EXPECT_NEAR(hole.area, 2 * q * q - 4 * segment, 1e-12);
  EXPECT_NEAR(hole.length, 4 * r * 2 * alpha, 1e-12);
  EXPECT_NEAR(hole.cx, x0, 1e-12);
  EXPECT_NEAR(hole.cy, y0, 1e-12);
  EXPECT_EQ(hole.n_cells, 4);
  EXPECT_EQ(outer.n_cells, 4);
  // The outer loop encloses the cells and the hole: the union of the
  // discs' quarter sectors outside the square plus the square's corners.
  EXPECT_NEAR(outer.cx, x0, 1e-12);
  EXPECT_NEAR(outer.cy, y0, 1e-12);
}

TEST(FreeLoops, PeriodicRowWrapsAroundTheBox) {
  // n discs at spacing d < 2 r along x in a box of length n d: the top and
  // bottom edges close only after a box vector.
  const int n = 5;
  const double r = 0.6, d = 1.0, L = n * d;
  const double a = std::acos(d / (2 * r));
  std::vector<FreeArc> arcs;
  for (int k = 0; k < n; k++) {
    FreeArc top, bottom;
    top.cell = bottom.cell = k;
    top.cx = bottom.cx = k * d;
    top.r = bottom.r = r;
    top.phi = a;
    top.theta = kPi - 2 * a;
    top.next = (k + n - 1) % n;
    bottom.phi = kPi + a;
    bottom.theta = kPi - 2 * a;
    bottom.next = (k + 1) % n;
    arcs.push_back(top);
    arcs.push_back(bottom);
  }
  int bad = -1;
  auto image = [L](double *x) { x[0] -= L * std::round(x[0] / L); };
  auto loops = free_loops(arcs, image, 1e-9, &bad);
  EXPECT_EQ(bad, 0);
  ASSERT_EQ(loops.size(), 2u);
  for (const FreeLoop &l : loops) {
    EXPECT_EQ(l.kind, LoopKind::Wrapping);
    EXPECT_EQ(l.area, 0.0);
    EXPECT_EQ(l.n_cells, n);
    EXPECT_NEAR(l.length, n * r * (kPi - 2 * a), 1e-12);
  }
  // Without the periodic image the chain does not close.
  loops = free_loops(arcs, MinimumImage(), 1e-9, &bad);
  EXPECT_GT(bad, 0);
}

TEST(FreeLoops, ArcsOfEachLoopInWalkingOrder) {
  // Four discs around a hole: every arc on exactly one loop, each arc
  // starting where the one before it ends.
  const double r = 0.62;
  std::vector<FreeArc> arcs;
  int bad = -1;
  auto loops = loops_of({-0.5, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5, 0.5}, r, &bad, &arcs);
  ASSERT_EQ(loops.size(), 2u);
  std::vector<int> seen(arcs.size(), 0);
  for (const FreeLoop &l : loops) {
    ASSERT_EQ(static_cast<int>(l.arcs.size()), l.n_arcs);
    ASSERT_EQ(l.shift.size(), 2 * l.arcs.size());
    const auto u = unwrapped_arcs(arcs, l);
    for (size_t k = 0; k < u.size(); k++) {
      seen[l.arcs[k]]++;
      const FreeArc &a = u[k], &b = u[(k + 1) % u.size()];
      EXPECT_NEAR(a.cx + r * std::cos(a.phi + a.theta), b.cx + r * std::cos(b.phi), 1e-12);
      EXPECT_NEAR(a.cy + r * std::sin(a.phi + a.theta), b.cy + r * std::sin(b.phi), 1e-12);
    }
  }
  for (int c : seen) EXPECT_EQ(c, 1);
}

TEST(FreeLoops, WindingNumbersOfRandomDiscs) {
  // Whatever the colonies and holes, the loops together bound the union of
  // the discs: their winding numbers sum to 1 on it and to 0 off it, and
  // each is -1, 0 or +1.  The locator's innermost loop is the smallest (the
  // first on a tie) of those whose winding number is not 0.
  std::mt19937 gen(20260704);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int points_in_holes = 0, points_on_cells = 0, points_outside = 0;
  for (int trial = 0; trial < 60; trial++) {
    // sparse to dense: single discs, colonies, colonies with holes
    const int n = 5 + trial % 40;
    const double side = std::sqrt(n) * (0.8 + 0.3 * u(gen)), r = 0.5 + 0.2 * u(gen);
    std::vector<double> xy;
    for (int i = 0; i < n; i++) xy.insert(xy.end(), {side * u(gen), side * u(gen)});
    std::vector<FreeArc> arcs;
    int bad = -1;
    const auto loops = loops_of(xy, r, &bad, &arcs);
    ASSERT_EQ(bad, 0);
    LoopBox box;
    box.lo[0] = box.lo[1] = -r;
    box.len[0] = box.len[1] = side + 2 * r;
    LoopLocator where(box);
    std::vector<std::vector<FreeArc>> chains;
    for (const FreeLoop &l : loops) {
      chains.push_back(unwrapped_arcs(arcs, l));
      where.add(chains.back().data(), static_cast<int>(chains.back().size()), l.area,
                l.kind == LoopKind::Wrapping);
    }
    where.finish();
    // Points all over, and more around each hole: in the box of its arcs' ends.
    std::vector<double> query;
    for (int q = 0; q < 400; q++)
      query.insert(query.end(), {-r + (side + 2 * r) * u(gen), -r + (side + 2 * r) * u(gen)});
    for (size_t l = 0; l < loops.size(); l++) {
      if (loops[l].kind != LoopKind::Hole) continue;
      double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
      for (const FreeArc &a : chains[l])
        for (const double t : {a.phi, a.phi + a.theta}) {
          const double e[2] = {a.cx + a.r * std::cos(t), a.cy + a.r * std::sin(t)};
          for (int d = 0; d < 2; d++) {
            lo[d] = std::min(lo[d], e[d]);
            hi[d] = std::max(hi[d], e[d]);
          }
        }
      for (int q = 0; q < 20; q++)
        query.insert(query.end(), {lo[0] + (hi[0] - lo[0]) * u(gen), lo[1] + (hi[1] - lo[1]) * u(gen)});
    }
    for (size_t q = 0; q < query.size(); q += 2) {
      const double *p = &query[q];
      int sum = 0, brute = 0;
      for (size_t l = 0; l < loops.size(); l++) {
        const int w = loop_winding(chains[l].data(), static_cast<int>(chains[l].size()), p);
        ASSERT_LE(std::abs(w), 1);
        EXPECT_EQ(w, where.winding(static_cast<int>(l) + 1, p));
        if (w != 0) EXPECT_EQ(w, loops[l].kind == LoopKind::Outer ? 1 : -1);
        sum += w;
        if (w != 0 && (brute == 0 || loops[l].area < loops[brute - 1].area))
          brute = static_cast<int>(l) + 1;
      }
      const bool on = covered(xy, r, p);
      ASSERT_EQ(sum, on ? 1 : 0) << "trial " << trial << " point " << p[0] << " " << p[1];
      ASSERT_EQ(where.innermost(p), brute);
      if (on) {
        points_on_cells++;
        EXPECT_EQ(loops[brute - 1].kind, LoopKind::Outer);    // its colony
      } else if (brute) {
        points_in_holes++;
        EXPECT_EQ(loops[brute - 1].kind, LoopKind::Hole);
      } else {
        points_outside++;
      }
    }
  }
  // (the cases the test is about all occurred)
  EXPECT_GT(points_in_holes, 200);
  EXPECT_GT(points_on_cells, 5000);
  EXPECT_GT(points_outside, 5000);
}

TEST(FreeLoops, LocatorFindsAHoleAcrossAPeriodicCorner) {
  // Four discs around a hole at the corner of a periodic box, unwrapped
  // around (0, 0): a point just inside the box's far corner is in the hole
  // through its image.  Tilted: the image is p - a - b with b = (xy, L).
  const double r = 0.62, L = 5.0;
  std::vector<FreeArc> arcs;
  int bad = -1;
  const auto loops = loops_of({-0.5, -0.5, 0.5, -0.5, 0.5, 0.5, -0.5, 0.5}, r, &bad, &arcs);
  ASSERT_EQ(loops.size(), 2u);
  const int hole = loops[0].kind == LoopKind::Hole ? 1 : 2;
  for (const double xy : {0.0, 1.3, -2.1}) {
    LoopBox box;
    box.len[0] = box.len[1] = L;
    box.xy = xy;
    box.periodic[0] = box.periodic[1] = true;
    LoopLocator where(box);
    std::vector<std::vector<FreeArc>> chains;
    for (const FreeLoop &l : loops) {
      chains.push_back(unwrapped_arcs(arcs, l));
      where.add(chains.back().data(), static_cast<int>(chains.back().size()), l.area, false);
    }
    where.finish();
    for (const double dx : {-0.03, 0.04}) {
      const double p[2] = {dx + L + xy, -0.02 + L};
      EXPECT_EQ(where.innermost(p), hole) << "xy " << xy;
      const double q[2] = {dx + 2 * L + 2 * xy, 2 * L - 0.02};    // another image
      EXPECT_EQ(where.innermost(q), hole) << "xy " << xy;
    }
    // on a disc (the outer loop, here a colony of four cells), and off all of them
    const double on[2] = {L + xy - 0.5, L - 0.5 + 0.3};
    EXPECT_EQ(where.innermost(on), 3 - hole);
    const double off[2] = {0.5 * L + 0.5 * xy, 0.5 * L};
    EXPECT_EQ(where.innermost(off), 0);
  }
  // Not periodic: no image, no hole.
  LoopBox open;
  open.len[0] = open.len[1] = L;
  LoopLocator where(open);
  auto chain = unwrapped_arcs(arcs, loops[hole - 1]);
  where.add(chain.data(), static_cast<int>(chain.size()), loops[hole - 1].area, false);
  where.finish();
  const double p[2] = {L - 0.03, L - 0.02}, q[2] = {-0.03, -0.02};
  EXPECT_EQ(where.innermost(p), 0);
  EXPECT_EQ(where.innermost(q), 1);
}

TEST(FreeLoops, WrappingLoopsEncloseNothing) {
  const int n = 5;
  const double r = 0.6, d = 1.0, L = n * d;
  const double a = std::acos(d / (2 * r));
  std::vector<FreeArc> arcs;
  for (int k = 0; k < n; k++) {
    FreeArc top, bottom;
    top.cell = bottom.cell = k;
    top.cx = bottom.cx = k * d;
    top.r = bottom.r = r;
    top.phi = a;
    top.theta = kPi - 2 * a;
    top.next = (k + n - 1) % n;
    bottom.phi = kPi + a;
    bottom.theta = kPi - 2 * a;
    bottom.next = (k + 1) % n;
    arcs.push_back(top);
    arcs.push_back(bottom);
  }
  auto image = [L](double *x) { x[0] -= L * std::round(x[0] / L); };
  const auto loops = free_loops(arcs, image, 1e-9);
  LoopBox box;
  box.lo[1] = -5.0;
  box.len[0] = L;
  box.len[1] = 10.0;
  box.periodic[0] = true;
  LoopLocator where(box);
  for (const FreeLoop &l : loops) {
    auto chain = unwrapped_arcs(arcs, l);
    where.add(chain.data(), static_cast<int>(chain.size()), l.area, l.kind == LoopKind::Wrapping);
  }
  where.finish();
  for (const double y : {-2.0, -0.3, 0.0, 0.3, 2.0}) {
    const double p[2] = {1.7, y};
    EXPECT_EQ(where.innermost(p), 0);
  }
}
