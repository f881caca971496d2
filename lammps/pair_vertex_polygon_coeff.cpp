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

   pair_style vertex/polygon: the pair_style keywords, pair_coeff (cell types
   in both parameter forms, junction tensions between types, vertex types),
   the core's model built from them, and restart files.
------------------------------------------------------------------------- */

#include "pair_vertex_polygon.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "hybrid_access.h"
#include "memory.h"
#include "tessera/vertex_model.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   pair_style vertex/polygon cutoff [t1 l_T1 l_new] [t2 a_T2]
------------------------------------------------------------------------- */

void PairVertexPolygon::settings(int narg, char **arg)
{
  if (narg < 1)
    error->all(FLERR,
               "Illegal pair_style vertex/polygon command: expected 'pair_style vertex/polygon "
               "cutoff [t1 l_T1 l_new] [t2 a_T2]'");
  cut_global = utils::numeric(FLERR, arg[0], false, lmp);
  if (!(cut_global > 0.0) || !std::isfinite(cut_global))
    error->all(FLERR,
               "pair_style vertex/polygon: cutoff must be > 0 and finite, got {}; use about 3.5 "
               "cell diameters",
               arg[0]);
  topo = tessera::TopologyParams();
  int iarg = 1;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "t1") == 0) {
      if (iarg + 3 > narg)
        error->all(FLERR, "pair_style vertex/polygon: keyword 't1' needs two values: l_T1 l_new");
      topo.t1_length = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      topo.t1_new = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
      if (!(topo.t1_length > 0.0) || !std::isfinite(topo.t1_length))
        error->all(FLERR, "pair_style vertex/polygon: t1 l_T1 must be > 0, got {}", arg[iarg + 1]);
      if (!(topo.t1_new > topo.t1_length) || !std::isfinite(topo.t1_new))
        error->all(FLERR,
                   "pair_style vertex/polygon: t1 l_new must be larger than l_T1 (else the new "
                   "edge is at once a candidate again), got l_T1 {} l_new {}",
                   arg[iarg + 1], arg[iarg + 2]);
      iarg += 3;
    } else if (strcmp(arg[iarg], "t2") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "pair_style vertex/polygon: keyword 't2' needs a value: a_T2");
      topo.t2_area = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(topo.t2_area > 0.0) || !std::isfinite(topo.t2_area))
        error->all(FLERR, "pair_style vertex/polygon: t2 a_T2 must be > 0, got {}", arg[iarg + 1]);
      iarg += 2;
    } else {
      error->all(FLERR, "pair_style vertex/polygon: unknown keyword '{}' (known: t1, t2)",
                 arg[iarg]);
    }
  }
}

void PairVertexPolygon::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  for (int i = 0; i <= n; i++)
    for (int j = 0; j <= n; j++) {
      setflag[i][j] = 0;
      cutsq[i][j] = 0.0;
    }
  roles.assign(n + 1, NONE);
  quad.assign(n + 1, 0);
  kappa.assign(n + 1, 0.0);
  area0.assign(n + 1, 0.0);
  gamma.assign(n + 1, 0.0);
  energy0.assign(n + 1, 0.0);
  lambda.assign(n + 1, std::vector<double>(n + 1, 0.0));
  sigma.assign(n + 1, std::vector<double>(n + 1, 0.0));
  lambda_set.assign(n + 1, std::vector<int>(n + 1, 0));
}

/* ----------------------------------------------------------------------
   pair_coeff I I quadratic KA A0 KP P0 | I I K A0 Gamma Lambda | I I vertex
   pair_coeff I J quadratic sigma | I J Lambda
------------------------------------------------------------------------- */

void PairVertexPolygon::coeff(int narg, char **arg)
{
  if (narg < 3)
    error->all(FLERR,
               "Incorrect args for pair_coeff of vertex/polygon: expected 'I I quadratic KA A0 KP "
               "P0', 'I I K A0 Gamma Lambda', 'I I vertex', 'I J quadratic sigma' or 'I J "
               "Lambda'");
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  const bool quadratic = strcmp(arg[2], "quadratic") == 0;
  const int nval = narg - 2 - (quadratic ? 1 : 0);
  auto number = [&](int k, const char *what) {
    const double v = utils::numeric(FLERR, arg[k], false, lmp);
    if (!std::isfinite(v))
      error->all(FLERR, "pair_coeff of vertex/polygon: {} must be finite, got {}", what, arg[k]);
    return v;
  };
  int count = 0;
  if (strcmp(arg[2], "vertex") == 0) {
    if (narg != 3) error->all(FLERR, "pair_coeff of vertex/polygon: 'I I vertex' takes no values");
    for (int i = ilo; i <= ihi; i++)
      for (int j = MAX(jlo, i); j <= jhi; j++) {
        if (i != j) continue;
        roles[i] = VERTEX;
        setflag[i][i] = 1;
        count++;
      }
  } else if (nval == 4) {
    // A cell type: quadratic KA A0 KP P0, or K A0 Gamma Lambda.
    const double v0 = number(2 + quadratic, quadratic ? "KA" : "K");
    const double a0 = number(3 + quadratic, "A0");
    const double v2 = number(4 + quadratic, quadratic ? "KP" : "Gamma");
    const double v3 = number(5 + quadratic, quadratic ? "P0" : "Lambda");
    if (!(v0 > 0.0))
      error->all(FLERR, "pair_coeff of vertex/polygon: {} must be > 0, got {}",
                 quadratic ? "KA" : "K", v0);
    if (!(a0 > 0.0)) error->all(FLERR, "pair_coeff of vertex/polygon: A0 must be > 0, got {}", a0);
    if (v2 < 0.0)
      error->all(FLERR, "pair_coeff of vertex/polygon: {} must be >= 0, got {}",
                 quadratic ? "KP" : "Gamma", v2);
    for (int i = ilo; i <= ihi; i++)
      for (int j = MAX(jlo, i); j <= jhi; j++) {
        if (i != j) continue;
        roles[i] = CELL;
        quad[i] = quadratic;
        area0[i] = a0;
        if (quadratic) {
          const tessera::QuadraticParams q{v0, a0, v2, v3};
          const tessera::CellType ct = tessera::cell_type_from_quadratic(q);
          kappa[i] = ct.K;
          gamma[i] = ct.Gamma;
          lambda[i][i] = tessera::lambda_from_quadratic(q, tessera::Tension::Edge);
        } else {
          kappa[i] = v0;
          gamma[i] = v2;
          lambda[i][i] = v3;
        }
        setflag[i][i] = 1;
        count++;
      }
  } else if (nval == 1) {
    // A junction tension between two types.
    const double v = number(2 + quadratic, quadratic ? "sigma" : "Lambda");
    for (int i = ilo; i <= ihi; i++)
      for (int j = MAX(jlo, i); j <= jhi; j++) {
        if (i == j) continue;
        if (quadratic) {
          sigma[i][j] = sigma[j][i] = v;
          lambda_set[i][j] = lambda_set[j][i] = 2;
        } else {
          lambda[i][j] = lambda[j][i] = v;
          lambda_set[i][j] = lambda_set[j][i] = 1;
        }
        setflag[i][j] = 1;
        count++;
      }
  } else {
    error->all(FLERR,
               "Incorrect args for pair_coeff of vertex/polygon: expected 'I I quadratic KA A0 KP "
               "P0', 'I I K A0 Gamma Lambda', 'I I vertex', 'I J quadratic sigma' or 'I J "
               "Lambda'");
  }
  if (count == 0)
    error->all(FLERR,
               "Incorrect args for pair_coeff of vertex/polygon: '{} {}' names no type pair this "
               "form applies to (cell and vertex types: I I; junction tensions: I J, I != J)",
               arg[0], arg[1]);
}

/* The core's model: per-type values, and Lambda_IJ given, the mean of the
   two same-type values, or that mean plus sigma; the quadratic form's
   constant per type. */

void PairVertexPolygon::build_model()
{
  const int n = atom->ntypes;
  model = tessera::Model(n);
  model.tension = tessera::Tension::Edge;
  for (int i = 1; i <= n; i++)
    model.types[i - 1] = roles[i] == CELL ? tessera::CellType{kappa[i], area0[i], gamma[i]}
                                          : tessera::CellType{1.0, 1.0, 0.0};
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      double lam = lambda[i][j];
      if (i != j && lambda_set[i][j] != 1) {
        lam = 0.5 * (lambda[i][i] + lambda[j][j]);
        if (lambda_set[i][j] == 2) lam += sigma[i][j];
      }
      model.set_lambda(i - 1, j - 1, lam);
    }
  // fix adapt's arrays: the values in use (reinit tells what it changed).
  if (!adapt_kappa) {
    memory->create(adapt_kappa, n + 1, n + 1, "pair:adapt_kappa");
    memory->create(adapt_area0, n + 1, n + 1, "pair:adapt_area0");
    memory->create(adapt_gamma, n + 1, n + 1, "pair:adapt_gamma");
    memory->create(adapt_lambda, n + 1, n + 1, "pair:adapt_lambda");
    memory->create(built_lambda, n + 1, n + 1, "pair:built_lambda");
  }
  for (int i = 0; i <= n; i++)
    for (int j = 0; j <= n; j++) {
      const int t = i <= j ? i : j;
      const bool cells = i > 0 && j > 0;
      adapt_kappa[i][j] = cells ? kappa[t] : 0.0;
      adapt_area0[i][j] = cells ? area0[t] : 0.0;
      adapt_gamma[i][j] = cells ? gamma[t] : 0.0;
      adapt_lambda[i][j] = built_lambda[i][j] = cells ? model.lambda_of(i - 1, j - 1) : 0.0;
    }
  const double w = model.tension_weight();
  for (int i = 1; i <= n; i++) {
    const double wl = w * model.lambda_of(i - 1, i - 1);
    energy0[i] = roles[i] == CELL && quad[i] && gamma[i] > 0.0 ? wl * wl / (2.0 * gamma[i]) : 0.0;
  }
  try {
    model.validate();
  } catch (tessera::Error &e) {
    error->all(FLERR, "pair_style vertex/polygon: {}", e.what());
  }
}

void PairVertexPolygon::print_model() const
{
  if (comm->me != 0) return;
  const int n = atom->ntypes;
  std::string msg = fmt::format("pair_style vertex/polygon: cutoff {:.6g}", cut_global);
  if (topo.t1_length > 0.0)
    msg += fmt::format(" t1 {:.6g} {:.6g}", topo.t1_length, topo.t1_new);
  else
    msg += " (no T1s)";
  if (topo.t2_area > 0.0)
    msg += fmt::format(" t2 {:.6g}", topo.t2_area);
  else
    msg += " (no T2s)";
  msg += fmt::format("; rings: i_vring, up to {} sides\n", ring_width);
  msg += "  type        KA         A0         KP         P0\n";
  for (int i = 1; i <= n; i++) {
    if (roles[i] != CELL) {
      msg += fmt::format("  {:4d}   {}\n", i,
                         roles[i] == VERTEX ? "vertices" : "particles (other pair styles)");
      continue;
    }
    const double lam = model.lambda_of(i - 1, i - 1);
    const double p0 = gamma[i] > 0.0 ? -0.5 * lam / gamma[i] : 0.0;
    msg += fmt::format("  {:4d} {:10.4g} {:10.4g} {:10.4g} {:>10}\n", i, 0.5 * kappa[i], area0[i],
                       0.5 * gamma[i], gamma[i] > 0.0 ? fmt::format("{:.4g}", p0) : "-");
  }
  msg += "  effective junction tension Lambda_IJ (each junction once):\n      ";
  for (int j = 1; j <= n; j++) msg += fmt::format(" {:>10d}", j);
  msg += "\n";
  for (int i = 1; i <= n; i++) {
    msg += fmt::format("  {:4d}", i);
    for (int j = 1; j <= n; j++)
      msg += roles[i] == CELL && roles[j] == CELL
          ? fmt::format(" {:10.4g}", model.lambda_of(i - 1, j - 1))
          : fmt::format(" {:>10}", "-");
    msg += "\n";
  }
  utils::logmesg(lmp, msg);
}

/* Restart files: the settings, the rings' width (to define fix vring again
   after read_restart), the counts, then per type and type pair. */

void PairVertexPolygon::write_restart_settings(FILE *fp)
{
  fwrite(&cut_global, sizeof(double), 1, fp);
  fwrite(&topo.t1_length, sizeof(double), 1, fp);
  fwrite(&topo.t1_new, sizeof(double), 1, fp);
  fwrite(&topo.t2_area, sizeof(double), 1, fp);
  fwrite(&ring_width, sizeof(int), 1, fp);
  fwrite(stats, sizeof(double), 4, fp);
  fwrite(&topology_step, sizeof(bigint), 1, fp);
  fwrite(&delete_step, sizeof(bigint), 1, fp);
}

void PairVertexPolygon::read_restart_settings(FILE *fp)
{
  if (comm->me == 0) {
    utils::sfread(FLERR, &cut_global, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &topo.t1_length, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &topo.t1_new, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &topo.t2_area, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &restart_ring_width, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, stats, sizeof(double), 4, fp, nullptr, error);
    utils::sfread(FLERR, &topology_step, sizeof(bigint), 1, fp, nullptr, error);
    utils::sfread(FLERR, &delete_step, sizeof(bigint), 1, fp, nullptr, error);
  }
  MPI_Bcast(&cut_global, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&topo.t1_length, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&topo.t1_new, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&topo.t2_area, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&restart_ring_width, 1, MPI_INT, 0, world);
  MPI_Bcast(stats, 4, MPI_DOUBLE, 0, world);
  MPI_Bcast(&topology_step, 1, MPI_LMP_BIGINT, 0, world);
  MPI_Bcast(&delete_step, 1, MPI_LMP_BIGINT, 0, world);
}

void PairVertexPolygon::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++) {
    fwrite(&roles[i], sizeof(int), 1, fp);
    fwrite(&quad[i], sizeof(int), 1, fp);
    fwrite(&kappa[i], sizeof(double), 1, fp);
    fwrite(&area0[i], sizeof(double), 1, fp);
    fwrite(&gamma[i], sizeof(double), 1, fp);
    for (int j = 1; j <= n; j++) {
      fwrite(&lambda_set[i][j], sizeof(int), 1, fp);
      fwrite(&lambda[i][j], sizeof(double), 1, fp);
      fwrite(&sigma[i][j], sizeof(double), 1, fp);
    }
  }
}

void PairVertexPolygon::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  const int n = atom->ntypes;
  const bool me0 = comm->me == 0;
  auto rd = [&](void *p, size_t size) {
    if (me0) utils::sfread(FLERR, p, size, 1, fp, nullptr, error);
  };
  for (int i = 1; i <= n; i++) {
    rd(&roles[i], sizeof(int));
    rd(&quad[i], sizeof(int));
    rd(&kappa[i], sizeof(double));
    rd(&area0[i], sizeof(double));
    rd(&gamma[i], sizeof(double));
    MPI_Bcast(&roles[i], 1, MPI_INT, 0, world);
    MPI_Bcast(&quad[i], 1, MPI_INT, 0, world);
    MPI_Bcast(&kappa[i], 1, MPI_DOUBLE, 0, world);
    MPI_Bcast(&area0[i], 1, MPI_DOUBLE, 0, world);
    MPI_Bcast(&gamma[i], 1, MPI_DOUBLE, 0, world);
    if (roles[i] != NONE) setflag[i][i] = 1;
    for (int j = 1; j <= n; j++) {
      rd(&lambda_set[i][j], sizeof(int));
      rd(&lambda[i][j], sizeof(double));
      rd(&sigma[i][j], sizeof(double));
      MPI_Bcast(&lambda_set[i][j], 1, MPI_INT, 0, world);
      MPI_Bcast(&lambda[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&sigma[i][j], 1, MPI_DOUBLE, 0, world);
      if (lambda_set[i][j]) setflag[i][j] = 1;
    }
  }
}

/* Under pair_style hybrid/overlay (or hybrid), the types without a
   pair_coeff of this style are particles: atoms of no cell that other
   sub-styles move among the vertices.  A cell atom is bookkeeping at its
   polygon's centroid whose force goes to its vertices shared as an active
   force is (fix polarity's), which for another style's force would not be
   the gradient of its energy: other styles act on vertex and particle types
   only.  A junction tension names two cell types. */

void PairVertexPolygon::check_hybrid() const
{
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++)
    for (int j = i + 1; j <= n; j++)
      if (lambda_set[i][j] && (role(i) != CELL || role(j) != CELL)) {
        const int t = role(i) != CELL ? i : j;
        error->all(FLERR,
                   "pair_coeff {} {} vertex/polygon: a junction tension between types {} and {}, "
                   "but type {} is {}: tensions are between cell types; remove this pair_coeff",
                   i, j, i, j, t, role(t) == VERTEX ? "a vertex type" : "no type of this style");
      }
  if (force->pair == this) return;
  auto *hybrid = dynamic_cast<PairHybrid *>(force->pair);
  if (!hybrid)
    error->all(FLERR, "pair_style vertex/polygon: the pair style {} is neither it nor a hybrid",
               force->pair_style);
  for (int m = 0; m < HybridAccess::count(hybrid); m++) {
    if (HybridAccess::style(hybrid, m) == this) continue;
    for (int i = 1; i <= n; i++)
      for (int j = 1; j <= n; j++)
        if (role(i) == CELL && HybridAccess::gives(hybrid, MIN(i, j), MAX(i, j), m))
          error->all(FLERR,
                     "pair_style {}: pair_coeff gives the type pair {} {} to pair style {}, but "
                     "type {} is a cell type of vertex/polygon: a cell atom sits at its polygon's "
                     "centroid and its force is shared among its vertices (as fix polarity's "
                     "is), which for {}'s force is not the gradient of its energy; let other "
                     "styles act on the vertex and particle types only (e.g. 'pair_coeff {} {} "
                     "none' after the pair_coeff that named them)",
                     force->pair_style, MIN(i, j), MAX(i, j), HybridAccess::keyword(hybrid, m), i,
                     HybridAccess::keyword(hybrid, m), MIN(i, j), MAX(i, j));
  }
}
