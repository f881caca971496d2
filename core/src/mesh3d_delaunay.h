// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Tessera's own 3D Delaunay tetrahedralisation (mesh3d_delaunay.cpp) and the
// exact geometry around it: the filtered predicates with their symbolic
// perturbation, the exactly rounded circumcentre of a sliver
// (mesh3d_exact.cpp).  Used by Mesh3::build and tessellate_local_3d; tested
// on its own (tests/core) and, where CGAL is found, against CGAL's
// Delaunay_triangulation_3.  Internal to the core (not installed).
//
// The triangulation.  The Delaunay tetrahedralisation of a point set is
// unique unless five or more points are co-spherical (BCC, FCC, simple cubic
// lattices) or four or more coplanar points lie on the convex hull.  Ties are
// broken by the symbolic perturbation of Devillers and Teillaud
// ("Perturbations for Delaunay and weighted Delaunay 3D triangulations",
// 2011), the one CGAL's Delaunay_triangulation_3 uses, which depends only on
// the points' lexicographic (x, y, z) order:
//
//  - in-sphere test of e against a positively oriented tetrahedron
//    (p0 p1 p2 p3) with an exact zero: the five points ranked
//    lexicographically; if e ranks highest it is outside; else the highest
//    ranked p_k is replaced by e and the orientation of that tetrahedron, if
//    not zero, is the answer; else the same with the second highest; (two
//    steps always decide);
//  - the convex hull: a point p beyond a hull triangle (a b c) is in
//    conflict with it; a point in the triangle's plane is when it lies
//    inside the circle through a, b, c, with exact zeros broken in the same
//    way in the plane: the four points ranked, p ranking highest is outside,
//    else the highest ranked of a, b, c replaced by p decides by the sign of
//    its orientation in the plane times that of (a b c) when not collinear,
//    then the second and third highest; if all three are collinear, outside
//    when (a b c) is positively oriented in the plane, inside otherwise (the
//    plane oriented from a point off it; the product does not depend on
//    which).
//
// These predicates define the perturbed Delaunay triangulation; it does not
// depend on the order of insertion, so the builder (Bowyer-Watson on a
// biased randomised insertion order, walking from the last tetrahedron) gets
// the same tetrahedra as CGAL's.  Every sign is exact: floating-point filters
// with static error bounds in front of tessera::exact's predicates.
#pragma once

#include "tessera/voronoi3d.h"

#include <cstddef>
#include <vector>

namespace tessera {
namespace detail3 {

// Sign of det[b-a; c-a; d-a] (+1: a b c d positively oriented); exact.
// exact_calls counts the calls the floating-point filter could not decide.
int orient3d_filtered(const double *a, const double *b, const double *c, const double *d,
                      long &exact_calls);

// +1 when e is inside the circumsphere of the positively oriented
// tetrahedron p0 p1 p2 p3 (the sign flips for a negatively oriented one),
// -1 outside, 0 co-spherical: CGAL's side_of_oriented_sphere, exact.
int insphere_filtered(const double *p0, const double *p1, const double *p2, const double *p3,
                      const double *e, long &exact_calls);

// Whether p precedes q in lexicographic (x, y, z) order.
inline bool less_xyz(const double *p, const double *q) {
  if (p[0] != q[0])
    return p[0] < q[0];
  if (p[1] != q[1])
    return p[1] < q[1];
  return p[2] < q[2];
}

// The in-sphere test with the perturbation above: +1 inside, -1 outside,
// never 0; t: the positively oriented tetrahedron's corners, e the point.
int insphere_perturbed(const double *const t[4], const double *e, long &exact_calls);

// Whether three points are collinear (exactly).
bool collinear3(const double *a, const double *b, const double *c);

// The finite tetrahedra of a Delaunay tetrahedralisation: corners (point
// indices, positively oriented; the smallest first, then the smallest of
// the other three), neighbours across the triangle opposite each corner (-1
// on the convex hull), one tetrahedron per point.  Tetrahedra are numbered by
// their corners in lexicographic order (the smallest corner first): a
// function of the points alone, whatever the order of insertion.
struct Tetrahedra {
  std::vector<int> tv; // 4 per tetrahedron
  std::vector<int> tn; // 4 per tetrahedron
  std::vector<int> vt; // per point
  int n_tets = 0;
  long exact_calls = 0;        // predicate calls the filters could not decide
  int duplicate[2] = {-1, -1}; // a pair of coincident points (kDuplicate)
};

enum class Delaunay3 { kOk, kDuplicate, kFlat };

// Triangulates the points of pts followed by the n_extra points extra[k]
// (index pts.n + k; Mesh3's far points).  kDuplicate: two points coincide
// (out.duplicate names one such pair), kFlat: fewer than four non-coplanar
// points; out is then not filled.  tv and tn get room for `slack` times
// their size more (flips that add tetrahedra later).  Coordinates must be
// finite.  sorted = false: the tetrahedra in the builder's order instead
// (cheaper; still a function of the input).
Delaunay3 delaunay_3d(const Points3 &pts, const double (*extra)[3], int n_extra, Tetrahedra &out,
                      double slack = 0.0, bool sorted = true);

// The circumcentre of tetrahedron p0 p1 p2 p3 (not flat), each coordinate
// the double nearest its exact value (ties to even): computed in rationals.
void exact_circumcentre(const double *p0, const double *p1, const double *p2, const double *p3,
                        double *c);

} // namespace detail3
} // namespace tessera
