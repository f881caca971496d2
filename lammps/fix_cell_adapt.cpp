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

   fix cell/adapt: per-cell parameters (d_area0, d_perim0, d_ka, d_kp of
   pair_style vertex/voronoi, or any d_name) follow atom-style variables
   during a run: every N steps, at the end of the step (after the forces,
   so that the variables may read this step's cells and species), each
   cell of the group gets its variable's value, which the next force
   computation uses.  The pair style's parameters must stay > 0: a value
   that is not stops the run naming the cell, the step and the variable.

   A run's setup computes the forces of its first step again.  When the
   last step of the previous run (or of the run a restart file continues)
   ended with this fix setting the properties, those forces must be
   computed with the values the step's own forces used, not the new ones:
   the fix keeps each cell's value from before it set it (per atom, moved
   with the atom and written to restart files), puts it back for the
   setup's forces and the new one after them.  So `run 5; run 5` and a
   restart at step 5 continue as `run 10` does.
------------------------------------------------------------------------- */

#include "fix_cell_adapt.h"

#include "atom.h"
#include "cell_group.h"
#include "comm.h"
#include "error.h"
#include "fix_cell_divide.h"
#include "force.h"
#include "group.h"
#include "input.h"
#include "memory.h"
#include "modify.h"
#include "cell_source.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;
using namespace FixConst;

static const char SYNTAX[] = "fix ID group cell/adapt N d_name v_name [d_name v_name ...]";
static const double NONE = std::numeric_limits<double>::quiet_NaN();

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

  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

FixCellAdapt::~FixCellAdapt()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(before);
}

int FixCellAdapt::setmask()
{
  // PRE_FORCE for setup_pre_force (pre_force itself does nothing)
  return PRE_FORCE | END_OF_STEP;
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
  pair = CellSource::find(lmp);
  check_growth();
}

/* fix cell/divide ... growth linear sets d_area0 before every step's
   forces: where both fixes take the same cells this fix's d_area0 never
   reaches the forces.  Said once. */

void FixCellAdapt::check_growth()
{
  if (warned_growth) return;
  bool area0 = false;
  for (const Target &t : targets) area0 = area0 || t.name == "area0";
  if (!area0) return;
  for (int k = 0; k < modify->nfix; k++) {
    auto *divide = dynamic_cast<FixCellDivide *>(modify->fix[k]);
    if (!divide || !divide->grows_area0()) continue;
    const int both = groupbit | group->bitmask[divide->igroup];
    int mine = 0, all = 0;
    for (int i = 0; i < atom->nlocal; i++)
      if ((atom->mask[i] & both) == both) mine = 1;
    MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MAX, world);
    if (!all) continue;
    warned_growth = true;
    if (comm->me == 0)
      error->warning(FLERR,
                     "fix {} cell/adapt sets d_area0, which fix {} cell/divide 'growth linear' "
                     "also sets, before every step's forces: for the cells of both groups the "
                     "forces use cell/divide's values and this fix's are lost; leave out one of "
                     "the two (growth driven by a variable: 'growth none' and this fix)",
                     id, divide->id);
    return;
  }
}

/* Whether the fix takes owned atom i: a cell of its group. */

bool FixCellAdapt::takes(int i) const
{
  return (atom->mask[i] & groupbit) && cell_group::is_cell(pair, atom->type[i]);
}

/* A run continuing from the step at whose end this fix set the
   properties: the setup's forces get the values that step's forces used. */

void FixCellAdapt::setup_pre_force(int /*vflag*/)
{
  const int nlocal = atom->nlocal;
  const size_t nt = targets.size();
  held.assign(nt * std::max(nlocal, 1), 0.0);
  restored.assign(std::max(nlocal, 1), 0);
  if (applied_step != update->ntimestep) return;
  for (int i = 0; i < nlocal; i++) {
    if (!takes(i) || std::isnan(before[i][0])) continue;
    restored[i] = 1;
    for (size_t k = 0; k < nt; k++) {
      double *d = atom->dvector[targets[k].index];
      held[nt * i + k] = d[i];
      d[i] = before[i][k];
    }
  }
}

/* After the setup's forces: the restored cells get back the values the
   last step set; cells this fix has not set yet (its first run, cells
   made since) get their variables' values. */

void FixCellAdapt::setup(int /*vflag*/)
{
  cell_group::note_particles(lmp, pair, igroup, fmt::format("fix {} cell/adapt", id),
                             "it leaves their properties as they are", noted_particles);
  const int nlocal = atom->nlocal;
  const size_t nt = targets.size();
  int fresh = 0, any = 0;
  for (int i = 0; i < nlocal; i++) {
    if (!takes(i)) continue;
    if (restored.size() > static_cast<size_t>(i) && restored[i]) {
      for (size_t k = 0; k < nt; k++) atom->dvector[targets[k].index][i] = held[nt * i + k];
    } else if (std::isnan(before[i][0])) {
      fresh = 1;
    }
  }
  held.clear();
  restored.clear();
  MPI_Allreduce(&fresh, &any, 1, MPI_INT, MPI_MAX, world);
  if (any) apply(true);
}

void FixCellAdapt::end_of_step()
{
  apply(false);
}

/* Every variable is evaluated before any property changes, so that one
   variable may read another's property at its value of this step.  With
   only_new, only the cells this fix has not set yet change. */

void FixCellAdapt::apply(bool only_new)
{
  const int nlocal = atom->nlocal;
  const size_t n = std::max(nlocal, 1);
  const size_t nt = targets.size();
  std::vector<char> set(n, 0);
  for (int i = 0; i < nlocal; i++) set[i] = takes(i) && (!only_new || std::isnan(before[i][0]));
  values.assign(nt * n, 0.0);
  modify->clearstep_compute();
  for (size_t k = 0; k < nt; k++) {
    const Target &t = targets[k];
    double *out = &values[k * n];
    input->variable->compute_atom(t.ivar, igroup, out, 1, 0);
    for (int i = 0; i < nlocal; i++) {
      if (!set[i]) continue;
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
  for (int i = 0; i < nlocal; i++) {
    if (!set[i]) continue;
    for (size_t k = 0; k < nt; k++) {
      double *d = atom->dvector[targets[k].index];
      before[i][k] = d[i];
      d[i] = values[k * n + i];
    }
  }
  applied_step = update->ntimestep;
}

/* ---- the per-atom values from before the last setting, as LAMMPS moves
   atoms between ranks and into restart files; the step of that setting in
   the global record ---- */

/* The properties' names, as one number (FNV-1a, 32 bits: exact in a
   double), to tell a restart file of this fix with other properties. */

double FixCellAdapt::names_key() const
{
  uint32_t h = 2166136261u;
  for (const Target &t : targets)
    for (const char c : t.name + '\n') h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
  return (double) h;
}

void FixCellAdapt::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  const double list[3] = {(double) applied_step, (double) targets.size(), names_key()};
  const int size = sizeof(list);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(list, sizeof(double), 3, fp);
}

/* The values kept for other properties are of no use: the run then starts
   as a first one (unpack_restart, called after this, drops them). */

void FixCellAdapt::restart(char *buf)
{
  const double *list = reinterpret_cast<const double *>(buf);
  foreign = !(list[1] == (double) targets.size() && list[2] == names_key());
  applied_step = foreign ? -1 : (bigint) list[0];
}

double FixCellAdapt::memory_usage()
{
  return (double) atom->nmax * targets.size() * sizeof(double);
}

void FixCellAdapt::grow_arrays(int nmax)
{
  memory->grow(before, nmax, static_cast<int>(targets.size()), "cell/adapt:before");
}

void FixCellAdapt::copy_arrays(int i, int j, int /*delflag*/)
{
  for (size_t k = 0; k < targets.size(); k++) before[j][k] = before[i][k];
}

/* An atom this fix has not set (one made by create_atoms or fix deposit,
   or present when the fix is defined).  A daughter of fix cell/divide is a
   copy of her mother, this value included. */

void FixCellAdapt::set_arrays(int i)
{
  for (size_t k = 0; k < targets.size(); k++) before[i][k] = NONE;
}

int FixCellAdapt::pack_exchange(int i, double *buf)
{
  const int nt = static_cast<int>(targets.size());
  for (int k = 0; k < nt; k++) buf[k] = before[i][k];
  return nt;
}

int FixCellAdapt::unpack_exchange(int nlocal, double *buf)
{
  const int nt = static_cast<int>(targets.size());
  for (int k = 0; k < nt; k++) before[nlocal][k] = buf[k];
  return nt;
}

int FixCellAdapt::pack_restart(int i, double *buf)
{
  const int nt = static_cast<int>(targets.size());
  buf[0] = nt + 1;
  for (int k = 0; k < nt; k++) buf[k + 1] = before[i][k];
  return nt + 1;
}

void FixCellAdapt::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  const int nt = static_cast<int>(targets.size());
  const bool same = !foreign && static_cast<int>(extra[nlocal][m]) == nt + 1;
  m++;
  for (int k = 0; k < nt; k++) before[nlocal][k] = same ? extra[nlocal][m + k] : NONE;
}

int FixCellAdapt::size_restart(int /*nlocal*/)
{
  return static_cast<int>(targets.size()) + 1;
}

int FixCellAdapt::maxsize_restart()
{
  return static_cast<int>(targets.size()) + 1;
}
