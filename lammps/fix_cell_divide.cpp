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

   fix cell/divide: cell division.  At the end of each step every cell of
   the group decides whether it divides (rate, cycle time or area trigger);
   the decision uses counter-based random numbers of (seed, atom ID, step),
   so the same cells divide on any number of ranks.  If any cell divides,
   the next step re-neighbors, and in its pre_exchange each mother is
   replaced by two daughters at +-d/2 along the division axis.  A daughter
   is a copy of its mother (velocity, polarity, image flags, every fix's
   per-atom state) with a new atom ID; IDs are given in the order of a
   global sorted list, again independent of the number of ranks.  The
   daughters (axis, placement, state): fix_cell_divide_daughters.cpp.
------------------------------------------------------------------------- */

#include "fix_cell_divide.h"

#include "cell_event_count.h"
#include "cell_event_log.h"

#include "atom.h"
#include "atom_vec.h"
#include "cell_events.h"
#include "cell_group.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_cell_death.h"
#include "fix_vertex_polygon.h"
#include "force.h"
#include "modify.h"
#include "math_const.h"
#include "memory.h"
#include "output.h"
#include "cell_source.h"
#include "region.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace cell_events;

static const char SYNTAX[] =
    "fix ID group cell/divide rate R|d_name | cycle T spread s | area Ac, seed S [axis "
    "random|long|short|polarity] [separation d] [growth none|linear] [region ID] [max N] "
    "[noise eta] [file path] [split d_name ...]";

struct FixCellDivide::Impl {
  cell_events::EventCount events;
  cell_events::EventLog log;
};

FixCellDivide::FixCellDivide(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), decide_time(0.0), cap_warned(false), region(nullptr), pair(nullptr),
    area0_index(-1), cellstate(nullptr), impl(new Impl), events(impl->events), log(impl->log)
{
  // The fix's clock starts at LAMMPS's time now (0 at the first run) and is
  // advanced by the fix itself: its value is kept in the restart file.
  clock = update->atime + (double) (update->ntimestep - update->atimestep) * update->dt;
  trigger = -1;
  axis = RANDOM;
  growth = 0;
  rate = cycle_mean = cycle_spread = area_max = 0.0;
  separation = 0.1;
  noise = 0.0;
  max_cells = -1;
  seed = -1;

  auto need = [&](int iarg, int n, const char *kw) {
    if (iarg + n >= narg)
      error->all(FLERR, "fix cell/divide: keyword '{}' needs {} value(s); syntax: {}", kw, n,
                 SYNTAX);
  };
  // One trigger per fix: a second one would silently replace the first.
  auto one_trigger = [&](int iarg, int n) {
    std::string text = arg[iarg];
    for (int k = 1; k <= n; k++) text += std::string(" ") + arg[iarg + k];
    if (trigger >= 0)
      error->all(FLERR,
                 "fix cell/divide: two triggers, '{}' and '{}'; give one (rate R, cycle T spread "
                 "s or area Ac), or define a second fix cell/divide for another group",
                 trigger_text, text);
    trigger_text = text;
  };
  int iarg = 3;
  while (iarg < narg) {
    const char *kw = arg[iarg];
    if (strcmp(kw, "rate") == 0) {
      need(iarg, 1, kw);
      one_trigger(iarg, 1);
      trigger = RATE;
      if (strncmp(arg[iarg + 1], "d_", 2) == 0 && arg[iarg + 1][2]) {
        rate_name = arg[iarg + 1] + 2;    // per cell, read at every decision
        rate = 0.0;
      } else {
        rate = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      }
      if (!(rate >= 0.0) || !std::isfinite(rate))
        error->all(FLERR,
                   "fix cell/divide: rate R must be >= 0 (divisions per cell per time), got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(kw, "cycle") == 0) {
      need(iarg, 3, kw);
      one_trigger(iarg, 3);
      trigger = CYCLE;
      cycle_mean = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (strcmp(arg[iarg + 2], "spread") != 0)
        error->all(FLERR, "fix cell/divide: expected 'cycle T spread s', got 'cycle {} {}'",
                   arg[iarg + 1], arg[iarg + 2]);
      cycle_spread = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
      if (!(cycle_mean > 0.0) || !std::isfinite(cycle_mean))
        error->all(FLERR, "fix cell/divide: cycle time T must be > 0, got {}", arg[iarg + 1]);
      if (!(cycle_spread >= 0.0) || !(cycle_spread < cycle_mean))
        error->all(FLERR,
                   "fix cell/divide: cycle spread s must be >= 0 and < T = {} (cycle times are "
                   "uniform in [T-s, T+s]), got {}",
                   cycle_mean, arg[iarg + 3]);
      iarg += 4;
    } else if (strcmp(kw, "area") == 0) {
      need(iarg, 1, kw);
      one_trigger(iarg, 1);
      trigger = AREA;
      area_max = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(area_max > 0.0) || !std::isfinite(area_max))
        error->all(FLERR, "fix cell/divide: area Ac must be > 0, got {}", arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(kw, "seed") == 0) {
      need(iarg, 1, kw);
      seed = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (seed <= 0) error->all(FLERR, "fix cell/divide: seed must be > 0, got {}", arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(kw, "axis") == 0) {
      need(iarg, 1, kw);
      const char *v = arg[iarg + 1];
      if (strcmp(v, "random") == 0)
        axis = RANDOM;
      else if (strcmp(v, "long") == 0)
        axis = LONG;
      else if (strcmp(v, "short") == 0)
        axis = SHORT;
      else if (strcmp(v, "polarity") == 0)
        axis = POLARITY;
      else
        error->all(FLERR, "fix cell/divide: axis must be random, long, short or polarity, got '{}'",
                   v);
      iarg += 2;
    } else if (strcmp(kw, "separation") == 0) {
      need(iarg, 1, kw);
      separation = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(separation > 0.0) || !std::isfinite(separation))
        error->all(FLERR,
                   "fix cell/divide: separation d must be > 0 (daughters at +-d/2 from the "
                   "mother's centre), got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(kw, "growth") == 0) {
      need(iarg, 1, kw);
      if (strcmp(arg[iarg + 1], "none") == 0)
        growth = 0;
      else if (strcmp(arg[iarg + 1], "linear") == 0)
        growth = 1;
      else
        error->all(FLERR, "fix cell/divide: growth must be none or linear, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(kw, "region") == 0) {
      need(iarg, 1, kw);
      region_id = arg[iarg + 1];
      if (!find_region(domain, region_id))
        error->all(FLERR,
                   "fix cell/divide: region '{}' does not exist; define it with 'region' first",
                   region_id);
      iarg += 2;
    } else if (strcmp(kw, "max") == 0) {
      need(iarg, 1, kw);
      max_cells = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      if (max_cells < 1)
        error->all(FLERR, "fix cell/divide: max N must be >= 1 cells, got {}", arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(kw, "noise") == 0) {
      need(iarg, 1, kw);
      noise = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(noise >= 0.0) || !std::isfinite(noise))
        error->all(FLERR,
                   "fix cell/divide: noise eta must be >= 0 (radians; daughters' polarities "
                   "turn by a uniform angle in [-eta, eta]), got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(kw, "file") == 0) {
      need(iarg, 1, kw);
      log.configure(lmp, id, "cell/divide", arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(kw, "split") == 0) {
      // Per-cell amounts (d_name) the daughters share: each gets half.
      need(iarg, 1, kw);
      if (strncmp(arg[iarg + 1], "d_", 2) != 0 || !arg[iarg + 1][2])
        error->all(FLERR, "fix cell/divide: split expects d_name (fix property/atom), got '{}'",
                   arg[iarg + 1]);
      split_names.emplace_back(arg[iarg + 1] + 2);
      iarg += 2;
    } else {
      error->all(FLERR, "fix cell/divide: unknown keyword '{}'; syntax: {}", kw, SYNTAX);
    }
  }
  if (trigger < 0)
    error->all(FLERR,
               "fix cell/divide: give a trigger: rate R, cycle T spread s, or area Ac; syntax: {}",
               SYNTAX);
  if (seed < 0) error->all(FLERR, "fix cell/divide: keyword 'seed S' is required");
  if (growth && trigger == AREA)
    error->all(FLERR,
               "fix cell/divide: growth linear needs a cycle time (trigger 'rate R', mean cycle "
               "1/R, or 'cycle T spread s'), not 'area'");
  if (growth && trigger == RATE && rate == 0.0 && rate_name.empty())
    error->all(FLERR, "fix cell/divide: growth linear with rate 0 has no cycle time (1/R)");
  if (axis == POLARITY && !atom->mu_flag)
    error->all(FLERR,
               "fix cell/divide: axis polarity needs atom_style dipole (the polarity is mu)");
  if (!atom->tag_enable) error->all(FLERR, "fix cell/divide requires atom IDs");

  force_reneighbor = 1;
  next_reneighbor = -1;
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 2;
  global_freq = 1;
  extscalar = 0;
  extvector = 0;
  peratom_flag = 1;
  size_peratom_cols = NCOL;
  peratom_freq = 1;
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);

  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
  if (trigger == CYCLE) {
    // A random phase, so that the first generation does not divide at once.
    const tagint *tag = atom->tag;
    for (int i = 0; i < atom->nlocal; i++)
      cellstate[i][AGE] = uniform01(seed, tag[i], CREATION, PHASE) * cellstate[i][CYCLE_TIME];
  }
}

FixCellDivide::~FixCellDivide()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(cellstate);
}

int FixCellDivide::setmask()
{
  return PRE_FORCE | END_OF_STEP | PRE_EXCHANGE;
}

void FixCellDivide::init()
{
  // The vertex model divides a cell by a new edge through it
  // (fix_cell_divide_vertex.cpp), through its internal fix.
  vertex = nullptr;
  deaths.clear();
  int ndivide = 0;
  for (int k = 0; k < modify->nfix; k++) {
    if (strcmp(modify->fix[k]->style, "cell/death") == 0)
      deaths.push_back(dynamic_cast<FixCellDeath *>(modify->fix[k]));
    if (strcmp(modify->fix[k]->style, "VERTEX_POLYGON") == 0)
      vertex = dynamic_cast<FixVertexPolygon *>(modify->fix[k]);
    if (strcmp(modify->fix[k]->style, "cell/divide") == 0) ndivide++;
  }
  if (vertex && ndivide > 1)
    error->all(FLERR,
               "fix cell/divide {}: pair_style vertex/polygon takes one fix cell/divide ({} are "
               "defined): its divisions need the ghost atoms, which the first one's new atoms "
               "replace; give the cells of every group one fix (a per-cell rate: rate d_name)",
               id, ndivide);
  log.open();
  region = nullptr;
  if (!region_id.empty()) {
    region = find_region(domain, region_id);
    if (!region) error->all(FLERR, "fix cell/divide: region '{}' no longer exists", region_id);
  }
  pair = CellSource::find(lmp);
  if (!pair && (trigger == AREA || axis == LONG || axis == SHORT))
    error->all(FLERR,
               "fix cell/divide: the area trigger and axis long/short need {} (its cells give "
               "the cells' shapes)",
               CellSource::styles());
  int flag = -1, cols = -1;
  split_index.clear();
  for (const std::string &name : split_names) {
    split_index.push_back(atom->find_custom(name.c_str(), flag, cols));
    if (split_index.back() < 0 || flag != 1 || cols != 0)
      error->all(FLERR,
                 "fix cell/divide: split d_{}: no such per-atom property; define it with 'fix "
                 "ID all property/atom d_{}'",
                 name, name);
  }
  rate_index = -1;
  if (!rate_name.empty()) {
    rate_index = atom->find_custom(rate_name.c_str(), flag, cols);
    if (rate_index < 0 || flag != 1 || cols != 0)
      error->all(FLERR,
                 "fix cell/divide: rate d_{}: no such per-atom property; define it with 'fix ID "
                 "all property/atom d_{}' and give every cell a rate with 'set'",
                 rate_name, rate_name);
  }
  area0_index = atom->find_custom("area0", flag, cols);
  if (area0_index >= 0 && (flag != 1 || cols != 0)) area0_index = -1;
  if (growth && area0_index < 0)
    error->all(FLERR,
               "fix cell/divide: growth linear changes each cell's preferred area, which needs "
               "'fix property/atom d_area0' (and 'set group all d_area0 A0')");
  // Daughters go d/2 either way from the mother; a periodic box wraps an
  // atom only once, and d beyond its length has no meaning (LAMMPS would
  // lose the daughters).
  const double prd[3] = {domain->xprd, domain->yprd, domain->zprd};
  for (int d = 0; d < domain->dimension; d++)
    if (domain->periodicity[d] && separation >= prd[d])
      error->all(FLERR,
                 "fix cell/divide: separation {} is not smaller than the periodic box length {} "
                 "along {}: the daughters, {} from the mother, would be lost; use a separation "
                 "below a cell diameter (default 0.1)",
                 separation, prd[d], "xyz"[d], 0.5 * separation);
}

/* Whether the fix takes owned atom i: a cell of its group (particles in
   the group neither age, grow nor divide). */

bool FixCellDivide::takes(int i) const
{
  if (!(atom->mask[i] & groupbit) || !cell_group::is_cell(pair, atom->type[i])) return false;
  for (const FixCellDeath *d : deaths)
    if (d->dying(i)) return false;
  return true;
}

/* The base preferred area of cells that have none yet (before the first run,
   or cells that entered the group): their d_area0 now. */

void FixCellDivide::fill_base_area0()
{
  if (area0_index < 0) return;
  const double *a0 = atom->dvector[area0_index];
  for (int i = 0; i < atom->nlocal; i++)
    if (!(cellstate[i][AREA0_BASE] > 0.0)) cellstate[i][AREA0_BASE] = a0[i];
}

/* Preferred areas of the current step: A0 grows linearly from its base to
   twice the base over the cell's cycle, and stays there if the cell does not
   divide (max N reached, a region it left). */

void FixCellDivide::set_area0()
{
  if (!growth || area0_index < 0) return;
  double *a0 = atom->dvector[area0_index];
  for (int i = 0; i < atom->nlocal; i++) {
    if (!takes(i)) continue;
    // (a cell of rate 0 has an infinite cycle: it keeps its base)
    const double cyc = trigger == CYCLE ? cellstate[i][CYCLE_TIME]
                                        : 1.0 / (rate_index < 0 ? rate : cell_rate(i));
    const double base = cellstate[i][AREA0_BASE];
    if (base > 0.0) a0[i] = base * (1.0 + MIN(cellstate[i][AGE] / cyc, 1.0));
  }
}

/* The ages and preferred areas of a step are set before its forces: in
   pre_force during a run, in setup_pre_force (without ageing) at the start
   of a run.  The forces at a step then depend on the state of that step
   alone, so a run split in two, or continued from a restart file, computes
   the same forces as an uninterrupted run. */

void FixCellDivide::setup_pre_force(int /*vflag*/)
{
  fill_base_area0();
  set_area0();
}

void FixCellDivide::pre_force(int /*vflag*/)
{
  clock += update->dt;
  for (int i = 0; i < atom->nlocal; i++)
    if (takes(i)) cellstate[i][AGE] += update->dt;
  set_area0();
}

/* The decisions of the current step are (re)made at the setup of every run:
   they are kept in memory only until the event at the next step, so a run
   continued from a restart file makes the same ones as an uninterrupted run
   (the restart holds the ages and positions they depend on). */

void FixCellDivide::setup(int /*vflag*/)
{
  cell_group::note_particles(lmp, pair, igroup, fmt::format("fix {} cell/divide", id),
                             "they neither age, grow nor divide", noted_particles);
  fill_base_area0();
  decide();
}

double FixCellDivide::draw_cycle(tagint tag, uint64_t step) const
{
  if (trigger != CYCLE) return 0.0;
  return cycle_mean + cycle_spread * (2.0 * uniform01(seed, tag, step, CYCLE) - 1.0);
}

/* This step's division decisions (the ages were advanced in pre_force). */

void FixCellDivide::end_of_step()
{
  decide();
}

void FixCellDivide::decide()
{
  const int nlocal = atom->nlocal;
  const tagint *tag = atom->tag;
  double **x = atom->x;
  const double dt = update->dt;
  const uint64_t step = update->ntimestep;

  const bool need_tess = trigger == AREA || axis == LONG || axis == SHORT;
  if (need_tess) pair->require_current_cells(fmt::format("fix cell/divide {}", id));
  if (region) region->prematch();

  std::vector<std::pair<double, tagint>> mine;
  pending.clear();
  decide_time = clock;
  for (int i = 0; i < nlocal; i++) {
    if (!takes(i)) continue;
    if (region && !region->match(x[i][0], x[i][1], x[i][2])) continue;
    bool divide = false;
    if (trigger == RATE)
      divide = uniform01(seed, tag[i], step, DIVIDE) < (rate_index < 0 ? rate : cell_rate(i)) * dt;
    else if (trigger == CYCLE)
      divide = cellstate[i][AGE] >= cellstate[i][CYCLE_TIME];
    else
      divide = pair->cells().measure(i) > area_max;
    if (!divide) continue;
    std::array<double, 3> u;
    cell_axis(i, u.data());
    pending[tag[i]] = u;
    mine.push_back({uniform01(seed, tag[i], step, PRIORITY), tag[i]});
  }

  int nmine = static_cast<int>(mine.size()), nall = 0;
  MPI_Allreduce(&nmine, &nall, 1, MPI_INT, MPI_SUM, world);
  daughter_tag.clear();
  if (nall == 0) return;
  std::vector<std::pair<double, tagint>> all = gather_sorted(mine, world);
  const bigint room = cap_room();
  if ((bigint) all.size() > room) {
    warn_cap((bigint) all.size() - room);
    all.resize(room);
  }
  if (all.empty()) {
    pending.clear();
    return;
  }
  // Daughter IDs are assigned at the event (after any deaths) from this order.
  for (size_t k = 0; k < all.size(); k++) daughter_tag[all[k].second] = static_cast<tagint>(k);
  next_reneighbor = update->ntimestep + 1;
  if (vertex) vertex->division_step = next_reneighbor;
}

/* How many more cells max N allows now (no cap: any number).  It counts
   the cells of the whole system, so that several fix cell/divide
   commands, or deaths in between, share the one cap; particles do not
   count.  Collective. */

bigint FixCellDivide::cap_room() const
{
  if (max_cells <= 0) return MAXBIGINT;
  return MAX((bigint) 0, max_cells - cell_group::count_cells(lmp, pair));
}

/* The cap stops m divisions: with growth linear the cells that may not
   divide keep growing to twice their base preferred area, once, say so. */

void FixCellDivide::warn_cap(bigint m)
{
  if (!growth || cap_warned || m <= 0) return;
  cap_warned = true;
  if (comm->me == 0)
    error->warning(FLERR,
                   "fix {} cell/divide: 'max {}' stops divisions from step {} on, while 'growth "
                   "linear' goes on: cells that may not divide keep their preferred area d_area0 "
                   "at twice its base (once their age reaches their cycle time); raise max, or "
                   "leave out growth linear if the tissue should not swell",
                   id, max_cells, update->ntimestep);
}

/* The division rate of owned cell i from 'rate d_name', which must be
   finite and >= 0. */

double FixCellDivide::cell_rate(int i) const
{
  const double r = atom->dvector[rate_index][i];
  if (!(r >= 0.0) || !std::isfinite(r))
    error->one(FLERR,
               "fix cell/divide {}: rate d_{} of cell {} is {} at step {}; it must be >= 0 and "
               "finite (divisions per cell per time)",
               id, rate_name, atom->tag[i], r, update->ntimestep);
  return r;
}

double FixCellDivide::compute_scalar()
{
  return (double) events.total;
}

double FixCellDivide::compute_vector(int n)
{
  return events.vector(n, update->ntimestep);
}
