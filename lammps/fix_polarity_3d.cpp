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

   fix polarity in 'dimension 3': the polarity is a unit vector, turned by
   rotations (Rodrigues) about n x h and by rotational noise on the sphere.
------------------------------------------------------------------------- */

#include "fix_polarity.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "math_const.h"
#include "cell_source.h"
#include "update.h"

#include "tessera/counter_rng.h"
#include "tessera/sphere.h"
#include "tessera/polarity.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {

using tessera::sincos_small;
using tessera::rng::gaussian;
using tessera::rng::mix;
using tessera::rng::uniform01;

}    // namespace

/* ----------------------------------------------------------------------
   dimension 3: the polarity is the unit vector n_i = mu_i/|mu_i|, the
   active force f_a n_i, and forward Euler on the sphere,
     n_i <- rotate n_i by the angle vector
            dt/gamma_R n_i x [ J_S sum_j n_j + J_G (n_i.g) g + J_V vhat_i ]
            + sqrt(2 D_r dt) xi_i                    (xi_i: 3 Gaussians)
   so that the deterministic part is dn/dt = (1/gamma_R) P_i [...] with P_i
   the projection perpendicular to n_i (the 2D torques of the same moduli for
   n in the plane), and the noise is rotational diffusion with
   <n(t).n(0)> = exp(-2 D_r t).  g = (cos phi, sin phi, 0) is the groove.
------------------------------------------------------------------------- */

void FixPolarity::init_angles_3d()
{
  double **mu = atom->mu;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    if (mu[i][3] > 0.0) continue;    // keep a given direction
    uint64_t b[3];
    for (int d = 0; d < 3; d++) std::memcpy(&b[d], &atom->x[i][d], sizeof b[d]);
    const uint64_t h = mix(mix(b[0]) ^ b[1]) ^ b[2];
    const double z = 2.0 * uniform01(seed, h, 0, 3) - 1.0;
    const double ph = MathConst::MY_2PI * uniform01(seed, h, 0, 4);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    mu[i][0] = r * std::cos(ph);
    mu[i][1] = r * std::sin(ph);
    mu[i][2] = z;
    mu[i][3] = 1.0;
  }
}

void FixPolarity::post_force_3d()
{
  record_state_positions();
  double **mu = atom->mu;
  double **f = atom->f;
  double **v = atom->v;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  vhat.resize(3 * nlocal);
  has_v.resize(nlocal);
  const bool need_v = params.J_V != 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (need_v) {
      const double s = std::sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
      has_v[i] = s > 0.0;
      for (int d = 0; d < 3; d++) vhat[3 * i + d] = has_v[i] ? v[i][d] / s : 0.0;
    } else {
      has_v[i] = 0;
    }
    if (!(mask[i] & groupbit) || !(mu[i][3] > 0.0)) continue;
    const double inv = (fa_index < 0 ? f_active : active_force(i)) / mu[i][3];
    for (int d = 0; d < 3; d++) f[i][d] += inv * mu[i][d];
  }
}

/* Cells on a sphere: the positions of owned and ghost atoms now, at a
   force computation.  The field (transport between neighbours, tangent
   planes) and the noise's axis of the next angle update read these, not
   atom->x: an integrator defined before this fix has moved the owned atoms
   by then but not their ghost copies, and the update must see the state
   whose tessellation it uses (the same on any number of ranks and in any
   order of the fixes). */

void FixPolarity::record_state_positions()
{
  if (!pair || !pair->on_sphere()) return;
  const int nall = atom->nlocal + atom->nghost;
  state_x.resize(3 * static_cast<size_t>(nall));
  double **x = atom->x;
  for (int i = 0; i < nall; i++)
    for (int d = 0; d < 3; d++) state_x[3 * i + d] = x[i][d];
}

const double *FixPolarity::state_position(int i) const
{
  if (3 * static_cast<size_t>(i) + 3 > state_x.size())
    error->one(FLERR,
               "fix polarity {}: internal error: no position of atom {} recorded at the last "
               "force computation",
               id, atom->tag[i]);
  return &state_x[3 * static_cast<size_t>(i)];
}

/* Calls term(i, j) for every owned cell i and each of its Voronoi
   neighbours j (contacts longer than 1e-9 of i's boundary) in the cells of
   pair vertex/voronoi recorded at the force computation of state_step. */

template <class Term> void FixPolarity::for_each_neighbour(bigint state_step, Term &&term)
{
  const int nlocal = atom->nlocal;
  const tessera::Contacts t = recorded_contacts(state_step);
  for (int i = 0; i < nlocal; i++) {
    const double floor = 1e-9 * pair->force_boundary(i);
    for (int f = t.offset[i]; f < t.offset[i + 1]; f++)
      if (t.size[f] > floor) term(i, t.neighbor[f]);
  }
}

/* The field h_i = J_S sum_j n_j + J_G (n_i.g) g + J_V vhat_i of every
   local atom (tau, 3 per atom), from the unit polarities of owned and ghost
   atoms and the cells of state_step. */

void FixPolarity::field_3d(bigint state_step)
{
  const int nlocal = atom->nlocal;
  double **mu = atom->mu;
  if (static_cast<int>(has_v.size()) != nlocal)
    error->one(FLERR, "fix polarity: internal error: velocity directions not recorded");
  const int nall = nlocal + atom->nghost;
  unit.resize(3 * nall);
  for (int i = 0; i < nall; i++) {
    const double inv = mu[i][3] > 0.0 ? 1.0 / mu[i][3] : 0.0;
    for (int d = 0; d < 3; d++) unit[3 * i + d] = mu[i][d] * inv;
  }
  tau.assign(3 * nlocal, 0.0);
  if (pair && pair->on_sphere()) {
    field_sphere(state_step);
    return;
  }
  if (params.J_S != 0.0)
    for_each_neighbour(state_step, [&](int i, int j) {
      for (int d = 0; d < 3; d++) tau[3 * i + d] += params.J_S * unit[3 * j + d];
    });
  const double g[3] = {std::cos(params.phi_G), std::sin(params.phi_G), 0.0};
  for (int i = 0; i < nlocal; i++) {
    const double *n = &unit[3 * i];
    if (params.J_G != 0.0) {
      const double ng = n[0] * g[0] + n[1] * g[1] + n[2] * g[2];
      for (int d = 0; d < 3; d++) tau[3 * i + d] += params.J_G * ng * g[d];
    }
    if (params.J_V != 0.0 && has_v[i])
      for (int d = 0; d < 3; d++) tau[3 * i + d] += params.J_V * vhat[3 * i + d];
  }
}

/* mu of local atom i rotated about the vector w by the angle |w| (Rodrigues),
   its length kept (1 if it had none). */

void FixPolarity::rotate_3d(int i, const double *w)
{
  double **mu = atom->mu;
  const double m = mu[i][3] > 0.0 ? mu[i][3] : 1.0;
  const double n[3] = {mu[i][0] / m, mu[i][1] / m, mu[i][2] / m};
  const double a = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  double r[3] = {n[0], n[1], n[2]};
  if (a > 0.0) {
    double s, c;
    sincos_small(a, s, c);
    const double k[3] = {w[0] / a, w[1] / a, w[2] / a};
    const double kn = k[0] * n[0] + k[1] * n[1] + k[2] * n[2];
    const double kxn[3] = {k[1] * n[2] - k[2] * n[1], k[2] * n[0] - k[0] * n[2],
                           k[0] * n[1] - k[1] * n[0]};
    for (int d = 0; d < 3; d++) r[d] = n[d] * c + kxn[d] * s + k[d] * kn * (1.0 - c);
  }
  const double inv = 1.0 / std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  for (int d = 0; d < 3; d++) mu[i][d] = m * r[d] * inv;
  mu[i][3] = m;
}

void FixPolarity::initial_integrate_3d()
{
  const int nlocal = atom->nlocal;
  double **mu = atom->mu;
  const int *mask = atom->mask;
  // Cells that appeared since (fix deposit, create_atoms) get a direction.
  init_angles_3d();
  field_3d(update->ntimestep - 1);

  const double dt = update->dt;
  const double noise = std::sqrt(2.0 * d_rot * dt);
  const bigint step = update->ntimestep;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double *n = &unit[3 * i];
    const double *h = &tau[3 * i];
    // angle vector w = dt/gamma_R n x h + noise xi
    double w[3] = {dt / gamma_r * (n[1] * h[2] - n[2] * h[1]),
                   dt / gamma_r * (n[2] * h[0] - n[0] * h[2]),
                   dt / gamma_r * (n[0] * h[1] - n[1] * h[0])};
    if (d_rot > 0.0) {
      double xi[3];
      noise_3d(i, noise, step, xi);
      for (int d = 0; d < 3; d++) w[d] += xi[d];
    }
    rotate_3d(i, w);
  }
  (void) mu;
}

/* 3d: polar order |<n>| and nematic order <P2(n.g)> = <(3 (n.g)^2 - 1)/2>
   along the groove direction g (1: all along +-g, 0: isotropic). */

void FixPolarity::polar_orders_3d(double &polar, double &nematic)
{
  double **mu = atom->mu;
  const int *mask = atom->mask;
  const double g[3] = {std::cos(params.phi_G), std::sin(params.phi_G), 0.0};
  double local[5] = {0.0, 0.0, 0.0, 0.0, 0.0}, all[5];
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit) || !(mu[i][3] > 0.0)) continue;
    double ng = 0.0;
    for (int d = 0; d < 3; d++) {
      local[d] += mu[i][d] / mu[i][3];
      ng += g[d] * mu[i][d] / mu[i][3];
    }
    local[3] += 1.5 * ng * ng - 0.5;
    local[4] += 1.0;
  }
  MPI_Allreduce(local, all, 5, MPI_DOUBLE, MPI_SUM, world);
  if (all[4] > 0.0) {
    polar = std::sqrt(all[0] * all[0] + all[1] * all[1] + all[2] * all[2]) / all[4];
    nematic = all[3] / all[4];
  } else {
    polar = nematic = 0.0;
  }
}

/* The rotational noise of local atom i in 3d (scale sqrt(2 D_r dt)): an
   angle vector of three Gaussians (rotational diffusion on the unit
   sphere), or, for a cell on a sphere, one Gaussian angle about the
   outward normal u_i (diffusion of the angle in the tangent plane, as in 2d:
   <n(t).n(0)> = exp(-D_r t)); a particle there diffuses as in space. */

void FixPolarity::noise_3d(int i, double scale, bigint step, double *w) const
{
  const tagint t = atom->tag[i];
  if (pair && pair->on_sphere() && pair->is_cell_type(atom->type[i])) {
    const double *c = pair->sphere_centre();
    const double *x = state_position(i);
    const double u[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
    const double l = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const double a = scale * gaussian(seed ^ 0x5bd1e995ULL, 3 * static_cast<uint64_t>(t), step);
    for (int d = 0; d < 3; d++) w[d] = l > 0.0 ? a * u[d] / l : 0.0;
    return;
  }
  for (int d = 0; d < 3; d++)
    w[d] = scale * gaussian(seed ^ 0x5bd1e995ULL, 3 * static_cast<uint64_t>(t) + d, step);
}

/* Cells on a sphere (pair_style vertex/voronoi ... surface sphere): the
   polarities are tangent (unit, of owned and ghost atoms, projected onto the
   tangent plane at their positions at the last force computation,
   record_state_positions()), and the field is
     h_i = J_S sum_j T_ji n_j + J_V vhat_i
   with T_ji the parallel transport from j to i along their geodesic
   (tessera::sphere_transport) and vhat_i the direction of the velocity's
   tangent part.  Then n_i x h_i lies along the outward normal: the turn
   dt/gamma_R n_i x h_i is a rotation in the tangent plane by
   dt/gamma_R [J_S sum_j u_i.(n_i x T_ji n_j) + J_V u_i.(n_i x vhat_i)],
   the core's sphere_alignment_torque for J_S (doc/sphere.md). */

void FixPolarity::field_sphere(bigint state_step)
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const double *cc = pair->sphere_centre();
  const tessera::Vec3 c{cc[0], cc[1], cc[2]};
  if (state_x.size() < 3 * static_cast<size_t>(nall)) state_position(nall - 1);    // stops
  auto at = [&](int i) {
    const double *x = &state_x[3 * static_cast<size_t>(i)];
    return tessera::Vec3{x[0], x[1], x[2]};
  };
  // Atoms that are no cells are active Brownian particles in space, off
  // the sphere (its surface fix leaves them free): their polarity is not
  // tangent to it, and one at its centre has no tangent plane at all.
  const int *type = atom->type;
  for (int i = 0; i < nall; i++) {
    double *n = &unit[3 * i];
    if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0) continue;
    if (!pair->is_cell_type(type[i])) continue;
    const tessera::Vec3 t = tessera::sphere_tangent(c, at(i), {n[0], n[1], n[2]});
    const double l = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
    if (!(l > 0.0)) continue;
    n[0] = t.x / l;
    n[1] = t.y / l;
    n[2] = t.z / l;
  }
  if (params.J_S != 0.0)
    for_each_neighbour(state_step, [&](int i, int j) {
      const double *nj = &unit[3 * j];
      tessera::Vec3 m;
      try {
        m = tessera::sphere_transport(c, at(j), at(i), {nj[0], nj[1], nj[2]});
      } catch (tessera::Error &e) {
        error->one(FLERR, "fix polarity on the sphere, atoms {} and {}: {}", atom->tag[j],
                   atom->tag[i], e.what());
      }
      tau[3 * i] += params.J_S * m.x;
      tau[3 * i + 1] += params.J_S * m.y;
      tau[3 * i + 2] += params.J_S * m.z;
    });
  if (params.J_V != 0.0)
    for (int i = 0; i < nlocal; i++) {
      if (!has_v[i]) continue;
      const double *w = &vhat[3 * i];
      if (!pair->is_cell_type(type[i])) {    // a particle: its velocity in space
        for (int d = 0; d < 3; d++) tau[3 * i + d] += params.J_V * w[d];
        continue;
      }
      const tessera::Vec3 t = tessera::sphere_tangent(c, at(i), {w[0], w[1], w[2]});
      const double l = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
      if (!(l > 0.0)) continue;
      tau[3 * i] += params.J_V * t.x / l;
      tau[3 * i + 1] += params.J_V * t.y / l;
      tau[3 * i + 2] += params.J_V * t.z / l;
    }
}
