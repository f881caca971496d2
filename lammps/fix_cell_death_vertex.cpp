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

   fix cell/death on the cells of the vertex model (pair_style
   vertex/polygon; doc/model.md, "Division and death"): a cell that dies is
   not deleted with its ring, which would leave a hole, but begins to die: its
   preferred area d_area0 and perimeter d_perim0 become those of a cell 0.03
   times its size (A0 times 0.0009, P0 times 0.03), so that it shrinks, loses
   sides by T1s and leaves by the model's own T2 (extrusion) once it is a
   triangle below the T2 area.
   The death is counted and logged when it begins; a dying cell no longer
   counts among the living cells of 'min N', neither dies again nor divides.
------------------------------------------------------------------------- */

#include "fix_cell_death.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "output.h"
#include "pair_vertex_polygon.h"
#include "update.h"

#include "cell_event_count.h"
#include "cell_event_log.h"
#include "cell_events.h"

#include "tessera/vertex_model.h"

using namespace LAMMPS_NS;
using namespace cell_events;

// A dying cell's preferred size, relative to its own: A0 is scaled by its
// square, P0 by it (the model needs both > 0).
static constexpr double DYING_SIZE = 0.03;

void FixCellDeath::init_vertex()
{
  int flag = -1, cols = -1;
  area0_index = atom->find_custom("area0", flag, cols);
  if (area0_index >= 0 && (flag != 1 || cols != 0)) area0_index = -1;
  perim0_index = atom->find_custom("perim0", flag, cols);
  if (perim0_index >= 0 && (flag != 1 || cols != 0)) perim0_index = -1;
  if (area0_index < 0 || perim0_index < 0)
    error->all(FLERR,
               "fix cell/death {}: a vertex-model cell (pair_style vertex/polygon) dies by "
               "shrinking until a T2 takes it, through its own preferred area and perimeter: "
               "define them with 'fix ID all property/atom d_area0 d_perim0' and set them "
               "(missing: {}{})",
               id, area0_index < 0 ? "d_area0 " : "", perim0_index < 0 ? "d_perim0" : "");
  auto *p = dynamic_cast<PairVertexPolygon *>(force->pair_match("vertex/polygon", 1));
  if (p && !(p->topology().t1_length > 0.0 && p->topology().t2_area > 0.0))
    error->all(FLERR,
               "fix cell/death {}: a dying vertex-model cell leaves by T1s and a T2, which "
               "pair_style vertex/polygon does not carry out: give it 't1 l_T1 l_new t2 A_T2' "
               "(now t1 {} t2 {})",
               id, p->topology().t1_length, p->topology().t2_area);
}

bigint FixCellDeath::count_dying() const
{
  bigint mine = 0, all = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if (dying(i)) mine++;
  MPI_Allreduce(&mine, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  return all;
}

void FixCellDeath::start_dying()
{
  const bigint room = floor_room();
  const double now = clock + update->dt;    // the time of this step
  double *a0 = atom->dvector[area0_index], *p0 = atom->dvector[perim0_index];
  int n = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    const auto found = pending.find(atom->tag[i]);
    if (found == pending.end() || found->second >= room || dying(i)) continue;
    log.add("death", atom->tag[i], 0, 0, atom->x[i]);
    dying_since[i] = now;
    a0[i] *= DYING_SIZE * DYING_SIZE;
    p0[i] *= DYING_SIZE;
    n++;
  }
  pending.clear();
  int nall = 0;
  MPI_Allreduce(&n, &nall, 1, MPI_INT, MPI_SUM, world);
  events.record(nall, update->ntimestep);
  log.flush(now);
}
