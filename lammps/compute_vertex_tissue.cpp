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

   compute vertex/tissue: global values of the Voronoi tessellation that
   pair_style vertex/voronoi computed, for thermo, variables and fix
   ave/time: mean shape index, multifold vertices, neighbour exchanges since
   the previous call, cells at an edge, free perimeter, and the heterotypic
   junctions (their fraction, length and the total).  The per-cell values
   are compute vertex/atom's.
------------------------------------------------------------------------- */

#include "compute_vertex_tissue.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "modify.h"
#include "cell_source.h"
#include "tessera_compat.h"
#include "update.h"
#include "vertex_pieces.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;
using vertex_pieces::piece_floor;

namespace {

constexpr int NVALUES = 8;

// The rows of the internal per-atom store (a FixStore in LAMMPS 2021, a
// FixStoreAtom since; the header holds it as a Fix).
static double **rows(Fix *fix)
{
  return static_cast<tessera_compat::FixStorePerAtom *>(fix)->astore;
}

// The neighbour memory of an atom (a row of the internal fix STORE):
// COUNT is how many neighbour tags follow (-1: none yet), OWNER the atom ID
// the row was written for, then up to MAXNEIGH neighbour tags, ascending.
// A row whose OWNER is not the atom's ID was copied from another atom (a
// daughter of fix cell/divide is a copy of its mother): that cell is new.
constexpr int COUNT = 0, OWNER = 1, FIRST = 2;

}    // namespace

/* ----------------------------------------------------------------------
   compute ID group vertex/tissue [rosette L]
------------------------------------------------------------------------- */

ComputeVertexTissue::ComputeVertexTissue(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), id_fix(nullptr), fix(nullptr), pair(nullptr), warned_overflow(0),
    rosette(0.0)
{
  int iarg = 3;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "rosette") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "compute vertex/tissue: keyword 'rosette' needs a length L");
      rosette = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(rosette > 0.0))
        error->all(FLERR, "compute vertex/tissue: rosette length must be > 0, got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else {
      error->all(FLERR,
                 "Illegal compute vertex/tissue command: unknown keyword '{}' (known: rosette L; "
                 "'compute ID group vertex/tissue [rosette L]')",
                 arg[iarg]);
    }
  }
  if (atom->tag_enable == 0)
    error->all(FLERR, "compute vertex/tissue requires atom IDs (atom_modify id yes)");

  vector_flag = 1;
  size_vector = NVALUES;
  extvector = 0;
  comm_forward = 1;
  create_attribute = 1;
  // The neighbour memory is for the members of a fixed group.
  dynamic_group_allow = 0;

  vector = new double[size_vector];
  for (int k = 0; k < size_vector; k++) vector[k] = 0.0;

  // Voronoi neighbours of each atom at the previous compute_vector(), which
  // must migrate with the atoms (rows: see COUNT, OWNER, FIRST).  Not
  // written to restart files: a restarted run starts counting afresh.
  id_fix = utils::strdup(std::string(id) + "_COMPUTE_STORE");
  fix = static_cast<tessera_compat::FixStorePerAtom *>(
      modify->add_fix(fmt::format("{} {} {}", id_fix, group->names[igroup],
                                  tessera_compat::store_peratom(FIRST + MAXNEIGH, false))));
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

ComputeVertexTissue::~ComputeVertexTissue()
{
  // Modify deletes all fixes before the computes at the end of a run.
  if (modify->nfix && modify->find_fix(id_fix) >= 0) modify->delete_fix(id_fix);
  delete[] id_fix;
  delete[] vector;
}

void ComputeVertexTissue::init()
{
  pair = CellSource::find(lmp);
  if (!pair)
    error->all(FLERR,
               "compute vertex/tissue {} reads the cells of pair_style vertex/voronoi or "
               "vertex/polygon, but the pair style is '{}'; define one of them (vertex/voronoi "
               "alone or as one sub-style of hybrid)",
               id, force->pair_style ? force->pair_style : "none");
  const int ifix = modify->find_fix(id_fix);
  if (ifix < 0)
    error->all(FLERR,
               "compute vertex/tissue: its internal fix {} was deleted; re-create the compute "
               "(uncompute, then compute)",
               id_fix);
  fix = static_cast<tessera_compat::FixStorePerAtom *>(modify->fix[ifix]);
  if (rosette > 0.0 && pair->finite_radius() > 0.0)
    error->all(FLERR,
               "compute vertex/tissue {}: 'rosette' needs the confluent tessellation; finite "
               "cells (pair_style vertex/voronoi ... radius r) have no Voronoi vertex clusters",
               id);
  if (rosette > 0.0 && pair->cells_are_vertices())
    error->all(FLERR,
               "compute vertex/tissue {}: 'rosette' clusters Voronoi vertices joined by short "
               "junctions; the vertex model's vertices are three-fold and its short edges go "
               "by T1s (pair_style vertex/polygon t1)",
               id);
  if (domain->dimension == 3 && rosette > 0.0 && !pair->on_sphere())
    error->all(FLERR, "compute vertex/tissue: keyword 'rosette' is for 2d tissues only");
}

/* New atoms (create_atoms, fix deposit) have no neighbour memory yet. */

void ComputeVertexTissue::set_arrays(int i)
{
  rows(fix)[i][COUNT] = -1.0;
  rows(fix)[i][OWNER] = 0.0;
}

void ComputeVertexTissue::check_cells()
{
  // (read before any run, e.g. through the library interface: no pair style yet)
  if (!pair)
    error->all(FLERR,
               "compute vertex/tissue {}: no cells yet: it reads the cells of pair_style "
               "vertex/voronoi or vertex/polygon, which exist after a run (e.g. 'run 0')",
               id);
  pair->require_current_cells(fmt::format("compute vertex/tissue {}", id));
}

/* flag[0..nlocal) to the ghost atoms (one value each). */

void ComputeVertexTissue::communicate_flags()
{
  flag.resize(atom->nmax);
  tessera_compat::forward_comm(comm, this);
}

int ComputeVertexTissue::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                           int * /*pbc*/)
{
  for (int k = 0; k < n; k++) buf[k] = flag[list[k]];
  return n;
}

void ComputeVertexTissue::unpack_forward_comm(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++) flag[first + k] = buf[k];
}

/* ---------------------------------------------------------------------- */

void ComputeVertexTissue::compute_vector()
{
  invoked_vector = update->ntimestep;
  check_cells();
  // Asked again for the same cells (LAMMPS may invoke a compute twice on one
  // step, e.g. at a run's setup): every value is a function of those cells,
  // and the neighbour exchanges are those since the previous cells, not 0.
  if (pair->compute_count() == vector_of) return;
  vector_of = pair->compute_count();

  const tessera::CellView &v = pair->cells();
  const int *mask = atom->mask;
  double local[4] = {0.0, 0.0, 0.0, 0.0}, all[4];
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    if (v.at_edge(i)) {
      local[2] += 1.0;
      local[3] += v.free_length(i);
    }
    if (!(v.measure(i) > 0.0)) continue;
    local[0] += v.shape_index(i);
    local[1] += 1.0;
  }
  MPI_Allreduce(local, all, 4, MPI_DOUBLE, MPI_SUM, world);
  vector[0] = all[1] > 0.0 ? all[0] / all[1] : 0.0;
  vector[1] = count_multifold();
  vector[2] = count_new_neighbors();
  vector[3] = all[2];    // cells at an edge (free arcs)
  vector[4] = all[3];    // free perimeter of the tissue
  double het = 0.0, total = 0.0;
  junction_lengths(het, total);
  vector[5] = total > 0.0 ? het / total : 0.0;
  vector[6] = het;
  vector[7] = total;
}

/* Junctions between two group cells (2d: edges, 3d: faces, of non-zero
   size): the total length (area) and that between cells of different
   types.  Every junction is seen from both of its cells (owned by this rank
   or another, or a periodic image of the same cell), so each sighting adds
   half of it: each junction counts once over all ranks, without an ID rule
   that a cell touching its own periodic image would break. */

void ComputeVertexTissue::junction_lengths(double &het, double &total)
{
  const tessera::CellView &v = pair->cells();
  const int *mask = atom->mask;
  const int *type = atom->type;
  double local[2] = {0.0, 0.0}, all[2];
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double floor = piece_floor(v, i);
    for (int k = v.piece_begin(i); k < v.piece_end(i); k++) {
      const int j = v.piece_neighbor(k);
      const double size = v.piece_size(k);
      if (j < 0 || !(size > floor) || !(mask[j] & groupbit)) continue;
      local[1] += 0.5 * size;
      if (type[j] != type[i]) local[0] += 0.5 * size;
    }
  }
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_SUM, world);
  het = all[0];
  total = all[1];
}

/* 2d: Voronoi vertices where four or more cells of the group meet, each
   counted once over all ranks and periodic images.  3d: pairs of group
   cells whose shared face has zero area (they meet at a vertex of more than
   four cells, co-spherical centres), each pair counted once by the owner of
   the lower ID. */

double ComputeVertexTissue::count_multifold()
{
  const tessera::CellView &v = pair->cells();
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  bigint count = 0;
  if (v.dimension() == 3) {
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit) || !(v.measure(i) > 0.0)) continue;
      const double floor = piece_floor(v, i);
      for (int k = v.piece_begin(i); k < v.piece_end(i); k++) {
        const int j = v.piece_neighbor(k);
        if (j >= 0 && !(v.piece_size(k) > floor) && (mask[j] & groupbit) && tag[j] > tag[i])
          count++;
      }
    }
  } else {
    // The view lists each multifold vertex around the owned cells with its
    // complete ring of cells (owned and ghost); with 'rosette L' the
    // clusters of vertices joined by junctions shorter than L take their
    // place.  A vertex is counted by the copy in which the group member with
    // the lowest ID is an owned atom: once over all ranks and images.
    if (rosette > 0.0) {
      if (!v.short_edge_clusters(rosette, cluster_offset, cluster_members)) {
        cluster_offset.assign(1, 0);
        cluster_members.clear();
      }
    } else {
      cluster_offset.assign(1, 0);
      cluster_members.clear();
      std::vector<int> ring;
      for (int g = 0; g < v.multifold_count(); g++) {
        v.multifold_ring(g, ring);
        cluster_members.insert(cluster_members.end(), ring.begin(), ring.end());
        cluster_offset.push_back(static_cast<int>(cluster_members.size()));
      }
    }
    const int nclusters = static_cast<int>(cluster_offset.size()) - 1;
    for (int g = 0; g < nclusters; g++) {
      int in_group = 0, lowest = -1;
      for (int k = cluster_offset[g]; k < cluster_offset[g + 1]; k++) {
        const int j = cluster_members[k];
        if (!(mask[j] & groupbit)) continue;
        in_group++;
        if (lowest < 0 || tag[j] < tag[lowest]) lowest = j;
      }
      if (in_group >= 4 && lowest < nlocal) count++;
    }
  }
  bigint total;
  MPI_Allreduce(&count, &total, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  return static_cast<double>(total);
}

/* Tags of the group's neighbours of owned cell c (across edges of non-zero
   length or faces of non-zero area), ascending and without repeats. */

void ComputeVertexTissue::neighbor_tags(int c, std::vector<tagint> &out)
{
  const tessera::CellView &v = pair->cells();
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  out.clear();
  const double floor = piece_floor(v, c);
  for (int k = v.piece_begin(c); k < v.piece_end(c); k++) {
    const int j = v.piece_neighbor(k);
    if (j < 0 || !(v.piece_size(k) > floor)) continue;
    if (mask[j] & groupbit) out.push_back(tag[j]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

/* Neighbour exchanges (T1 transitions) since the previous call: the number
   of pairs of group cells that share a non-zero edge (face) now but did not
   then.  Each pair is counted by the cell with the lower atom ID.  Every T1
   makes one new pair (and breaks one), so this counts T1 transitions.
   Births and deaths also make new pairs, which are not exchanges: a pair
   counts only if both cells existed at the previous call and neither cell's
   neighbourhood changed by an event since (a neighbour that is new, or a
   remembered neighbour that no longer exists).  A cell existed at the
   previous call if its memory row was written for its own atom ID: a
   daughter of fix cell/divide carries a copy of its mother's row, and an
   atom ID freed by a death and given to a newborn names another cell.
   Exchanges next to a division or death in the same interval are therefore
   not counted. */

double ComputeVertexTissue::count_new_neighbors()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  double **memo = rows(fix);

  // Which cells existed at the previous call (they have a memory of their
  // own), on the ghosts too.
  flag.assign(atom->nmax, 0.0);
  for (int i = 0; i < nlocal; i++)
    flag[i] = (mask[i] & groupbit) && memo[i][COUNT] >= 0.0 &&
            memo[i][OWNER] == static_cast<double>(tag[i])
        ? 1.0
        : 0.0;
  communicate_flags();
  std::vector<char> known(nall);
  present.clear();
  for (int i = 0; i < nall; i++) {
    known[i] = flag[i] != 0.0;
    if (known[i]) present.push_back(tag[i]);
  }
  std::sort(present.begin(), present.end());

  // Cells touched by an event: a neighbour that did not exist (just born or
  // just joined the group), or a remembered neighbour that no longer exists
  // (its ID is gone, or now names a new cell).
  std::vector<tagint> now;
  flag.assign(atom->nmax, 0.0);
  const tessera::CellView &v = pair->cells();
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    bool touched = !known[i];
    const double floor = piece_floor(v, i);
    for (int k = v.piece_begin(i); !touched && k < v.piece_end(i); k++) {
      const int j = v.piece_neighbor(k);
      if (j >= 0 && v.piece_size(k) > floor && (mask[j] & groupbit) && !known[j]) touched = true;
    }
    const double *old = memo[i];
    const int kept = known[i] ? MIN(static_cast<int>(old[COUNT]), MAXNEIGH) : 0;
    for (int k = 0; !touched && k < kept; k++)
      if (!std::binary_search(present.begin(), present.end(), static_cast<tagint>(old[FIRST + k])))
        touched = true;
    flag[i] = touched ? 1.0 : 0.0;
  }
  communicate_flags();

  bigint count = 0;
  int most = 0;
  for (int i = 0; i < nlocal; i++) {
    double *old = memo[i];
    if (!(mask[i] & groupbit)) {
      set_arrays(i);
      continue;
    }
    neighbor_tags(i, now);
    if (known[i] && flag[i] == 0.0) {
      const int nold = static_cast<int>(old[COUNT]);
      const int kept = MIN(nold, MAXNEIGH);
      for (tagint j : now) {
        if (j <= tag[i]) continue;    // each pair once, by the lower ID
        const double *begin = old + FIRST, *end = old + FIRST + kept;
        const bool seen = std::binary_search(begin, end, static_cast<double>(j));
        // Beyond the remembered tags we cannot tell: do not count.
        const bool unknown = nold > MAXNEIGH && static_cast<double>(j) > old[FIRST + kept - 1];
        if (seen || unknown) continue;
        // The neighbour's own state: it existed and no event touched it.
        bool eligible = false;
        for (int k = v.piece_begin(i); k < v.piece_end(i); k++) {
          const int q = v.piece_neighbor(k);
          if (q >= 0 && tag[q] == j) {
            eligible = known[q] && flag[q] == 0.0;
            break;
          }
        }
        if (eligible) count++;
      }
    }
    const int n = static_cast<int>(now.size());
    most = MAX(most, n);
    old[COUNT] = n;
    old[OWNER] = static_cast<double>(tag[i]);
    for (int k = 0; k < MIN(n, MAXNEIGH); k++) old[FIRST + k] = static_cast<double>(now[k]);
  }

  int most_all;
  MPI_Allreduce(&most, &most_all, 1, MPI_INT, MPI_MAX, world);
  if (most_all > MAXNEIGH && !warned_overflow && comm->me == 0)
    error->warning(FLERR,
                   "compute vertex/tissue {}: a cell has {} Voronoi neighbours, more than the "
                   "{} it remembers; neighbour exchanges may be under-counted",
                   id, most_all, MAXNEIGH);
  if (most_all > MAXNEIGH) warned_overflow = 1;

  bigint total;
  MPI_Allreduce(&count, &total, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  return static_cast<double>(total);
}

/* ---------------------------------------------------------------------- */

double ComputeVertexTissue::memory_usage()
{
  return (double) (flag.capacity() * sizeof(double) + present.capacity() * sizeof(tagint));
}
