// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Free-boundary loops (tessera/loops.h) against analytic shapes: an isolated
// disc, the union of two overlapping discs (two discs less their lens), four
// discs at the corners of a square around a hole (a square of the arcs'
// corners less four circular segments), and a periodic row of discs, whose
// two edges wrap around the box and enclose no area.

#include "tessera/loops.h"

#include "tessera/finite.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace tessera;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<FreeLoop> loops_of(const std::vector<double> &xy, double r, int *unmatched)
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
  return free_loops(arcs, MinimumImage(), 1e-9 * r, unmatched);
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
