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

   fix brownian: Euler-Maruyama integration of overdamped translation,
     dr = F / gamma_t dt + sqrt(2 kT / gamma_t) dW,
   with the arguments of upstream LAMMPS's BROWNIAN package (see
   doc/fix_brownian.rst), so input scripts run unchanged on either.
------------------------------------------------------------------------- */

#include "fix_brownian.h"

#include "integrator_chatter.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "random_mars.h"
#include "update.h"
#include "utils.h"

#include "tessera/overdamped.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

// RanMars accepts seeds in [1, 900000000]; each rank uses seed + its rank.
static constexpr int MAX_MARSAGLIA_SEED = 900000000;

/* ---------------------------------------------------------------------- */

FixBrownianTessera::FixBrownianTessera(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), random(nullptr), chatter(new IntegratorChatter(lmp))
{
  if (narg < 5)
    error->all(FLERR,
               "Illegal fix {} command (fix ID {}): expected "
               "'fix ID group {} T seed gamma_t value [rng uniform|gaussian|none]'",
               style, id, style);

  time_integrate = 1;
  dynamic_group_allow = 1;

  temperature = parse_number("temperature T", arg[3]);
  if (temperature <= 0.0)
    error->all(FLERR,
               "Fix {} (ID {}): temperature T = {} must be > 0 "
               "(for dynamics without noise keep T > 0 and add 'rng none')",
               style, id, arg[3]);

  if (!utils::is_integer(arg[4]))
    error->all(FLERR, "Fix {} (ID {}): seed must be an integer, got '{}'", style, id, arg[4]);
  seed = utils::inumeric(FLERR, arg[4], false, lmp);
  if (seed <= 0 || seed > MAX_MARSAGLIA_SEED - (comm->nprocs - 1))
    error->all(FLERR, "Fix {} (ID {}): seed = {} must be in [1, {}] on {} MPI rank(s)", style, id,
               arg[4], MAX_MARSAGLIA_SEED - (comm->nprocs - 1), comm->nprocs);

  gamma_t = 0.0;
  noise = NOISE_UNIFORM;

  int iarg = 5;
  while (iarg < narg) {
    const char *keyword = arg[iarg];
    if (strcmp(keyword, "gamma_t") == 0 || strcmp(keyword, "rng") == 0) {
      if (iarg + 1 >= narg)
        error->all(FLERR, "Fix {} (ID {}): keyword {} needs a value", style, id, keyword);
      const char *value = arg[iarg + 1];
      if (strcmp(keyword, "gamma_t") == 0) {
        gamma_t = parse_number("gamma_t", value);
        if (gamma_t <= 0.0)
          error->all(FLERR, "Fix {} (ID {}): gamma_t = {} must be > 0", style, id, value);
      } else if (strcmp(value, "uniform") == 0) {
        noise = NOISE_UNIFORM;
      } else if (strcmp(value, "gaussian") == 0) {
        noise = NOISE_GAUSSIAN;
      } else if (strcmp(value, "none") == 0) {
        noise = NOISE_NONE;
      } else {
        error->all(FLERR, "Fix {} (ID {}): rng must be uniform, gaussian or none, got '{}'", style,
                   id, value);
      }
      iarg += 2;
    } else if (strcmp(keyword, "gamma_r") == 0 || strcmp(keyword, "gamma_t_eigen") == 0 ||
               strcmp(keyword, "gamma_r_eigen") == 0 || strcmp(keyword, "dipole") == 0 ||
               strcmp(keyword, "rotation_temp") == 0 || strcmp(keyword, "rotation_style") == 0 ||
               strcmp(keyword, "planar_rotation") == 0) {
      error->all(FLERR,
                 "Fix {} (ID {}): keyword {} belongs to upstream's fix brownian/sphere or "
                 "brownian/asphere, which Tessera does not provide; fix brownian moves positions "
                 "only (polarity dynamics: fix polarity)",
                 style, id, keyword);
    } else {
      error->all(FLERR, "Fix {} (ID {}): unknown keyword '{}' (expected gamma_t or rng)", style, id,
                 keyword);
    }
  }
  if (gamma_t == 0.0) error->all(FLERR, "Fix {} (ID {}): keyword gamma_t is required", style, id);

  // A different stream on each rank, as upstream does.
  random = new RanMars(lmp, seed + comm->me);
}

/* ---------------------------------------------------------------------- */

FixBrownianTessera::~FixBrownianTessera()
{
  delete random;
}

/* ---------------------------------------------------------------------- */

int FixBrownianTessera::setmask()
{
  return INITIAL_INTEGRATE;
}

/* ---------------------------------------------------------------------- */

void FixBrownianTessera::init()
{
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix {} (ID {}) does not support run_style respa", style, id);
  set_step();
}

/* ---------------------------------------------------------------------- */

void FixBrownianTessera::reset_dt()
{
  set_step();
}

/* ----------------------------------------------------------------------
   Displacement per step and component:
     dr = dt mobility F + sqrt(2 D dt) xi,  D = kB T / gamma_t,
   xi of zero mean and unit variance.  The unit conversions make F / gamma_t
   a velocity (ftm2v) and kB T / gamma_t a diffusion constant (mvv2e) in
   every LAMMPS unit system.  Uniform noise is u - 1/2 with u in [0,1),
   whose variance is 1/12.
------------------------------------------------------------------------- */

void FixBrownianTessera::set_step()
{
  dt = update->dt;
  // (0 is allowed for 'run 0', which takes no step; initial_integrate
  // refuses it)
  if (!(dt >= 0.0) || !std::isfinite(dt))
    error->all(FLERR,
               "Fix {} (ID {}): the timestep must be > 0 for overdamped dynamics (a displacement "
               "dt F/gamma_t and noise sqrt(2 D dt)), got {}; set it with 'timestep'",
               style, id, dt);
  mobility = force->ftm2v / gamma_t;
  const double diffusion = force->boltz * temperature / (force->mvv2e * gamma_t);
  const double sigma = sqrt(2.0 * diffusion * dt);
  if (noise == NOISE_UNIFORM)
    noise_scale = sqrt(12.0) * sigma;
  else if (noise == NOISE_GAUSSIAN)
    noise_scale = sigma;
  else
    noise_scale = 0.0;
}

/* ---------------------------------------------------------------------- */

void FixBrownianTessera::initial_integrate(int /*vflag*/)
{
  if (!(dt > 0.0))
    error->all(FLERR,
               "Fix {} (ID {}): the timestep must be > 0 to take a step (the velocity is the "
               "displacement over dt), got {}; set it with 'timestep'",
               style, id, dt);
  chatter->start(groupbit);
  const bool three_d = domain->dimension == 3;
  double watch[IntegratorChatter::NSUMS] = {0.0, 0.0, 0.0, 0.0};
  switch (noise) {
    case NOISE_UNIFORM:
      three_d ? move<NOISE_UNIFORM, 1>(watch) : move<NOISE_UNIFORM, 0>(watch);
      break;
    case NOISE_GAUSSIAN:
      three_d ? move<NOISE_GAUSSIAN, 1>(watch) : move<NOISE_GAUSSIAN, 0>(watch);
      break;
    default:
      three_d ? move<NOISE_NONE, 1>(watch) : move<NOISE_NONE, 0>(watch);
  }
  chatter->observe(style, id, watch, dt);
}

/* ----------------------------------------------------------------------
   One Euler-Maruyama step with the forces of the previous step; v = dr/dt.
   Random numbers are drawn per atom in the order x, y (, z).  The same
   pass adds the chatter watch's sums of the step (v before and after it)
   to watch.
------------------------------------------------------------------------- */

template <int NOISE, int THREE_D> void FixBrownianTessera::move(double *watch)
{
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  int *mask = atom->mask;
  int nlocal = atom->nlocal;
  if (igroup == atom->firstgroup) nlocal = atom->nfirst;

  const int ndim = THREE_D ? 3 : 2;
  const double drift = dt * mobility;

  // Without noise in 2D: the core's kernel on the flat arrays (LAMMPS keeps
  // 3 doubles per atom in one block), both components at once.
  const long last = 3 * static_cast<long>(nlocal - 1);
  if (NOISE == NOISE_NONE && !THREE_D && nlocal > 0 && x[nlocal - 1] == x[0] + last &&
      v[nlocal - 1] == v[0] + last && f[nlocal - 1] == f[0] + last) {
    tessera::overdamped_step_2d(nlocal, x[0], v[0], f[0], drift, dt, igroup == 0 ? nullptr : mask,
                                groupbit, watch);
    return;
  }

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double before[3] = {v[i][0], v[i][1], v[i][2]};
    for (int d = 0; d < ndim; d++) {
      double dr = drift * f[i][d];
      if (NOISE == NOISE_UNIFORM)
        dr += noise_scale * (random->uniform() - 0.5);
      else if (NOISE == NOISE_GAUSSIAN)
        dr += noise_scale * random->gaussian();
      x[i][d] += dr;
      v[i][d] = dr / dt;
    }
    if (!THREE_D) v[i][2] = 0.0;
    IntegratorChatter::add(watch, before, v[i], ndim);
  }
}

/* ---------------------------------------------------------------------- */

double FixBrownianTessera::parse_number(const char *what, const char *text)
{
  if (!utils::is_double(text))
    error->all(FLERR, "Fix {} (ID {}): {} must be a number, got '{}'", style, id, what, text);
  return utils::numeric(FLERR, text, false, lmp);
}
