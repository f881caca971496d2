// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// 3D Voronoi cells and energy: against half-space clipping (reference3d.h),
// the BCC and FCC lattices' analytic cells, finite differences of the energy
// (forces and virial), and bad input.

#include "reference3d.h"
#include "test_util.h"

#include "tessera/voronoi3d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

using namespace tessera;

namespace {

struct Config3 {
  Box3 box;
  std::vector<double> xyz;
  std::vector<int> type;
  int n() const { return static_cast<int>(xyz.size() / 3); }
  Points3 points() const { return Points3{xyz.data(), n(), 3}; }
};

// A jittered simple-cubic arrangement (nx*ny*nz cells of volume ~1) in a box
// with its lower corner away from the origin; jitter amplitude in units of the
// spacing.  Random types in [0, ntypes).
Config3 jittered(int nx, int ny, int nz, double jitter, uint64_t seed, int ntypes = 2) {
  testutil::Rng rng(seed);
  Config3 c;
  const int nn[3] = {nx, ny, nz};
  const double lo[3] = {-0.7, 0.3, 1.9};
  for (int d = 0; d < 3; ++d) {
    c.box.lo[d] = lo[d];
    c.box.hi[d] = lo[d] + nn[d] * (1.0 + 0.05 * d);
  }
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) {
        const int ijk[3] = {i, j, k};
        for (int d = 0; d < 3; ++d) {
          const double a = c.box.length(d) / nn[d];
          double x = c.box.lo[d] + a * (ijk[d] + 0.5 + jitter * rng.uniform(-1.0, 1.0));
          if (x < c.box.lo[d]) x += c.box.length(d);
          if (x >= c.box.hi[d]) x -= c.box.length(d);
          c.xyz.push_back(x);
        }
        c.type.push_back(rng.below(ntypes));
      }
  return c;
}

// Cubic lattice with conventional cell a: basis sites (fractions of a).
Config3 lattice(int n, double a, const std::vector<std::array<double, 3>> &basis) {
  Config3 c;
  for (int d = 0; d < 3; ++d) {
    c.box.lo[d] = 0.0;
    c.box.hi[d] = n * a;
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto &b : basis) {
          c.xyz.push_back((i + b[0]) * a);
          c.xyz.push_back((j + b[1]) * a);
          c.xyz.push_back((k + b[2]) * a);
          c.type.push_back(0);
        }
  return c;
}
const std::vector<std::array<double, 3>> kBCC = {{0, 0, 0}, {0.5, 0.5, 0.5}};
const std::vector<std::array<double, 3>> kFCC = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};

// Random two-type model with face tensions of both signs.
Model random_model(uint64_t seed, Tension tension = Tension::Edge) {
  testutil::Rng rng(seed);
  Model m(2);
  for (auto &t : m.types) {
    t.K = rng.uniform(0.5, 1.5);
    t.A0 = rng.uniform(0.8, 1.2);
    t.Gamma = rng.uniform(0.05, 0.3);
  }
  m.set_lambda(0, 0, -rng.uniform(0.5, 1.5));
  m.set_lambda(1, 1, -rng.uniform(0.5, 1.5));
  m.set_lambda(0, 1, rng.uniform(0.1, 0.5));
  m.tension = tension;
  return m;
}

double periodic_energy(const Config3 &c, const Model &m) {
  const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
  std::vector<int> ty(t.n_points);
  for (int p = 0; p < t.n_points; ++p) ty[p] = c.type[t.origin[p]];
  return compute_energy_3d(t, ty.data(), m);
}

void wrap(Config3 &c) {
  for (int i = 0; i < c.n(); ++i)
    for (int d = 0; d < 3; ++d) {
      double &x = c.xyz[3 * i + d];
      const double L = c.box.length(d);
      x -= L * std::floor((x - c.box.lo[d]) / L);
      if (x >= c.box.hi[d]) x -= L;
    }
}

// Central-difference check of the forces; returns the largest deviation
// relative to the largest force.
void expect_fd(const Config3 &c0, const Model &m, double h, double rel_tol) {
  std::vector<double> f;
  periodic_forces_3d(c0.box, c0.points(), c0.type.data(), m, f);
  double fmax = 0.0, err = 0.0;
  for (double v : f) fmax = std::max(fmax, std::abs(v));
  ASSERT_GT(fmax, 1e-3);
  for (int i = 0; i < c0.n(); ++i)
    for (int d = 0; d < 3; ++d) {
      Config3 cp = c0, cm = c0;
      cp.xyz[3 * i + d] += h;
      cm.xyz[3 * i + d] -= h;
      wrap(cp);
      wrap(cm);
      const double fd = -(periodic_energy(cp, m) - periodic_energy(cm, m)) / (2 * h);
      err = std::max(err, std::abs(fd - f[3 * i + d]));
    }
  EXPECT_LT(err, rel_tol * fmax) << "max |F - F_fd| = " << err << ", max |F| = " << fmax;
}

}  // namespace

TEST(Voronoi3D, MatchesHalfSpaceClipping) {
  for (uint64_t seed : {1u, 2u, 3u}) {
    const Config3 c = jittered(3, 3, 4, 0.45, seed);
    const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
    const double L[3] = {c.box.length(0), c.box.length(1), c.box.length(2)};
    const auto ref = ref3d::cells(c.xyz, c.box.lo, L);
    double vsum = 0.0;
    for (int i = 0; i < c.n(); ++i) {
      vsum += t.volume[i];
      EXPECT_NEAR(t.volume[i], ref[i].volume, 1e-10) << "cell " << i;
      EXPECT_NEAR(t.surface[i], ref[i].surface, 1e-10) << "cell " << i;
      // Every reference face, by the position of the neighbour across it.
      int matched = 0;
      for (const auto &rf : ref[i].faces) {
        ASSERT_FALSE(rf.box) << "reference cell " << i << " still touches its bounding box";
        const ref3d::P av = ref3d::vector_area(rf.poly);
        const double area = std::sqrt(ref3d::dot(av, av));
        if (area < 1e-9) continue;
        bool found = false;
        for (int f = t.cell_offset[i]; f < t.cell_offset[i + 1]; ++f) {
          const double *q = &t.position[3 * t.face_neighbor[f]];
          if (std::abs(q[0] - rf.neighbour.x) + std::abs(q[1] - rf.neighbour.y) +
                  std::abs(q[2] - rf.neighbour.z) < 1e-9) {
            EXPECT_NEAR(t.face_area[f], area, 1e-10);
            found = true;
          }
        }
        EXPECT_TRUE(found) << "cell " << i << ": reference face not found";
        matched++;
      }
      EXPECT_EQ(t.face_count(i), matched) << "cell " << i;
      for (int f = t.cell_offset[i]; f < t.cell_offset[i + 1]; ++f) EXPECT_GT(t.face_area[f], -1e-12);
    }
    EXPECT_NEAR(vsum, c.box.volume(), 1e-9);
  }
}

TEST(Voronoi3D, BCCTruncatedOctahedra) {
  const double a = 1.3;
  const Config3 c = lattice(3, a, kBCC);
  const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
  // Truncated octahedron of edge l = a / (2 sqrt 2): V = 8 sqrt2 l^3 = a^3/2,
  // S = (6 + 12 sqrt3) l^2.
  const double l = a / (2.0 * std::sqrt(2.0));
  const double V = 8.0 * std::sqrt(2.0) * l * l * l, S = (6.0 + 12.0 * std::sqrt(3.0)) * l * l;
  EXPECT_NEAR(V, a * a * a / 2, 1e-12);
  EXPECT_NEAR(S / std::cbrt(V * V), 5.3147, 5e-5);  // Merkel & Manning's value
  for (int i = 0; i < c.n(); ++i) {
    EXPECT_NEAR(t.volume[i], V, 1e-12);
    EXPECT_NEAR(t.surface[i], S, 1e-12);
    EXPECT_EQ(t.face_count(i), 14);
  }
  // Quadratic energy KV (V - V0)^2 + KS (S - S0)^2: K = 2 KV, Gamma = 2 KS, and
  // the face tension giving S0 (edge form); the model drops the constant KS S0^2.
  const QuadraticParams q{1.7, 1.1, 0.6, 5.0};
  Model m(1);
  m.types[0] = cell_type_from_quadratic(q);
  m.set_lambda(0, 0, lambda_from_quadratic(q, Tension::Edge));
  std::vector<double> f;
  const ForceOutput3 out = periodic_forces_3d(c.box, c.points(), c.type.data(), m, f);
  const double e = c.n() * (q.KA * (V - q.A0) * (V - q.A0) + q.KP * (S - q.P0) * (S - q.P0) - q.KP * q.P0 * q.P0);
  EXPECT_NEAR(out.energy, e, 1e-10 * std::abs(e));
  EXPECT_LT(testutil::max_abs(f), 1e-11);
}

TEST(Voronoi3D, FCCRhombicDodecahedraWithSixFoldVertices) {
  const double a = 1.1;
  const Config3 c = lattice(3, a, kFCC);
  const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
  // Rhombic dodecahedron of edge e = a sqrt3 / 4: V = 16 sqrt3/9 e^3 = a^3/4,
  // S = 8 sqrt2 e^2.
  const double e = a * std::sqrt(3.0) / 4.0;
  const double V = 16.0 * std::sqrt(3.0) / 9.0 * e * e * e, S = 8.0 * std::sqrt(2.0) * e * e;
  EXPECT_NEAR(V, a * a * a / 4, 1e-12);
  EXPECT_NEAR(S / std::cbrt(V * V), 5.3454, 5e-5);
  int zero_faces = 0;
  for (int i = 0; i < c.n(); ++i) {
    EXPECT_NEAR(t.volume[i], V, 1e-12);
    EXPECT_NEAR(t.surface[i], S, 1e-12);
    EXPECT_EQ(t.face_count(i), 12);
    EXPECT_NEAR(t.shape_index(i), S / std::cbrt(V * V), 1e-12);
    zero_faces += t.face_count_total(i) - t.face_count(i);
  }
  // CGAL splits each octahedral hole (six co-spherical centres) into four
  // tetrahedra around one diagonal: a face of area zero.
  EXPECT_GT(zero_faces, 0);
  const QuadraticParams q{1.0, 0.5, 0.3, 5.5};
  Model m(1);
  m.types[0] = cell_type_from_quadratic(q);
  m.set_lambda(0, 0, lambda_from_quadratic(q, Tension::Edge));
  std::vector<double> f;
  const ForceOutput3 out = periodic_forces_3d(c.box, c.points(), c.type.data(), m, f);
  const double en = c.n() * (q.KA * (V - q.A0) * (V - q.A0) + q.KP * (S - q.P0) * (S - q.P0) - q.KP * q.P0 * q.P0);
  EXPECT_NEAR(out.energy, en, 1e-10 * std::abs(en));
  EXPECT_LT(testutil::max_abs(f), 1e-11);
}

TEST(Voronoi3D, ForcesMatchCentralDifferences) {
  for (Tension tn : {Tension::Edge, Tension::Cell}) {
    const Config3 c = jittered(3, 3, 3, 0.4, 7);
    expect_fd(c, random_model(11, tn), 1e-6, 1e-6);
  }
}

// Two cell types on FCC sites: the six-fold vertices stay, the forces do
// not vanish, and they are the derivative of the energy (which is
// continuously differentiable there; see voronoi3d.cpp).
TEST(Voronoi3D, ForcesAtSixFoldVerticesMatchCentralDifferences) {
  Config3 c = lattice(2, 1.0, kFCC);
  testutil::Rng rng(5);
  for (int &ty : c.type) ty = rng.below(2);
  expect_fd(c, random_model(3), 1e-6, 1e-6);
  Config3 b = lattice(2, 1.26, kBCC);
  for (int &ty : b.type) ty = rng.below(2);
  expect_fd(b, random_model(4), 1e-6, 1e-6);
}

TEST(Voronoi3D, ForcesSumToZeroAndVirialIsStrainDerivative) {
  const Config3 c = jittered(3, 3, 3, 0.4, 9);
  const Model m = random_model(12);
  std::vector<double> f;
  const ForceOutput3 out = periodic_forces_3d(c.box, c.points(), c.type.data(), m, f);
  for (int d = 0; d < 3; ++d) {
    double s = 0.0;
    for (int i = 0; i < c.n(); ++i) s += f[3 * i + d];
    EXPECT_NEAR(s, 0.0, 1e-10);
  }
  // dE/d(eps_dd) for x_d -> (1 + eps) x_d (box and centres) equals -W_dd.
  const double h = 1e-6;
  for (int d = 0; d < 3; ++d) {
    auto strained = [&](double eps) {
      Config3 s = c;
      s.box.lo[d] *= 1 + eps;
      s.box.hi[d] *= 1 + eps;
      for (int i = 0; i < s.n(); ++i) s.xyz[3 * i + d] *= 1 + eps;
      return periodic_energy(s, m);
    };
    const double de = (strained(h) - strained(-h)) / (2 * h);
    EXPECT_NEAR(-out.virial[4 * d], de, 1e-6 * (1 + std::abs(de))) << "component " << d;
  }
}

TEST(Voronoi3D, CellEnergiesAddUp) {
  const Config3 c = jittered(3, 3, 3, 0.3, 21);
  const Model m = random_model(2);
  std::vector<double> f, ce;
  const ForceOutput3 out = periodic_forces_3d(c.box, c.points(), c.type.data(), m, f, &ce);
  double s = 0.0;
  for (double e : ce) s += e;
  EXPECT_NEAR(s, out.energy, 1e-10 * (1 + std::abs(s)));
}

TEST(Voronoi3D, CellVirialsAddUpToTheVirial) {
  const Config3 c = jittered(3, 3, 3, 0.35, 23);
  const Model m = random_model(5);
  const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
  std::vector<int> ty(t.n_points);
  for (int p = 0; p < t.n_points; ++p) ty[p] = c.type[t.origin[p]];
  std::vector<double> f(3 * static_cast<size_t>(t.n_points), 0.0), w(9 * static_cast<size_t>(c.n()));
  const Points3 all{t.position.data(), t.n_points, 3};
  const ForceOutput3 out = compute_forces_3d(t, all, ty.data(), m, f.data(), 3, nullptr, w.data());
  for (int a = 0; a < 9; ++a) {
    double sum = 0.0;
    for (int i = 0; i < c.n(); ++i) sum += w[9 * i + a];
    EXPECT_NEAR(sum, out.virial[a], 1e-9 * (1 + std::abs(out.virial[a]))) << "component " << a;
  }
  EXPECT_GT(std::abs(out.virial[0]), 1e-3);
}

TEST(Voronoi3D, BadInputIsNamed) {
  Config3 c = jittered(2, 2, 2, 0.2, 1);
  std::vector<long> ids(c.n());
  for (int i = 0; i < c.n(); ++i) ids[i] = 100 + i;
  Config3 dup = c;
  for (int d = 0; d < 3; ++d) dup.xyz[3 * 5 + d] = dup.xyz[3 * 2 + d];
  try {
    tessellate_periodic_3d(dup.box, dup.points(), ids.data());
    FAIL() << "coincident points accepted";
  } catch (const Error &e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("id 102"), std::string::npos) << msg;
    EXPECT_NE(msg.find("id 105"), std::string::npos) << msg;
  }
  Config3 out = c;
  out.xyz[3 * 3 + 1] = out.box.hi[1] + 0.1;
  EXPECT_THROW(tessellate_periodic_3d(out.box, out.points(), ids.data()), Error);
  std::vector<double> flat = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  EXPECT_THROW(tessellate_local_3d(Points3{flat.data(), 4, 3}, 1), Error);
  // No owned cells (an MPI rank without atoms) is not an error, even with
  // too few points to triangulate.
  const Tessellation3 none = tessellate_local_3d(Points3{flat.data(), 2, 3}, 0);
  EXPECT_EQ(none.n_owned, 0);
  EXPECT_TRUE(none.volume.empty());
  EXPECT_TRUE(check_coverage_3d(none, c.box.lo, c.box.hi).ok);
  Config3 nanc = c;
  nanc.xyz[0] = std::nan("");
  EXPECT_THROW(tessellate_periodic_3d(nanc.box, nanc.points()), Error);
}

// At six-fold vertices CGAL breaks the tie by a symbolic perturbation that
// depends on the coordinates; a rotation of the lattice by 90 degrees about x
// (a symmetry of FCC) changes which tetrahedra it picks (checked below), but
// the forces are the derivative of the energy either way, so they rotate
// with the lattice.
TEST(Voronoi3D, SixFoldForcesDoNotDependOnTheTieBreak) {
  Config3 c = lattice(3, 1.0, kFCC);
  testutil::Rng rng(8);
  for (int &ty : c.type) ty = rng.below(2);
  const Model m = random_model(6);
  Config3 r = c;  // (x, y, z) -> (x, L - z, y), folded into [0, L)
  const double L = c.box.length(0);
  for (int i = 0; i < c.n(); ++i) {
    double y = L - c.xyz[3 * i + 2];
    if (y >= L) y -= L;
    r.xyz[3 * i + 1] = y;
    r.xyz[3 * i + 2] = c.xyz[3 * i + 1];
  }
  // The zero-area faces (pairs of cells touching at a six-fold vertex) differ.
  auto zero_pairs = [](const Config3 &cfg) {
    const Tessellation3 t = tessellate_periodic_3d(cfg.box, cfg.points());
    std::vector<std::pair<int, int>> z;
    for (int i = 0; i < t.n_owned; ++i)
      for (int f = t.cell_offset[i]; f < t.cell_offset[i + 1]; ++f)
        if (!(t.face_area[f] > 1e-9 * t.surface[i])) z.emplace_back(i, t.origin[t.face_neighbor[f]]);
    std::sort(z.begin(), z.end());
    return z;
  };
  const auto zc = zero_pairs(c), zr = zero_pairs(r);
  ASSERT_FALSE(zc.empty());
  EXPECT_NE(zc, zr) << "the rotation did not change CGAL's tie-break; the test shows nothing";
  std::vector<double> f, g;
  periodic_forces_3d(c.box, c.points(), c.type.data(), m, f);
  periodic_forces_3d(r.box, r.points(), r.type.data(), m, g);
  ASSERT_GT(testutil::max_abs(f), 1e-3);
  for (int i = 0; i < c.n(); ++i) {
    EXPECT_NEAR(g[3 * i], f[3 * i], 1e-11) << "atom " << i;
    EXPECT_NEAR(g[3 * i + 1], -f[3 * i + 2], 1e-11) << "atom " << i;
    EXPECT_NEAR(g[3 * i + 2], f[3 * i + 1], 1e-11) << "atom " << i;
  }
}

namespace {

// A jittered simple-cubic arrangement in a triclinic box (tilts in units of
// the box lengths), wrapped into the box.
Config3 jittered_triclinic(int m, double txy, double txz, double tyz, uint64_t seed) {
  testutil::Rng rng(seed);
  Config3 c;
  const double lo[3] = {-0.4, 1.3, 0.2};
  for (int d = 0; d < 3; ++d) {
    c.box.lo[d] = lo[d];
    c.box.hi[d] = lo[d] + m * (1.0 + 0.07 * d);
  }
  c.box.xy = txy * c.box.length(0);
  c.box.xz = txz * c.box.length(0);
  c.box.yz = tyz * c.box.length(1);
  const Region3 r = c.box.region();
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        double s[3] = {(i + 0.5 + 0.4 * rng.uniform(-1, 1)) / m, (j + 0.5 + 0.4 * rng.uniform(-1, 1)) / m,
                       (k + 0.5 + 0.4 * rng.uniform(-1, 1)) / m};
        for (double &v : s) v -= std::floor(v);
        for (int d = 0; d < 3; ++d) c.xyz.push_back(r.o[d] + s[0] * r.a[d] + s[1] * r.b[d] + s[2] * r.c[d]);
        c.type.push_back(rng.below(2));
      }
  return c;
}

}  // namespace

TEST(Voronoi3DTriclinic, MatchesHalfSpaceClipping) {
  const Config3 c = jittered_triclinic(3, 0.3, -0.2, 0.25, 31);
  const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
  const Region3 r = c.box.region();
  const ref3d::P e[3] = {{r.a[0], r.a[1], r.a[2]}, {r.b[0], r.b[1], r.b[2]}, {r.c[0], r.c[1], r.c[2]}};
  const auto ref = ref3d::cells(c.xyz, e);
  double vsum = 0.0;
  for (int i = 0; i < c.n(); ++i) {
    vsum += t.volume[i];
    EXPECT_NEAR(t.volume[i], ref[i].volume, 1e-10) << "cell " << i;
    EXPECT_NEAR(t.surface[i], ref[i].surface, 1e-10) << "cell " << i;
    int faces = 0;
    for (const auto &rf : ref[i].faces) {
      ASSERT_FALSE(rf.box);
      const ref3d::P av = ref3d::vector_area(rf.poly);
      faces += std::sqrt(ref3d::dot(av, av)) > 1e-9;
    }
    EXPECT_EQ(t.face_count(i), faces) << "cell " << i;
  }
  EXPECT_NEAR(vsum, c.box.volume(), 1e-9);
}

TEST(Voronoi3DTriclinic, ForcesMatchCentralDifferences) {
  const Config3 c = jittered_triclinic(3, -0.25, 0.3, 0.2, 32);
  const Model m = random_model(13);
  std::vector<double> f;
  periodic_forces_3d(c.box, c.points(), c.type.data(), m, f);
  const double h = 1e-6;
  double err = 0.0;
  auto wrapped = [&](Config3 x) {
    const Region3 r = x.box.region();
    for (int i = 0; i < x.n(); ++i) {
      double s[3];
      x.box.fractional(&x.xyz[3 * i], s);
      for (double &v : s) v -= std::floor(v);
      for (int d = 0; d < 3; ++d) x.xyz[3 * i + d] = r.o[d] + s[0] * r.a[d] + s[1] * r.b[d] + s[2] * r.c[d];
    }
    return x;
  };
  for (int i = 0; i < c.n(); ++i)
    for (int d = 0; d < 3; ++d) {
      Config3 cp = c, cm = c;
      cp.xyz[3 * i + d] += h;
      cm.xyz[3 * i + d] -= h;
      const double fd = -(periodic_energy(wrapped(cp), m) - periodic_energy(wrapped(cm), m)) / (2 * h);
      err = std::max(err, std::abs(fd - f[3 * i + d]));
    }
  EXPECT_LT(err, 1e-6 * testutil::max_abs(f));
  EXPECT_GT(testutil::max_abs(f), 1e-3);
}

// Simple shear x -> x + g y (box tilt xy += g ly): dE/dg = -W_yx, and the
// same for x -> x + g z (xz) and y -> y + g z (yz); the virial is symmetric.
TEST(Voronoi3DTriclinic, ShearVirialIsStrainDerivative) {
  const Config3 c = jittered_triclinic(3, 0.1, 0.05, -0.1, 33);
  const Model m = random_model(14);
  std::vector<double> f;
  const ForceOutput3 out = periodic_forces_3d(c.box, c.points(), c.type.data(), m, f);
  const double h = 1e-6;
  // (a, b): x_a += g x_b
  const int pairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (const auto &ab : pairs) {
    const int a = ab[0], b = ab[1];
    auto sheared = [&](double g) {
      Config3 s = c;
      for (int i = 0; i < s.n(); ++i) s.xyz[3 * i + a] += g * (s.xyz[3 * i + b] - s.box.lo[b]);
      // the edge vectors (lx,0,0), (xy,ly,0), (xz,yz,lz) deform alike
      if (a == 0 && b == 1) {
        s.box.xy += g * s.box.length(1);
        s.box.xz += g * s.box.yz;
      }
      if (a == 0 && b == 2) s.box.xz += g * s.box.length(2);
      if (a == 1 && b == 2) s.box.yz += g * s.box.length(2);
      return periodic_energy(s, m);
    };
    const double de = (sheared(h) - sheared(-h)) / (2 * h);
    EXPECT_NEAR(-out.virial[3 * b + a], de, 1e-6 * (1 + std::abs(de))) << a << b;
    EXPECT_NEAR(out.virial[3 * b + a], out.virial[3 * a + b], 1e-8 * (1 + std::abs(de)));
  }
}
