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

   The surface constraint of pair_style vertex/voronoi ... surface sphere
   (see fix_vertex_sphere.h).
------------------------------------------------------------------------- */

#include "fix_vertex_sphere.h"

#include "fix_cell_divide.h"
#include "fix_clock.h"
#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "comm.h"
#include "math_const.h"
#include "error.h"
#include "modify.h"
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
  return POST_INTEGRATE | PRE_EXCHANGE | END_OF_STEP | MIN_PRE_EXCHANGE | MIN_PRE_FORCE |
      MIN_POST_FORCE;
}

void FixVertexSphere::project_one(const double *c, double R, double *x, double *mu, const double *a)
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
  if (start_natoms < 0) {
    start_natoms = atom->natoms;
    start_step = update->ntimestep;
    start_R = R;
  }
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

/* The force on each owned cell in the tangent plane of the sphere: the
   gradient of the energy restricted to the sphere, which is what the
   minimisers' line searches and fnorm need (particles keep theirs). */

void FixVertexSphere::min_post_force(int)
{
  if (!pair || !pair->on_sphere()) return;
  const double *c = pair->sphere_centre();
  double **x = atom->x;
  double **f = atom->f;
  const int *type = atom->type;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!pair->is_cell_type(type[i])) continue;
    const double u[3] = {x[i][0] - c[0], x[i][1] - c[1], x[i][2] - c[2]};
    const double l2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    if (!(l2 > 0.0)) continue;
    const double s = (f[i][0] * u[0] + f[i][1] * u[1] + f[i][2] * u[2]) / l2;
    for (int d = 0; d < 3; d++) f[i][d] -= s * u[d];
  }
}

/* LAMMPS's time is atime + (step - atimestep) dt.  With atime 0 at a step
   atimestep > 0 it counts from 0 at that step: LAMMPS 29 Sep 2021 does that
   at the first run after read_restart (it keeps no time in restart files),
   and reset_timestep to an earlier step does it on every version.  Whether
   the radius reads that time is found by evaluating it once more with
   LAMMPS's time as if the run had kept this timestep from step 0. */

void FixVertexSphere::check_time()
{
  if (time_checked || !pair || !pair->on_sphere()) return;
  time_checked = 1;
  if (!(update->atime == 0.0 && update->atimestep > 0 && update->dt > 0.0)) return;
  const double R = pair->sphere_radius();
  const double saved = update->atime;
  const double guess = update->dt * static_cast<double>(update->atimestep);
  // (fix clock follows LAMMPS's time within a run: it holds its value)
  std::vector<FixClock *> clocks;
  for (int k = 0; k < modify->nfix; k++)
    if (auto *c = dynamic_cast<FixClock *>(modify->fix[k])) clocks.push_back(c);
  for (auto *c : clocks) c->hold(true);
  update->atime = guess;
  const double R_guess = pair->sphere_radius();
  update->atime = saved;
  for (auto *c : clocks) c->hold(false);
  if (R_guess == R || comm->me != 0) return;
  error->warning(FLERR,
                 "pair_style vertex/voronoi: the sphere radius reads LAMMPS's time, which is 0 "
                 "at step {}: LAMMPS 29 Sep 2021 starts it again at 0 at the first run after "
                 "read_restart (its restart files keep no time), and reset_timestep to an "
                 "earlier step does too. The radius is {:.6g}, its value at time 0, where at "
                 "time {:.6g} ({} steps of {:.6g}) it would be {:.6g}. For a time that continues "
                 "across restart files define 'fix ID all clock' (before the first run, and "
                 "again with the same ID after read_restart) and read f_ID instead of time",
                 update->atimestep, R, guess, update->atimestep, update->dt, R_guess);
}

/* Why the sphere outgrew the box: the cell count and radius then and now,
   and each area trigger of fix cell/divide against the cells' mean area on
   the sphere (4 pi R^2 / N) and their mean preferred area (d_area0, else
   their types' A0).  A trigger below the preferred area divides every
   cell again as soon as it has grown back, and a radius that follows the
   cells (the sum of their preferred areas) grows with every division: the
   divisions run away. */

std::string FixVertexSphere::growth_note(double R) const
{
  double sum[2] = {0.0, 0.0}, all[2] = {0.0, 0.0};
  int flag = -1, cols = -1;
  const int a0 = atom->find_custom("area0", flag, cols);
  const bool per_cell = a0 >= 0 && flag == 1 && cols == 0;
  for (int i = 0; i < atom->nlocal; i++) {
    const int t = atom->type[i];
    if (!pair->is_cell_type(t)) continue;
    double v[4];
    pair->type_cell_values(t, v);
    sum[0] += per_cell ? atom->dvector[a0][i] : v[0];
    sum[1] += 1.0;
  }
  MPI_Allreduce(sum, all, 2, MPI_DOUBLE, MPI_SUM, world);
  const double ncells = all[1];
  const double preferred = ncells > 0.0 ? all[0] / ncells : 0.0;
  const double area = ncells > 0.0 ? 4.0 * MathConst::MY_PI * R * R / ncells : 0.0;
  std::string text;
  if (start_natoms >= 0)
    text = fmt::format("; since step {} the atoms grew from {} to {} and the radius from {:.4g} "
                       "to {:.4g}",
                       start_step, start_natoms, atom->natoms, start_R, R);
  for (int k = 0; k < modify->nfix; k++) {
    auto *div = dynamic_cast<FixCellDivide *>(modify->fix[k]);
    if (!div || div->division_area() < 0.0) continue;
    const double ac = div->division_area();
    text += fmt::format("; fix cell/divide {} divides cells whose area exceeds {:.4g}, while "
                        "the cells' mean area on the sphere is {:.4g} and their mean preferred "
                        "area {:.4g}",
                        div->id, ac, area, preferred);
    if (ac < preferred)
      text += ": below the preferred area, every cell divides again as soon as it grows back to "
              "it, and a radius that follows the cells (such as the sum of their preferred "
              "areas) grows with every division, so the divisions run away; set the division "
              "area above the preferred area (e.g. 1.5 times it)";
    else if (ac < area)
      text += ": below the cells' area, so they keep dividing while the sphere grows faster "
              "than they do; slow the radius's growth or raise the division area";
  }
  return text;
}
