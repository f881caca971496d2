// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Small 3-vector helpers shared by sphere.cpp and sphere_forces.cpp (internal),
// on top of the 3D sources' vector type.
#pragma once

#include "tessera/voronoi3d.h"

#include "vec3_detail.h"

#include <cmath>
#include <numeric>
#include <vector>

namespace tessera {
namespace sphere_detail {

// The vector type and its basic operations are the 3D sources' own
// (vec3_detail.h); the operators are found through V3's namespace.
using V = detail3::V3;
using detail3::cross;
using detail3::dot;
inline double norm(V a) { return std::sqrt(dot(a, a)); }
using detail3::vv;
inline Vec3 to3(V a) { return Vec3{a.x, a.y, a.z}; }
inline void add_to(V &a, V b) { a = a + b; }

// Angle between two (unit or not) vectors, accurate also near 0 and pi.
inline double angle(V a, V b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }

// Solid angle of the geodesic triangle of unit vectors a, b, c (signed:
// positive when counter-clockwise seen from outside).
inline double solid_angle(V a, V b, V c) {
  const double D = dot(a, cross(b, c));
  const double S = 1.0 + dot(a, b) + dot(b, c) + dot(c, a);
  return 2.0 * std::atan2(D, S);
}

inline bool finite3(const double *p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// Poles (triangles) joined into one vertex where the edge between two of
// them has no length: disjoint sets with path halving.
struct PoleSets {
  std::vector<int> parent;
  explicit PoleSets(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int root(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(int a, int b) {
    a = root(a);
    b = root(b);
    if (a != b) parent[a] = b;
  }
};

}  // namespace sphere_detail
}  // namespace tessera
