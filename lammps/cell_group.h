/* -*- c++ -*- ----------------------------------------------------------
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

   Which atoms the cell-only fixes (cell/signal, cell/adapt, cell/divide,
   cell/death) act on: the cells of their group, that is the atoms whose
   type has cell parameters of pair_style vertex/voronoi or vertex/polygon
   (every atom when there is no such pair style; vertex atoms are no
   cells).  Other atoms of the group (particles under pair_style
   hybrid/overlay) are left alone, so that 'all' means every cell; the fix
   says once in the log how many it leaves out.
------------------------------------------------------------------------- */

#ifndef LMP_TESSERA_CELL_GROUP_H
#define LMP_TESSERA_CELL_GROUP_H

#include "atom.h"
#include "comm.h"
#include "group.h"
#include "lammps.h"
#include "cell_source.h"
#include "pair_vertex_voronoi.h"
#include "utils.h"

#include <mpi.h>

#include <string>
#include <vector>

namespace LAMMPS_NS {
namespace cell_group {

  // Pair: CellSource (either pair style) or PairVertexVoronoi itself.

  template <class Pair> inline bool is_cell(const Pair *pair, int type)
  {
    return !pair || pair->is_cell_type(type);
  }

  // Some atom type has no cell parameters (whether or not it has atoms).
  template <class Pair> inline bool any_particle_type(const Pair *pair, int ntypes)
  {
    if (!pair) return false;
    for (int t = 1; t <= ntypes; t++)
      if (!pair->is_cell_type(t)) return true;
    return false;
  }

  // The number of cells in the whole system (every group).  Collective.
  template <class Pair> inline bigint count_cells(LAMMPS *lmp, const Pair *pair)
  {
    Atom *atom = lmp->atom;
    if (!pair) return atom->natoms;
    bigint mine = 0, all = 0;
    for (int i = 0; i < atom->nlocal; i++)
      if (pair->is_cell_type(atom->type[i])) mine++;
    MPI_Allreduce(&mine, &all, 1, MPI_LMP_BIGINT, MPI_SUM, lmp->world);
    return all;
  }

  // Says once (noted) in the screen and log how many atoms of group igroup
  // are no cells, and of which types: 'who' (e.g. "fix s cell/signal") leaves
  // them alone, 'what' says how.  Collective.
  template <class Pair>
  inline void note_particles(LAMMPS *lmp, const Pair *pair, int igroup, const std::string &who,
                             const std::string &what, bool &noted)
  {
    if (noted || !pair) return;
    Atom *atom = lmp->atom;
    const int groupbit = lmp->group->bitmask[igroup];
    const int ntypes = atom->ntypes;
    std::vector<int> seen(ntypes + 1, 0), seen_all(ntypes + 1, 0);
    bigint mine = 0, all = 0;
    for (int i = 0; i < atom->nlocal; i++)
      if ((atom->mask[i] & groupbit) && !pair->is_cell_type(atom->type[i])) {
        mine++;
        seen[atom->type[i]] = 1;
      }
    MPI_Allreduce(&mine, &all, 1, MPI_LMP_BIGINT, MPI_SUM, lmp->world);
    if (all == 0) return;
    MPI_Allreduce(seen.data(), seen_all.data(), ntypes + 1, MPI_INT, MPI_MAX, lmp->world);
    noted = true;
    std::string types;
    for (int t = 1; t <= ntypes; t++)
      if (seen_all[t]) types += (types.empty() ? "" : " ") + std::to_string(t);
    if (lmp->comm->me == 0)
      utils::logmesg(
          lmp,
          "{}: group '{}' holds {} atom(s) that are no cells (type {}: no cell parameters "
          "of the pair style); {}\n",
          who, lmp->group->names[igroup], all, types, what);
  }

}    // namespace cell_group
}    // namespace LAMMPS_NS

#endif
