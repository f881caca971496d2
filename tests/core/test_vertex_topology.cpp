// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The vertex model's topology: a T1 on a honeycomb, a T2 of a small
// triangle, division; the rule's choice among conflicting events (never two
// events on one cell, and the same decision on any patch that can decide);
// and a seeded fuzz of many T1s, T2s, divisions and vertex moves that keeps
// every cell valid and the tissue consistent.
#include "test_util.h"
#include "vertex_test_util.h"
#include "tessera/vertex_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <vector>

using tessera::EventStatus;
using tessera::TopologyEvent;
using tessera::TopologyParams;
using tessera::VertexTissue;

namespace {

double total_area(const VertexTissue &t) {
  double s = 0.0;
  for (int c = 0; c < t.n_cells(); ++c)
    if (!t.rings[c].empty())
      s += t.measures(c).area;
  return s;
}

// Moves the two ends of edge (a, b) towards its midpoint so that it has
// length l.
void shrink_edge(VertexTissue &t, int a, int b, double l) {
  const tessera::Vec2 d = t.delta(a, b);
  const double l0 = std::hypot(d.x, d.y);
  const double s = 0.5 * (l0 - l) / l0;
  t.pos[a].x += s * d.x;
  t.pos[a].y += s * d.y;
  t.pos[b].x -= s * d.x;
  t.pos[b].y -= s * d.y;
}

TEST(VertexTopology, T1OnAHoneycomb) {
  VertexTissue t = vtest::honeycomb(6, 4);
  const int X = 7, a0 = t.rings[X][0], b0 = t.rings[X][1];
  shrink_edge(t, a0, b0, 0.01);
  ASSERT_NO_THROW(tessera::check_tissue(t));
  const tessera::EdgeMap m(t);
  const TopologyParams p{0.05, 0.08, 0.0};
  const std::vector<TopologyEvent> ev = tessera::find_events(t, m, p);
  ASSERT_EQ(ev.size(), 1u);
  const TopologyEvent e = ev[0];
  EXPECT_EQ(e.kind, TopologyEvent::T1);
  EXPECT_NEAR(e.size, 0.01, 1e-12);
  EXPECT_TRUE(e.decidable);
  const int Y = e.cells[1], W = e.cells[2], Z = e.cells[3];
  std::map<int, size_t> before;
  for (int c : e.cells)
    before[c] = t.rings[c].size();
  ASSERT_EQ(tessera::decide_events(t, m, ev)[0], EventStatus::Carry);
  const double area = total_area(t);
  const tessera::Vec2 old_d = t.delta(e.a, e.b);
  const tessera::Vec2 mid{t.pos[e.a].x + 0.5 * old_d.x, t.pos[e.a].y + 0.5 * old_d.y};
  ASSERT_TRUE(tessera::apply_event(t, e, p));
  EXPECT_NO_THROW(tessera::check_tissue(t));
  EXPECT_EQ(t.rings[e.cells[0]].size(), before[e.cells[0]] - 1);
  EXPECT_EQ(t.rings[Y].size(), before[Y] - 1);
  EXPECT_EQ(t.rings[W].size(), before[W] + 1);
  EXPECT_EQ(t.rings[Z].size(), before[Z] + 1);
  // The new edge: length l_new, perpendicular to the old one, centred on its
  // midpoint, shared by W and Z (W holds b -> a).
  const tessera::Vec2 d = t.delta(e.a, e.b);
  EXPECT_NEAR(std::hypot(d.x, d.y), 0.08, 1e-12);
  EXPECT_NEAR(d.x * old_d.x + d.y * old_d.y, 0.0, 1e-12);
  const tessera::Vec2 c =
      t.image(t.pos[e.a].x + 0.5 * d.x - mid.x, t.pos[e.a].y + 0.5 * d.y - mid.y);
  EXPECT_NEAR(c.x, 0.0, 1e-12);
  EXPECT_NEAR(c.y, 0.0, 1e-12);
  const tessera::EdgeMap m2(t);
  EXPECT_EQ(m2.cell(e.b, e.a), W);
  EXPECT_EQ(m2.cell(e.a, e.b), Z);
  EXPECT_NEAR(total_area(t), area, 1e-12 * area);
}

// A T1 whose new edge would not fit (cells too thin) is refused and
// changes nothing.
TEST(VertexTopology, T1RefusedWhenTheResultIsInvalid) {
  VertexTissue t = vtest::honeycomb(12, 12);
  const int X = 7, a0 = t.rings[X][0], b0 = t.rings[X][1];
  shrink_edge(t, a0, b0, 0.01);
  const tessera::EdgeMap m(t);
  // A new edge too long to fit: its ends would lie outside the four cells.
  const TopologyParams p{0.05, 5.0, 0.0};
  const std::vector<TopologyEvent> ev = tessera::find_events(t, m, p);
  ASSERT_EQ(ev.size(), 1u);
  const VertexTissue before = t;
  EXPECT_FALSE(tessera::apply_event(t, ev[0], p));
  EXPECT_EQ(t.rings, before.rings);
  for (int v = 0; v < t.n_vertices(); ++v) {
    EXPECT_EQ(t.pos[v].x, before.pos[v].x);
    EXPECT_EQ(t.pos[v].y, before.pos[v].y);
  }
}

// The first three-sided cell of a random tissue, or -1.
int find_triangle(const VertexTissue &t) {
  for (int c = 0; c < t.n_cells(); ++c)
    if (t.rings[c].size() == 3)
      return c;
  return -1;
}

// Scales cell c's vertices towards its centroid by factor s.
void shrink_cell(VertexTissue &t, int c, double s) {
  const tessera::Vec2 cm = t.measures(c).centroid;
  for (int v : t.rings[c]) {
    const tessera::Vec2 d = t.image(t.pos[v].x - cm.x, t.pos[v].y - cm.y);
    t.pos[v].x = cm.x + s * d.x;
    t.pos[v].y = cm.y + s * d.y;
  }
}

TEST(VertexTopology, T2RemovesASmallTriangle) {
  VertexTissue t;
  int T = -1;
  for (uint64_t seed = 1; seed < 200 && T < 0; ++seed) {
    t = vtest::random_tissue(seed, 40, 6.0);
    T = find_triangle(t);
  }
  ASSERT_GE(T, 0);
  shrink_cell(t, T, 0.3);
  ASSERT_NO_THROW(tessera::check_tissue(t));
  const double area = total_area(t);
  const double tri_area = t.measures(T).area;
  const tessera::EdgeMap m(t);
  const TopologyParams p{0.0, 0.0, 1.1 * tri_area};
  std::vector<TopologyEvent> ev = tessera::find_events(t, m, p);
  ev.erase(
      std::remove_if(ev.begin(), ev.end(), [&](const TopologyEvent &e) { return e.cells[0] != T; }),
      ev.end());
  ASSERT_EQ(ev.size(), 1u);
  const std::vector<int> tri = t.rings[T];
  size_t sides[3];
  for (int k = 0; k < 3; ++k)
    sides[k] = t.rings[ev[0].cells[k + 1]].size();
  ASSERT_TRUE(tessera::apply_event(t, ev[0], p));
  EXPECT_TRUE(t.rings[T].empty());
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(t.rings[ev[0].cells[k + 1]].size(), sides[k] - 1);
  int removed = 0;
  for (int v : tri)
    removed += t.removed(v);
  EXPECT_EQ(removed, 2);
  EXPECT_NO_THROW(tessera::check_tissue(t));
  EXPECT_NEAR(total_area(t), area, 1e-12 * area);
}

TEST(VertexTopology, DivisionAlongAnAxis) {
  VertexTissue t = vtest::honeycomb(6, 4);
  const double area = total_area(t);
  const int c = 9;
  const tessera::Vec2 cm = t.measures(c).centroid;
  const int d = tessera::divide_cell(t, c, tessera::Vec2{1.0, 0.2});
  ASSERT_GE(d, 0);
  EXPECT_NO_THROW(tessera::check_tissue(t));
  EXPECT_EQ(t.n_vertices(), 2 * t.n_cells());
  EXPECT_NEAR(total_area(t), area, 1e-12 * area);
  // The daughter lies on the side +axis, the mother on the side -axis.
  const tessera::Vec2 dm = t.measures(d).centroid, mm = t.measures(c).centroid;
  EXPECT_GT(t.image(dm.x - cm.x, dm.y - cm.y).x, 0.0);
  EXPECT_LT(t.image(mm.x - cm.x, mm.y - cm.y).x, 0.0);
  // A symmetric cut of a regular hexagon along x: equal halves.
  VertexTissue h = vtest::honeycomb(6, 4);
  const int d2 = tessera::divide_cell(h, 9, tessera::Vec2{0.0, 1.0});
  ASSERT_GE(d2, 0);
  EXPECT_NEAR(h.measures(9).area, h.measures(d2).area, 1e-12);
}

// find_events looks only at the cells a cheap test leaves; every_cell (the
// oracle) looks at all.  The same events in the same order, on fuzzed
// tissues (short edges, sharp corners from moved vertices, small cells),
// with and without T2s, whole and as patches with unknown vertices.
void expect_same_events(const VertexTissue &t, const TopologyParams &p, int *found) {
  const tessera::EdgeMap m(t);
  const std::vector<TopologyEvent> fast = tessera::find_events(t, m, p);
  const std::vector<TopologyEvent> all = tessera::find_events(t, m, p, true);
  ASSERT_EQ(fast.size(), all.size());
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(fast[i].kind, all[i].kind);
    EXPECT_EQ(fast[i].size, all[i].size);
    EXPECT_EQ(fast[i].id0, all[i].id0);
    EXPECT_EQ(fast[i].id1, all[i].id1);
    EXPECT_EQ(fast[i].a, all[i].a);
    EXPECT_EQ(fast[i].b, all[i].b);
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(fast[i].cells[k], all[i].cells[k]);
    EXPECT_EQ(fast[i].decidable, all[i].decidable);
  }
  *found += static_cast<int>(all.size());
}

TEST(VertexTopology, CandidatesOfTheCheapTestAreThoseOfEveryCell) {
  testutil::Rng rng(77);
  int found = 0;
  for (int trial = 0; trial < 30; ++trial) {
    VertexTissue t = vtest::random_tissue(300 + trial, 40, 6.5, 1, trial % 3 ? 0.0 : 0.9);
    for (int s = 0; s < 30; ++s) {
      const int c = rng.below(t.n_cells());
      VertexTissue u = t;
      if (s % 3 == 0) { // a vertex moved: sharp corners
        const int v = u.rings[c][rng.below(static_cast<int>(u.rings[c].size()))];
        u.pos[v].x += rng.uniform(-0.3, 0.3);
        u.pos[v].y += rng.uniform(-0.3, 0.3);
      } else { // a short edge
        const int k = rng.below(static_cast<int>(t.rings[c].size()));
        shrink_edge(u, t.rings[c][k], t.rings[c][(k + 1) % t.rings[c].size()],
                    rng.uniform(0.0, 0.1));
      }
      try {
        tessera::check_tissue(u);
        t = u;
      } catch (const tessera::Error &) {
      }
    }
    for (const TopologyParams &p :
         {TopologyParams{0.05, 0.08, 0.0}, TopologyParams{0.12, 0.15, 0.0},
          TopologyParams{0.05, 0.08, 0.6}, TopologyParams{0.0, 0.0, 0.6}}) {
      expect_same_events(t, p, &found);
      VertexTissue patch = t;
      patch.vertex_known.assign(t.n_vertices(), 1);
      for (int v = 0; v < t.n_vertices(); ++v)
        if (rng.uniform() < 0.1)
          patch.vertex_known[v] = 0;
      expect_same_events(patch, p, &found);
    }
  }
  EXPECT_GT(found, 200); // (the fuzz makes candidates)
}

// Conflicting candidates: several short edges in one neighbourhood.  The
// events carried out never share a cell, the smallest is always carried
// out, and a patch (some cells unknown) decides every event it can decide
// exactly as the whole tissue does.
TEST(VertexTopology, RuleIsLocalAndConsistent) {
  testutil::Rng rng(21);
  for (int trial = 0; trial < 20; ++trial) {
    VertexTissue t = vtest::random_tissue(100 + trial, 50, 7.0);
    // Shrink a dozen random edges.
    for (int s = 0; s < 12; ++s) {
      const int c = rng.below(t.n_cells());
      const int k = rng.below(static_cast<int>(t.rings[c].size()));
      const int a = t.rings[c][k], b = t.rings[c][(k + 1) % t.rings[c].size()];
      VertexTissue u = t;
      shrink_edge(u, a, b, rng.uniform(0.0, 0.04));
      try {
        tessera::check_tissue(u);
        t = u;
      } catch (const tessera::Error &) {
      }
    }
    const TopologyParams p{0.05, 0.08, 0.0};
    const tessera::EdgeMap m(t);
    const std::vector<TopologyEvent> ev = tessera::find_events(t, m, p);
    const std::vector<EventStatus> st = tessera::decide_events(t, m, ev);
    std::set<int> used;
    int carried = 0, smallest = -1;
    for (size_t i = 0; i < ev.size(); ++i) {
      EXPECT_TRUE(ev[i].decidable);
      if (smallest < 0 || ev[i].before(ev[smallest]))
        smallest = static_cast<int>(i);
      if (st[i] != EventStatus::Carry)
        continue;
      ++carried;
      for (int c : ev[i].cells)
        EXPECT_TRUE(used.insert(c).second) << "cell in two events";
    }
    if (!ev.empty()) {
      EXPECT_GT(carried, 0);
      EXPECT_EQ(st[smallest], EventStatus::Carry);
    }
    // Patches: the cells within a radius of a random point.
    std::map<std::tuple<int, long, long>, EventStatus> whole;
    for (size_t i = 0; i < ev.size(); ++i)
      whole[{ev[i].kind, ev[i].id0, ev[i].id1}] = st[i];
    for (int q = 0; q < 5; ++q) {
      VertexTissue patch = t;
      const double cx = rng.uniform(0, 7), cy = rng.uniform(0, 7), R = rng.uniform(1.0, 3.5);
      patch.vertex_known.assign(t.n_vertices(), 0);
      for (int c = 0; c < t.n_cells(); ++c) {
        const tessera::Vec2 cm = t.measures(c).centroid;
        const tessera::Vec2 d = t.image(cm.x - cx, cm.y - cy);
        if (d.x * d.x + d.y * d.y > R * R) {
          patch.rings[c].clear();
        } else {
          for (int v : t.rings[c])
            patch.vertex_known[v] = 1;
        }
      }
      // A vertex seen only through a ring may still be unknown.
      for (int v = 0; v < t.n_vertices(); ++v)
        if (patch.vertex_known[v] && rng.uniform() < 0.05)
          patch.vertex_known[v] = 0;
      const tessera::EdgeMap pm(patch);
      const std::vector<TopologyEvent> pev = tessera::find_events(patch, pm, p);
      const std::vector<EventStatus> pst = tessera::decide_events(patch, pm, pev);
      for (size_t i = 0; i < pev.size(); ++i) {
        if (!pev[i].decidable)
          continue;
        const auto it = whole.find({pev[i].kind, pev[i].id0, pev[i].id1});
        ASSERT_NE(it, whole.end());
        EXPECT_EQ(pst[i], it->second) << "trial " << trial << " patch " << q;
      }
    }
  }
}

// Many random operations, each followed by the full check: vertex moves (kept
// only if the cells stay valid), short edges resolved by T1s, small
// triangles removed by T2s, divisions along random axes.
TEST(VertexTopology, FuzzKeepsEveryCellValid) {
  int t1 = 0, t2 = 0, div = 0, refused = 0;
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    testutil::Rng rng(1000 + seed);
    VertexTissue t = vtest::random_tissue(seed, 30, 5.5, 1, seed % 2 ? 0.0 : 1.3);
    ASSERT_NO_THROW(tessera::check_tissue(t));
    const double box_area = t.box.area();
    for (int step = 0; step < 150; ++step) {
      const int op = rng.below(10);
      const int c = rng.below(t.n_cells());
      if (t.rings[c].empty())
        continue;
      if (op < 3) { // random moves of one cell's vertices
        VertexTissue u = t;
        for (int v : u.rings[c]) {
          u.pos[v].x += rng.uniform(-0.15, 0.15);
          u.pos[v].y += rng.uniform(-0.15, 0.15);
        }
        try {
          tessera::check_tissue(u);
          t = u;
        } catch (const tessera::Error &) {
        }
      } else if (op < 7) { // shrink an edge, then a T1 step
        const int k = rng.below(static_cast<int>(t.rings[c].size()));
        const int a = t.rings[c][k], b = t.rings[c][(k + 1) % t.rings[c].size()];
        VertexTissue u = t;
        shrink_edge(u, a, b, rng.uniform(0.0, 0.03));
        try {
          tessera::check_tissue(u);
        } catch (const tessera::Error &) {
          continue;
        }
        int no = 0;
        t1 += tessera::topology_step(u, TopologyParams{0.05, 0.1, 0.0}, &no);
        refused += no;
        t = u;
      } else if (op < 8) { // shrink a triangle, then a T2 step
        const int tri = find_triangle(t);
        if (tri < 0)
          continue;
        VertexTissue u = t;
        shrink_cell(u, tri, 0.2);
        try {
          tessera::check_tissue(u);
        } catch (const tessera::Error &) {
          continue;
        }
        int no = 0;
        t2 += tessera::topology_step(u, TopologyParams{0.0, 0.0, 0.05}, &no);
        refused += no;
        t = u;
      } else { // divide
        const double phi = rng.uniform(0, 2 * std::acos(-1.0));
        if (tessera::divide_cell(t, c, tessera::Vec2{std::cos(phi), std::sin(phi)}) >= 0)
          ++div;
      }
      ASSERT_NO_THROW(tessera::check_tissue(t)) << "seed " << seed << " step " << step;
      ASSERT_NEAR(total_area(t), box_area, 1e-9 * box_area);
    }
  }
  EXPECT_GT(t1, 50);
  EXPECT_GT(t2, 2);
  EXPECT_GT(div, 50);
  RecordProperty("t1", t1);
  RecordProperty("t2", t2);
  RecordProperty("divisions", div);
  RecordProperty("refused", refused);
}

} // namespace
