// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Reliability of the 3D path on co-spherical lattices (SC, FCC) in tilted
// boxes (slivers), what 3D does at four-fold Voronoi edges, and overflow;
// at the end the 2D (confluent) rounded co-circular rosette far from the
// origin.

#include "reference3d.h"
#include "test_util.h"

#include "tessera/energy.h"
#include "tessera/tessellation.h"
#include "tessera/mesh3d.h"
#include "tessera/voronoi3d.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

using namespace tessera;

namespace {

struct Lattice3 {
  Box3 box;
  std::vector<double> xyz;
  std::vector<int> type;
  int n() const { return static_cast<int>(xyz.size() / 3); }
  Points3 points() const { return Points3{xyz.data(), n(), 3}; }
};

const std::vector<std::array<double, 3>> kSC = {{0, 0, 0}};
const std::vector<std::array<double, 3>> kFCC = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};

// Wrap x into the (possibly tilted) box by whole edge vectors (exact for
// dyadic coordinates; otherwise rounded like any wrapped coordinate).
void wrap_into(const Box3 &box, double *x) {
  const Region3 r = box.region();
  const double *e[3] = {r.a, r.b, r.c};
  for (int pass = 0; pass < 8; ++pass) {
    double s[3];
    box.fractional(x, s);
    bool inside = true;
    for (int k = 2; k >= 0; --k) {
      const double m = s[k] < 0.0 ? -1.0 : s[k] >= 1.0 ? 1.0 : 0.0;
      if (m == 0.0) continue;
      inside = false;
      for (int d = 0; d < 3; ++d) x[d] -= m * e[k][d];
      break;
    }
    if (inside) return;
  }
}

// m^3 conventional cells of edge a, lower corner at lo, tilt xy (the lattice
// itself is not sheared: with xy a lattice vector's x component the box is
// still a period of the lattice).  Sites wrapped into the tilted box.
Lattice3 lattice(int m, double a, const std::vector<std::array<double, 3>> &basis, double xy,
                 double lo = 0.0) {
  Lattice3 c;
  for (int d = 0; d < 3; ++d) {
    c.box.lo[d] = lo;
    c.box.hi[d] = lo + m * a;
  }
  c.box.xy = xy;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k)
        for (const auto &b : basis) {
          double x[3] = {lo + (i + b[0]) * a, lo + (j + b[1]) * a, lo + (k + b[2]) * a};
          wrap_into(c.box, x);
          c.xyz.insert(c.xyz.end(), x, x + 3);
          c.type.push_back(0);
        }
  return c;
}

double energy_of(const Lattice3 &c, const Model &m) {
  std::vector<double> f;
  return periodic_forces_3d(c.box, c.points(), c.type.data(), m, f).energy;
}

Model one_type() {
  Model m(1);
  m.types[0].K = 1.0;
  m.types[0].A0 = 0.9;
  m.types[0].Gamma = 0.2;
  m.set_lambda(0, 0, -0.5);
  return m;
}

}  // namespace

// Uniform lattices whose box is a period of the lattice: every cell is the
// same polyhedron, so each volume is V/N (the orthogonal box's value) and,
// as the lattice has inversion symmetry about every site, every force is 0.
// With the lower corner at 0.3 the coordinates are rounded, and CGAL
// triangulates FCC's octahedral holes (six co-spherical centres) with flat
// tetrahedra (slivers) whose circumcentres are round-off: before slivers of
// co-spherical points were dropped from the faces, the forces were 1e-2 and
// with xy = 0.5 (sheared lattice) the volumes NaN.
TEST(Reliability3D, TiltedFCCLatticeHasZeroForcesAndEqualCells) {
  const Model m = one_type();
  // (With lo = 0.3 and xy = -1 some sites have no representable position
  // inside the box: wrapping rounds them across the face and back.)
  const double cases[][2] = {{0.0, 1.0}, {0.0, -1.0}, {0.0, 2.0}, {0.3, 1.0},
                             {0.3, 2.0}, {-1.7, 1.0}, {-1.7, 2.0}, {100.1, 1.0}};
  for (const auto &lx : cases) {
    const double lo = lx[0], xy = lx[1];
    const Lattice3 c = lattice(3, 1.0, kFCC, xy, lo);
      const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
      double vsum = 0.0;
      for (int i = 0; i < c.n(); ++i) {
        vsum += t.volume[i];
        ASSERT_NEAR(t.volume[i], 0.25, 1e-12) << "lo " << lo << " xy " << xy << " cell " << i;
        // Rhombic dodecahedron of edge sqrt3/4: S = 8 sqrt2 e^2.
        ASSERT_NEAR(t.surface[i], 8.0 * std::sqrt(2.0) * 3.0 / 16.0, 1e-12);
        ASSERT_EQ(t.face_count(i), 12);
      }
      EXPECT_NEAR(vsum, c.box.volume(), 1e-10);
      std::vector<double> f;
      periodic_forces_3d(c.box, c.points(), c.type.data(), m, f);
      EXPECT_LT(testutil::max_abs(f), 1e-10) << "lo " << lo << " xy " << xy;
  }
}

// The lattice sheared with the box (sites at fixed fractional coordinates,
// tilt xy = 0.5): a Bravais lattice, so all cells have volume V/N, and they
// tile the box.  The shear keeps the squares of sites in the xz planes,
// four-fold Voronoi edges where the energy has a kink; with the mean of the
// branches there every site has the same force, so the forces are 0 (they
// were not before that rule; see MultifoldEdges below).
TEST(Reliability3D, ShearedLatticeCellsAreEqual) {
  for (const auto *basis : {&kFCC, &kSC})
    for (double lo : {0.0, 0.3}) {
      Lattice3 c;
      for (int d = 0; d < 3; ++d) {
        c.box.lo[d] = lo;
        c.box.hi[d] = lo + 3.0;
      }
      c.box.xy = 0.5;
      const Region3 r = c.box.region();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          for (int k = 0; k < 3; ++k)
            for (const auto &b : *basis) {
              const double s[3] = {(i + b[0] + 0.25) / 3.0, (j + b[1] + 0.25) / 3.0, (k + b[2] + 0.25) / 3.0};
              double x[3];
              for (int d = 0; d < 3; ++d) x[d] = r.o[d] + s[0] * r.a[d] + s[1] * r.b[d] + s[2] * r.c[d];
              wrap_into(c.box, x);
              c.xyz.insert(c.xyz.end(), x, x + 3);
              c.type.push_back(0);
            }
      const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
      const double v0 = c.box.volume() / c.n();
      double vsum = 0.0;
      for (int i = 0; i < c.n(); ++i) {
        vsum += t.volume[i];
        ASSERT_NEAR(t.volume[i], v0, 1e-12) << "cell " << i;
        ASSERT_NEAR(t.surface[i], t.surface[0], 1e-12) << "cell " << i;
      }
      EXPECT_NEAR(vsum, c.box.volume(), 1e-10);
      std::vector<double> f;
      periodic_forces_3d(c.box, c.points(), c.type.data(), one_type(), f);
      EXPECT_LT(testutil::max_abs(f), 1e-10) << (basis == &kSC ? "SC" : "FCC") << " lo " << lo;
    }
}

// FCC in a tilted box with rounded coordinates, jittered by 1e-9, two cell
// types: forces are the central differences of the energy (which is
// continuously differentiable at FCC's six-fold vertices).  (The jitter
// already breaks the exact ties, so this passed before the sliver fix too;
// it guards the fix's tolerances, which must not swallow real geometry.)
TEST(Reliability3D, JitteredTiltedFCCForcesMatchCentralDifferences) {
  const Model m = testutil::two_types_fixed(0.24, 0.27);
  Lattice3 c = lattice(3, 1.0, kFCC, 1.0, 0.3);
  testutil::Rng rng(17);
  for (int &ty : c.type) ty = rng.below(2);
  for (double &x : c.xyz) x += 1e-9 * rng.uniform(-1.0, 1.0);
  for (int i = 0; i < c.n(); ++i) wrap_into(c.box, &c.xyz[3 * i]);
  std::vector<double> f;
  periodic_forces_3d(c.box, c.points(), c.type.data(), m, f);
  const double fmax = testutil::max_abs(f);
  ASSERT_GT(fmax, 1e-2);
  const double h = 1e-6;
  double err = 0.0;
  for (int k = 0; k < 40; ++k) {
    const int q = rng.below(3 * c.n());
    Lattice3 p = c, n = c;
    p.xyz[q] += h;
    n.xyz[q] -= h;
    wrap_into(p.box, &p.xyz[q - q % 3]);
    wrap_into(n.box, &n.xyz[q - q % 3]);
    const double fd = -(energy_of(p, m) - energy_of(n, m)) / (2 * h);
    err = std::max(err, std::abs(fd - f[q]));
  }
  EXPECT_LT(err, 1e-6 * fmax) << "max |F - F_fd| = " << err << ", max |F| = " << fmax;
}

// The local path (tessellate_local_3d with a ghost shell, as LAMMPS calls it)
// shares the cause: FCC sites in a box tilted by xy = 0.5 (not a period of
// the lattice, so the cells differ) with rounded coordinates, ghosts out to
// 1.5 in a parallelepiped shell; the cells must match half-space clipping
// (reference3d.h) and the coverage check must pass.  Before, a sliver's
// round-off circumcentre made volumes NaN.
TEST(Reliability3D, LocalPathWithTriclinicRegionMatchesClipping) {
  const Lattice3 c = lattice(3, 1.0, kFCC, 0.5, 0.3);
  const Region3 r = c.box.region();
  std::vector<double> all = c.xyz;
  const double margin = 1.5;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int d = -1; d <= 1; ++d) {
        if (a == 0 && b == 0 && d == 0) continue;
        for (int i = 0; i < c.n(); ++i) {
          double x[3];
          for (int k = 0; k < 3; ++k) x[k] = c.xyz[3 * i + k] + a * r.a[k] + b * r.b[k] + d * r.c[k];
          // keep images within `margin` of the box (perpendicular distance,
          // enough here: the box is close to a cube)
          double s[3];
          c.box.fractional(x, s);
          bool in = true;
          for (int k = 0; k < 3; ++k) in = in && s[k] > -margin / 3.0 && s[k] < 1.0 + margin / 3.0;
          if (in) all.insert(all.end(), x, x + 3);
        }
      }
  const Points3 pts{all.data(), static_cast<int>(all.size() / 3), 3};
  const Tessellation3 t = tessellate_local_3d(pts, c.n());
  const Coverage cov = check_coverage_3d(t, r, 1.3);
  EXPECT_TRUE(cov.ok) << "needs " << cov.needed_margin << " more";
  const ref3d::P e[3] = {{r.a[0], r.a[1], r.a[2]}, {r.b[0], r.b[1], r.b[2]}, {r.c[0], r.c[1], r.c[2]}};
  const auto ref = ref3d::cells(c.xyz, e);
  double vsum = 0.0;
  for (int i = 0; i < c.n(); ++i) {
    vsum += t.volume[i];
    EXPECT_NEAR(t.volume[i], ref[i].volume, 1e-10) << "cell " << i;
    EXPECT_NEAR(t.surface[i], ref[i].surface, 1e-10) << "cell " << i;
  }
  EXPECT_NEAR(vsum, c.box.volume(), 1e-9);
}

// Energies beyond double's range: an Error naming the cell and the value
// (not inf or NaN), from compute_forces_3d and compute_energy_3d; also when
// every cell's energy is finite but their sum is not.
TEST(Reliability3D, EnergyOverflowIsAnError) {
  const Lattice3 c = lattice(2, 1.0, kFCC, 0.0);
  const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
  std::vector<int> ty(t.n_points, 0);
  const Points3 all{t.position.data(), t.n_points, 3};
  std::vector<double> f(3 * static_cast<size_t>(t.n_points), 0.0);
  Model m = one_type();
  m.types[0].Gamma = 1e308;  // Gamma/2 S^2 with S = 2.6
  for (int which = 0; which < 2; ++which) {
    try {
      if (which == 0)
        compute_forces_3d(t, all, ty.data(), m, f.data(), 3);
      else
        compute_energy_3d(t, ty.data(), m);
      ADD_FAILURE() << "no error";
    } catch (const Error &e) {
      const std::string s = e.what();
      EXPECT_NE(s.find("energy of the cell of point 0"), std::string::npos) << s;
      EXPECT_NE(s.find("inf"), std::string::npos) << s;
      EXPECT_NE(s.find("far outside reduced units"), std::string::npos) << s;
    }
  }
  // K/2 (V - V0)^2 = 0.5 * 1.7e308 * 0.75^2 = 4.8e307 per cell, 32 cells.
  m.types[0].Gamma = 0.0;
  m.types[0].K = 1.7e308;
  m.types[0].A0 = 1.0;
  try {
    compute_energy_3d(t, ty.data(), m);
    ADD_FAILURE() << "no error";
  } catch (const Error &e) {
    EXPECT_NE(std::string(e.what()).find("total energy"), std::string::npos) << e.what();
  }
  EXPECT_THROW(compute_forces_3d(t, all, ty.data(), m, f.data(), 3), Error);
}

// Found by Fuzz3D: a simple-cubic arrangement jittered by 1e-10 in a box
// with arbitrary tilts.  CGAL's triangulation holds slivers (flatness 5e-11)
// that are real Voronoi vertices (on four-fold edges, not co-spherical with
// a neighbour); the circumcentre formula lost eps/flatness of their radius,
// which put their vertices 5e-8 off the faces' bisector planes, so a face
// had two different areas seen from its two cells and the volumes did not
// tile the box (error 1.6e-9 of it).  Sliver circumcentres are now exact.
TEST(Reliability3D, SliverCircumcentresAreExact) {
  Lattice3 c;
  for (int d = 0; d < 3; ++d) {
    c.box.lo[d] = -3.6701161548697527;
    c.box.hi[d] = -0.10776206000552024;
  }
  c.box.xy = 0.94534853994367918;
  c.box.yz = -0.5371346307860223;
  c.xyz = {-0.107762060128898,   -3.6701161547548891, -3.6701161548096661, -0.10776206008609845,
           -3.6701161549499437,  -1.8889391074336914, -0.10776206011517164, -2.426073738293268,
           -0.10776206002668776, -0.1077620600245246, -1.8889391073361359, -1.8889391074999917,
           -0.94359056737818503, -0.10776206005234013, -3.670116154800469,  -1.8889391074143835,
           -3.6701161549797816,  -1.8889391075284323, -1.8889391073227453, -2.426073738285607,
           -0.10776206007886868, -1.8889391073235646, -1.8889391074479687, -1.8889391073595172};
  const Tessellation3 t = tessellate_periodic_3d(c.box, c.points());
  const Region3 r = c.box.region();
  const ref3d::P e[3] = {{r.a[0], r.a[1], r.a[2]}, {r.b[0], r.b[1], r.b[2]}, {r.c[0], r.c[1], r.c[2]}};
  const auto ref = ref3d::cells(c.xyz, e);
  double vsum = 0.0;
  for (int i = 0; i < c.n(); ++i) {
    vsum += t.volume[i];
    EXPECT_NEAR(t.volume[i], ref[i].volume, 1e-12) << "cell " << i;
    EXPECT_NEAR(t.surface[i], ref[i].surface, 1e-11) << "cell " << i;
  }
  EXPECT_NEAR(vsum, c.box.volume(), 1e-12);
  // Every vertex of every face is equidistant from the face's two centres.
  for (int i = 0; i < c.n(); ++i)
    for (int f = t.cell_offset[i]; f < t.cell_offset[i + 1]; ++f)
      for (int k = t.face_offset[f]; k < t.face_offset[f + 1]; ++k) {
        const Vec3 &h = t.vertices[t.face_vertex[k]];
        const double *a = &t.position[3 * i], *b = &t.position[3 * t.face_neighbor[f]];
        const double da = std::hypot(h.x - a[0], h.y - a[1], h.z - a[2]);
        const double db = std::hypot(h.x - b[0], h.y - b[1], h.z - b[2]);
        ASSERT_NEAR(da, db, 1e-12) << "cell " << i << " face " << f;
      }
}

// Four-fold Voronoi edges (four co-circular, coplanar centres: every square
// of a simple cubic lattice).  The energy has a kink there: a perturbation
// opens a thin face of area ~ |edge| e between one diagonal pair or the
// other, and the surfaces change at first order.  The force takes the mean
// of the two branches at each such edge (doc/model.md, "Four-fold edges
// (3D)").  Moving one site along a coordinate crosses the kinks of all the
// squares it is a corner of, each from one branch to the other, so the
// force is the mean of the one-sided derivatives: the central difference.
// Tested on a two-type lattice (exact coordinates, orthogonal box):
// (a) the true energy has kinks (one-sided differences disagree);
// (b) the force is their mean.  (Before the rule the force was the exact
// gradient of the branch CGAL's tie-break chose, which matched neither.)
TEST(Reliability3D, MultifoldEdgesForceIsTheMeanOfTheOneSidedDerivatives) {
  Lattice3 c = lattice(3, 1.0, kSC, 0.0);
  testutil::Rng rng(23);
  for (int &ty : c.type) ty = rng.below(2);
  const Model m = testutil::two_types_fixed(0.24, 0.27);
  std::vector<double> f;
  periodic_forces_3d(c.box, c.points(), c.type.data(), m, f);
  const double h = 1e-6, e0 = energy_of(c, m);
  int kinks = 0;
  double err = 0.0, jump = 0.0;
  for (int k = 0; k < 24; ++k) {
    const int q = rng.below(3 * c.n());
    Lattice3 p = c, n = c;
    p.xyz[q] += h;
    n.xyz[q] -= h;
    wrap_into(p.box, &p.xyz[q - q % 3]);
    wrap_into(n.box, &n.xyz[q - q % 3]);
    const double right = -(energy_of(p, m) - e0) / h, left = -(e0 - energy_of(n, m)) / h;
    kinks += std::abs(right - left) > 1e-3;
    jump = std::max(jump, std::abs(right - left));
    err = std::max(err, std::abs(0.5 * (right + left) - f[q]));
  }
  EXPECT_GT(kinks, 0) << "no kink seen: the lattice has no four-fold edges?";
  EXPECT_LT(err, 1e-6 * testutil::max_abs(f)) << "one-sided derivatives differ by up to " << jump;
}

// Confluent 2D: 23 centres on a circle of radius 1.8 around x = 1e7.  The
// coordinates are rounded to 2e-9, and the circumcentres of the fan
// triangles (three neighbouring points of the circle: nearly collinear)
// scatter by up to 2e-8, far beyond 1e-10 of the circumradius.  The
// multifold-vertex tolerance counts each circumcentre's error bound (which
// grows with the coordinates' magnitude and the triangle's flatness), so
// the whole ring is one vertex and every cell around it takes the same
// branches; the forces then sum to zero.  (With the tolerance 1e-10 of the
// radius alone only some triangles were grouped, rings of 4 and 8 instead
// of one of 23, and the forces summed to 5e-4 of sum |F|.)  More in
// test_rosettes.cpp.
TEST(Confluent2D, RoundedRosetteForcesSumToZero) {
  for (double X : {0.0, 1e5, 1e7})
    for (int k : {7, 12, 23}) {
      const double R = 1.8, pi = 3.141592653589793;
      const Box box = Box::rect(X - 3.0, X + 3.0, -3.0, 3.0);
      std::vector<double> xy;
      std::vector<int> type;
      for (int i = 0; i < k; ++i) {
        xy.push_back(X + R * std::cos(2 * pi * i / k));
        xy.push_back(R * std::sin(2 * pi * i / k));
        type.push_back(i % 2);
      }
      Model m(2);
      m.types[0].K = 1.0;
      m.types[0].A0 = 36.0 / k;
      m.types[0].Gamma = 0.1;
      m.types[1] = m.types[0];
      m.set_lambda(0, 0, -0.2);
      m.set_lambda(1, 1, -0.3);
      m.set_lambda(0, 1, 0.4);
      std::vector<double> f;
      periodic_forces(box, Points{xy.data(), k, 2}, type.data(), m, f);
      double sx = 0.0, sy = 0.0, sa = 0.0;
      for (int i = 0; i < k; ++i) {
        sx += f[2 * i];
        sy += f[2 * i + 1];
        sa += std::abs(f[2 * i]) + std::abs(f[2 * i + 1]);
      }
      EXPECT_LT(std::hypot(sx, sy), 1e-9 * sa) << "x " << X << ", " << k << " centres";
    }
}

// Two centres 1e-8 .. 1e-15 apart in a simple cubic tissue (whose
// co-spherical cubes make the pair pass for a four-fold edge) used to give
// NaN forces blamed on an unrelated point; now both builders (CGAL's and
// Mesh3's, from scratch and after flips) refuse them, naming both points
// and their distance, and 1e-5 apart gives finite forces.
TEST(Reliability3D, NearlyCoincidentCentresAreRefusedByEveryPath) {
  Box3 box;
  for (int d = 0; d < 3; ++d) box.lo[d] = 0.0, box.hi[d] = 4.0;
  auto tissue = [](double dist) {
    std::vector<double> x;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 4; ++k) x.insert(x.end(), {i + 0.0, j + 0.0, k + 0.0});
    x.insert(x.end(), {1.3, 1.2, 1.1, 1.3 + dist, 1.2, 1.1});
    return x;
  };
  Model m(1);
  m.types[0] = {1.0, 1.0, 0.2};
  m.set_lambda(0, 0, -1.6);
  std::vector<int> type(66, 0);
  for (double dist : {1e-8, 1e-13, 1e-15}) {
    SCOPED_TRACE(dist);
    const std::vector<double> x = tissue(dist);
    const Points3 pts{x.data(), 66, 3};
    std::vector<double> f;
    std::string what;
    try {
      periodic_forces_3d(box, pts, type.data(), m, f);
    } catch (const Error &e) {
      what = e.what();
    }
    EXPECT_NE(what.find("nearly coincide"), std::string::npos) << what;
    EXPECT_NE(what.find("point 64 at (1.3, 1.2, 1.1"), std::string::npos) << what;
    EXPECT_NE(what.find("point 65 at (1.3"), std::string::npos) << what;
    // Mesh3 on the same points without periodicity (owned: the 64 lattice
    // points and the pair, which lie inside): from scratch, and after a
    // move that brings the pair from 1e-3 to dist (advance() then asks for
    // a rebuild, which names them).
    Mesh3 mesh;
    Tessellation3 t;
    EXPECT_THROW(
        {
          mesh.build(pts);
          mesh.cells(pts, 66, t, nullptr, false);
        },
        Error);
    std::vector<double> y = tissue(1e-3);
    const Points3 qts{y.data(), 66, 3};
    mesh.build(qts);
    mesh.cells(qts, 66, t, nullptr, false);
    y[3 * 65] = 1.3 + dist;
    const double lo[3] = {-10, -10, -10}, hi[3] = {10, 10, 10};
    EXPECT_FALSE(mesh.advance(qts, 66, lo, hi, t));
  }
  const std::vector<double> x = tissue(1e-5);
  std::vector<double> f;
  periodic_forces_3d(box, Points3{x.data(), 66, 3}, type.data(), m, f);
  for (double v : f) ASSERT_TRUE(std::isfinite(v));
}
