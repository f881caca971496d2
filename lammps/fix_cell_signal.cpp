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

   fix cell/signal: chemical species carried by the cells (per-atom
   properties d_name of fix property/atom), integrated at the end of every
   step:
     du_i/dt = sum_j P s_ij (u_j - u_i) + Pb F_i (cb - u_i) - k u_i + sum of productions
   over the neighbours j of cell i in the group, s_ij the size of the shared
   junction (edge length, face area), F_i the length of cell i's free arcs
   (finite cells).  The exchange term of a pair of cells is computed from the
   same values on both sides (ghost values by forward communication), so it
   moves amounts between cells and the total is conserved to round-off when
   there is no bath, degradation or production.  Explicit Euler substeps,
   enough of them that no cell loses more than half its amount per substep
   to exchange and degradation ('substeps auto'), keep stiff exchange stable
   and the amounts non-negative.  Productions: atom-style variables
   (evaluated once per step) and Hill functions of a field or of its
   junction-weighted mean over the neighbours (evaluated every substep).
   The substeps are in fix_cell_signal_explicit.cpp; 'implicit yes'
   replaces them by one backward-Euler step of exchange, bath and
   degradation (fix_cell_signal_implicit.cpp).
------------------------------------------------------------------------- */

#include "fix_cell_signal.h"

#include "atom.h"
#include "cell_group.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "modify.h"
#include "pair_vertex_voronoi.h"
#include "tessera_compat.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

static const char SYNTAX[] =
    "fix ID group cell/signal keyword args ...; keywords: exchange d_u P | bath d_u Pb cb | "
    "degrade d_u k | produce d_u v_name | produce d_u hill|hillr vmax K n [mean] d_x | "
    "substeps auto|N | implicit yes|no";

FixCellSignal::FixCellSignal(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), nsub_fixed(0), nsub_last(0), pair(nullptr)
{
  create_attribute = 1;
  auto need = [&](int iarg, int n, const char *kw) {
    if (iarg + n >= narg)
      error->all(FLERR, "fix cell/signal: keyword '{}' needs {} value(s); syntax: {}", kw, n,
                 SYNTAX);
  };
  auto rate_value = [&](const char *kw, const char *v, const char *what) {
    const double x = utils::numeric(FLERR, v, false, lmp);
    if (!(x >= 0.0) || !std::isfinite(x))
      error->all(FLERR, "fix cell/signal: {} {} must be >= 0 and finite, got {}", kw, what, v);
    return x;
  };
  int iarg = 3;
  while (iarg < narg) {
    const char *kw = arg[iarg];
    if (strcmp(kw, "exchange") == 0) {
      need(iarg, 2, kw);
      const int f = field_of(arg[iarg + 1], kw);
      fields[f].P = rate_value(kw, arg[iarg + 2], "permeability P");
      fields[f].species = true;
      iarg += 3;
    } else if (strcmp(kw, "bath") == 0) {
      need(iarg, 3, kw);
      const int f = field_of(arg[iarg + 1], kw);
      fields[f].Pb = rate_value(kw, arg[iarg + 2], "permeability Pb");
      fields[f].cb = rate_value(kw, arg[iarg + 3], "bath value cb");
      fields[f].species = true;
      iarg += 4;
    } else if (strcmp(kw, "degrade") == 0) {
      need(iarg, 2, kw);
      const int f = field_of(arg[iarg + 1], kw);
      fields[f].k = rate_value(kw, arg[iarg + 2], "rate k");
      fields[f].species = true;
      iarg += 3;
    } else if (strcmp(kw, "produce") == 0) {
      need(iarg, 2, kw);
      Production p;
      p.target = field_of(arg[iarg + 1], kw);
      fields[p.target].species = true;
      p.ivar = -1;
      p.vmax = p.K = p.n = 0.0;
      p.input = -1;
      p.mean = false;
      const char *law = arg[iarg + 2];
      if (strncmp(law, "v_", 2) == 0) {
        p.kind = VAR;
        p.var = law + 2;
        p.text = fmt::format("produce {} {}", arg[iarg + 1], law);
        iarg += 3;
      } else if (strcmp(law, "hill") == 0 || strcmp(law, "hillr") == 0) {
        p.kind = strcmp(law, "hill") == 0 ? HILL : HILLR;
        need(iarg, 6, kw);
        p.vmax = rate_value(law, arg[iarg + 3], "vmax");
        p.K = utils::numeric(FLERR, arg[iarg + 4], false, lmp);
        p.n = utils::numeric(FLERR, arg[iarg + 5], false, lmp);
        if (!(p.K > 0.0) || !std::isfinite(p.K))
          error->all(FLERR, "fix cell/signal: {} K must be > 0, got {}", law, arg[iarg + 4]);
        if (!(p.n > 0.0) || !std::isfinite(p.n))
          error->all(FLERR, "fix cell/signal: {} exponent n must be > 0, got {}", law,
                     arg[iarg + 5]);
        int at = iarg + 6;
        if (strcmp(arg[at], "mean") == 0) {
          p.mean = true;
          need(at, 1, "mean");
          at++;
        }
        p.input = field_of(arg[at], law);
        p.text = fmt::format("produce {} {} {} {} {}{} {}", arg[iarg + 1], law, arg[iarg + 3],
                             arg[iarg + 4], arg[iarg + 5], p.mean ? " mean" : "", arg[at]);
        iarg = at + 1;
      } else {
        error->all(FLERR,
                   "fix cell/signal: unknown production law '{}' for {}; give v_name (an "
                   "atom-style variable) or hill|hillr vmax K n [mean] d_x",
                   law, arg[iarg + 1]);
      }
      laws.push_back(p);
    } else if (strcmp(kw, "implicit") == 0) {
      need(iarg, 1, kw);
      if (strcmp(arg[iarg + 1], "yes") == 0)
        implicit = 1;
      else if (strcmp(arg[iarg + 1], "no") == 0)
        implicit = 0;
      else
        error->all(FLERR, "fix cell/signal: implicit must be yes or no, got '{}'", arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(kw, "substeps") == 0) {
      need(iarg, 1, kw);
      if (strcmp(arg[iarg + 1], "auto") == 0)
        nsub_fixed = 0;
      else {
        const bigint n = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
        if (n < 1)
          error->all(FLERR, "fix cell/signal: substeps must be auto or an integer >= 1, got {}",
                     arg[iarg + 1]);
        // The most 'substeps auto' takes: each substep passes over every
        // cell and junction, so more would make a step take minutes.
        if (n >= 10000000)
          error->all(FLERR,
                     "fix cell/signal: substeps {} is not below 10000000, the most 'substeps "
                     "auto' takes (each substep passes over every cell and junction, so a step "
                     "would take that many times as long); give the count the rates need, or "
                     "'substeps auto', which finds it every step",
                     arg[iarg + 1]);
        nsub_fixed = static_cast<int>(n);
      }
      iarg += 2;
    } else {
      error->all(FLERR, "fix cell/signal: unknown keyword '{}'; syntax: {}", kw, SYNTAX);
    }
  }
  for (size_t f = 0; f < fields.size(); f++) {
    coef_kneg.push_back(fields[f].species ? -fields[f].k : 0.0);
    coef_P.push_back(fields[f].species ? fields[f].P : 0.0);
    if (!fields[f].species) continue;
    species.push_back(static_cast<int>(f));
    if (fields[f].Pb > 0.0) any_bath = true;
  }
  if (species.empty())
    error->all(FLERR, "fix cell/signal: no species; give at least one law; syntax: {}", SYNTAX);
  if (!atom->tag_enable) error->all(FLERR, "fix cell/signal requires atom IDs");

  // (the implicit step sends two vectors at once)
  comm_forward = std::max(static_cast<int>(fields.size()), 2);
  vector_flag = 1;
  size_vector = static_cast<int>(fields.size()) + 1;
  global_freq = 1;
  extvector = 0;
  nevery = 1;
}

/* The field named d_name (added on first mention), which fix property/atom
   must define. */

int FixCellSignal::field_of(const char *arg, const char *keyword)
{
  if (strncmp(arg, "d_", 2) != 0 || !arg[2])
    error->all(FLERR,
               "fix cell/signal: {} expects a species d_name (a per-atom property of fix "
               "property/atom), got '{}'",
               keyword, arg);
  const std::string name = arg + 2;
  for (size_t f = 0; f < fields.size(); f++)
    if (fields[f].name == name) return static_cast<int>(f);
  int flag = -1, cols = -1;
  const int index = atom->find_custom(name.c_str(), flag, cols);
  if (index < 0 || flag != 1 || cols != 0)
    error->all(FLERR,
               "fix cell/signal: {} {}: unknown species; define it first with 'fix ID all "
               "property/atom d_{}' (and set its values with 'set')",
               keyword, arg, name);
  fields.push_back({name, index, false, 0.0, 0.0, 0.0, 0.0});
  return static_cast<int>(fields.size()) - 1;
}

/* Cells made by fix deposit, fix pour or create_atoms start without any of
   the species this fix changes (LAMMPS leaves a new atom's custom
   properties holding whatever the memory held, often a ghost's value);
   daughters of fix cell/divide are copies, not new atoms here. */

void FixCellSignal::set_arrays(int i)
{
  for (const Field &f : fields) {
    if (!f.species) continue;
    int flag = -1, cols = -1;
    const int index = atom->find_custom(f.name.c_str(), flag, cols);
    if (index >= 0 && flag == 1 && cols == 0) atom->dvector[index][i] = 0.0;
  }
}

int FixCellSignal::setmask()
{
  return END_OF_STEP;
}

void FixCellSignal::init()
{
  pair = CellSource::find(lmp);
  if (!pair)
    error->all(FLERR,
               "fix cell/signal {} exchanges across the junctions of pair_style vertex/voronoi "
               "or vertex/polygon, but the pair style is '{}'; define one of them",
               id, force->pair_style ? force->pair_style : "none");
  all_taken = igroup == 0 && !cell_group::any_particle_type(pair, atom->ntypes);
  // Only finite cells have free arcs: elsewhere a bath would never act.
  if (any_bath && !(pair->finite_radius() > 0.0))
    for (const Field &f : fields)
      if (f.Pb > 0.0)
        error->all(FLERR,
                   "fix cell/signal {}: bath d_{} exchanges across the free arcs of finite cells, "
                   "but these cells have none (pair_style vertex/voronoi without 'radius r': "
                   "confluent 2d cells, 3d cells or cells on a sphere tile space, so the bath "
                   "would never act); remove 'bath d_{} ...', or use finite cells",
                   id, f.name, f.name);
  for (Field &f : fields) {
    int flag = -1, cols = -1;
    f.index = atom->find_custom(f.name.c_str(), flag, cols);
    if (f.index < 0 || flag != 1 || cols != 0)
      error->all(FLERR,
                 "fix cell/signal {}: species d_{} no longer exists; define it again with 'fix "
                 "ID all property/atom d_{}'",
                 id, f.name, f.name);
  }
  for (Production &p : laws) {
    if (p.kind != VAR) continue;
    p.ivar = input->variable->find(p.var.c_str());
    if (p.ivar < 0)
      error->all(FLERR, "fix cell/signal {}: law '{}': no variable named '{}'", id, p.text, p.var);
    if (!input->variable->atomstyle(p.ivar))
      error->all(FLERR, "fix cell/signal {}: law '{}': variable {} is not atom-style", id, p.text,
                 p.var);
  }
}

void FixCellSignal::check_cells(const char *when)
{
  pair->require_current_cells(fmt::format("fix cell/signal {} ({})", id, when));
}

/* Whether the fix takes owned atom i: a cell of its group. */

bool FixCellSignal::takes(int i) const
{
  return (atom->mask[i] & groupbit) && cell_group::is_cell(pair, atom->type[i]);
}

/* This step's flags of the owned atoms the fix takes. */

void FixCellSignal::mark_taken()
{
  const int nlocal = atom->nlocal;
  taken.assign(std::max(nlocal, 1), 0);
  for (int i = 0; i < nlocal; i++) taken[i] = takes(i) ? 1 : 0;
}

/* Every field of every cell taken must be finite and >= 0. */

void FixCellSignal::check_values(const char *when)
{
  for (const Field &f : fields) {
    const double *u = atom->dvector[f.index];
    for (int i = 0; i < atom->nlocal; i++)
      if (takes(i) && !(u[i] >= 0.0 && std::isfinite(u[i])))
        error->one(FLERR,
                   "fix cell/signal {}: d_{} of cell {} is {} at step {} ({}); species must be "
                   "finite and >= 0",
                   id, f.name, atom->tag[i], u[i], update->ntimestep, when);
  }
}

void FixCellSignal::setup(int /*vflag*/)
{
  cell_group::note_particles(lmp, pair, igroup, fmt::format("fix {} cell/signal", id),
                             "it neither integrates their values nor counts them in its totals, "
                             "and no cell exchanges with them",
                             noted_particles);
  check_values("at the start of the run");
  nsub_last = 0;
  warned_implicit.clear();
}

/* The variable laws' rates on the owned cells, once per step. */

void FixCellSignal::evaluate_variables()
{
  const int nlocal = atom->nlocal;
  bool any = false;
  for (const Production &p : laws) any = any || p.kind == VAR;
  if (!any) return;
  modify->clearstep_compute();
  for (Production &p : laws) {
    if (p.kind != VAR) continue;
    p.value.assign(std::max(nlocal, 1), 0.0);
    input->variable->compute_atom(p.ivar, igroup, p.value.data(), 1, 0);
    for (int i = 0; i < nlocal; i++)
      if (taken[i] && !std::isfinite(p.value[i]))
        error->one(FLERR, "fix cell/signal {}: law '{}' gives {} for cell {} at step {}", id,
                   p.text, p.value[i], atom->tag[i], update->ntimestep);
  }
  modify->addstep_compute(update->ntimestep + 1);
}

/* This step's rows of junctions between group cells, and (with a bath or
   the implicit step) the free arc lengths. */

void FixCellSignal::prepare_rows()
{
  const tessera::CellView &v = pair->cells();
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  // The shared pieces in compressed rows (tessera::Contacts: no free arcs).
  const tessera::Contacts c = v.contacts();
  if (any_bath || implicit) {
    freelen.resize(nlocal);
    for (int i = 0; i < nlocal; i++) freelen[i] = taken[i] ? v.free_length(i) : 0.0;
  } else
    freelen.clear();
  if (igroup == 0) {
    row_offset = c.offset;
    row_index = c.neighbor;
    row_size = c.size;
    return;
  }
  nb_offset.assign(nlocal + 1, 0);
  nb_index.clear();
  nb_size.clear();
  for (int i = 0; i < nlocal; i++) {
    if (taken[i]) {
      for (int k = c.offset[i]; k < c.offset[i + 1]; k++) {
        const int j = c.neighbor[k];
        if (j < 0 || !(mask[j] & groupbit)) continue;
        nb_index.push_back(j);
        nb_size.push_back(c.size[k]);
      }
    }
    nb_offset[i + 1] = static_cast<int>(nb_index.size());
  }
  row_offset = nb_offset.data();
  row_index = nb_index.data();
  row_size = nb_size.data();
}

namespace {
/* vmax x^n / (K^n + x^n) (kind 1, activation) or vmax K^n / (K^n + x^n)
   (repression), through t = (x/K)^n where x <= K and t = (K/x)^n where
   x > K, so that t stays in [0, 1] and no power overflows, whatever n and
   the ratio (x >= 0). */
double hill_value(int kind, double vmax, double K, double n, double x)
{
  if (x <= K) {
    const double t = std::pow(x / K, n);
    return kind == 1 ? vmax * t / (1.0 + t) : vmax / (1.0 + t);
  }
  const double t = std::pow(K / x, n);
  return kind == 1 ? vmax / (1.0 + t) : vmax * t / (1.0 + t);
}
}    // namespace

/* The junction-weighted mean of x over owned cell i's group neighbours
   (as junction_mean(), from this step's rows); the values of cell j are
   x[stride * j]. */

double FixCellSignal::mean_of(int i, const double *x, int stride) const
{
  double sum = 0.0, weight = 0.0;
  for (int k = row_offset[i]; k < row_offset[i + 1]; k++) {
    sum += row_size[k] * x[static_cast<size_t>(stride) * row_index[k]];
    weight += row_size[k];
  }
  return weight > 0.0 ? sum / weight : 0.0;
}

/* Production p's rate in owned cell i, reading its input field from x as
   mean_of() does. */

double FixCellSignal::hill_term(const Production &p, int i, const double *x, int stride) const
{
  const double in = p.mean ? mean_of(i, x, stride) : x[static_cast<size_t>(stride) * i];
  return hill_value(p.kind == HILL ? 1 : 0, p.vmax, p.K, p.n, in);
}

/* The productions of every species on the owned group cells (the implicit
   step's right-hand side), from the values on owned and ghost cells. */

void FixCellSignal::productions()
{
  const int nlocal = atom->nlocal;
  rate.assign(fields.size() * static_cast<size_t>(nlocal), 0.0);
  for (const Production &p : laws) {
    double *r = &rate[p.target * static_cast<size_t>(nlocal)];
    if (p.kind == VAR) {
      for (int i = 0; i < nlocal; i++)
        if (taken[i]) r[i] += p.value[i];
      continue;
    }
    const double *x = atom->dvector[fields[p.input].index];
    for (int i = 0; i < nlocal; i++)
      if (taken[i]) r[i] += hill_term(p, i, x, 1);
  }
}

/* Stops the run: field f of owned cell i would become next.  The law to
   blame: a production that is negative or not finite, else `otherwise`.
   The fields' values the rates were computed from: field g of cell j at
   x[stride * j + g], or (x null) in atom->dvector. */

void FixCellSignal::fail(size_t f, int i, double next, const std::string &otherwise,
                         const double *x, int stride)
{
  std::string blame = otherwise;
  for (const Production &p : laws) {
    if (p.target != static_cast<int>(f)) continue;
    double term;
    if (p.kind == VAR)
      term = p.value[i];
    else if (!x)
      term = hill_term(p, i, atom->dvector[fields[p.input].index], 1);
    else
      term = hill_term(p, i, x + p.input, stride);
    if (!(term >= 0.0) || !std::isfinite(term)) {
      blame = fmt::format("law '{}' gives {}", p.text, term);
      break;
    }
  }
  error->one(FLERR, "fix cell/signal {}: d_{} of cell {} would become {} at step {}: {}", id,
             fields[f].name, atom->tag[i], next, update->ntimestep, blame);
}

void FixCellSignal::end_of_step()
{
  check_cells("fix cell/signal integrates after the force computation of each step");
  const double dt = update->dt;
  mark_taken();
  evaluate_variables();
  prepare_rows();
  if (implicit) {
    nsub_last = 1;
    implicit_step(dt);
  } else
    explicit_step(dt);
}

/* Totals of each field over the group (index f), and the last step's
   substeps (index nfields). */

double FixCellSignal::compute_vector(int n)
{
  if (n == static_cast<int>(fields.size())) return nsub_last;
  const double *u = atom->dvector[fields[n].index];
  double local = 0.0, all = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    if (takes(i)) local += u[i];
  MPI_Allreduce(&local, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return all;
}

int FixCellSignal::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  if (comm_vector && comm_vector2) {
    for (int k = 0; k < n; k++) {
      buf[2 * k] = comm_vector[list[k]];
      buf[2 * k + 1] = comm_vector2[list[k]];
    }
    return 2 * n;
  }
  if (comm_vector) {
    for (int k = 0; k < n; k++) buf[k] = comm_vector[list[k]];
    return n;
  }
  int m = 0;
  if (comm_packed) {
    const size_t nf = fields.size();
    if (nf == 1) {
      for (int k = 0; k < n; k++) buf[k] = value[list[k]];
      return n;
    }
    for (int k = 0; k < n; k++) {
      const double *v = &value[nf * list[k]];
      for (size_t f = 0; f < nf; f++) buf[m++] = v[f];
    }
    return m;
  }
  for (const Field &f : fields) {
    const double *u = atom->dvector[f.index];
    for (int k = 0; k < n; k++) buf[m++] = u[list[k]];
  }
  return m;
}

void FixCellSignal::unpack_forward_comm(int n, int first, double *buf)
{
  if (comm_vector && comm_vector2) {
    for (int k = 0; k < n; k++) {
      comm_vector[first + k] = buf[2 * k];
      comm_vector2[first + k] = buf[2 * k + 1];
    }
    return;
  }
  if (comm_vector) {
    for (int k = 0; k < n; k++) comm_vector[first + k] = buf[k];
    return;
  }
  if (comm_packed) {
    const size_t nf = fields.size();
    std::copy(buf, buf + nf * n, &value[nf * first]);
    return;
  }
  int m = 0;
  for (const Field &f : fields) {
    double *u = atom->dvector[f.index];
    for (int k = 0; k < n; k++) u[first + k] = buf[m++];
  }
}
