// Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
//
// fix brownian/heun: the overdamped dynamics of fix brownian (same arguments)
// integrated by the stochastic Heun (predictor-corrector) scheme, together
// with the angles of fix polarity (through the CoupledDof interface of
// coupled_dof.h).  Documentation: doc/fix_brownian_heun.rst.

#ifdef FIX_CLASS
// clang-format off
FixStyle(brownian/heun,FixBrownianHeun);
// clang-format on
#else

#ifndef TESSERA_FIX_BROWNIAN_HEUN_H
#define TESSERA_FIX_BROWNIAN_HEUN_H

#include "coupled_dof.h"
#include "fix_brownian.h"

#include <vector>

namespace LAMMPS_NS {

class FixBrownianHeun : public FixBrownianTessera, public CoupledIntegrator {
 public:
  FixBrownianHeun(class LAMMPS *, int, char **);
  ~FixBrownianHeun() override;
  void init() override;
  void setup(int) override;
  void initial_integrate(int) override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;

 private:
  // Per atom, kept through the step's second force computation (which may
  // exchange atoms when the pair style widens its ghost shell): the force at
  // the start of the step (3), the noise displacement (3), the rates of the
  // coupled degrees of freedom at the start of the step (ncoupled).
  double **saved;
  int ncol;
  int nmax_saved;
  std::vector<CoupledDof *> coupled;
  std::vector<int> coupled_offset;    // first column of each coupled fix's rates
  int ncoupled;
  std::vector<double> scratch;

  void allocate_saved();
  void force_at_predicted_state();
  void drift_velocity();
  template <int NOISE, int THREE_D> void predict();
  template <int THREE_D> void correct();
};

}    // namespace LAMMPS_NS

#endif
#endif
