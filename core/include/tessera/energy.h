// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Vertex-model energy of the Voronoi cells and its exact gradient with respect
// to the cell centres (chain rule through the circumcentres), plus the virial.
#pragma once

#include "tessera/tessellation.h"

#include <vector>

namespace tessera {

// How the junction tension enters the energy (doc/model.md, "Energy: the junction term").
//   Edge: sum over junctions of Lambda_IJ * l_ij, each junction once
//         (Farhadifar 2007; consistent with p0 = -Lambda_bar / (2 Gamma_bar)).
//   Cell: sum over cells of sum over the cell's junctions Lambda_IJ * l_ij, so
//         each junction counts twice (Lambda * P_i for uniform Lambda); this is
//         what the thesis's own code computes, with preferred perimeter -Lambda/Gamma.
enum class Tension { Edge, Cell };

struct CellType {
  double K = 1.0;      // area modulus
  double A0 = 1.0;     // preferred area
  double Gamma = 0.0;  // perimeter (contractility) modulus
};

// Parameters of the energy for n types (0-based type indices).
//   E = sum_i [ K_i/2 (A_i - A0_i)^2 + Gamma_i/2 P_i^2 ] + tension term
struct Model {
  std::vector<CellType> types;
  std::vector<double> lambda;  // ntypes * ntypes, symmetric, Lambda_IJ
  Tension tension = Tension::Edge;
  // Optional per-cell preferred areas, indexed like the type array (one per
  // point; only owned cells' entries are read).  When set they replace the
  // types' A0; the caller keeps the array alive and valid (> 0, finite).
  const double *cell_area0 = nullptr;
  // Optional per-cell stiffnesses and preferred perimeter (LAMMPS: d_ka,
  // d_kp, d_perim0), indexed like cell_area0, in the quadratic form's units
  // (in 3D: KV, KS and the preferred surface S0).  Any of them may be set;
  // each replaces the type's value for every cell:
  //   K_c = 2 cell_KA[c]            (else the type's K)
  //   Gamma_c = 2 cell_KP[c]        (else the type's Gamma)
  //   s_c = -Gamma_c P0_c           (the cell's own linear perimeter coefficient)
  // with P0_c = cell_P0[c], else the type's P0_t = -w Lambda_tt / Gamma_t
  // (w = tension_weight(); a type with Gamma_t = 0 has no P0: its cells keep
  // s_c = w Lambda_tt).  Cell c's energy is then
  //   K_c/2 (A - A0_c)^2 + Gamma_c/2 P^2 + shift_c P + w sum_k Lambda_{t t_k} l_k
  // with shift_c = s_c - w Lambda_tt: in a tissue of one type, with the
  // constant Gamma_c/2 P0_c^2 added, KA_c (A - A0_c)^2 + KP_c (P - P0_c)^2;
  // the junction tensions' heterotypic parts stay per type pair.
  const double *cell_KA = nullptr;
  const double *cell_KP = nullptr;
  const double *cell_P0 = nullptr;

  explicit Model(int ntypes = 1);
  int ntypes() const { return static_cast<int>(types.size()); }
  double lambda_of(int ti, int tj) const { return lambda[ti * ntypes() + tj]; }
  void set_lambda(int ti, int tj, double value);
  // Weight of a junction's Lambda * l in one adjacent cell's energy: 1/2 for
  // Edge (so the two cells add up to one junction), 1 for Cell.
  double area0_of(int c, int tc) const { return cell_area0 ? cell_area0[c] : types[tc].A0; }
  double tension_weight() const { return tension == Tension::Edge ? 0.5 : 1.0; }
  // Whether any of cell_KA, cell_KP, cell_P0 is set (cell_area0 is not
  // counted: the type-parameter paths read it themselves).
  bool has_cell_params() const { return cell_KA || cell_KP || cell_P0; }
  // Cell c's (type tc) parameters in use: K_c, A0_c, Gamma_c, shift_c.
  struct CellParams {
    double K, A0, Gamma, shift;
  };
  CellParams cell_params(int c, int tc) const {
    const CellType &ct = types[tc];
    CellParams p{cell_KA ? 2.0 * cell_KA[c] : ct.K, area0_of(c, tc),
                 cell_KP ? 2.0 * cell_KP[c] : ct.Gamma, 0.0};
    const double wl = tension_weight() * lambda_of(tc, tc);
    if (cell_P0)
      p.shift = -p.Gamma * cell_P0[c] - wl;
    else if (ct.Gamma > 0.0)
      p.shift = (p.Gamma - ct.Gamma) * (wl / ct.Gamma);  // exactly 0 when Gamma_c = Gamma_t
    return p;
  }
  // The constant that completes the quadratic form of cell c's perimeter
  // term, Gamma_c/2 P0_c^2 = s_c^2 / (2 Gamma_c) (0 when Gamma_c = 0), from
  // the values in use: LAMMPS adds it to pe for types given in that form.
  double quadratic_constant(int c, int tc) const {
    const CellParams p = cell_params(c, tc);
    const double s = cell_P0 ? -p.Gamma * cell_P0[c] : tension_weight() * lambda_of(tc, tc) + p.shift;
    return p.Gamma > 0.0 ? s * s / (2.0 * p.Gamma) : 0.0;
  }
  // Throws Error naming the cell and the value unless every owned cell's
  // per-cell values (of the n_owned first entries) are finite with KA > 0,
  // KP >= 0 (cell_area0: > 0).
  void validate_cells(int n_owned) const;
  // Throws Error naming the type and the value if K <= 0, A0 <= 0 or anything
  // is non-finite.  Gamma may be zero; Lambda may have either sign.
  void validate() const;
};

// Quadratic form E = sum K_A (A - A0)^2 + K_P (P - P0)^2 (Bi et al.) for one
// type: K = 2 K_A, Gamma = 2 K_P, and Lambda such that the preferred
// perimeter is P0 under the given tension convention:
//   Edge: Lambda = -2 Gamma P0;  Cell: Lambda = -Gamma P0.
struct QuadraticParams {
  double KA, A0, KP, P0;
};
CellType cell_type_from_quadratic(const QuadraticParams &q);
double lambda_from_quadratic(const QuadraticParams &q, Tension tension);

struct ForceOutput {
  double energy = 0.0;  // sum over owned cells
  // Virial W_ab = sum over all n_points of r_a F_b, computed with the positions
  // the triangulation used (ghosts at their image positions) and with forces on
  // ghosts not yet folded; then dE/d(strain_ab) = -W_ab.  Order: xx, yy, xy, yx.
  double virial[4] = {0.0, 0.0, 0.0, 0.0};
  // The closest pair of Voronoi neighbours: owned cell closest_cell and the
  // point closest_neighbor (an index into pts) at squared distance
  // closest_distance2 (the first such pair in cell order; -1 without cells).
  int closest_cell = -1, closest_neighbor = -1;
  double closest_distance2 = -1.0;
};

// Energy of the owned cells and forces on all n_points points (owned and
// ghost) from it.  Forces are *added* to f (stride f_stride, n_points rows);
// cell_energy (optional, n_owned entries) receives each owned cell's energy,
// with its junction terms weighted by tension_weight().  cell_virial
// (optional, 4 per owned cell: xx, yy, xy, yx) receives the virial of each
// cell's own energy term, sum_p (r_p - r_c) F_p over the points it moves;
// the cells' virials add up to ForceOutput::virial (costs about one more
// force evaluation).  type holds 0-based types for all n_points.  pts must
// be the points that were tessellated (for tessellate_periodic pass
// positions_of(t)).
// The per-cell half of compute_forces (each cell's energy and dE/dh on its
// Voronoi vertices, the closest pair), done by Mesh::advance() block by block
// as it reads the cells (pass it as advance's observer), so that
// compute_forces(..., &pass) only moves the vertex gradients onto the points.
// compute_forces uses it only when it covers the tessellation given (the
// same advance() call filled it, every cell was read) and that tessellation
// has no multifold vertex and no per-cell virial is asked for; otherwise it
// does everything itself.  Same arithmetic, same order: the same bits.
class CellPass;

// With want_virial false ForceOutput::virial stays zero (a run that takes
// the virial from LAMMPS's f dot r saves the work); the check that the
// forces are finite is made either way.  pass: see CellPass.
ForceOutput compute_forces(const Tessellation &t, const Points &pts, const int *type,
                           const Model &model, double *f, int f_stride,
                           double *cell_energy = nullptr, double *cell_virial = nullptr,
                           bool want_virial = true, const CellPass *pass = nullptr);

class CellPass : public CellObserver {
public:
  CellPass() = default;
  // pts, type, model and cell_energy as for compute_forces (pointers kept).
  CellPass(const Points &pts, const int *type, const Model &model, double *cell_energy) {
    set(pts, type, model, cell_energy);
  }
  void set(const Points &pts, const int *type, const Model &model, double *cell_energy) {
    pts_ = pts;
    type_ = type;
    model_ = &model;
    cell_energy_ = cell_energy;
    stamp_ = 0;
  }
  void begin(const Tessellation &t) override;
  void cells(const Tessellation &t, int c0, int c1) override;
  void end(const Tessellation &t) override;
  bool covers(const Tessellation &t) const;

  std::vector<Vec2> grad;  // dE/dh per triangle
  double energy = 0.0;
  double best2 = -1.0;
  int best_c = -1, best_q = -1;

private:
  Points pts_;
  const int *type_ = nullptr;
  const Model *model_ = nullptr;
  double *cell_energy_ = nullptr;
  int done_ = 0;
  unsigned long stamp_ = 0;
};

// Energy only (no gradient); used by tests and finite differences.
double compute_energy(const Tessellation &t, const int *type, const Model &model,
                      double *cell_energy = nullptr);

// The positions a periodic tessellation triangulated (owned then images), as
// a flat stride-2 array, for compute_forces.
std::vector<double> positions_of(const Tessellation &t);

// Periodic convenience: tessellate, compute forces, fold image forces onto
// their owners.  f receives n forces (stride 2, overwritten).
ForceOutput periodic_forces(const Box &box, const Points &pts, const int *type,
                            const Model &model, std::vector<double> &f,
                            std::vector<double> *cell_energy = nullptr);

}  // namespace tessera
