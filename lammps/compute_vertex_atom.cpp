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

   compute vertex/atom: per-cell observables of the Voronoi tessellation that
   pair_style vertex/voronoi computed (area, perimeter, shape index, number of
   neighbours, cell energy, velocity coordination and orientation, free arc
   length and edge flag), as a per-atom array only.  The global values are
   compute vertex/tissue's: a compute with both a global vector and a
   per-atom array would make c_ID[I] in an atom-style variable read the
   global element I on LAMMPS versions that resolve c_ID[I] by the compute's
   flags (the global vector first) rather than by the variable's style.
------------------------------------------------------------------------- */

#include "compute_vertex_atom.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "cell_source.h"
#include "tessera_compat.h"
#include "update.h"
#include "vertex_pieces.h"

#include "tessera/polarity.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using vertex_pieces::piece_floor;
using vertex_pieces::REL_TOL;

namespace {

constexpr int NCOLS = 9;

}    // namespace

/* ----------------------------------------------------------------------
   compute ID group vertex/atom
------------------------------------------------------------------------- */

ComputeVertexAtom::ComputeVertexAtom(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0), values(nullptr), pair(nullptr)
{
  if (narg > 3 && strcmp(arg[3], "rosette") == 0)
    error->all(FLERR,
               "compute vertex/atom {}: keyword 'rosette' belongs to the global values, which "
               "are compute vertex/tissue's: use 'compute ID {} vertex/tissue rosette L' and "
               "read its element 2 (c_ID[2])",
               id, arg[1]);
  if (narg > 3)
    error->all(FLERR,
               "Illegal compute vertex/atom command: unknown keyword '{}' (it takes none: "
               "'compute ID group vertex/atom'; the global values are compute vertex/tissue's)",
               arg[3]);
  if (atom->tag_enable == 0)
    error->all(FLERR, "compute vertex/atom requires atom IDs (atom_modify id yes)");

  peratom_flag = 1;
  size_peratom_cols = NCOLS;
  comm_forward = 3;
  dynamic_group_allow = 0;
}

ComputeVertexAtom::~ComputeVertexAtom()
{
  memory->destroy(values);
}

void ComputeVertexAtom::init()
{
  pair = CellSource::find(lmp);
  if (!pair)
    error->all(FLERR,
               "compute vertex/atom {} reads the cells of pair_style vertex/voronoi or "
               "vertex/polygon, but the pair style is '{}'; define one of them (vertex/voronoi "
               "alone or as one sub-style of hybrid)",
               id, force->pair_style ? force->pair_style : "none");
}

void ComputeVertexAtom::check_cells()
{
  // (read before any run, e.g. through the library interface: no pair style yet)
  if (!pair)
    error->all(FLERR,
               "compute vertex/atom {}: no cells yet: it reads the cells of pair_style "
               "vertex/voronoi or vertex/polygon, which exist after a run (e.g. 'run 0')",
               id);
  pair->require_current_cells(fmt::format("compute vertex/atom {}", id));
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

double ComputeVertexAtom::memory_usage()
{
  double bytes = (double) nmax * NCOLS * sizeof(double);
  bytes += (double) vel.capacity() * sizeof(double);
  bytes += (double) (coordination.capacity() + orientation.capacity()) * sizeof(double);
  return bytes;
}
