/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   compute vertex/atom: per-cell observables of the Voronoi tessellation that
   pair_style vertex/voronoi computed (area, perimeter, shape index, number of
   neighbours, cell energy, velocity coordination and orientation), and
   global ones for thermo (mean shape index, multifold vertices, neighbour
   exchanges since the previous call).
------------------------------------------------------------------------- */

#include "compute_vertex_atom.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "pair_vertex_voronoi.h"
#include "tessera_compat.h"
#include "update.h"

#include "tessera/polarity.h"
#include "tessera/tessellation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

namespace {

constexpr int NCOLS = 9;

// Same criterion as Tessellation::coordination_number: an edge counts as a
// neighbour relation if it is longer than this fraction of the cell's mean
// edge length, so zero-length edges of multifold vertices do not.
constexpr double REL_TOL = 1e-9;

double edge_floor(const tessera::Tessellation &t, int c)
{
  const int o = t.cell_offset[c], m = t.cell_size(c);
  if (m == 0) return 0.0;
  double mean = 0.0;
  for (int k = 0; k < m; k++) mean += t.edge_length[o + k];
  return REL_TOL * mean / m;
}

}    // namespace

/* ----------------------------------------------------------------------
   compute ID group vertex/atom
------------------------------------------------------------------------- */

ComputeVertexAtom::ComputeVertexAtom(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0), values(nullptr), id_fix(nullptr), fix(nullptr), pair(nullptr),
    warned_overflow(0), rosette(0.0)
{
  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "rosette") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "compute vertex/atom: keyword 'rosette' needs a length L");
      rosette = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(rosette > 0.0))
        error->all(FLERR, "compute vertex/atom: rosette length must be > 0, got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else {
      error->all(FLERR,
                 "Illegal compute vertex/atom command: unknown keyword '{}' (known: rosette L; "
                 "'compute ID group vertex/atom [rosette L]')",
                 arg[iarg]);
    }
  }
  if (atom->tag_enable == 0)
    error->all(FLERR, "compute vertex/atom requires atom IDs (atom_modify id yes)");

  peratom_flag = 1;
  size_peratom_cols = NCOLS;
  vector_flag = 1;
  size_vector = 5;
  extvector = 0;
  comm_forward = 3;
  create_attribute = 1;
  // The neighbour memory is for the members of a fixed group.
  dynamic_group_allow = 0;

  vector = new double[size_vector];
  for (int k = 0; k < size_vector; k++) vector[k] = 0.0;

  // Voronoi neighbours of each atom at the previous compute_vector(), which
  // must migrate with the atoms: column 0 is how many tags follow (-1: none
  // yet, so nothing is counted for that atom), then up to MAXNEIGH tags of
  // neighbours with larger IDs, ascending.  Not written to restart files: a
  // restarted run starts counting afresh.
  id_fix = utils::strdup(std::string(id) + "_COMPUTE_STORE");
  fix = static_cast<tessera_compat::FixStorePerAtom *>(
      modify->add_fix(fmt::format("{} {} {}", id_fix, group->names[igroup],
                                  tessera_compat::store_peratom(MAXNEIGH + 1, false))));
  for (int i = 0; i < atom->nlocal; i++) fix->astore[i][0] = -1.0;
}

ComputeVertexAtom::~ComputeVertexAtom()
{
  // Modify deletes all fixes before the computes at the end of a run.
  if (modify->nfix && modify->find_fix(id_fix) >= 0) modify->delete_fix(id_fix);
  delete[] id_fix;
  delete[] vector;
  memory->destroy(values);
}

void ComputeVertexAtom::init()
{
  pair = dynamic_cast<PairVertexVoronoi *>(force->pair_match("vertex/voronoi", 1));
  if (!pair)
    error->all(FLERR,
               "compute vertex/atom {} reads the tessellation of pair_style vertex/voronoi, "
               "but the pair style is '{}'; define 'pair_style vertex/voronoi' (alone or as "
               "one sub-style of hybrid)",
               id, force->pair_style ? force->pair_style : "none");
  const int ifix = modify->find_fix(id_fix);
  if (ifix < 0)
    error->all(FLERR,
               "compute vertex/atom: its internal fix {} was deleted; re-create the compute "
               "(uncompute, then compute)",
               id_fix);
  fix = static_cast<tessera_compat::FixStorePerAtom *>(modify->fix[ifix]);
  if (rosette > 0.0 && pair->finite_radius() > 0.0)
    error->all(FLERR,
               "compute vertex/atom {}: 'rosette' needs the confluent tessellation; finite "
               "cells (pair_style vertex/voronoi ... radius r) have no Voronoi vertex clusters",
               id);
  if (domain->dimension == 3 && rosette > 0.0)
    error->all(FLERR, "compute vertex/atom: keyword 'rosette' is for 2d tissues only");
}

/* New atoms (create_atoms, fix deposit) have no neighbour memory yet. */

void ComputeVertexAtom::set_arrays(int i)
{
  fix->astore[i][0] = -1.0;
}

void ComputeVertexAtom::check_tessellation()
{
  const bool current =
      domain->dimension == 3 ? pair->tessellation3_current() : pair->tessellation_current();
  int stale = current ? 0 : 1, any;
  MPI_Allreduce(&stale, &any, 1, MPI_INT, MPI_MAX, world);
  if (any)
    error->all(FLERR,
               "compute vertex/atom {} must be invoked on a timestep when pair vertex/voronoi "
               "computed forces (e.g. by thermo, dump or fix ave/* during a run, not between "
               "runs); step {} has no current tessellation",
               id, update->ntimestep);
}

/* LAMMPS does not send velocities to ghost atoms unless 'comm_modify vel
   yes'; coordination needs those of the ghost neighbours, so send them here
   from a buffer of our own. */

void ComputeVertexAtom::communicate_velocities()
{
  const int nlocal = atom->nlocal;
  vel.resize(3 * static_cast<size_t>(atom->nmax));
  double **v = atom->v;
  for (int i = 0; i < nlocal; i++) {
    vel[3 * i] = v[i][0];
    vel[3 * i + 1] = v[i][1];
    vel[3 * i + 2] = v[i][2];
  }
  tessera_compat::forward_comm(comm, this);
}

int ComputeVertexAtom::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                         int * /*pbc*/)
{
  int m = 0;
  for (int k = 0; k < n; k++) {
    const int j = list[k];
    buf[m++] = vel[3 * j];
    buf[m++] = vel[3 * j + 1];
    buf[m++] = vel[3 * j + 2];
  }
  return m;
}

void ComputeVertexAtom::unpack_forward_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first + n; i++) {
    vel[3 * i] = buf[m++];
    vel[3 * i + 1] = buf[m++];
    vel[3 * i + 2] = buf[m++];
  }
}

/* ---------------------------------------------------------------------- */

void ComputeVertexAtom::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  check_tessellation();
  if (domain->dimension == 3) {
    compute_peratom_3d();    // compute_vertex_atom_3d.cpp
    return;
  }

  if (atom->nmax > nmax) {
    memory->destroy(values);
    nmax = atom->nmax;
    memory->create(values, nmax, NCOLS, "vertex/atom:values");
    array_atom = values;
  }

  communicate_velocities();
  const tessera::Tessellation &t = pair->tessellation();
  const std::vector<double> &energy = pair->cell_energy();
  const int nlocal = atom->nlocal;
  coordination.resize(nlocal);
  orientation.resize(nlocal);
  tessera::velocity_observables(t, vel.data(), 3, coordination.data(), orientation.data());

  const int *mask = atom->mask;
  for (int i = 0; i < nlocal; i++) {
    double *row = values[i];
    if (!(mask[i] & groupbit)) {
      for (int k = 0; k < NCOLS; k++) row[k] = 0.0;
      continue;
    }
    const double a = t.area[i], p = t.perimeter[i];
    row[0] = a;
    row[1] = p;
    row[2] = a > 0.0 ? p / std::sqrt(a) : 0.0;
    row[3] = t.coordination_number(i, REL_TOL);
    row[4] = energy[i];
    row[5] = coordination[i];
    row[6] = orientation[i];
    // Finite cells: free (cell-medium) arc length, and 1 for a cell at an edge.
    const bool finite = pair->finite_radius() > 0.0;
    row[7] = finite ? pair->finite_cells().free_length[i] : 0.0;
    row[8] = finite && pair->finite_cells().at_edge(i) ? 1.0 : 0.0;
  }
}

/* ---------------------------------------------------------------------- */

void ComputeVertexAtom::compute_vector()
{
  invoked_vector = update->ntimestep;
  check_tessellation();
  // Asked again for the same tessellation (LAMMPS may invoke a compute twice
  // on one step, e.g. at a run's setup): every value is a function of that
  // tessellation, and the neighbour exchanges are those since the previous
  // tessellation, not 0.
  if (pair->compute_count() == vector_of) return;
  vector_of = pair->compute_count();
  if (domain->dimension == 3) {
    compute_vector_3d();    // compute_vertex_atom_3d.cpp
    return;
  }

  const tessera::Tessellation &t = pair->tessellation();
  const int *mask = atom->mask;
  double local[4] = {0.0, 0.0, 0.0, 0.0}, all[4];
  const bool finite = pair->finite_radius() > 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    if (finite && pair->finite_cells().at_edge(i)) {
      local[2] += 1.0;
      local[3] += pair->finite_cells().free_length[i];
    }
    if (!(t.area[i] > 0.0)) continue;
    local[0] += t.perimeter[i] / std::sqrt(t.area[i]);
    local[1] += 1.0;
  }
  MPI_Allreduce(local, all, 4, MPI_DOUBLE, MPI_SUM, world);
  vector[0] = all[1] > 0.0 ? all[0] / all[1] : 0.0;
  vector[1] = count_multifold();
  vector[2] = count_new_neighbors();
  vector[3] = all[2];    // cells at an edge (free arcs)
  vector[4] = all[3];    // free perimeter of the tissue
}

/* Voronoi vertices where four or more cells of the group meet, each counted
   once over all ranks and periodic images. */

double ComputeVertexAtom::count_multifold()
{
  const tessera::Tessellation &t = pair->tessellation();
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;

  // The tessellation lists each multifold vertex around the owned cells with
  // its complete ring of cells (owned and ghost); with 'rosette L' the
  // clusters of vertices joined by junctions shorter than L take their place.
  // A vertex is counted by the copy in which the group member with the
  // lowest ID is an owned atom: once over all ranks and periodic images.
  const int *offset, *members;
  int nclusters;
  if (rosette > 0.0) {
    t.short_edge_clusters(rosette, cluster_offset, cluster_members);
    offset = cluster_offset.data();
    members = cluster_members.data();
    nclusters = static_cast<int>(cluster_offset.size()) - 1;
  } else {
    offset = t.group_offset.data();
    members = t.group_point.data();
    nclusters = static_cast<int>(t.group_offset.size()) - 1;
  }
  bigint count = 0;
  for (int g = 0; g < nclusters; g++) {
    int in_group = 0, lowest = -1;
    for (int k = offset[g]; k < offset[g + 1]; k++) {
      const int j = members[k];
      if (!(mask[j] & groupbit)) continue;
      in_group++;
      if (lowest < 0 || tag[j] < tag[lowest]) lowest = j;
    }
    if (in_group >= 4 && lowest < nlocal) count++;
  }
  bigint total;
  MPI_Allreduce(&count, &total, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  return static_cast<double>(total);
}

/* Tags of the group's Voronoi neighbours of owned cell c (non-zero edges)
   with IDs larger than c's, ascending and without repeats. */

void ComputeVertexAtom::neighbor_tags(int c, std::vector<tagint> &out)
{
  if (domain->dimension == 3) {
    neighbor_tags_3d(c, out);    // compute_vertex_atom_3d.cpp
    return;
  }
  const tessera::Tessellation &t = pair->tessellation();
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  out.clear();
  const double zero_len = edge_floor(t, c);
  for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; k++) {
    if (t.edge_length[k] <= zero_len) continue;
    const int j = t.cell_neighbor[k];
    if ((mask[j] & groupbit) && tag[j] > tag[c]) out.push_back(tag[j]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

/* Neighbour exchanges (T1 transitions) since the previous call: the number
   of pairs of group cells that share a non-zero edge now but did not then.
   Each pair is counted by the cell with the lower atom ID.  Every T1 makes
   one new pair (and breaks one), so this counts T1 transitions. */

double ComputeVertexAtom::count_new_neighbors()
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double **memo = fix->astore;

  std::vector<tagint> now;
  bigint count = 0;
  int most = 0;
  for (int i = 0; i < nlocal; i++) {
    double *old = memo[i];
    if (!(mask[i] & groupbit)) {
      old[0] = -1.0;
      continue;
    }
    neighbor_tags(i, now);
    const int nold = static_cast<int>(old[0]);
    if (nold >= 0) {
      const int kept = MIN(nold, MAXNEIGH);
      for (tagint j : now) {
        const double *begin = old + 1, *end = old + 1 + kept;
        const bool known = std::binary_search(begin, end, static_cast<double>(j));
        // Beyond the remembered tags we cannot tell: do not count.
        const bool unknown = nold > MAXNEIGH && static_cast<double>(j) > old[kept];
        if (!known && !unknown) count++;
      }
    }
    const int n = static_cast<int>(now.size());
    most = MAX(most, n);
    old[0] = n;
    for (int k = 0; k < MIN(n, MAXNEIGH); k++) old[1 + k] = static_cast<double>(now[k]);
  }

  int most_all;
  MPI_Allreduce(&most, &most_all, 1, MPI_INT, MPI_MAX, world);
  if (most_all > MAXNEIGH && !warned_overflow && comm->me == 0)
    error->warning(FLERR,
                   "compute vertex/atom {}: a cell has {} Voronoi neighbours with larger IDs, "
                   "more than the {} it remembers; neighbour exchanges may be under-counted",
                   id, most_all, MAXNEIGH);
  if (most_all > MAXNEIGH) warned_overflow = 1;

  bigint total;
  MPI_Allreduce(&count, &total, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  return static_cast<double>(total);
}

/* ---------------------------------------------------------------------- */

double ComputeVertexAtom::memory_usage()
{
  double bytes = (double) nmax * NCOLS * sizeof(double);
  bytes += (double) vel.capacity() * sizeof(double);
  bytes += (double) (coordination.capacity() + orientation.capacity()) * sizeof(double);
  return bytes;
}
