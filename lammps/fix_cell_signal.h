/* -*- c++ -*- ----------------------------------------------------------
   TESSERA package for LAMMPS: vertex models of cell tissues
   LAMMPS: https://www.lammps.org/

   Copyright (2026) the Tessera developers.  This software is distributed
   under the GNU General Public License, version 2 or (at your option) any
   later version.
   SPDX-License-Identifier: GPL-2.0-or-later

   See the README file in the package's directory (src/TESSERA).
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing authors: the Tessera developers
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(cell/signal,FixCellSignal);
// clang-format on
#else

#ifndef LMP_FIX_CELL_SIGNAL_H
#define LMP_FIX_CELL_SIGNAL_H

#include "fix.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixCellSignal : public Fix {
 public:
  FixCellSignal(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  void set_arrays(int) override;
  double compute_vector(int) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;

 protected:
  // A per-atom property the laws read or change (d_name of fix property/atom).
  struct Field {
    std::string name;       // without d_
    int index;              // in atom->dvector
    bool species;           // changed by this fix (has a law)
    double P, Pb, cb, k;    // exchange permeability, bath permeability and value, degradation
  };
  enum Kind { VAR, HILL, HILLR };
  struct Production {
    int target;    // field
    int kind;
    std::string text;    // the law as given, for error messages
    std::string var;     // VAR: variable name
    int ivar;
    double vmax, K, n;
    int input;                    // HILL/HILLR: field read
    bool mean;                    // the input's junction-weighted mean over the neighbours
    std::vector<double> value;    // VAR: this step's rate per owned atom
  };
  std::vector<Field> fields;
  std::vector<Production> laws;
  int nsub_fixed;    // substeps N (0: auto)
  int nsub_last;     // substeps of the last step
  class CellSource *pair;
  std::vector<int> species;    // the fields that are species
  bool any_bath = false;       // some species has a bath (Pb > 0)
  // The atoms the fix takes: the cells of its group (cell_group.h).  taken:
  // this step's flag per owned atom; all_taken: every atom is taken.
  std::vector<char> taken;
  bool all_taken = false;
  bool noted_particles = false;
  bool takes(int i) const;
  void mark_taken();
  // Per owned atom: free arc length (only with a bath or 'implicit yes').
  std::vector<double> freelen;
  // This step's junctions of each owned group cell with group cells
  // (compressed rows: local index and size), read once from the cells.
  // For group all, the cells' own rows; else a filtered copy.
  std::vector<int> nb_offset, nb_index;
  std::vector<double> nb_size;
  const int *row_offset = nullptr, *row_index = nullptr;
  const double *row_size = nullptr;
  // The junction-weighted mean over owned cell i's group neighbours of the
  // values x[stride * j].
  double mean_of(int i, const double *x, int stride) const;

  // Explicit substeps (fix_cell_signal_explicit.cpp): every field of owned
  // and ghost cells in one array, cell-major (value[nfields * i + f]), so
  // that one pass over the junctions serves every species; rates likewise.
  std::vector<double> value, drate, exch;
  std::vector<double *> exch_out;
  std::vector<double> coef_kneg, coef_P;    // per field: -k and P (0 if not a species)
  bool comm_packed = false;                 // forward-communicate `value`
  void pack_values();
  template <int NF, bool PLAIN>
  double explicit_pass(bool apply, double h, bool want_fastest, int &bad);
  double explicit_rates(bool apply, double h, bool want_fastest, int &bad);
  void explicit_apply(double dt);
  void explicit_step(double dt);
  double hill_term(const Production &p, int i, const double *x, int stride) const;

  int field_of(const char *arg, const char *keyword);
  void check_cells(const char *when);
  void check_values(const char *when);
  void evaluate_variables();
  void prepare_rows();
  void productions();
  void fail(size_t f, int i, double next, const std::string &otherwise, const double *x,
            int stride);
  // 'implicit yes': one backward-Euler step of exchange, bath and
  // degradation per step (fix_cell_signal_implicit.cpp).
  int implicit = 0;
  double *comm_vector = nullptr;     // forward-communicate this vector, not the fields
  double *comm_vector2 = nullptr;    // and this one after it, if given
  std::vector<double> rate;          // implicit: productions, nfields x nlocal
  // The solution x1 + xd, a correction, the solver's vectors, the
  // right-hand side and the residual.
  std::vector<double> cg_x, cg_xd, cg_d, cg_r, cg_p, cg_q, cg_b, cg_res;
  std::vector<double> cg_keep;          // x1 and xd before a correction
  std::vector<char> warned_implicit;    // per field: the accuracy warning was given
  void implicit_step(double dt);
  void forward_vectors(double *x, double *x2);
  double apply_matrix(const Field &f, double dt, double *x, double *out);
  double exchange_of(int i, const double *x1, const double *xd) const;
  double residual(const Field &f, double dt, const double *b, double *x1, double *xd, double *r);
  int cg(const Field &f, double dt, const double *rhs, double *x, double scale, double &reached);
  void inaccurate(const Field &f, double dt, double rel);
  double dot(const double *a, const double *b);
};

}    // namespace LAMMPS_NS

#endif
#endif
