// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Finite Voronoi cells (Voronoi cell cut by a disc of radius r) against an
// independent slow reference (a fine regular polygon standing for the disc,
// cut by every bisector half-plane), against closed-form one- and two-cell
// values, and their forces against central differences of the energy.

#include "tessera/energy.h"
#include "tessera/finite.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

class Rng {
public:
  explicit Rng(uint64_t seed) : s_(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}
  double uniform() {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }

private:
  uint64_t s_;
};

// ---- slow reference: polygon clipping ----
struct RefCell {
  double area = 0, perimeter = 0, free_length = 0;
  std::map<int, double> contact;  // neighbour -> edge length
};

struct PV {
  double x, y;
  int tag;  // edge from this vertex to the next: -1 on the disc polygon, j on bisector j
};

RefCell reference_cell(const std::vector<double> &xy, int c, double r, int nside = 1 << 16) {
  const int n = static_cast<int>(xy.size() / 2);
  const double cx = xy[2 * c], cy = xy[2 * c + 1];
  std::vector<PV> poly(nside), next;
  // Inscribed polygon: it never reaches past the circle, so tangent pairs
  // stay apart; arcs are short by a relative dth^2/24, areas by dth^2/6.
  const double dth = 2 * kPi / nside;
  const double R = r;
  for (int k = 0; k < nside; ++k)
    poly[k] = PV{R * std::cos(k * dth), R * std::sin(k * dth), -1};
  for (int j = 0; j < n; ++j) {
    if (j == c) continue;
    const double dx = xy[2 * j] - cx, dy = xy[2 * j + 1] - cy;
    const double d = std::hypot(dx, dy);
    if (d >= 2 * r) continue;
    auto s = [&](const PV &p) { return (p.x * dx + p.y * dy) / d - 0.5 * d; };
    next.clear();
    const int m = static_cast<int>(poly.size());
    for (int k = 0; k < m; ++k) {
      const PV &a = poly[k], &b = poly[(k + 1) % m];
      const double sa = s(a), sb = s(b);
      if (sa <= 0) next.push_back(a);
      if ((sa <= 0) != (sb <= 0)) {
        const double f = sa / (sa - sb);
        PV q{a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), sa <= 0 ? j : a.tag};
        if (sa <= 0) next.back().tag = a.tag;
        next.push_back(q);
      }
    }
    poly.swap(next);
  }
  RefCell out;
  const int m = static_cast<int>(poly.size());
  for (int k = 0; k < m; ++k) {
    const PV &a = poly[k], &b = poly[(k + 1) % m];
    const double l = std::hypot(b.x - a.x, b.y - a.y);
    out.area += 0.5 * (a.x * b.y - a.y * b.x);
    out.perimeter += l;
    if (a.tag < 0)
      out.free_length += l;
    else
      out.contact[a.tag] += l;
  }
  return out;
}

// The polygon is off by O(dth^2) (more where a bisector meets the circle at a
// grazing angle): compare with this relative tolerance.
constexpr double kRefTol = 1e-7;

std::vector<double> random_cluster(Rng &rng, int n, double w, double h, double min_dist) {
  std::vector<double> xy;
  while (static_cast<int>(xy.size()) < 2 * n) {
    const double x = rng.uniform(0, w), y = rng.uniform(0, h);
    bool ok = true;
    for (size_t k = 0; k < xy.size(); k += 2)
      if (std::hypot(xy[k] - x, xy[k + 1] - y) < min_dist) ok = false;
    if (ok) {
      xy.push_back(x);
      xy.push_back(y);
    }
  }
  return xy;
}

tessera::Model random_model(Rng &rng, int ntypes, tessera::Tension tension) {
  tessera::Model m(ntypes);
  m.tension = tension;
  for (int t = 0; t < ntypes; ++t)
    m.types[t] = tessera::CellType{rng.uniform(0.5, 2.0), rng.uniform(0.6, 1.4), rng.uniform(0.05, 0.5)};
  for (int a = 0; a < ntypes; ++a)
    for (int b = a; b < ntypes; ++b) m.set_lambda(a, b, rng.uniform(-1.0, 0.5));
  return m;
}

void check_against_reference(const std::vector<double> &xy, double r, const char *what) {
  const int n = static_cast<int>(xy.size() / 2);
  const tessera::FiniteTessellation t =
      tessera::finite_tessellate(tessera::Points{xy.data(), n, 2}, n, r);
  for (int c = 0; c < n; ++c) {
    const RefCell ref = reference_cell(xy, c, r);
    const double scale = r;
    EXPECT_NEAR(t.area[c], ref.area, kRefTol * scale * scale) << what << " cell " << c;
    EXPECT_NEAR(t.perimeter[c], ref.perimeter, kRefTol * scale) << what << " cell " << c;
    EXPECT_NEAR(t.free_length[c], ref.free_length, kRefTol * scale) << what << " cell " << c;
    std::map<int, double> mine;
    for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
      if (t.pieces[k].neighbor >= 0) mine[t.pieces[k].neighbor] += t.pieces[k].length;
    // Contact lengths near tangency are sensitive to the polygon's R - r.
    for (const auto &kv : ref.contact)
      if (kv.second > 1e-3 * r) {
        ASSERT_TRUE(mine.count(kv.first)) << what << " cell " << c << " misses " << kv.first;
        EXPECT_NEAR(mine[kv.first], kv.second, 2e-6 * r) << what << " cell " << c;
      }
    for (const auto &kv : mine)
      if (kv.second > 1e-3 * r) EXPECT_TRUE(ref.contact.count(kv.first)) << what << " " << c;
  }
}

// Central differences of the total energy of the owned cells with respect to
// every point, against the forces.
void check_forces_open(const std::vector<double> &xy0, double r, const std::vector<int> &type,
                       const tessera::Model &model, const std::vector<double> &free_t,
                       const char *what, double h = 1e-6, double tol = 2e-6) {
  const int n = static_cast<int>(xy0.size() / 2);
  auto energy = [&](const std::vector<double> &xy) {
    const auto t = tessera::finite_tessellate(tessera::Points{xy.data(), n, 2}, n, r);
    return tessera::finite_energy(t, type.data(), model, free_t.data());
  };
  const auto t = tessera::finite_tessellate(tessera::Points{xy0.data(), n, 2}, n, r);
  std::vector<double> f(2 * n, 0.0);
  tessera::finite_forces(t, tessera::Points{xy0.data(), n, 2}, type.data(), model, free_t.data(),
                         f.data(), 2);
  double fmax = 0.0;
  for (double v : f) fmax = std::max(fmax, std::fabs(v));
  std::vector<double> xy = xy0;
  for (int i = 0; i < 2 * n; ++i) {
    xy[i] = xy0[i] + h;
    const double ep = energy(xy);
    xy[i] = xy0[i] - h;
    const double em = energy(xy);
    xy[i] = xy0[i];
    const double fd = -(ep - em) / (2 * h);
    EXPECT_NEAR(f[i], fd, tol * (1.0 + fmax)) << what << " coordinate " << i;
  }
}

// Two cells of radius r at distance d < 2r: each is the disc less a cap.
void two_cells(double r, double d, double &A, double &P, double &L) {
  const double ca = d / (2 * r);
  const double alpha = std::acos(ca);
  const double sa = std::sqrt(1 - ca * ca);
  A = r * r * (kPi - alpha + sa * ca);
  L = 2 * r * (kPi - alpha);
  P = L + 2 * r * sa;
}

TEST(Finite, IsolatedCellIsADisc) {
  const double r = 0.7;
  std::vector<double> xy = {0.3, -0.2, 5.0, 5.0};  // the second is 2r + away
  const auto t = tessera::finite_tessellate(tessera::Points{xy.data(), 2, 2}, 2, r);
  for (int c = 0; c < 2; ++c) {
    EXPECT_NEAR(t.area[c], kPi * r * r, 1e-14);
    EXPECT_NEAR(t.perimeter[c], 2 * kPi * r, 1e-14);
    EXPECT_NEAR(t.free_length[c], 2 * kPi * r, 1e-14);
    EXPECT_TRUE(t.at_edge(c));
  }
  // Quadratic energy KA (A - A0)^2 + KP (P - P0)^2 + Lambda L, written in the
  // K, Gamma, Lambda form: free tension Lambda - 2 KP P0 plus the constant.
  const double KA = 1.3, A0 = 1.1, KP = 0.4, P0 = 3.2, Lam = 0.25;
  const tessera::QuadraticParams q{KA, A0, KP, P0};
  tessera::Model m(1);
  m.types[0] = tessera::cell_type_from_quadratic(q);
  m.set_lambda(0, 0, tessera::lambda_from_quadratic(q, m.tension));
  const double F = Lam - 2 * KP * P0;
  const std::vector<int> type = {0, 0};
  const double e = tessera::finite_energy(t, type.data(), m, &F);
  const double A = kPi * r * r, P = 2 * kPi * r;
  const double analytic = KA * (A - A0) * (A - A0) + KP * (P - P0) * (P - P0) + Lam * P;
  EXPECT_NEAR(e + 2 * KP * P0 * P0, 2 * analytic, 1e-12);
  std::vector<double> f(4, 0.0);
  tessera::finite_forces(t, tessera::Points{xy.data(), 2, 2}, type.data(), m, &F, f.data(), 2);
  for (double v : f) EXPECT_EQ(v, 0.0);
}

TEST(Finite, TwoTouchingCellsMatchClosedForm) {
  const double r = 1.0;
  for (double d : {0.2, 0.9, 1.5, 1.99, 2.0 - 1e-6, 2.0 - 1e-12}) {
    std::vector<double> xy = {0.1, 0.2, 0.1 + d * 0.6, 0.2 + d * 0.8};
    const auto t = tessera::finite_tessellate(tessera::Points{xy.data(), 2, 2}, 2, r);
    double A, P, L;
    two_cells(r, d, A, P, L);
    for (int c = 0; c < 2; ++c) {
      EXPECT_NEAR(t.area[c], A, 1e-12) << d;
      EXPECT_NEAR(t.perimeter[c], P, 1e-9) << d;
      EXPECT_NEAR(t.free_length[c], L, 1e-9) << d;
    }
    // Energy KA (A - A0)^2 + KP (P - P0)^2 + Lambda L per cell.
    const double KA = 1.0, A0 = 2.0, KP = 0.3, P0 = 4.0, Lam = 0.6;
    const tessera::QuadraticParams q{KA, A0, KP, P0};
    tessera::Model m(1);
    m.types[0] = tessera::cell_type_from_quadratic(q);
    m.set_lambda(0, 0, tessera::lambda_from_quadratic(q, m.tension));
    const double F = Lam - 2 * KP * P0;
    const std::vector<int> type = {0, 0};
    const double e = tessera::finite_energy(t, type.data(), m, &F) + 2 * KP * P0 * P0;
    const double analytic = 2 * (KA * (A - A0) * (A - A0) + KP * (P - P0) * (P - P0) + Lam * L);
    EXPECT_NEAR(e, analytic, 1e-8) << d;
    // Force along the line of centres: -dE/dd of the closed form.
    auto E_of = [&](double dd) {
      double a, p, l;
      two_cells(r, dd, a, p, l);
      return 2 * (KA * (a - A0) * (a - A0) + KP * (p - P0) * (p - P0) + Lam * l);
    };
    if (d < 1.999) {
      std::vector<double> f(4, 0.0);
      tessera::finite_forces(t, tessera::Points{xy.data(), 2, 2}, type.data(), m, &F, f.data(), 2);
      const double hh = 1e-6;
      const double dEdd = (E_of(d + hh) - E_of(d - hh)) / (2 * hh);
      // Moving cell 1 away along (0.6, 0.8) increases d: f1 . u = -dE/dd.
      EXPECT_NEAR(f[2] * 0.6 + f[3] * 0.8, -dEdd, 1e-6 * (1 + std::fabs(dEdd))) << d;
      EXPECT_NEAR(f[0] + f[2], 0.0, 1e-12);
      EXPECT_NEAR(f[1] + f[3], 0.0, 1e-12);
    }
  }
  // Apart: two discs.
  std::vector<double> xy = {0.0, 0.0, 2.0, 0.0};
  const auto t = tessera::finite_tessellate(tessera::Points{xy.data(), 2, 2}, 2, r);
  EXPECT_NEAR(t.area[0], kPi, 1e-14);
  EXPECT_EQ(t.cell_size(0), 1);
}

TEST(Finite, RandomClustersMatchPolygonClipping) {
  Rng rng(11);
  for (int trial = 0; trial < 4; ++trial) {
    const auto xy = random_cluster(rng, 25, 5.0, 4.0, 0.2);
    for (double r : {0.45, 0.8, 1.6}) check_against_reference(xy, r, "cluster");
  }
}

TEST(Finite, LatticeAndMultifoldMatchPolygonClipping) {
  // A square lattice: every Voronoi vertex is four-fold.  r around the
  // corner distance sqrt(2)/2 cuts the corners or leaves them.
  std::vector<double> xy;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      xy.push_back(i);
      xy.push_back(j);
    }
  for (double r : {0.5, 0.6, std::sqrt(0.5) - 1e-9, std::sqrt(0.5), std::sqrt(0.5) + 1e-9, 0.9})
    check_against_reference(xy, r, "square lattice");
  // Hexagonal lattice with r just at the vertex distance.
  xy.clear();
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      xy.push_back(i + 0.5 * (j % 2));
      xy.push_back(j * std::sqrt(0.75));
    }
  for (double r : {0.49, 0.51, 1 / std::sqrt(3.0) - 1e-10, 1 / std::sqrt(3.0), 0.62})
    check_against_reference(xy, r, "hex lattice");
}

TEST(Finite, ForcesAreCentralDifferencesInOpenClusters) {
  Rng rng(5);
  for (int trial = 0; trial < 6; ++trial) {
    const int ntypes = 1 + trial % 2;
    const auto xy = random_cluster(rng, 14, 3.0, 2.5, 0.25);
    std::vector<int> type(14);
    for (int i = 0; i < 14; ++i) type[i] = i % ntypes;
    const auto model = random_model(rng, ntypes, trial % 3 == 2 ? tessera::Tension::Cell
                                                                : tessera::Tension::Edge);
    std::vector<double> free_t(ntypes);
    for (double &v : free_t) v = rng.uniform(-0.3, 0.6);
    const double r = rng.uniform(0.4, 1.0);
    check_forces_open(xy, r, type, model, free_t, "open cluster");
  }
}

TEST(Finite, PerCellPreferredAreas) {
  // Model::cell_area0 (LAMMPS's d_area0) replaces the types' A0 in finite
  // cells too: the energy is the sum with each cell's own A0 (against the
  // polygon-clipping areas) and the forces are its central differences.
  Rng rng(17);
  for (int trial = 0; trial < 3; ++trial) {
    const int n = 12;
    const auto xy = random_cluster(rng, n, 3.0, 2.5, 0.25);
    std::vector<int> type(n, 0);
    auto model = random_model(rng, 1, tessera::Tension::Edge);
    std::vector<double> a0(n);
    for (double &v : a0) v = rng.uniform(0.3, 2.0);
    model.cell_area0 = a0.data();
    const std::vector<double> free_t = {rng.uniform(-0.3, 0.6)};
    const double r = rng.uniform(0.5, 1.0);
    const auto t = tessera::finite_tessellate(tessera::Points{xy.data(), n, 2}, n, r);
    std::vector<double> ec(n);
    tessera::finite_energy(t, type.data(), model, free_t.data(), ec.data());
    const tessera::CellType &ct = model.types[0];
    for (int c = 0; c < n; ++c) {
      const RefCell ref = reference_cell(xy, c, r);
      double lam = 0.0;
      for (const auto &kv : ref.contact) lam += kv.second;
      const double e = 0.5 * ct.K * (ref.area - a0[c]) * (ref.area - a0[c]) +
                       0.5 * ct.Gamma * ref.perimeter * ref.perimeter +
                       model.tension_weight() * model.lambda_of(0, 0) * lam +
                       free_t[0] * ref.free_length;
      EXPECT_NEAR(ec[c], e, 1e-5 * (1.0 + std::fabs(e))) << "trial " << trial << " cell " << c;
    }
    check_forces_open(xy, r, type, model, free_t, "per-cell A0");
  }
}

// Corners that are about to appear or vanish: a contact edge barely cut,
// an arc that has nearly vanished, a Voronoi vertex just inside the disc.
TEST(Finite, ForcesNearTopologyChanges) {
  tessera::Model m(1);
  m.types[0] = tessera::CellType{1.0, 1.2, 0.3};
  m.set_lambda(0, 0, -0.4);
  const std::vector<double> F = {0.2};
  const double r = 1.0;
  // Equilateral triangle with side s: the Voronoi vertex is at distance
  // s/sqrt(3) from each centre; it is inside the disc if s < sqrt(3) r.
  for (double eps : {1e-3, 1e-5, -1e-5, -1e-3}) {
    const double s = std::sqrt(3.0) * r * (1 + eps);
    std::vector<double> xy = {0, 0, s, 0, 0.5 * s, 0.5 * std::sqrt(3.0) * s};
    const std::vector<int> type(3, 0);
    const auto t = tessera::finite_tessellate(tessera::Points{xy.data(), 3, 2}, 3, r);
    check_against_reference(xy, r, "triangle");
    // The FD step must stay well inside the distance to the event.
    check_forces_open(xy, r, type, m, F, "triangle", 1e-3 * std::fabs(eps), 1e-5);
    (void)t;
  }
  // Two cells nearly tangent: d = 2r (1 - eps); the contact edge is
  // 2 r sqrt(2 eps) long and the forces stay finite.
  for (double eps : {1e-4, 1e-8, 1e-12}) {
    std::vector<double> xy = {0, 0, 2 * r * (1 - eps), 0.0, 1.0, 1.9};
    const std::vector<int> type(3, 0);
    const auto t = tessera::finite_tessellate(tessera::Points{xy.data(), 3, 2}, 3, r);
    std::vector<double> f(6, 0.0);
    tessera::finite_forces(t, tessera::Points{xy.data(), 3, 2}, type.data(), m, F.data(),
                           f.data(), 2);
    for (double v : f) EXPECT_TRUE(std::isfinite(v));
    if (eps >= 1e-8) check_forces_open(xy, r, type, m, F, "near tangent", 1e-3 * eps * r, 1e-4);
  }
  // Equal arc and contact tensions (F = w Lambda): at onset the perimeter
  // is smooth, and the force is continuous through tangency.
  {
    tessera::Model q(1);
    q.types[0] = tessera::CellType{1.0, 1.2, 0.3};
    q.set_lambda(0, 0, -0.4);
    const double Fq = 0.5 * -0.4;
    const std::vector<int> type(2, 0);
    double fx[2];
    int k = 0;
    for (double d : {2.0 - 1e-10, 2.0 + 1e-10}) {
      std::vector<double> xy = {0, 0, d, 0};
      const auto t = tessera::finite_tessellate(tessera::Points{xy.data(), 2, 2}, 2, r);
      std::vector<double> f(4, 0.0);
      tessera::finite_forces(t, tessera::Points{xy.data(), 2, 2}, type.data(), q, &Fq, f.data(), 2);
      fx[k++] = f[2];
    }
    EXPECT_NEAR(fx[0], fx[1], 1e-3);
  }
}

TEST(Finite, LatticeForcesFiniteAndBalanced) {
  // Four-fold vertices and corners exactly on the circle are normal input.
  std::vector<double> xy;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      xy.push_back(i);
      xy.push_back(j);
    }
  const int n = 16;
  tessera::Model m(1);
  m.types[0] = tessera::CellType{1.0, 0.9, 0.2};
  m.set_lambda(0, 0, -0.3);
  const double F = 0.1;
  const std::vector<int> type(n, 0);
  for (double r : {0.6, std::sqrt(0.5), 0.8}) {
    const auto t = tessera::finite_tessellate(tessera::Points{xy.data(), n, 2}, n, r);
    std::vector<double> f(2 * n, 0.0);
    const auto out =
        tessera::finite_forces(t, tessera::Points{xy.data(), n, 2}, type.data(), m, &F, f.data(), 2);
    double sx = 0, sy = 0;
    for (int i = 0; i < n; ++i) {
      EXPECT_TRUE(std::isfinite(f[2 * i]) && std::isfinite(f[2 * i + 1]));
      sx += f[2 * i];
      sy += f[2 * i + 1];
    }
    EXPECT_NEAR(sx, 0.0, 1e-12);
    EXPECT_NEAR(sy, 0.0, 1e-12);
    EXPECT_TRUE(std::isfinite(out.energy));
  }
}

// Periodic box with holes: images built by brute force for the reference.
TEST(Finite, PeriodicMatchesReferenceAndCentralDifferences) {
  Rng rng(21);
  for (int trial = 0; trial < 3; ++trial) {
    tessera::Box box = tessera::Box::rect(0, 4.0, -1.0, 2.0);
    if (trial == 2) box.xy = 1.3;
    auto xy = random_cluster(rng, 12, 4.0, 3.0, 0.3);
    for (size_t k = 0; k < xy.size(); k += 2) xy[k + 1] -= 1.0;
    tessera::wrap_into_box(box, xy);
    const int n = 12;
    const double r = 0.7 + 0.2 * trial;
    const auto t = tessera::finite_tessellate_periodic(box, tessera::Points{xy.data(), n, 2}, r);
    // Reference: every image within a 5x5 block of boxes.
    std::vector<double> all(xy.begin(), xy.end());
    for (int a = -2; a <= 2; ++a)
      for (int b = -2; b <= 2; ++b) {
        if (a == 0 && b == 0) continue;
        for (int i = 0; i < n; ++i) {
          all.push_back(xy[2 * i] + a * box.length(0) + b * box.xy);
          all.push_back(xy[2 * i + 1] + b * box.length(1));
        }
      }
    double total = 0;
    for (int c = 0; c < n; ++c) {
      const RefCell ref = reference_cell(all, c, r);
      EXPECT_NEAR(t.area[c], ref.area, kRefTol * r * r) << trial << " cell " << c;
      EXPECT_NEAR(t.perimeter[c], ref.perimeter, kRefTol * r) << trial << " cell " << c;
      EXPECT_NEAR(t.free_length[c], ref.free_length, kRefTol * r) << trial << " cell " << c;
      total += t.area[c];
    }
    EXPECT_LE(total, box.area() * (1 + 1e-12));

    const tessera::Model model = random_model(rng, 2, tessera::Tension::Edge);
    std::vector<int> type(n);
    for (int i = 0; i < n; ++i) type[i] = i % 2;
    const double free_t[2] = {0.3, -0.1};
    std::vector<double> f;
    tessera::finite_periodic_forces(box, tessera::Points{xy.data(), n, 2}, r, type.data(), model,
                                    free_t, f);
    auto energy = [&](const tessera::Box &bx, std::vector<double> p) {
      tessera::wrap_into_box(bx, p);
      const auto tt = tessera::finite_tessellate_periodic(bx, tessera::Points{p.data(), n, 2}, r);
      std::vector<int> ty(tt.n_points);
      for (int k = 0; k < tt.n_points; ++k) ty[k] = type[tt.origin[k]];
      return tessera::finite_energy(tt, ty.data(), model, free_t);
    };
    const double h = 1e-6;
    double fmax = 0;
    for (double v : f) fmax = std::max(fmax, std::fabs(v));
    std::vector<double> p = xy;
    for (int i = 0; i < 2 * n; ++i) {
      p[i] = xy[i] + h;
      const double ep = energy(box, p);
      p[i] = xy[i] - h;
      const double em = energy(box, p);
      p[i] = xy[i];
      EXPECT_NEAR(f[i], -(ep - em) / (2 * h), 2e-6 * (1 + fmax)) << trial << " coord " << i;
    }
    // Virial: dE/d(strain_xx) = -W_xx, dE/d(strain_yy) = -W_yy.
    std::vector<double> pos = tessera::positions_of(t);
    std::vector<int> ty(t.n_points);
    for (int k = 0; k < t.n_points; ++k) ty[k] = type[t.origin[k]];
    std::vector<double> fall(2 * t.n_points, 0.0), cv(4 * n);
    const auto out = tessera::finite_forces(t, tessera::Points{pos.data(), t.n_points, 2}, ty.data(),
                                            model, free_t, fall.data(), 2, nullptr, cv.data());
    for (int d = 0; d < 2; ++d) {
      auto strained = [&](double eps) {
        tessera::Box bx = box;
        bx.hi[d] = box.lo[d] + box.length(d) * (1 + eps);
        if (d == 0) bx.xy = box.xy * (1 + eps);  // x -> (1 + eps) x maps (xy, ly) too
        std::vector<double> q = xy;
        for (int i = 0; i < n; ++i) q[2 * i + d] = box.lo[d] + (xy[2 * i + d] - box.lo[d]) * (1 + eps);
        return energy(bx, q);
      };
      const double dE = (strained(h) - strained(-h)) / (2 * h);
      EXPECT_NEAR(-out.virial[d], dE, 1e-5 * (1 + std::fabs(dE))) << trial << " dim " << d;
      double sum = 0;
      for (int c = 0; c < n; ++c) sum += cv[4 * c + d];
      EXPECT_NEAR(sum, out.virial[d], 1e-10 * (1 + std::fabs(dE)));
    }
  }
}

TEST(Finite, BadInputIsReported) {
  std::vector<double> xy = {0, 0, 0, 0};
  const long ids[2] = {7, 9};
  try {
    tessera::finite_tessellate(tessera::Points{xy.data(), 2, 2}, 2, 1.0, ids);
    FAIL() << "coincident points accepted";
  } catch (const tessera::Error &e) {
    EXPECT_NE(std::string(e.what()).find("id 7"), std::string::npos) << e.what();
  }
  xy = {0, 0, 1, 0};
  EXPECT_THROW(tessera::finite_tessellate(tessera::Points{xy.data(), 2, 2}, 2, 0.0), tessera::Error);
  EXPECT_THROW(tessera::finite_tessellate(tessera::Points{xy.data(), 2, 2}, 2, NAN), tessera::Error);
  xy = {0, NAN, 1, 0};
  EXPECT_THROW(tessera::finite_tessellate(tessera::Points{xy.data(), 2, 2}, 2, 1.0), tessera::Error);
}

}  // namespace
