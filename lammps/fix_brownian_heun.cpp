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

   fix brownian/heun: stochastic Heun (predictor-corrector) integration of
     dr = F / gamma_t dt + sqrt(2 kT / gamma_t) dW
   and of the degrees of freedom of the CoupledDof fixes (fix polarity's
   angles), with the arguments of fix brownian (doc/fix_brownian_heun.rst).
   Per step:
     predictor  r~ = r + dt F(r)/gamma_t + w,          q~ = q + dt k(q) + w_q
     forces     at r~, q~ (ghosts updated, pair style, every fix's post_force)
     corrector  r' = r~ + dt/2 (F(r~) - F(r))/gamma_t,  q' = q~ + dt/2 (k(q~) - k(q))
   so r' = r + dt/2 (F(r) + F(r~))/gamma_t + w with the same noise w in both
   stages: second order without noise, strong order 1 and weak order 2 with
   additive noise.  The corrector's increment is the difference between the
   Heun and the Euler step, the local error estimate of the adaptive step
   ('adapt', fix_brownian_heun_adapt.cpp): a step whose estimate exceeds the
   tolerance is undone and taken again with a smaller dt.
------------------------------------------------------------------------- */

#include "fix_brownian_heun.h"

#include "coupled_dof.h"
#include "integrator_chatter.h"

#include "angle.h"
#include "atom.h"
#include "bond.h"
#include "comm.h"
#include "dihedral.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "improper.h"
#include "memory.h"
#include "modify.h"
#include "pair.h"
#include "random_mars.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

// Columns of saved: the start-of-step force (3), the attempt's noise
// displacement (3), the start position (3) and image flags (2, the low and
// high 32 bits); then the coupled rates and saved states.
enum { COL_F0 = 0, COL_W = 3, COL_X0 = 6, COL_IMG = 9, NFIXED = 11 };
// Noise drawn from the adaptive step's queue (fix_brownian_heun_adapt.cpp).
static constexpr int NOISE_QUEUE = 3;

/* Number of arguments before 'adapt' (the adaptive step's settings come
   last), which the base class parses. */

static int args_before_adapt(int narg, char **arg)
{
  for (int i = 5; i < narg; i++)
    if (strcmp(arg[i], "adapt") == 0) return i;
  return narg;
}

/* ---------------------------------------------------------------------- */

FixBrownianHeun::FixBrownianHeun(LAMMPS *lmp, int narg, char **arg) :
    FixBrownianTessera(lmp, args_before_adapt(narg, arg), arg), saved(nullptr), ncol(NFIXED),
    nmax_saved(0), col_k1(NFIXED), col_q0(NFIXED), ncoupled(0), nstate(0), nwiener_coupled(0),
    adapt(0), tol(0.0), tol_angle(0.0), dtmin(0.0), dtmax(-1.0), safety(0.9), grow_max(2.0),
    shrink_min(0.2), dt_next(-1.0), dt_set(-1.0), naccept(0), nreject(0), nforced(0), err_last(0.0),
    est_last(0.0), forced_warned(0), qbuf(nullptr), qcap(0), nwiener(0), draws(0), noise_seed(0),
    diffusion_amp(0.0), consumed(0)
{
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 7;
  global_freq = 1;
  extscalar = 0;
  extvector = 0;
  const int first = args_before_adapt(narg, arg);
  if (first < narg) parse_adapt(narg - first, arg + first);
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  if (adapt) {
    create_attribute = 1;
    restart_global = 1;
    restart_peratom = 1;
    atom->add_callback(Atom::RESTART);
  }
}

/* ---------------------------------------------------------------------- */

FixBrownianHeun::~FixBrownianHeun()
{
  atom->delete_callback(id, Atom::GROW);
  if (adapt) atom->delete_callback(id, Atom::RESTART);
  memory->destroy(saved);
  memory->destroy(qbuf);
}

/* ---------------------------------------------------------------------- */

int FixBrownianHeun::setmask()
{
  return INITIAL_INTEGRATE;
}

/* ----------------------------------------------------------------------
   The coupled fixes are found anew at every run, so that a fix polarity
   defined (or deleted) between runs is picked up.
------------------------------------------------------------------------- */

void FixBrownianHeun::init()
{
  FixBrownianTessera::init();
  if (force->kspace)
    error->all(FLERR,
               "Fix {} (ID {}): a kspace style is not supported (the predictor's force "
               "computation leaves it out)",
               style, id);
  coupled.clear();
  coupled_offset.clear();
  state_offset.clear();
  wiener_offset.clear();
  ncoupled = nstate = nwiener_coupled = 0;
  for (int i = 0; i < modify->nfix; i++) {
    int dim = 0;
    auto *c = static_cast<CoupledDof *>(modify->fix[i]->extract(CoupledDof::extract_name, dim));
    if (!c) continue;
    coupled.push_back(c);
    coupled_offset.push_back(ncoupled);
    state_offset.push_back(nstate);
    wiener_offset.push_back(nwiener_coupled);
    ncoupled += c->coupled_size();
    if (adapt) {
      const int ns = c->coupled_state_size();
      if (ns <= 0)
        error->all(FLERR,
                   "Fix {} (ID {}): with 'adapt' a rejected step restores every degree of "
                   "freedom, but fix {} ({}) cannot save its state; leave out 'adapt'",
                   style, id, modify->fix[i]->id, modify->fix[i]->style);
      nstate += ns;
      nwiener_coupled += c->coupled_wiener_size();
    }
  }
  const int newcol = NFIXED + ncoupled + nstate;
  if (newcol != ncol) {
    // (per-step values only: nothing to keep across runs)
    memory->destroy(saved);
    saved = nullptr;
    ncol = newcol;
    memory->create(saved, std::max(nmax_saved, 1), ncol, "brownian/heun:saved");
  }
  col_k1 = NFIXED;
  col_q0 = NFIXED + ncoupled;
  if (adapt) init_adapt();
}

/* ----------------------------------------------------------------------
   At the start of a run v becomes the drift velocity F/gamma_t of the
   initial state (nothing of this fix depends on the v stored before), so
   that a fix dt/reset defined after this fix picks its first timestep from
   the cells' actual speeds rather than from v = 0.
------------------------------------------------------------------------- */

void FixBrownianHeun::setup(int /*vflag*/)
{
  drift_velocity();
  if (adapt) setup_adapt();
}

/* ----------------------------------------------------------------------
   One step: the rates and state at the start, then attempts (predictor,
   forces at the predicted state, corrector increments) until one is
   accepted; without 'adapt' the first one is.
------------------------------------------------------------------------- */

void FixBrownianHeun::initial_integrate(int /*vflag*/)
{
  if (adapt) begin_adaptive_step();
  if (!(update->dt > 0.0))
    error->all(FLERR,
               "Fix {} (ID {}): the timestep must be > 0 to take a step, got {}; set it with "
               "'timestep'",
               style, id, update->dt);
  const bool three_d = domain->dimension == 3;
  const bigint step = update->ntimestep;

  chatter->begin(groupbit);
  save_start();
  // Coupled degrees of freedom: every rate at the start state before any
  // of them moves (and, for a rejected step, their state).
  if (!coupled.empty()) drift_velocity();
  double *base = saved ? saved[0] : nullptr;
  for (size_t c = 0; c < coupled.size(); c++) {
    coupled[c]->coupled_rate(base + col_k1 + coupled_offset[c], ncol, step - 1);
    if (adapt) coupled[c]->coupled_save(base + col_q0 + state_offset[c], ncol);
  }

  bool rejected = false;
  double err = 0.0, est = 0.0;
  for (;;) {
    if (adapt && nwiener > 0) attempt_noise(dt);
    predict_coupled();
    if (adapt) {
      if (diffusion_amp > 0.0)
        three_d ? predict<NOISE_QUEUE, 1>() : predict<NOISE_QUEUE, 0>();
      else
        three_d ? predict<NOISE_NONE, 1>() : predict<NOISE_NONE, 0>();
    } else {
      switch (noise) {
        case NOISE_UNIFORM:
          three_d ? predict<NOISE_UNIFORM, 1>() : predict<NOISE_UNIFORM, 0>();
          break;
        case NOISE_GAUSSIAN:
          three_d ? predict<NOISE_GAUSSIAN, 1>() : predict<NOISE_GAUSSIAN, 0>();
          break;
        default:
          three_d ? predict<NOISE_NONE, 1>() : predict<NOISE_NONE, 0>();
      }
    }

    force_at_predicted_state();
    corrector_coupled(step);
    err = error_ratio(est);
    if (!adapt || accept(err)) break;
    // Undo the attempt and take it again with a smaller step.
    restore_start();
    nreject++;
    rejected = true;
    set_timestep(controller(dt, err, true));
  }

  for (size_t c = 0; c < coupled.size(); c++)
    coupled[c]->coupled_advance(scratch.data() + coupled_offset[c], ncoupled);
  three_d ? correct<1>() : correct<0>();
  naccept++;
  est_last = est;
  err_last = err;
  if (adapt) finish_adaptive_step(err, rejected);
  chatter->end(style, id, groupbit, dt);
}

/* ----------------------------------------------------------------------
   The start of the step, kept for the predictor and, with 'adapt', for
   undoing a rejected attempt: the force, the position and image flags.
------------------------------------------------------------------------- */

void FixBrownianHeun::save_start()
{
  double **x = atom->x;
  double **f = atom->f;
  const imageint *image = atom->image;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int d = 0; d < 3; d++) {
      saved[i][COL_F0 + d] = f[i][d];
      saved[i][COL_X0 + d] = x[i][d];
    }
    const auto im = static_cast<uint64_t>(image[i]);
    saved[i][COL_IMG] = static_cast<double>(im & 0xffffffffULL);
    saved[i][COL_IMG + 1] = static_cast<double>(im >> 32);
  }
}

/* ----------------------------------------------------------------------
   Predictor of the coupled degrees of freedom: q~ = q + dt k1 + w_q, the
   noise from the coupled fix (fixed step) or from the queue (adapt).
------------------------------------------------------------------------- */

void FixBrownianHeun::predict_coupled()
{
  if (coupled.empty()) return;
  const int nlocal = atom->nlocal;
  scratch.assign(static_cast<size_t>(nlocal) * ncoupled, 0.0);
  for (size_t c = 0; c < coupled.size(); c++) {
    const int off = coupled_offset[c], n = coupled[c]->coupled_size();
    double *w = scratch.data() + off;
    if (!adapt)
      coupled[c]->coupled_noise(w, ncoupled);
    else if (coupled[c]->coupled_wiener_size() > 0)
      coupled[c]->coupled_wiener_increment(
          wscratch.data() + (nwiener - nwiener_coupled) + wiener_offset[c], nwiener, w, ncoupled);
    for (int i = 0; i < nlocal; i++)
      for (int k = 0; k < n; k++) w[i * ncoupled + k] += dt * saved[i][col_k1 + off + k];
  }
  for (size_t c = 0; c < coupled.size(); c++)
    coupled[c]->coupled_advance(scratch.data() + coupled_offset[c], ncoupled);
}

/* ----------------------------------------------------------------------
   The coupled corrector increments dt/2 (k2 - k1) into scratch (atoms may
   have been exchanged by the force computation), not applied yet.
------------------------------------------------------------------------- */

void FixBrownianHeun::corrector_coupled(bigint step)
{
  if (coupled.empty()) return;
  const int nlocal = atom->nlocal;
  drift_velocity();
  scratch.assign(static_cast<size_t>(nlocal) * ncoupled, 0.0);
  for (size_t c = 0; c < coupled.size(); c++)
    coupled[c]->coupled_rate(scratch.data() + coupled_offset[c], ncoupled, step);
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < ncoupled; k++)
      scratch[i * ncoupled + k] = 0.5 * dt * (scratch[i * ncoupled + k] - saved[i][col_k1 + k]);
}

/* ----------------------------------------------------------------------
   The local error estimate of the attempt, the largest difference between
   the Heun and the Euler step of any atom (over all ranks): |dr| of the
   position's corrector, over tol, and |dq| of each coupled fix's corrector
   (per atom, the norm over its degrees of freedom), over tol_angle.
   Returns the larger ratio (without 'adapt' the position's only, for
   output); est is the position's estimate in length units.  A non-finite
   estimate counts as infinite.
------------------------------------------------------------------------- */

double FixBrownianHeun::error_ratio(double &est)
{
  double **f = atom->f;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int ndim = domain->dimension;
  const double half = 0.5 * dt * mobility;
  double local[2] = {0.0, 0.0};
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double s = 0.0;
    for (int d = 0; d < ndim; d++) {
      const double dr = half * (f[i][d] - saved[i][COL_F0 + d]);
      s += dr * dr;
    }
    const double e = std::sqrt(s);
    if (!(e <= local[0])) local[0] = std::isfinite(e) ? e : INFINITY;
  }
  for (size_t c = 0; adapt && c < coupled.size(); c++) {
    const int off = coupled_offset[c], n = coupled[c]->coupled_size();
    for (int i = 0; i < nlocal; i++) {
      double s = 0.0;
      for (int k = 0; k < n; k++) {
        const double dq = scratch[i * ncoupled + off + k];
        s += dq * dq;
      }
      const double e = std::sqrt(s);
      if (!(e <= local[1])) local[1] = std::isfinite(e) ? e : INFINITY;
    }
  }
  double all[2];
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_MAX, world);
  est = all[0];
  if (!adapt) return 0.0;
  return std::max(all[0] / tol, all[1] / tol_angle);
}

/* ----------------------------------------------------------------------
   Undo a rejected attempt: positions and image flags of the start of the
   step, the coupled fixes' state, the start force (the predictor's); the
   atoms are where the attempt's force computation left them (it may have
   exchanged them), their saved rows with them.
------------------------------------------------------------------------- */

void FixBrownianHeun::restore_start()
{
  double **x = atom->x;
  double **f = atom->f;
  imageint *image = atom->image;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int d = 0; d < 3; d++) {
      x[i][d] = saved[i][COL_X0 + d];
      f[i][d] = saved[i][COL_F0 + d];
    }
    const auto lo = static_cast<uint64_t>(saved[i][COL_IMG]);
    const auto hi = static_cast<uint64_t>(saved[i][COL_IMG + 1]);
    image[i] = static_cast<imageint>(lo | (hi << 32));
  }
  double *base = saved ? saved[0] : nullptr;
  for (size_t c = 0; c < coupled.size(); c++)
    coupled[c]->coupled_restore(base + col_q0 + state_offset[c], ncol);
}

/* ----------------------------------------------------------------------
   Predictor: r~ = r + dt mobility F0 + w, noise drawn as in fix brownian
   (per atom in the order x, y (, z)) or, with 'adapt', sqrt(2 D) times the
   queue's Wiener increments; v = (r~ - r)/dt for the fixes that look at
   velocities at the predicted state.
------------------------------------------------------------------------- */

template <int NOISE, int THREE_D> void FixBrownianHeun::predict()
{
  double **x = atom->x;
  double **v = atom->v;
  int *mask = atom->mask;
  int nlocal = atom->nlocal;
  if (igroup == atom->firstgroup) nlocal = atom->nfirst;

  const int ndim = THREE_D ? 3 : 2;
  const double drift = dt * mobility;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int d = 0; d < 3; d++) saved[i][COL_W + d] = 0.0;
    for (int d = 0; d < ndim; d++) {
      double w = 0.0;
      if (NOISE == NOISE_UNIFORM)
        w = noise_scale * (random->uniform() - 0.5);
      else if (NOISE == NOISE_GAUSSIAN)
        w = noise_scale * random->gaussian();
      else if (NOISE == NOISE_QUEUE)
        w = diffusion_amp * wscratch[static_cast<size_t>(i) * nwiener + d];
      saved[i][COL_W + d] = w;
      const double dr = drift * saved[i][COL_F0 + d] + w;
      x[i][d] += dr;
      v[i][d] = dr / dt;
    }
    if (!THREE_D) v[i][2] = 0.0;
  }
}

/* ----------------------------------------------------------------------
   v = F / gamma_t, the velocity of the current state without noise, which
   the coupled fixes see (fix polarity's velocity alignment); the step's
   own velocity (r' - r)/dt replaces it at the end of the step.
------------------------------------------------------------------------- */

void FixBrownianHeun::drift_velocity()
{
  double **v = atom->v;
  double **f = atom->f;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int ndim = domain->dimension;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int d = 0; d < ndim; d++) v[i][d] = mobility * f[i][d];
    if (ndim == 2) v[i][2] = 0.0;
  }
}

/* ----------------------------------------------------------------------
   Corrector: r' = r~ + dt/2 mobility (F(r~) - F(r)); v = (r' - r)/dt.
------------------------------------------------------------------------- */

template <int THREE_D> void FixBrownianHeun::correct()
{
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  int *mask = atom->mask;
  int nlocal = atom->nlocal;
  if (igroup == atom->firstgroup) nlocal = atom->nfirst;

  const int ndim = THREE_D ? 3 : 2;
  const double half = 0.5 * dt * mobility;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int d = 0; d < ndim; d++) {
      x[i][d] += half * (f[i][d] - saved[i][COL_F0 + d]);
      v[i][d] = 0.5 * mobility * (saved[i][COL_F0 + d] + f[i][d]) + saved[i][COL_W + d] / dt;
    }
    if (!THREE_D) v[i][2] = 0.0;
  }
}

/* ----------------------------------------------------------------------
   The forces at the predicted positions, as a step of run computes them
   between the integrator's two halves: ghost positions (and, with atom
   style dipole, moments) from their owners, forces cleared, the pair
   style (which tessellates the predicted positions) and bonded styles,
   ghost forces back to their owners, and every fix's pre_force,
   pre_reverse and post_force (fix polarity's active force at the
   predicted polarity, fix addforce, ...).  Energy and virial are not
   tallied here: the step's own force computation at its end does that.
------------------------------------------------------------------------- */

void FixBrownianHeun::force_at_predicted_state()
{
  comm->forward_comm();

  const int nlocal = atom->nlocal;
  const int nclear = nlocal + (force->newton ? atom->nghost : 0);
  if (nclear > 0) {
    memset(&atom->f[0][0], 0, sizeof(double) * 3 * nclear);
    if (atom->torque_flag) memset(&atom->torque[0][0], 0, sizeof(double) * 3 * nclear);
  }

  modify->pre_force(0);
  if (force->pair) force->pair->compute(0, 0);
  if (force->bond) force->bond->compute(0, 0);
  if (force->angle) force->angle->compute(0, 0);
  if (force->dihedral) force->dihedral->compute(0, 0);
  if (force->improper) force->improper->compute(0, 0);
  modify->pre_reverse(0, 0);
  if (force->newton) comm->reverse_comm();
  modify->post_force(0);
}

/* ----------------------------------------------------------------------
   Per-atom storage that follows atoms through exchanges: saved (this
   step's values) and, with a noise queue, qbuf (the revealed Wiener
   increments, which outlive the step).
------------------------------------------------------------------------- */

double FixBrownianHeun::memory_usage()
{
  return static_cast<double>(nmax_saved) * (ncol + qcols()) * sizeof(double) +
      (scratch.capacity() + wscratch.capacity()) * sizeof(double);
}

void FixBrownianHeun::grow_arrays(int nmax)
{
  memory->grow(saved, nmax, ncol, "brownian/heun:saved");
  if (qcols() > 0) {
    const int old = nmax_saved;
    memory->grow(qbuf, nmax, qcols(), "brownian/heun:queue");
    for (int i = old; i < nmax; i++) qbuf[i][0] = -1.0;    // no owner yet
  }
  nmax_saved = nmax;
}

void FixBrownianHeun::copy_arrays(int i, int j, int /*delflag*/)
{
  for (int k = 0; k < ncol; k++) saved[j][k] = saved[i][k];
  for (int k = 0; k < qcols(); k++) qbuf[j][k] = qbuf[i][k];
}

void FixBrownianHeun::set_arrays(int i)
{
  if (qcols() > 0) qbuf[i][0] = -1.0;
}

int FixBrownianHeun::pack_exchange(int i, double *buf)
{
  for (int k = 0; k < ncol; k++) buf[k] = saved[i][k];
  for (int k = 0; k < qcols(); k++) buf[ncol + k] = qbuf[i][k];
  return ncol + qcols();
}

int FixBrownianHeun::unpack_exchange(int nlocal, double *buf)
{
  for (int k = 0; k < ncol; k++) saved[nlocal][k] = buf[k];
  for (int k = 0; k < qcols(); k++) qbuf[nlocal][k] = buf[ncol + k];
  return ncol + qcols();
}

/* Tells the CoupledDof fixes (fix polarity) that this fix integrates their
   degrees of freedom (coupled_dof.h). */

void *FixBrownianHeun::extract(const char *name, int &dim)
{
  dim = 0;
  return strcmp(name, CoupledDof::integrator_name) == 0 ? this : nullptr;
}
