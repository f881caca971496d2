/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   pair_style vertex/voronoi: the vertex-model energy of the Voronoi cells of
   the atoms, with exact forces on the atoms and the virial.  Each rank
   triangulates its owned and ghost atoms; the ghost shell (pair cutoff) must
   cover every circumcircle of an owned cell, which is checked every step.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "fix.h"
#include "neighbor.h"
#include "output.h"
#include "thermo.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   The step guard, an internal fix the pair style adds.  It keeps each owned
   atom's position from the last force computation and, after the
   integrators have moved the atoms (post_integrate, before atoms migrate
   between ranks), compares.  A step that moves an atom by more than a cell
   diameter sqrt(A0) does not resolve the forces (typically two centres
   nearly collided: the Voronoi forces grow as 1/distance): a warning, once
   per run, since such runs usually recover.  A step that moves it so far
   that LAMMPS would lose it (past the neighbouring rank's sub-domain, or
   half the box with one rank along that direction), or to a non-finite
   position, stops the run with an error.  Integrator-independent: it
   measures the displacement.
------------------------------------------------------------------------- */

namespace {

const char *const GUARD_STYLE = "VERTEX_VORONOI_GUARD";

class FixVertexGuard : public Fix {
 public:
  FixVertexGuard(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg), pair(nullptr) {}
  int setmask() override { return FixConst::POST_INTEGRATE | FixConst::POST_FORCE; }
  void init() override { warned = 0; }
  void setup(int) override { record(); }
  void post_force(int) override { record(); }
  void post_integrate() override;
  PairVertexVoronoi *pair;

 private:
  std::vector<double> x0;
  std::vector<tagint> tag0;
  std::vector<double> size2;    // per type: the squared warning limit
  bigint step0 = -1;
  int warned = 0;
  void record()
  {
    const int n = atom->nlocal;
    x0.resize(2 * static_cast<size_t>(n));
    tag0.resize(n);
    for (int i = 0; i < n; i++) {
      x0[2 * i] = atom->x[i][0];
      x0[2 * i + 1] = atom->x[i][1];
      tag0[i] = atom->tag[i];
    }
    step0 = update->ntimestep;
  }
  double loss_limit() const;
  std::string describe(int i, double moved, double size) const;
};

Fix *create_guard(LAMMPS *lmp, int narg, char **arg)
{
  return new FixVertexGuard(lmp, narg, arg);
}

}    // namespace

/* The largest displacement LAMMPS's atom migration survives: one
   neighbouring sub-domain, or half the box along a direction with one rank. */

double FixVertexGuard::loss_limit() const
{
  double limit = std::numeric_limits<double>::max();
  const double prd[2] = {domain->xprd, domain->yprd};
  for (int d = 0; d < 2; d++) {
    // One rank along an open direction: nothing to migrate past (an atom
    // that leaves a fixed boundary is reported by the pair style's count).
    if (comm->procgrid[d] == 1 && !domain->periodicity[d]) continue;
    const double width = (domain->triclinic ? domain->subhi_lamda[d] - domain->sublo_lamda[d]
                                            : (domain->subhi[d] - domain->sublo[d]) / prd[d]) * prd[d];
    limit = MIN(limit, comm->procgrid[d] > 1 ? width : 0.5 * prd[d]);
  }
  return limit;
}

std::string FixVertexGuard::describe(int i, double moved, double size) const
{
  tagint j = 0;
  double d = -1.0;
  if (static_cast<int>(x0.size()) == 2 * atom->nlocal) pair->closest_neighbour(i, x0.data(), j, d);
  return fmt::format(
      "atom {} moved by {:.3g} in the step from {} to {}, more than a cell diameter sqrt(A0) = "
      "{:.3g}: the timestep does not resolve the forces of step {} (its closest Voronoi "
      "neighbour then, atom {}, was {:.3g} away; Voronoi forces grow as 1/distance when two "
      "centres nearly collide)",
      atom->tag[i], moved, step0, update->ntimestep, size, step0, j, d);
}

void FixVertexGuard::post_integrate()
{
  if (!pair) return;
  const int n = atom->nlocal;
  // Atoms added or re-ordered without a force computation (run N pre no):
  // nothing to compare on this rank, but it still takes part below.
  bool valid = static_cast<int>(tag0.size()) == n;
  for (int i = 0; valid && i < n; i++) valid = atom->tag[i] == tag0[i];
  double **x = atom->x;
  const int *type = atom->type;
  const double lost = loss_limit();
  // Squared distances against squared limits (one sqrt per type, not per atom).
  const int ntypes = atom->ntypes;
  size2.resize(ntypes + 1);
  for (int t = 1; t <= ntypes; t++) size2[t] = pair->cell_size(t) * pair->cell_size(t);
  const double lost2 = lost < std::sqrt(std::numeric_limits<double>::max()) ? lost * lost
                                                                            : std::numeric_limits<double>::max();
  int worst = -1;
  double worst_moved2 = 0.0;
  for (int i = 0; valid && i < n; i++) {
    const double dx = x[i][0] - x0[2 * i], dy = x[i][1] - x0[2 * i + 1];
    const double moved2 = dx * dx + dy * dy;
    if (!(moved2 <= lost2)) {    // also NaN
      const double moved = std::sqrt(moved2);
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

PairVertexVoronoi::PairVertexVoronoi(LAMMPS *lmp) : Pair(lmp)
{
  single_enable = 0;
  restartinfo = 1;
  one_coeff = 0;
  manybody_flag = 1;
  centroidstressflag = CENTROID_NOTAVAIL;

  cut_global = 0.0;
  tension = tessera::Tension::Edge;
  kappa = area0 = gamma = nullptr;
  lambda = nullptr;
  lambda_set = nullptr;
  type_set = nullptr;
  lambda_extra = adapt_kappa = adapt_area0 = adapt_gamma = lambda_built = nullptr;
  close_i = close_j = 0;
  close_d = -1.0;
  close_step = -1;
  tess_step = -1;
  incremental = 1;
  mesh_ncalls = -1;
  nextra = 8;
  reference_every = 0;
  grow = 1;
  cutghost_saved = -1.0;
  guard_id = std::string("VERTEX_VORONOI_GUARD_") + std::to_string(instance_me);
  radius = 0.0;
  free_tension = nullptr;
  free_set = 0;
  pvector = stats;
  for (double &v : stats) v = 0.0;
}

PairVertexVoronoi::~PairVertexVoronoi()
{
  if (cutghost_saved >= 0.0) comm->cutghostuser = cutghost_saved;
  if (modify && modify->find_fix(guard_id) >= 0) modify->delete_fix(guard_id);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(kappa);
    memory->destroy(area0);
    memory->destroy(gamma);
    memory->destroy(lambda);
    memory->destroy(lambda_set);
    memory->destroy(type_set);
    memory->destroy(lambda_extra);
    memory->destroy(adapt_kappa);
    memory->destroy(adapt_area0);
    memory->destroy(adapt_gamma);
    memory->destroy(lambda_built);
    memory->destroy(free_tension);
  }
}

void PairVertexVoronoi::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  memory->create(kappa, n + 1, "pair:kappa");
  memory->create(area0, n + 1, "pair:area0");
  memory->create(gamma, n + 1, "pair:gamma");
  memory->create(lambda, n + 1, n + 1, "pair:lambda");
  memory->create(lambda_set, n + 1, n + 1, "pair:lambda_set");
  memory->create(type_set, n + 1, "pair:type_set");
  memory->create(lambda_extra, n + 1, n + 1, "pair:lambda_extra");
  memory->create(adapt_kappa, n + 1, n + 1, "pair:adapt_kappa");
  memory->create(adapt_area0, n + 1, n + 1, "pair:adapt_area0");
  memory->create(adapt_gamma, n + 1, n + 1, "pair:adapt_gamma");
  memory->create(lambda_built, n + 1, n + 1, "pair:lambda_built");
  memory->create(free_tension, n + 1, "pair:free_tension");
  for (int i = 0; i <= n; i++) {
    kappa[i] = area0[i] = gamma[i] = 0.0;
    free_tension[i] = 0.0;
    type_set[i] = 0;
    for (int j = 0; j <= n; j++) {
      setflag[i][j] = 0;
      lambda[i][j] = 0.0;
      lambda_set[i][j] = 0;
      cutsq[i][j] = 0.0;
      lambda_extra[i][j] = adapt_kappa[i][j] = adapt_area0[i][j] = adapt_gamma[i][j] = 0.0;
      lambda_built[i][j] = 0.0;
    }
  }
}

/* ----------------------------------------------------------------------
   pair_style vertex/voronoi cutoff [tension edge|cell]
------------------------------------------------------------------------- */

void PairVertexVoronoi::settings(int narg, char **arg)
{
  if (narg < 1)
    error->all(FLERR,
               "Illegal pair_style vertex/voronoi command: expected 'pair_style vertex/voronoi "
               "cutoff [tension edge|cell]'");
  cut_global = utils::numeric(FLERR, arg[0], false, lmp);
  if (!(cut_global > 0.0))
    error->all(FLERR,
               "pair_style vertex/voronoi: cutoff must be > 0, got {}; use about 2.5 to 3 "
               "cell diameters",
               arg[0]);
  int iarg = 1;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "tension") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "pair_style vertex/voronoi: keyword 'tension' needs a value (edge or cell)");
      if (strcmp(arg[iarg + 1], "edge") == 0)
        tension = tessera::Tension::Edge;
      else if (strcmp(arg[iarg + 1], "cell") == 0)
        tension = tessera::Tension::Cell;
      else
        error->all(FLERR,
                   "pair_style vertex/voronoi: tension must be 'edge' (each junction once, "
                   "default) or 'cell' (Lambda*P per cell, as the thesis code), got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "incremental") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "pair_style vertex/voronoi: keyword 'incremental' needs a value (yes or no)");
      if (strcmp(arg[iarg + 1], "yes") == 0)
        incremental = 1;
      else if (strcmp(arg[iarg + 1], "no") == 0)
        incremental = 0;
      else if (strcmp(arg[iarg + 1], "check") == 0)
        incremental = 2;
      else
        error->all(FLERR,
                   "pair_style vertex/voronoi: incremental must be yes, no or check, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "grow") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "pair_style vertex/voronoi: keyword 'grow' needs a value (yes or no)");
      if (strcmp(arg[iarg + 1], "yes") == 0)
        grow = 1;
      else if (strcmp(arg[iarg + 1], "no") == 0)
        grow = 0;
      else
        error->all(FLERR, "pair_style vertex/voronoi: grow must be yes or no, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "reference") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "pair_style vertex/voronoi: keyword 'reference' needs a value N");
      reference_every = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (reference_every < 0)
        error->all(FLERR, "pair_style vertex/voronoi: reference N must be >= 0, got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "radius") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "pair_style vertex/voronoi: keyword 'radius' needs a value r (the "
                          "radius of the finite Voronoi cells)");
      radius = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(radius > 0.0) || !std::isfinite(radius))
        error->all(FLERR, "pair_style vertex/voronoi: radius must be > 0, got {}", arg[iarg + 1]);
      iarg += 2;
    } else {
      error->all(FLERR,
                 "pair_style vertex/voronoi: unknown keyword '{}' (known: tension, incremental, "
                 "grow, reference, radius)",
                 arg[iarg]);
    }
  }
  // Allocating now lets a missing pair_coeff be reported by type in init_style
  // rather than by LAMMPS's generic "All pair coeffs are not set".
  if (!allocated && atom->ntypes > 0) {
    allocate();
    for (int i = 1; i <= atom->ntypes; i++) setflag[i][i] = 1;
  }
}

/* ----------------------------------------------------------------------
   pair_coeff I I K A0 Gamma Lambda
   pair_coeff I I quadratic KA A0 KP P0
   pair_coeff I J Lambda           (I != J: junction tension between types)
------------------------------------------------------------------------- */

void PairVertexVoronoi::coeff(int narg, char **arg)
{
  if (!allocated) {
    allocate();
    for (int i = 1; i <= atom->ntypes; i++) setflag[i][i] = 1;
  }
  if (narg < 3)
    error->all(FLERR,
               "pair_coeff for vertex/voronoi: expected 'pair_coeff I I K A0 Gamma Lambda', "
               "'pair_coeff I I quadratic KA A0 KP P0' or 'pair_coeff I J Lambda'");

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  const bool same = (ilo == jlo && ihi == jhi);
  const std::string where = fmt::format("pair_coeff {} {}", arg[0], arg[1]);

  // Trailing 'free F': the tension of the free (cell-medium) arcs of finite
  // Voronoi cells.
  bool has_free = false;
  double free_value = 0.0;
  if (narg >= 5 && strcmp(arg[narg - 2], "free") == 0) {
    has_free = true;
    free_value = utils::numeric(FLERR, arg[narg - 1], false, lmp);
    if (!std::isfinite(free_value))
      error->all(FLERR, "{}: free tension must be finite, got {}", where, arg[narg - 1]);
    narg -= 2;
  }

  // pair_coeff I J Lambda_IJ, or pair_coeff I J quadratic sigma: the extra
  // tension sigma of a heterotypic junction on top of the default mean
  // (energy sigma * l per junction, in either tension convention).
  const bool het_quadratic = narg == 4 && strcmp(arg[2], "quadratic") == 0;
  if (narg == 3 || het_quadratic) {
    const char *value = arg[narg - 1];
    const double lam = utils::numeric(FLERR, value, false, lmp);
    if (!std::isfinite(lam))
      error->all(FLERR, "{}: {} must be finite, got {}", where,
                 het_quadratic ? "the heterotypic tension sigma" : "Lambda", value);
    const int how = het_quadratic ? 2 : 1;
    int count = 0;
    auto set = [&](int i, int j) {
      lambda_set[i][j] = lambda_set[j][i] = how;
      if (how == 1) {
        lambda[i][j] = lambda[j][i] = lam;
      } else {
        lambda_extra[i][j] = lambda_extra[j][i] = lam;
      }
      count++;
    };
    for (int i = ilo; i <= ihi; i++)
      for (int j = MAX(jlo, i + 1); j <= jhi; j++) set(i, j);
    for (int i = jlo; i <= jhi; i++)
      for (int j = MAX(ilo, i + 1); j <= ihi; j++) set(i, j);
    if (has_free)
      error->all(FLERR,
                 "{}: 'free' is a per-type tension: give it with the cell parameters "
                 "(pair_coeff I I ... free F)",
                 where);
    if (count == 0 && het_quadratic)
      error->all(FLERR,
                 "{}: 'quadratic sigma' with one value sets the extra tension between two "
                 "different types; for type I's own cells use 'pair_coeff I I quadratic KA A0 KP "
                 "P0'",
                 where);
    if (count == 0)
      error->all(FLERR,
                 "{}: a single value sets Lambda between two different types; for type I's own "
                 "cells use 'pair_coeff I I K A0 Gamma Lambda'",
                 where);
    return;
  }

  if (!same)
    error->all(FLERR,
               "{}: cell parameters need the same type twice (pair_coeff I I K A0 Gamma "
               "Lambda); between different types give only Lambda (pair_coeff I J Lambda)",
               where);

  double K, A0, G, lam, ftension = free_value;
  if (strcmp(arg[2], "quadratic") == 0) {
    if (narg != 7)
      error->all(FLERR, "{}: expected 'pair_coeff I I quadratic KA A0 KP P0 [free Lambda]'",
                 where);
    tessera::QuadraticParams q;
    q.KA = utils::numeric(FLERR, arg[3], false, lmp);
    q.A0 = utils::numeric(FLERR, arg[4], false, lmp);
    q.KP = utils::numeric(FLERR, arg[5], false, lmp);
    q.P0 = utils::numeric(FLERR, arg[6], false, lmp);
    if (!(q.KA > 0.0)) error->all(FLERR, "{}: KA must be > 0, got {}", where, arg[3]);
    if (!(q.KP >= 0.0)) error->all(FLERR, "{}: KP must be >= 0, got {}", where, arg[5]);
    const tessera::CellType ct = tessera::cell_type_from_quadratic(q);
    K = ct.K;
    A0 = ct.A0;
    G = ct.Gamma;
    lam = tessera::lambda_from_quadratic(q, tension);
    // KP (P - P0)^2 + Lambda L: the arcs carry -2 KP P0 per length besides Lambda.
    ftension = free_value - 2.0 * q.KP * q.P0;
  } else {
    if (narg != 6)
      error->all(FLERR,
                 "{}: expected 4 values K A0 Gamma Lambda (the thesis's order kappa, A0, Gamma, "
                 "Lambda), got {}",
                 where, narg - 2);
    K = utils::numeric(FLERR, arg[2], false, lmp);
    A0 = utils::numeric(FLERR, arg[3], false, lmp);
    G = utils::numeric(FLERR, arg[4], false, lmp);
    lam = utils::numeric(FLERR, arg[5], false, lmp);
    if (!(K > 0.0) || !std::isfinite(K))
      error->all(FLERR, "{}: area modulus K must be > 0, got {}", where, arg[2]);
    if (!std::isfinite(G)) error->all(FLERR, "{}: Gamma must be finite, got {}", where, arg[4]);
    if (!std::isfinite(lam)) error->all(FLERR, "{}: Lambda must be finite, got {}", where, arg[5]);
  }
  if (!(A0 > 0.0) || !std::isfinite(A0))
    error->all(FLERR, "{}: preferred area A0 must be > 0, got {}", where, A0);

  for (int i = ilo; i <= ihi; i++) {
    kappa[i] = K;
    area0[i] = A0;
    gamma[i] = G;
    lambda[i][i] = lam;
    lambda_set[i][i] = 1;
    type_set[i] = 1;
    setflag[i][i] = 1;
    free_tension[i] = ftension;
  }
  if (has_free) free_set = 1;
}

void PairVertexVoronoi::init_style()
{
  if (domain->dimension == 3) init_style_3d();  // 3D cells: pair_vertex_voronoi_3d.cpp
  if (domain->dimension == 2 && radius == 0.0 && (!domain->xperiodic || !domain->yperiodic))
    error->all(FLERR,
               "pair_style vertex/voronoi requires periodic x and y boundaries ('boundary p p "
               "p'); a confluent tissue has no free edge in this model (for tissue edges use "
               "finite cells: 'pair_style vertex/voronoi cutoff radius r')");
  if (radius > 0.0 && cut_global < 2.0 * radius)
    error->all(FLERR,
               "pair_style vertex/voronoi: cutoff {} is smaller than twice the radius {} of "
               "the finite cells (cells up to 2r apart touch); use 'pair_style vertex/voronoi "
               "{} radius {}'",
               cut_global, radius, 2.0 * radius, radius);
  if (radius == 0.0 && free_set && comm->me == 0)
    error->warning(FLERR,
                   "pair_style vertex/voronoi: 'free' tensions are ignored without 'radius r' "
                   "(confluent cells have no free arcs)");
  if (force->newton_pair == 0)
    error->all(FLERR, "pair_style vertex/voronoi requires 'newton on' (forces go to ghost atoms)");
  if (atom->tag_enable == 0) error->all(FLERR, "pair_style vertex/voronoi requires atom IDs");

  for (int i = 1; i <= atom->ntypes; i++)
    if (!type_set[i])
      error->all(FLERR,
                 "pair_style vertex/voronoi: no cell parameters for atom type {}; add "
                 "'pair_coeff {} {} K A0 Gamma Lambda'",
                 i, i, i);

  // The ghost shell is complete only if atoms have moved less than half the
  // skin since the last rebuild, which needs a distance check every step.
  // LAMMPS's default delay of 10 steps is lifted silently; settings that skip
  // the check altogether are overridden with a warning.
  if (neighbor->every != 1 || neighbor->dist_check == 0) {
    if (comm->me == 0)
      error->warning(FLERR,
                     "pair_style vertex/voronoi: setting 'neigh_modify every 1 delay 0 check "
                     "yes' so that the ghost shell stays complete");
    neighbor->every = 1;
    neighbor->dist_check = 1;
  }
  neighbor->delay = 0;

  build_model();
  print_model();
  // The step guard (see FixVertexGuard), added once; internal, not in the style table.
  if (modify->fix_map->find(GUARD_STYLE) == modify->fix_map->end())
    (*modify->fix_map)[GUARD_STYLE] = &create_guard;
  if (modify->find_fix(guard_id) < 0) modify->add_fix(guard_id + " all " + GUARD_STYLE);
  auto guard = dynamic_cast<FixVertexGuard *>(modify->fix[modify->find_fix(guard_id)]);
  if (guard) guard->pair = this;
  // No neighbor list is requested: the tessellation needs only the ghost atoms.
  for (double &v : stats) v = 0.0;
  close_d = -1.0;
}

/* The core's model from the per-type values and the junction tensions:
   Lambda_IJ given (lambda_set 1), the mean of the two same-type values
   (0), or that mean plus the heterotypic sigma (2).  Fills the type-pair
   arrays that extract() gives fix adapt with the values in use, so that
   reinit() can tell what fix adapt changed. */

void PairVertexVoronoi::build_model()
{
  const int n = atom->ntypes;
  model = tessera::Model(n);
  model.tension = tension;
  for (int i = 1; i <= n; i++) model.types[i - 1] = tessera::CellType{kappa[i], area0[i], gamma[i]};
  // sigma is the energy per junction length; Tension::Cell counts Lambda_IJ twice.
  const double per_junction = tension == tessera::Tension::Edge ? 1.0 : 0.5;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      double lam = lambda[i][j];
      if (i != j && lambda_set[i][j] != 1) {
        lam = 0.5 * (lambda[i][i] + lambda[j][j]);
        if (lambda_set[i][j] == 2) lam += per_junction * lambda_extra[i][j];
      }
      model.set_lambda(i - 1, j - 1, lam);
      lambda[i][j] = lambda[j][i] = lam;
      lambda_built[i][j] = lambda_built[j][i] = lam;
    }
  for (int i = 1; i <= n; i++)
    for (int j = 1; j <= n; j++) {
      const int t = i <= j ? i : j;
      adapt_kappa[i][j] = kappa[t];
      adapt_area0[i][j] = area0[t];
      adapt_gamma[i][j] = gamma[t];
    }
  free_t0.assign(n, 0.0);
  for (int i = 1; i <= n; i++) free_t0[i - 1] = free_tension[i];
  try {
    model.validate();
  } catch (tessera::Error &e) {
    error->all(FLERR, "pair_style vertex/voronoi: {}", e.what());
  }
}

/* The per-type parameters and the effective junction tension matrix, in
   the model's reduced units, once per run. */

void PairVertexVoronoi::print_model() const
{
  if (comm->me != 0) return;
  const int n = atom->ntypes;
  static const char *inc_name[] = {"no", "yes", "check"};
  std::string msg = fmt::format(
      "pair_style vertex/voronoi: cutoff {:.6g} tension {} incremental {} grow {} reference {}\n",
      cut_global, tension == tessera::Tension::Edge ? "edge" : "cell", inc_name[incremental],
      grow ? "yes" : "no", reference_every);
  msg += fmt::format(
      "  junction energy = {} Lambda_IJ * length; reduced units: length sqrt(A0), "
      "energy K A0^2\n"
      "  type          K         A0      Gamma     Lambda_II         p0\n",
      tension == tessera::Tension::Edge ? "1 x" : "2 x");
  const double c = tension == tessera::Tension::Edge ? 2.0 : 1.0;
  for (int i = 1; i <= n; i++) {
    const double lam = model.lambda_of(i - 1, i - 1);
    const double p0 = gamma[i] != 0.0 ? -lam / (c * gamma[i] * std::sqrt(area0[i])) : 0.0;
    msg += fmt::format("  {:4d} {:10.4g} {:10.4g} {:10.4g} {:13.4g} {:>10}\n", i, kappa[i],
                       area0[i], gamma[i], lam, gamma[i] != 0.0 ? fmt::format("{:.4g}", p0) : "-");
  }
  msg += "  effective junction tension Lambda_IJ:\n      ";
  for (int j = 1; j <= n; j++) msg += fmt::format(" {:>10d}", j);
  msg += "\n";
  for (int i = 1; i <= n; i++) {
    msg += fmt::format("  {:4d}", i);
    for (int j = 1; j <= n; j++) msg += fmt::format(" {:10.4g}", model.lambda_of(i - 1, j - 1));
    msg += "\n";
  }
  utils::logmesg(lmp, msg);
}

/* fix adapt changed the arrays of extract(): take the per-type values from
   the diagonal, mark junction tensions it changed as given, and rebuild the
   model for the next force computation. */

void PairVertexVoronoi::reinit()
{
  Pair::reinit();
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++) {
    if (!(adapt_kappa[i][i] > 0.0) || !std::isfinite(adapt_kappa[i][i]))
      error->all(FLERR, "pair_style vertex/voronoi (fix adapt): kappa of type {} must be > 0, got {}",
                 i, adapt_kappa[i][i]);
    if (!(adapt_area0[i][i] > 0.0) || !std::isfinite(adapt_area0[i][i]))
      error->all(FLERR, "pair_style vertex/voronoi (fix adapt): area0 of type {} must be > 0, got {}",
                 i, adapt_area0[i][i]);
    kappa[i] = adapt_kappa[i][i];
    area0[i] = adapt_area0[i][i];
    gamma[i] = adapt_gamma[i][i];
  }
  // fix adapt writes the upper triangle (j >= i).
  for (int i = 1; i <= n; i++)
    for (int j = i + 1; j <= n; j++)
      if (lambda[i][j] != lambda_built[i][j]) {
        lambda_set[i][j] = lambda_set[j][i] = 1;
        lambda[j][i] = lambda[i][j];
      }
  build_model();
}

double PairVertexVoronoi::init_one(int i, int j)
{
  if (setflag[i][j] == 0) setflag[i][j] = 1;
  return cut_global;
}

/* Width of the region around this rank's sub-domain in which every atom is
   known: the ghost cutoff less half the skin that atoms may have moved since
   the last neighbor list build. */

double PairVertexVoronoi::ghost_width() const
{
  return MAX(neighbor->cutneighmax, comm->cutghostuser) - 0.5 * neighbor->skin;
}

/* This rank's sub-domain as a parallelogram in box coordinates (a rectangle
   for orthogonal boxes; tilted sides for triclinic ones, whose ghost shell
   is bounded by planes parallel to the sides). */

tessera::Region PairVertexVoronoi::subdomain() const
{
  if (!domain->triclinic) return tessera::Region::rect(domain->sublo, domain->subhi);
  double lo[3] = {domain->sublo_lamda[0], domain->sublo_lamda[1], 0.0};
  double corner[3];
  domain->lamda2x(lo, corner);
  tessera::Region r;
  r.o[0] = corner[0];
  r.o[1] = corner[1];
  r.ax = (domain->subhi_lamda[0] - domain->sublo_lamda[0]) * domain->xprd;
  const double fy = domain->subhi_lamda[1] - domain->sublo_lamda[1];
  r.bx = fy * domain->xy;
  r.by = fy * domain->yprd;
  return r;
}

bool PairVertexVoronoi::tessellation_current() const
{
  return tess_step == update->ntimestep && tess.n_owned == atom->nlocal;
}

/* Triangulation of owned + ghost atoms.  Between neighbor list builds the
   atoms keep their local indices, so the mesh of the previous step is
   updated by flips; after a rebuild (atoms exchanged, sorted, or a new
   run) it is triangulated from scratch. */

bool PairVertexVoronoi::tessellate()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  tessera::Points pts{&atom->x[0][0], nall, 3};
  const double w = ghost_width();
  const tessera::Region sub = subdomain();
  // The updated mesh is certified inside a smaller region: thin triangles on
  // the hull of the ghost shell fold over often, and outside this region
  // they are frozen rather than forcing a rebuild.  Owned cells' circumdisks
  // reach about one cell beyond the sub-domain, well inside it.
  const double wi = 0.6 * w;
  double lo_inc[2], hi_inc[2];
  sub.bounding_box(wi, lo_inc, hi_inc);

  // A rank that owns no cell has nothing to compute (its ghosts are other
  // ranks' cells); it only takes part in the collective check below.
  if (nlocal == 0) {
    tess = tessera::Tessellation();
    tess.n_points = nall;
    tess.cell_offset.assign(1, 0);
    mesh_ncalls = -1;    // triangulate from scratch when cells arrive
  }

  bool fresh = false;
  auto build = [&]() {
    // The cells are read afresh after a rebuild: their arrays go first, so
    // that they and CGAL's triangulation never hold memory at the same time
    // (the peak memory per cell is a rebuild's).
    tess = tessera::Tessellation();
    try {
      mesh.build(pts);
    } catch (tessera::Error &) {
      // Redo with atom IDs so that the message names them.
      std::vector<long> ids(nall);
      for (int i = 0; i < nall; i++) ids[i] = atom->tag[i];
      try {
        mesh.build(pts, ids.data());
      } catch (tessera::Error &e) {
        error->one(FLERR,
                   "pair_style vertex/voronoi at step {}: {} (during a run two centres come "
                   "this close when the timestep does not resolve their forces: use a smaller "
                   "timestep, 'fix dt/reset' or fix brownian/heun)",
                   update->ntimestep, e.what());
      }
      error->one(FLERR, "pair_style vertex/voronoi: tessellation failed");
    }
    mesh_ncalls = neighbor->ncalls;
    fresh = true;
    stats[2] += 1.0;
  };
  // Between rebuilds Mesh::advance() updates the mesh by flips and reads the
  // cells in one go (the same cells as update() + cells(), faster).
  bool have_cells = false;
  if (nlocal == 0)
    ;
  else if (!incremental || mesh_ncalls != neighbor->ncalls || !mesh.valid() || mesh.n_points() != nall)
    build();
  else if (mesh.advance(pts, nlocal, lo_inc, hi_inc, tess, fuse_cells ? &cell_pass : nullptr)) {
    stats[3] += mesh.flips_last_update();
    have_cells = true;
  } else
    build();
  if (nlocal > 0 && !have_cells) mesh.cells(pts, nlocal, tess);

  tessera::Coverage cov;  // ok unless checked below
  if (nlocal > 0 && !fresh && !tessera::check_coverage(tess, sub, wi).ok) {
    // A cell reaches past the region where the updated mesh is certified:
    // triangulate from scratch, then check against the full ghost shell.
    build();
    mesh.cells(pts, nlocal, tess);
  }
  if (incremental == 2 && !fresh && nlocal > 0) check_against_scratch(pts, sub, w);
  // An updated mesh that passed the smaller region passes the full one.
  if (fresh) cov = tessera::check_coverage(tess, sub, w);
  double need = cov.needed_margin, need_all;
  MPI_Allreduce(&need, &need_all, 1, MPI_DOUBLE, MPI_MAX, world);
  if (need_all > 0.0) {
    const bool infinite = std::isinf(need_all);
    const double needed = infinite ? 2.0 * cut_global : 1.1 * (cut_global + need_all);
    if (grow && force->pair == this &&
        needed <= 2.0 * MAX(domain->xprd, domain->yprd) + cut_global) {
      grow_ghost_shell(MAX(needed, 1.2 * cut_global));
      return true;
    }
    if (infinite)
      error->all(FLERR,
                 "pair_style vertex/voronoi: cutoff {} is far too small: some cells have no "
                 "complete ring of neighbours; use a cutoff of at least 2.5 cell diameters",
                 cut_global);
    error->all(FLERR,
               "pair_style vertex/voronoi: cutoff {:.6g} is too small for this configuration "
               "(a Voronoi vertex's circumcircle reaches past the ghost atoms); use "
               "'pair_style vertex/voronoi {:.3g}' or larger",
               cut_global, needed);
  }
  tess_step = update->ntimestep;
  return false;
}

/* The ghost shell was too thin: widen it to cut and acquire the ghost atoms
   again now, with the steps of a neighbor-list build (remap into the box,
   exchange, borders, the fixes' neighbor hooks, the distance-check
   reference), so that this step's forces are computed with complete cells.
   The pair style computes the first forces of a step, so the force array
   only needs clearing for the new set of atoms. */

void PairVertexVoronoi::grow_ghost_shell(double cut)
{
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "pair_style vertex/voronoi: cutoff grown from {:.4g} to {:.4g} at step {} (a "
                   "cell needed a wider ghost shell)\n",
                   cut_global, cut, update->ntimestep);
  cut_global = cut;
  cutforce = cut;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = 1; j <= atom->ntypes; j++) cutsq[i][j] = cut * cut;
  if (cutghost_saved < 0.0) cutghost_saved = comm->cutghostuser;
  comm->cutghostuser = MAX(comm->cutghostuser, cut + neighbor->skin);
  if (domain->triclinic) domain->x2lamda(atom->nlocal);
  domain->pbc();
  comm->setup();
  comm->exchange();
  comm->borders();
  if (domain->triclinic) domain->lamda2x(atom->nlocal + atom->nghost);
  if (modify->n_pre_neighbor) modify->pre_neighbor();
  neighbor->build(1);
  if (modify->n_post_neighbor) modify->post_neighbor();
  const int nall = atom->nlocal + atom->nghost;
  double **f = atom->f;
  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  if (atom->torque_flag)
    for (int i = 0; i < nall; i++) atom->torque[i][0] = atom->torque[i][1] = atom->torque[i][2] = 0.0;
}

/* incremental check: the updated mesh's cells against a from-scratch
   triangulation of the same atoms.  Every Voronoi neighbour across an edge
   longer than a round-off threshold must be found by both; areas and
   perimeters must agree.  For tests of the incremental path. */

void PairVertexVoronoi::check_against_scratch(const tessera::Points &pts,
                                              const tessera::Region &sub, double w)
{
  tessera::Mesh scratch;
  scratch.build(pts);
  tessera::Tessellation ref;
  scratch.cells(pts, tess.n_owned, ref);
  if (!tessera::check_coverage(ref, sub, w).ok) return;    // the shell grows or the run stops
  for (int c = 0; c < tess.n_owned; c++) {
    auto strong = [](const tessera::Tessellation &t, int cell) {
      std::vector<int> nb;
      for (int k = t.cell_offset[cell]; k < t.cell_offset[cell + 1]; k++)
        if (t.edge_length[k] > 1e-8 * t.radius[t.cell_vertex[k]]) nb.push_back(t.cell_neighbor[k]);
      std::sort(nb.begin(), nb.end());
      return nb;
    };
    const double scale = std::sqrt(std::fabs(ref.area[c])) + 1.0;
    if (strong(tess, c) != strong(ref, c) || std::fabs(tess.area[c] - ref.area[c]) > 1e-9 * scale * scale ||
        std::fabs(tess.perimeter[c] - ref.perimeter[c]) > 1e-9 * scale)
      error->one(FLERR,
                 "pair_style vertex/voronoi incremental check: the cell of atom {} differs from a "
                 "from-scratch triangulation at step {} (area {} vs {}, perimeter {} vs {})",
                 atom->tag[c], update->ntimestep, tess.area[c], ref.area[c], tess.perimeter[c],
                 ref.perimeter[c]);
  }
}

void PairVertexVoronoi::compute(int eflag, int vflag)
{
  ncompute++;
  if (domain->dimension == 3) {
    compute_3d(eflag, vflag);    // pair_vertex_voronoi_3d.cpp
    return;
  }
  ev_init(eflag, vflag);
  check_lost_atoms();
  if (radius > 0.0) {
    compute_finite();
    return;
  }

  const double t0 = MPI_Wtime();
  // Types and preferred areas of this step's atoms, for the forces' per-cell
  // half, which Mesh::advance runs while it reads the cells (tessera::CellPass;
  // without per-atom virials, which need the general loop).  Its time counts
  // as tessellation in the statistics (values 1 and 2).
  auto prepare = [&]() {
    const int nall = atom->nlocal + atom->nghost;
    type0.resize(nall);
    const int *type = atom->type;
    for (int i = 0; i < nall; i++) type0[i] = type[i] - 1;
    cell_e.resize(atom->nlocal);
    bind_cell_area0();
    cell_pass.set(tessera::Points{&atom->x[0][0], nall, 3}, type0.data(), model, cell_e.data());
  };
  prepare();
  fuse_cells = !vflag_atom;
  // Each pass that widens the ghost shell re-acquires the atoms; then the
  // energy/virial accumulators are set up again for the new atom count.
  for (int pass = 0; tessellate(); pass++) {
    if (pass == 8) error->all(FLERR, "pair_style vertex/voronoi: the ghost shell did not converge");
    ev_init(eflag, vflag);
    prepare();
  }
  fuse_cells = false;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const double t1 = MPI_Wtime();

  tessera::Points pts{&atom->x[0][0], nall, 3};
  // Per-atom virial (compute stress/atom): each cell's own energy term's
  // virial, assigned to its atom; the cells' virials add up to the total.
  if (vflag_atom) cell_w.resize(4 * static_cast<size_t>(nlocal));
  tessera::ForceOutput out;
  try {
    // The global virial comes from LAMMPS's f dot r (virial_fdotr_compute).
    out = tessera::compute_forces(tess, pts, type0.data(), model, &atom->f[0][0], 3, cell_e.data(),
                                  vflag_atom ? cell_w.data() : nullptr, false, &cell_pass);
  } catch (tessera::Error &e) {
    // Energy or virial overflow (parameters or lengths far outside the
    // model's reduced units); the core names the local point.
    error->one(FLERR, "pair_style vertex/voronoi at step {}: {}", update->ntimestep, e.what());
  }
  if (vflag_atom)
    for (int i = 0; i < nlocal; i++) {
      vatom[i][0] += cell_w[4 * i];
      vatom[i][1] += cell_w[4 * i + 1];
      vatom[i][3] += 0.5 * (cell_w[4 * i + 2] + cell_w[4 * i + 3]);
    }

  // The closest pair of Voronoi neighbours, for the message of lost atoms
  // (compute_forces finds it on the way).
  note_closest_pair(out.closest_cell, out.closest_neighbor, out.closest_distance2);
  stats[0] += t1 - t0;
  stats[1] += MPI_Wtime() - t1;
  stats[4] += 1.0;
  if (reference_every > 0 && update->ntimestep % reference_every == 0) {
    // A from-scratch CGAL triangulation of the same points, timed for
    // benchmarks (bench/): the yardstick of the incremental mesh.
    {
      const double r0 = MPI_Wtime();
      tessera::Mesh scratch;
      scratch.build(pts);
      stats[5] += MPI_Wtime() - r0;
      stats[6] += 1.0;
    }
    // And the plain yardstick: CGAL's own Delaunay triangulation of the
    // owned points alone (no ghosts, no flat arrays), timed inside the core
    // after the scratch mesh is freed (the two never coexist in memory).
    stats[7] += tessera::time_plain_delaunay(pts, nlocal);
  }
  if (eflag_global) eng_vdwl += out.energy;
  if (eflag_atom)
    for (int i = 0; i < nlocal; i++) eatom[i] += cell_e[i];
  if (vflag_fdotr) virial_fdotr_compute();
}

/* Per-cell preferred areas from 'fix property/atom d_area0', when defined
   (otherwise the types' A0), for the confluent and the finite cells.  Only
   owned cells' values are read. */

void PairVertexVoronoi::bind_cell_area0()
{
  model.cell_area0 = nullptr;
  int a0_flag = -1, a0_cols = -1;
  const int a0_index = atom->find_custom("area0", a0_flag, a0_cols);
  if (a0_index < 0 || a0_flag != 1 || a0_cols != 0) return;
  const double *a0 = atom->dvector[a0_index];
  for (int i = 0; i < atom->nlocal; i++)
    if (!(a0[i] > 0.0) || !std::isfinite(a0[i]))
      error->one(FLERR,
                 "pair_style vertex/voronoi: per-atom preferred area d_area0 of atom {} is {}; "
                 "it must be > 0 (e.g. 'set group all d_area0 1.0' after 'fix property/atom "
                 "d_area0')",
                 atom->tag[i], a0[i]);
  model.cell_area0 = a0;
}

/* Cell diameter sqrt(A0) of a type (1-based), the step guard's limit. */

double PairVertexVoronoi::cell_size(int type) const
{
  return std::sqrt(area0[type]);
}

/* The closest Voronoi neighbour of owned atom i in the last tessellation,
   at the positions of that force computation: owned atoms' from owned_xy
   (2 per atom, recorded then: the guard's copy), ghosts' from atom->x (not
   yet updated when the guard asks, between the move and the next forward
   communication). */

bool PairVertexVoronoi::closest_neighbour(int i, const double *owned_xy, tagint &j,
                                          double &d) const
{
  d = -1.0;
  const int nlocal = atom->nlocal;
  if (i < 0 || i >= tess.n_owned || tess.n_owned != nlocal ||
      tess.n_points != nlocal + atom->nghost || static_cast<int>(tess.cell_offset.size()) != nlocal + 1)
    return false;
  double **x = atom->x;
  for (int k = tess.cell_offset[i]; k < tess.cell_offset[i + 1]; k++) {
    const int q = tess.cell_neighbor[k];
    const double qx = q < nlocal ? owned_xy[2 * q] : x[q][0];
    const double qy = q < nlocal ? owned_xy[2 * q + 1] : x[q][1];
    const double dx = qx - owned_xy[2 * i], dy = qy - owned_xy[2 * i + 1];
    const double r = std::sqrt(dx * dx + dy * dy);
    if (d < 0.0 || r < d) {
      d = r;
      j = atom->tag[q];
    }
  }
  return d >= 0.0;
}

/* The closest pair of Voronoi neighbours among this rank's cells at this
   force computation, for the error message of lost atoms (IDs and distance
   are kept: they are read at the next step, after the atoms moved); the
   confluent path gets it from compute_forces, the finite one from here. */

void PairVertexVoronoi::note_closest_pair()
{
  // Squared distances and one sqrt at the end, straight from atom->x.
  double best = -1.0;
  int bi = -1, bq = -1;
  const int *off = tess.cell_offset.data();
  const int *nbr = tess.cell_neighbor.data();
  double **x = atom->x;
  for (int i = 0; i < tess.n_owned; i++) {
    const double xi = x[i][0], yi = x[i][1];
    for (int k = off[i]; k < off[i + 1]; k++) {
      const int q = nbr[k];
      const double dx = x[q][0] - xi, dy = x[q][1] - yi;
      const double r2 = dx * dx + dy * dy;
      if (best < 0.0 || r2 < best) {
        best = r2;
        bi = i;
        bq = q;
      }
    }
  }
  note_closest_pair(bi, bq, best);
}

/* Records owned atom i and atom q at squared distance d2 as this step's
   closest pair (i < 0: none). */

void PairVertexVoronoi::note_closest_pair(int i, int q, double d2)
{
  close_d = -1.0;
  if (i >= 0) {
    close_d = std::sqrt(d2);
    close_i = atom->tag[i];
    close_j = atom->tag[q];
  }
  close_step = update->ntimestep;
}

/* Atoms lost since the last step (moved out of the box or past a
   neighbouring rank in one step): say so before the tessellation of what is
   left fails, with the closest pair of the previous step. */

void PairVertexVoronoi::check_lost_atoms()
{
  bigint n = atom->nlocal, ntotal = 0;
  MPI_Allreduce(&n, &ntotal, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (ntotal == atom->natoms) return;
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
  const std::string closest =
      best.d < std::numeric_limits<double>::max()
          ? fmt::format("; at step {} the closest centres were atoms {} and {}, {:.3g} apart", when,
                        ids[0], ids[1], best.d)
          : std::string();
  error->all(FLERR,
             "pair_style vertex/voronoi: {} of {} atoms are left at step {}: the others were lost "
             "(moved out of the box, or past a neighbouring rank's domain in one step; during a "
             "run usually because the forces were too large for the timestep: two centres nearly "
             "colliding, or very stiff parameters){}. Use a smaller timestep, 'fix dt/reset', or "
             "fix brownian/heun",
             ntotal, atom->natoms, update->ntimestep, closest);
}

// The restart layout: settings, then per type and type pair.  Files of the
// first layout (cutoff and tension only) store tension as 0 or 1; later ones
// add RESTART_V2 to it and carry every keyword and the heterotypic sigma.
static constexpr int RESTART_V2 = 16;

/* Finite Voronoi cells: each owned cell is cut by every atom (owned or
   ghost) within 2r; the ghost shell (cutoff >= 2r) holds them all, so no
   triangulation and no coverage check are needed. */

void PairVertexVoronoi::compute_finite()
{
  const double t0 = MPI_Wtime();
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  tessera::Points pts{&atom->x[0][0], nall, 3};
  try {
    ftess = tessera::finite_tessellate(pts, nlocal, radius);
  } catch (tessera::Error &) {
    std::vector<long> ids(nall);
    for (int i = 0; i < nall; i++) ids[i] = atom->tag[i];
    try {
      ftess = tessera::finite_tessellate(pts, nlocal, radius, ids.data());
    } catch (tessera::Error &e) {
      error->one(FLERR, "pair_style vertex/voronoi: {}", e.what());
    }
  }
  tessera::finite_contacts(ftess, tess);
  tess_step = update->ntimestep;
  note_closest_pair();
  const double t1 = MPI_Wtime();

  type0.resize(nall);
  const int *type = atom->type;
  for (int i = 0; i < nall; i++) type0[i] = type[i] - 1;
  cell_e.resize(nlocal);
  bind_cell_area0();
  if (vflag_atom) cell_w.resize(4 * static_cast<size_t>(nlocal));
  const tessera::ForceOutput out = tessera::finite_forces(
      ftess, pts, type0.data(), model, free_t0.data(), &atom->f[0][0], 3, cell_e.data(),
      vflag_atom ? cell_w.data() : nullptr);
  if (vflag_atom)
    for (int i = 0; i < nlocal; i++) {
      vatom[i][0] += cell_w[4 * i];
      vatom[i][1] += cell_w[4 * i + 1];
      vatom[i][3] += 0.5 * (cell_w[4 * i + 2] + cell_w[4 * i + 3]);
    }
  stats[0] += t1 - t0;
  stats[1] += MPI_Wtime() - t1;
  stats[4] += 1.0;
  if (eflag_global) eng_vdwl += out.energy;
  if (eflag_atom)
    for (int i = 0; i < nlocal; i++) eatom[i] += cell_e[i];
  if (vflag_fdotr) virial_fdotr_compute();
}

void PairVertexVoronoi::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++) {
    fwrite(&type_set[i], sizeof(int), 1, fp);
    fwrite(&kappa[i], sizeof(double), 1, fp);
    fwrite(&area0[i], sizeof(double), 1, fp);
    fwrite(&gamma[i], sizeof(double), 1, fp);
    for (int j = 1; j <= n; j++) {
      fwrite(&lambda_set[i][j], sizeof(int), 1, fp);
      fwrite(&lambda[i][j], sizeof(double), 1, fp);
      fwrite(&lambda_extra[i][j], sizeof(double), 1, fp);
    }
  }
  for (int i = 1; i <= n; i++) fwrite(&free_tension[i], sizeof(double), 1, fp);
  fwrite(&free_set, sizeof(int), 1, fp);
}

void PairVertexVoronoi::read_restart(FILE *fp)
{
  const int version = read_restart_settings_version(fp);
  allocate();
  const int n = atom->ntypes;
  const int me = comm->me;
  for (int i = 1; i <= n; i++) {
    if (me == 0) {
      utils::sfread(FLERR, &type_set[i], sizeof(int), 1, fp, nullptr, error);
      utils::sfread(FLERR, &kappa[i], sizeof(double), 1, fp, nullptr, error);
      utils::sfread(FLERR, &area0[i], sizeof(double), 1, fp, nullptr, error);
      utils::sfread(FLERR, &gamma[i], sizeof(double), 1, fp, nullptr, error);
    }
    MPI_Bcast(&type_set[i], 1, MPI_INT, 0, world);
    MPI_Bcast(&kappa[i], 1, MPI_DOUBLE, 0, world);
    MPI_Bcast(&area0[i], 1, MPI_DOUBLE, 0, world);
    MPI_Bcast(&gamma[i], 1, MPI_DOUBLE, 0, world);
    setflag[i][i] = 1;
    for (int j = 1; j <= n; j++) {
      if (me == 0) {
        utils::sfread(FLERR, &lambda_set[i][j], sizeof(int), 1, fp, nullptr, error);
        utils::sfread(FLERR, &lambda[i][j], sizeof(double), 1, fp, nullptr, error);
      }
      if (me == 0 && version >= 2)
        utils::sfread(FLERR, &lambda_extra[i][j], sizeof(double), 1, fp, nullptr, error);
      MPI_Bcast(&lambda_set[i][j], 1, MPI_INT, 0, world);
      MPI_Bcast(&lambda[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&lambda_extra[i][j], 1, MPI_DOUBLE, 0, world);
    }
  }
  // Finite cells: the free tensions per type, after everything else (files
  // of the first layout have none).
  if (version < 2) return;
  for (int i = 1; i <= n; i++) {
    if (me == 0) utils::sfread(FLERR, &free_tension[i], sizeof(double), 1, fp, nullptr, error);
    MPI_Bcast(&free_tension[i], 1, MPI_DOUBLE, 0, world);
  }
  if (me == 0) utils::sfread(FLERR, &free_set, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&free_set, 1, MPI_INT, 0, world);
}

void PairVertexVoronoi::write_restart_settings(FILE *fp)
{
  int t = (tension == tessera::Tension::Edge ? 0 : 1) + RESTART_V2;
  fwrite(&cut_global, sizeof(double), 1, fp);
  fwrite(&t, sizeof(int), 1, fp);
  fwrite(&incremental, sizeof(int), 1, fp);
  fwrite(&grow, sizeof(int), 1, fp);
  fwrite(&reference_every, sizeof(int), 1, fp);
  fwrite(&radius, sizeof(double), 1, fp);
}

void PairVertexVoronoi::read_restart_settings(FILE *fp)
{
  read_restart_settings_version(fp);
}

int PairVertexVoronoi::read_restart_settings_version(FILE *fp)
{
  int t = 0;
  if (comm->me == 0) {
    utils::sfread(FLERR, &cut_global, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &t, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Bcast(&cut_global, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&t, 1, MPI_INT, 0, world);
  const int version = t >= RESTART_V2 ? 2 : 1;
  if (version >= 2) {
    t -= RESTART_V2;
    int v[3] = {incremental, grow, reference_every};
    if (comm->me == 0) utils::sfread(FLERR, v, sizeof(int), 3, fp, nullptr, error);
    MPI_Bcast(v, 3, MPI_INT, 0, world);
    incremental = v[0];
    grow = v[1];
    reference_every = v[2];
    if (comm->me == 0) utils::sfread(FLERR, &radius, sizeof(double), 1, fp, nullptr, error);
    MPI_Bcast(&radius, 1, MPI_DOUBLE, 0, world);
  }
  tension = t == 0 ? tessera::Tension::Edge : tessera::Tension::Cell;
  return version;
}

void *PairVertexVoronoi::extract(const char *str, int &dim)
{
  // Type-pair arrays, the form fix adapt needs; the per-type parameters are
  // read from the diagonal (I I) in reinit().
  dim = 2;
  if (strcmp(str, "kappa") == 0) return adapt_kappa;
  if (strcmp(str, "area0") == 0) return adapt_area0;
  if (strcmp(str, "gamma") == 0) return adapt_gamma;
  if (strcmp(str, "lambda") == 0) return lambda;
  return nullptr;
}

double PairVertexVoronoi::memory_usage()
{
  double bytes = Pair::memory_usage();
  bytes += (double) tess.triangles.capacity() * (3 * sizeof(int) + sizeof(tessera::Vec2) + sizeof(double));
  bytes += (double) tess.cell_vertex.capacity() * (2 * sizeof(int) + sizeof(double));
  bytes += (double) type0.capacity() * sizeof(int) + cell_e.capacity() * sizeof(double);
  return bytes;
}
