/* ----------------------------------------------------------------------
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

   fix clock: a time that continues across restart files (see fix_clock.h).
------------------------------------------------------------------------- */

#include "fix_clock.h"

#include "comm.h"
#include "error.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

FixClock::FixClock(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg), offset(0.0)
{
  if (narg != 3)
    error->all(FLERR,
               "fix clock: takes no arguments after the style ('fix {} {} clock'), got {} more",
               arg[0], arg[1], narg - 3);
  scalar_flag = 1;
  global_freq = 1;
  extscalar = 0;
  restart_global = 1;
  // A fix defined during a script starts at LAMMPS's time now; one defined
  // after read_restart with the ID of the file's takes the file's value in
  // restart(), which LAMMPS calls after this constructor.
  last = lammps_time();
}

int FixClock::setmask()
{
  return 0;    // init and post_run are called for every fix
}

double FixClock::lammps_time() const
{
  return update->atime + static_cast<double>(update->ntimestep - update->atimestep) * update->dt;
}

/* At the start of a run (after LAMMPS's own init, which may have moved its
   time: LAMMPS 29 Sep 2021 starts it at 0 at the first run after
   read_restart, reset_timestep may too, and the steps of a minimize that
   LAMMPS counted drop out again only now): the clock goes on from its last
   value.  The offset changes only when the two disagree, so a script whose
   LAMMPS time never breaks reads exactly LAMMPS's time. */

void FixClock::init()
{
  if (update->whichflag != 1) return;    // minimize: the clock stands still
  const double t = lammps_time();
  if (offset + t == last) return;
  const double before = offset;
  offset = last - t;
  if (comm->me == 0 && before == 0.0)
    utils::logmesg(lmp,
                   "fix clock {}: the clock goes on at {:.8g} at step {}, where LAMMPS's own "
                   "time is {:.8g} (it restarted: LAMMPS 29 Sep 2021 does not keep it in restart "
                   "files, and reset_timestep can move it); read f_{} for the time, not 'time'\n",
                   id, last, update->ntimestep, t, id);
}

void FixClock::post_run()
{
  if (update->whichflag == 1) last = offset + lammps_time();
}

void FixClock::hold(bool on)
{
  if (on) held_value = compute_scalar();
  held = on;
}

double FixClock::compute_scalar()
{
  if (held) return held_value;
  return update->whichflag == 1 ? offset + lammps_time() : last;
}

void FixClock::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  const double value = compute_scalar();
  const int size = sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(&value, sizeof(double), 1, fp);
}

void FixClock::restart(char *buf)
{
  double value = 0.0;
  memcpy(&value, buf, sizeof(double));
  if (!std::isfinite(value))
    error->all(FLERR, "fix clock {}: the restart file holds a non-finite time {}", id, value);
  last = value;
  offset = 0.0;
}
