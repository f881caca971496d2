/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   fix cell/adapt: per-cell parameters (d_area0, d_perim0, d_ka, d_kp of
   pair_style vertex/voronoi, or any d_name) follow atom-style variables
   during a run: every N steps, at the end of the step (after the forces,
   so that the variables may read this step's cells and species), each
   cell of the group gets its variable's value, which the next force
   computation uses.  The pair style's parameters must stay > 0: a value
   that is not stops the run naming the cell, the step and the variable.
------------------------------------------------------------------------- */

#include "fix_cell_adapt.h"

#include "atom.h"
#include "error.h"
#include "input.h"
#include "modify.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

static const char SYNTAX[] = "fix ID group cell/adapt N d_name v_name [d_name v_name ...]";

FixCellAdapt::FixCellAdapt(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  if (narg < 6 || (narg - 4) % 2)
    error->all(FLERR, "fix cell/adapt: give N and pairs of d_name v_name; syntax: {}", SYNTAX);
  nevery = utils::inumeric(FLERR, arg[3], false, lmp);
  if (nevery < 1) error->all(FLERR, "fix cell/adapt: N must be >= 1 steps, got {}", arg[3]);
  for (int iarg = 4; iarg < narg; iarg += 2) {
    if (strncmp(arg[iarg], "d_", 2) != 0 || !arg[iarg][2])
      error->all(FLERR, "fix cell/adapt: expected a per-cell property d_name, got '{}'; syntax: {}",
                 arg[iarg], SYNTAX);
    if (strncmp(arg[iarg + 1], "v_", 2) != 0 || !arg[iarg + 1][2])
      error->all(FLERR, "fix cell/adapt: {} needs an atom-style variable v_name, got '{}'",
                 arg[iarg], arg[iarg + 1]);
    Target t;
    t.name = arg[iarg] + 2;
    t.var = arg[iarg + 1] + 2;
    t.index = t.ivar = -1;
    t.positive = t.name == "area0" || t.name == "perim0" || t.name == "ka" || t.name == "kp";
    for (const Target &o : targets)
      if (o.name == t.name)
        error->all(FLERR, "fix cell/adapt: d_{} is given twice; give each property once", t.name);
    targets.push_back(t);
  }
  if (!atom->tag_enable) error->all(FLERR, "fix cell/adapt requires atom IDs");
}

int FixCellAdapt::setmask()
{
  return END_OF_STEP;
}

void FixCellAdapt::init()
{
  for (Target &t : targets) {
    int flag = -1, cols = -1;
    t.index = atom->find_custom(t.name.c_str(), flag, cols);
    if (t.index < 0 || flag != 1 || cols != 0)
      error->all(FLERR,
                 "fix cell/adapt {}: d_{} is no per-atom property; define it with 'fix ID all "
                 "property/atom d_{}' and give every cell a value with 'set'",
                 id, t.name, t.name);
    t.ivar = input->variable->find(t.var.c_str());
    if (t.ivar < 0) error->all(FLERR, "fix cell/adapt {}: no variable named '{}'", id, t.var);
    if (!input->variable->atomstyle(t.ivar))
      error->all(FLERR, "fix cell/adapt {}: variable {} is not atom-style", id, t.var);
  }
}

/* At the start of a run the parameters are set from the variables (which may read
   the cells: the setup's forces have been computed). */

void FixCellAdapt::setup(int /*vflag*/)
{
  apply();
}

void FixCellAdapt::end_of_step()
{
  apply();
}

/* Every variable is evaluated before any property changes, so that one
   variable may read another's property at its value of this step. */

void FixCellAdapt::apply()
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  const size_t n = std::max(nlocal, 1);
  values.assign(targets.size() * n, 0.0);
  modify->clearstep_compute();
  for (size_t k = 0; k < targets.size(); k++) {
    const Target &t = targets[k];
    double *out = &values[k * n];
    input->variable->compute_atom(t.ivar, igroup, out, 1, 0);
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      const bool bad = t.positive ? !(out[i] > 0.0) || !std::isfinite(out[i])
                                  : !std::isfinite(out[i]);
      if (bad)
        error->one(FLERR,
                   "fix cell/adapt {}: variable {} gives d_{} = {} for cell {} at step {}; {}", id,
                   t.var, t.name, out[i], atom->tag[i], update->ntimestep,
                   t.positive ? "the pair style's parameters must be > 0 and finite"
                              : "values must be finite");
    }
  }
  modify->addstep_compute((update->ntimestep / nevery) * nevery + nevery);
  for (size_t k = 0; k < targets.size(); k++) {
    double *d = atom->dvector[targets[k].index];
    const double *out = &values[k * n];
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) d[i] = out[i];
  }
}
