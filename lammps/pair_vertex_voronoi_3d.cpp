/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   pair_style vertex/voronoi in 'dimension 3': the 3D Voronoi cells of the
   atoms (tessera/voronoi3d.h), energy
     E = sum_i [ K/2 (V_i - V0)^2 + Gamma/2 S_i^2 ] + sum_faces Lambda_IJ a_f
   with the pair_coeff values of 2D read as K, V0, Gamma, Lambda (and
   'quadratic KV V0 KS S0' for Merkel & Manning's form).  Each rank
   tetrahedralises its owned and ghost atoms from scratch every step; every
   circumsphere of an owned cell must lie inside the ghost shell, checked
   every step, and the shell grows as in 2D when it does not.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <vector>

using namespace LAMMPS_NS;

void PairVertexVoronoi::init_style_3d()
{
  if (!domain->xperiodic || !domain->yperiodic || !domain->zperiodic)
    error->all(FLERR,
               "pair_style vertex/voronoi in 3d requires periodic x, y and z boundaries "
               "('boundary p p p')");
  if (radius > 0.0)
    error->all(FLERR,
               "pair_style vertex/voronoi: finite cells ('radius') are for 2d tissues; in 3d "
               "the cells are confluent Voronoi polyhedra");
  int flag = -1, cols = -1;
  if (atom->find_custom("area0", flag, cols) >= 0)
    error->all(FLERR,
               "pair_style vertex/voronoi: per-atom preferred areas (d_area0) are for 2d; in 3d "
               "the preferred volume V0 is set per type by pair_coeff");
  if (reference_every > 0)
    error->all(FLERR,
               "pair_style vertex/voronoi: 'reference' times the 2d triangulation; in 3d every "
               "step is a from-scratch triangulation already");
  if (incremental == 2)
    error->all(FLERR,
               "pair_style vertex/voronoi: 'incremental check' is for 2d; in 3d the cells are "
               "triangulated from scratch every step");
}

bool PairVertexVoronoi::tessellation3_current() const
{
  return tess3_step == update->ntimestep && tess3.n_owned == atom->nlocal;
}

bool PairVertexVoronoi::tessellate_3d()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const tessera::Points3 pts{&atom->x[0][0], nall, 3};
  try {
    tess3 = tessera::tessellate_local_3d(pts, nlocal, nullptr, false);
  } catch (tessera::Error &) {
    // Redo with atom IDs so that the message names them.
    std::vector<long> ids(nall);
    for (int i = 0; i < nall; i++) ids[i] = atom->tag[i];
    try {
      tess3 = tessera::tessellate_local_3d(pts, nlocal, ids.data(), false);
    } catch (tessera::Error &e) {
      error->one(FLERR, "pair_style vertex/voronoi: {}", e.what());
    }
    error->one(FLERR, "pair_style vertex/voronoi: tessellation failed");
  }
  stats[2] += 1.0;
  // This rank's sub-domain: a box, or for a triclinic box the parallelepiped
  // of its lamda range, whose ghost shell is bounded by planes parallel to
  // its faces at the ghost cutoff.
  tessera::Region3 sub;
  if (!domain->triclinic) {
    for (int d = 0; d < 3; d++) {
      sub.o[d] = domain->sublo[d];
      sub.a[d] = sub.b[d] = sub.c[d] = 0.0;
    }
    sub.a[0] = domain->subhi[0] - domain->sublo[0];
    sub.b[1] = domain->subhi[1] - domain->sublo[1];
    sub.c[2] = domain->subhi[2] - domain->sublo[2];
  } else {
    double lo[3] = {domain->sublo_lamda[0], domain->sublo_lamda[1], domain->sublo_lamda[2]};
    domain->lamda2x(lo, sub.o);
    const double f[3] = {domain->subhi_lamda[0] - domain->sublo_lamda[0],
                         domain->subhi_lamda[1] - domain->sublo_lamda[1],
                         domain->subhi_lamda[2] - domain->sublo_lamda[2]};
    sub.a[0] = f[0] * domain->xprd;
    sub.a[1] = sub.a[2] = 0.0;
    sub.b[0] = f[1] * domain->xy;
    sub.b[1] = f[1] * domain->yprd;
    sub.b[2] = 0.0;
    sub.c[0] = f[2] * domain->xz;
    sub.c[1] = f[2] * domain->yz;
    sub.c[2] = f[2] * domain->zprd;
  }
  const tessera::Coverage cov = tessera::check_coverage_3d(tess3, sub, ghost_width());
  double need = cov.needed_margin, need_all;
  MPI_Allreduce(&need, &need_all, 1, MPI_DOUBLE, MPI_MAX, world);
  if (need_all > 0.0) {
    const bool infinite = std::isinf(need_all);
    const double needed = infinite ? 2.0 * cut_global : 1.1 * (cut_global + need_all);
    const double lmax = MAX(domain->xprd, MAX(domain->yprd, domain->zprd));
    if (grow && force->pair == this && needed <= 2.0 * lmax + cut_global) {
      grow_ghost_shell(MAX(needed, 1.2 * cut_global));
      return true;
    }
    if (infinite)
      error->all(FLERR,
                 "pair_style vertex/voronoi: cutoff {} is far too small: some cells have no "
                 "complete shell of neighbours; use a cutoff of at least 2.5 cell diameters",
                 cut_global);
    error->all(FLERR,
               "pair_style vertex/voronoi: cutoff {:.6g} is too small for this configuration "
               "(a Voronoi vertex's circumsphere reaches past the ghost atoms); use "
               "'pair_style vertex/voronoi {:.3g}' or larger",
               cut_global, needed);
  }
  tess3_step = update->ntimestep;
  return false;
}

void PairVertexVoronoi::compute_3d(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  const double t0 = MPI_Wtime();
  for (int pass = 0; tessellate_3d(); pass++) {
    if (pass == 8) error->all(FLERR, "pair_style vertex/voronoi: the ghost shell did not converge");
    ev_init(eflag, vflag);
  }
  const double t1 = MPI_Wtime();
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  type0.resize(nall);
  for (int i = 0; i < nall; i++) type0[i] = atom->type[i] - 1;
  cell_e.resize(nlocal);
  const tessera::Points3 pts{&atom->x[0][0], nall, 3};
  // Per-atom virial (compute stress/atom): each cell's own energy term's
  // virial, assigned to its atom; the cells' virials add up to the total.
  if (vflag_atom) cell_w.resize(9 * static_cast<size_t>(nlocal));
  const tessera::ForceOutput3 out =
      tessera::compute_forces_3d(tess3, pts, type0.data(), model, &atom->f[0][0], 3,
                                 cell_e.data(), vflag_atom ? cell_w.data() : nullptr);
  if (vflag_atom)
    for (int i = 0; i < nlocal; i++) {
      const double *w = &cell_w[9 * static_cast<size_t>(i)];
      vatom[i][0] += w[0];
      vatom[i][1] += w[4];
      vatom[i][2] += w[8];
      vatom[i][3] += 0.5 * (w[1] + w[3]);
      vatom[i][4] += 0.5 * (w[2] + w[6]);
      vatom[i][5] += 0.5 * (w[5] + w[7]);
    }
  stats[0] += t1 - t0;
  stats[1] += MPI_Wtime() - t1;
  stats[4] += 1.0;
  if (eflag_global) eng_vdwl += out.energy;
  if (eflag_atom)
    for (int i = 0; i < nlocal; i++) eatom[i] += cell_e[i];
  if (vflag_fdotr) virial_fdotr_compute();
}
