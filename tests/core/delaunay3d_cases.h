// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The point sets the 3D Delaunay builder is tested on (test_delaunay3d.cpp
// against its own definition, oracle/test_delaunay3d_cgal.cpp against CGAL):
// random points, and the degenerate input the model meets, co-spherical
// lattices (simple cubic, BCC, FCC: cubes of eight and octahedra of six
// points on one sphere, hulls of coplanar squares) exact and with rounded or
// slightly jittered coordinates, points on a sphere, a thin slab.  One table,
// one driver per test file.
#pragma once

#include "test_util.h"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace delaunay3d_cases {

struct Case {
  std::string name;
  std::vector<double> xyz;  // 3 per point
  bool far = false;         // with Mesh3's eight far points (extra points)
  int n() const { return static_cast<int>(xyz.size() / 3); }
};

enum class Kind { SC, BCC, FCC };

// m^3 unit cells of a lattice of spacing a with origin o, lattice order.
inline std::vector<double> lattice(Kind kind, int m, double a, double o = 0.0) {
  std::vector<std::array<double, 3>> basis{{0, 0, 0}};
  if (kind == Kind::BCC) basis.push_back({0.5, 0.5, 0.5});
  if (kind == Kind::FCC) basis = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  std::vector<double> x;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k)
        for (const auto &b : basis) {
          x.push_back(o + a * (i + b[0]));
          x.push_back(o + a * (j + b[1]));
          x.push_back(o + a * (k + b[2]));
        }
  return x;
}

inline std::vector<double> random_cube(int n, uint64_t seed) {
  testutil::Rng rng(seed);
  std::vector<double> x(3 * static_cast<size_t>(n));
  for (double &v : x) v = rng.uniform(0.0, 1.0);
  return x;
}

inline std::vector<double> jitter(std::vector<double> x, double amp, uint64_t seed) {
  testutil::Rng rng(seed);
  for (double &v : x) v += rng.uniform(-amp, amp);
  return x;
}

// (x, y, z) -> (x, L - z, y): a symmetry of the lattices that changes the
// points' lexicographic order, hence the perturbation's choices.
inline std::vector<double> rotate_x(std::vector<double> x, double L) {
  for (size_t i = 0; i < x.size(); i += 3) {
    const double y = x[i + 1], z = x[i + 2];
    x[i + 1] = L - z;
    x[i + 2] = y;
  }
  return x;
}

// Integer points on the sphere x^2 + y^2 + z^2 = r2 (and its centre).
inline std::vector<double> sphere_points(int r2) {
  std::vector<double> x{0.0, 0.0, 0.0};
  const int r = static_cast<int>(std::sqrt(static_cast<double>(r2))) + 1;
  for (int i = -r; i <= r; ++i)
    for (int j = -r; j <= r; ++j)
      for (int k = -r; k <= r; ++k)
        if (i * i + j * j + k * k == r2) x.insert(x.end(), {double(i), double(j), double(k)});
  return x;
}

// A 7 x 7 x 2 grid: most points on the hull's two large square faces.
inline std::vector<double> slab() {
  std::vector<double> x;
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j)
      for (int k = 0; k < 2; ++k) x.insert(x.end(), {double(i), double(j), 0.5 * k});
  return x;
}

inline std::vector<Case> cases() {
  std::vector<Case> c;
  c.push_back({"random 10", random_cube(10, 1)});
  c.push_back({"random 300", random_cube(300, 2)});
  c.push_back({"random 3000", random_cube(3000, 3)});
  c.push_back({"SC 3", lattice(Kind::SC, 3, 1.0)});
  c.push_back({"SC 5", lattice(Kind::SC, 5, 1.0)});
  c.push_back({"SC 4 spacing 0.1 at 0.3", lattice(Kind::SC, 4, 0.1, 0.3)});
  c.push_back({"BCC 3", lattice(Kind::BCC, 3, 1.0)});
  c.push_back({"BCC 4 spacing 1.1", lattice(Kind::BCC, 4, 1.1)});
  c.push_back({"BCC 4 rotated", rotate_x(lattice(Kind::BCC, 4, 1.0), 3.5)});
  c.push_back({"FCC 3", lattice(Kind::FCC, 3, 1.0)});
  c.push_back({"FCC 3 spacing 1.1 at 0.3", lattice(Kind::FCC, 3, 1.1, 0.3)});
  c.push_back({"FCC 3 rotated", rotate_x(lattice(Kind::FCC, 3, 1.0), 2.5)});
  c.push_back({"BCC 4 jittered 1e-13", jitter(lattice(Kind::BCC, 4, 1.0), 1e-13, 4)});
  c.push_back({"FCC 3 jittered 1e-9", jitter(lattice(Kind::FCC, 3, 1.0), 1e-9, 5)});
  c.push_back({"sphere r^2 = 50", sphere_points(50)});
  c.push_back({"slab 7 x 7 x 2", slab()});
  c.push_back({"random 300 with far points", random_cube(300, 6), true});
  c.push_back({"BCC 3 with far points", lattice(Kind::BCC, 3, 1.0), true});
  c.push_back({"SC 4 with far points", lattice(Kind::SC, 4, 1.0), true});
  return c;
}

// Mesh3's far points for a case: the corners of the bounding box's centre
// +- 32 times its largest extent (as Mesh3::build places them).
inline void far_points(const Case &c, double far[8][3]) {
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) lo[d] = hi[d] = c.xyz[d];
  for (int i = 0; i < c.n(); ++i)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], c.xyz[3 * i + d]);
      hi[d] = std::max(hi[d], c.xyz[3 * i + d]);
    }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  for (int k = 0; k < 8; ++k)
    for (int d = 0; d < 3; ++d)
      far[k][d] = 0.5 * (lo[d] + hi[d]) + ((k >> d) & 1 ? 32.0 : -32.0) * extent;
}

}  // namespace delaunay3d_cases
