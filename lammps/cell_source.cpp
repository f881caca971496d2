/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   The pair style that makes cells, for the computes and fixes that read
   them (see cell_source.h).
------------------------------------------------------------------------- */

#include "cell_source.h"

#include "force.h"
#include "lammps.h"
#include "pair.h"

using namespace LAMMPS_NS;

CellSource *CellSource::find(LAMMPS *lmp)
{
  for (const char *style : {"vertex/voronoi", "vertex/polygon"}) {
    Pair *p = lmp->force->pair_match(style, 1);
    if (p) return dynamic_cast<CellSource *>(p);
  }
  return nullptr;
}
