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

   Detection of an explicit overdamped integrator that chatters: forward
   Euler (and Heun) past its stability limit, or across a point where the
   force changes abruptly (a kink of the energy), does not blow up, it
   oscillates about the state with period two (each step overshoots and
   the next one comes back), so the energy alternates and a run looks
   plausible.  Used by fix brownian and fix brownian/heun (doc/fix_brownian.rst,
   "Chatter").  When the oscillation is found, a probe of the next PROBE
   steps names the atoms that alternate most and the force term that
   reverses on them (each sub-style of pair_style hybrid/overlay evaluated
   alone, and the rest: fixes, bonds), then warns once.
------------------------------------------------------------------------- */

#ifndef LMP_TESSERA_INTEGRATOR_CHATTER_H
#define LMP_TESSERA_INTEGRATOR_CHATTER_H

#include "lmptype.h"
#include "pointers.h"

#include <string>
#include <unordered_map>
#include <vector>

namespace LAMMPS_NS {

class IntegratorChatter : protected Pointers {
 public:
  // Over the last STEPS steps, the mean correlation of successive
  // displacements below which the steps chatter, and how much the squared
  // displacements may shrink over those steps (a decaying oscillation,
  // which converges, is no chatter).
  static constexpr int STEPS = 50;
  static constexpr double ANTI = -0.3;
  static constexpr double DECAY = 0.1;
  // Steps whose RMS displacement is below this times the box length are at
  // the positions' round-off and start the watch anew.
  static constexpr double FLOOR = 1e-10;
  // States the probe records (an even number: the alternating sum of a
  // constant force vanishes), and how many atoms the warning names.
  static constexpr int PROBE = 8;
  static constexpr int NAMED = 5;

  explicit IntegratorChatter(class LAMMPS *lmp) : Pointers(lmp) {}

  // What one step adds up over the group's atoms, in the integrator's own
  // loop over them (the components up to the dimension): v_old . v_new,
  // |v_old|^2, |v_new|^2 and the number of atoms, v_old being v before the
  // step (the previous step's displacement over dt, which fix brownian and
  // brownian/heun store there) and v_new this step's.
  enum { DOT, OLD2, NEW2, COUNT, NSUMS };
  static void add(double *sums, const double *v_old, const double *v_new, int ndim)
  {
    for (int d = 0; d < ndim; d++) {
      sums[DOT] += v_old[d] * v_new[d];
      sums[OLD2] += v_old[d] * v_old[d];
      sums[NEW2] += v_new[d] * v_new[d];
    }
    sums[COUNT] += 1.0;
  }
  // At the start of a step (positions and forces of the state the step
  // starts from, ghosts current): a no-op unless the probe runs, which
  // then records the group's atoms and the force terms on them.
  // Collective while the probe runs.
  void start(int groupbit);
  // At the end of the step, with this rank's sums (NSUMS values).
  // Collective (one MPI_Allreduce).  Starts the probe once per fix when over
  // the last STEPS steps the two displacement fields were on average
  // anti-parallel (weighted by their lengths) without dying out; the
  // warning follows when the probe has its PROBE states.
  void observe(const char *style, const char *id, const double *sums, double dt);

  // For an integrator that overwrites v within the step before the end of
  // it (fix brownian/heun's drift velocity for the coupled fixes): begin()
  // keeps v at the start of the step (and calls start()), end() makes the
  // sums from it and v at the end of the step and observes them (collective).
  void begin(int groupbit);
  void end(const char *style, const char *id, int groupbit, double dt);
  // The correlation sum(v_old.v_new) / sqrt(sum v_old^2 sum v_new^2) of
  // the last step observed (0 when either is zero).
  double last_correlation() const { return corr; }
  // Text added to the warning by the integrator (e.g. its adaptive step's
  // tolerance), set before the run.
  std::string context;

 private:
  std::vector<double> corrs, sizes;    // the last steps' correlations and squared displacements
  double corr = 0.0;
  bool warned = false;
  std::vector<double> before;    // v of the group's atoms at begin() (3 per atom)
  int nbefore = -1;              // nlocal at begin()

  // The probe: per atom ID, PROBE records of the unwrapped position (3)
  // and the force of each term (3 each); the terms' names; what the warning
  // reports about the oscillation that started it.
  int probing = 0;    // states recorded so far + 1 (0: no probe)
  std::unordered_map<tagint, std::vector<double>> records;
  std::vector<std::string> terms;
  std::string fix_style, fix_id;
  bigint first_step = 0, last_step = 0;
  double mean_corr = 0.0, probe_dt = 0.0;
  void record_state(int groupbit);
  void term_forces(std::vector<double> &forces);
  bool report();    // false: no atom kept the oscillation up (collective)
};

}    // namespace LAMMPS_NS

#endif
