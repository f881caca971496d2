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

   fix brownian/heun: the overdamped dynamics of fix brownian (same arguments)
   integrated by the stochastic Heun (predictor-corrector) scheme, together
   with the angles of fix polarity (through the CoupledDof interface of
   coupled_dof.h); with 'adapt', an error-controlled timestep (the Euler
   predictor and the Heun corrector as an embedded pair).  Documentation:
   doc/fix_brownian_heun.rst.  The step is in fix_brownian_heun.cpp, the
   adaptive step's controller, noise and restart in fix_brownian_heun_adapt.cpp.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(brownian/heun,FixBrownianHeun);
// clang-format on
#else

#ifndef TESSERA_FIX_BROWNIAN_HEUN_H
#define TESSERA_FIX_BROWNIAN_HEUN_H

#include "fix_brownian.h"

#include <cstdint>
#include <vector>

namespace LAMMPS_NS {

class CoupledDof;

class FixBrownianHeun : public FixBrownianTessera {
 public:
  FixBrownianHeun(class LAMMPS *, int, char **);
  ~FixBrownianHeun() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void initial_integrate(int) override;
  void *extract(const char *, int &) override;

  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

 private:
  // Per atom, kept through the step's second force computation (which may
  // exchange atoms when the pair style widens its ghost shell): in saved,
  // the force at the start of the step (3), the attempt's noise
  // displacement (3), the start position (3) and image flags (2), the
  // rates of the coupled degrees of freedom at the start (ncoupled) and,
  // with 'adapt', the coupled fixes' saved state (nstate).
  double **saved;
  int ncol;
  int nmax_saved;
  int col_k1, col_q0;
  std::vector<CoupledDof *> coupled;
  std::vector<int> coupled_offset;    // first column of each coupled fix's rates
  std::vector<int> state_offset;      // first column of each coupled fix's saved state
  std::vector<int> wiener_offset;     // first Wiener process of each coupled fix
  int ncoupled, nstate, nwiener_coupled;
  std::vector<double> scratch;     // the coupled increments of an attempt (ncoupled per atom)
  std::vector<double> wscratch;    // the Wiener increments of an attempt (nwiener per atom)

  void save_start();
  void predict_coupled();
  void corrector_coupled(bigint step);
  double error_ratio(double &estimate);
  void restore_start();
  void force_at_predicted_state();
  void drift_velocity();
  template <int NOISE, int THREE_D> void predict();
  template <int THREE_D> void correct();

  // ---- the adaptive step ('adapt', fix_brownian_heun_adapt.cpp) ----
  int adapt;
  double tol, tol_angle;    // error tolerances: length; radians for coupled dof
  double dtmin, dtmax;      // bounds (<= 0 before the first run: defaults)
  double safety, grow_max, shrink_min;
  double dt_next;                      // the controller's proposal for the next step
  double dt_set;                       // update->dt as this fix last set it
  bigint naccept, nreject, nforced;    // accepted steps, rejected attempts, accepted above tol
  double err_last, est_last;           // last accepted step: error / tol, estimate (length)
  int forced_warned;
  // The noise of the adaptive step: the revealed future of the Wiener
  // processes as a queue of intervals qtau (the same on every rank) with
  // their keys qid, and per atom in qbuf the owner's tag and the
  // increments (qcap intervals of nwiener); draws keys fresh numbers.
  double **qbuf;
  std::vector<double> qtau;
  std::vector<uint64_t> qid;
  int qcap;
  int nwiener;    // Wiener processes per atom: the positions' (rng gaussian) + the coupled fixes'
  uint64_t draws;
  uint64_t noise_seed;
  double diffusion_amp;    // sqrt(2 D) of the positions (rng gaussian)
  int consumed;            // queue intervals the current attempt uses

  void parse_adapt(int narg, char **arg);
  void init_adapt();
  void setup_adapt();
  void set_timestep(double h);
  void begin_adaptive_step();
  bool accept(double err);
  double controller(double h, double err, bool rejected);
  void finish_adaptive_step(double err, bool rejected);
  int qcols() const;
  void ensure_queue_capacity(int n);
  void fresh_queue_rows();
  void append_fresh(double h);
  void split_entry(int k, double first);
  void pop_queue(int n);
  void attempt_noise(double h);
};

}    // namespace LAMMPS_NS

#endif
#endif
