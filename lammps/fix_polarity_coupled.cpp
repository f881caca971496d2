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

   fix polarity integrated by fix brownian/heun: the CoupledDof interface
   (coupled_dof.h) through which the integrator advances the polarity
   together with the positions.  Apart from fix_polarity.cpp, whose own
   forward Euler step does not use it.
------------------------------------------------------------------------- */

#include "fix_polarity.h"

#include "coupled_dof.h"

#include "atom.h"
#include "cell_source.h"
#include "domain.h"
#include "error.h"
#include "modify.h"
#include "update.h"

#include "tessera/counter_rng.h"
#include "tessera/polarity.h"

#include <cmath>
#include <cstring>
#include <memory>

using namespace LAMMPS_NS;

namespace {

// Counter-based random numbers as in fix_polarity.cpp (the same draws).
using tessera::sincos_small;
using tessera::rng::gaussian;

}    // namespace

/* ----------------------------------------------------------------------
   Integration by fix brownian/heun (the CoupledDof interface of
   coupled_dof.h).  The degree of freedom is the polarity angle; its rate
   is tau / gamma_R at the current positions, polarities and velocities
   (the integrator puts the velocity of the state, F / gamma_t, into v),
   its noise the same Gaussian increment that the Euler step above draws.
------------------------------------------------------------------------- */

void FixPolarity::find_driver()
{
  int n = 0;
  for (int i = 0; i < modify->nfix; i++)
    if (int dim = 0; modify->fix[i]->extract(CoupledDof::integrator_name, dim)) n++;
  if (n > 1)
    error->all(FLERR,
               "fix polarity {}: {} fixes (brownian/heun) want to integrate its angles; "
               "keep one",
               id, n);
  driven = n;
}

/* tau of the local atoms (in the vector tau) from the tessellation of
   state_step (the current positions) and the current polarities, including
   the ghosts', and velocity directions. */

void FixPolarity::angle_torques(bigint state_step)
{
  const int nlocal = atom->nlocal;
  double **mu = atom->mu;
  if (static_cast<int>(has_v.size()) != nlocal)
    error->one(FLERR, "fix polarity: internal error: velocity directions not recorded");
  const int nall = nlocal + atom->nghost;
  unit.resize(2 * nall);
  for (int i = 0; i < nall; i++) {
    const double inv = mu[i][3] > 0.0 ? 1.0 / mu[i][3] : 0.0;
    unit[2 * i] = mu[i][0] * inv;
    unit[2 * i + 1] = mu[i][1] * inv;
  }
  tau.resize(nlocal);
  if (params.J_S != 0.0) {
    const tessera::Contacts t = recorded_contacts(state_step);
    tessera::polarity_torque_vec(t, unit.data(), 2, params, vhat.data(), has_v.data(), tau.data());
  } else {
    none.n_owned = nlocal;
    none.cell_offset.assign(nlocal + 1, 0);
    tessera::polarity_torque_vec(none, unit.data(), 2, params, vhat.data(), has_v.data(),
                                 tau.data());
  }
}

void FixPolarity::coupled_rate(double *rate, int stride, bigint state_step)
{
  // The integrator has put the velocity of this state into v.
  double **v = atom->v;
  const int nlocal = atom->nlocal;
  if (domain->dimension == 3) {
    // The rotation vector's rate (1/gamma_R) n x h.
    vhat.resize(3 * nlocal);
    has_v.assign(nlocal, 0);
    if (params.J_V != 0.0)
      for (int i = 0; i < nlocal; i++) {
        const double s = std::sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
        has_v[i] = s > 0.0;
        for (int d = 0; d < 3; d++) vhat[3 * i + d] = has_v[i] ? v[i][d] / s : 0.0;
      }
    init_angles_3d();
    field_3d(state_step);
    const int *mask = atom->mask;
    for (int i = 0; i < nlocal; i++) {
      const double *n = &unit[3 * i], *h = &tau[3 * i];
      const bool on = mask[i] & groupbit;
      rate[i * stride] = on ? (n[1] * h[2] - n[2] * h[1]) / gamma_r : 0.0;
      rate[i * stride + 1] = on ? (n[2] * h[0] - n[0] * h[2]) / gamma_r : 0.0;
      rate[i * stride + 2] = on ? (n[0] * h[1] - n[1] * h[0]) / gamma_r : 0.0;
    }
    return;
  }
  vhat.resize(2 * nlocal);
  has_v.assign(nlocal, 0);
  if (params.J_V != 0.0)
    for (int i = 0; i < nlocal; i++) {
      const double s = std::sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1]);
      has_v[i] = s > 0.0;
      vhat[2 * i] = has_v[i] ? v[i][0] / s : 0.0;
      vhat[2 * i + 1] = has_v[i] ? v[i][1] / s : 0.0;
    }
  angle_torques(state_step);
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    rate[i * stride] = (mask[i] & groupbit) ? tau[i] / gamma_r : 0.0;
}

void FixPolarity::coupled_noise(double *w, int stride)
{
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  const double noise = std::sqrt(2.0 * d_rot * update->dt);
  const bigint step = update->ntimestep;
  if (domain->dimension == 3) {
    // The same Gaussian increments as the forward Euler step draws.
    for (int i = 0; i < atom->nlocal; i++) {
      double *wi = w + i * stride;
      if (d_rot > 0.0 && (mask[i] & groupbit))
        noise_3d(i, noise, step, wi);
      else
        wi[0] = wi[1] = wi[2] = 0.0;
    }
    return;
  }
  for (int i = 0; i < atom->nlocal; i++)
    w[i * stride] = (d_rot > 0.0 && (mask[i] & groupbit)) ? noise * gaussian(seed, tag[i], step)
                                                          : 0.0;
}

void FixPolarity::coupled_advance(const double *dq, int stride)
{
  const int *mask = atom->mask;
  const bool three = domain->dimension == 3;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit) {
      if (three)
        rotate_3d(i, dq + i * stride);
      else
        rotate(i, dq[i * stride]);
    }
}

void FixPolarity::coupled_save(double *q, int stride)
{
  double **mu = atom->mu;
  for (int i = 0; i < atom->nlocal; i++)
    for (int k = 0; k < 4; k++) q[i * stride + k] = mu[i][k];
}

void FixPolarity::coupled_restore(const double *q, int stride)
{
  double **mu = atom->mu;
  for (int i = 0; i < atom->nlocal; i++)
    for (int k = 0; k < 4; k++) mu[i][k] = q[i * stride + k];
}

int FixPolarity::coupled_wiener_size() const
{
  if (!(d_rot > 0.0)) return 0;
  if (domain->dimension == 2 || (pair && pair->on_sphere())) return 1;
  return 3;
}

/* The same increments as coupled_noise's for Wiener increments dW of
   variance dt: 2d the angle, 3d the rotation vector (isotropic), on a
   sphere a rotation about the cell's normal (noise_3d). */

void FixPolarity::coupled_wiener_increment(const double *dW, int wstride, double *w, int stride)
{
  const int *mask = atom->mask;
  const double amp = std::sqrt(2.0 * d_rot);
  const int n = coupled_size();
  const bool sphere = domain->dimension == 3 && pair && pair->on_sphere();
  for (int i = 0; i < atom->nlocal; i++) {
    double *wi = w + i * stride;
    const double *dw = dW + i * wstride;
    for (int k = 0; k < n; k++) wi[k] = 0.0;
    if (!(d_rot > 0.0) || !(mask[i] & groupbit)) continue;
    if (sphere) {
      const double *c = pair->sphere_centre();
      const double *x = state_position(i);
      const double u[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
      const double l = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      for (int d = 0; d < 3; d++) wi[d] = l > 0.0 ? amp * dw[0] * u[d] / l : 0.0;
    } else {
      for (int k = 0; k < n; k++) wi[k] = amp * dw[k];
    }
  }
}

/* mu of local atom i turned by dth, its length kept (1 if it had none). */

void FixPolarity::rotate(int i, double dth)
{
  double **mu = atom->mu;
  const double m = mu[i][3] > 0.0 ? mu[i][3] : 1.0;
  const double nx = mu[i][3] > 0.0 ? mu[i][0] / m : 1.0;
  const double ny = mu[i][3] > 0.0 ? mu[i][1] / m : 0.0;
  double s, c;
  sincos_small(dth, s, c);
  const double rx = c * nx - s * ny, ry = s * nx + c * ny;
  const double r = 1.0 / std::sqrt(rx * rx + ry * ry);
  mu[i][0] = m * rx * r;
  mu[i][1] = m * ry * r;
  mu[i][2] = 0.0;
  mu[i][3] = m;
}

/* The CoupledDof that fix brownian/heun integrates: this fix's coupled_*
   members (one virtual call per call, as when the fix derived from it). */

namespace {
class PolarityDof final : public CoupledDof {
 public:
  explicit PolarityDof(FixPolarity &fix) : p(fix) {}
  int coupled_size() const override { return p.coupled_size(); }
  void coupled_rate(double *r, int s, bigint step) override { p.coupled_rate(r, s, step); }
  void coupled_noise(double *w, int s) override { p.coupled_noise(w, s); }
  void coupled_advance(const double *dq, int s) override { p.coupled_advance(dq, s); }
  int coupled_state_size() const override { return p.coupled_state_size(); }
  void coupled_save(double *q, int s) override { p.coupled_save(q, s); }
  void coupled_restore(const double *q, int s) override { p.coupled_restore(q, s); }
  int coupled_wiener_size() const override { return p.coupled_wiener_size(); }
  void coupled_wiener_increment(const double *dw, int ws, double *w, int s) override
  {
    p.coupled_wiener_increment(dw, ws, w, s);
  }

 private:
  FixPolarity &p;
};
}    // namespace

std::unique_ptr<CoupledDof> CoupledDof::of(FixPolarity &fix)
{
  return std::unique_ptr<CoupledDof>(new PolarityDof(fix));
}

void *FixPolarity::extract(const char *name, int &dim)
{
  dim = 0;
  if (strcmp(name, CoupledDof::extract_name) != 0) return nullptr;
  if (!coupled_dof) coupled_dof = CoupledDof::of(*this);
  return coupled_dof.get();
}
