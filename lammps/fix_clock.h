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
FixStyle(clock,FixClock);
// clang-format on
#else

#ifndef LMP_FIX_CLOCK_H
#define LMP_FIX_CLOCK_H

#include "fix.h"

namespace LAMMPS_NS {

/* fix ID group clock: the simulated time as a global scalar (f_ID) that
   continues across restart files on every LAMMPS version.  LAMMPS 29 Sep
   2021 does not store its elapsed time in restart files, and every LAMMPS
   starts `time` again at 0 when reset_timestep goes back; scripts whose
   physics follows the time (a sphere radius growing as exp(r t)) read f_ID
   instead.  Within a run f_ID is LAMMPS's own time plus an offset that is
   0 until LAMMPS's time breaks (so the two are the same number, bit for
   bit, in a script that never restarts); the offset is set at the start
   of a run when LAMMPS's time is not the clock's last value.  Steps taken
   by minimize do not advance it (the same clock as fix cell/divide's). */

class FixClock : public Fix {
 public:
  FixClock(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void post_run() override;
  double compute_scalar() override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  // Holds the value while a caller moves LAMMPS's time to probe what reads
  // it (fix_vertex_sphere.cpp), so that f_ID is not taken for 'time'.
  void hold(bool on);

 private:
  bool held = false;
  double held_value = 0.0;
  double offset;    // the clock minus LAMMPS's time during a run
  double last;      // the clock between runs (its value at the end of the last one)
  double lammps_time() const;
};

}    // namespace LAMMPS_NS

#endif
#endif
