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

   pair_style vertex/voronoi: the checks of a run's start (init_style) that
   stop input LAMMPS would otherwise mishandle without a useful word: a
   cutoff outside the usable range, two integrators moving the same cells,
   keywords the model does not use, a box too large for LAMMPS's atom sort.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "group.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

/* The cutoff only sets how far around its sub-domain a rank keeps ghost
   atoms.  A cell's neighbours lie about one cell diameter s away, and the
   ghost shell grows by itself when a cell needs more (at most 8 times per
   step, by at most 2x each), so a cutoff below s/100 can never hold them.
   Beyond a few diameters a larger cutoff changes no cell but multiplies the
   ghost atoms (with a periodic box, by 2 cutoff / length + 1 per direction),
   and LAMMPS's communication allocates a swap per box length the shell
   spans: above 100 s the run would only exhaust memory (or overflow). */

void PairVertexVoronoi::check_cutoff_range() const
{
  // The cell types only: other types (particles under hybrid/overlay) have no size here.
  double smin = 0.0, smax = 0.0;
  bool first = true;
  for (int i = 1; i <= atom->ntypes; i++) {
    if (!type_set[i]) continue;
    const double s = cell_size(i);
    if (first || s < smin) smin = s;
    if (first || s > smax) smax = s;
    first = false;
  }
  if (!(smin > 0.0)) return;
  const double lo = 0.01 * smin, hi = 100.0 * smax;
  if (cut_global >= lo && cut_global <= hi) return;
  const bool three = domain->dimension == 3 && !sphere_on;
  const std::string size = smin == smax ? fmt::format("{:.3g}", smin)
                                        : fmt::format("{:.3g} to {:.3g}", smin, smax);
  const char *why = cut_global < lo
      ? "a cell's neighbours lie about one diameter away, and the ghost shell, which grows "
        "by itself when a cell needs it, cannot grow that far"
      : "beyond a few diameters a larger cutoff changes no cell but multiplies the ghost atoms "
        "(and LAMMPS's communication allocates memory for every box length the ghost shell "
        "spans)";
  error->all(FLERR,
             "pair_style vertex/voronoi: cutoff {:.6g} is outside the usable range {:.3g} to "
             "{:.3g} (1/100 to 100 cell diameters {} = {}, from pair_coeff's {}): {}; use about "
             "3 cell diameters, e.g. 'pair_style vertex/voronoi {:.3g}'",
             cut_global, lo, hi, three ? "cbrt(V0)" : "sqrt(A0)", size, three ? "V0" : "A0", why,
             3.0 * smax);
}

/* Two fixes that integrate positions (fix brownian, brownian/heun, nve, ...)
   on the same cells move them twice per step; LAMMPS only warns that "one
   or more atoms are time integrated more than once", without naming them. */

void PairVertexVoronoi::check_integrators() const
{
  Fix **fixes = modify->fix;
  const int nfix = modify->nfix;
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  for (int a = 0; a < nfix; a++) {
    if (!fixes[a]->time_integrate) continue;
    for (int b = a + 1; b < nfix; b++) {
      if (!fixes[b]->time_integrate) continue;
      const int bits = fixes[a]->groupbit | fixes[b]->groupbit;
      bigint n = 0, both = 0;
      for (int i = 0; i < nlocal; i++)
        if ((mask[i] & bits) == bits) n++;
      MPI_Allreduce(&n, &both, 1, MPI_LMP_BIGINT, MPI_SUM, world);
      if (both == 0) continue;
      error->all(FLERR,
                 "pair_style vertex/voronoi: fix {} ({}, group {}) and fix {} ({}, group {}) both "
                 "integrate the positions of {} cells, which then move twice per step; keep one "
                 "integrator per cell ('unfix' one of them, or give them groups without common "
                 "atoms)",
                 fixes[a]->id, fixes[a]->style, group->names[fixes[a]->igroup], fixes[b]->id,
                 fixes[b]->style, group->names[fixes[b]->igroup], both);
    }
  }
}

/* LAMMPS sorts atoms into bins of half the neighbor cutoff (or the bin size
   of 'atom_modify sort'), counted in an int per direction.  Its neighbor
   binning checks that a box fits ("Domain too large for neighbor bins"),
   but this style requests no neighbor list, so nothing checks before the
   sort's count overflows: the same check, with the limit and the fixes. */

void PairVertexVoronoi::check_sort_bins() const
{
  if (atom->sortfreq <= 0) return;
  const double bin = atom->userbinsize > 0.0 ? atom->userbinsize
                                             : 0.5 * (cut_global + neighbor->skin);
  if (!(bin > 0.0)) return;
  const double prd[3] = {domain->xprd, domain->yprd, domain->zprd};
  const double tilt[3] = {std::fabs(domain->xy) + std::fabs(domain->xz), std::fabs(domain->yz),
                          0.0};
  double total = 1.0;
  static const char *axis = "xyz";
  for (int d = 0; d < domain->dimension; d++) {
    const double extent = prd[d] + (domain->triclinic ? tilt[d] : 0.0);
    const double nbin = extent / bin;
    total *= nbin;
    if (nbin > MAXSMALLINT || total > MAXSMALLINT)
      error->all(FLERR,
                 "pair_style vertex/voronoi: the box ({:.6g} along {}) is too large for LAMMPS's "
                 "atom sort, which bins it into {} of {:.6g} (half the cutoff plus skin, or "
                 "'atom_modify sort' bin size) and cannot count more than {} bins; make the box "
                 "fit the cells (a smaller region, or shrink-wrapped boundaries 'boundary s s s'), "
                 "or turn the sort off with 'atom_modify sort 0 0.0'",
                 extent, axis[d], d == 0 ? "bins" : "bins per plane or volume", bin, MAXSMALLINT);
  }
}

/* Each pass doubles the cutoff at least (or widens it to what the cells
   asked for): 8 passes without a complete shell mean cells that no
   cutoff reachable within the step would hold. */

void PairVertexVoronoi::ghost_shell_failed() const
{
  double smax = 0.0;
  for (int i = 1; i <= atom->ntypes; i++) smax = MAX(smax, cell_size(i));
  error->all(FLERR,
             "pair_style vertex/voronoi: the ghost shell did not converge at step {}: it was "
             "widened 8 times, to a cutoff of {:.6g}, and some cells still reached past it (cells "
             "far larger than their preferred size, or a cutoff far below it); start from a "
             "cutoff of about 3 cell diameters ('pair_style vertex/voronoi {:.3g}') and check "
             "that the cells' sizes match pair_coeff's {}",
             update->ntimestep, cut_global, 3.0 * smax,
             domain->dimension == 3 && !sphere_on ? "V0" : "A0");
  // Not reached: older LAMMPS (29 Sep 2021) does not declare Error::all
  // noreturn, which this function is.
  std::abort();
}

std::string PairVertexVoronoi::step_advice() const
{
  bool heun = false;
  for (int i = 0; i < modify->nfix; i++)
    heun = heun || strcmp(modify->fix[i]->style, "brownian/heun") == 0;
  return heun ? "use a smaller timestep, or 'fix dt/reset' to limit the displacement per step"
              : "use a smaller timestep, 'fix dt/reset' to limit the displacement per step, or "
                "the second-order integrator fix brownian/heun";
}
