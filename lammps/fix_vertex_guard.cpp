/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   The step guard of pair_style vertex/voronoi (see fix_vertex_guard.h).
------------------------------------------------------------------------- */

#include "fix_vertex_guard.h"

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "update.h"

#include <cmath>
#include <limits>

using namespace LAMMPS_NS;
using namespace FixConst;

FixVertexGuard::FixVertexGuard(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg) {}

Fix *FixVertexGuard::creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixVertexGuard(lmp, narg, arg);
}

int FixVertexGuard::setmask()
{
  return POST_INTEGRATE | POST_FORCE;
}

void FixVertexGuard::record()
{
  dim = domain->dimension;
  const int n = atom->nlocal;
  x0.resize(static_cast<size_t>(dim) * n);
  tag0.resize(n);
  for (int i = 0; i < n; i++) {
    for (int d = 0; d < dim; d++) x0[dim * i + d] = atom->x[i][d];
    tag0[i] = atom->tag[i];
  }
  step0 = update->ntimestep;
}

/* The largest displacement LAMMPS's atom migration survives: one
   neighbouring sub-domain, or half the box along a direction with one rank. */

double FixVertexGuard::loss_limit() const
{
  double limit = std::numeric_limits<double>::max();
  const double prd[3] = {domain->xprd, domain->yprd, domain->zprd};
  for (int d = 0; d < dim; d++) {
    // One rank along an open direction: nothing to migrate past (an atom
    // that leaves a fixed boundary is reported by the pair style's count).
    if (comm->procgrid[d] == 1 && !domain->periodicity[d]) continue;
    const double width = (domain->triclinic ? domain->subhi_lamda[d] - domain->sublo_lamda[d]
                                            : (domain->subhi[d] - domain->sublo[d]) / prd[d]) *
        prd[d];
    limit = MIN(limit, comm->procgrid[d] > 1 ? width : 0.5 * prd[d]);
  }
  return limit;
}

std::string FixVertexGuard::describe(int i, double moved, double size) const
{
  tagint j = 0;
  double d = -1.0;
  if (static_cast<int>(x0.size()) == dim * atom->nlocal)
    pair->closest_neighbour(i, x0.data(), j, d);
  const char *what = dim == 3 ? "cbrt(V0)" : "sqrt(A0)";
  std::string text = fmt::format(
      "atom {} moved by {:.3g} in the step from {} to {}, more than a cell diameter {} = {:.3g}: "
      "the timestep does not resolve the forces of step {}",
      atom->tag[i], moved, step0, update->ntimestep, what, size, step0);
  if (d >= 0.0)
    text += fmt::format(" (its closest Voronoi neighbour then, atom {}, was {:.3g} away", j, d);
  else
    text += " (it had no Voronoi neighbour then";
  if (pair->finite_radius() > 0.0)
    text += "; finite cells: the force of a contact that just formed grows as 1/sqrt(2r - d), "
            "which is not a collision, and 'fix dt/reset' limits the step it causes)";
  else
    text += "; Voronoi forces grow as 1/distance when two centres nearly collide)";
  return text;
}

void FixVertexGuard::post_integrate()
{
  if (!pair) return;
  const int n = atom->nlocal;
  // Atoms added or re-ordered without a force computation (run N pre no):
  // nothing to compare on this rank, but it still takes part below.
  bool valid = static_cast<int>(tag0.size()) == n && dim == domain->dimension;
  for (int i = 0; valid && i < n; i++) valid = atom->tag[i] == tag0[i];
  double **x = atom->x;
  const int *type = atom->type;
  const double lost = loss_limit();
  // Squared distances against squared limits (one sqrt per type, not per atom).
  const int ntypes = atom->ntypes;
  size2.resize(ntypes + 1);
  const double big = std::numeric_limits<double>::max();
  // Atoms that are no cells have no cell size to compare with.
  for (int t = 1; t <= ntypes; t++)
    size2[t] = pair->is_cell_type(t) ? pair->cell_size(t) * pair->cell_size(t) : big;
  const double lost2 = lost < std::sqrt(big) ? lost * lost : big;
  int worst = -1;
  double worst_moved2 = 0.0;
  for (int i = 0; valid && i < n; i++) {
    double moved2 = 0.0;
    for (int d = 0; d < dim; d++) {
      const double dx = x[i][d] - x0[dim * i + d];
      moved2 += dx * dx;
    }
    if (!(moved2 <= lost2)) {    // also NaN
      // The distance without overflow of its square.
      double big_d = 0.0, sum = 0.0;
      for (int d = 0; d < dim; d++) big_d = MAX(big_d, std::fabs(x[i][d] - x0[dim * i + d]));
      for (int d = 0; d < dim; d++) {
        const double q = (x[i][d] - x0[dim * i + d]) / big_d;
        sum += q * q;
      }
      const double moved = big_d * std::sqrt(sum);
      bool finite = true;
      for (int d = 0; d < dim; d++) finite = finite && std::isfinite(x[i][d]);
      if (!finite)
        error->one(FLERR,
                   "pair_style vertex/voronoi: atom {} has a non-finite position after the step "
                   "from {} to {} (a non-finite force or velocity: check the parameters and the "
                   "fixes that move atoms)",
                   atom->tag[i], step0, update->ntimestep);
      error->one(FLERR,
                 "pair_style vertex/voronoi: {}; it would be lost (limit {:.3g} for this domain "
                 "decomposition). Use a smaller timestep, 'fix dt/reset' to limit the "
                 "displacement per step, or the second-order integrator fix brownian/heun",
                 describe(i, moved, pair->cell_size(type[i])), lost);
    }
    if (moved2 > size2[type[i]] && moved2 > worst_moved2) {
      worst = i;
      worst_moved2 = moved2;
    }
  }
  const double worst_moved = std::sqrt(worst_moved2);
  if (warned) return;
  // The largest such step over all ranks, reported by rank 0 (other ranks
  // have no screen).
  struct {
    double moved;
    int rank;
  } mine{worst >= 0 ? worst_moved : -1.0, comm->me}, top;
  MPI_Allreduce(&mine, &top, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  if (top.moved < 0.0) return;
  warned = 1;
  std::string text;
  if (comm->me == top.rank) text = describe(worst, worst_moved, pair->cell_size(atom->type[worst]));
  int len = static_cast<int>(text.size());
  MPI_Bcast(&len, 1, MPI_INT, top.rank, world);
  text.resize(len);
  MPI_Bcast(&text[0], len, MPI_CHAR, top.rank, world);
  if (comm->me == 0)
    error->warning(FLERR,
                   "pair_style vertex/voronoi: {}. The run goes on, but such steps are not "
                   "accurate; use a smaller timestep, 'fix dt/reset' or fix brownian/heun "
                   "(reported once per run)",
                   text);
}
