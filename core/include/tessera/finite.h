// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The finite Voronoi model (Teomy, Kessler & Levine, PRE 98, 042418, 2018;
// Huang, Levine & Bi, Soft Matter 19, 9389, 2023): each cell is its Voronoi
// cell intersected with the disc of radius r around its centre.  Its boundary
// is a convex loop of straight contact edges (shared with a neighbour, on
// their bisector) and circular free arcs (radius r, centred on the cell).
// Only points closer than 2 r can share an edge, so no triangulation and no
// coverage check are needed: a cell is exact as soon as every point within
// 2 r of its centre is among the input points (an open plane, or a periodic
// box with holes, or an MPI sub-domain with a ghost shell of 2 r).
//
// Energy of cell i of type I (E_i; the sum is the total):
//   K/2 (A_i - A0)^2 + Gamma/2 P_i^2 + w sum_contacts Lambda_IJ l_ij + F_I L_i
// with P_i the whole perimeter (contact edges and arcs), L_i the length of
// the free arcs, w = Model::tension_weight() and F_I the per-type tension of
// the cell-medium boundary ("free").  doc/model.md derives the forces.
// Per-cell KA, KP, P0 (Model::cell_params) add shift_c P_i over the whole
// perimeter, so contact edges and free arcs both see the cell's own P0.
#pragma once

#include "tessera/energy.h"
#include "tessera/tessellation.h"

#include <vector>

namespace tessera {

// One piece of a finite cell's boundary, counter-clockwise.  It runs from
// `start` to the next piece's start (cyclically).  neighbor >= 0: a straight
// contact edge with that point; neighbor == -1: a free arc of the cell's
// circle from angle phi over theta > 0 radians (a whole circle: theta = 2 pi,
// the only piece).
struct FinitePiece {
  int neighbor = -1;
  Vec2 start;
  double phi = 0.0, theta = 0.0;
  double length = 0.0;  // edge length, or r * theta for an arc
};

struct FiniteTessellation {
  int n_points = 0;
  int n_owned = 0;
  double radius = 0.0;
  std::vector<int> cell_offset;  // n_owned + 1 entries into pieces
  std::vector<FinitePiece> pieces;
  std::vector<double> area, perimeter, free_length;  // per owned cell
  // For finite_tessellate_periodic: owner of each point (owned first, then
  // images) and the position it was used at.  Empty otherwise.
  std::vector<int> origin;
  std::vector<Vec2> position;

  int cell_size(int c) const { return cell_offset[c + 1] - cell_offset[c]; }
  bool at_edge(int c) const { return free_length[c] > 0.0; }
};

// Two cells at distance d touch when their half-chord sqrt(r^2 - d^2/4)
// exceeds kFiniteTouchTol * r (so exactly tangent and round-off-tangent
// pairs do not).
constexpr double kFiniteTouchTol = 1e-9;

// Finite Voronoi cells of the first n_owned of the points (the others only
// bound them: ghosts or images).  Throws Error if r is not positive and
// finite, on non-finite coordinates, or on coincident points (named by ids
// if given).
FiniteTessellation finite_tessellate(const Points &pts, int n_owned, double radius,
                                     const long *ids = nullptr);

// The same in a periodic box (orthogonal or triclinic): images within 2 r of
// the box are added, so boxes smaller than 4 r work too.  Points must lie in
// the box.
FiniteTessellation finite_tessellate_periodic(const Box &box, const Points &pts, double radius,
                                              const long *ids = nullptr);

// Energy of the owned cells and forces on all points (added to f, stride
// f_stride); type: 0-based types of all n_points (images and ghosts too);
// free_tension: F per type (nullptr: 0).  cell_energy (n_owned)
// and cell_virial (4 per owned cell, xx yy xy yx: sum_p (r_p - r_c) F_p of
// the cell's own energy term) are optional.  ForceOutput::virial is their sum.
ForceOutput finite_forces(const FiniteTessellation &t, const Points &pts, const int *type,
                          const Model &model, const double *free_tension, double *f,
                          int f_stride, double *cell_energy = nullptr,
                          double *cell_virial = nullptr);

double finite_energy(const FiniteTessellation &t, const int *type, const Model &model,
                     const double *free_tension, double *cell_energy = nullptr);

// Periodic convenience: tessellate, forces, image forces folded onto their
// owners (f: n forces, stride 2, overwritten).
ForceOutput finite_periodic_forces(const Box &box, const Points &pts, double radius,
                                   const int *type, const Model &model,
                                   const double *free_tension, std::vector<double> &f);

// Positions a periodic finite tessellation used (owned then images), stride 2.
std::vector<double> positions_of(const FiniteTessellation &t);

// The contact edges of the finite cells as a Tessellation (cell_neighbor,
// edge_length, area, perimeter; no triangles or vertices), for code that
// reads neighbours and cell sizes (polarity alignment, compute vertex/atom).
void finite_contacts(const FiniteTessellation &ft, Tessellation &t);

}  // namespace tessera
