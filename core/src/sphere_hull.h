// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The convex hull of points near the unit sphere (internal to the core; sphere.cpp's
// triangulation, doc/sphere.md "Computation").  For points on the sphere the hull's
// facets are the spherical Delaunay triangles (a circle of the sphere is the sphere
// cut by a plane: a triangle's circumcircle bounds an empty cap iff no point lies
// beyond its facet's plane).  The points are unit directions rounded to doubles, so
// they lie near the sphere, not on it: what is built is the exact convex hull of the
// rounded points, every sign decided by exact predicates (exact_predicates.h) behind a
// floating-point filter.
#pragma once

#include <array>
#include <vector>

namespace tessera {
namespace sphere_detail {

// How the points are inserted.  Walk: a well-spread first tetrahedron, then the rest
// along a Hilbert curve on the sphere, each located by walking from the last facet
// made (the fast route).  Conflict: in a seeded random order, each point remembering
// one facet it sees (randomised incremental construction; no point location), the
// reference the tests compare Walk with, and Walk's fallback when its first
// tetrahedron is too flat to hold a double-precision point strictly inside it.
enum class HullRoute { Walk, Conflict };

struct HullResult {
  enum Status {
    Ok,    // triangles: the hull's facets
    Equal, // points i and j are equal (the same three doubles)
    Flat,  // all points lie on one plane (exactly; their hull has no interior)
    Hidden // point i lies in the hull of the others (on or inside it): no vertex
  };
  Status status = Ok;
  int i = -1, j = -1;
  HullRoute route = HullRoute::Walk; // the route that built it (Walk may fall back)
  // Counter-clockwise seen from outside: every point p satisfies
  // exact::orient3d(a, b, c, p) <= 0 for each triangle (a, b, c).  Four or more
  // coplanar points on a hull face (co-circular points) give a triangulation of that
  // face, which one depends on the order of insertion.
  std::vector<std::array<int, 3>> triangles;
  // neighbors[t][k]: the triangle across the edge from corner k to corner k + 1.
  std::vector<std::array<int, 3>> neighbors;
};

// The hull of the n >= 4 points xyz[3i..3i+2] (unit directions as rounded to doubles).
HullResult sphere_hull(const double *xyz, int n, HullRoute route);

} // namespace sphere_detail
} // namespace tessera
