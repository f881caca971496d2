// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The vertex model's polygons and tissues: measures against closed forms,
// forces against central differences of the energy (every energy term,
// heterotypic tensions, per-cell values, tilted boxes), the virial against
// a finite deformation of the box, zero force on regular hexagons, the
// validity test on bad polygons and the tissue check on broken tissues.
#include "test_util.h"
#include "vertex_test_util.h"
#include "tessera/vertex_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

using tessera::Model;
using tessera::PolygonDefect;
using tessera::VertexTissue;

namespace {

TEST(VertexPolygon, RegularHexagonAndRectangle) {
  const double s = 0.7, pi = std::acos(-1.0);
  std::vector<double> xy;
  for (int k = 0; k < 6; ++k) {
    xy.push_back(3.0 + s * std::cos(pi / 3 * k));
    xy.push_back(-2.0 + s * std::sin(pi / 3 * k));
  }
  const tessera::PolygonMeasures m = tessera::polygon_measures(xy.data(), 6);
  EXPECT_NEAR(m.area, 1.5 * std::sqrt(3.0) * s * s, 1e-14);
  EXPECT_NEAR(m.perimeter, 6 * s, 1e-14);
  EXPECT_NEAR(m.centroid.x, 3.0, 1e-14);
  EXPECT_NEAR(m.centroid.y, -2.0, 1e-14);
  // q = P / sqrt(A) of a regular hexagon
  EXPECT_NEAR(m.perimeter / std::sqrt(m.area), std::sqrt(8 * std::sqrt(3.0)), 1e-13);
  const double rect[] = {0, 0, 2, 0, 2, 1, 0, 1};
  const tessera::PolygonMeasures r = tessera::polygon_measures(rect, 4);
  EXPECT_DOUBLE_EQ(r.area, 2.0);
  EXPECT_DOUBLE_EQ(r.perimeter, 6.0);
  EXPECT_DOUBLE_EQ(r.centroid.x, 1.0);
  EXPECT_DOUBLE_EQ(r.centroid.y, 0.5);
  const double cw[] = {0, 0, 0, 1, 2, 1, 2, 0};
  EXPECT_DOUBLE_EQ(tessera::polygon_measures(cw, 4).area, -2.0);
}

// A model of two types with every term: different K, A0, Gamma, homotypic and
// heterotypic tensions of both signs.
Model two_type_model() {
  Model m(2);
  m.types[0] = tessera::CellType{1.3, 1.1, 0.4};
  m.types[1] = tessera::CellType{0.8, 0.9, 0.25};
  m.set_lambda(0, 0, -1.6);
  m.set_lambda(1, 1, -0.9);
  m.set_lambda(0, 1, 0.35);
  return m;
}

// Polygon energy's gradient against central differences, for random
// polygons (star-shaped around a centre) with neighbour types.
TEST(VertexPolygon, GradientIsCentralDifference) {
  testutil::Rng rng(11);
  const Model m = two_type_model();
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 3 + rng.below(8);
    std::vector<double> xy;
    const double pi = std::acos(-1.0);
    for (int k = 0; k < n; ++k) {
      const double phi = 2 * pi * (k + rng.uniform(0.1, 0.9)) / n, r = rng.uniform(0.4, 0.9);
      xy.push_back(5.0 + r * std::cos(phi));
      xy.push_back(7.0 + r * std::sin(phi));
    }
    std::vector<int> nt(n);
    for (int &t : nt)
      t = rng.below(2);
    const int tc = rng.below(2);
    std::vector<double> g(2 * n);
    tessera::PolygonMeasures pm;
    tessera::polygon_energy(xy.data(), n, m, 0, tc, nt.data(), g.data(), &pm);
    // The measures made in the same pass are polygon_measures'.
    const tessera::PolygonMeasures want = tessera::polygon_measures(xy.data(), n);
    EXPECT_EQ(pm.area, want.area);
    EXPECT_NEAR(pm.perimeter, want.perimeter, 1e-13 * want.perimeter);
    EXPECT_EQ(pm.centroid.x, want.centroid.x);
    EXPECT_EQ(pm.centroid.y, want.centroid.y);
    const double h = 1e-6;
    for (int k = 0; k < 2 * n; ++k) {
      std::vector<double> p = xy, q = xy;
      p[k] += h;
      q[k] -= h;
      const double fd = (tessera::polygon_energy(p.data(), n, m, 0, tc, nt.data(), nullptr) -
                         tessera::polygon_energy(q.data(), n, m, 0, tc, nt.data(), nullptr)) /
                        (2 * h);
      EXPECT_NEAR(g[k], fd, 1e-7 * (1.0 + std::fabs(fd))) << "trial " << trial << " k " << k;
    }
  }
}

// The energy of a polygon written out: K/2 (A - A0)^2 + Gamma/2 P^2 + w
// sum Lambda l, with w = 1/2 (each junction once between two cells).
TEST(VertexPolygon, EnergyIsTheWrittenFormula) {
  const Model m = two_type_model();
  const double xy[] = {0, 0, 1.2, 0.1, 1.0, 0.9, 0.1, 1.1};
  const int nt[] = {1, 0, 1, 1};
  const tessera::PolygonMeasures pm = tessera::polygon_measures(xy, 4);
  double lam = 0.0;
  for (int k = 0; k < 4; ++k) {
    const int k1 = (k + 1) % 4;
    lam +=
        m.lambda_of(0, nt[k]) * std::hypot(xy[2 * k1] - xy[2 * k], xy[2 * k1 + 1] - xy[2 * k + 1]);
  }
  const double want = 0.5 * 1.3 * (pm.area - 1.1) * (pm.area - 1.1) +
                      0.5 * 0.4 * pm.perimeter * pm.perimeter + 0.5 * lam;
  EXPECT_NEAR(tessera::polygon_energy(xy, 4, m, 0, 0, nt, nullptr), want, 1e-14);
}

// Forces on a disordered vertex tissue against central differences of the
// tissue's energy, for the types-only model and with every per-cell value.
void check_tissue_forces(VertexTissue t, Model m, uint64_t seed) {
  testutil::Rng rng(seed);
  // Disorder the vertices, halving the disorder until every cell is valid
  // (random Voronoi polygons have short edges).
  std::vector<double> kick(2 * t.n_vertices());
  for (double &k : kick)
    k = rng.uniform(-0.06, 0.06);
  const std::vector<tessera::Vec2> start = t.pos;
  for (int tries = 0; tries < 20; ++tries) {
    for (int v = 0; v < t.n_vertices(); ++v) {
      t.pos[v].x = start[v].x + kick[2 * v];
      t.pos[v].y = start[v].y + kick[2 * v + 1];
    }
    try {
      tessera::check_tissue(t);
      break;
    } catch (const tessera::Error &) {
      for (double &k : kick)
        k *= 0.5;
    }
  }
  ASSERT_NO_THROW(tessera::check_tissue(t));
  std::vector<double> f;
  double w[4];
  const double e = tessera::tissue_forces(t, m, f, w);
  EXPECT_NEAR(e, tessera::tissue_energy(t, m), 1e-12 * std::fabs(e));
  double fx = 0.0, fy = 0.0, scale = 0.0;
  for (int v = 0; v < t.n_vertices(); ++v) {
    fx += f[2 * v];
    fy += f[2 * v + 1];
    scale = std::max(scale, std::fabs(f[2 * v]) + std::fabs(f[2 * v + 1]));
  }
  ASSERT_GT(scale, 1e-3);
  EXPECT_NEAR(fx, 0.0, 1e-11 * scale * t.n_vertices());
  EXPECT_NEAR(fy, 0.0, 1e-11 * scale * t.n_vertices());
  const double h = 1e-6;
  double worst = 0.0;
  for (int v = 0; v < t.n_vertices(); ++v)
    for (int d = 0; d < 2; ++d) {
      VertexTissue p = t, q = t;
      (d ? p.pos[v].y : p.pos[v].x) += h;
      (d ? q.pos[v].y : q.pos[v].x) -= h;
      const double fd = -(tessera::tissue_energy(p, m) - tessera::tissue_energy(q, m)) / (2 * h);
      worst = std::max(worst, std::fabs(fd - f[2 * v + d]));
    }
  EXPECT_LT(worst, 1e-7 * scale);
  // Virial: dE/d(strain_ab) = -W_ab, by deforming box and vertices.
  const double eps = 1e-6;
  struct Strain {
    double f11, f12, f22;
    int component; // 0: xx, 1: yy, 2: xy
  };
  for (const Strain &s :
       {Strain{1 + eps, 0, 1, 0}, Strain{1, 0, 1 + eps, 1}, Strain{1, eps, 1, 2}}) {
    VertexTissue p = t, q = t;
    vtest::deform(p, s.f11, s.f12, s.f22);
    vtest::deform(q, 2 - s.f11, -s.f12, 2 - s.f22);
    const double dE = (tessera::tissue_energy(p, m) - tessera::tissue_energy(q, m)) / (2 * eps);
    EXPECT_NEAR(dE, -w[s.component], 1e-6 * (1.0 + std::fabs(dE))) << "strain " << s.component;
  }
}

TEST(VertexTissue, ForcesAreCentralDifferencesTypes) {
  VertexTissue t = vtest::random_tissue(3, 30, 5.5, 2);
  check_tissue_forces(t, two_type_model(), 4);
}

TEST(VertexTissue, ForcesAreCentralDifferencesTilted) {
  VertexTissue t = vtest::random_tissue(5, 30, 5.5, 2, 1.7);
  check_tissue_forces(t, two_type_model(), 6);
}

TEST(VertexTissue, ForcesAreCentralDifferencesPerCell) {
  VertexTissue t = vtest::random_tissue(7, 30, 5.5, 2);
  Model m = two_type_model();
  testutil::Rng rng(8);
  std::vector<double> a0(t.n_cells()), ka(t.n_cells()), kp(t.n_cells()), p0(t.n_cells());
  for (int c = 0; c < t.n_cells(); ++c) {
    a0[c] = rng.uniform(0.7, 1.3);
    ka[c] = rng.uniform(0.5, 1.5);
    kp[c] = rng.uniform(0.05, 0.5);
    p0[c] = rng.uniform(3.4, 4.2);
  }
  m.cell_area0 = a0.data();
  m.cell_KA = ka.data();
  m.cell_KP = kp.data();
  m.cell_P0 = p0.data();
  check_tissue_forces(t, m, 9);
  // Each cell's energy is then KA (A - A0)^2 + KP (P - P0)^2 less KP P0^2,
  // plus the heterotypic junctions' excess over the same-type tension.
  std::vector<double> ce;
  tessera::tissue_energy(t, m, &ce);
  const tessera::EdgeMap em(t);
  for (int c = 0; c < t.n_cells(); ++c) {
    const tessera::PolygonMeasures pm = t.measures(c);
    std::vector<double> xy;
    t.polygon(c, xy);
    double excess = 0.0;
    const int n = static_cast<int>(t.rings[c].size());
    for (int k = 0; k < n; ++k) {
      const int o = tessera::twin_cell(t, em, c, k);
      const int k1 = (k + 1) % n;
      const double l = std::hypot(xy[2 * k1] - xy[2 * k], xy[2 * k1 + 1] - xy[2 * k + 1]);
      excess += 0.5 * (m.lambda_of(t.type[c], t.type[o]) - m.lambda_of(t.type[c], t.type[c])) * l;
    }
    const double want = ka[c] * (pm.area - a0[c]) * (pm.area - a0[c]) +
                        kp[c] * (pm.perimeter - p0[c]) * (pm.perimeter - p0[c]) -
                        kp[c] * p0[c] * p0[c] + excess;
    EXPECT_NEAR(ce[c], want, 1e-12 * (1.0 + std::fabs(want))) << "cell " << c;
  }
}

// Regular hexagons: zero force whatever the parameters (every vertex sees
// three equal cells), and the areas add up to the box.
TEST(VertexTissue, RegularHexagonsHaveZeroForce) {
  for (double A : {0.8, 1.0, 1.3}) {
    const VertexTissue t = vtest::honeycomb(6, 4, A);
    ASSERT_EQ(t.n_vertices(), 2 * t.n_cells());
    ASSERT_NO_THROW(tessera::check_tissue(t));
    for (int c = 0; c < t.n_cells(); ++c) {
      ASSERT_EQ(t.rings[c].size(), 6u);
      EXPECT_NEAR(t.measures(c).area, A, 1e-12);
      EXPECT_NEAR(t.measures(c).perimeter, std::sqrt(8 * std::sqrt(3.0) * A), 1e-12);
    }
    for (double p0 : {3.5, 3.7224, 4.0}) {
      std::vector<double> f;
      tessera::tissue_forces(t, vtest::quadratic_model(1.0, 1.0, 0.5, p0), f);
      for (double v : f)
        EXPECT_NEAR(v, 0.0, 1e-12);
    }
  }
}

TEST(VertexPolygon, Defects) {
  const double ok[] = {0, 0, 1, 0, 0, 1};
  EXPECT_EQ(tessera::polygon_defect(ok, 3), PolygonDefect::None);
  const double cw[] = {0, 0, 0, 1, 1, 0};
  EXPECT_EQ(tessera::polygon_defect(cw, 3), PolygonDefect::NotPositive);
  EXPECT_EQ(tessera::polygon_defect(ok, 2), PolygonDefect::TooFewSides);
  // A bow tie with a positive net area: its edges cross.
  const double bow[] = {0, 0, 2, 0, 2, 1, 1.5, -0.3, 0, 1};
  EXPECT_GT(tessera::polygon_measures(bow, 5).area, 0.0);
  EXPECT_EQ(tessera::polygon_defect(bow, 5), PolygonDefect::SelfIntersecting);
  const long ids[] = {4, 7, 4};
  EXPECT_EQ(tessera::polygon_defect(ok, 3, ids), PolygonDefect::RepeatedVertex);
  const double nan[] = {0, 0, 1, 0, std::nan(""), 1};
  EXPECT_EQ(tessera::polygon_defect(nan, 3), PolygonDefect::NotFinite);
  // A spike: an edge folds back onto the one before it.
  const double spike[] = {0, 0, 2, 0, 2, 1, 2, 2.5, 2, 1.5, 0, 1};
  EXPECT_EQ(tessera::polygon_defect(spike, 6), PolygonDefect::SelfIntersecting);
  // Two corners at one point (a zero-length edge) are allowed.
  const double zero[] = {0, 0, 1, 0, 1, 0, 1, 1, 0, 1};
  EXPECT_EQ(tessera::polygon_defect(zero, 5), PolygonDefect::None);
  // A corner inside a non-adjacent edge (touching): not allowed.
  const double touch[] = {0, 0, 2, 0, 2, 2, 1, 0, 0, 2};
  EXPECT_NE(tessera::polygon_defect(touch, 5), PolygonDefect::None);
}

// The fast answer (convex polygons skip the pairwise test) against the
// pairwise test itself on fuzzed polygons: star-shaped ones (convex and not),
// jittered regular ones, random corners (mostly crossing), clockwise ones,
// stars that wind twice, ones with coinciding corners, with a non-finite or
// huge coordinate, and with a repeated vertex ID.
TEST(VertexPolygon, FastDefectAgreesWithPairwise) {
  testutil::Rng rng(2026);
  const double pi = std::acos(-1.0);
  int convex = 0, bad = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int n = 3 + rng.below(10), kind = rng.below(8);
    std::vector<double> xy(2 * n);
    for (int k = 0; k < n; ++k) {
      double phi = 2 * pi * (k + rng.uniform(0.0, 1.0)) / n, r = rng.uniform(0.2, 1.0);
      if (kind == 1 || kind >= 6) { // nearly regular: mostly convex
        phi = 2 * pi * (k + rng.uniform(-0.2, 0.2)) / n;
        r = 1.0 + rng.uniform(-0.1, 0.1);
      } else if (kind == 4) { // winding twice
        phi = 4 * pi * (k + rng.uniform(0.0, 0.3)) / n;
        r = 1.0;
      }
      xy[2 * k] = r * std::cos(phi) + 3.0;
      xy[2 * k + 1] = r * std::sin(phi) - 2.0;
      if (kind == 2) { // random corners
        xy[2 * k] = rng.uniform(-1.0, 1.0);
        xy[2 * k + 1] = rng.uniform(-1.0, 1.0);
      }
    }
    if (kind == 3) // clockwise
      for (int k = 0; k < n; ++k)
        xy[2 * k + 1] = -xy[2 * k + 1];
    if (kind == 5 && n > 3) { // a corner on the next one, or on the one before
      const int k = rng.below(n), k1 = k + 1 == n ? 0 : k + 1;
      xy[2 * k1] = xy[2 * k];
      xy[2 * k1 + 1] = xy[2 * k + 1];
    }
    if (kind == 6) { // a non-finite corner coordinate in a (mostly convex) polygon
      const double bad[] = {INFINITY, -INFINITY, NAN, 1e308};
      xy[rng.below(2 * n)] = bad[rng.below(4)];
    }
    // Repeated IDs now and then.
    std::vector<long> ids(n);
    for (int k = 0; k < n; ++k)
      ids[k] = 10 + k;
    if (kind == 7)
      ids[rng.below(n)] = 10 + rng.below(n);
    const PolygonDefect fast = tessera::polygon_defect(xy.data(), n, ids.data());
    const PolygonDefect slow = tessera::polygon_defect_pairwise(xy.data(), n, ids.data());
    ASSERT_EQ(fast, slow) << "trial " << trial << " kind " << kind << " n " << n;
    bad += slow != PolygonDefect::None;
    // (the convex ones: the fast path's own cases)
    bool left = true;
    for (int k = 0; k < n; ++k) {
      const int k1 = (k + 1) % n, k2 = (k + 2) % n;
      left = left && (xy[2 * k1] - xy[2 * k]) * (xy[2 * k2 + 1] - xy[2 * k1 + 1]) -
                             (xy[2 * k1 + 1] - xy[2 * k + 1]) * (xy[2 * k2] - xy[2 * k1]) >
                         0.0;
    }
    convex += left && slow == PolygonDefect::None;
  }
  // Both answers were exercised.
  EXPECT_GT(convex, 2000);
  EXPECT_GT(bad, 2000);
}

// The force of a zero-length edge's tension is the mean of its one-sided
// derivatives: nothing from that edge.
TEST(VertexPolygon, ZeroLengthEdgeIsFinite) {
  const Model m = two_type_model();
  const double xy[] = {0, 0, 1, 0, 1, 0, 1, 1, 0, 1};
  std::vector<double> g(10);
  tessera::polygon_energy(xy, 5, m, 0, 0, nullptr, g.data());
  for (double v : g)
    EXPECT_TRUE(std::isfinite(v));
}

std::string check_message(const VertexTissue &t) {
  try {
    tessera::check_tissue(t);
  } catch (const tessera::Error &e) {
    return e.what();
  }
  return "";
}

TEST(VertexTissue, CheckNamesWhatIsBroken) {
  const VertexTissue good = vtest::random_tissue(13, 20, 4.5);
  EXPECT_EQ(check_message(good), "");
  {
    VertexTissue t = good; // a clockwise ring
    std::reverse(t.rings[3].begin(), t.rings[3].end());
    EXPECT_NE(check_message(t).find("same direction"), std::string::npos) << check_message(t);
  }
  {
    VertexTissue t = good; // a vertex dropped from one ring: the ring does not close
    t.rings[5].erase(t.rings[5].begin());
    EXPECT_NE(check_message(t).find("no cell on its other side"), std::string::npos)
        << check_message(t);
  }
  {
    VertexTissue t = good; // a vertex pulled across its cell: an inverted or crossing cell
    const int v = t.rings[2][0];
    const tessera::Vec2 c = t.measures(2).centroid;
    const tessera::Vec2 d = t.image(c.x - t.pos[v].x, c.y - t.pos[v].y);
    t.pos[v].x += 2.5 * d.x;
    t.pos[v].y += 2.5 * d.y;
    const std::string msg = check_message(t);
    EXPECT_TRUE(msg.find("crosses itself") != std::string::npos ||
                msg.find("negative area") != std::string::npos)
        << msg;
  }
  {
    VertexTissue t = good; // a two-sided cell
    t.rings[1].resize(2);
    EXPECT_NE(check_message(t).find("three"), std::string::npos);
  }
}

// Co-circular centres (a square lattice): several vertices at one point,
// joined by zero-length edges; still a consistent tissue with finite forces.
TEST(VertexTissue, SquareLatticeGivesZeroLengthEdges) {
  std::vector<double> pts;
  std::vector<int> type;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      pts.push_back(i + 0.5);
      pts.push_back(j + 0.5);
      type.push_back(0);
    }
  const tessera::Box box = tessera::Box::rect(0, 4, 0, 4);
  const VertexTissue t =
      tessera::vertex_tissue_from_voronoi(box, tessera::Points{pts.data(), 16, 2}, type.data());
  EXPECT_EQ(t.n_vertices(), 32);
  EXPECT_NO_THROW(tessera::check_tissue(t));
  std::vector<double> f;
  tessera::tissue_forces(t, vtest::quadratic_model(1, 1, 0.3, 3.8), f);
  for (double v : f)
    EXPECT_TRUE(std::isfinite(v));
  int zero = 0;
  const tessera::EdgeMap m(t);
  for (int c = 0; c < t.n_cells(); ++c) {
    EXPECT_NEAR(t.measures(c).area, 1.0, 1e-12);
    for (size_t k = 0; k < t.rings[c].size(); ++k) {
      const tessera::Vec2 d = t.delta(t.rings[c][k], t.rings[c][(k + 1) % t.rings[c].size()]);
      if (d.x == 0.0 && d.y == 0.0)
        ++zero;
    }
  }
  EXPECT_EQ(zero, 32); // one zero-length edge per four-fold vertex, seen from two cells
}

} // namespace

namespace {

// The vertex model's cells in the consumers' view: every cell a slot, the
// pieces its edges, the neighbours the cells across, the derived quantities
// (neighbour count, centroid, principal axis) those of the polygons.
TEST(VertexCells, ViewOfAStretchedHoneycomb) {
  VertexTissue t = vtest::honeycomb(6, 4);
  vtest::deform(t, 1.2, 0.0, 1.0 / 1.2);
  const tessera::EdgeMap m(t);
  std::vector<double> centres;
  for (int c = 0; c < t.n_cells(); ++c) {
    const tessera::Vec2 cm = t.measures(c).centroid;
    centres.push_back(cm.x);
    centres.push_back(cm.y);
  }
  tessera::PolygonCells view;
  // Slots 0 .. n-1 hold the cells, one more slot stays empty.
  view.clear(t.n_cells() + 1, t.n_cells(), tessera::Points{centres.data(), t.n_cells(), 2});
  std::vector<double> xy;
  for (int c = 0; c < t.n_cells(); ++c) {
    t.polygon(c, xy);
    std::vector<int> nbr;
    for (size_t k = 0; k < t.rings[c].size(); ++k)
      nbr.push_back(tessera::twin_cell(t, m, c, static_cast<int>(k)));
    const tessera::PolygonMeasures pm = t.measures(c);
    view.add_cell(c, xy.data(), static_cast<int>(nbr.size()), nbr.data(), pm.area, pm.perimeter);
  }
  view.finish();
  const int n = t.n_cells();
  EXPECT_EQ(view.piece_begin(n), view.piece_end(n)); // the empty slot
  const tessera::Contacts con = view.contacts();
  for (int c = 0; c < n; ++c) {
    EXPECT_NEAR(view.measure(c), 1.0, 1e-12);
    EXPECT_EQ(view.coordination_number(c), 6);
    double x[2];
    view.centroid(c, x);
    EXPECT_NEAR(x[0], centres[2 * c], 1e-12);
    EXPECT_NEAR(x[1], centres[2 * c + 1], 1e-12);
    ASSERT_TRUE(view.principal_axis(c, true, x));
    EXPECT_NEAR(std::fabs(x[0]), 1.0, 1e-9);
    // Each neighbour lists this cell back.
    for (int k = con.offset[c]; k < con.offset[c + 1]; ++k) {
      const int o = con.neighbor[k];
      bool back = false;
      for (int j = con.offset[o]; j < con.offset[o + 1]; ++j)
        back = back || con.neighbor[j] == c;
      EXPECT_TRUE(back);
    }
  }
}

} // namespace

namespace {

// The view filled lazily (set_rings: corners by index into a table of
// points, pieces made at the first read) against add_cell (the oracle):
// fuzzed tissues in slots with gaps, corners shared by several cells or
// copied per cell, tables of stride 2 and 3; every accessor the same bits.
TEST(VertexCells, LazyRingsAreAddCell) {
  testutil::Rng rng(4711);
  for (int trial = 0; trial < 40; ++trial) {
    const VertexTissue t = vtest::random_tissue(100 + trial, 5 + rng.below(30), 6.0,
                                                1 + rng.below(2), rng.below(2) ? 0.7 : 0.0);
    // Slots: cells at increasing slots, empty slots between some of them.
    std::vector<int> slot_cell;
    for (int c = 0; c < t.n_cells(); ++c) {
      while (rng.below(3) == 0)
        slot_cell.push_back(-1);
      slot_cell.push_back(c);
    }
    if (rng.below(2))
      slot_cell.push_back(-1);
    const int ns = static_cast<int>(slot_cell.size());
    const int stride = 2 + rng.below(2);
    std::vector<double> table; // the points, stride values each
    std::vector<int> offset(ns + 1, 0), corner, neighbor;
    std::vector<double> area(ns, 0.0), perimeter(ns, 0.0);
    std::vector<double> centres(2 * static_cast<size_t>(ns), 0.0);
    tessera::PolygonCells eager, lazy;
    std::vector<double> xy;
    auto add_point = [&](double x, double y) {
      table.push_back(x);
      table.push_back(y);
      if (stride == 3)
        table.push_back(rng.uniform());
      return static_cast<int>(table.size()) / stride - 1;
    };
    eager.clear(ns, ns, tessera::Points{centres.data(), ns, 2});
    lazy.clear(ns, ns, tessera::Points{centres.data(), ns, 2});
    for (int s = 0; s < ns; ++s) {
      offset[s] = static_cast<int>(corner.size());
      const int c = slot_cell[s];
      if (c < 0)
        continue;
      t.polygon(c, xy);
      const int n = static_cast<int>(t.rings[c].size());
      std::vector<int> nbr(n);
      for (int k = 0; k < n; ++k) {
        nbr[k] = rng.below(ns);
        neighbor.push_back(nbr[k]);
        // A decoy point now and then: indices need not be in ring order.
        if (rng.below(4) == 0)
          add_point(rng.uniform(), rng.uniform());
        corner.push_back(add_point(xy[2 * k], xy[2 * k + 1]));
      }
      const tessera::PolygonMeasures pm = tessera::polygon_measures(xy.data(), n);
      area[s] = pm.area;
      perimeter[s] = pm.perimeter;
      eager.add_cell(s, xy.data(), n, nbr.data(), pm.area, pm.perimeter);
    }
    offset[ns] = static_cast<int>(corner.size());
    eager.finish();
    const int npts = static_cast<int>(table.size()) / stride;
    lazy.set_rings(offset.data(), corner.data(), neighbor.data(),
                   tessera::Points{table.data(), npts, stride});
    for (int s = 0; s < ns; ++s)
      lazy.set_measures(s, area[s], perimeter[s]);
    // The table changes after the force computation: the view keeps its copy.
    for (double &v : table)
      v += 1.0;
    ASSERT_EQ(lazy.n_owned(), eager.n_owned());
    // Read in an order of its own: sizes first, corners first, or contacts first.
    const int first = rng.below(3);
    if (first == 1) {
      std::vector<double> tmp;
      if (offset[ns] > 0)
        lazy.piece_corners(0, tmp);
    } else if (first == 2) {
      lazy.contacts();
    }
    for (int s = 0; s < ns; ++s) {
      ASSERT_EQ(lazy.piece_begin(s), eager.piece_begin(s));
      ASSERT_EQ(lazy.piece_end(s), eager.piece_end(s));
      EXPECT_EQ(lazy.measure(s), eager.measure(s));
      EXPECT_EQ(lazy.boundary(s), eager.boundary(s));
      for (int k = eager.piece_begin(s); k < eager.piece_end(s); ++k) {
        EXPECT_EQ(lazy.piece_neighbor(k), eager.piece_neighbor(k));
        EXPECT_EQ(lazy.piece_size(k), eager.piece_size(k));
        std::vector<double> a, b;
        EXPECT_EQ(lazy.piece_corners(k, a), eager.piece_corners(k, b));
        EXPECT_EQ(a, b);
      }
      double pa[2], pb[2];
      if (eager.piece_end(s) > eager.piece_begin(s) && eager.principal_axis(s, true, pb)) {
        ASSERT_TRUE(lazy.principal_axis(s, true, pa));
        EXPECT_EQ(pa[0], pb[0]);
        EXPECT_EQ(pa[1], pb[1]);
      }
    }
    const tessera::Contacts ca = lazy.contacts(), cb = eager.contacts();
    ASSERT_EQ(ca.n_owned, cb.n_owned);
    for (int k = 0; k < offset[ns]; ++k) {
      EXPECT_EQ(ca.neighbor[k], cb.neighbor[k]);
      EXPECT_EQ(ca.size[k], cb.size[k]);
    }
    for (int s = 0; s <= ns; ++s)
      EXPECT_EQ(ca.offset[s], cb.offset[s]);
  }
}

} // namespace

namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// image()'s shortcut for differences within a quarter period against the
// divisions and floors alone (image_reference): the same bits, signed zeros
// included, on fuzzed boxes (tilted or not, either sign) and differences
// near the quarter, half and whole periods, zeros and non-finite ones.
TEST(VertexTissue, ImageShortcutIsReference) {
  testutil::Rng rng(8128);
  int shortcut = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    VertexTissue t;
    const double lx = rng.uniform(0.5, 50.0), ly = rng.uniform(0.5, 50.0);
    t.box = tessera::Box::rect(rng.uniform(-5.0, 5.0), 0.0, rng.uniform(-5.0, 5.0), 0.0);
    t.box.hi[0] = t.box.lo[0] + lx;
    t.box.hi[1] = t.box.lo[1] + ly;
    const int tilt = rng.below(4);
    t.box.xy = tilt == 0 ? 0.0 : tilt == 1 ? -0.0 : rng.uniform(-0.6, 0.6) * lx;
    t.periodic = rng.below(8) != 0;
    double d[2];
    for (int a = 0; a < 2; ++a) {
      const double l = a == 0 ? lx : ly;
      const int kind = rng.below(6);
      if (kind == 0)
        d[a] = rng.below(2) ? 0.0 : -0.0;
      else if (kind == 1) // near a quarter period
        d[a] = (rng.below(2) ? 1 : -1) * 0.25 * l * (1.0 + rng.uniform(-1e-15, 1e-15));
      else if (kind == 2)
        d[a] = rng.uniform(-0.3, 0.3) * l;
      else if (kind == 3)
        d[a] = rng.uniform(-3.0, 3.0) * l;
      else if (kind == 4) // tiny
        d[a] = rng.uniform(-1e-300, 1e-300);
      else
        d[a] = rng.below(3) == 0 ? std::nan("") : (rng.below(2) ? 1 : -1) * HUGE_VAL;
    }
    const tessera::Vec2 f = t.image(d[0], d[1]), r = t.image_reference(d[0], d[1]);
    ASSERT_TRUE(same_bits(f.x, r.x) && same_bits(f.y, r.y))
        << "dx " << d[0] << " dy " << d[1] << " box " << lx << " x " << ly << " xy " << t.box.xy
        << ": " << f.x << ", " << f.y << " against " << r.x << ", " << r.y;
    shortcut += t.periodic && std::fabs(d[0]) < 0.25 * lx && std::fabs(d[1]) < 0.25 * ly;
  }
  EXPECT_GT(shortcut, 20000); // the shortcut was taken often
}

} // namespace
