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

   The internal fix of pair_style vertex/polygon (see fix_vertex_polygon.h):
   its hooks, communication, the hand-over of the cell atoms' forces and the
   deletion of removed atoms.  The topology step itself:
   fix_vertex_polygon_topology.cpp.
------------------------------------------------------------------------- */

#include "fix_vertex_polygon.h"

#include "pair_vertex_polygon.h"
#include "tessera_compat.h"

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "modify.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace FixConst;

FixVertexPolygon::FixVertexPolygon(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  force_reneighbor = 1;
  next_reneighbor = -1;
  comm_forward = 2;
  comm_reverse = 2;
  // An atom another fix adds (fix deposit: particles) takes its local slot
  // with whatever i_vring held there (a ghost's ring): it starts with none.
  create_attribute = 1;
}

void FixVertexPolygon::set_arrays(int i)
{
  if (!pair || pair->ring_index < 0) return;
  int *ring = atom->iarray[pair->ring_index][i];
  for (int k = 0; k < pair->ring_width; k++) ring[k] = 0;
}

Fix *FixVertexPolygon::creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixVertexPolygon(lmp, narg, arg);
}

int FixVertexPolygon::setmask()
{
  int mask = 0;
  mask |= PRE_EXCHANGE;
  mask |= PRE_NEIGHBOR;
  mask |= MIN_PRE_NEIGHBOR;
  mask |= POST_FORCE;
  mask |= END_OF_STEP;
  return mask;
}

void FixVertexPolygon::init()
{
  if (!pair || force->pair_match("vertex/polygon", 1) != (Pair *) pair)
    error->all(FLERR, "Internal fix {} needs pair_style vertex/polygon", style);
  comm_forward = MAX(pair->ring_width, 2);
  pair->check_integrators();
  // Forces on cell atoms come from fixes with post_force (fix polarity,
  // fix addforce, ...): without any, there is nothing to hand over.
  transfer = 0;
  for (int k = 0; k < modify->nfix; k++)
    if (modify->fix[k] != this && (modify->fmask[k] & POST_FORCE)) transfer = 1;
  // Steps scheduled before (in this process, or before a restart file was
  // written) stay scheduled.
  const bigint now = update->ntimestep;
  next_reneighbor = -1;
  // fix cell/divide decides again at the setup of the run (and says so then).
  division_step = -1;
  for (bigint s : {pair->topology_step, pair->delete_step})
    if (s > now && (next_reneighbor < 0 || s < next_reneighbor)) next_reneighbor = s;
}

/* A run starts: atoms a T2 removed before a restart file was written go
   now; then the caches and checks. */

void FixVertexPolygon::setup_pre_exchange()
{
  delete_removed();
}

/* A run starts.  Unless the last run scheduled a topology step for the next
   step (then it comes at that step, as in one uninterrupted run), the
   candidates present now (a fresh tissue from create_vertices or a data
   file) are resolved before the first step, pass after pass. */

void FixVertexPolygon::setup_pre_neighbor()
{
  pair->epoch++;
  pair->refresh();
  if (update->whichflag == 1 && pair->topology_step != update->ntimestep + 1)
    for (int pass = 0; pass < 20 && run_topology() > 0; pass++) pair->epoch++;
  pair->refresh();
}

void FixVertexPolygon::setup(int vflag)
{
  post_force(vflag);
  request_steps();
  cell_velocities();
}

void FixVertexPolygon::pre_exchange()
{
  // Divisions at this step need the ghosts: they delete after dividing.
  if (update->ntimestep == pair->delete_step && division_step != update->ntimestep)
    delete_removed();
}

void FixVertexPolygon::delete_due()
{
  if (update->ntimestep == pair->delete_step) delete_removed();
}

void FixVertexPolygon::pre_neighbor()
{
  pair->epoch++;
  if (update->ntimestep == pair->topology_step) run_topology();
}

void FixVertexPolygon::min_pre_neighbor()
{
  pair->epoch++;
}

void FixVertexPolygon::end_of_step()
{
  request_steps();
  cell_velocities();
}

/* A cell atom has no integrator: its velocity is the mean of its vertices'
   velocities (which the integrators set to dr/dt of the step), i.e. the
   velocity of the mean of its corners. */

void FixVertexPolygon::cell_velocities()
{
  if (pair->cache_epoch != pair->epoch) return;    // no force computation yet
  mode = VELOCITY;
  tessera_compat::forward_comm(comm, this);
  double **v = atom->v;
  const int *type = atom->type;
  for (int i = 0; i < atom->nlocal; i++) {
    if (pair->role(type[i]) != PairVertexPolygon::CELL) continue;
    const int n = pair->off[i + 1] - pair->off[i];
    if (n == 0) continue;
    double vx = 0.0, vy = 0.0;
    for (int k = pair->off[i]; k < pair->off[i + 1]; k++) {
      vx += v[pair->ring_local[k]][0];
      vy += v[pair->ring_local[k]][1];
    }
    v[i][0] = vx / n;
    v[i][1] = vy / n;
    v[i][2] = 0.0;
  }
}

/* A topology step at the next step if some rank saw a candidate. */

void FixVertexPolygon::request_steps()
{
  int local = pair->request, any = 0;
  pair->request = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, world);
  if (any) {
    pair->topology_step = update->ntimestep + 1;
    next_reneighbor = update->ntimestep + 1;
  }
}

/* Each cell atom's force to its vertices, a third of it to each (Barton et
   al.'s active vertex model: a vertex moves with the mean of its three
   cells' forces), then zeroed. */

void FixVertexPolygon::post_force(int /*vflag*/)
{
  if (!transfer) return;
  if (pair->cache_epoch != pair->epoch) return;    // no force computation yet
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  double **f = atom->f;
  const int *type = atom->type;
  share.assign(2 * static_cast<size_t>(nall), 0.0);
  for (int i = 0; i < nlocal; i++) {
    if (pair->role(type[i]) != PairVertexPolygon::CELL) continue;
    const double fx = f[i][0] / 3.0, fy = f[i][1] / 3.0;
    f[i][0] = f[i][1] = f[i][2] = 0.0;
    for (int k = pair->off[i]; k < pair->off[i + 1]; k++) {
      const int j = pair->ring_local[k];
      share[2 * j] += fx;
      share[2 * j + 1] += fy;
    }
  }
  mode = SHARE;
  tessera_compat::reverse_comm(comm, this);
  for (int i = 0; i < nlocal; i++) {
    f[i][0] += share[2 * i];
    f[i][1] += share[2 * i + 1];
  }
}

void FixVertexPolygon::forward_rings()
{
  mode = RINGS;
  tessera_compat::forward_comm(comm, this);
}

void FixVertexPolygon::reverse_counts(std::vector<double> &count)
{
  counts = &count;
  mode = COUNT;
  tessera_compat::reverse_comm(comm, this);
  counts = nullptr;
}

int FixVertexPolygon::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                        int * /*pbc*/)
{
  int m = 0;
  if (mode == RINGS) {
    int **ring = atom->iarray[pair->ring_index];
    const int w = pair->ring_width;
    for (int k = 0; k < n; k++)
      for (int c = 0; c < w; c++) buf[m++] = ring[list[k]][c];
  } else if (mode == VELOCITY) {
    double **v = atom->v;
    for (int k = 0; k < n; k++) {
      buf[m++] = v[list[k]][0];
      buf[m++] = v[list[k]][1];
    }
  } else {
    // The owner's coordinates, without the periodic shift of the copy.
    for (int k = 0; k < n; k++) {
      buf[m++] = canon[2 * list[k]];
      buf[m++] = canon[2 * list[k] + 1];
    }
  }
  return m;
}

void FixVertexPolygon::unpack_forward_comm(int n, int first, double *buf)
{
  int m = 0;
  if (mode == RINGS) {
    int **ring = atom->iarray[pair->ring_index];
    const int w = pair->ring_width;
    for (int i = first; i < first + n; i++)
      for (int c = 0; c < w; c++) ring[i][c] = static_cast<int>(buf[m++]);
  } else if (mode == VELOCITY) {
    double **v = atom->v;
    for (int i = first; i < first + n; i++) {
      v[i][0] = buf[m++];
      v[i][1] = buf[m++];
    }
  } else {
    for (int i = first; i < first + n; i++) {
      canon[2 * i] = buf[m++];
      canon[2 * i + 1] = buf[m++];
    }
  }
}

int FixVertexPolygon::pack_reverse_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) {
    if (mode == SHARE) {
      buf[m++] = share[2 * i];
      buf[m++] = share[2 * i + 1];
    } else {
      buf[m++] = (*counts)[i];
    }
  }
  return m;
}

void FixVertexPolygon::unpack_reverse_comm(int n, int *list, double *buf)
{
  int m = 0;
  for (int k = 0; k < n; k++) {
    const int j = list[k];
    if (mode == SHARE) {
      share[2 * j] += buf[m++];
      share[2 * j + 1] += buf[m++];
    } else {
      (*counts)[j] += buf[m++];
    }
  }
}

/* The atoms a T2 removed (first entry of their i_vring row -1), deleted
   before atoms migrate, as fix evaporate deletes atoms. */

void FixVertexPolygon::delete_removed()
{
  int **ring = atom->iarray[pair->ring_index];
  int nlocal = atom->nlocal;
  int i = 0;
  bigint ndel = 0;
  while (i < nlocal) {
    if (ring[i][0] < 0) {
      atom->avec->copy(nlocal - 1, i, 1);
      nlocal--;
      ndel++;
    } else {
      i++;
    }
  }
  bigint all = 0;
  MPI_Allreduce(&ndel, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (all == 0) return;
  atom->nlocal = nlocal;
  bigint nblocal = nlocal;
  MPI_Allreduce(&nblocal, &atom->natoms, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (atom->map_style != 0) {
    atom->nghost = 0;
    atom->map_init();
    atom->map_set();
  }
}
