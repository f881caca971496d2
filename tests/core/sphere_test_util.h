// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// A small vector type with its operations, and the icosahedron, for the sphere tests
// (test_sphere.cpp, test_sphere_cells.cpp, test_sphere_fuzz.cpp): independent of the
// core's own vector helpers, so that the tests' geometry does not share code with what
// they test.
#pragma once

#include "tessera/sphere.h"

#include <cmath>
#include <vector>

namespace spheretest {

constexpr double kPi = 3.14159265358979323846;

struct W {
  double x, y, z;
};
inline W operator+(W a, W b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline W operator-(W a, W b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline W operator*(double s, W a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(W a, W b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline W cross(W a, W b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double norm(W a) { return std::sqrt(dot(a, a)); }
inline W unit(W a) { return (1.0 / norm(a)) * a; }
inline W w3(const tessera::Vec3 &v) { return {v.x, v.y, v.z}; }
inline tessera::Vec3 v3(W a) { return tessera::Vec3{a.x, a.y, a.z}; }
inline double angle(W a, W b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }

// The 12 vertices of a regular icosahedron (edge 2, circumradius about 1.902).
inline std::vector<W> icosahedron() {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<W> v;
  for (int s1 : {-1, 1})
    for (int s2 : {-1, 1}) {
      v.push_back({0.0, 1.0 * s1, phi * s2});
      v.push_back({1.0 * s1, phi * s2, 0.0});
      v.push_back({phi * s2, 0.0, 1.0 * s1});
    }
  return v;
}

}  // namespace spheretest
