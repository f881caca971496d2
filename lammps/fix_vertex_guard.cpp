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

   The step guard of pair_style vertex/voronoi (see fix_vertex_guard.h).
------------------------------------------------------------------------- */

#include "fix_vertex_guard.h"

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "update.h"
#include "tessera/subset_cells.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

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
  // (an atom still outside is noted again at the next move)
  left = Left();
  recorded_count = pair ? pair->compute_count() : -1;
  // The neighbourhood only matters when the guard fires.  Where nothing
  // computes forces between the end of a step and the next post_integrate
  // (fix brownian, fix nve, ...), the cells of the last force computation
  // are still there then, and it is found from them only if needed: most
  // steps skip the pass over every cell's neighbours.  Where something does
  // (fix brownian/heun tessellates its predicted positions in
  // initial_integrate), it is recorded now, as the step's start.
  deferred = defer_ok;
  if (!deferred) record_neighbourhood();
}

/* The neighbourhood the last record() deferred, from the cells still in
   the pair style's view.  The view's points of owned atoms may be the atoms'
   positions themselves, which the integrator has moved since: the
   positions of the record (x0) stand in for them.  Ghosts move only at the
   next communication, after post_integrate. */

void FixVertexGuard::ensure_neighbourhood()
{
  if (!deferred) return;
  deferred = false;
  record_neighbourhood(true);
}

/* Each owned cell's neighbourhood in the cells of the last force
   computation, with the positions that tessellation used (the view's
   points: a ghost's image, or on a sphere the point in space), so that the
   neighbour and its distance belong to the same state.  With fix
   brownian/heun the cells at the guard's check are those of the predicted
   positions; these are the step's start, the state the message names. */

void FixVertexGuard::record_neighbourhood(bool moved)
{
  const int n = atom->nlocal;
  around.assign(n, Around());
  nb_offset.assign(n + 1, 0);
  nb_tag.clear();
  if (!pair) return;
  const tessera::CellView &v = pair->cells();
  if (v.n_owned() != n || v.n_points() != n + atom->nghost) return;
  const tessera::Contacts c = v.contacts();
  const int sd = v.space_dimension();
  double xi[3] = {0.0, 0.0, 0.0}, xq[3] = {0.0, 0.0, 0.0};
  const bool from_x0 = moved && sd <= dim && static_cast<int>(x0.size()) == dim * n;
  auto point = [&](int q, double *out) {
    if (from_x0 && q < n)
      for (int d = 0; d < sd; d++) out[d] = x0[dim * q + d];
    else
      v.point(q, out);
  };
  double **f = atom->f;
  for (int i = 0; i < n; i++) {
    Around &a = around[i];
    a.force = std::sqrt(f[i][0] * f[i][0] + f[i][1] * f[i][1] + f[i][2] * f[i][2]);
    if (!pair->is_cell_type(atom->type[i])) continue;
    a.measure = v.measure(i);
    a.boundary = v.boundary(i);
    point(i, xi);
    for (int k = c.offset[i]; k < c.offset[i + 1]; k++) {
      const int q = c.neighbor[k];
      point(q, xq);
      double r2 = 0.0;
      for (int d = 0; d < sd; d++) r2 += (xq[d] - xi[d]) * (xq[d] - xi[d]);
      const double r = std::sqrt(r2);
      if (a.near_d < 0.0 || r < a.near_d) {
        a.near_d = r;
        a.near_tag = atom->tag[q];
      }
      nb_tag.push_back(atom->tag[q]);
    }
    nb_offset[i + 1] = static_cast<int>(nb_tag.size());
  }
  for (int i = 0; i < n; i++) nb_offset[i + 1] = MAX(nb_offset[i + 1], nb_offset[i]);
}

/* Owned cell i's area and perimeter (3d: volume, surface) at the last
   record against its preferred ones (d_area0 and d_perim0 when defined,
   else its type's), and how far it exceeds them beyond the tissue's
   typical cell (typical: the mean A/A0 and P - P0 over all cells).  Far
   above (excess >= 1): an area A0 more than the typical ratio gives, or a
   perimeter three cell diameters longer than the typical excess gives
   (3d: volume, and surface by three cbrt(V0)^2).  Measured against the
   tissue, so that parameters every cell is far from (a P0 no cell can
   reach) are not taken for the cause of one step. */

FixVertexGuard::State FixVertexGuard::state_of(int i, const double *typical) const
{
  State st;
  if (i < 0 || i >= static_cast<int>(around.size()) || around[i].measure < 0.0) return st;
  double values[4] = {0.0, 0.0, 0.0, 0.0};
  pair->type_cell_values(atom->type[i], values);
  static const char *names[2] = {"area0", "perim0"};
  double *pref[2] = {&values[0], &values[3]};
  for (int k = 0; k < 2; k++) {
    int flag = -1, cols = -1;
    const int index = atom->find_custom(names[k], flag, cols);
    if (index >= 0 && flag == 1 && cols == 0) *pref[k] = atom->dvector[index][i];
  }
  st.tag = atom->tag[i];
  st.A = around[i].measure;
  st.A0 = values[0];
  st.P = around[i].boundary;
  st.P0 = values[3];
  if (!(st.A0 > 0.0)) return st;
  st.excess = 0.0;
  if (!typical) return st;
  st.excess = MAX(0.0, st.A / st.A0 - typical[0]);
  const double unit = dim == 3 && !pair->on_sphere() ? std::cbrt(st.A0 * st.A0) : std::sqrt(st.A0);
  if (st.P0 > 0.0) st.excess = MAX(st.excess, (st.P - st.P0 - typical[1]) / (3.0 * unit));
  return st;
}

/* An owned atom outside a fixed ('f') boundary after the move: LAMMPS
   drops it at the next exchange, and the lost-atom message names it. */

void FixVertexGuard::note_left_box()
{
  int fixed = 0;
  for (int d = 0; d < domain->dimension; d++)
    fixed |= domain->boundary[d][0] == 1 || domain->boundary[d][1] == 1;
  if (!fixed) return;
  double **x = atom->x;
  const double *lo = domain->triclinic ? domain->boxlo_lamda : domain->boxlo;
  const double *hi = domain->triclinic ? domain->boxhi_lamda : domain->boxhi;
  double lamda[3];
  for (int i = 0; i < atom->nlocal; i++) {
    const double *p = x[i];
    if (domain->triclinic) {
      domain->x2lamda(x[i], lamda);
      p = lamda;
    }
    for (int d = 0; d < domain->dimension; d++)
      for (int side = 0; side < 2; side++) {
        if (domain->boundary[d][side] != 1) continue;
        if (side == 0 ? !(p[d] < lo[d]) : !(p[d] > hi[d])) continue;
        if (left.step == update->ntimestep) {
          left.count++;
          if (atom->tag[i] > left.tag) continue;
        } else {
          left.count = 1;
        }
        left.step = update->ntimestep;
        left.tag = atom->tag[i];
        left.dim = d;
        left.side = side;
        left.x = x[i][d];
        left.bound = side == 0 ? domain->boxlo[d] : domain->boxhi[d];
      }
  }
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

/* The cell that most exceeds its preferred area or perimeter among
   owned atom i of rank root and its Voronoi neighbours (found on the ranks
   that own them), then the message's text, built on root and sent to
   every rank. */

std::string FixVertexGuard::describe_all(int root, int i, double moved)
{
  ensure_neighbourhood();
  const bool mine = comm->me == root;
  const bool known = mine && i >= 0 && i < static_cast<int>(around.size());
  // i's neighbours' IDs, from root to every rank
  std::vector<tagint> tags;
  if (known) tags.assign(nb_tag.begin() + nb_offset[i], nb_tag.begin() + nb_offset[i + 1]);
  int count = static_cast<int>(tags.size());
  MPI_Bcast(&count, 1, MPI_INT, root, world);
  tags.resize(count);
  if (count) MPI_Bcast(tags.data(), count, MPI_LMP_TAGINT, root, world);
  // the tissue's typical cell: mean A/A0 and P - P0 over all cells
  const int nrec = MIN(atom->nlocal, static_cast<int>(around.size()));
  double sums[3] = {0.0, 0.0, 0.0}, typical[3];
  for (int k = 0; k < nrec; k++) {
    const State st = state_of(k, nullptr);
    if (st.excess < 0.0) continue;
    sums[0] += st.A / st.A0;
    if (st.P0 > 0.0) sums[1] += st.P - st.P0;
    sums[2] += 1.0;
  }
  MPI_Allreduce(sums, typical, 3, MPI_DOUBLE, MPI_SUM, world);
  if (typical[2] > 0.0) {
    typical[0] /= typical[2];
    typical[1] /= typical[2];
  }
  // the worst of those this rank owns (and i itself on root)
  State worst;
  double ratio[2] = {-1.0, -HUGE_VAL};    // the largest A/A0 and P - P0 around i
  if (count || known) {
    std::unordered_map<tagint, int> local;
    for (int k = 0; k < nrec; k++) local[atom->tag[k]] = k;
    auto consider = [&](int k) {
      const State st = state_of(k, typical);
      if (st.excess > worst.excess) worst = st;
      if (st.A0 > 0.0) ratio[0] = MAX(ratio[0], st.A / st.A0);
      if (st.P0 > 0.0) ratio[1] = MAX(ratio[1], st.P - st.P0);
    };
    if (known) consider(i);
    for (tagint t : tags) {
      auto it = local.find(t);
      if (it != local.end()) consider(it->second);
    }
  }
  struct {
    double excess;
    int rank;
  } in{worst.excess, comm->me}, out;
  MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  double ratio_all[2];
  MPI_Allreduce(ratio, ratio_all, 2, MPI_DOUBLE, MPI_MAX, world);
  double w[6] = {worst.excess, worst.A,  worst.A0,
                 worst.P,      worst.P0, static_cast<double>(worst.tag)};
  MPI_Bcast(w, 6, MPI_DOUBLE, out.rank, world);
  worst.excess = w[0];
  worst.A = w[1];
  worst.A0 = w[2];
  worst.P = w[3];
  worst.P0 = w[4];
  worst.tag = static_cast<tagint>(w[5]);
  // the closest pair of Voronoi neighbours anywhere, at the same state
  struct {
    double d;
    int rank;
  } near_in{std::numeric_limits<double>::max(), comm->me}, near_out;
  tagint pair_tags[2] = {0, 0};
  for (int k = 0; k < nrec; k++)
    if (around[k].near_d >= 0.0 && around[k].near_d < near_in.d) {
      near_in.d = around[k].near_d;
      pair_tags[0] = atom->tag[k];
      pair_tags[1] = around[k].near_tag;
    }
  MPI_Allreduce(&near_in, &near_out, 1, MPI_DOUBLE_INT, MPI_MINLOC, world);
  MPI_Bcast(pair_tags, 2, MPI_LMP_TAGINT, near_out.rank, world);
  closest = {near_out.d < std::numeric_limits<double>::max() ? near_out.d : -1.0, pair_tags[0],
             pair_tags[1]};
  std::string text;
  if (mine) text = describe(i, moved, pair->cell_size(atom->type[i]), worst, ratio_all, typical);
  int len = static_cast<int>(text.size());
  MPI_Bcast(&len, 1, MPI_INT, root, world);
  text.resize(len);
  if (len) MPI_Bcast(&text[0], len, MPI_CHAR, root, world);
  return text;
}

/* The text for owned atom i: what moved, how far, and the cause that fits
   the numbers of the step's start (its closest neighbour's distance; the
   cells around it against their preferred area and perimeter, worst being
   the one that exceeds them most; else the forces that are not the
   cells'). */

std::string FixVertexGuard::describe(int i, double moved, double size, const State &worst,
                                     const double *ratio, const double *typical) const
{
  // An atom that is no cell: the cells' forces do not move it.
  if (!pair->is_cell_type(atom->type[i]))
    return fmt::format(
        "atom {} of type {}, which is no cell (no vertex/voronoi parameters), moved by {:.3g} in "
        "the step from {} to {}: the forces on it come from the other sub-styles of the pair "
        "style, its bonds and angles, and the fixes that act on it (check their parameters "
        "and that the timestep resolves their stiffest force)",
        atom->tag[i], atom->type[i], moved, step0, update->ntimestep);
  const bool have = i < static_cast<int>(around.size());
  const tagint j = have ? around[i].near_tag : 0;
  const double d = have ? around[i].near_d : -1.0;
  const bool sphere = pair->on_sphere();
  const bool three = dim == 3 && !sphere;
  std::string text = fmt::format(
      "atom {} moved by {:.3g}{} in the step from {} to {}, more than a cell diameter {} = "
      "{:.3g}: the timestep does not resolve the forces of step {}",
      atom->tag[i], moved, sphere ? " on the sphere (the chord from its old to its new place)" : "",
      step0, update->ntimestep, three ? "cbrt(V0)" : "sqrt(A0)", size, step0);
  const std::string nearest = d >= 0.0
      ? fmt::format("its closest Voronoi neighbour then, atom {}, was {:.3g} away, "
                    "{:.2g} cell diameters",
                    j, d, d / size)
      : std::string("it had no Voronoi neighbour then");
  const char *area = three ? "volume" : "area";
  const char *perim = three ? "surface" : "perimeter";
  std::vector<std::string> causes;
  // A close pair: well inside a cell diameter.
  const bool close = d >= 0.0 && d < 0.25 * size;
  if (close)
    causes.push_back("a close pair: " + nearest +
                     ", and Voronoi forces grow as 1/distance when two centres nearly collide");
  if (worst.excess >= 1.0) {
    std::string big = fmt::format(
        "a cell far above its preferred {} or {}: {} had {} {:.3g}, {:.2g} times {} = {:.3g}", area,
        perim,
        worst.tag == atom->tag[i] ? std::string("the cell itself")
                                  : fmt::format("its Voronoi neighbour, atom {},", worst.tag),
        area, worst.A, worst.A / worst.A0, three ? "V0" : "A0", worst.A0);
    big += fmt::format(" (the tissue's mean {:.2g} times)", typical[0]);
    if (worst.P0 > 0.0)
      big += fmt::format(", and {} {:.3g} against {} = {:.3g}", perim, worst.P, three ? "S0" : "P0",
                         worst.P0);
    if (pair->finite_radius() > 0.0)
      big +=
          fmt::format(" (its {} term pulls on its neighbours in proportion to the excess)", area);
    else
      big += fmt::format(" (a confluent Voronoi cell next to an empty region fills it, and its "
                         "{} term pulls on its neighbours in proportion to the excess: fill the "
                         "region, or use finite cells, 'radius r', which end at a free edge)",
                         area);
    causes.push_back(big + (close ? "" : "; " + nearest));
  }
  // A near collision elsewhere (a hundredth of a cell diameter, not a
  // pair that random positions give): an integrator that computes the
  // forces again at predicted positions (fix brownian/heun) moves every
  // atom by the forces of a state that pair has thrown about.
  if (causes.empty() && closest.d >= 0.0 && closest.d < 0.01 * size) {
    bool predicts = false;
    for (int k = 0; k < modify->nfix; k++)
      predicts = predicts || strcmp(modify->fix[k]->style, "brownian/heun") == 0;
    causes.push_back(fmt::format(
        "a close pair elsewhere: atoms {} and {} were {:.3g} apart at step {}, {:.2g} cell "
        "diameters, and Voronoi forces grow as 1/distance when two centres nearly collide{} "
        "({})",
        closest.a, closest.b, closest.d, step0, closest.d / size,
        predicts ? "; the integrator computes the forces again at its predicted positions, "
                   "where that pair has thrown the cells around it about, and moves every atom "
                   "by them"
                 : "",
        nearest));
  }
  if (causes.empty() && pair->finite_radius() > 0.0)
    causes.push_back(nearest +
                     "; finite cells: the force of a contact that just formed grows as "
                     "1/sqrt(2r - d), which is not a collision, and 'fix dt/reset' limits the "
                     "step it causes");
  if (causes.empty()) {
    // The cells around it were ordinary: name the forces that are not theirs.
    std::string around_it;
    if (ratio[0] >= 0.0)
      around_it = fmt::format(", the cells around it at most {:.2g} times their preferred {}",
                              ratio[0], area);
    if (ratio[1] > -HUGE_VAL)
      around_it += fmt::format(" and {:.2g} above their preferred {}", ratio[1], perim);
    if (typical[2] > 0.0)
      around_it += fmt::format(" (the tissue's mean: {:.2g} times and {:.2g} above)", typical[0],
                               typical[1]);
    std::string elsewhere;
    if (force->pair != pair)
      elsewhere = fmt::format("a stiff force from another sub-style of pair_style {}{}",
                              force->pair_style, force->bond ? ", or from its bonds," : "");
    else if (force->bond)
      elsewhere = "a stiff force from its bonds";
    causes.push_back(fmt::format(
        "not the cells around it (neither a close pair nor a cell far above its preferred {} or "
        "{}: {}{}), so the force on it then, {:.3g}, is likely {}{}",
        area, perim, nearest, around_it, have ? around[i].force : 0.0, elsewhere,
        elsewhere.empty() ? "the cells' own force, too stiff for this timestep, or that of a fix "
                            "that adds forces (fix polarity's active force, fix addforce, ...)"
                          : " or from a fix that adds forces (fix polarity's active force, fix "
                            "addforce, ...)"));
  }
  text += ". Cause: " + causes[0];
  for (size_t k = 1; k < causes.size(); k++) text += "; and " + causes[k];
  return text;
}

void FixVertexGuard::post_integrate()
{
  if (!pair) return;
  // Did a force computation come between the last record and this check?
  // If so, the cells now in the view are not the step's start: a deferred
  // neighbourhood is lost for this step (none is named), and from now on
  // it is recorded at once.
  const bool unchanged = pair->compute_count() == recorded_count;
  if (deferred && !unchanged) {
    deferred = false;
    around.clear();
    nb_offset.assign(atom->nlocal + 1, 0);
    nb_tag.clear();
  }
  defer_ok = unchanged;
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
  note_left_box();
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
  // The atom to name when atoms would be lost: one that is no cell first
  // (its forces are never the cells'), else the one that moved farthest.
  int lost_i = -1;
  const double none = std::numeric_limits<double>::lowest();
  double lost_moved = -1.0, lost_key = none;
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
      const double key = (pair->is_cell_type(type[i]) ? 0.0 : 1000.0) + std::log10(moved);
      if (key > lost_key) {
        lost_i = i;
        lost_moved = moved;
        lost_key = key;
      }
      continue;
    }
    step_max2 = MAX(step_max2, moved2);
    if (moved2 > size2[type[i]] && moved2 > worst_moved2) {
      worst = i;
      worst_moved2 = moved2;
    }
  }
  const double worst_moved = std::sqrt(worst_moved2);
  pair->step_move_local = valid ? std::sqrt(step_max2) : -1.0;
  // The farthest move past the loss limit, and (until warned) the largest
  // one past a cell diameter, over all ranks: one reduction per step.
  struct {
    double moved;
    int rank;
  } mine[2] = {{lost_key, comm->me}, {!warned && worst >= 0 ? worst_moved : -1.0, comm->me}},
    top[2];
  MPI_Allreduce(mine, top, 2, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  if (top[0].moved > none) {
    const std::string text = describe_all(top[0].rank, lost_i, lost_moved);
    double limit = lost;
    MPI_Bcast(&limit, 1, MPI_DOUBLE, top[0].rank, world);
    error->all(FLERR,
               "pair_style vertex/voronoi: {}; it would be lost (limit {:.3g} for this domain "
               "decomposition). To resolve the forces, {}",
               text, limit, pair->step_advice());
  }
  if (top[1].moved < 0.0) return;
  warned = 1;
  // reported by rank 0 (other ranks have no screen)
  const std::string text = describe_all(top[1].rank, worst, top[1].moved);
  if (comm->me == 0)
    error->warning(FLERR,
                   "pair_style vertex/voronoi: {}. The run goes on, but such steps are not "
                   "accurate; {} (reported once per run)",
                   text, pair->step_advice());
}
