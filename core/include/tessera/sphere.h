// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The Voronoi model on a sphere (doc/sphere.md): cell centres on the sphere
// of centre c and radius R, their spherical Delaunay triangulation (the
// convex hull of the points) and its dual, the
// spherical Voronoi diagram; each cell a spherical polygon with geodesic
// (great-circle) edges.  The energy has the flat model's form
//
//   E = sum_i [ K_i/2 (A_i - A0_i)^2 + Gamma_i/2 P_i^2 ] + sum_junctions Lambda_IJ l_ij
//
// (tessera::Model unchanged: Tension::Cell counts each junction once per
// cell, cell_area0 replaces the types' A0, cell_KA, cell_KP, cell_P0 replace
// K, Gamma and the preferred perimeter cell by cell exactly as in the plane
// (Model::cell_params: the cell's energy gains shift_c P_i), quadratic
// parameters through cell_type_from_quadratic / lambda_from_quadratic) with
// A_i the spherical area, P_i the geodesic perimeter and l_ij the geodesic
// edge length.  Per-cell arrays are indexed like the points (all n_points
// entries are read: every point is a cell).
//
// Input points are projected radially onto the sphere: point p stands for
// c + R (p - c)/|p - c|.  Everything below (geometry, forces, virial) is of
// the projected points; a point off the sphere is treated as if it were at
// its projection.  There are no ghosts: every point is a cell.
#pragma once

#include "tessera/energy.h"
#include "tessera/voronoi3d.h"

#include <array>
#include <vector>

namespace tessera {

// Voronoi vertex t is the pole of Delaunay triangle triangles[t] (point
// indices, counter-clockwise seen from outside the sphere): the point of the
// sphere equidistant from its three points on the side of its empty
// circumcircle, i.e. c + R times the unit outward normal of the hull facet.
// (When the centre lies inside the hull this is the triangle's circumcentre
// projected radially onto the sphere.)
//
// Cell i has vertices cell_vertex[k], k = cell_offset[i] .. cell_offset[i+1]-1,
// counter-clockwise seen from outside; the geodesic edge from vertex k to
// vertex k+1 (cyclically) separates i from point cell_neighbor[k] and has
// length edge_length[k].  Four or more co-circular points (cube vertices,
// a T1 in progress) give several triangles with one pole: the edges between
// them have length exactly 0 and are kept, so the polygon always matches the
// triangulation.  An edge is set to 0 when its angle is below the
// round-off of the poles at its ends, 1e-10 rho + 8 eps / rho with rho the
// smaller of its two triangles' angular circumradii (eps = 2^-52).
struct SphereTessellation {
  int n_points = 0;
  Vec3 centre;
  double R = 1.0;

  std::vector<Vec3> direction;  // unit vector of each point, (p - c)/|p - c|

  std::vector<std::array<int, 3>> triangles;  // counter-clockwise from outside
  std::vector<Vec3> vertex_direction;         // unit vector of each Voronoi vertex
  std::vector<double> circumradius;           // geodesic circumradius of each triangle

  std::vector<int> cell_offset;  // n_points + 1
  std::vector<int> cell_vertex;
  std::vector<int> cell_neighbor;
  std::vector<double> edge_length;  // geodesic

  std::vector<double> area;       // per cell, spherical
  std::vector<double> perimeter;  // per cell, geodesic

  int cell_size(int c) const { return cell_offset[c + 1] - cell_offset[c]; }
  // Position of point i / Voronoi vertex t on the sphere (c + R u).
  Vec3 point(int i) const;
  Vec3 vertex(int t) const;
  // Number of edges longer than rel_tol times the geodesic distance between
  // the cell's centre and the neighbour's (the same seen from either).
  int coordination_number(int c, double rel_tol = 1e-9) const;
};

// The spherical Voronoi cells of the n points (each projected radially onto
// the sphere).  ids (optional, n entries) name points in error messages.
// Throws Error on: R not positive or not finite, a non-finite centre or
// coordinate, a point at the centre, fewer than 4 points, two points whose
// projections are closer than 2^-23 R = 1.2e-7 R (chord; below that double
// precision cannot triangulate them), all points on one circle of the
// sphere (one plane: a great circle or a small one; also when the rounding
// of their directions lifts them off it).
// The triangulation is the exact convex hull of the directions as rounded to
// doubles (core/src/sphere_hull.cpp: inserted along a Hilbert curve on the
// sphere, exact predicates), on the sphere or on any part of it (all points
// in one hemisphere included).  With reference_hull, the same hull built by a
// different route (seeded random order, each point keeping a facet it sees;
// slower, the tests' oracle for the first).  Both give the same triangles
// except where four or more points are co-circular (co-planar: the face is a
// polygon, which each route splits into triangles its own way; the cells do
// not depend on the split).
SphereTessellation tessellate_sphere(const Vec3 &centre, double R, const Points3 &pts,
                                     const long *ids = nullptr, bool reference_hull = false);

struct SphereForceOutput {
  double energy = 0.0;
  // W_ab = sum_p (r_p - c)_a F_b (row-major xx xy xz yx yy yz zx zy zz).
  // Its trace is 0 (the forces are tangent) and it is symmetric
  // (the forces have no torque about c).
  double virial[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  // dE/dR with the points' directions fixed (the work of inflating the
  // sphere; -dE/dR / (4 pi R^2) is a pressure).  Exact, since A scales as
  // R^2 and P, l as R:
  //   R dE/dR = sum_i [ 2 K_i (A_i - A0_i) A_i + Gamma_i P_i^2 + shift_i P_i ] + E_junctions
  // with E_junctions the tension term of E (linear in R) and shift_i the
  // per-cell linear perimeter coefficient (0 without per-cell parameters).
  double dE_dR = 0.0;
};

// Energy and forces.  pts: the points given to tessellate_sphere (checked:
// same count, same directions to 1e-12; the directions stored in t are used).
// type: 0-based, n_points entries (an Error on a type out of range, or on
// a bad per-cell value: Model::validate_cells over all n_points).  Forces
// F_p = -dE/dr_p on the projected points, tangent to the sphere (E depends
// on the points only through their directions, so there is no radial part:
// the constraint force keeping the points on the sphere is not the model's),
// are *added* to f (stride f_stride, n_points rows, 3 components).  cell_energy (optional, n_points)
// receives each cell's energy, junction terms weighted by
// model.tension_weight().  cell_virial (optional, 9 per cell, order as
// SphereForceOutput::virial) receives sum_p (r_p - r_i)_a F^(i)_p,b over the
// points p that cell i's own energy term moves (forces F^(i) = -dE_i/dr_p).
// Unlike in the plane a cell's forces need not add up to zero, so the cell
// virials add up to the total only after adding sum_i (r_i - c) (x) sum_p F^(i)_p.
//
// Multifold vertices (co-circular points): as in the plane (doc/model.md,
// Geometry), the force is the mean of the energy's branch gradients over the
// fan triangulations of the vertex's ring, each zero-length edge taking the
// direction it has on its branch's side (for a four-fold vertex: the central
// difference); it does not depend on how the triangulation split the polygon.
SphereForceOutput sphere_forces(const SphereTessellation &t, const Points3 &pts, const int *type,
                                const Model &model, double *f, int f_stride,
                                double *cell_energy = nullptr, double *cell_virial = nullptr);

// Energy only (cell_energy optional, as above).
double sphere_energy(const SphereTessellation &t, const int *type, const Model &model,
                     double *cell_energy = nullptr);

// Polarity on the sphere: tangent vectors, moved between cells along great
// circles (the Levi-Civita parallel transport).  All take absolute positions
// (a, b, p on or off the sphere: only their directions from the centre count).

// v minus its component along the normal (p - c)/|p - c|.  Throws Error if p == c.
Vec3 sphere_tangent(const Vec3 &centre, const Vec3 &p, const Vec3 &v);

// Parallel transport of the tangent vector v at a (v is first projected onto
// the tangent plane at a) to b along the shorter great-circle arc: the
// rotation about the axis a x b taking a's direction to b's, which keeps the
// length and the angle to the geodesic.  Closed form, with unit a, b:
//   v' = v - (b . v) / (1 + a . b) (a + b).
// Throws Error if a and b are antipodal (no unique arc) or one is at the centre.
Vec3 sphere_transport(const Vec3 &centre, const Vec3 &a, const Vec3 &b, const Vec3 &v);

// The tangent vector v at p (projected first) turned by angle radians about
// the outward normal (counter-clockwise seen from outside).
Vec3 sphere_rotate_tangent(const Vec3 &centre, const Vec3 &p, const Vec3 &v, double angle);

// Neighbour alignment of tangent polarities: for each cell i, the torque
// about its outward normal u_i
//   tau_i = J_S sum_j u_i . (n_i x T_ji n_j)
// over its Voronoi neighbours j (edges of non-zero length), T_ji the
// parallel transport from j to i.  n: a polarity per point (stride
// n_stride, 3 components; projected onto the tangent plane, not normalised);
// tau: n_points values.  tau_i = -dU/dphi_i for the alignment energy
// U = -J_S sum_{neighbour pairs} n_i . T_ji n_j, phi_i turning n_i about
// u_i; in the plane it is polarity_torque's J_S sum_j sin(th_j - th_i).
void sphere_alignment_torque(const SphereTessellation &t, const double *n, int n_stride,
                             double J_S, double *tau);

}  // namespace tessera
