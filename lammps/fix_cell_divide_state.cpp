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

   fix cell/divide: its per-atom state (age, generation, cycle time, base
   preferred area, mother, birth time) as LAMMPS moves it between ranks and
   into restart files, and the fix's global record in restart files.
------------------------------------------------------------------------- */

#include "fix_cell_divide.h"

#include "atom.h"
#include "cell_events.h"
#include "comm.h"
#include "memory.h"
#include "cell_event_count.h"
#include "cell_event_log.h"

#include <cstdio>

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace cell_events;

/* The global record: the event count and clock (cell_events::EventCount). */

void FixCellDivide::write_restart(FILE *fp)
{
  if (comm->me == 0) events.write_restart(fp, clock);
}

void FixCellDivide::restart(char *buf)
{
  log.continuing();
  events.restart(buf, clock);
}

double FixCellDivide::memory_usage()
{
  return (double) atom->nmax * NCOL * sizeof(double);
}

void FixCellDivide::grow_arrays(int nmax)
{
  memory->grow(cellstate, nmax, NCOL, "cell/divide:cellstate");
  array_atom = cellstate;
}

void FixCellDivide::copy_arrays(int i, int j, int /*delflag*/)
{
  for (int c = 0; c < NCOL; c++) cellstate[j][c] = cellstate[i][c];
}

/* A cell that appears other than by division (create_atoms, read_data after
   this fix, fix deposit), or exists when the fix is defined: age 0,
   generation 0, its own cycle time, no mother (ID 0), born now. */

void FixCellDivide::set_arrays(int i)
{
  cellstate[i][AGE] = 0.0;
  cellstate[i][GENERATION] = 0.0;
  cellstate[i][CYCLE_TIME] = draw_cycle(atom->tag[i], CREATION);
  cellstate[i][AREA0_BASE] = 0.0;
  cellstate[i][MOTHER] = 0.0;
  cellstate[i][BIRTH] = clock;
}

int FixCellDivide::pack_exchange(int i, double *buf)
{
  for (int c = 0; c < NCOL; c++) buf[c] = cellstate[i][c];
  return NCOL;
}

int FixCellDivide::unpack_exchange(int nlocal, double *buf)
{
  for (int c = 0; c < NCOL; c++) cellstate[nlocal][c] = buf[c];
  return NCOL;
}

int FixCellDivide::pack_restart(int i, double *buf)
{
  buf[0] = NCOL + 1;
  for (int c = 0; c < NCOL; c++) buf[c + 1] = cellstate[i][c];
  return NCOL + 1;
}

void FixCellDivide::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  // A restart file of an older version has fewer (leading) columns: the
  // others keep their defaults (no mother, birth time 0).
  const int ncol = MIN(static_cast<int>(extra[nlocal][m]) - 1, (int) NCOL);
  m++;
  for (int c = 0; c < ncol; c++) cellstate[nlocal][c] = extra[nlocal][m++];
  for (int c = ncol; c < NCOL; c++) cellstate[nlocal][c] = 0.0;
}

int FixCellDivide::size_restart(int /*nlocal*/)
{
  return NCOL + 1;
}

int FixCellDivide::maxsize_restart()
{
  return NCOL + 1;
}
