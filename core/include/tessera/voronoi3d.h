// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Three dimensions: the Voronoi cells of 3D cell centres, as the dual of their
// Delaunay tetrahedralisation (the core's own, with exact predicates),
// their volumes, surfaces and faces, and the energy
//
//   E = sum_i [ K_i/2 (V_i - V0_i)^2 + Gamma_i/2 S_i^2 ] + sum_faces Lambda_IJ a_f
// (per-cell KV, KS, S0 through Model::cell_KA, cell_KP, cell_P0 as in 2D,
// with the volume, surface and face areas for area, perimeter and lengths)
//
// (the 2D model with area -> volume, perimeter -> surface, junction length ->
// face area; tessera::Model is reused, CellType::A0 holding V0) with its exact
// gradient with respect to the centres and the virial.  With uniform
// parameters it is the quadratic form of Merkel and Manning (New J. Phys. 20,
// 022002, 2018), sum_i K_V (V_i - V0)^2 + K_S (S_i - S0)^2, up to a constant
// (cell_type_from_quadratic / lambda_from_quadratic apply unchanged).
#pragma once

#include "tessera/energy.h"
#include "tessera/tessellation.h"

#include <array>
#include <vector>

namespace tessera {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

// n points with a fixed stride (LAMMPS's x[i][0..2]: stride 3).
struct Points3 {
  const double *data = nullptr;
  int n = 0;
  int stride = 3;
  const double *p(int i) const { return data + static_cast<long>(i) * stride; }
};

// A parallelepiped o + s a + t b + u c (s, t, u in [0, 1]): a LAMMPS
// (sub-)domain, with a = (ax, 0, 0), b = (bx, by, 0), c = (cx, cy, cz).
struct Region3 {
  double o[3] = {0.0, 0.0, 0.0};
  double a[3] = {1.0, 0.0, 0.0};
  double b[3] = {0.0, 1.0, 0.0};
  double c[3] = {0.0, 0.0, 1.0};
};

// Periodic box with edge vectors (lx, 0, 0), (xy, ly, 0), (xz, yz, lz) from
// lo, as in LAMMPS (all tilts 0: orthogonal, [lo, hi]).
struct Box3 {
  double lo[3] = {0.0, 0.0, 0.0};
  double hi[3] = {1.0, 1.0, 1.0};
  double xy = 0.0, xz = 0.0, yz = 0.0;
  double length(int d) const { return hi[d] - lo[d]; }
  double volume() const { return length(0) * length(1) * length(2); }
  bool triclinic() const { return xy != 0.0 || xz != 0.0 || yz != 0.0; }
  Region3 region() const;
  // Fractional coordinates (in [0, 1) for a point inside).
  void fractional(const double x[3], double s[3]) const;
  // Throws Error if a length is not positive or not finite, or a tilt is not finite.
  void validate() const;
};

// A four-fold Voronoi edge: four coplanar, co-circular centres p (indices
// into the triangulated points, in cyclic order round their circle), whose
// Voronoi edge, shared by their four cells, runs between end[0] and end[1]
// (the centres of the co-spherical clusters on either side).  The energy
// has a kink there; compute_forces_3d takes the mean of the two branches
// (one diagonal of the square or the other), doc/model.md "Four-fold edges
// (3D)".
struct FourFoldEdge3 {
  std::array<int, 4> p{{-1, -1, -1, -1}};
  Vec3 end[2];
};

// The tessellation of n_points points, of which the first n_owned are the
// cells we want; the rest (ghosts, periodic images) only complete them.
//
// Voronoi vertex t is the circumcentre vertices[t] of Delaunay tetrahedron
// tets[t] (positively oriented).  Owned cell c has faces
// f = cell_offset[c] .. cell_offset[c+1]-1; face f separates c from point
// face_neighbor[f], has area face_area[f] and its polygon is the
// circumcentres of the tetrahedra face_vertex[face_offset[f] ..
// face_offset[f+1]) (the tetrahedra around the Delaunay edge c-neighbour),
// counter-clockwise seen from the neighbour (its vector area points from c
// to the neighbour).  Co-spherical points (BCC, FCC lattices) give several
// tetrahedra with one circumcentre: faces of area 0 and repeated polygon
// vertices, kept so that the topology always matches the triangulation.
struct Tessellation3 {
  int n_points = 0;
  int n_owned = 0;

  std::vector<std::array<int, 4>> tets;
  std::vector<Vec3> vertices;
  std::vector<double> radius;

  std::vector<int> cell_offset;  // n_owned + 1
  std::vector<int> face_neighbor;
  std::vector<double> face_area;
  std::vector<int> face_offset;  // faces + 1
  std::vector<int> face_vertex;

  std::vector<double> volume;   // per owned cell
  std::vector<double> surface;  // per owned cell

  // An owned cell on the convex hull (unbounded), or -1; only set when
  // tessellate_local_3d was asked not to throw.
  int unbounded_cell = -1;

  // The four-fold edges with an owned corner, found by the builders
  // (tessellate_local_3d, Mesh3::cells) from the triangulation's adjacency;
  // cleared by remeasure_3d (a branch has none).
  std::vector<FourFoldEdge3> fourfold;

  // Set by Mesh3::cells(): which call filled this tessellation (lets the
  // next call on it keep the faces of the cells no flip changed); 0 if none.
  unsigned long mesh_stamp = 0;

  // tessellate_periodic_3d: the owned point each point is an image of, and
  // the positions triangulated (stride 3, owned points first).
  std::vector<int> origin;
  std::vector<double> position;

  int face_count_total(int c) const { return cell_offset[c + 1] - cell_offset[c]; }
  // Faces of area above rel_tol times the cell's surface (the zero-area
  // faces of co-spherical points excluded): the number of neighbours.
  int face_count(int c, double rel_tol = 1e-9) const;
  // s = S / V^(2/3).
  double shape_index(int c) const;
};

// Triangulate points (owned first, then ghosts) without periodicity and build
// the owned cells.  ids (optional) name points in error messages.  Throws
// Error on non-finite coordinates, coincident or nearly coincident points
// (doc/model.md, "Limits of the input"), fewer than 4 non-coplanar points,
// and (if throw_if_unbounded) an owned cell on the hull.
Tessellation3 tessellate_local_3d(const Points3 &pts, int n_owned, const long *ids = nullptr,
                                  bool throw_if_unbounded = true);

// The same triangulation at moved points: circumcentres, radii, face areas,
// volumes and surfaces recomputed, the tetrahedra and faces kept.  Its
// energy is the smooth branch the triangulation stands for, which the
// forces of compute_forces_3d are the exact gradient of; it is the true
// energy only while the triangulation stays Delaunay (doc/model.md,
// "Reliability of the finite and 3D paths").  t.fourfold is cleared: the
// forces are then that branch's gradient, also at four-fold edges.
void remeasure_3d(Tessellation3 &t, const Points3 &pts);

// Whether every tetrahedron of an owned cell has its circumsphere inside the
// box [lo, hi] grown by margin (then no unseen point outside can change the
// owned cells).  needed_margin: how much more margin the worst one needs.
Coverage check_coverage_3d(const Tessellation3 &t, const double lo[3], const double hi[3],
                           double margin = 0.0);
// The same for a parallelepiped grown by margin on every side (perpendicular
// distance), e.g. a triclinic sub-domain and its ghost shell.
Coverage check_coverage_3d(const Tessellation3 &t, const Region3 &region, double margin = 0.0);

// Periodic tessellation of n points inside box (orthogonal or triclinic;
// images within a margin, grown until check_coverage_3d passes).  Throws
// Error for points outside.
Tessellation3 tessellate_periodic_3d(const Box3 &box, const Points3 &pts,
                                     const long *ids = nullptr);

struct ForceOutput3 {
  double energy = 0.0;
  // W_ab = sum over all points of r_a F_b (positions as triangulated);
  // dE/d(strain_ab) = -W_ab.  Row-major: xx xy xz yx yy yz zx zy zz.
  double virial[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
};

// Energy of the owned cells and forces (added to f, stride f_stride) on all
// n_points points.  type: 0-based, n_points entries.  cell_energy (optional,
// n_owned) receives each owned cell's energy (face tension weighted by
// model.tension_weight()).  cell_virial (optional, 9 per owned cell, order
// as ForceOutput3::virial) receives the virial sum_p (r_p - r_c) F_p of each
// cell's own energy term over the points it moves; they add up to the total.
// The forces are the exact gradient of the energy, except at the four-fold
// edges of t.fourfold, where they are the mean of the two branches'
// gradients (the energy has a kink there).
ForceOutput3 compute_forces_3d(const Tessellation3 &t, const Points3 &pts, const int *type,
                               const Model &model, double *f, int f_stride,
                               double *cell_energy = nullptr, double *cell_virial = nullptr);
double compute_energy_3d(const Tessellation3 &t, const int *type, const Model &model,
                         double *cell_energy = nullptr);

// Periodic convenience: tessellate, forces folded onto the n owners (f:
// stride 3, overwritten).
ForceOutput3 periodic_forces_3d(const Box3 &box, const Points3 &pts, const int *type,
                                const Model &model, std::vector<double> &f,
                                std::vector<double> *cell_energy = nullptr);

}  // namespace tessera
