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

   pair_style vertex/voronoi: restart files carry every setting and every
   per-type and type-pair value (see the layout below).
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "tessera/subset_cells.h"

using namespace LAMMPS_NS;

// The restart layout: settings, then per type and type pair.  Files of the
// first layout (cutoff and tension only) store tension as 0 or 1; later ones
// add RESTART_V2 to it and carry every keyword and the heterotypic sigma;
// the third layout (RESTART_V3) adds, at the end, which types were given in
// the quadratic form (whose constant the energy includes); the fourth
// (RESTART_V4) adds the 'surface' settings after the radius.
static constexpr int RESTART_V2 = 16;
static constexpr int RESTART_V3 = 32;
static constexpr int RESTART_V4 = 64;

void PairVertexVoronoi::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++) {
    fwrite(&type_set[i], sizeof(int), 1, fp);
    fwrite(&kappa[i], sizeof(double), 1, fp);
    fwrite(&area0[i], sizeof(double), 1, fp);
    fwrite(&gamma[i], sizeof(double), 1, fp);
    for (int j = 1; j <= n; j++) {
      fwrite(&lambda_set[i][j], sizeof(int), 1, fp);
      fwrite(&lambda[i][j], sizeof(double), 1, fp);
      fwrite(&lambda_extra[i][j], sizeof(double), 1, fp);
    }
  }
  for (int i = 1; i <= n; i++) fwrite(&free_tension[i], sizeof(double), 1, fp);
  fwrite(&free_set, sizeof(int), 1, fp);
  for (int i = 1; i <= n; i++) fwrite(&quad_set[i], sizeof(int), 1, fp);
}

void PairVertexVoronoi::read_restart(FILE *fp)
{
  const int version = read_restart_settings_version(fp);
  allocate();
  const int n = atom->ntypes;
  const int me = comm->me;
  for (int i = 1; i <= n; i++) {
    if (me == 0) {
      utils::sfread(FLERR, &type_set[i], sizeof(int), 1, fp, nullptr, error);
      utils::sfread(FLERR, &kappa[i], sizeof(double), 1, fp, nullptr, error);
      utils::sfread(FLERR, &area0[i], sizeof(double), 1, fp, nullptr, error);
      utils::sfread(FLERR, &gamma[i], sizeof(double), 1, fp, nullptr, error);
    }
    MPI_Bcast(&type_set[i], 1, MPI_INT, 0, world);
    MPI_Bcast(&kappa[i], 1, MPI_DOUBLE, 0, world);
    MPI_Bcast(&area0[i], 1, MPI_DOUBLE, 0, world);
    MPI_Bcast(&gamma[i], 1, MPI_DOUBLE, 0, world);
    setflag[i][i] = 1;
    for (int j = 1; j <= n; j++) {
      if (me == 0) {
        utils::sfread(FLERR, &lambda_set[i][j], sizeof(int), 1, fp, nullptr, error);
        utils::sfread(FLERR, &lambda[i][j], sizeof(double), 1, fp, nullptr, error);
      }
      if (me == 0 && version >= 2)
        utils::sfread(FLERR, &lambda_extra[i][j], sizeof(double), 1, fp, nullptr, error);
      MPI_Bcast(&lambda_set[i][j], 1, MPI_INT, 0, world);
      MPI_Bcast(&lambda[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&lambda_extra[i][j], 1, MPI_DOUBLE, 0, world);
    }
  }
  // Finite cells: the free tensions per type, after everything else (files
  // of the first layout have none).
  if (version < 2) return;
  for (int i = 1; i <= n; i++) {
    if (me == 0) utils::sfread(FLERR, &free_tension[i], sizeof(double), 1, fp, nullptr, error);
    MPI_Bcast(&free_tension[i], 1, MPI_DOUBLE, 0, world);
  }
  if (me == 0) utils::sfread(FLERR, &free_set, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&free_set, 1, MPI_INT, 0, world);
  if (version < 3) return;
  for (int i = 1; i <= n; i++) {
    if (me == 0) utils::sfread(FLERR, &quad_set[i], sizeof(int), 1, fp, nullptr, error);
    MPI_Bcast(&quad_set[i], 1, MPI_INT, 0, world);
  }
}

void PairVertexVoronoi::write_restart_settings(FILE *fp)
{
  int t = (tension == tessera::Tension::Edge ? 0 : 1) + RESTART_V4;
  fwrite(&cut_global, sizeof(double), 1, fp);
  fwrite(&t, sizeof(int), 1, fp);
  fwrite(&incremental, sizeof(int), 1, fp);
  fwrite(&grow, sizeof(int), 1, fp);
  fwrite(&reference_every, sizeof(int), 1, fp);
  fwrite(&radius, sizeof(double), 1, fp);
  write_sphere_settings(fp);
}

void PairVertexVoronoi::read_restart_settings(FILE *fp)
{
  read_restart_settings_version(fp);
}

int PairVertexVoronoi::read_restart_settings_version(FILE *fp)
{
  int t = 0;
  if (comm->me == 0) {
    utils::sfread(FLERR, &cut_global, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &t, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Bcast(&cut_global, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&t, 1, MPI_INT, 0, world);
  const int version = t >= RESTART_V4 ? 4 : t >= RESTART_V3 ? 3 : t >= RESTART_V2 ? 2 : 1;
  if (version >= 2) {
    t -= version == 4 ? RESTART_V4 : version == 3 ? RESTART_V3 : RESTART_V2;
    int v[3] = {incremental, grow, reference_every};
    if (comm->me == 0) utils::sfread(FLERR, v, sizeof(int), 3, fp, nullptr, error);
    MPI_Bcast(v, 3, MPI_INT, 0, world);
    incremental = v[0];
    grow = v[1];
    reference_every = v[2];
    if (comm->me == 0) utils::sfread(FLERR, &radius, sizeof(double), 1, fp, nullptr, error);
    MPI_Bcast(&radius, 1, MPI_DOUBLE, 0, world);
  }
  if (version >= 4) read_sphere_settings(fp);
  tension = t == 0 ? tessera::Tension::Edge : tessera::Tension::Cell;
  return version;
}
