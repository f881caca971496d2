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

   The interface between an overdamped integrator that takes more than one
   force evaluation per step (fix brownian/heun) and the fixes whose own
   per-atom degrees of freedom must follow the positions in the same scheme
   (fix polarity's angles).  A fix with such degrees of freedom implements
   CoupledDof; the integrator implements CoupledIntegrator.

   Without a CoupledIntegrator among the fixes, a CoupledDof fix advances its
   degrees of freedom itself (fix polarity: forward Euler in its
   initial_integrate), which is how it works with fix brownian (Tessera's or
   upstream LAMMPS's).  With one, it leaves that to the integrator, which in
   each step calls, for the local atoms 0..nlocal-1:

     coupled_rate(k1, step - 1)     the rate dq/dt at the state the step starts from
     coupled_noise(w)               this step's noise increment (the same in both stages)
     coupled_advance(dt k1 + w)     predictor
     ... positions predicted, ghosts updated, forces recomputed (pair style
     ... and every fix's post_force, so the coupled fix sees the predicted state)
     coupled_rate(k2, step)         the rate at the predicted state
     coupled_advance(dt/2 (k2 - k1))  corrector

   Values for atom i live at q[i * stride + k], k < coupled_size().  Atoms
   outside the coupled fix's group get rate and noise 0 and are not changed.
   An increment is added to the degree of freedom (for an angle: a rotation
   by that angle), so the integrator stores no absolute values and needs
   nothing from the coupled fix when atoms migrate.
------------------------------------------------------------------------- */

#ifndef TESSERA_COUPLED_DOF_H
#define TESSERA_COUPLED_DOF_H

#include "lmptype.h"

#include <memory>

namespace LAMMPS_NS {

class FixPolarity;

class CoupledDof {
 public:
  static constexpr const char *extract_name = "tessera/coupled_dof";
  static constexpr const char *integrator_name = "tessera/coupled_integrator";
  // fix polarity's side (fix_polarity_coupled.cpp), which the fix owns.
  static std::unique_ptr<CoupledDof> of(FixPolarity &);
  virtual ~CoupledDof() = default;

  // Number of scalar degrees of freedom per atom.
  virtual int coupled_size() const = 0;
  // Deterministic rate dq/dt at the current positions, degrees of freedom,
  // forces and velocities (atom->v holds the drift velocity of this state,
  // F / gamma_t, for the integrator's atoms); state_step is the timestep whose
  // force computation (and tessellation) describes the current positions,
  // checked by the fix.
  virtual void coupled_rate(double *rate, int stride, bigint state_step) = 0;
  // The stochastic increment of this timestep (zero without noise).
  virtual void coupled_noise(double *w, int stride) = 0;
  // q += dq for the local atoms of the fix's group.
  virtual void coupled_advance(const double *dq, int stride) = 0;

  // For an integrator that may reject a step and take it again with a
  // smaller timestep (fix brownian/heun with 'adapt'):
  //
  //   coupled_state_size()             doubles per atom that hold the state
  //   coupled_save(q) / coupled_restore(q)   a copy of that state and back,
  //                                    bit for bit, for the local atoms
  //   coupled_wiener_size()            independent Wiener processes per atom
  //                                    that drive the noise (0: no noise)
  //   coupled_wiener_increment(dW, w)  the increment w of the degrees of
  //                                    freedom for the Wiener increments dW
  //                                    (each of variance h for a step h)
  //
  // Such an integrator chooses the noise itself (a rejected step's Wiener
  // increment is split by a Brownian bridge, not drawn anew) and calls
  // coupled_wiener_increment instead of coupled_noise.  A fix whose state
  // size is 0 cannot be integrated that way (the integrator says so).
  virtual int coupled_state_size() const { return 0; }
  virtual void coupled_save(double * /*q*/, int /*stride*/) {}
  virtual void coupled_restore(const double * /*q*/, int /*stride*/) {}
  virtual int coupled_wiener_size() const { return 0; }
  virtual void coupled_wiener_increment(const double * /*dW*/, int /*wstride*/, double * /*w*/,
                                        int /*stride*/)
  {
  }
};

}    // namespace LAMMPS_NS

#endif
