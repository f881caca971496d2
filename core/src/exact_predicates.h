// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Exact geometric predicates: the sign of a determinant of double-precision
// input, exact for every finite input (no rounding decides a sign).  The
// builders keep their own floating-point filters in front of these and call
// them only when the filter cannot decide.  Internal to the core.
#pragma once

namespace tessera::exact {

// Sign (+1, 0, -1) of det[b-a; c-a] in 2D: +1 when a, b, c turn
// counter-clockwise, 0 when they are collinear.
int orient2d(const double *a, const double *b, const double *c);

// +1 when d lies strictly inside the circle through a, b, c and a, b, c turn
// counter-clockwise (the sign flips for clockwise a, b, c), 0 when the four
// points are co-circular (or a, b, c collinear and d on their line).
// CGAL's side_of_oriented_circle.
int incircle(const double *a, const double *b, const double *c, const double *d);

// Sign of det[b-a; c-a; d-a] in 3D: +1 when the tetrahedron a b c d is
// positively oriented (CGAL's orientation), 0 when the points are coplanar.
int orient3d(const double *a, const double *b, const double *c, const double *d);

// +1 when e lies strictly inside the sphere through a, b, c, d and the
// tetrahedron a b c d is positively oriented (the sign flips for a negatively
// oriented one), 0 when the five points are co-spherical.  CGAL's
// side_of_oriented_sphere.
int insphere(const double *a, const double *b, const double *c, const double *d, const double *e);

} // namespace tessera::exact
