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
#include "force.h"
#include "update.h"

#include <cmath>
#include <limits>

using namespace LAMMPS_NS;
using namespace FixConst;

FixVertexGuard::FixVertexGuard(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg)
{
  create_attribute = 1;
}

/* A new atom (fix deposit, fix pour, create_atoms; not a daughter of fix
   cell/divide, which copies its mother): its type's values in the per-cell
   properties the pair style reads.  The pair style is looked up each time
   (a new pair_style command replaces the object this fix was given). */

void FixVertexGuard::set_arrays(int i)
{
  static const char *names[4] = {"area0", "ka", "kp", "perim0"};
  auto *p = dynamic_cast<PairVertexVoronoi *>(force->pair_match("vertex/voronoi", 1));
  double values[4] = {0.0, 0.0, 0.0, 0.0};
  if (p) p->type_cell_values(atom->type[i], values);
  for (int k = 0; k < 4; k++) {
    int flag = -1, cols = -1;
    const int index = atom->find_custom(names[k], flag, cols);
    if (index >= 0 && flag == 1 && cols == 0) atom->dvector[index][i] = values[k];
  }
}

Fix *FixVertexGuard::creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixVertexGuard(lmp, narg, arg);
}

/* After the other fixes' init (the guard is added last), so that their own,
   more specific checks speak first. */

void FixVertexGuard::init()
{
  warned = 0;
  if (pair) pair->check_integrators();
}

int FixVertexGuard::setmask()
{
  return POST_INTEGRATE | END_OF_STEP;
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
  // An atom that is no cell: the cells' forces do not move it.
  if (!pair->is_cell_type(atom->type[i]))
    return fmt::format(
        "atom {} of type {}, which is no cell (no vertex/voronoi parameters), moved by {:.3g} in "
        "the step from {} to {}: the forces on it come from the other sub-styles of the pair "
        "style, its bonds and angles, and the fixes that act on it (check their parameters "
        "and that the timestep resolves their stiffest force)",
        atom->tag[i], atom->type[i], moved, step0, update->ntimestep);
  tagint j = 0;
  double d = -1.0;
  if (static_cast<int>(x0.size()) == dim * atom->nlocal)
    pair->closest_neighbour(i, x0.data(), j, d);
  const bool sphere = pair->on_sphere();
  const char *what = dim == 3 && !sphere ? "cbrt(V0)" : "sqrt(A0)";
  std::string text = fmt::format(
      "atom {} moved by {:.3g}{} in the step from {} to {}, more than a cell diameter {} = "
      "{:.3g}: the timestep does not resolve the forces of step {}",
      atom->tag[i], moved, sphere ? " on the sphere (the chord from its old to its new place)" : "",
      step0, update->ntimestep, what, size, step0);
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
  double worst_moved2 = 0.0, step_max2 = 0.0;
  // On a sphere an integrator moves the cells in space and the surface's
  // fix (after this one) puts them back on the sphere: the move is from the
  // old place to the new one's projection, at most 2R.
  const bool sphere = valid && pair->on_sphere();
  const double *c = sphere ? pair->sphere_centre() : nullptr;
  const double R = sphere ? pair->sphere_radius() : 0.0;
  double dx[3] = {0.0, 0.0, 0.0};
  auto displacement = [&](int i) {
    for (int d = 0; d < dim; d++) dx[d] = x[i][d] - x0[dim * i + d];
    if (!sphere) return;
    const double u[3] = {x[i][0] - c[0], x[i][1] - c[1], x[i][2] - c[2]};
    const double l = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (!(l > 0.0) || !std::isfinite(l)) return;
    for (int d = 0; d < 3; d++) dx[d] = c[d] + R * u[d] / l - x0[3 * i + d];
  };
  for (int i = 0; valid && i < n; i++) {
    displacement(i);
    double moved2 = 0.0;
    for (int d = 0; d < dim; d++) moved2 += dx[d] * dx[d];
    if (!(moved2 <= lost2)) {    // also NaN
      // The distance without overflow of its square.
      double big_d = 0.0, sum = 0.0;
      for (int d = 0; d < dim; d++) big_d = MAX(big_d, std::fabs(dx[d]));
      for (int d = 0; d < dim; d++) {
        const double q = dx[d] / big_d;
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
                 "decomposition). To resolve the forces, {}",
                 describe(i, moved, pair->cell_size(type[i])), lost, pair->step_advice());
    }
    step_max2 = MAX(step_max2, moved2);
    if (moved2 > size2[type[i]] && moved2 > worst_moved2) {
      worst = i;
      worst_moved2 = moved2;
    }
  }
  const double worst_moved = std::sqrt(worst_moved2);
  pair->step_move_local = valid ? std::sqrt(step_max2) : -1.0;
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
                   "accurate; {} (reported once per run)",
                   text, pair->step_advice());
}
