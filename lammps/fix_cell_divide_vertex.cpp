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

   fix cell/divide on the cells of the vertex model (pair_style
   vertex/polygon): the decisions are the Voronoi cells' (fix_cell_divide.cpp);
   the event cuts each mother by a new edge through her centroid, normal to
   the division axis (the internal fix's divide(), which makes the new cell
   atom and the two new vertex atoms); the daughters' state is set as for
   Voronoi cells.  'separation' has no meaning here: the daughters' atoms sit
   at their polygons' centroids.
------------------------------------------------------------------------- */

#include "fix_cell_divide.h"

#include "atom.h"
#include "error.h"
#include "fix_vertex_polygon.h"
#include "output.h"
#include "update.h"

#include "cell_event_count.h"
#include "cell_event_log.h"
#include "cell_events.h"

#include <array>
#include <unordered_map>

using namespace LAMMPS_NS;
using namespace cell_events;

void FixCellDivide::divide_vertex_cells()
{
  tagint maxtag = 0, maxtag_all = 0;
  for (int i = 0; i < atom->nlocal; i++) maxtag = MAX(maxtag, atom->tag[i]);
  MPI_Allreduce(&maxtag, &maxtag_all, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  if ((double) maxtag_all + 3.0 * daughter_tag.size() + 3.0 >= (double) MAXTAGINT)
    error->all(FLERR, "fix cell/divide: new atom IDs would exceed the largest atom ID");
  const bigint room = cap_room();
  if ((bigint) daughter_tag.size() > room) warn_cap((bigint) daughter_tag.size() - room);

  std::vector<FixVertexPolygon::Division> mothers;
  std::unordered_map<tagint, std::array<double, 2>> where;    // mothers' centres before
  for (int i = 0; i < atom->nlocal; i++) {
    const auto found = pending.find(atom->tag[i]);
    if (found == pending.end()) continue;
    const auto rank = daughter_tag.find(atom->tag[i]);
    if (rank == daughter_tag.end() || (bigint) rank->second >= room) continue;    // the cap
    if (!takes(i)) continue;    // began to die at this step (fix cell/death)
    mothers.push_back({atom->tag[i], found->second[0], found->second[1], (bigint) rank->second});
    where[atom->tag[i]] = {atom->x[i][0], atom->x[i][1]};
  }
  pending.clear();
  daughter_tag.clear();
  vertex->division_step = -1;

  bigint done = 0;
  const std::vector<std::pair<int, int>> made = vertex->divide(mothers, maxtag_all + 1, &done);
  const uint64_t step = update->ntimestep;
  for (const auto &mj : made) {
    const int i = mj.first, j = mj.second;
    for (const int index : split_index) atom->dvector[index][j] = atom->dvector[index][i] *= 0.5;
    const tagint mother = atom->tag[i];
    const std::array<double, 2> &x0 = where[mother];
    const double xm[3] = {x0[0], x0[1], atom->x[i][2]};
    log.add("divide", mother, mother, atom->tag[j], xm);
    born(i, mother, step);
    born(j, mother, step);
  }
  events.record((int) done, update->ntimestep);
  log.flush(clock + update->dt);    // the time of this step (pre_force advances the clock)
  // Atoms a T2 removed at the step before go now (after the divisions,
  // which needed the ghosts).
  vertex->delete_due();
  if (done > 0) refresh_dumps(output);
}
