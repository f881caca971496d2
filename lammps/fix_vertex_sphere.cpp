/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   The surface constraint of pair_style vertex/voronoi ... surface sphere
   (see fix_vertex_sphere.h).
------------------------------------------------------------------------- */

#include "fix_vertex_sphere.h"

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "error.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace FixConst;

FixVertexSphere::FixVertexSphere(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg) {}

Fix *FixVertexSphere::creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixVertexSphere(lmp, narg, arg);
}

int FixVertexSphere::setmask()
{
  return POST_INTEGRATE | PRE_EXCHANGE | END_OF_STEP | MIN_PRE_EXCHANGE | MIN_PRE_FORCE;
}

void FixVertexSphere::project_one(const double *c, double R, double *x, double *mu,
                                  const double *a)
{
  double u[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
  const double l = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (int d = 0; d < 3; d++) {
    u[d] /= l;
    x[d] = c[d] + R * u[d];
  }
  if (!mu || !(mu[3] > 0.0)) return;
  if (a) {
    // Parallel transport from a to u: mu - (u.mu)/(1 + a.u) (a + u).
    const double au = a[0] * u[0] + a[1] * u[1] + a[2] * u[2];
    if (au > -0.5) {
      const double s = (u[0] * mu[0] + u[1] * mu[1] + u[2] * mu[2]) / (1.0 + au);
      for (int d = 0; d < 3; d++) mu[d] -= s * (a[d] + u[d]);
    }
  }
  const double un = u[0] * mu[0] + u[1] * mu[1] + u[2] * mu[2];
  double t[3] = {mu[0] - un * u[0], mu[1] - un * u[1], mu[2] - un * u[2]};
  double m = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  if (!(m > 1e-12 * mu[3])) {
    // A radial moment has no tangent part: take u x z (or u x x at the poles).
    const bool pole = std::fabs(u[2]) > 0.9;
    t[0] = pole ? 0.0 : u[1];
    t[1] = pole ? u[2] : -u[0];
    t[2] = pole ? -u[1] : 0.0;
    m = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  }
  for (int d = 0; d < 3; d++) mu[d] = mu[3] * t[d] / m;
}

void FixVertexSphere::record()
{
  if (!pair || !pair->on_sphere()) return;
  const double *c = pair->sphere_centre();
  const int n = atom->nlocal;
  tag0.resize(n);
  u0.resize(3 * static_cast<size_t>(n));
  for (int i = 0; i < n; i++) {
    tag0[i] = atom->tag[i];
    const double *x = atom->x[i];
    const double d[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
    const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int k = 0; k < 3; k++) u0[3 * i + k] = l > 0.0 ? d[k] / l : 0.0;
  }
}

void FixVertexSphere::project(bool transport)
{
  if (!pair || !pair->on_sphere()) return;
  const double *c = pair->sphere_centre();
  const double R = pair->sphere_radius();
  pair->check_sphere_box(R);
  double **x = atom->x;
  double **mu = atom->mu_flag ? atom->mu : nullptr;
  const int *type = atom->type;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!pair->is_cell_type(type[i])) continue;    // particles move freely in space
    const double d[3] = {x[i][0] - c[0], x[i][1] - c[1], x[i][2] - c[2]};
    const double l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (!(l2 > 0.0) || !std::isfinite(l2))
      error->one(FLERR,
                 "pair_style vertex/voronoi surface sphere at step {}: atom {} is at {} {} {}, "
                 "{}; it cannot be put on the sphere (centre {} {} {})",
                 update->ntimestep, atom->tag[i], x[i][0], x[i][1], x[i][2],
                 l2 > 0.0 ? "not a finite position" : "the centre of the sphere", c[0], c[1], c[2]);
    const bool known = transport && i < static_cast<int>(tag0.size()) && tag0[i] == atom->tag[i];
    project_one(c, R, x[i], mu ? mu[i] : nullptr, known ? &u0[3 * i] : nullptr);
  }
  if (!transport) tag0.clear();    // atoms added or exchanged: no directions to carry from
}
