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

   fix cell/death: apoptosis (rate R) or extrusion (area below Amin).  As in
   fix cell/divide, cells decide at the end of a step with counter-based
   random numbers of (seed, atom ID, step), and are removed in the
   pre_exchange of the next step, which re-neighbors; the neighbouring
   Voronoi cells fill the space at once, so the tissue stays confluent.
------------------------------------------------------------------------- */

#include "fix_cell_death.h"

#include "cell_event_count.h"
#include "cell_event_log.h"

#include "atom.h"
#include "atom_vec.h"
#include "cell_events.h"
#include "cell_group.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "output.h"
#include "cell_source.h"
#include "memory.h"
#include "pair_vertex_voronoi.h"
#include "region.h"
#include "update.h"

#include <cmath>
#include <cstring>
#include <unordered_set>

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace cell_events;

// The fewest cells a tessellation of a sphere has (a tetrahedron's).
static constexpr bigint SPHERE_MIN_CELLS = 4;

static const char SYNTAX[] =
    "fix ID group cell/death rate R | area Amin, seed S [region ID] [min N] [file path]";

struct FixCellDeath::Impl {
  cell_events::EventCount events;
  cell_events::EventLog log;
};

FixCellDeath::FixCellDeath(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), region(nullptr), pair(nullptr), impl(new Impl), events(impl->events),
    log(impl->log)
{
  clock = update->atime + (double) (update->ntimestep - update->atimestep) * update->dt;
  trigger = -1;
  seed = -1;
  rate = area_min = 0.0;
  min_cells = 1;
  std::string trigger_text;

  auto need = [&](int iarg, const char *kw) {
    if (iarg + 1 >= narg)
      error->all(FLERR, "fix cell/death: keyword '{}' needs a value; syntax: {}", kw, SYNTAX);
  };
  int iarg = 3;
  while (iarg < narg) {
    const char *kw = arg[iarg];
    need(iarg, kw);
    const char *v = arg[iarg + 1];
    if ((strcmp(kw, "rate") == 0 || strcmp(kw, "area") == 0) && trigger >= 0)
      error->all(FLERR,
                 "fix cell/death: two triggers, '{}' and '{} {}'; give one (rate R or area Amin), "
                 "or define a second fix cell/death for another rule",
                 trigger_text, kw, v);
    if (strcmp(kw, "rate") == 0) {
      trigger = RATE;
      trigger_text = std::string(kw) + " " + v;
      rate = utils::numeric(FLERR, v, false, lmp);
      if (!(rate >= 0.0) || !std::isfinite(rate))
        error->all(FLERR, "fix cell/death: rate R must be >= 0 (deaths per cell per time), got {}",
                   v);
    } else if (strcmp(kw, "area") == 0) {
      trigger = AREA;
      trigger_text = std::string(kw) + " " + v;
      area_min = utils::numeric(FLERR, v, false, lmp);
      if (!(area_min > 0.0) || !std::isfinite(area_min))
        error->all(FLERR, "fix cell/death: area Amin must be > 0, got {}", v);
    } else if (strcmp(kw, "seed") == 0) {
      seed = utils::inumeric(FLERR, v, false, lmp);
      if (seed <= 0) error->all(FLERR, "fix cell/death: seed must be > 0, got {}", v);
    } else if (strcmp(kw, "region") == 0) {
      region_id = v;
      if (!find_region(domain, region_id))
        error->all(FLERR,
                   "fix cell/death: region '{}' does not exist; define it with 'region' first",
                   region_id);
    } else if (strcmp(kw, "min") == 0) {
      min_cells = min_user = utils::bnumeric(FLERR, v, false, lmp);
      if (min_cells < 0)
        error->all(FLERR,
                   "fix cell/death: min N must be >= 0 cells (0: every cell may die), got {}", v);
    } else if (strcmp(kw, "file") == 0) {
      log.configure(lmp, id, "cell/death", v);
    } else {
      error->all(FLERR, "fix cell/death: unknown keyword '{}'; syntax: {}", kw, SYNTAX);
    }
    iarg += 2;
  }
  if (trigger < 0)
    error->all(FLERR, "fix cell/death: give a trigger: rate R or area Amin; syntax: {}", SYNTAX);
  if (seed < 0) error->all(FLERR, "fix cell/death: keyword 'seed S' is required");
  if (!atom->tag_enable) error->all(FLERR, "fix cell/death requires atom IDs");
  if (atom->molecular)
    error->all(FLERR, "fix cell/death cannot remove atoms of a molecular system");

  force_reneighbor = 1;
  next_reneighbor = -1;
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 2;
  global_freq = 1;
  extscalar = 0;
  extvector = 0;
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

FixCellDeath::~FixCellDeath()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(dying_since);
}

int FixCellDeath::setmask()
{
  return END_OF_STEP | PRE_EXCHANGE;
}

void FixCellDeath::init()
{
  log.open();
  region = nullptr;
  if (!region_id.empty()) {
    region = find_region(domain, region_id);
    if (!region) error->all(FLERR, "fix cell/death: region '{}' no longer exists", region_id);
  }
  pair = CellSource::find(lmp);
  vertex = pair && pair->cells_are_vertices();
  if (vertex) init_vertex();
  // A tessellation of a sphere needs 4 cells: there the floor is at least 4.
  const bool sphere = pair && pair->on_sphere();
  if (sphere && min_user >= 0 && min_user < SPHERE_MIN_CELLS)
    error->all(FLERR,
               "fix cell/death: min {} is below the {} cells a tessellation of a sphere needs "
               "(pair_style vertex/voronoi ... surface sphere); use 'min {}' or more",
               min_user, SPHERE_MIN_CELLS, SPHERE_MIN_CELLS);
  min_cells = min_user >= 0 ? min_user : sphere ? SPHERE_MIN_CELLS : 1;
  warned_floor = 0;
  if (!pair && trigger == AREA)
    error->all(FLERR, "fix cell/death: the area trigger needs {} (its cells give the cells' areas)",
               CellSource::styles());
}

/* Whether the fix takes owned atom i: a cell of its group (particles in
   the group do not die). */

bool FixCellDeath::takes(int i) const
{
  return (atom->mask[i] & groupbit) && cell_group::is_cell(pair, atom->type[i]) && !dying(i);
}

/* How many cells may die now above the floor: the cells of the whole
   system count, particles do not.  Collective. */

bigint FixCellDeath::floor_room() const
{
  if (min_cells <= 0) return MAXBIGINT;
  // (the vertex model: cells that are dying are no longer living cells)
  const bigint dead = vertex ? count_dying() : 0;
  return MAX((bigint) 0, cell_group::count_cells(lmp, pair) - dead - min_cells);
}

/* As for fix cell/divide, a run's setup re-makes the current step's decisions. */

void FixCellDeath::setup(int /*vflag*/)
{
  cell_group::note_particles(lmp, pair, igroup, fmt::format("fix {} cell/death", id),
                             "they do not die, and the floor 'min' counts cells only",
                             noted_particles);
  decide();
}

void FixCellDeath::end_of_step()
{
  clock += update->dt;
  decide();
}

void FixCellDeath::decide()
{
  const int nlocal = atom->nlocal;
  const tagint *tag = atom->tag;
  double **x = atom->x;
  const uint64_t step = update->ntimestep;
  if (trigger == AREA)
    pair->require_current_cells(fmt::format("fix cell/death {} (trigger area)", id));
  if (region) region->prematch();

  std::vector<std::pair<double, tagint>> mine;
  pending.clear();
  for (int i = 0; i < nlocal; i++) {
    if (!takes(i)) continue;
    if (region && !region->match(x[i][0], x[i][1], x[i][2])) continue;
    const bool die = trigger == RATE ? uniform01(seed, tag[i], step, DEATH) < rate * update->dt
                                     : pair->cells().measure(i) < area_min;
    if (!die) continue;
    pending[tag[i]] = 0;
    mine.push_back({uniform01(seed, tag[i], step, DEATH_PRIORITY), tag[i]});
  }
  int nmine = static_cast<int>(mine.size()), nall = 0;
  MPI_Allreduce(&nmine, &nall, 1, MPI_INT, MPI_SUM, world);
  if (nall == 0) return;
  if (min_cells > 0) {
    // Keep at least min N cells: the first of the sorted list die, the same
    // ones on any number of ranks.  (min 0: every cell may die.)
    // Each keeps its place in the list, for the check at the event.
    std::vector<std::pair<double, tagint>> all = gather_sorted(mine, world);
    const bigint room = floor_room();
    if ((bigint) all.size() > room) {
      if (!warned_floor && comm->me == 0)
        error->warning(FLERR,
                       "fix cell/death {}: at step {} {} cells would die, but the floor 'min {}'{} "
                       "keeps {} of them alive: the tissue keeps at least {} cells (said once per "
                       "run)",
                       id, update->ntimestep, all.size(), min_cells,
                       min_user < 0 ? " (the default)" : "", (bigint) all.size() - room, min_cells);
      warned_floor = 1;
      all.resize(room);
    }
    std::unordered_set<tagint> local;
    for (const auto &m : mine) local.insert(m.second);
    pending.clear();
    for (size_t k = 0; k < all.size(); k++)
      if (local.count(all[k].second)) pending[all[k].second] = static_cast<bigint>(k);
    if (all.empty()) return;
  }
  next_reneighbor = update->ntimestep + 1;
}

void FixCellDeath::pre_exchange()
{
  if (next_reneighbor != update->ntimestep) return;
  next_reneighbor = -1;
  if (vertex) {
    start_dying();
    return;
  }
  // min N again, against the cell count now: another fix cell/death may have
  // removed cells at this step since the decisions, so that the floor holds
  // for the whole system (divisions only add cells).
  const bigint room = floor_room();
  int ndel = 0;
  int i = 0;
  while (i < atom->nlocal) {
    const auto found = pending.find(atom->tag[i]);
    if (found != pending.end() && found->second < room) {
      log.add("death", atom->tag[i], 0, 0, atom->x[i]);
      atom->avec->copy(atom->nlocal - 1, i, 1);
      atom->nlocal--;
      ndel++;
    } else {
      i++;
    }
  }
  pending.clear();
  int nall = 0;
  MPI_Allreduce(&ndel, &nall, 1, MPI_INT, MPI_SUM, world);
  atom->natoms -= nall;
  events.record(nall, update->ntimestep);
  log.flush(clock + update->dt);    // the time of this step (end_of_step advances the clock)
  if (atom->map_style) {
    atom->nghost = 0;
    atom->map_init();
    atom->map_set();
  }
  if (nall > 0) refresh_dumps(output);
}

double FixCellDeath::compute_scalar()
{
  return (double) events.total;
}

double FixCellDeath::compute_vector(int n)
{
  return events.vector(n, update->ntimestep);
}

double FixCellDeath::memory_usage()
{
  return (double) atom->nmax * sizeof(double);
}

void FixCellDeath::grow_arrays(int nmax)
{
  memory->grow(dying_since, nmax, "cell/death:dying_since");
}

void FixCellDeath::copy_arrays(int i, int j, int /*delflag*/)
{
  dying_since[j] = dying_since[i];
}

void FixCellDeath::set_arrays(int i)
{
  dying_since[i] = 0.0;
}

int FixCellDeath::pack_exchange(int i, double *buf)
{
  buf[0] = dying_since[i];
  return 1;
}

int FixCellDeath::unpack_exchange(int nlocal, double *buf)
{
  dying_since[nlocal] = buf[0];
  return 1;
}

int FixCellDeath::pack_restart(int i, double *buf)
{
  buf[0] = 2;
  buf[1] = dying_since[i];
  return 2;
}

void FixCellDeath::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  dying_since[nlocal] = extra[nlocal][m + 1];
}

int FixCellDeath::size_restart(int /*nlocal*/)
{
  return 2;
}

int FixCellDeath::maxsize_restart()
{
  return 2;
}

/* The global record: the event count and clock (cell_events::EventCount). */

void FixCellDeath::write_restart(FILE *fp)
{
  if (comm->me == 0) events.write_restart(fp, clock);
}

void FixCellDeath::restart(char *buf)
{
  log.continuing();
  events.restart(buf, clock);
}
