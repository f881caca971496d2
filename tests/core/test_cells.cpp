// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The cell views (tessera/cells.h) against analytic shapes: rectangles and
// boxes from stretched lattices (second moments a^3 b / 12, long axis along
// the longer side), regular hexagons and truncated octahedra (isotropic, no
// principal axis), an isolated finite cell (a disc) and a finite doublet (a
// disc cut by a chord: the centroid of a disc less a circular segment).
// Every view must also close each cell's pieces into its boundary.

#include "tessera/cells.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace tessera;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A jitter-free lattice of nx x ny points with spacings a, b (rectangles),
// in a periodic box, tessellated with periodic images.
struct Rect2 {
  std::vector<double> xy;
  Tessellation t;
  ConfluentCells view;
  Rect2(int nx, int ny, double a, double b, double shift_x = 0.0) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        double x = (i + 0.5) * a + (j % 2) * shift_x;
        x -= nx * a * std::floor(x / (nx * a));
        xy.push_back(x);
        xy.push_back((j + 0.5) * b);
      }
    Box box = Box::rect(0, nx * a, 0, ny * b);
    t = tessellate_periodic(box, Points{xy.data(), nx * ny, 2});
    view.bind(t, Points{&t.position[0].x, t.n_points, 2});
  }
};

}  // namespace

TEST(CellView, RectanglesHaveTheirSecondMomentsAndLongAxis) {
  const double a = 1.7, b = 0.9;
  Rect2 r(4, 6, a, b);
  const CellView &v = r.view;
  ASSERT_EQ(v.dimension(), 2);
  ASSERT_EQ(v.n_owned(), 24);
  for (int c = 0; c < v.n_owned(); ++c) {
    double x[2], p[2], m[4], ax[2];
    v.point(c, p);
    v.centroid(c, x);
    EXPECT_NEAR(x[0], p[0], 1e-12);
    EXPECT_NEAR(x[1], p[1], 1e-12);
    v.second_moments(c, m);
    EXPECT_NEAR(m[0], a * a * a * b / 12.0, 1e-12);
    EXPECT_NEAR(m[3], a * b * b * b / 12.0, 1e-12);
    EXPECT_NEAR(m[1], 0.0, 1e-12);
    EXPECT_NEAR(m[2], 0.0, 1e-12);
    ASSERT_TRUE(v.principal_axis(c, true, ax));
    EXPECT_NEAR(std::fabs(ax[0]), 1.0, 1e-12);
    ASSERT_TRUE(v.principal_axis(c, false, ax));
    EXPECT_NEAR(std::fabs(ax[1]), 1.0, 1e-12);
    EXPECT_EQ(v.coordination_number(c), 4);  // zero-length edges of 4-fold vertices left out
    EXPECT_NEAR(v.shape_index(c), 2 * (a + b) / std::sqrt(a * b), 1e-12);
  }
  EXPECT_GT(v.multifold_count(), 0);  // every vertex of a rectangular lattice is 4-fold
  std::vector<int> ring;
  v.multifold_ring(0, ring);
  EXPECT_EQ(ring.size(), 4u);
}

TEST(CellView, PiecesCloseIntoTheBoundary) {
  Rect2 r(5, 6, 1.0, std::sqrt(3.0) / 2.0, 0.5);  // hexagonal lattice
  const CellView &v = r.view;
  std::vector<double> xyz;
  for (int c = 0; c < v.n_owned(); ++c) {
    double len = 0.0;
    for (int k = v.piece_begin(c); k < v.piece_end(c); ++k) {
      xyz.clear();
      ASSERT_EQ(v.piece_corners(k, xyz), 2);
      EXPECT_NEAR(std::hypot(xyz[2] - xyz[0], xyz[3] - xyz[1]), v.piece_size(k), 1e-12);
      len += v.piece_size(k);
      const int next = k + 1 < v.piece_end(c) ? k + 1 : v.piece_begin(c);
      std::vector<double> n;
      v.piece_corners(next, n);
      EXPECT_NEAR(n[0], xyz[2], 1e-12);
      EXPECT_NEAR(n[1], xyz[3], 1e-12);
    }
    EXPECT_NEAR(len, v.boundary(c), 1e-12);
    double ax[2];
    EXPECT_FALSE(v.principal_axis(c, true, ax));  // a regular hexagon is isotropic
    EXPECT_NEAR(v.shape_index(c), std::sqrt(8.0 * std::sqrt(3.0)), 1e-9);
    EXPECT_EQ(v.coordination_number(c), 6);
  }
  const Contacts ct = v.contacts();
  EXPECT_EQ(ct.n_owned, v.n_owned());
  EXPECT_EQ(ct.offset[ct.n_owned], v.piece_end(v.n_owned() - 1));
}

TEST(CellView, FiniteDiscAndDoublet) {
  const double r = 0.8, d = 1.1;
  // One isolated cell: a disc.
  {
    std::vector<double> xy = {0.3, -0.2};
    Points pts{xy.data(), 1, 2};
    FiniteTessellation ft = finite_tessellate(pts, 1, r);
    Tessellation con;
    finite_contacts(ft, con);
    FiniteCells v;
    v.bind(ft, con, pts);
    double x[2], m[4], ax[2];
    v.centroid(0, x);
    EXPECT_NEAR(x[0], 0.3, 1e-14);
    EXPECT_NEAR(x[1], -0.2, 1e-14);
    v.second_moments(0, m);
    EXPECT_NEAR(m[0], kPi * r * r * r * r / 4.0, 1e-13);
    EXPECT_NEAR(m[3], kPi * r * r * r * r / 4.0, 1e-13);
    EXPECT_NEAR(m[1], 0.0, 1e-13);
    EXPECT_FALSE(v.principal_axis(0, true, ax));
    EXPECT_NEAR(v.free_length(0), 2 * kPi * r, 1e-13);
    EXPECT_TRUE(v.at_edge(0));
    EXPECT_EQ(v.coordination_number(0), 0);
  }
  // A doublet along x: each cell is the disc less the segment beyond x = d/2.
  std::vector<double> xy = {0.0, 0.0, d, 0.0};
  Points pts{xy.data(), 2, 2};
  FiniteTessellation ft = finite_tessellate(pts, 2, r);
  Tessellation con;
  finite_contacts(ft, con);
  FiniteCells v;
  v.bind(ft, con, pts);
  const double h = 0.5 * d, s = std::sqrt(r * r - h * h);
  const double seg = r * r * std::acos(h / r) - h * s;
  const double area = kPi * r * r - seg;
  const double xc = -(2.0 / 3.0) * s * s * s / area;  // moment of the segment removed
  double x[2], ax[2];
  v.centroid(0, x);
  EXPECT_NEAR(v.measure(0), area, 1e-13);
  EXPECT_NEAR(x[0], xc, 1e-13);
  EXPECT_NEAR(x[1], 0.0, 1e-13);
  v.centroid(1, x);
  EXPECT_NEAR(x[0], d - xc, 1e-13);
  // Cut across x, the cell is longer along y.
  ASSERT_TRUE(v.principal_axis(0, true, ax));
  EXPECT_NEAR(std::fabs(ax[1]), 1.0, 1e-12);
  EXPECT_EQ(v.coordination_number(0), 1);
  int arcs = 0;
  double phi, theta, len = 0.0;
  for (int k = v.piece_begin(0); k < v.piece_end(0); ++k) {
    arcs += v.piece_arc(k, phi, theta);
    len += v.piece_size(k);
  }
  EXPECT_EQ(arcs, 1);
  EXPECT_NEAR(len, v.boundary(0), 1e-13);
  EXPECT_NEAR(v.free_length(0), 2 * r * (kPi - std::acos(h / r)), 1e-13);
}

TEST(CellView, BoxesAndTruncatedOctahedraIn3D) {
  // A stretched simple cubic lattice: boxes a x b x c.
  const double a = 1.3, b = 1.0, cz = 0.8;
  const int n = 3;
  std::vector<double> p;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) p.insert(p.end(), {(i + 0.5) * a, (j + 0.5) * b, (k + 0.5) * cz});
  Box3 box;
  box.hi[0] = n * a;
  box.hi[1] = n * b;
  box.hi[2] = n * cz;
  Tessellation3 t = tessellate_periodic_3d(box, Points3{p.data(), n * n * n, 3});
  Cells3 v;
  v.bind(t, Points3{t.position.data(), t.n_points, 3});
  const double vol = a * b * cz;
  for (int c = 0; c < v.n_owned(); ++c) {
    double x[3], q[3], m[9], ax[3];
    v.point(c, q);
    v.centroid(c, x);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(x[d], q[d], 1e-12);
    v.second_moments(c, m);
    EXPECT_NEAR(m[0], vol * a * a / 12.0, 1e-12);
    EXPECT_NEAR(m[4], vol * b * b / 12.0, 1e-12);
    EXPECT_NEAR(m[8], vol * cz * cz / 12.0, 1e-12);
    EXPECT_NEAR(m[1], 0.0, 1e-12);
    ASSERT_TRUE(v.principal_axis(c, true, ax));
    EXPECT_NEAR(std::fabs(ax[0]), 1.0, 1e-10);
    ASSERT_TRUE(v.principal_axis(c, false, ax));
    EXPECT_NEAR(std::fabs(ax[2]), 1.0, 1e-10);
    EXPECT_EQ(v.coordination_number(c), 6);
    EXPECT_NEAR(v.measure(c), vol, 1e-12);
  }
  // BCC: truncated octahedra, isotropic, 14 neighbours, s = 5.3147.
  std::vector<double> q;
  const double s = 1.0;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        q.insert(q.end(), {i * s, j * s, k * s});
        q.insert(q.end(), {(i + 0.5) * s, (j + 0.5) * s, (k + 0.5) * s});
      }
  Box3 box2;
  box2.hi[0] = box2.hi[1] = box2.hi[2] = 3 * s;
  Tessellation3 t2 = tessellate_periodic_3d(box2, Points3{q.data(), 54, 3});
  Cells3 v2;
  v2.bind(t2, Points3{t2.position.data(), t2.n_points, 3});
  for (int c = 0; c < v2.n_owned(); ++c) {
    double ax[3];
    EXPECT_FALSE(v2.principal_axis(c, true, ax));
    EXPECT_EQ(v2.coordination_number(c), 14);
    EXPECT_NEAR(v2.shape_index(c), 5.3147, 1e-4);
    double area = 0.0;
    std::vector<double> xyz;
    for (int k = v2.piece_begin(c); k < v2.piece_end(c); ++k) {
      xyz.clear();
      const int m = v2.piece_corners(k, xyz);
      EXPECT_GE(m, 3);
      area += v2.piece_size(k);
    }
    EXPECT_NEAR(area, v2.boundary(c), 1e-12);
  }
}
