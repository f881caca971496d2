/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   Period-two oscillation of an explicit overdamped integrator (see
   integrator_chatter.h).
------------------------------------------------------------------------- */

#include "integrator_chatter.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "update.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

/* For a mode of stiffness lambda (force -lambda x), forward Euler
   multiplies the displacement by m = 1 - dt lambda / gamma_t per step: for
   dt lambda / gamma_t > 1 successive displacements are anti-parallel, and
   past 2 (|m| > 1) they no longer die out (Heun: m = 1 - z + z^2/2 with
   z = dt lambda / gamma_t, negative only for complex z, i.e. forces that
   also turn).  The sums are over the fix's group and weighted by the
   displacements' lengths, so a few chattering cells with large moves show
   even when most cells move smoothly. */

void IntegratorChatter::begin(int groupbit)
{
  double **v = atom->v;
  const int *mask = atom->mask;
  nbefore = atom->nlocal;
  before.resize(3 * static_cast<size_t>(nbefore));
  for (int i = 0; i < nbefore; i++)
    for (int d = 0; d < 3; d++) before[3 * i + d] = (mask[i] & groupbit) ? v[i][d] : 0.0;
}

void IntegratorChatter::end(const char *style, const char *id, int groupbit, double dt)
{
  double **v = atom->v;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int ndim = domain->dimension;
  // Atoms exchanged within the step (a pair style that widened its ghost
  // shell) have other indices: nothing to compare on this step.
  int same = nlocal == nbefore ? 1 : 0, all_same;
  MPI_Allreduce(&same, &all_same, 1, MPI_INT, MPI_MIN, world);
  nbefore = -1;
  if (!all_same) return;
  double sums[NSUMS] = {0.0, 0.0, 0.0, 0.0};
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) add(sums, &before[3 * static_cast<size_t>(i)], v[i], ndim);
  observe(style, id, sums, dt);
}

void IntegratorChatter::observe(const char *style, const char *id, const double *sums, double dt)
{
  const int ndim = domain->dimension;
  double all[NSUMS];
  MPI_Allreduce(sums, all, NSUMS, MPI_DOUBLE, MPI_SUM, world);
  const double norm = std::sqrt(all[OLD2] * all[NEW2]);
  corr = norm > 0.0 && std::isfinite(norm) ? all[DOT] / norm : 0.0;
  const double size = dt * dt * all[NEW2];
  // Moves at the round-off of the positions (a converged state) may flip
  // from step to step: they are no chatter.
  double length = std::max(domain->xprd, domain->yprd);
  if (ndim == 3) length = std::max(length, domain->zprd);
  const bool resolved = all[COUNT] > 0.0 && std::sqrt(size / all[COUNT]) > FLOOR * length;
  if (!resolved) {
    corrs.clear();
    sizes.clear();
    return;
  }
  corrs.push_back(corr);
  sizes.push_back(size);
  if (static_cast<int>(corrs.size()) > STEPS) {
    corrs.erase(corrs.begin());
    sizes.erase(sizes.begin());
  }
  if (warned || static_cast<int>(corrs.size()) < STEPS) return;
  double mean = 0.0;
  for (double c : corrs) mean += c / STEPS;
  // Squared displacements of the first and the last tenth of the window.
  const int tenth = STEPS / 10;
  double first = 0.0, last = 0.0;
  for (int k = 0; k < tenth; k++) {
    first += sizes[k];
    last += sizes[STEPS - 1 - k];
  }
  if (!(mean < ANTI) || !(last >= DECAY * first)) return;
  warned = true;
  if (comm->me == 0)
    error->warning(FLERR,
                   "fix {} {}: the cells' displacements have reversed direction from step to "
                   "step over steps {} to {} (mean correlation of successive displacements "
                   "{:.2f}) without dying out: the integrator oscillates about the state instead "
                   "of following it (the timestep {} is past its stability limit for the "
                   "stiffest motion, about 2 gamma_t / stiffness), so positions and energy "
                   "alternate from step to step and are not the model's.  Use a smaller "
                   "timestep, or 'fix dt/reset' to cap the displacement per step (reported once)",
                   id, style, update->ntimestep - STEPS + 1, update->ntimestep, mean, dt);
}
