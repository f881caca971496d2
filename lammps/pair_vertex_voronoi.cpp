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

   pair_style vertex/voronoi, the face: settings, pair_coeff, the per-type
   table, fix adapt, the shared accumulation of energy and virial, and the
   choice of the model unit that computes the cells
   (pair_vertex_voronoi_confluent.cpp, _finite.cpp, _3d.cpp).  The ghost
   shell: pair_vertex_voronoi_ghost.cpp.  Restart files:
   pair_vertex_voronoi_restart.cpp.  The step guard:
   fix_vertex_guard.cpp, with the closest pairs and lost atoms it reports:
   pair_vertex_voronoi_closest.cpp.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"
#include "cell_source.h"

#include "fix_vertex_guard.h"
#include "pair_vertex_voronoi_3d.h"
#include "pair_vertex_voronoi_confluent.h"
#include "pair_vertex_voronoi_finite.h"
#include "pair_vertex_voronoi_sphere.h"
#include "tessera_citations.h"

#include "atom.h"
#include "citeme.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "output.h"
#include "thermo.h"
#include "update.h"
#include "tessera/subset_cells.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

using namespace LAMMPS_NS;

struct PairVertexVoronoi::Impl {
  tessera::Model model;
  tessera::SubsetCells subset;
};

PairVertexVoronoi::PairVertexVoronoi(LAMMPS *lmp) :
    Pair(lmp), impl(new Impl), model(impl->model), subset(impl->subset)
{
  if (lmp->citeme) lmp->citeme->add(tessera_cite::thesis);
  single_enable = 0;
  restartinfo = 1;
  one_coeff = 0;
  manybody_flag = 1;
  centroidstressflag = CENTROID_NOTAVAIL;

  cut_global = 0.0;
  keyword_defaults();
  kappa = area0 = gamma = nullptr;
  lambda = nullptr;
  lambda_set = nullptr;
  type_set = quad_set = nullptr;
  energy0 = nullptr;
  lambda_extra = adapt_kappa = adapt_area0 = adapt_gamma = lambda_built = nullptr;
  close_i = close_j = 0;
  close_d = -1.0;
  close_step = -1;
  tess_step = -1;
  nextra = 8;
  cutghost_saved = -1.0;
  guard_id = std::string("VERTEX_VORONOI_GUARD_") + std::to_string(instance_me);
  free_tension = nullptr;
  free_set = 0;
  pvector = stats;
  for (double &v : stats) v = 0.0;
}

PairVertexVoronoi::~PairVertexVoronoi()
{
  if (cutghost_saved >= 0.0) comm->cutghostuser = cutghost_saved;
  if (modify && modify->find_fix(guard_id) >= 0) modify->delete_fix(guard_id);
  if (modify && !sphere_fix_id.empty() && modify->find_fix(sphere_fix_id) >= 0)
    modify->delete_fix(sphere_fix_id);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(kappa);
    memory->destroy(area0);
    memory->destroy(gamma);
    memory->destroy(lambda);
    memory->destroy(lambda_set);
    memory->destroy(type_set);
    memory->destroy(quad_set);
    memory->destroy(energy0);
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
  memory->create(quad_set, n + 1, "pair:quad_set");
  memory->create(energy0, n + 1, "pair:energy0");
  memory->create(lambda_extra, n + 1, n + 1, "pair:lambda_extra");
  memory->create(adapt_kappa, n + 1, n + 1, "pair:adapt_kappa");
  memory->create(adapt_area0, n + 1, n + 1, "pair:adapt_area0");
  memory->create(adapt_gamma, n + 1, n + 1, "pair:adapt_gamma");
  memory->create(lambda_built, n + 1, n + 1, "pair:lambda_built");
  memory->create(free_tension, n + 1, "pair:free_tension");
  for (int i = 0; i <= n; i++) {
    kappa[i] = area0[i] = gamma[i] = 0.0;
    free_tension[i] = 0.0;
    type_set[i] = quad_set[i] = 0;
    energy0[i] = 0.0;
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

void PairVertexVoronoi::init_style()
{
  // The model's unit: 3D polyhedra, finite 2D cells ('radius') or confluent
  // 2D cells; kept across runs while the model stays the same.
  std::unique_ptr<VertexModel> want;
  // The global virial: f dot r, or under 'pair_modify nofdotr' the sum of the
  // cells' own virials (accumulate; the same total); the sphere's unit
  // always computes its own.
  no_virial_fdotr_compute = nofdotr_given;
  if (sphere_on)
    want = std::make_unique<VertexSphere>(lmp, this);
  else if (domain->dimension == 3)
    want = std::make_unique<Vertex3d>(lmp, this);
  else if (radius > 0.0)
    want = std::make_unique<VertexFinite>(lmp, this);
  else
    want = std::make_unique<VertexConfluent>(lmp, this);
  if (!unit || strcmp(unit->name(), want->name()) != 0) unit = std::move(want);
  unit->init();
  // The publication of the model in use.
  if (lmp->citeme)
    lmp->citeme->add(domain->dimension == 3 && !sphere_on ? tessera_cite::voronoi_3d
                         : radius > 0.0                   ? tessera_cite::voronoi_finite
                                                          : tessera_cite::voronoi_2d);
  if (radius == 0.0 && free_set && comm->me == 0)
    error->warning(FLERR,
                   "pair_style vertex/voronoi: 'free' tensions are ignored without 'radius r' "
                   "(confluent cells have no free arcs)");
  if (force->newton_pair == 0)
    error->all(FLERR, "pair_style vertex/voronoi requires 'newton on' (forces go to ghost atoms)");
  if (atom->tag_enable == 0) error->all(FLERR, "pair_style vertex/voronoi requires atom IDs");

  // The cells: the atoms of the types with cell parameters (others only
  // under hybrid/overlay; pair_vertex_voronoi_cells.cpp).
  check_cell_types();
  check_cutoff_range();
  check_sort_bins();

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
  // The step guard (fix_vertex_guard.cpp), added once; an internal style,
  // registered here on first use (it is not for input scripts).
  const std::string guard_style = FixVertexGuard::style_name();
  if (modify->fix_map->find(guard_style) == modify->fix_map->end())
    (*modify->fix_map)[guard_style] = &FixVertexGuard::creator;
  if (modify->find_fix(guard_id) < 0) modify->add_fix(guard_id + " all " + guard_style);
  auto guard = dynamic_cast<FixVertexGuard *>(modify->fix[modify->find_fix(guard_id)]);
  if (guard) guard->pair = this;
  if (sphere_on) add_sphere_fix();
  // No neighbor list is requested: the tessellation needs only the ghost atoms.
  for (double &v : stats) v = 0.0;
  close_d = -1.0;
  step_move_local = -1.0;
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
  // A type without cell parameters has no cells (hybrid/overlay): the core
  // never reads its entry, which gets valid placeholder values.
  for (int i = 1; i <= n; i++)
    model.types[i - 1] = type_set[i] ? tessera::CellType{kappa[i], area0[i], gamma[i]}
                                     : tessera::CellType{1.0, 1.0, 0.0};
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
  // The quadratic form KP (P - P0)^2 = Gamma/2 P^2 + w Lambda P + KP P0^2
  // (Gamma = 2 KP, w Lambda = -2 KP P0; in 3d KS (S - S0)^2 alike): the
  // constant KP P0^2 = (w Lambda)^2 / (2 Gamma) is part of the energy the
  // user wrote, so each cell of such a type adds it (from the values in
  // use, so that fix adapt of gamma or lambda keeps the form complete).
  const double w = model.tension_weight();
  for (int i = 1; i <= n; i++) {
    const double wl = w * model.lambda_of(i - 1, i - 1);
    energy0[i] = quad_set[i] && gamma[i] > 0.0 ? wl * wl / (2.0 * gamma[i]) : 0.0;
  }
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
  const char *tname = tension == tessera::Tension::Edge ? "edge" : "cell";
  const bool three = domain->dimension == 3 && !sphere_on, finite = radius > 0.0;
  // The settings that apply to this model only.
  std::string msg;
  if (sphere_on)
    msg = fmt::format("pair_style vertex/voronoi: cutoff {:.6g} tension {} surface sphere {:.6g} "
                      "{:.6g} {:.6g} {} (cells on a sphere)\n",
                      cut_global, tname, sphere_c[0], sphere_c[1], sphere_c[2],
                      sphere_var.empty() ? fmt::format("{:.6g}", sphere_R) : "v_" + sphere_var);
  else if (finite)
    msg = fmt::format("pair_style vertex/voronoi: cutoff {:.6g} tension {} radius {:.6g} (finite "
                      "cells)\n",
                      cut_global, tname, radius);
  else if (three)
    msg =
        fmt::format("pair_style vertex/voronoi: cutoff {:.6g} tension {} incremental {} grow {} "
                    "reference {} (3d cells)\n",
                    cut_global, tname, inc_name[incremental], grow ? "yes" : "no", reference_every);
  else
    msg = fmt::format(
        "pair_style vertex/voronoi: cutoff {:.6g} tension {} incremental {} grow {} reference {}\n",
        cut_global, tname, inc_name[incremental], grow ? "yes" : "no", reference_every);
  msg += fmt::format("  {} energy = {} Lambda_IJ * {}; reduced units: length {}, energy {}\n"
                     "  type          K {}      Gamma     Lambda_II {}{}\n",
                     three ? "face" : "junction", tension == tessera::Tension::Edge ? "1 x" : "2 x",
                     three ? "area" : "length", three ? "V0^(1/3)" : "sqrt(A0)",
                     three ? "K V0^2" : "K A0^2", three ? "        V0" : "        A0",
                     three ? "        s0" : "        p0", finite ? "     free F" : "");
  const double c = tension == tessera::Tension::Edge ? 2.0 : 1.0;
  for (int i = 1; i <= n; i++) {
    if (!type_set[i]) {
      msg += fmt::format("  {:4d}   no cell parameters: its atoms are not cells\n", i);
      continue;
    }
    const double lam = model.lambda_of(i - 1, i - 1);
    const double size = three ? std::cbrt(area0[i] * area0[i]) : std::sqrt(area0[i]);
    const double p0 = gamma[i] != 0.0 ? -lam / (c * gamma[i] * size) : 0.0;
    msg += fmt::format("  {:4d} {:10.4g} {:10.4g} {:10.4g} {:13.4g} {:>10}", i, kappa[i], area0[i],
                       gamma[i], lam, gamma[i] != 0.0 ? fmt::format("{:.4g}", p0) : "-");
    if (finite) msg += fmt::format(" {:10.4g}", free_tension[i]);
    msg += "\n";
  }
  // Per-cell values that replace the types' (fix property/atom).
  std::string per_cell;
  for (const char *name : {"area0", "ka", "kp", "perim0"}) {
    int flag = -1, cols = -1;
    if (atom->find_custom(name, flag, cols) >= 0) per_cell += fmt::format(" d_{}", name);
  }
  if (!per_cell.empty())
    msg += fmt::format("  per-cell values (fix property/atom) replace the types':{}\n", per_cell);
  msg += "  effective junction tension Lambda_IJ:\n      ";
  for (int j = 1; j <= n; j++) msg += fmt::format(" {:>10d}", j);
  msg += "\n";
  for (int i = 1; i <= n; i++) {
    msg += fmt::format("  {:4d}", i);
    for (int j = 1; j <= n; j++)
      msg += type_set[i] && type_set[j] ? fmt::format(" {:10.4g}", model.lambda_of(i - 1, j - 1))
                                        : fmt::format(" {:>10}", "-");
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
    if (!type_set[i]) continue;    // no cells of this type
    if (!(adapt_kappa[i][i] > 0.0) || !std::isfinite(adapt_kappa[i][i]))
      error->all(FLERR,
                 "pair_style vertex/voronoi (fix adapt): kappa of type {} must be > 0, got {}", i,
                 adapt_kappa[i][i]);
    if (!(adapt_area0[i][i] > 0.0) || !std::isfinite(adapt_area0[i][i]))
      error->all(FLERR,
                 "pair_style vertex/voronoi (fix adapt): area0 of type {} must be > 0, got {}", i,
                 adapt_area0[i][i]);
    const bool kappa_changed = adapt_kappa[i][i] != kappa[i];
    kappa[i] = adapt_kappa[i][i];
    if (adapt_area0[i][i] != area0[i] && !warned_area0) {
      int flag = -1, cols = -1;
      if (atom->find_custom("area0", flag, cols) >= 0 && comm->me == 0) {
        error->warning(FLERR,
                       "pair_style vertex/voronoi (fix adapt): area0 of type {} changed, but each "
                       "cell's preferred measure comes from its per-atom d_area0, which this does "
                       "not change; adapt d_area0 instead (e.g. with 'set' or fix cell/divide's "
                       "growth)",
                       i);
        warned_area0 = 1;
      }
    }
    area0[i] = adapt_area0[i][i];
    // The same for the per-cell stiffnesses (d_ka, d_kp replace K, Gamma).
    const char *changed = kappa_changed ? "ka" : adapt_gamma[i][i] != gamma[i] ? "kp" : nullptr;
    int flag = -1, cols = -1;
    if (changed && !warned_percell && atom->find_custom(changed, flag, cols) >= 0) {
      if (comm->me == 0)
        error->warning(FLERR,
                       "pair_style vertex/voronoi (fix adapt): {} of type {} changed, but each "
                       "cell's value comes from its per-atom d_{}, which this does not change",
                       changed[1] == 'a' ? "kappa" : "gamma", i, changed);
      warned_percell = 1;
    }
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

/* Whether fix adapt changed a value of extract()'s arrays since the model
   was built. */

bool PairVertexVoronoi::adapted() const
{
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++) {
    if (!type_set[i]) continue;
    if (adapt_kappa[i][i] != kappa[i] || adapt_area0[i][i] != area0[i] ||
        adapt_gamma[i][i] != gamma[i])
      return true;
    for (int j = i + 1; j <= n; j++)
      if (lambda[i][j] != lambda_built[i][j]) return true;
  }
  return false;
}

double PairVertexVoronoi::init_one(int i, int j)
{
  if (setflag[i][j] == 0) setflag[i][j] = 1;
  return cut_global;
}

/* This step's 0-based types of the owned and ghost cells (gather_cells'
   list), the per-cell energy array, and the per-cell preferred measures. */

void PairVertexVoronoi::prepare_atoms()
{
  type0.resize(ncell_all);
  const int *type = atom->type;
  // (Locals rather than cell_atom(p) and ncell_all: the stores to type0
  // could alias those members, which would keep the compiler from
  // vectorizing the plain copy.)
  int *t0 = type0.data();
  const int n = ncell_all;
  if (all_cell_types)
    for (int p = 0; p < n; p++) t0[p] = type[p] - 1;
  else
    for (int p = 0; p < n; p++) t0[p] = type[cell_local[p]] - 1;
  cell_e.resize(ncell_local);
  bind_cell_area0();
  bind_cell_params();
}

/* Per-cell preferred areas (volumes in 3d) from 'fix property/atom
   d_area0', when defined (otherwise the types' A0), for every model.  Only
   owned cells' values are read (atoms that are no cells need none). */

void PairVertexVoronoi::bind_cell_area0()
{
  model.cell_area0 = nullptr;
  int a0_flag = -1, a0_cols = -1;
  const int a0_index = atom->find_custom("area0", a0_flag, a0_cols);
  if (a0_index < 0 || a0_flag != 1 || a0_cols != 0) return;
  const double *a0 = compact_values(atom->dvector[a0_index], 0);
  for (int i = 0; i < ncell_local; i++)
    if (!(a0[i] > 0.0) || !std::isfinite(a0[i]))
      error->one(FLERR,
                 "pair_style vertex/voronoi: per-atom preferred {} d_area0 of atom {} is {}; "
                 "it must be > 0 (e.g. 'set group all d_area0 1.0' after 'fix property/atom "
                 "d_area0')",
                 domain->dimension == 3 ? "volume" : "area", cell_tag(i), a0[i]);
  model.cell_area0 = a0;
}

/* Per-cell stiffnesses and preferred perimeter (surface in 3d) from 'fix
   property/atom d_ka d_kp d_perim0', each when defined, in the quadratic
   form's units for every model: the cell's energy is d_ka (A - A0)^2 +
   d_kp (P - d_perim0)^2 in place of its type's (see tessera::Model).  A
   zero (what fix property/atom leaves unset) is an error naming the atom.
   Without any of them the model's pointers stay null and the force loops
   take their types-only path. */

void PairVertexVoronoi::bind_cell_params()
{
  const bool three = domain->dimension == 3;
  const char *names[3] = {"ka", "kp", "perim0"};
  const char *what[3] = {three ? "volume modulus KV" : "area modulus KA",
                         three ? "surface modulus KS" : "perimeter modulus KP",
                         three ? "preferred surface S0" : "preferred perimeter P0"};
  const double *v[3] = {nullptr, nullptr, nullptr};
  const int nlocal = ncell_local;
  for (int k = 0; k < 3; k++) {
    int flag = -1, cols = -1;
    const int index = atom->find_custom(names[k], flag, cols);
    if (index < 0) continue;
    if (flag != 1 || cols != 0)
      error->all(FLERR,
                 "pair_style vertex/voronoi: the per-atom property '{}' must be a double "
                 "vector (fix property/atom d_{}), not an integer or an array",
                 names[k], names[k]);
    v[k] = compact_values(atom->dvector[index], 1 + k);
    for (int i = 0; i < nlocal; i++)
      if (!(v[k][i] > 0.0) || !std::isfinite(v[k][i]))
        error->one(FLERR,
                   "pair_style vertex/voronoi: per-atom {} d_{} of atom {} is {}; it must be > "
                   "0 (set it for every atom, e.g. 'set group all d_{} value', after 'fix "
                   "property/atom d_{}')",
                   what[k], names[k], cell_tag(i), v[k][i], names[k], names[k]);
  }
  model.cell_KA = v[0];
  model.cell_KP = v[1];
  model.cell_P0 = v[2];
  // A per-cell KP keeps the type's preferred perimeter -w Lambda_II / Gamma_I,
  // which a type with Gamma = 0 does not define.
  if (v[1] && !v[2]) {
    for (int i = 0; i < nlocal; i++)
      if (!(gamma[type0[i] + 1] > 0.0))
        error->one(FLERR,
                   "pair_style vertex/voronoi: atom {} has a per-atom d_kp, but its type {} has "
                   "{} modulus 0 (Gamma = 2 {}), which defines no preferred {}: also define "
                   "d_perim0 (fix property/atom d_perim0) and set it",
                   cell_tag(i), type0[i] + 1, three ? "surface" : "perimeter", three ? "KS" : "KP",
                   three ? "surface" : "perimeter");
  }
}

/* The shared tail of every model unit: cell_e holds each owned cell's
   energy and energy their sum (the forces are in atom->f); cell_w the
   per-cell virials (nw each) when per-atom virials are wanted.  The
   quadratic forms' constant is added here, once for every model. */

void PairVertexVoronoi::accumulate(double energy, int nw)
{
  // Cells in gather_cells' list: owned cell i is local atom cell_atom(i).
  const int nlocal = ncell_local;
  if (model.has_cell_params()) {
    // KP_c P0_c^2 from each cell's values in use (types in the quadratic form).
    for (int i = 0; i < nlocal; i++) {
      const double e0 = quad_set[type0[i] + 1] ? model.quadratic_constant(i, type0[i]) : 0.0;
      cell_e[i] += e0;
      energy += e0;
    }
  } else {
    for (int i = 0; i < nlocal; i++) {
      const double e0 = energy0[type0[i] + 1];
      cell_e[i] += e0;
      energy += e0;
    }
  }
  if (!std::isfinite(energy))
    error->one(FLERR,
               "pair_style vertex/voronoi at step {}: the energy of this rank's cells is {} (the "
               "parameters or the cells' sizes are far outside the model's reduced units)",
               update->ntimestep, energy);
  tess_step = update->ntimestep;
  finish_cells();
  record_view_state();
  // The cells' virials: per atom, and summed into the global virial when
  // LAMMPS asks the style for it instead of f dot r ('pair_modify nofdotr';
  // the sphere's unit adds its own).
  const bool global = vflag_global && !sphere_on;
  if (vflag_atom || global) {
    for (int c = 0; c < nlocal; c++) {
      const double *w = &cell_w[static_cast<size_t>(nw) * c];
      double v[6] = {w[0], w[1], 0.0, 0.5 * (w[2] + w[3]), 0.0, 0.0};
      if (nw == 9) {
        v[1] = w[4];
        v[2] = w[8];
        v[3] = 0.5 * (w[1] + w[3]);
        v[4] = 0.5 * (w[2] + w[6]);
        v[5] = 0.5 * (w[5] + w[7]);
      }
      const int i = cell_atom(c);
      for (int k = 0; k < 6; k++) {
        if (vflag_atom) vatom[i][k] += v[k];
        if (global) virial[k] += v[k];
      }
    }
  }
  if (eflag_global) eng_vdwl += energy;
  if (eflag_atom)
    for (int c = 0; c < nlocal; c++) eatom[cell_atom(c)] += cell_e[c];
  if (vflag_fdotr) virial_fdotr_compute();
}

void PairVertexVoronoi::compute(int eflag, int vflag)
{
  ncompute++;
  nforce++;
  ev_init(eflag, vflag);
  check_lost_atoms();
  if (!unit) error->all(FLERR, "pair_style vertex/voronoi: compute before init");
  // fix adapt calls reinit() of the pair style it was given; inside
  // pair_style hybrid that is hybrid's, which does not pass it on: take
  // the changes here.
  if (force->pair != this && adapted()) reinit();
  unit->compute(eflag, vflag);
}

const tessera::CellView &PairVertexVoronoi::cells() const
{
  static const tessera::ConfluentCells none;
  if (!unit) return none;
  if (all_cell_types) return unit->cells();
  return subset;
}

/* Cell diameter of a type (1-based), the step guard's limit: sqrt(A0) in
   2d, cbrt(V0) in 3d. */

double PairVertexVoronoi::cell_size(int type) const
{
  if (!is_cell_type(type)) return 0.0;    // no cell
  return domain->dimension == 3 && !sphere_on ? std::cbrt(area0[type]) : std::sqrt(area0[type]);
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
  if (strcmp(str, CellSource::extract_name) == 0) {
    dim = 0;
    if (!source) source = CellSource::of(*this);
    return source.get();
  }
  return nullptr;
}

/* 'pair_modify nofdotr' sets LAMMPS's flag, which init_style sets for the
   sphere's unit: remember that the user asked for it. */

void PairVertexVoronoi::modify_params(int narg, char **arg)
{
  Pair::modify_params(narg, arg);
  for (int i = 0; i < narg; i++)
    if (strcmp(arg[i], "nofdotr") == 0) nofdotr_given = 1;
}

double PairVertexVoronoi::memory_usage()
{
  double bytes = Pair::memory_usage();
  if (unit) bytes += unit->memory_usage();
  bytes += (double) type0.capacity() * sizeof(int) + cell_e.capacity() * sizeof(double);
  // The list of cell atoms among others (pair_vertex_voronoi_cells.cpp).
  bytes += (double) (cell_local.capacity() + cell_scratch.capacity()) * sizeof(int) +
      (double) (cell_xbuf.capacity() + cell_fbuf.capacity() + cell_e_atom.capacity()) *
          sizeof(double);
  for (const auto &v : cell_pc) bytes += (double) v.capacity() * sizeof(double);
  return bytes;
}
