// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Small 3D vector helpers shared by the 3D sources (voronoi3d, mesh3d):
// the vector type and its operations, points and vertices read as vectors,
// the circumcentre and flatness of a tetrahedron, the parity of a
// permutation of 0..3.
// Internal to the core (not installed).
#pragma once

#include "tessera/voronoi3d.h"

#include <algorithm>
#include <cmath>

namespace tessera {
namespace detail3 {

struct V3 {
  double x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline V3 load(const Points3 &pts, int i) {
  const double *p = pts.p(i);
  return {p[0], p[1], p[2]};
}
inline V3 vv(const Vec3 &v) { return {v.x, v.y, v.z}; }

// Circumcentre of a tetrahedron, computed relative to p0 (ill-conditioned
// for flat tetrahedra: voronoi3d.cpp computes those exactly).
inline V3 circumcentre(V3 p0, V3 p1, V3 p2, V3 p3) {
  const V3 e1 = p1 - p0, e2 = p2 - p0, e3 = p3 - p0;
  const V3 c23 = cross(e2, e3), c31 = cross(e3, e1), c12 = cross(e1, e2);
  const double s = 0.5 / dot(e1, c23);
  return p0 + s * (dot(e1, e1) * c23 + dot(e2, e2) * c31 + dot(e3, e3) * c12);
}

// |det| of the edge vectors over the cube of the longest edge component:
// the flatness of a tetrahedron (0 flat, 1/6.. for a well-shaped one).
inline double flatness(V3 p0, V3 p1, V3 p2, V3 p3) {
  const V3 e1 = p1 - p0, e2 = p2 - p0, e3 = p3 - p0;
  double l = 0.0;
  for (const V3 &e : {e1, e2, e3}) l = std::max({l, std::fabs(e.x), std::fabs(e.y), std::fabs(e.z)});
  const double det = dot(e1, cross(e2, e3));
  return l > 0.0 ? std::fabs(det) / (l * l * l) : 0.0;
}

// Two cell centres closer than this fraction of the smallest circumradius
// of the tetrahedra around their Delaunay edge (half the distance to their
// nearest other neighbour or more) are not resolved by the 3D geometry: the
// tetrahedra around the edge are flatter than the slivers' threshold (1e-6)
// and both points lie within the co-spherical tolerance (1e-8 of a radius)
// of every sphere through one of them, so the pair would pass for a cluster
// of co-spherical points or a four-fold edge (whose forces then divide by
// zero).  Nor closer than kMinSeparation3Coord times their coordinates'
// magnitude (double precision, as in 2D), nor than kMinLength3.
constexpr double kMinSeparation3 = 1e-6;
constexpr double kMinSeparation3Coord = 1e-10;
constexpr double kMinLength3 = 1e-100;

// Throws Error naming the closest such pair among the owned cells' faces
// of t (ids: as for tessellate_local_3d), before any force is computed.
// d2min (optional): the smallest squared distance across those faces, if
// the caller has it (then nothing more is read when it is clearly fine).
void check_separation_3d(const Tessellation3 &t, const Points3 &pts, const long *ids,
                         double d2min = -1.0);

// Parity of the permutation (a, b, c, d) of (0, 1, 2, 3): +1 even, -1 odd.
inline int parity(int a, int b, int c, int d) {
  int p[4] = {a, b, c, d}, sign = 1;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (p[i] > p[j]) sign = -sign;
  return sign;
}

}  // namespace detail3
}  // namespace tessera
