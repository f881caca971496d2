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

   fix cell/signal: the explicit Euler substeps of a step.  Every field of
   every owned and ghost cell sits in one array, cell after cell, so that a
   substep is one copy of the owned values, one forward communication of all
   fields and one pass over the junctions that accumulates the exchange of
   every species at once (and the junction sizes that 'substeps auto' and
   the neighbour means need) and applies the rates.  Each species'
   arithmetic is that of a species integrated alone.
------------------------------------------------------------------------- */

#include "fix_cell_signal.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "tessera_compat.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <limits>

using namespace LAMMPS_NS;

namespace {
// 'substeps auto': no cell loses more than this fraction of an amount per
// substep to exchange, the bath and degradation.
constexpr double MAX_LOSS = 0.5;
}    // namespace

/* value[nf * i + f] = field f of cell i: the owned cells from the fields,
   the ghosts by forward communication. */

void FixCellSignal::pack_values()
{
  const size_t nf = fields.size();
  const int nlocal = atom->nlocal;
  const size_t need = nf * static_cast<size_t>(std::max(atom->nmax, 1));
  if (value.size() < need) value.resize(need);
  for (size_t f = 0; f < nf; f++) {
    const double *u = atom->dvector[fields[f].index];
    double *v = value.data() + f;
    for (int i = 0; i < nlocal; i++) v[nf * i] = u[i];
  }
  comm_packed = true;
  tessera_compat::forward_comm(comm, this);
  comm_packed = false;
}

/* One pass over the owned group cells and their junctions for all fields
   (NF of them, or any number when NF is 0), from `value`.  Each species'
   rate is -k u + Pb F (cb - u) + P sum_j s_ij (u_j - u_i) + productions,
   summed in that order (a term of a zero rate adds a zero).  With apply,
   the species become u + h rate at once (in atom->dvector; `value` keeps
   the old values) and `bad` counts the cells where one would be negative or
   not finite; else the rates go to drate[nf * i + f].  With want_fastest,
   returns this rank's largest P W_i + Pb F_i + k over the group cells and
   species (W_i: cell i's total junction size), which sets the substeps.
   PLAIN: every atom taken (group all, no particles), no bath, no
   production (every field is a species). */

template <int NF, bool PLAIN>
double FixCellSignal::explicit_pass(bool apply, double h, bool want_fastest, int &bad)
{
  const int nf = NF > 0 ? NF : static_cast<int>(fields.size());
  const int nlocal = atom->nlocal;
  const char *take = taken.data();
  const bool all = all_taken;
  const bool store = !apply;
  if (store) {
    const size_t need = static_cast<size_t>(nf) * std::max(nlocal, 1);
    if (drate.size() < need) drate.resize(need);
  }
  double fixed[NF > 0 ? 2 * NF : 1];
  double *fixed_out[NF > 0 ? NF : 1];
  if (NF == 0) {
    if (exch.size() < 2 * static_cast<size_t>(nf)) exch.resize(2 * nf);
    if (exch_out.size() < static_cast<size_t>(nf)) exch_out.resize(nf);
  }
  double *ex = NF > 0 ? fixed : exch.data();    // exchange sums
  double *rloc = ex + nf;                       // rates (apply)
  double **out = NF > 0 ? fixed_out : exch_out.data();
  for (int f = 0; f < nf; f++)
    out[f] = fields[f].species ? atom->dvector[fields[f].index] : nullptr;
  const double *v = value.data();
  const double *kneg = coef_kneg.data(), *perm = coef_P.data();
  const int *offset = row_offset, *index = row_index;
  const double *size = row_size;
  double *rate_of = drate.data();
  const double huge = std::numeric_limits<double>::max();
  double wmax = 0.0, fastest = 0.0;
  bool any_cell = false;
  int nbad = 0;
  for (int i = 0; i < nlocal; i++) {
    if (!PLAIN && !all && !take[i]) continue;
    any_cell = true;
    const double *ui = v + static_cast<size_t>(nf) * i;
    for (int f = 0; f < nf; f++) ex[f] = 0.0;
    double w = 0.0;
    // Two junctions per round, each added in turn (the order of a plain loop).
    int k = offset[i];
    const int end = offset[i + 1];
    for (; k + 1 < end; k += 2) {
      const double s0 = size[k], s1 = size[k + 1];
      const double *u0 = v + static_cast<size_t>(nf) * index[k];
      const double *u1 = v + static_cast<size_t>(nf) * index[k + 1];
      w += s0;
      w += s1;
      for (int f = 0; f < nf; f++) {
        ex[f] += s0 * (u0[f] - ui[f]);
        ex[f] += s1 * (u1[f] - ui[f]);
      }
    }
    if (k < end) {
      const double s0 = size[k];
      const double *u0 = v + static_cast<size_t>(nf) * index[k];
      w += s0;
      for (int f = 0; f < nf; f++) ex[f] += s0 * (u0[f] - ui[f]);
    }
    double *r = store ? rate_of + static_cast<size_t>(nf) * i : rloc;
    if (PLAIN) {
      for (int f = 0; f < nf; f++) r[f] = kneg[f] * ui[f] + perm[f] * ex[f];
    } else {
      for (int f = 0; f < nf; f++) r[f] = kneg[f] * ui[f];
      if (any_bath)
        for (int f : species) {
          const Field &fd = fields[f];
          if (fd.Pb > 0.0) r[f] += fd.Pb * freelen[i] * (fd.cb - ui[f]);
        }
      for (int f = 0; f < nf; f++) r[f] += perm[f] * ex[f];
      for (const Production &p : laws)
        r[p.target] += p.kind == VAR ? p.value[i] : hill_term(p, i, v + p.input, nf);
    }
    if (!store) {
      bool ok = true;
      for (int f = 0; f < nf; f++) {
        if (!PLAIN && !out[f]) continue;
        const double next = ui[f] + h * r[f];
        ok = ok && next >= 0.0 && next <= huge;    // false for NaN
        out[f][i] = next;
      }
      nbad += ok ? 0 : 1;
    }
    if (want_fastest) {
      wmax = std::max(wmax, w);
      if (!PLAIN && any_bath)
        for (int f : species) {
          const Field &fd = fields[f];
          if (fd.Pb > 0.0) fastest = std::max(fastest, fd.P * w + fd.Pb * freelen[i] + fd.k);
        }
    }
  }
  bad = nbad;
  // Without a bath, P W_i + k is largest where W_i is (rounding keeps the order).
  if (want_fastest && any_cell)
    for (int f : species) {
      const Field &fd = fields[f];
      if (!(fd.Pb > 0.0)) fastest = std::max(fastest, fd.P * wmax + fd.k);
    }
  return fastest;
}

double FixCellSignal::explicit_rates(bool apply, double h, bool want_fastest, int &bad)
{
  const bool plain = laws.empty() && !any_bath && all_taken;
  switch (fields.size()) {
    case 1:
      return plain ? explicit_pass<1, true>(apply, h, want_fastest, bad)
                   : explicit_pass<1, false>(apply, h, want_fastest, bad);
    case 2:
      return plain ? explicit_pass<2, true>(apply, h, want_fastest, bad)
                   : explicit_pass<2, false>(apply, h, want_fastest, bad);
    case 3:
      return plain ? explicit_pass<3, true>(apply, h, want_fastest, bad)
                   : explicit_pass<3, false>(apply, h, want_fastest, bad);
    case 4:
      return plain ? explicit_pass<4, true>(apply, h, want_fastest, bad)
                   : explicit_pass<4, false>(apply, h, want_fastest, bad);
    default:
      return explicit_pass<0, false>(apply, h, want_fastest, bad);
  }
}

/* u = old value + dt * rate (drate) on the owned group cells, species
   after species; a value that would become negative or not finite stops
   the run with the law to blame. */

void FixCellSignal::explicit_apply(double dt)
{
  const size_t nf = fields.size();
  const int nlocal = atom->nlocal;
  const double *rate_of = drate.data();
  for (int f : species) {
    double *u = atom->dvector[fields[f].index];
    const double *r = rate_of + f;
    const double *old = value.data() + f;
    for (int i = 0; i < nlocal; i++) {
      if (!taken[i]) continue;
      const double next = old[nf * i] + dt * r[nf * i];
      if (!(next >= 0.0 && next <= std::numeric_limits<double>::max()))
        fail(f, i, next,
             fmt::format("exchange and degradation remove more than it holds in a substep of "
                         "{}; use 'substeps auto' or more substeps",
                         dt),
             value.data(), static_cast<int>(nf));
      u[i] = next;
    }
  }
}

/* The substeps of a step of length dt: the fixed count, or (auto) enough
   that dt_sub (P W_i + Pb F_i + k) <= MAX_LOSS for every cell and species.
   The first substep is taken with the count of the last step while the
   count is found; when the count differs (or a value went bad: the message
   names the first one species by species), it is taken again from the
   same old values. */

void FixCellSignal::explicit_step(double dt)
{
  pack_values();
  const int guess = nsub_fixed ? nsub_fixed : std::max(nsub_last, 1);
  int bad = 0;
  const double fastest = explicit_rates(true, dt / guess, nsub_fixed == 0, bad);
  int n = nsub_fixed;
  if (n == 0) {
    double all = 0.0;
    MPI_Allreduce(&fastest, &all, 1, MPI_DOUBLE, MPI_MAX, world);
    const double need = std::ceil(dt * all / MAX_LOSS);
    if (!(need < 1e7))
      error->all(FLERR,
                 "fix cell/signal {}: exchange and degradation at rate {} need {} substeps of a "
                 "step of {}; lower the rates or the timestep",
                 id, all, need, dt);
    n = std::max(1, static_cast<int>(need));
  }
  nsub_last = n;
  const double h = dt / n;
  if (n != guess || bad) {
    explicit_rates(false, 0.0, false, bad);
    explicit_apply(h);
  }
  for (int s = 1; s < n; s++) {
    pack_values();
    explicit_rates(true, h, false, bad);
    if (bad) {
      explicit_rates(false, 0.0, false, bad);
      explicit_apply(h);
    }
  }
}
