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

   pair_style vertex/voronoi: what the lost-atom check reports: this
   step's closest pair of neighbours, and the error when atoms were lost
   since the last step (the step guard, fix_vertex_guard.cpp, finds each
   cell's closest neighbour itself).
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"
#include "fix_vertex_guard.h"
#include "pair_vertex_voronoi_model.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "modify.h"
#include "output.h"
#include "thermo.h"
#include "update.h"

#include <cmath>
#include <limits>
#include <string>

using namespace LAMMPS_NS;

/* The closest pair of neighbours among this rank's cells at this force
   computation, for the error message of lost atoms (IDs and distance are
   kept: they are read at the next step, after the atoms moved); the
   confluent unit gets it from compute_forces, the others from here.  Read
   from the unit's own cells, in the list of cell atoms (gather_cells). */

void PairVertexVoronoi::note_closest_pair()
{
  double best = -1.0;
  int bi = -1, bq = -1;
  const tessera::Contacts c = unit->cells().contacts();
  const int dim = domain->dimension;
  const double *x = cell_x();
  for (int i = 0; i < c.n_owned; i++)
    for (int k = c.offset[i]; k < c.offset[i + 1]; k++) {
      const int q = c.neighbor[k];
      double r2 = 0.0;
      for (int a = 0; a < dim; a++)
        r2 += (x[3 * q + a] - x[3 * i + a]) * (x[3 * q + a] - x[3 * i + a]);
      if (best < 0.0 || r2 < best) {
        best = r2;
        bi = i;
        bq = q;
      }
    }
  note_closest_pair(bi, bq, best);
}

/* Records owned cell i and cell q (in the list of cell atoms) at squared
   distance d2 as this step's closest pair (i < 0: none). */

void PairVertexVoronoi::note_closest_pair(int i, int q, double d2)
{
  close_d = -1.0;
  if (i >= 0) {
    close_d = std::sqrt(d2);
    close_i = cell_tag(i);
    close_j = cell_tag(q);
  }
  close_step = update->ntimestep;
}

/* Atoms lost since the last force computation: say so before the
   tessellation of what is left fails, and why.  LAMMPS drops an atom that
   is outside the box (a periodic box wraps it once), or past the
   neighbouring rank's sub-domain, when atoms are exchanged.  Atoms added
   since (fix cell/divide, fix deposit) point at where they were placed; an
   integration step that moved no atom far points at commands that set
   positions; otherwise the step was too large for the forces. */

void PairVertexVoronoi::check_lost_atoms()
{
  bigint n = atom->nlocal, ntotal = 0;
  MPI_Allreduce(&n, &ntotal, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  const bigint seen = natoms_seen;
  if (ntotal == atom->natoms) {
    natoms_seen = atom->natoms;
    return;
  }
  if (output && output->thermo && output->thermo->lostflag != Thermo::ERROR) return;
  // The globally closest pair of the last force computation.
  struct {
    double d;
    int rank;
  } mine{close_d >= 0.0 ? close_d : std::numeric_limits<double>::max(), comm->me}, best;
  MPI_Allreduce(&mine, &best, 1, MPI_DOUBLE_INT, MPI_MINLOC, world);
  tagint ids[2] = {close_i, close_j};
  bigint when = close_step;
  MPI_Bcast(ids, 2, MPI_LMP_TAGINT, best.rank, world);
  MPI_Bcast(&when, 1, MPI_LMP_BIGINT, best.rank, world);
  const std::string closest = best.d < std::numeric_limits<double>::max()
      ? fmt::format("; at step {} the closest centres were atoms {} and {}, {:.3g} apart", when,
                    ids[0], ids[1], best.d)
      : std::string();
  // The largest move of the last integration step (-1 on every rank: none).
  double moved = -1.0;
  MPI_Allreduce(&step_move_local, &moved, 1, MPI_DOUBLE, MPI_MAX, world);
  double smax = 0.0;
  for (int i = 1; i <= atom->ntypes; i++) smax = MAX(smax, cell_size(i));
  const std::string head = fmt::format(
      "pair_style vertex/voronoi: {} of {} atoms are left at step {}: the others were lost "
      "(LAMMPS drops an atom outside the box, a periodic box wraps it only once, or past a "
      "neighbouring rank's domain)",
      ntotal, atom->natoms, update->ntimestep);
  if (update->setupflag)
    error->all(
        FLERR,
        "{}, before the first step of this run: a command since the last force computation "
        "(set, displace_atoms, create_atoms, change_box, read_dump, ...) put them out of the "
        "box; keep the atoms inside it",
        head);
  if (seen >= 0 && atom->natoms > seen)
    error->all(
        FLERR,
        "{}. {} atoms were added since the last force computation (by fix cell/divide, "
        "fix deposit, create_atoms, ...), and the lost ones are likely among them: place new atoms "
        "inside the box and near their neighbours (fix cell/divide's separation d puts the "
        "daughters d/2 from the mother: keep it below a cell diameter; fix deposit's "
        "region must lie inside the box, which with shrink-wrapped boundaries 'boundary "
        "s' is only as large as the atoms)",
        head, atom->natoms - seen);
  // An atom the integrators moved past a fixed boundary (the latest).
  FixVertexGuard::Left left;
  const int iguard = modify->find_fix(guard_id);
  if (iguard >= 0)
    if (auto *guard = dynamic_cast<FixVertexGuard *>(modify->fix[iguard])) left = guard->left_box();
  // the latest step any rank saw, and of its atoms the lowest ID
  bigint lstep = -1;
  MPI_Allreduce(&left.step, &lstep, 1, MPI_LMP_BIGINT, MPI_MAX, world);
  if (lstep >= 0) {
    const bool mine = left.step == lstep;
    int count = 0, nleft = mine ? left.count : 0;
    MPI_Allreduce(&nleft, &count, 1, MPI_INT, MPI_SUM, world);
    struct {
      double tag;
      int rank;
    } lin{mine ? static_cast<double>(left.tag) : std::numeric_limits<double>::max(), comm->me},
        lout;
    MPI_Allreduce(&lin, &lout, 1, MPI_DOUBLE_INT, MPI_MINLOC, world);
    double w[4] = {static_cast<double>(left.dim), static_cast<double>(left.side), left.x,
                   left.bound};
    MPI_Bcast(w, 4, MPI_DOUBLE, lout.rank, world);
    static const char *axis = "xyz";
    const int d = static_cast<int>(w[0]);
    const bool upper = w[1] > 0.5;
    error->all(FLERR,
               "{}. Atom {} left the box through its fixed ('f') {} {} boundary at step {} ({} = "
               "{:.6g}, {} {:.6g}){}, and LAMMPS drops an atom outside a fixed boundary: keep the "
               "cells in with a wall (fix wall/harmonic, fix wall/region), let the box follow them "
               "with a shrink-wrapped boundary ('s' in the boundary command), or enlarge the box{}",
               head, static_cast<tagint>(lout.tag), upper ? "upper" : "lower", axis[d], lstep,
               axis[d], w[2], upper ? "past" : "below", w[3],
               count > 1 ? fmt::format(" with {} more atoms", count - 1) : std::string(), closest);
  }
  if (moved >= 0.0 && moved <= smax)
    error->all(FLERR,
               "{}. The last integration step moved no atom further than {:.3g} (less than a cell "
               "diameter, {:.3g}), so the timestep did not lose them: a command or fix that sets "
               "positions or changes the box (set, displace_atoms, change_box, a fix) put them "
               "out of the box{}",
               head, moved, smax, closest);
  error->all(FLERR,
             "{}; during a run usually because the forces were too large for the timestep (two "
             "centres nearly colliding, or very stiff parameters){}. To resolve the forces, {}",
             head, closest, step_advice());
}
