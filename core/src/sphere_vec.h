// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Small 3-vector helpers shared by sphere.cpp and sphere_forces.cpp (internal).
#pragma once

#include "tessera/voronoi3d.h"

#include <cmath>

namespace tessera {
namespace sphere_detail {

struct V {
  double x, y, z;
};
inline V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V cross(V a, V b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(V a) { return std::sqrt(dot(a, a)); }
inline V vv(const Vec3 &a) { return {a.x, a.y, a.z}; }
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

}  // namespace sphere_detail
}  // namespace tessera
