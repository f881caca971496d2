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

   pair_style vertex/voronoi: the ghost shell.  Its width, and its growth
   in the middle of a step when a cell reaches past the ghost atoms (the
   atoms acquired again as at a neighbor-list build), or the error that
   names the cutoff to use.  Apart from the face (pair_vertex_voronoi.cpp):
   every model unit asks it, and it talks only to LAMMPS's communication.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

/* Width of the region around this rank's sub-domain in which every atom is
   known: the ghost cutoff less half the skin that atoms may have moved since
   the last neighbor list build. */

double PairVertexVoronoi::ghost_width() const
{
  return MAX(neighbor->cutneighmax, comm->cutghostuser) - 0.5 * neighbor->skin;
}

/* The ghost shell was too thin: widen it to cut and acquire the ghost atoms
   again now, with the steps of a neighbor-list build (remap into the box,
   exchange, borders, the fixes' neighbor hooks, the distance-check
   reference), so that this step's forces are computed with complete cells.
   The pair style computes the first forces of a step, so the force array
   only needs clearing for the new set of atoms. */

void PairVertexVoronoi::grow_ghost_shell(double cut)
{
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "pair_style vertex/voronoi: cutoff grown from {:.4g} to {:.4g} at step {} (a "
                   "cell needed a wider ghost shell)\n",
                   cut_global, cut, update->ntimestep);
  cut_global = cut;
  cutforce = cut;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = 1; j <= atom->ntypes; j++) cutsq[i][j] = cut * cut;
  if (cutghost_saved < 0.0) cutghost_saved = comm->cutghostuser;
  comm->cutghostuser = MAX(comm->cutghostuser, cut + neighbor->skin);
  if (domain->triclinic) domain->x2lamda(atom->nlocal);
  domain->pbc();
  comm->setup();
  comm->exchange();
  comm->borders();
  if (domain->triclinic) domain->lamda2x(atom->nlocal + atom->nghost);
  if (modify->n_pre_neighbor) modify->pre_neighbor();
  neighbor->build(1);
  if (modify->n_post_neighbor) modify->post_neighbor();
  const int nall = atom->nlocal + atom->nghost;
  double **f = atom->f;
  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  if (atom->torque_flag)
    for (int i = 0; i < nall; i++)
      atom->torque[i][0] = atom->torque[i][1] = atom->torque[i][2] = 0.0;
}

/* need_local: how much wider this rank's cells need the ghost shell. */

bool PairVertexVoronoi::ghost_shell_complete(double need_local)
{
  double need_all;
  MPI_Allreduce(&need_local, &need_all, 1, MPI_DOUBLE, MPI_MAX, world);
  if (!(need_all > 0.0)) return true;
  const bool infinite = std::isinf(need_all);
  const double needed = infinite ? 2.0 * cut_global : 1.1 * (cut_global + need_all);
  double lmax = MAX(domain->xprd, domain->yprd);
  if (domain->dimension == 3) lmax = MAX(lmax, domain->zprd);
  if (grow && force->pair == this && needed <= 2.0 * lmax + cut_global) {
    grow_ghost_shell(MAX(needed, 1.2 * cut_global));
    return false;
  }
  // Inside pair_style hybrid/overlay the other sub-styles may have computed
  // this step's forces already: the atoms cannot be acquired again now.
  if (force->pair != this)
    error->all(FLERR,
               "pair_style vertex/voronoi: cutoff {:.6g} is too small for this configuration "
               "({}); inside pair_style hybrid/overlay the ghost shell cannot grow during a "
               "step: give vertex/voronoi a cutoff of {:.3g} or larger ('pair_style "
               "hybrid/overlay vertex/voronoi {:.3g} ...')",
               cut_global,
               infinite ? "some cells have no complete ring of neighbours"
                        : "a cell reaches past the ghost atoms",
               needed, needed);
  if (infinite)
    error->all(FLERR,
               "pair_style vertex/voronoi: cutoff {} is far too small: some cells have no "
               "complete {} of neighbours; use a cutoff of at least 2.5 cell diameters",
               cut_global, domain->dimension == 3 ? "shell" : "ring");
  // On the sphere every rank holds every cell; what it needs within the
  // ghost shell are the owned cells' neighbours, not circumspheres.
  const char *why = sphere_on  ? "a neighbour of a cell of this rank lies past the ghost atoms"
      : domain->dimension == 3 ? "a Voronoi vertex's circumsphere reaches past the ghost atoms"
                               : "a Voronoi vertex's circumcircle reaches past the ghost atoms";
  error->all(FLERR,
             "pair_style vertex/voronoi: cutoff {:.6g} is too small for this configuration "
             "({}); use 'pair_style vertex/voronoi {:.3g}' or larger",
             cut_global, why, needed);
  return true;
}
