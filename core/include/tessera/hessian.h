// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Exact second derivatives of the vertex-model energy with respect to the cell
// centres (the Hessian, or dynamical matrix at unit mass), through the
// circumcentres of the Delaunay triangles, and the affine-strain terms that
// linear elasticity needs: for a homogeneous deformation r -> (I + eps D) r of
// every point (periodic images included, so the box deforms with them),
//   Born term  d2E/d eps^2 at fixed reduced coordinates,
//   Xi         d2E/dr d eps (the force each cell feels when the box is
//              strained without letting the cells relax),
// so that the relaxed (quasistatic) second derivative is Born - Xi^T H^+ Xi.
//
// Each cell's energy is differentiated as a smooth function of its centre and
// its Voronoi neighbours, with the triangulation held fixed: the Hessian is
// that of the energy on the configuration's own triangulation, exact as long
// as no neighbour changes.  Edge lengths are taken as (h_{k+1} - h_k) . n,
// with n the unit normal of the Delaunay edge, which equals |h_{k+1} - h_k| on
// a Delaunay triangulation and stays accurate for very short edges.
//
// Multifold vertices (four or more co-circular centres, e.g. the square
// lattice) have no Hessian: the energy is not differentiable there (it has a
// kink; the forces of compute_forces are the mean of the one-sided branches),
// so compute_hessian throws Error naming the cell and the vertex.
#pragma once

#include "tessera/energy.h"
#include "tessera/tessellation.h"

#include <vector>

namespace tessera {

// A sparse symmetric matrix in coordinate form; row and col index
// 2 * point + component (component 0 = x, 1 = y).
struct SparseMatrix {
  int n = 0;  // the matrix is n x n
  std::vector<int> row, col;
  std::vector<double> val;
  // Sorts by (row, col) and adds up duplicate entries.
  void compress();
};

// d2E/dr_p dr_q of compute_energy(t, ...) for all t.n_points points (owned and
// ghost), as a 2 n_points square matrix (entries are added; may hold
// duplicates until compress()).  Throws Error if an owned cell has a
// multifold vertex or a point is not a neighbour of the cells it should be.
void compute_hessian(const Tessellation &t, const Points &pts, const int *type,
                     const Model &model, SparseMatrix &h);

// Everything linear elasticity needs for a periodic configuration.
struct PeriodicHessian {
  int n = 0;            // owned cells
  double area = 0.0;    // box area
  double energy = 0.0;  // as compute_forces
  double virial[4] = {0.0, 0.0, 0.0, 0.0};  // as ForceOutput: xx, yy, xy, yx
  std::vector<double> force;                 // 2 n, as periodic_forces
  SparseMatrix hessian;                      // 2n x 2n, images folded onto owners, compressed
  // Affine strains: shear x += gamma y (D = [[0,1],[0,0]], LAMMPS's xy tilt),
  // dilation r += eps r (D = I).
  double born_shear = 0.0, born_dilation = 0.0;  // d2E/dgamma^2, d2E/deps^2 (affine)
  std::vector<double> xi_shear, xi_dilation;     // 2 n each: d2E/dr dgamma, d2E/dr deps
};

// Tessellates, computes energy, forces and virial (compute_forces) and the
// Hessian with its affine terms.  The points must lie in the box.
PeriodicHessian periodic_hessian(const Box &box, const Points &pts, const int *type,
                                 const Model &model);

// The affine terms for a general velocity gradient D (row-major 2x2, the
// displacement of point p per unit strain is D r_p) from the unfolded Hessian
// of tessellate_periodic's points: born = v^T H v, xi (2 n_owned) the rows of
// H v folded onto the owners.  Used by periodic_hessian.
void affine_terms(const Tessellation &t, const SparseMatrix &full, const double D[4],
                  double &born, std::vector<double> &xi);

}  // namespace tessera
