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

   fix polarity: active force f_a n_i along each cell's polarity and the
   overdamped dynamics of the polarity angle (neighbour, groove and velocity
   alignment, rotational noise).  The polarity is the direction of the dipole
   moment mu, so it migrates with atoms, goes to ghosts and into restarts.
------------------------------------------------------------------------- */

#include "fix_polarity.h"

#include "coupled_dof.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "math_const.h"
#include "modify.h"
#include "cell_source.h"
#include "citeme.h"
#include "tessera_citations.h"
#include "update.h"

#include "tessera/counter_rng.h"
#include "tessera/polarity.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {

// Counter-based random numbers (tessera/counter_rng.h): a value depends
// only on (seed, atom ID, timestep, stream), not on the rank or the order of
// atoms (runs on other rank counts and restarts then agree to round-off; see
// the doc).
using tessera::rng::gaussian_mixed;
using tessera::rng::mix;
using tessera::rng::uniform01;

// Whether the n rows of a LAMMPS per-atom array (stride values each) are one
// block, as memory->create allocates them.
inline bool one_block(double **a, int n, int stride)
{
  return n <= 0 || a[n - 1] == a[0] + stride * static_cast<long>(n - 1);
}

}    // namespace

/* ----------------------------------------------------------------------
   fix ID group polarity f_a|d_name gamma_R [neighbor J_S] [groove J_G phi]
                                     [velocity J_V] [noise D_r seed] [seed S]
------------------------------------------------------------------------- */

struct FixPolarity::Impl {
  tessera::PolarityParams params;
  tessera::Tessellation none;
};

FixPolarity::FixPolarity(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), impl(new Impl), params(impl->params), d_rot(0.0), seed(0), pair(nullptr),
    none(impl->none)
{
  if (lmp->citeme) lmp->citeme->add(tessera_cite::thesis);
  if (narg < 5)
    error->all(FLERR,
               "Illegal fix polarity command: expected 'fix ID group polarity f_a gamma_R "
               "[neighbor J_S] [groove J_G phi] [velocity J_V] [noise D_r seed] [seed S]'");
  // f_a: a number, or d_name, a per-atom property giving each cell's own.
  if (strncmp(arg[3], "d_", 2) == 0) {
    if (!arg[3][2])
      error->all(FLERR,
                 "fix polarity: active force 'd_' names no per-atom property; give a "
                 "number or d_name (fix property/atom d_name)");
    fa_name = arg[3] + 2;
    f_active = 0.0;
  } else {
    f_active = utils::numeric(FLERR, arg[3], false, lmp);
  }
  gamma_r = utils::numeric(FLERR, arg[4], false, lmp);
  if (!std::isfinite(f_active))
    error->all(FLERR, "fix polarity: active force f_a must be finite, got {}", arg[3]);
  if (!(gamma_r > 0.0) || !std::isfinite(gamma_r))
    error->all(FLERR, "fix polarity: rotational friction gamma_R must be > 0, got {}", arg[4]);

  int seed_given = 0;
  int iarg = 5;
  // Keyword at arg[iarg] takes n values.
  auto need = [&](int n, const char *usage) {
    if (iarg + n + 1 > narg) error->all(FLERR, "fix polarity: keyword {}", usage);
  };
  while (iarg < narg) {
    if (strcmp(arg[iarg], "neighbor") == 0) {
      need(1, "'neighbor' needs a value: neighbor J_S");
      params.J_S = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      iarg += 2;
    } else if (strcmp(arg[iarg], "groove") == 0) {
      need(2, "'groove' needs two values: groove J_G phi (phi in degrees from the x axis)");
      params.J_G = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      params.phi_G = utils::numeric(FLERR, arg[iarg + 2], false, lmp) * MathConst::MY_PI / 180.0;
      iarg += 3;
    } else if (strcmp(arg[iarg], "velocity") == 0) {
      need(1, "'velocity' needs a value: velocity J_V");
      params.J_V = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      iarg += 2;
    } else if (strcmp(arg[iarg], "noise") == 0) {
      need(2, "'noise' needs two values: noise D_r seed");
      d_rot = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      seed = utils::inumeric(FLERR, arg[iarg + 2], false, lmp);
      if (d_rot < 0.0)
        error->all(FLERR, "fix polarity: rotational diffusion D_r must be >= 0, got {}",
                   arg[iarg + 1]);
      if (seed <= 0)
        error->all(FLERR, "fix polarity: noise seed must be > 0, got {}", arg[iarg + 2]);
      seed_given = 1;
      iarg += 3;
    } else if (strcmp(arg[iarg], "seed") == 0) {
      need(1, "'seed' needs a value: seed S (for the initial random angles)");
      seed = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (seed <= 0) error->all(FLERR, "fix polarity: seed must be > 0, got {}", arg[iarg + 1]);
      seed_given = 1;
      iarg += 2;
    } else {
      error->all(FLERR,
                 "fix polarity: unknown keyword '{}' (known: neighbor, groove, velocity, noise, "
                 "seed)",
                 arg[iarg]);
    }
  }
  for (double v : {params.J_S, params.J_G, params.J_V, params.phi_G})
    if (!std::isfinite(v)) error->all(FLERR, "fix polarity: alignment moduli must be finite");
  if (!seed_given) seed = 12345;

  if (!atom->mu_flag)
    error->all(FLERR,
               "fix polarity: the polarity is stored in the dipole moment mu, which this atom "
               "style lacks; use 'atom_style dipole' or 'atom_style hybrid sphere dipole'");

  vector_flag = 1;
  size_vector = 2;
  global_freq = 1;
  extvector = 0;
  dynamic_group_allow = 1;
}

int FixPolarity::setmask()
{
  int mask = 0;
  mask |= POST_FORCE;
  mask |= INITIAL_INTEGRATE;
  return mask;
}

void FixPolarity::init()
{
  fa_index = -1;
  if (!fa_name.empty()) {
    int flag = -1, cols = -1;
    fa_index = atom->find_custom(fa_name.c_str(), flag, cols);
    if (fa_index < 0 || flag != 1 || cols != 0)
      error->all(FLERR,
                 "fix polarity {}: active force d_{} is no per-atom double property; define it "
                 "with 'fix ID all property/atom d_{}' and give every cell a value with 'set'",
                 id, fa_name, fa_name);
  }

  pair = CellSource::find(lmp);
  if (!pair && params.J_S != 0.0)
    error->all(FLERR,
               "fix polarity: 'neighbor' alignment needs pair_style vertex/voronoi or "
               "vertex/polygon, whose cells give the neighbours");
  if (domain->dimension == 3)
    init_angles_3d();
  else
    init_angles();
  // Cells on a sphere: no direction in space is tangent everywhere.
  if (pair && pair->on_sphere() && params.J_G != 0.0)
    error->all(FLERR,
               "fix polarity {}: 'groove' alignment has no meaning for cells on a sphere (the "
               "groove is a fixed direction in space, tangent to the sphere only along one great "
               "circle); leave out 'groove' (neighbor, velocity and noise work on the sphere)",
               id);
  find_driver();
  if (!(update->dt >= 0.0) || !std::isfinite(update->dt))
    error->all(FLERR,
               "fix polarity {}: the timestep must be > 0 (rotational noise sqrt(2 D_r dt), "
               "turn dt/gamma_R torque), got {}; set it with 'timestep'",
               id, update->dt);
}

int FixPolarity::coupled_size() const
{
  return domain->dimension == 3 ? 3 : 1;
}

/* Atoms with mu = 0 get a uniformly random polarity angle (thesis 4.1.4: a
   biased start biases the streams).  The angle depends only on the seed and
   the atom's position (not on its ID, which create_atoms assigns differently
   on different numbers of ranks), so a script starts alike on any number of
   ranks. */

void FixPolarity::init_angles()
{
  double **mu = atom->mu;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    if (mu[i][3] > 0.0) {
      // Keep the direction, but polarity lives in the plane.
      const double s = std::hypot(mu[i][0], mu[i][1]);
      if (s > 0.0) {
        mu[i][0] *= mu[i][3] / s;
        mu[i][1] *= mu[i][3] / s;
        mu[i][2] = 0.0;
        continue;
      }
    }
    uint64_t bx, by;
    std::memcpy(&bx, &atom->x[i][0], sizeof bx);
    std::memcpy(&by, &atom->x[i][1], sizeof by);
    const double th = MathConst::MY_2PI * uniform01(seed, mix(bx) ^ by, 0, 3);
    mu[i][0] = std::cos(th);
    mu[i][1] = std::sin(th);
    mu[i][2] = 0.0;
    mu[i][3] = 1.0;
  }
}

/* Cells that appeared since the last step (fix deposit, fix pour, create_atoms
   between runs, cell division) with mu = 0 in the plane get a uniformly
   random angle from the seed and their atom ID, owned and ghost copies alike
   (a ghost's image position differs from its owner's, its ID does not), so
   every copy agrees without communication.  A non-zero mu (set by whatever
   created the cell) is kept. */

void FixPolarity::fresh_angles(int from, int to)
{
  const int *mask = atom->mask;
  double **mu = atom->mu;
  for (int i = from; i < to; i++)
    if ((mask[i] & groupbit) && mu[i][0] == 0.0 && mu[i][1] == 0.0) fresh_angle(i);
}

void FixPolarity::fresh_angle(int i)
{
  double *m_i = atom->mu[i];
  const double th = MathConst::MY_2PI * uniform01(seed, atom->tag[i], 0, 5);
  const double m = m_i[3] > 0.0 ? m_i[3] : 1.0;
  m_i[0] = m * std::cos(th);
  m_i[1] = m * std::sin(th);
  m_i[2] = 0.0;
  m_i[3] = m;
}

/* unit[2 i .. 2 i + 1] = mu_i / |mu_i| (0 where |mu_i| = 0) of the owned and
   ghost atoms, after fresh_angles() of each (one pass).  |mu| is nearly
   always exactly 1, where mu itself is the unit vector: the division is
   skipped (x / 1 = x exactly, so the values are the same). */

void FixPolarity::unit_polarities()
{
  const int nall = atom->nlocal + atom->nghost;
  const int *mask = atom->mask;
  double **mu = atom->mu;
  unit.resize(2 * static_cast<size_t>(nall));
  double *u = unit.data();
  auto pass = [&](auto row) {
    for (int i = 0; i < nall; i++) {
      const double *m_i = row(i);
      if (m_i[0] == 0.0 && m_i[1] == 0.0 && (mask[i] & groupbit)) fresh_angle(i);
      const double len = m_i[3];
      if (len == 1.0) {
        u[2 * i] = m_i[0];
        u[2 * i + 1] = m_i[1];
      } else {
        const double inv = len > 0.0 ? 1.0 / len : 0.0;
        u[2 * i] = m_i[0] * inv;
        u[2 * i + 1] = m_i[1] * inv;
      }
    }
  };
  // Rows of one block (LAMMPS's memory->create): index it directly rather
  // than through the row pointers (one memory stream less).
  if (nall > 0 && one_block(mu, nall, 4))
    pass([m0 = mu[0]](int i) {
      return m0 + 4 * static_cast<long>(i);
    });
  else
    pass([mu](int i) {
      return mu[i];
    });
}

void FixPolarity::setup(int vflag)
{
  post_force(vflag);
}

/* Adds the active force along the current polarity, and notes the
   direction of each cell's velocity (dr/dt of the step that just ended) for
   the next angle update, before an integrator overwrites v. */

void FixPolarity::post_force(int /*vflag*/)
{
  record_contacts();
  if (domain->dimension == 3) {
    post_force_3d();
    return;
  }
  double **mu = atom->mu;
  double **f = atom->f;
  double **v = atom->v;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  fresh_angles(nlocal, nlocal + atom->nghost);    // the owned ones in the loop below
  has_v.resize(nlocal);
  if (params.J_V != 0.0) {    // only velocity alignment needs the directions
    vhat.resize(2 * static_cast<size_t>(nlocal));
    for (int i = 0; i < nlocal; i++) {
      const double s = std::sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1]);
      has_v[i] = s > 0.0;
      vhat[2 * i] = has_v[i] ? v[i][0] / s : 0.0;
      vhat[2 * i + 1] = has_v[i] ? v[i][1] / s : 0.0;
    }
  }
  // Without J_V, has_v stays all 0 (resize() value-initialises what it adds,
  // and nothing else writes it then) and vhat is not read.
  auto pass = [&](auto row_mu, auto row_f) {
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      double *m_i = row_mu(i);
      if (m_i[0] == 0.0 && m_i[1] == 0.0) fresh_angle(i);
      const double len = m_i[3];
      if (!(len > 0.0)) continue;
      const double fa = fa_index < 0 ? f_active : active_force(i);
      const double inv = len == 1.0 ? fa : fa / len;    // the same value
      double *f_i = row_f(i);
      f_i[0] += inv * m_i[0];
      f_i[1] += inv * m_i[1];
    }
  };
  if (nlocal > 0 && one_block(mu, nlocal, 4) && one_block(f, nlocal, 3))
    pass(
        [m0 = mu[0]](int i) {
          return m0 + 4 * static_cast<long>(i);
        },
        [f0 = f[0]](int i) {
          return f0 + 3 * static_cast<long>(i);
        });
  else
    pass(
        [mu](int i) {
          return mu[i];
        },
        [f](int i) {
          return f[i];
        });
}

/* The active force of owned atom i from the per-atom property d_name
   (fix polarity d_name gamma_R ...), which must be finite. */

double FixPolarity::active_force(int i) const
{
  const double fa = atom->dvector[fa_index][i];
  if (!std::isfinite(fa))
    error->one(FLERR,
               "fix polarity {}: active force d_{} of cell {} is {} at step {}; it must be "
               "finite (set it with 'set' or fix cell/adapt)",
               id, fa_name, atom->tag[i], fa, update->ntimestep);
  return fa;
}

/* Forward Euler (Euler-Maruyama with noise) step of the angle, at the start
   of step n+1 from the positions (Voronoi neighbours), angles and velocities
   of step n, the same state whose active force moves the positions in this
   step.  Doing it here rather than at the end of step n keeps mu at the end
   of every step equal to the angle that step's force used, so that a new
   run or a restart continues from the same state.  The torque works on unit vectors
   (cross products instead of sines of angle differences); the angle change
   is applied as a rotation of mu. */

void FixPolarity::initial_integrate(int /*vflag*/)
{
  // (timestep 0 is fine for 'run 0', which takes no step)
  if (!(update->dt > 0.0))
    error->all(FLERR,
               "fix polarity {}: the timestep must be > 0 to take a step, got {}; set it with "
               "'timestep'",
               id, update->dt);
  if (driven) return;    // fix brownian/heun advances the angles (coupled_*)
  if (domain->dimension == 3) {
    initial_integrate_3d();
    return;
  }
  const int nlocal = atom->nlocal;
  double **mu = atom->mu;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  // Atoms appended since the last post_force (create_atoms before 'run N pre
  // no') have no recorded velocity: no velocity torque on their first step.
  // Removed atoms have shifted the others' indices: that needs a setup.
  const int nrec = static_cast<int>(has_v.size());
  if (nrec > nlocal || (nrec < nlocal && params.J_S != 0.0))
    error->one(FLERR,
               "fix polarity: {} atoms on this rank at step {}, but {} when forces were last "
               "computed: atoms were {} without a setup; use 'run N pre yes' after "
               "create_atoms or delete_atoms",
               nlocal, update->ntimestep, nrec, nrec > nlocal ? "removed" : "added");
  if (nrec < nlocal) {
    has_v.resize(nlocal, 0);
    vhat.resize(2 * nlocal, 0.0);
  }

  // Unit polarities of owned and ghost cells (fresh angles first).
  unit_polarities();
  tau.resize(nlocal);

  if (params.J_S != 0.0) {
    const tessera::Contacts t = recorded_contacts(update->ntimestep - 1);
    tessera::polarity_torque_vec(t, unit.data(), 2, params, vhat.data(), has_v.data(), tau.data());
  } else {
    // Without neighbour alignment no tessellation is needed: the torque of
    // each cell depends on its own polarity and velocity only.
    none.n_owned = nlocal;
    if (none.cell_offset.size() != static_cast<size_t>(nlocal) + 1)
      none.cell_offset.assign(nlocal + 1, 0);
    tessera::polarity_torque_vec(none, unit.data(), 2, params, vhat.data(), has_v.data(),
                                 tau.data());
  }

  // Two passes: first the angle increments (the random numbers: a chain of
  // hashes per atom, independent between atoms), then the rotations.  Each
  // loop body is short enough for the processor to overlap several atoms.
  // (Drawing the random numbers in the torque's loop over cells, to overlap
  // the hashes with the neighbour loads, was measured and gained nothing.)
  const double dt = update->dt;
  const double noise = std::sqrt(2.0 * d_rot * dt);
  const bigint step = update->ntimestep;
  const uint64_t mixed_seed = mix(static_cast<uint64_t>(seed));
  double *dth = tau.data();    // tau[i] becomes the angle increment of cell i
  // x / gamma_R is x itself when gamma_R = 1: no division then.
  auto increments = [&](auto unit_gamma) {
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      const double drift = unit_gamma ? dt * tau[i] : dt * tau[i] / gamma_r;
      dth[i] = d_rot > 0.0 ? drift + noise * gaussian_mixed(mixed_seed, tag[i], step) : drift;
    }
  };
  if (gamma_r == 1.0)
    increments(std::true_type());
  else
    increments(std::false_type());
  // mu is one block of 4 doubles per atom (LAMMPS's memory->create), which
  // the rotation reads and writes as such.
  const unsigned char *active = nullptr;
  if (igroup != 0) {    // not group all
    in_group.resize(nlocal);
    for (int i = 0; i < nlocal; i++) in_group[i] = (mask[i] & groupbit) ? 1 : 0;
    active = in_group.data();
  }
  if (nlocal > 0 && one_block(mu, nlocal, 4))
    tessera::rotate_polarities(nlocal, unit.data(), dth, mu[0], active);
  else
    for (int i = 0; i < nlocal; i++)
      if (!active || active[i])
        tessera::rotate_polarities_reference(1, &unit[2 * i], &dth[i], mu[i], nullptr);
}

/* Notes which force computation's cells the next step's alignment reads
   (only 'neighbor' alignment reads them).  The pair style keeps their
   neighbour lists even when it computes the cells again for output after
   the end of the step (fix deform): CellSource::force_contacts(). */

void FixPolarity::record_contacts()
{
  if (params.J_S == 0.0 || !pair) return;
  rec_step = pair->cells_step();
  rec_force = pair->force_count();
  rec_n = pair->cells().n_owned();
}

/* The neighbour lists of that force computation, which must be those of
   state_step and of the atoms now owned. */

tessera::Contacts FixPolarity::recorded_contacts(bigint state_step)
{
  const int n = rec_force == pair->force_count() ? rec_n : -1;
  if (rec_step != state_step || n != atom->nlocal)
    error->one(FLERR,
               "fix polarity: the cells of the pair style are from step {} with {} "
               "cells, the polarities need it for step {} with {}",
               rec_step, n, state_step, atom->nlocal);
  return pair->force_contacts();
}

/* Polar order |<n>| and nematic order <cos 2(theta - phi_G)> over the group. */

void FixPolarity::polar_orders(double &polar, double &nematic)
{
  if (domain->dimension == 3) {
    polar_orders_3d(polar, nematic);
    return;
  }
  double **mu = atom->mu;
  const int *mask = atom->mask;
  double local[4] = {0.0, 0.0, 0.0, 0.0}, all[4];
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit) || !(mu[i][3] > 0.0)) continue;
    const double cx = mu[i][0] / mu[i][3], cy = mu[i][1] / mu[i][3];
    local[0] += cx;
    local[1] += cy;
    const double th = std::atan2(cy, cx) - params.phi_G;
    local[2] += std::cos(2.0 * th);
    local[3] += 1.0;
  }
  MPI_Allreduce(local, all, 4, MPI_DOUBLE, MPI_SUM, world);
  if (all[3] > 0.0) {
    polar = std::hypot(all[0], all[1]) / all[3];
    nematic = all[2] / all[3];
  } else {
    polar = nematic = 0.0;
  }
}

double FixPolarity::compute_vector(int n)
{
  double polar, nematic;
  polar_orders(polar, nematic);
  return n == 0 ? polar : nematic;
}

// (here, where Impl is complete)
FixPolarity::~FixPolarity() = default;
