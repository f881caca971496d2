/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   compute vertex/local: one row per junction (Voronoi edge of non-zero
   length) of each owned cell of the group, from the tessellation that
   pair_style vertex/voronoi computed for the forces of this timestep:
   cell ID, neighbour ID, the junction's two end vertices (in the frame of
   the cell's own coordinates, counter-clockwise) and its length.
------------------------------------------------------------------------- */

#include "compute_vertex_local.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "pair_vertex_voronoi.h"
#include "update.h"

#include "tessera/tessellation.h"

#include <cstring>

using namespace LAMMPS_NS;

namespace {

constexpr int NCOLS = 7;

}    // namespace

/* ----------------------------------------------------------------------
   compute ID group vertex/local
------------------------------------------------------------------------- */

ComputeVertexLocal::ComputeVertexLocal(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0), rows(nullptr), pair(nullptr)
{
  if (narg > 3)
    error->all(FLERR,
               "Illegal compute vertex/local command: unexpected argument '{}' (it takes none: "
               "'compute ID group vertex/local')",
               arg[3]);
  if (atom->tag_enable == 0)
    error->all(FLERR, "compute vertex/local requires atom IDs (atom_modify id yes)");
  if (domain->dimension == 3)
    error->all(FLERR,
               "compute vertex/local lists 2d junctions and is not available in 3d; use "
               "compute vertex/atom for the 3d cells");

  local_flag = 1;
  size_local_rows = 0;
  size_local_cols = NCOLS;
}

ComputeVertexLocal::~ComputeVertexLocal()
{
  memory->destroy(rows);
}

void ComputeVertexLocal::init()
{
  pair = dynamic_cast<PairVertexVoronoi *>(force->pair_match("vertex/voronoi", 1));
  if (!pair)
    error->all(FLERR,
               "compute vertex/local {} reads the tessellation of pair_style vertex/voronoi, "
               "but the pair style is '{}'; define 'pair_style vertex/voronoi' (alone or as "
               "one sub-style of hybrid)",
               id, force->pair_style ? force->pair_style : "none");
}

/* ---------------------------------------------------------------------- */

void ComputeVertexLocal::compute_local()
{
  invoked_local = update->ntimestep;

  int stale = pair->tessellation_current() ? 0 : 1, any;
  MPI_Allreduce(&stale, &any, 1, MPI_INT, MPI_MAX, world);
  if (any)
    error->all(FLERR,
               "compute vertex/local {} must be invoked on a timestep when pair vertex/voronoi "
               "computed forces (e.g. by a dump during a run, or after 'run 0'); step {} has no "
               "current tessellation",
               id, update->ntimestep);

  const tessera::Tessellation &t = pair->tessellation();
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;

  int n = 0;
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit)
      for (int k = t.cell_offset[i]; k < t.cell_offset[i + 1]; k++)
        if (t.edge_length[k] > 0.0) n++;
  if (n > nmax) {
    memory->destroy(rows);
    nmax = MAX(n, 1);
    memory->create(rows, nmax, NCOLS, "vertex/local:rows");
  }

  // Edge k runs from vertex k to vertex k+1 (cyclically) of the cell.  The
  // zero-length edges of a multifold vertex are not junctions: they are left
  // out, and a junction ends where the next junction starts, so that a cell's
  // rows close exactly into its counter-clockwise polygon.
  int m = 0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const int o = t.cell_offset[i], len = t.cell_size(i);
    const int first = m;
    for (int e = 0; e < len; e++) {
      const int k = o + e;
      if (!(t.edge_length[k] > 0.0)) continue;
      const tessera::Vec2 &h = t.vertices[t.cell_vertex[k]];
      double *row = rows[m];
      row[0] = static_cast<double>(tag[i]);
      row[1] = static_cast<double>(tag[t.cell_neighbor[k]]);
      row[2] = h.x;
      row[3] = h.y;
      row[6] = t.edge_length[k];
      if (m > first) {
        rows[m - 1][4] = h.x;
        rows[m - 1][5] = h.y;
      }
      m++;
    }
    if (m > first) {
      rows[m - 1][4] = rows[first][2];
      rows[m - 1][5] = rows[first][3];
    }
  }

  size_local_rows = m;
  array_local = rows;
}

/* ---------------------------------------------------------------------- */

double ComputeVertexLocal::memory_usage()
{
  return (double) nmax * NCOLS * sizeof(double);
}
