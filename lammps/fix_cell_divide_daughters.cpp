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

   fix cell/divide: the daughters.  The division axis of a cell (random,
   along its polarity or its principal axes, tangent on a sphere), the
   event in pre_exchange that replaces each mother by two daughters with
   new atom IDs, and each daughter's state and polarity.  Apart from the
   decisions (fix_cell_divide.cpp), which only record the axis; the
   division of vertex/polygon cells: fix_cell_divide_vertex.cpp.
------------------------------------------------------------------------- */

#include "fix_cell_divide.h"

#include "cell_event_count.h"
#include "cell_event_log.h"

#include "atom.h"
#include "atom_vec.h"
#include "cell_events.h"
#include "cell_source.h"
#include "domain.h"
#include "error.h"
#include "math_const.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace cell_events;

/* A uniform random unit vector (2d: in the plane) from the draws of one
   cell at one step, streams s1 and s2. */

static void random_direction(uint64_t seed, tagint t, uint64_t step, uint64_t s1, uint64_t s2,
                             int dim, double *u)
{
  const double phi = MathConst::MY_2PI * uniform01(seed, t, step, s1);
  if (dim == 2) {
    u[0] = std::cos(phi);
    u[1] = std::sin(phi);
    u[2] = 0.0;
    return;
  }
  const double z = 2.0 * uniform01(seed, t, step, s2) - 1.0, r = std::sqrt(MAX(0.0, 1.0 - z * z));
  u[0] = r * std::cos(phi);
  u[1] = r * std::sin(phi);
  u[2] = z;
}

/* Direction u (3 values) along which the daughters of local atom i are
   placed: the division plane is normal to it. */

void FixCellDivide::cell_axis(int i, double *u) const
{
  const tagint t = atom->tag[i];
  const uint64_t step = update->ntimestep;
  const int dim = domain->dimension;
  random_direction(seed, t, step, AXIS, AXIS_Z, dim, u);
  if (axis == POLARITY) {
    const double *mu = atom->mu[i];
    if (dim == 2 && std::hypot(mu[0], mu[1]) > 0.0) {
      const double theta = std::atan2(mu[1], mu[0]);
      u[0] = std::cos(theta);
      u[1] = std::sin(theta);
    }
    const double m = std::sqrt(mu[0] * mu[0] + mu[1] * mu[1] + mu[2] * mu[2]);
    if (dim == 3 && m > 0.0)
      for (int d = 0; d < 3; d++) u[d] = mu[d] / m;
  } else if (axis == LONG || axis == SHORT) {
    // The principal axes of the cell's second moments (any model: polygons,
    // finite cells with their arcs, polyhedra); a cell whose tensor is
    // isotropic keeps the random axis.
    double a[3] = {0.0, 0.0, 0.0};
    if (pair->cells().principal_axis(i, axis == LONG, a))
      for (int d = 0; d < 3; d++) u[d] = a[d];
  }
  // Cells on a sphere: the daughters sit along the tangent part of the axis
  // (the pair style then puts them on the sphere).
  if (pair && pair->on_sphere()) {
    const double *c = pair->sphere_centre();
    double n[3] = {atom->x[i][0] - c[0], atom->x[i][1] - c[1], atom->x[i][2] - c[2]};
    const double ln = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (ln > 0.0) {
      for (int d = 0; d < 3; d++) n[d] /= ln;
      const double un = u[0] * n[0] + u[1] * n[1] + u[2] * n[2];
      double t[3] = {u[0] - un * n[0], u[1] - un * n[1], u[2] - un * n[2]};
      double lt = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
      if (!(lt > 1e-6)) {    // a radial axis: any tangent one
        const bool pole = std::fabs(n[2]) > 0.9;
        t[0] = pole ? 0.0 : n[1];
        t[1] = pole ? n[2] : -n[0];
        t[2] = pole ? -n[1] : 0.0;
        lt = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
      }
      for (int d = 0; d < 3; d++) u[d] = t[d] / lt;
    }
  }
}

/* The unit polarity of a daughter k (3 values): her mother's direction (or
   a random one if she had none), turned by the noise: by a uniform angle in
   [-eta, eta] in the plane (2d), or about a random axis normal to it (3d). */

static void daughter_polarity(uint64_t seed, tagint t, uint64_t step, double noise, int dim,
                              const double *mu, double *n)
{
  if (dim == 2) {
    double th = std::hypot(mu[0], mu[1]) > 0.0
        ? std::atan2(mu[1], mu[0])
        : MathConst::MY_2PI * uniform01(seed, t, step, DIRECTION);
    if (noise > 0.0) th += noise * (2.0 * uniform01(seed, t, step, NOISE) - 1.0);
    n[0] = std::cos(th);
    n[1] = std::sin(th);
    n[2] = 0.0;
    return;
  }
  double m = 0.0;
  for (int d = 0; d < dim; d++) m += mu[d] * mu[d];
  m = std::sqrt(m);
  if (m > 0.0)
    for (int d = 0; d < 3; d++) n[d] = d < dim ? mu[d] / m : 0.0;
  else
    random_direction(seed, t, step, DIRECTION, DIRECTION_Z, dim, n);
  if (!(noise > 0.0)) return;
  const double th = noise * (2.0 * uniform01(seed, t, step, NOISE) - 1.0);
  // An axis normal to n: a random direction less its component along n.
  double a[3];
  random_direction(seed, t, step, NOISE_AXIS, AXIS_Z, 3, a);
  const double an = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
  for (int d = 0; d < 3; d++) a[d] -= an * n[d];
  const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (!(la > 1e-12)) return;
  for (int d = 0; d < 3; d++) a[d] /= la;
  // Rodrigues: n cos th + (a x n) sin th (a is normal to n).
  const double axn[3] = {a[1] * n[2] - a[2] * n[1], a[2] * n[0] - a[0] * n[2],
                         a[0] * n[1] - a[1] * n[0]};
  for (int d = 0; d < 3; d++) n[d] = n[d] * std::cos(th) + axn[d] * std::sin(th);
}

/* The divisions decided at the end of the previous step. */

void FixCellDivide::pre_exchange()
{
  if (next_reneighbor != update->ntimestep) return;
  next_reneighbor = -1;
  if (vertex) {
    divide_vertex_cells();
    return;
  }

  tagint maxtag = 0, maxtag_all = 0;
  for (int i = 0; i < atom->nlocal; i++) maxtag = MAX(maxtag, atom->tag[i]);
  MPI_Allreduce(&maxtag, &maxtag_all, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  if ((double) maxtag_all + daughter_tag.size() >= (double) MAXTAGINT)
    error->all(FLERR, "fix cell/divide: new atom IDs would exceed the largest atom ID");

  // The cap again, against the atom count now: another fix cell/divide may
  // have added cells at this step since the decisions (deaths only make
  // room, and the decisions already kept within the cap of that time).
  const bigint room = cap_room();
  if ((bigint) daughter_tag.size() > room) warn_cap((bigint) daughter_tag.size() - room);

  // Ghost atoms are rebuilt by this re-neighboring; their slots take daughters.
  atom->nghost = 0;
  const uint64_t step = update->ntimestep;
  const int nold = atom->nlocal;
  int ncreated = 0;
  for (int i = 0; i < nold; i++) {
    const auto found = pending.find(atom->tag[i]);
    if (found == pending.end()) continue;
    const auto rank = daughter_tag.find(atom->tag[i]);
    if (rank == daughter_tag.end()) continue;       // over the cap
    if ((bigint) rank->second >= room) continue;    // over the cap, with the other fixes' cells
    const std::array<double, 3> &u = found->second;
    if (atom->nlocal == atom->nmax) atom->avec->grow(0);
    const int j = atom->nlocal;
    atom->avec->copy(i, j, 0);    // every per-atom value, and every fix's
    for (const int index : split_index) atom->dvector[index][j] = atom->dvector[index][i] *= 0.5;
    atom->nlocal++;
    ncreated++;
    const tagint mother = atom->tag[i];
    atom->tag[j] = maxtag_all + 1 + rank->second;
    double **x = atom->x;
    log.add("divide", mother, mother, atom->tag[j], x[i]);
    const double h = 0.5 * separation;
    for (int d = 0; d < domain->dimension; d++) {
      x[i][d] -= h * u[d];
      x[j][d] += h * u[d];
    }
    for (const int k : {i, j}) born(k, mother, step);
  }
  pending.clear();
  daughter_tag.clear();

  int nall = 0;
  MPI_Allreduce(&ncreated, &nall, 1, MPI_INT, MPI_SUM, world);
  atom->natoms += nall;
  events.record(nall, update->ntimestep);
  log.flush(clock + update->dt);    // the time of this step (pre_force advances the clock)
  if (atom->map_style) {
    atom->map_init();
    atom->map_set();
  }
  if (nall > 0) refresh_dumps(output);
}

/* The state of daughter k of mother (both daughters: the mother's atom and
   the new one): age 0, one generation more, her mother and birth time, a
   new cycle time, the base preferred area under growth linear, and her
   polarity with the noise. */

void FixCellDivide::born(int k, tagint mother, uint64_t step)
{
  cellstate[k][AGE] = 0.0;
  cellstate[k][GENERATION] += 1.0;
  cellstate[k][MOTHER] = (double) mother;
  cellstate[k][BIRTH] = decide_time;
  cellstate[k][CYCLE_TIME] = draw_cycle(atom->tag[k], step);
  if (growth && cellstate[k][AREA0_BASE] > 0.0)
    atom->dvector[area0_index][k] = cellstate[k][AREA0_BASE];
  if (atom->mu_flag) {
    double *mu = atom->mu[k];
    double n[3];
    daughter_polarity(seed, atom->tag[k], step, noise, domain->dimension, mu, n);
    mu[0] = n[0];
    mu[1] = n[1];
    mu[2] = n[2];
    mu[3] = 1.0;
  }
}
