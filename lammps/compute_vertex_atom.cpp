/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   compute vertex/atom: per-cell observables of the Voronoi tessellation that
   pair_style vertex/voronoi computed (area, perimeter, shape index, number of
   neighbours, cell energy, velocity coordination and orientation), and
   global ones for thermo (mean shape index, multifold vertices, neighbour
   exchanges since the previous call, cells at an edge, free perimeter, and
   the heterotypic junctions: their fraction, length and the total).
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

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

namespace {

constexpr int NCOLS = 9;

// A shared piece counts as a neighbour relation if it exceeds this fraction
// of the cell's mean edge length (2d) or of its surface (3d), so that the
// zero-length edges and zero-area faces of multifold vertices do not
// (tessera::CellView::coordination_number).
constexpr double REL_TOL = 1e-9;

// The size below which cell c's pieces are no neighbour relation.
double piece_floor(const tessera::CellView &v, int c)
{
  if (v.dimension() == 3) return REL_TOL * v.boundary(c);
  double mean = 0.0;
  int m = 0;
  for (int k = v.piece_begin(c); k < v.piece_end(c); k++)
    if (v.piece_neighbor(k) >= 0) {
      mean += v.piece_size(k);
      m++;
    }
  return m ? REL_TOL * mean / m : 0.0;
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
  size_vector = 8;
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
  // neighbours, ascending.  Not written to restart files: a
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
  if (domain->dimension == 3 && rosette > 0.0 && !pair->on_sphere())
    error->all(FLERR, "compute vertex/atom: keyword 'rosette' is for 2d tissues only");
}

/* New atoms (create_atoms, fix deposit) have no neighbour memory yet. */

void ComputeVertexAtom::set_arrays(int i)
{
  fix->astore[i][0] = -1.0;
}

void ComputeVertexAtom::check_cells()
{
  int stale = pair->cells_current() ? 0 : 1, any;
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
  comm_what = 0;
  tessera_compat::forward_comm(comm, this);
}

/* flag[0..nlocal) to the ghost atoms (one value each). */

void ComputeVertexAtom::communicate_flags()
{
  flag.resize(atom->nmax);
  comm_what = 1;
  tessera_compat::forward_comm(comm, this);
  comm_what = 0;
}

int ComputeVertexAtom::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                         int * /*pbc*/)
{
  int m = 0;
  for (int k = 0; k < n; k++) {
    const int j = list[k];
    if (comm_what == 1) {
      buf[m++] = flag[j];
      continue;
    }
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
    if (comm_what == 1) {
      flag[i] = buf[m++];
      continue;
    }
    vel[3 * i] = buf[m++];
    vel[3 * i + 1] = buf[m++];
    vel[3 * i + 2] = buf[m++];
  }
}

/* ---------------------------------------------------------------------- */

void ComputeVertexAtom::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  check_cells();
  if (atom->nmax > nmax) {
    memory->destroy(values);
    nmax = atom->nmax;
    memory->create(values, nmax, NCOLS, "vertex/atom:values");
    array_atom = values;
  }

  communicate_velocities();
  const tessera::CellView &v = pair->cells();
  const int dim = v.space_dimension();    // 3 for cells on a sphere
  const int nlocal = atom->nlocal;
  // Velocity coordination and orientation (tessera::velocity_observables in
  // 2d; the same definitions with 3d unit vectors in 3d).
  auto unit = [&](int i, double u[3]) {
    const double *w = &vel[3 * static_cast<size_t>(i)];
    double s2 = 0.0;
    for (int d = 0; d < dim; d++) s2 += w[d] * w[d];
    const double s = std::sqrt(s2);
    if (!(s > 0.0)) return false;
    for (int d = 0; d < 3; d++) u[d] = d < dim ? w[d] / s : 0.0;
    return true;
  };
  const int *mask = atom->mask;
  for (int i = 0; i < nlocal; i++) {
    double *row = values[i];
    for (int k = 0; k < NCOLS; k++) row[k] = 0.0;
    if (!(mask[i] & groupbit)) continue;
    if (!pair->is_cell_type(atom->type[i])) continue;    // no cell: a zero row
    row[0] = v.measure(i);
    row[1] = v.boundary(i);
    row[2] = v.shape_index(i);
    row[3] = v.coordination_number(i, REL_TOL);
    row[4] = v.energy ? v.energy[i] : 0.0;
    // Finite cells: free (cell-medium) arc length, and 1 for a cell at an edge.
    row[7] = v.free_length(i);
    row[8] = v.at_edge(i) ? 1.0 : 0.0;
    double ui[3], uj[3];
    if (!unit(i, ui)) {
      row[6] = -1.0;
      continue;
    }
    row[6] = std::acos(std::max(-1.0, std::min(1.0, ui[0])));
    const double floor = piece_floor(v, i);
    double sum = 0.0;
    int count = 0;
    for (int k = v.piece_begin(i); k < v.piece_end(i); k++) {
      const int j = v.piece_neighbor(k);
      if (j < 0 || !(v.piece_size(k) > floor) || !unit(j, uj)) continue;
      sum += ui[0] * uj[0] + ui[1] * uj[1] + ui[2] * uj[2];
      count++;
    }
    row[5] = count ? sum / count : 0.0;
  }
}

/* ---------------------------------------------------------------------- */

void ComputeVertexAtom::compute_vector()
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

void ComputeVertexAtom::junction_lengths(double &het, double &total)
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

double ComputeVertexAtom::count_multifold()
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

void ComputeVertexAtom::neighbor_tags(int c, std::vector<tagint> &out)
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
   remembered neighbour that no longer exists).  Exchanges next to a
   division or death in the same interval are therefore not counted. */

double ComputeVertexAtom::count_new_neighbors()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  double **memo = fix->astore;

  // Which cells existed at the previous call (they have a memory), on the
  // ghosts too.
  flag.assign(atom->nmax, 0.0);
  for (int i = 0; i < nlocal; i++) flag[i] = (mask[i] & groupbit) && memo[i][0] >= 0.0 ? 1.0 : 0.0;
  communicate_flags();
  std::vector<char> known(flag.begin(), flag.begin() + nall);
  present.assign(tag, tag + nall);
  std::sort(present.begin(), present.end());

  // Cells touched by an event: a neighbour without a memory (just born or
  // just joined the group), or a remembered neighbour that is gone.
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
    const int kept = old[0] >= 0.0 ? MIN(static_cast<int>(old[0]), MAXNEIGH) : 0;
    for (int k = 0; !touched && k < kept; k++)
      if (!std::binary_search(present.begin(), present.end(), static_cast<tagint>(old[1 + k])))
        touched = true;
    flag[i] = touched ? 1.0 : 0.0;
  }
  communicate_flags();

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
    if (nold >= 0 && flag[i] == 0.0) {
      const int kept = MIN(nold, MAXNEIGH);
      for (tagint j : now) {
        if (j <= tag[i]) continue;    // each pair once, by the lower ID
        const double *begin = old + 1, *end = old + 1 + kept;
        const bool seen = std::binary_search(begin, end, static_cast<double>(j));
        // Beyond the remembered tags we cannot tell: do not count.
        const bool unknown = nold > MAXNEIGH && static_cast<double>(j) > old[kept];
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
    old[0] = n;
    for (int k = 0; k < MIN(n, MAXNEIGH); k++) old[1 + k] = static_cast<double>(now[k]);
  }

  int most_all;
  MPI_Allreduce(&most, &most_all, 1, MPI_INT, MPI_MAX, world);
  if (most_all > MAXNEIGH && !warned_overflow && comm->me == 0)
    error->warning(FLERR,
                   "compute vertex/atom {}: a cell has {} Voronoi neighbours, more than the "
                   "{} it remembers; neighbour exchanges may be under-counted",
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
