// Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
//
// fix brownian/heun: stochastic Heun (predictor-corrector) integration of
//   dr = F / gamma_t dt + sqrt(2 kT / gamma_t) dW
// and of the degrees of freedom of the CoupledDof fixes (fix polarity's
// angles), with the arguments of fix brownian (doc/fix_brownian_heun.rst).
// Per step:
//   predictor  r~ = r + dt F(r)/gamma_t + w,          q~ = q + dt k(q) + w_q
//   forces     at r~, q~ (ghosts updated, pair style, every fix's post_force)
//   corrector  r' = r~ + dt/2 (F(r~) - F(r))/gamma_t,  q' = q~ + dt/2 (k(q~) - k(q))
// so r' = r + dt/2 (F(r) + F(r~))/gamma_t + w with the same noise w in both
// stages: second order without noise, strong order 1 and weak order 2 with
// additive noise.

#include "fix_brownian_heun.h"

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

#include <cstring>

using namespace LAMMPS_NS;

static constexpr int NSAVED = 6;    // start-of-step force (3) and noise displacement (3)

/* ---------------------------------------------------------------------- */

FixBrownianHeun::FixBrownianHeun(LAMMPS *lmp, int narg, char **arg) :
    FixBrownianTessera(lmp, narg, arg), saved(nullptr), ncol(NSAVED), nmax_saved(0),
    ncoupled(0)
{
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
}

/* ---------------------------------------------------------------------- */

FixBrownianHeun::~FixBrownianHeun()
{
  atom->delete_callback(id, Atom::GROW);
  memory->destroy(saved);
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
  ncoupled = 0;
  for (int i = 0; i < modify->nfix; i++) {
    auto *c = dynamic_cast<CoupledDof *>(modify->fix[i]);
    if (!c) continue;
    coupled.push_back(c);
    coupled_offset.push_back(ncoupled);
    ncoupled += c->coupled_size();
  }
  if (ncol != NSAVED + ncoupled) {
    memory->destroy(saved);
    saved = nullptr;
    ncol = NSAVED + ncoupled;
    grow_arrays(atom->nmax);
  }
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
}

/* ---------------------------------------------------------------------- */

void FixBrownianHeun::initial_integrate(int /*vflag*/)
{
  if (!(update->dt > 0.0))
    error->all(FLERR,
               "Fix {} (ID {}): the timestep must be > 0 to take a step, got {}; set it with "
               "'timestep'",
               style, id, update->dt);
  const bool three_d = domain->dimension == 3;
  const bigint step = update->ntimestep;

  // Coupled degrees of freedom, predictor: every rate at the start state
  // before any of them moves.
  chatter.begin(groupbit);
  int nlocal = atom->nlocal;
  double *base = saved ? saved[0] : nullptr;
  if (!coupled.empty()) drift_velocity();
  for (size_t c = 0; c < coupled.size(); c++)
    coupled[c]->coupled_rate(base + NSAVED + coupled_offset[c], ncol, step - 1);
  scratch.assign(static_cast<size_t>(nlocal) * (ncoupled > 0 ? ncoupled : 1), 0.0);
  for (size_t c = 0; c < coupled.size(); c++) {
    const int off = coupled_offset[c], n = coupled[c]->coupled_size();
    double *w = scratch.data() + off;
    coupled[c]->coupled_noise(w, ncoupled);
    for (int i = 0; i < nlocal; i++)
      for (int k = 0; k < n; k++) w[i * ncoupled + k] += dt * saved[i][NSAVED + off + k];
  }
  for (size_t c = 0; c < coupled.size(); c++)
    coupled[c]->coupled_advance(scratch.data() + coupled_offset[c], ncoupled);

  // Positions, predictor.
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

  force_at_predicted_state();

  // Coupled degrees of freedom, corrector (atoms may have been exchanged).
  nlocal = atom->nlocal;
  if (!coupled.empty()) drift_velocity();
  scratch.assign(static_cast<size_t>(nlocal) * (ncoupled > 0 ? ncoupled : 1), 0.0);
  for (size_t c = 0; c < coupled.size(); c++)
    coupled[c]->coupled_rate(scratch.data() + coupled_offset[c], ncoupled, step);
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < ncoupled; k++)
      scratch[i * ncoupled + k] = 0.5 * dt * (scratch[i * ncoupled + k] - saved[i][NSAVED + k]);
  for (size_t c = 0; c < coupled.size(); c++)
    coupled[c]->coupled_advance(scratch.data() + coupled_offset[c], ncoupled);

  three_d ? correct<1>() : correct<0>();
  chatter.end(style, id, groupbit, dt);
}

/* ----------------------------------------------------------------------
   Predictor: r~ = r + dt mobility F + w, noise drawn as in fix brownian
   (per atom in the order x, y (, z)), v = (r~ - r)/dt for the fixes that
   look at velocities at the predicted state.
------------------------------------------------------------------------- */

template <int NOISE, int THREE_D> void FixBrownianHeun::predict()
{
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  int *mask = atom->mask;
  int nlocal = atom->nlocal;
  if (igroup == atom->firstgroup) nlocal = atom->nfirst;

  const int ndim = THREE_D ? 3 : 2;
  const double drift = dt * mobility;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    for (int d = 0; d < 3; d++) saved[i][d] = saved[i][3 + d] = 0.0;
    for (int d = 0; d < ndim; d++) {
      double w = 0.0;
      if (NOISE == NOISE_UNIFORM)
        w = noise_scale * (random->uniform() - 0.5);
      else if (NOISE == NOISE_GAUSSIAN)
        w = noise_scale * random->gaussian();
      saved[i][d] = f[i][d];
      saved[i][3 + d] = w;
      const double dr = drift * f[i][d] + w;
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
      x[i][d] += half * (f[i][d] - saved[i][d]);
      v[i][d] = 0.5 * mobility * (saved[i][d] + f[i][d]) + saved[i][3 + d] / dt;
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
   Per-atom storage that follows atoms through exchanges.
------------------------------------------------------------------------- */

double FixBrownianHeun::memory_usage()
{
  return static_cast<double>(nmax_saved) * ncol * sizeof(double) +
      scratch.capacity() * sizeof(double);
}

void FixBrownianHeun::grow_arrays(int nmax)
{
  memory->grow(saved, nmax, ncol, "brownian/heun:saved");
  nmax_saved = nmax;
}

void FixBrownianHeun::copy_arrays(int i, int j, int /*delflag*/)
{
  for (int k = 0; k < ncol; k++) saved[j][k] = saved[i][k];
}

int FixBrownianHeun::pack_exchange(int i, double *buf)
{
  for (int k = 0; k < ncol; k++) buf[k] = saved[i][k];
  return ncol;
}

int FixBrownianHeun::unpack_exchange(int nlocal, double *buf)
{
  for (int k = 0; k < ncol; k++) saved[nlocal][k] = buf[k];
  return ncol;
}
