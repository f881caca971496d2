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

   pair_style vertex/voronoi with 'radius r': finite Voronoi cells.  Each
   owned cell is cut by every atom (owned or ghost) within 2r; the ghost
   shell (cutoff >= 2r) holds them all, so no triangulation and no coverage
   check are needed.  Open (f, s) and periodic boundaries both work.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi_finite.h"

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "error.h"
#include "update.h"

#include <vector>

using namespace LAMMPS_NS;

void VertexFinite::init()
{
  if (pair->cut_global < 2.0 * pair->radius)
    error->all(FLERR,
               "pair_style vertex/voronoi: cutoff {} is smaller than twice the radius {} of "
               "the finite cells (cells up to 2r apart touch); use 'pair_style vertex/voronoi "
               "{} radius {}'",
               pair->cut_global, pair->radius, 2.0 * pair->radius, pair->radius);
}

void VertexFinite::compute(int /*eflag*/, int /*vflag*/)
{
  const double t0 = MPI_Wtime();
  // The owned and ghost cells (atoms that are no cells leave holes).
  pair->gather_cells();
  const int nlocal = pair->ncell_local;
  const int nall = pair->ncell_all;
  tessera::Points pts{pair->cell_x(), nall, 3};
  try {
    ftess = tessera::finite_tessellate(pts, nlocal, pair->radius);
  } catch (tessera::Error &) {
    std::vector<long> ids(nall);
    for (int i = 0; i < nall; i++) ids[i] = pair->cell_tag(i);
    try {
      ftess = tessera::finite_tessellate(pts, nlocal, pair->radius, ids.data());
    } catch (tessera::Error &e) {
      error->one(FLERR, "pair_style vertex/voronoi at step {}: {}", update->ntimestep, e.what());
    }
  }
  tessera::finite_contacts(ftess, contacts);
  cells_.bind(ftess, contacts, pts);
  pair->note_closest_pair();
  const double t1 = MPI_Wtime();

  pair->prepare_atoms();
  // Per-cell virials: per-atom, and the global one under 'pair_modify nofdotr'.
  const bool cell_virial = pair->vflag_atom || pair->vflag_global;
  if (cell_virial) pair->cell_w.resize(4 * static_cast<size_t>(nlocal));
  tessera::ForceOutput out;
  try {
    out = tessera::finite_forces(ftess, pts, pair->type0.data(), pair->model, pair->free_t0.data(),
                                 pair->cell_f(), 3, pair->cell_e.data(),
                                 cell_virial ? pair->cell_w.data() : nullptr);
  } catch (tessera::Error &e) {
    error->one(FLERR, "pair_style vertex/voronoi at step {}: {}", update->ntimestep, e.what());
  }
  pair->stats[0] += t1 - t0;
  pair->stats[1] += MPI_Wtime() - t1;
  pair->stats[4] += 1.0;
  pair->accumulate(out.energy, 4);
}

double VertexFinite::memory_usage() const
{
  return (double) ftess.pieces.capacity() * sizeof(tessera::FinitePiece) +
      (double) contacts.cell_neighbor.capacity() * (sizeof(int) + sizeof(double));
}
