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

   pair_style vertex/voronoi: the pair_style keywords and pair_coeff (both
   parameter forms, junction tensions between types, free tensions).
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "tessera/subset_cells.h"

#include <cmath>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

/* The pair_style keywords' defaults: for a new style and for a repeated
   pair_style line (LAMMPS calls settings() again on the same object). */

void PairVertexVoronoi::keyword_defaults()
{
  sphere_on = 0;
  tension = tessera::Tension::Edge;
  incremental = 1;
  incremental_given = 0;
  grow = 1;
  reference_every = 0;
  radius = 0.0;
}

/* ----------------------------------------------------------------------
   pair_style vertex/voronoi cutoff [tension edge|cell] [... surface sphere cx cy cz R]
------------------------------------------------------------------------- */

void PairVertexVoronoi::settings(int narg, char **arg)
{
  if (narg < 1)
    error->all(FLERR,
               "Illegal pair_style vertex/voronoi command: expected 'pair_style vertex/voronoi "
               "cutoff [tension edge|cell]'");
  cut_global = utils::numeric(FLERR, arg[0], false, lmp);
  if (!(cut_global > 0.0) || !std::isfinite(cut_global))
    error->all(FLERR,
               "pair_style vertex/voronoi: cutoff must be > 0 and finite, got {}; use "
               "about 2.5 to 3 cell diameters",
               arg[0]);
  int iarg = 1;
  // LAMMPS calls settings() again on the same object when a script repeats
  // 'pair_style vertex/voronoi': every keyword not on the new line takes its
  // default (a repeated line without 'radius' gives confluent cells again,
  // without 'surface' cells in the plane or in space), as for a new style.
  keyword_defaults();
  while (iarg < narg) {
    if (strcmp(arg[iarg], "tension") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR,
                   "pair_style vertex/voronoi: keyword 'tension' needs a value (edge or cell)");
      if (strcmp(arg[iarg + 1], "edge") == 0)
        tension = tessera::Tension::Edge;
      else if (strcmp(arg[iarg + 1], "cell") == 0)
        tension = tessera::Tension::Cell;
      else
        error->all(FLERR,
                   "pair_style vertex/voronoi: tension must be 'edge' (each junction once, "
                   "default) or 'cell' (Lambda*P per cell, as the thesis code), got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "incremental") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR,
                   "pair_style vertex/voronoi: keyword 'incremental' needs a value (yes or no)");
      incremental_given = 1;
      if (strcmp(arg[iarg + 1], "yes") == 0)
        incremental = 1;
      else if (strcmp(arg[iarg + 1], "no") == 0)
        incremental = 0;
      else if (strcmp(arg[iarg + 1], "check") == 0)
        incremental = 2;
      else
        error->all(FLERR,
                   "pair_style vertex/voronoi: incremental must be yes, no or check, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "grow") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "pair_style vertex/voronoi: keyword 'grow' needs a value (yes or no)");
      if (strcmp(arg[iarg + 1], "yes") == 0)
        grow = 1;
      else if (strcmp(arg[iarg + 1], "no") == 0)
        grow = 0;
      else
        error->all(FLERR, "pair_style vertex/voronoi: grow must be yes or no, got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "reference") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "pair_style vertex/voronoi: keyword 'reference' needs a value N");
      reference_every = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (reference_every < 0)
        error->all(FLERR, "pair_style vertex/voronoi: reference N must be >= 0, got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "radius") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR,
                   "pair_style vertex/voronoi: keyword 'radius' needs a value r (the "
                   "radius of the finite Voronoi cells)");
      radius = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(radius > 0.0) || !std::isfinite(radius))
        error->all(FLERR, "pair_style vertex/voronoi: radius must be > 0, got {}", arg[iarg + 1]);
      iarg += 2;
    } else if (strcmp(arg[iarg], "surface") == 0) {
      iarg = parse_surface(iarg, narg, arg);
    } else {
      error->all(FLERR,
                 "pair_style vertex/voronoi: unknown keyword '{}' (known: tension, incremental, "
                 "grow, reference, radius, surface)",
                 arg[iarg]);
    }
  }
  // Allocating now lets a missing pair_coeff be reported by type in init_style
  // rather than by LAMMPS's generic "All pair coeffs are not set".
  if (!allocated && atom->ntypes > 0) {
    allocate();
    for (int i = 1; i <= atom->ntypes; i++) setflag[i][i] = 1;
  }
}

/* ----------------------------------------------------------------------
   pair_coeff I I K A0 Gamma Lambda
   pair_coeff I I quadratic KA A0 KP P0
   pair_coeff I J Lambda           (I != J: junction tension between types)
------------------------------------------------------------------------- */

/* Every cell, whatever its type, is in one tessellation with all the
   others: a second vertex/voronoi under pair_style hybrid would tessellate
   its cells as if the first one's were not there (and the computes, which
   read one style's cells, would not find the style). */

void PairVertexVoronoi::check_single_instance() const
{
  if (force->pair == this) return;
  // (pair_match returns the only match whatever the sub-style number)
  Pair *second = force->pair_match("vertex/voronoi", 1, 2);
  if (!second || second == force->pair_match("vertex/voronoi", 1, 1)) return;
  error->all(FLERR,
             "pair_style {}: vertex/voronoi is given more than once; every cell shares one "
             "tessellation with all the others, whatever their types, so one vertex/voronoi "
             "describes them all: keep one in the pair_style line and give each cell type its "
             "parameters with 'pair_coeff I I vertex/voronoi ...' (and 'pair_coeff I J "
             "vertex/voronoi Lambda' for the tension between types I and J)",
             force->pair_style);
}

void PairVertexVoronoi::coeff(int narg, char **arg)
{
  check_single_instance();
  if (!allocated) {
    allocate();
    for (int i = 1; i <= atom->ntypes; i++) setflag[i][i] = 1;
  }
  if (narg < 3)
    error->all(FLERR,
               "pair_coeff for vertex/voronoi: expected 'pair_coeff I I K A0 Gamma Lambda', "
               "'pair_coeff I I quadratic KA A0 KP P0' or 'pair_coeff I J Lambda'");

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  const bool same = (ilo == jlo && ihi == jhi);
  const std::string where = fmt::format("pair_coeff {} {}", arg[0], arg[1]);

  // Trailing 'free F': the tension of the free (cell-medium) arcs of finite
  // Voronoi cells.
  bool has_free = false;
  double free_value = 0.0;
  if (narg >= 3 && strcmp(arg[narg - 1], "free") == 0)
    error->all(FLERR,
               "{}: keyword 'free' needs a value F (the tension of the cell-medium boundary of "
               "finite cells), e.g. 'pair_coeff I I K A0 Gamma Lambda free 0.2'",
               where);
  if (narg >= 5 && strcmp(arg[narg - 2], "free") == 0) {
    has_free = true;
    free_value = utils::numeric(FLERR, arg[narg - 1], false, lmp);
    if (!std::isfinite(free_value))
      error->all(FLERR, "{}: free tension must be finite, got {}", where, arg[narg - 1]);
    narg -= 2;
  }

  if (narg == 3 && strcmp(arg[2], "quadratic") == 0) {
    if (same)
      error->all(FLERR,
                 "{}: 'quadratic' needs the four values KA A0 KP P0 of the cells of this type: "
                 "'pair_coeff I I quadratic KA A0 KP P0'",
                 where);
    error->all(FLERR,
               "{}: 'quadratic' needs a value: the extra tension sigma of the junctions between "
               "the two types, 'pair_coeff I J quadratic sigma' (e.g. 'pair_coeff {} {} quadratic "
               "0.1')",
               where, arg[0], arg[1]);
  }

  // pair_coeff I J Lambda_IJ, or pair_coeff I J quadratic sigma: the extra
  // tension sigma of a heterotypic junction on top of the default mean
  // (energy sigma * l per junction, in either tension convention).
  const bool het_quadratic = narg == 4 && strcmp(arg[2], "quadratic") == 0;
  if (narg == 3 || het_quadratic) {
    const char *value = arg[narg - 1];
    const double lam = utils::numeric(FLERR, value, false, lmp);
    if (!std::isfinite(lam))
      error->all(FLERR, "{}: {} must be finite, got {}", where,
                 het_quadratic ? "the heterotypic tension sigma" : "Lambda", value);
    const int how = het_quadratic ? 2 : 1;
    int count = 0;
    auto set = [&](int i, int j) {
      setflag[i][j] = 1;    // pair_style hybrid maps the pair I J to this style
      lambda_set[i][j] = lambda_set[j][i] = how;
      if (how == 1) {
        lambda[i][j] = lambda[j][i] = lam;
      } else {
        lambda_extra[i][j] = lambda_extra[j][i] = lam;
      }
      count++;
    };
    for (int i = ilo; i <= ihi; i++)
      for (int j = MAX(jlo, i + 1); j <= jhi; j++) set(i, j);
    for (int i = jlo; i <= jhi; i++)
      for (int j = MAX(ilo, i + 1); j <= ihi; j++) set(i, j);
    if (has_free)
      error->all(FLERR,
                 "{}: 'free' is a per-type tension: give it with the cell parameters "
                 "(pair_coeff I I ... free F)",
                 where);
    if (count == 0 && het_quadratic)
      error->all(FLERR,
                 "{}: 'quadratic sigma' with one value sets the extra tension between two "
                 "different types; for type I's own cells use 'pair_coeff I I quadratic KA A0 KP "
                 "P0'",
                 where);
    if (count == 0)
      error->all(FLERR,
                 "{}: a single value sets Lambda between two different types; for type I's own "
                 "cells use 'pair_coeff I I K A0 Gamma Lambda'",
                 where);
    return;
  }

  if (!same)
    error->all(FLERR,
               "{}: cell parameters need the same type twice (pair_coeff I I K A0 Gamma "
               "Lambda); between different types give only Lambda (pair_coeff I J Lambda)",
               where);

  double K, A0, G, lam, ftension = free_value;
  const bool quadratic = strcmp(arg[2], "quadratic") == 0;
  if (quadratic) {
    if (narg != 7)
      error->all(FLERR, "{}: expected 'pair_coeff I I quadratic KA A0 KP P0 [free Lambda]'", where);
    tessera::QuadraticParams q;
    q.KA = utils::numeric(FLERR, arg[3], false, lmp);
    q.A0 = utils::numeric(FLERR, arg[4], false, lmp);
    q.KP = utils::numeric(FLERR, arg[5], false, lmp);
    q.P0 = utils::numeric(FLERR, arg[6], false, lmp);
    if (!(q.KA > 0.0)) error->all(FLERR, "{}: KA must be > 0, got {}", where, arg[3]);
    if (!(q.KP >= 0.0)) error->all(FLERR, "{}: KP must be >= 0, got {}", where, arg[5]);
    const tessera::CellType ct = tessera::cell_type_from_quadratic(q);
    K = ct.K;
    A0 = ct.A0;
    G = ct.Gamma;
    lam = tessera::lambda_from_quadratic(q, tension);
    // KP (P - P0)^2 + Lambda L: the arcs carry -2 KP P0 per length besides Lambda.
    ftension = free_value - 2.0 * q.KP * q.P0;
  } else {
    if (narg != 6)
      error->all(FLERR,
                 "{}: expected 4 values K A0 Gamma Lambda (the thesis's order kappa, A0, Gamma, "
                 "Lambda), got {}",
                 where, narg - 2);
    K = utils::numeric(FLERR, arg[2], false, lmp);
    A0 = utils::numeric(FLERR, arg[3], false, lmp);
    G = utils::numeric(FLERR, arg[4], false, lmp);
    lam = utils::numeric(FLERR, arg[5], false, lmp);
    if (!(K > 0.0) || !std::isfinite(K))
      error->all(FLERR, "{}: area modulus K must be > 0, got {}", where, arg[2]);
    if (!(G >= 0.0) || !std::isfinite(G))
      error->all(FLERR,
                 "{}: perimeter modulus Gamma must be >= 0, got {} (with Gamma < 0 the energy "
                 "has no minimum: cells lower it by growing their perimeters without bound)",
                 where, arg[4]);
    if (!std::isfinite(lam)) error->all(FLERR, "{}: Lambda must be finite, got {}", where, arg[5]);
  }
  if (!(A0 > 0.0) || !std::isfinite(A0))
    error->all(FLERR, "{}: preferred area A0 must be > 0, got {}", where, A0);

  for (int i = ilo; i <= ihi; i++) {
    kappa[i] = K;
    area0[i] = A0;
    gamma[i] = G;
    lambda[i][i] = lam;
    lambda_set[i][i] = 1;
    type_set[i] = 1;
    setflag[i][i] = 1;
    free_tension[i] = ftension;
    quad_set[i] = quadratic ? 1 : 0;
  }
  if (has_free) free_set = 1;
}
