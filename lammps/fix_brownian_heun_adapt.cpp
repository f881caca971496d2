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

   fix brownian/heun ... adapt tol T: the error-controlled timestep.

   The Euler predictor and the Heun corrector are an embedded pair: the
   corrector's increment dt/2 (F(r~) - F(r))/gamma_t is the difference of the
   two solutions, an estimate of the Euler step's local error (O(dt^2) for
   smooth forces).  A step whose largest estimate over all atoms exceeds the
   tolerance is undone (positions, image flags, the coupled fixes' state)
   and taken again with a smaller dt; the accepted Heun solution is kept
   (local extrapolation), and the next step's dt follows the controller
     dt' = dt min(grow, max(shrink, safety (tol/est)^(1/2)))
   within [dtmin, dtmax] (no growth right after a rejection).

   Noise (rejection sampling with memory, Rackauckas and Nie 2017): the
   Wiener increments of a step are parts of one Brownian path whose future is
   revealed as the steps need it and kept in a queue of intervals.  A step of
   length h takes the front intervals that fit, splits the next one at h by a
   Brownian bridge (given W at both ends, W in between is Gaussian with mean
   the linear interpolation and variance q (1 - q) tau), or draws a fresh
   interval when the queue runs out.  A rejected attempt gives nothing back:
   its intervals stay revealed and the smaller retry takes the front part of
   them.  Every increment used is therefore an increment of the same path,
   whichever steps were rejected, and no draw is discarded because of its
   value: the noise is unbiased.  Fresh Gaussian numbers are counter-based
   (seed, atom ID, draw number), so the noise does not depend on the number
   of ranks or the order of atoms.
------------------------------------------------------------------------- */

#include "fix_brownian_heun.h"

#include "integrator_chatter.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "output.h"
#include "pair.h"
#include "update.h"
#include "utils.h"

#include "tessera/counter_rng.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {

// Output::reset_dt() exists in current LAMMPS (time-based dump output), not
// in 29 Sep 2021's; called where it exists, as fix dt/reset does.
template <class O> auto output_reset_dt(O *o, int) -> decltype(o->reset_dt(), void())
{
  o->reset_dt();
}
template <class O> void output_reset_dt(O *, long) {}

// Gaussian numbers per (stream, atom, counter): one stream for fresh
// intervals and bridges, one for atoms that join a queue (new atoms).
constexpr uint64_t STREAM_DRAW = 0x41ab9d3f2c5e7781ULL;
constexpr uint64_t STREAM_JOIN = 0x7f4a7c159e3779b9ULL;
constexpr int MAX_WIENER = 64;    // Wiener processes per atom (keys: draw * 64 + component)

// Two durations equal up to the rounding of sums of intervals.
bool same_time(double a, double b)
{
  return std::fabs(a - b) <= 1e-12 * std::max(std::fabs(a), std::fabs(b));
}

}    // namespace

/* ----------------------------------------------------------------------
   adapt tol T [dtmin a] [dtmax b] [angle ta] [safety s] [grow g] [shrink s]
   (arg[0] is 'adapt'; everything after it belongs to the adaptive step)
------------------------------------------------------------------------- */

void FixBrownianHeun::parse_adapt(int narg, char **arg)
{
  adapt = 1;
  tol = tol_angle = -1.0;
  auto value = [&](int iarg, const char *name, double lo, bool open) {
    if (iarg + 1 >= narg)
      error->all(FLERR, "Fix {} (ID {}): adapt keyword {} needs a value", style, id, name);
    const char *text = arg[iarg + 1];
    if (!utils::is_double(text))
      error->all(FLERR, "Fix {} (ID {}): adapt {} must be a number, got '{}'", style, id, name,
                 text);
    const double v = utils::numeric(FLERR, text, false, lmp);
    if (!std::isfinite(v) || (open ? !(v > lo) : !(v >= lo)))
      error->all(FLERR, "Fix {} (ID {}): adapt {} = {} must be {} {}", style, id, name, text,
                 open ? ">" : ">=", lo);
    return v;
  };
  int iarg = 1;
  while (iarg < narg) {
    const char *k = arg[iarg];
    if (strcmp(k, "tol") == 0) {
      tol = value(iarg, "tol", 0.0, true);
    } else if (strcmp(k, "angle") == 0) {
      tol_angle = value(iarg, "angle", 0.0, true);
    } else if (strcmp(k, "dtmin") == 0) {
      dtmin = value(iarg, "dtmin", 0.0, true);
    } else if (strcmp(k, "dtmax") == 0) {
      dtmax = value(iarg, "dtmax", 0.0, true);
    } else if (strcmp(k, "safety") == 0) {
      safety = value(iarg, "safety", 0.0, true);
      if (safety >= 1.0)
        error->all(FLERR, "Fix {} (ID {}): adapt safety = {} must be < 1", style, id, safety);
    } else if (strcmp(k, "grow") == 0) {
      grow_max = value(iarg, "grow", 1.0, false);
    } else if (strcmp(k, "shrink") == 0) {
      shrink_min = value(iarg, "shrink", 0.0, true);
      if (shrink_min >= 1.0)
        error->all(FLERR, "Fix {} (ID {}): adapt shrink = {} must be < 1", style, id, shrink_min);
    } else {
      error->all(FLERR,
                 "Fix {} (ID {}): unknown adapt keyword '{}' (expected tol, dtmin, dtmax, angle, "
                 "safety, grow or shrink; the adapt settings come last)",
                 style, id, k);
    }
    iarg += 2;
  }
  if (tol < 0.0)
    error->all(FLERR,
               "Fix {} (ID {}): 'adapt' needs a tolerance: adapt tol T (T a length, the largest "
               "error of one step of one atom)",
               style, id);
  if (tol_angle < 0.0) tol_angle = tol;
  if (dtmax > 0.0 && dtmin > dtmax)
    error->all(FLERR, "Fix {} (ID {}): adapt dtmin = {} is larger than dtmax = {}", style, id,
               dtmin, dtmax);
}

/* ----------------------------------------------------------------------
   At every run: the noise's Wiener processes (positions with rng gaussian,
   the coupled fixes'), checked against a queue carried over (a restart).
------------------------------------------------------------------------- */

void FixBrownianHeun::init_adapt()
{
  if (noise == NOISE_UNIFORM)
    error->all(FLERR,
               "Fix {} (ID {}): 'adapt' needs Gaussian noise (a rejected step's Wiener increment "
               "is split by a Brownian bridge): add 'rng gaussian' (or 'rng none')",
               style, id);
  for (int i = 0; i < modify->nfix; i++)
    if (strcmp(modify->fix[i]->style, "dt/reset") == 0)
      error->all(FLERR,
                 "Fix {} (ID {}) with 'adapt' sets the timestep itself; fix {} (dt/reset) would "
                 "set it too: remove one of them",
                 style, id, modify->fix[i]->id);
  const int ndim = domain->dimension;
  const int npos = noise == NOISE_GAUSSIAN ? ndim : 0;
  const int want = npos + nwiener_coupled;
  if (want > MAX_WIENER)
    error->all(FLERR, "Fix {} (ID {}): {} Wiener processes per atom, at most {}", style, id, want,
               MAX_WIENER);
  if (want != nwiener) {
    if (!qtau.empty())
      error->all(FLERR,
                 "Fix {} (ID {}): the noise carried over from the last run (or the restart "
                 "file) has {} Wiener processes per atom, this run {}: define the same fixes with "
                 "the same noise (fix polarity noise, rng) as before",
                 style, id, nwiener, want);
    memory->destroy(qbuf);
    qbuf = nullptr;
    nwiener = want;
    qcap = nwiener > 0 ? 4 : 0;
    if (qcols() > 0) {
      memory->create(qbuf, std::max(nmax_saved, 1), qcols(), "brownian/heun:queue");
      for (int i = 0; i < std::max(nmax_saved, 1); i++) qbuf[i][0] = -1.0;
    }
  }
  wscratch.assign(static_cast<size_t>(atom->nmax) * std::max(nwiener, 1), 0.0);
  noise_seed = tessera::rng::mix(static_cast<uint64_t>(seed));
  diffusion_amp = 0.0;
  if (noise == NOISE_GAUSSIAN)
    diffusion_amp = std::sqrt(2.0 * force->boltz * temperature / (force->mvv2e * gamma_t));
  chatter->context = fmt::format("; this run's adapt tol {} gives each step an error estimate "
                                 "below {} (a length), so a period-two oscillation left is at most "
                                 "that large",
                                 tol, tol);
  maxexchange_dynamic = 1;
  maxexchange = ncol + qcols();
}

/* ----------------------------------------------------------------------
   At the start of a run: the bounds (dtmax defaults to the timestep of the
   first run, dtmin to 1e-6 dtmax) and the first proposal, which is the
   timestep unless the fix carries its own from an earlier run or a
   restart (a 'timestep' command given since replaces it).
------------------------------------------------------------------------- */

void FixBrownianHeun::setup_adapt()
{
  if (dtmax < 0.0) dtmax = update->dt;
  if (dtmin <= 0.0) dtmin = 1e-6 * dtmax;
  if (dtmin > dtmax)
    error->all(FLERR, "Fix {} (ID {}): adapt dtmin = {} is larger than dtmax = {}", style, id,
               dtmin, dtmax);
  if (dt_next < 0.0 || update->dt != dt_set) dt_next = update->dt;
  dt_next = std::min(dtmax, std::max(dtmin, dt_next));
}

/* ----------------------------------------------------------------------
   The timestep of the current step becomes h, as fix dt/reset sets it:
   the simulated time up to the previous step with the old one, then
   update->dt, and every class that depends on it (pair style, fixes,
   output).
------------------------------------------------------------------------- */

void FixBrownianHeun::set_timestep(double h)
{
  dt_set = h;
  if (h == update->dt) return;
  update->atime += (update->ntimestep - 1 - update->atimestep) * update->dt;
  update->atimestep = update->ntimestep - 1;
  update->dt = h;
  update->dt_default = 0;
  if (force->pair) force->pair->reset_dt();
  for (int i = 0; i < modify->nfix; i++) modify->fix[i]->reset_dt();
  output_reset_dt(output, 0);
}

void FixBrownianHeun::begin_adaptive_step()
{
  set_timestep(dt_next);
}

/* An attempt with error ratio err is accepted when err <= 1, or at dtmin
   (nothing smaller may be tried), which is counted and reported once. */

bool FixBrownianHeun::accept(double err)
{
  if (err <= 1.0) return true;
  if (dt > dtmin * (1.0 + 1e-12)) return false;
  nforced++;
  if (!forced_warned && comm->me == 0)
    error->warning(FLERR,
                   "fix {} {}: step {} was taken at dtmin = {} with an error estimate {:.3g} "
                   "times the tolerance (adapt tol {}); lower dtmin or raise tol (reported once; "
                   "the fix's vector element 7 counts such steps)",
                   style, id, update->ntimestep, dtmin, err, tol);
  forced_warned = 1;
  return true;
}

/* The next step for the error ratio err of a step of length h. */

double FixBrownianHeun::controller(double h, double err, bool rejected)
{
  double factor = grow_max;
  if (!std::isfinite(err))
    factor = shrink_min;
  else if (err > 0.0)
    factor = std::min(grow_max, std::max(shrink_min, safety / std::sqrt(err)));
  if (rejected) factor = std::min(factor, 1.0);
  return std::min(dtmax, std::max(dtmin, h * factor));
}

/* After the accepted attempt: the queue's used intervals go, the next
   step is proposed. */

void FixBrownianHeun::finish_adaptive_step(double err, bool rejected)
{
  if (consumed > 0) pop_queue(consumed);
  consumed = 0;
  dt_next = controller(dt, err, rejected);
}

/* ----------------------------------------------------------------------
   The noise queue.  Interval k has length qtau[k] and, per atom, the
   Wiener increments qbuf[i][1 + k nwiener + c] (variance qtau[k] each);
   qbuf[i][0] is the ID of the atom the row was drawn for.
------------------------------------------------------------------------- */

int FixBrownianHeun::qcols() const
{
  return (adapt && nwiener > 0) ? 1 + qcap * nwiener : 0;
}

void FixBrownianHeun::ensure_queue_capacity(int n)
{
  if (n <= qcap) return;
  const int oldcols = qcols();
  qcap = std::max(n, 2 * qcap);
  double **grown = nullptr;
  const int nrows = std::max(nmax_saved, 1);
  memory->create(grown, nrows, qcols(), "brownian/heun:queue");
  for (int i = 0; i < nrows; i++) {
    for (int k = 0; k < qcols(); k++) grown[i][k] = k < oldcols && qbuf ? qbuf[i][k] : 0.0;
    if (!qbuf) grown[i][0] = -1.0;
  }
  memory->destroy(qbuf);
  qbuf = grown;
  maxexchange = ncol + qcols();
}

/* Atoms whose row was drawn for another atom (new atoms, a daughter that
   copied her mother's row) get their own increments for every interval:
   an atom that joins has nothing revealed, so fresh numbers are right. */

void FixBrownianHeun::fresh_queue_rows()
{
  const tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    if (qbuf[i][0] == static_cast<double>(tag[i])) continue;
    qbuf[i][0] = static_cast<double>(tag[i]);
    for (size_t k = 0; k < qtau.size(); k++) {
      const double s = std::sqrt(qtau[k]);
      for (int c = 0; c < nwiener; c++)
        qbuf[i][1 + k * nwiener + c] = s *
            tessera::rng::gaussian_mixed(noise_seed ^ STREAM_JOIN, tag[i], qid[k] * MAX_WIENER + c);
    }
  }
}

/* A fresh interval of length h at the end of the queue. */

void FixBrownianHeun::append_fresh(double h)
{
  ensure_queue_capacity(static_cast<int>(qtau.size()) + 1);
  const int k = static_cast<int>(qtau.size());
  const uint64_t key = draws++;
  qtau.push_back(h);
  qid.push_back(key);
  const tagint *tag = atom->tag;
  const double s = std::sqrt(h);
  for (int i = 0; i < atom->nlocal; i++)
    for (int c = 0; c < nwiener; c++)
      qbuf[i][1 + k * nwiener + c] =
          s * tessera::rng::gaussian_mixed(noise_seed ^ STREAM_DRAW, tag[i], key * MAX_WIENER + c);
}

/* Interval k becomes two, of lengths first and qtau[k] - first, with W at
   the split point from the Brownian bridge between its ends. */

void FixBrownianHeun::split_entry(int k, double first)
{
  ensure_queue_capacity(static_cast<int>(qtau.size()) + 1);
  const int n = static_cast<int>(qtau.size());
  const double tau = qtau[k];
  const double q = first / tau;
  const double sd = std::sqrt(q * (1.0 - q) * tau);
  const uint64_t key = draws++;
  const tagint *tag = atom->tag;
  for (int i = 0; i < atom->nlocal; i++) {
    double *row = qbuf[i] + 1;
    std::memmove(row + (k + 1) * nwiener, row + k * nwiener, sizeof(double) * (n - k) * nwiener);
    for (int c = 0; c < nwiener; c++) {
      const double whole = row[(k + 1) * nwiener + c];
      const double part = q * whole +
          sd * tessera::rng::gaussian_mixed(noise_seed ^ STREAM_DRAW, tag[i], key * MAX_WIENER + c);
      row[k * nwiener + c] = part;
      row[(k + 1) * nwiener + c] = whole - part;
    }
  }
  qtau.insert(qtau.begin() + k + 1, tau - first);
  qtau[k] = first;
  qid.insert(qid.begin() + k + 1, key);
}

void FixBrownianHeun::pop_queue(int n)
{
  const int total = static_cast<int>(qtau.size());
  for (int i = 0; i < atom->nlocal; i++) {
    double *row = qbuf[i] + 1;
    std::memmove(row, row + n * nwiener, sizeof(double) * (total - n) * nwiener);
  }
  qtau.erase(qtau.begin(), qtau.begin() + n);
  qid.erase(qid.begin(), qid.begin() + n);
}

/* The Wiener increments of an attempt of length h, per local atom into
   wscratch (nwiener each): the sum of the front intervals that make up h,
   after splitting or extending the queue as needed.  Sets consumed. */

void FixBrownianHeun::attempt_noise(double h)
{
  fresh_queue_rows();
  double cum = 0.0;
  int k = 0;
  for (;;) {
    if (k == static_cast<int>(qtau.size())) {
      append_fresh(h - cum);
      k++;
      break;
    }
    const double rest = h - cum;
    if (qtau[k] <= rest || same_time(qtau[k], rest)) {
      cum += qtau[k++];
      if (cum >= h || same_time(cum, h)) break;
      continue;
    }
    split_entry(k, rest);
    k++;
    break;
  }
  consumed = k;
  const int nlocal = atom->nlocal;
  wscratch.assign(static_cast<size_t>(nlocal) * nwiener, 0.0);
  for (int i = 0; i < nlocal; i++)
    for (int j = 0; j < k; j++)
      for (int c = 0; c < nwiener; c++)
        wscratch[static_cast<size_t>(i) * nwiener + c] += qbuf[i][1 + j * nwiener + c];
}

/* ----------------------------------------------------------------------
   Output: scalar the timestep of the last step; vector 1 the same, 2 the
   proposal for the next step, 3 accepted steps, 4 rejected attempts, 5 the
   last step's error estimate (length), 6 its error over the tolerance
   (with adapt; 0 without), 7 steps accepted at dtmin above the tolerance.
------------------------------------------------------------------------- */

double FixBrownianHeun::compute_scalar()
{
  return update->dt;
}

double FixBrownianHeun::compute_vector(int n)
{
  switch (n) {
    case 0:
      return update->dt;
    case 1:
      return adapt && dt_next > 0.0 ? dt_next : update->dt;
    case 2:
      return static_cast<double>(naccept);
    case 3:
      return static_cast<double>(nreject);
    case 4:
      return est_last;
    case 5:
      return err_last;
    default:
      return static_cast<double>(nforced);
  }
}

/* ----------------------------------------------------------------------
   Restart: the controller (proposal, bounds, counters, last error), the
   draw counter and the queue's intervals; per atom the queue's increments.
------------------------------------------------------------------------- */

static constexpr double RESTART_VERSION = 1.0;

void FixBrownianHeun::write_restart(FILE *fp)
{
  std::vector<double> list = {RESTART_VERSION,
                              dt_next,
                              dt_set,
                              dtmin,
                              dtmax,
                              static_cast<double>(naccept),
                              static_cast<double>(nreject),
                              static_cast<double>(nforced),
                              err_last,
                              est_last,
                              static_cast<double>(draws),
                              static_cast<double>(nwiener),
                              update->atime + (update->ntimestep - update->atimestep) * update->dt,
                              static_cast<double>(update->ntimestep),
                              static_cast<double>(qtau.size())};
  for (size_t k = 0; k < qtau.size(); k++) {
    list.push_back(qtau[k]);
    list.push_back(static_cast<double>(qid[k]));
  }
  if (comm->me == 0) {
    const int size = static_cast<int>(list.size() * sizeof(double));
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list.data(), sizeof(double), list.size(), fp);
  }
}

void FixBrownianHeun::restart(char *buf)
{
  if (!adapt) return;
  const auto *list = reinterpret_cast<const double *>(buf);
  if (list[0] != RESTART_VERSION)
    error->all(FLERR, "Fix {} (ID {}): unknown restart data version {}", style, id, list[0]);
  dt_next = list[1];
  dt_set = list[2];
  dtmin = list[3];
  dtmax = list[4];
  naccept = static_cast<bigint>(list[5]);
  nreject = static_cast<bigint>(list[6]);
  nforced = static_cast<bigint>(list[7]);
  err_last = list[8];
  est_last = list[9];
  draws = static_cast<uint64_t>(list[10]);
  nwiener = static_cast<int>(list[11]);
  // The simulated time at the restart's step: LAMMPS 29 Sep 2021 does not
  // keep it in restart files (it takes step times dt, wrong once dt varied).
  if (update->ntimestep == static_cast<bigint>(list[13])) {
    update->atime = list[12];
    update->atimestep = update->ntimestep;
  }
  const int nq = static_cast<int>(list[14]);
  qtau.clear();
  qid.clear();
  for (int k = 0; k < nq; k++) {
    qtau.push_back(list[15 + 2 * k]);
    qid.push_back(static_cast<uint64_t>(list[16 + 2 * k]));
  }
  memory->destroy(qbuf);
  qbuf = nullptr;
  qcap = nwiener > 0 ? std::max(4, nq) : 0;
  if (qcols() > 0) {
    memory->create(qbuf, std::max(nmax_saved, 1), qcols(), "brownian/heun:queue");
    for (int i = 0; i < std::max(nmax_saved, 1); i++) qbuf[i][0] = -1.0;
  }
}

int FixBrownianHeun::pack_restart(int i, double *buf)
{
  const int n = qtau.empty() ? 0 : 1 + static_cast<int>(qtau.size()) * nwiener;
  buf[0] = n + 1;
  for (int k = 0; k < n; k++) buf[1 + k] = qbuf[i][k];
  return n + 1;
}

void FixBrownianHeun::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  const int n = static_cast<int>(extra[nlocal][m]) - 1;
  m++;
  if (n <= 0 || qcols() <= 0) return;
  for (int k = 0; k < n && k < qcols(); k++) qbuf[nlocal][k] = extra[nlocal][m + k];
}

int FixBrownianHeun::size_restart(int /*nlocal*/)
{
  return 1 + (qtau.empty() ? 0 : 1 + static_cast<int>(qtau.size()) * nwiener);
}

int FixBrownianHeun::maxsize_restart()
{
  return size_restart(0);
}
