/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   pair_style vertex/voronoi: the vertex-model energy of the Voronoi cells of
   the atoms, with exact forces on the atoms and the virial.  Each rank
   triangulates its owned and ghost atoms; the ghost shell (pair cutoff) must
   cover every circumcircle of an owned cell, which is checked every step.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

using namespace LAMMPS_NS;

PairVertexVoronoi::PairVertexVoronoi(LAMMPS *lmp) : Pair(lmp)
{
  single_enable = 0;
  restartinfo = 1;
  one_coeff = 0;
  manybody_flag = 1;
  centroidstressflag = CENTROID_NOTAVAIL;

  cut_global = 0.0;
  tension = tessera::Tension::Edge;
  kappa = area0 = gamma = nullptr;
  lambda = nullptr;
  lambda_set = nullptr;
  type_set = nullptr;
  tess_step = -1;
  incremental = 1;
  mesh_ncalls = -1;
  nextra = 7;
  reference_every = 0;
  grow = 1;
  cutghost_saved = -1.0;
  pvector = stats;
  for (double &v : stats) v = 0.0;
}

PairVertexVoronoi::~PairVertexVoronoi()
{
  if (cutghost_saved >= 0.0) comm->cutghostuser = cutghost_saved;
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(kappa);
    memory->destroy(area0);
    memory->destroy(gamma);
    memory->destroy(lambda);
    memory->destroy(lambda_set);
    memory->destroy(type_set);
  }
}

void PairVertexVoronoi::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  memory->create(kappa, n + 1, "pair:kappa");
  memory->create(area0, n + 1, "pair:area0");
  memory->create(gamma, n + 1, "pair:gamma");
  memory->create(lambda, n + 1, n + 1, "pair:lambda");
  memory->create(lambda_set, n + 1, n + 1, "pair:lambda_set");
  memory->create(type_set, n + 1, "pair:type_set");
  for (int i = 0; i <= n; i++) {
    kappa[i] = area0[i] = gamma[i] = 0.0;
    type_set[i] = 0;
    for (int j = 0; j <= n; j++) {
      setflag[i][j] = 0;
      lambda[i][j] = 0.0;
      lambda_set[i][j] = 0;
      cutsq[i][j] = 0.0;
    }
  }
}

/* ----------------------------------------------------------------------
   pair_style vertex/voronoi cutoff [tension edge|cell]
------------------------------------------------------------------------- */

void PairVertexVoronoi::settings(int narg, char **arg)
{
  if (narg < 1)
    error->all(FLERR,
               "Illegal pair_style vertex/voronoi command: expected 'pair_style vertex/voronoi "
               "cutoff [tension edge|cell]'");
  cut_global = utils::numeric(FLERR, arg[0], false, lmp);
  if (!(cut_global > 0.0))
    error->all(FLERR,
               "pair_style vertex/voronoi: cutoff must be > 0, got {}; use about 2.5 to 3 "
               "cell diameters",
               arg[0]);
  int iarg = 1;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "tension") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "pair_style vertex/voronoi: keyword 'tension' needs a value (edge or cell)");
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
        error->all(FLERR, "pair_style vertex/voronoi: keyword 'incremental' needs a value (yes or no)");
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
    } else {
      error->all(FLERR,
                 "pair_style vertex/voronoi: unknown keyword '{}' (known: tension, incremental, "
                 "grow, reference)",
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

void PairVertexVoronoi::coeff(int narg, char **arg)
{
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

  if (narg == 3) {
    const double lam = utils::numeric(FLERR, arg[2], false, lmp);
    if (!std::isfinite(lam)) error->all(FLERR, "{}: Lambda must be finite, got {}", where, arg[2]);
    int count = 0;
    for (int i = ilo; i <= ihi; i++)
      for (int j = MAX(jlo, i + 1); j <= jhi; j++) {
        lambda[i][j] = lambda[j][i] = lam;
        lambda_set[i][j] = lambda_set[j][i] = 1;
        count++;
      }
    for (int i = jlo; i <= jhi; i++)
      for (int j = MAX(ilo, i + 1); j <= ihi; j++) {
        lambda[i][j] = lambda[j][i] = lam;
        lambda_set[i][j] = lambda_set[j][i] = 1;
        count++;
      }
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

  double K, A0, G, lam;
  if (strcmp(arg[2], "quadratic") == 0) {
    if (narg != 7)
      error->all(FLERR, "{}: expected 'pair_coeff I I quadratic KA A0 KP P0'", where);
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
    if (!std::isfinite(G)) error->all(FLERR, "{}: Gamma must be finite, got {}", where, arg[4]);
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
  }
}

void PairVertexVoronoi::init_style()
{
  if (domain->dimension == 3) init_style_3d();  // 3D cells: pair_vertex_voronoi_3d.cpp
  if (!domain->xperiodic || !domain->yperiodic)
    error->all(FLERR,
               "pair_style vertex/voronoi requires periodic x and y boundaries ('boundary p p "
               "p'); a confluent tissue has no free edge in this model");
  if (force->newton_pair == 0)
    error->all(FLERR, "pair_style vertex/voronoi requires 'newton on' (forces go to ghost atoms)");
  if (atom->tag_enable == 0) error->all(FLERR, "pair_style vertex/voronoi requires atom IDs");

  for (int i = 1; i <= atom->ntypes; i++)
    if (!type_set[i])
      error->all(FLERR,
                 "pair_style vertex/voronoi: no cell parameters for atom type {}; add "
                 "'pair_coeff {} {} K A0 Gamma Lambda'",
                 i, i, i);

  // The ghost shell is complete only if atoms have moved less than half the
  // skin since the last rebuild, which needs a distance check every step.
  // LAMMPS's default delay of 10 steps is lifted silently; settings that skip
  // the check altogether are overridden with a warning.
  if (neighbor->every != 1 || neighbor->dist_check == 0) {
    if (comm->me == 0)
      error->warning(FLERR,
                     "pair_style vertex/voronoi: setting 'neigh_modify every 1 delay 0 check "
                     "yes' so that the ghost shell stays complete");
    neighbor->every = 1;
    neighbor->dist_check = 1;
  }
  neighbor->delay = 0;

  const int n = atom->ntypes;
  model = tessera::Model(n);
  model.tension = tension;
  for (int i = 1; i <= n; i++) model.types[i - 1] = tessera::CellType{kappa[i], area0[i], gamma[i]};
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      const double lam = lambda_set[i][j] ? lambda[i][j] : 0.5 * (lambda[i][i] + lambda[j][j]);
      model.set_lambda(i - 1, j - 1, lam);
    }
  // No neighbor list is requested: the tessellation needs only the ghost atoms.
  for (double &v : stats) v = 0.0;
}

double PairVertexVoronoi::init_one(int i, int j)
{
  if (setflag[i][j] == 0) setflag[i][j] = 1;
  return cut_global;
}

/* Width of the region around this rank's sub-domain in which every atom is
   known: the ghost cutoff less half the skin that atoms may have moved since
   the last neighbor list build. */

double PairVertexVoronoi::ghost_width() const
{
  return MAX(neighbor->cutneighmax, comm->cutghostuser) - 0.5 * neighbor->skin;
}

/* This rank's sub-domain as a parallelogram in box coordinates (a rectangle
   for orthogonal boxes; tilted sides for triclinic ones, whose ghost shell
   is bounded by planes parallel to the sides). */

tessera::Region PairVertexVoronoi::subdomain() const
{
  if (!domain->triclinic) return tessera::Region::rect(domain->sublo, domain->subhi);
  double lo[3] = {domain->sublo_lamda[0], domain->sublo_lamda[1], 0.0};
  double corner[3];
  domain->lamda2x(lo, corner);
  tessera::Region r;
  r.o[0] = corner[0];
  r.o[1] = corner[1];
  r.ax = (domain->subhi_lamda[0] - domain->sublo_lamda[0]) * domain->xprd;
  const double fy = domain->subhi_lamda[1] - domain->sublo_lamda[1];
  r.bx = fy * domain->xy;
  r.by = fy * domain->yprd;
  return r;
}

bool PairVertexVoronoi::tessellation_current() const
{
  return tess_step == update->ntimestep && tess.n_owned == atom->nlocal;
}

/* Triangulation of owned + ghost atoms.  Between neighbor list builds the
   atoms keep their local indices, so the mesh of the previous step is
   updated by flips; after a rebuild (atoms exchanged, sorted, or a new
   run) it is triangulated from scratch. */

bool PairVertexVoronoi::tessellate()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  tessera::Points pts{&atom->x[0][0], nall, 3};
  const double w = ghost_width();
  const tessera::Region sub = subdomain();
  // The updated mesh is certified inside a smaller region: thin triangles on
  // the hull of the ghost shell fold over often, and outside this region
  // they are frozen rather than forcing a rebuild.  Owned cells' circumdisks
  // reach about one cell beyond the sub-domain, well inside it.
  const double wi = 0.6 * w;
  double lo_inc[2], hi_inc[2];
  sub.bounding_box(wi, lo_inc, hi_inc);

  bool fresh = false;
  auto build = [&]() {
    try {
      mesh.build(pts);
    } catch (tessera::Error &) {
      // Redo with atom IDs so that the message names them.
      std::vector<long> ids(nall);
      for (int i = 0; i < nall; i++) ids[i] = atom->tag[i];
      try {
        mesh.build(pts, ids.data());
      } catch (tessera::Error &e) {
        error->one(FLERR, "pair_style vertex/voronoi: {}", e.what());
      }
      error->one(FLERR, "pair_style vertex/voronoi: tessellation failed");
    }
    mesh_ncalls = neighbor->ncalls;
    fresh = true;
    stats[2] += 1.0;
  };
  if (!incremental || mesh_ncalls != neighbor->ncalls || !mesh.valid() || mesh.n_points() != nall)
    build();
  else if (mesh.update(pts, lo_inc, hi_inc))
    stats[3] += mesh.flips_last_update();
  else
    build();
  mesh.cells(pts, nlocal, tess);

  tessera::Coverage cov;  // ok unless checked below
  if (!fresh && !tessera::check_coverage(tess, sub, wi).ok) {
    // A cell reaches past the region where the updated mesh is certified:
    // triangulate from scratch, then check against the full ghost shell.
    build();
    mesh.cells(pts, nlocal, tess);
  }
  if (incremental == 2 && !fresh) check_against_scratch(pts, sub, w);
  // An updated mesh that passed the smaller region passes the full one.
  if (fresh) cov = tessera::check_coverage(tess, sub, w);
  double need = cov.needed_margin, need_all;
  MPI_Allreduce(&need, &need_all, 1, MPI_DOUBLE, MPI_MAX, world);
  if (need_all > 0.0) {
    const bool infinite = std::isinf(need_all);
    const double needed = infinite ? 2.0 * cut_global : 1.1 * (cut_global + need_all);
    if (grow && force->pair == this &&
        needed <= 2.0 * MAX(domain->xprd, domain->yprd) + cut_global) {
      grow_ghost_shell(MAX(needed, 1.2 * cut_global));
      return true;
    }
    if (infinite)
      error->all(FLERR,
                 "pair_style vertex/voronoi: cutoff {} is far too small: some cells have no "
                 "complete ring of neighbours; use a cutoff of at least 2.5 cell diameters",
                 cut_global);
    error->all(FLERR,
               "pair_style vertex/voronoi: cutoff {:.6g} is too small for this configuration "
               "(a Voronoi vertex's circumcircle reaches past the ghost atoms); use "
               "'pair_style vertex/voronoi {:.3g}' or larger",
               cut_global, needed);
  }
  tess_step = update->ntimestep;
  return false;
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
    for (int i = 0; i < nall; i++) atom->torque[i][0] = atom->torque[i][1] = atom->torque[i][2] = 0.0;
}

/* incremental check: the updated mesh's cells against a from-scratch
   triangulation of the same atoms.  Every Voronoi neighbour across an edge
   longer than a round-off threshold must be found by both; areas and
   perimeters must agree.  For tests of the incremental path. */

void PairVertexVoronoi::check_against_scratch(const tessera::Points &pts,
                                              const tessera::Region &sub, double w)
{
  tessera::Mesh scratch;
  scratch.build(pts);
  tessera::Tessellation ref;
  scratch.cells(pts, tess.n_owned, ref);
  if (!tessera::check_coverage(ref, sub, w).ok) return;    // the shell grows or the run stops
  for (int c = 0; c < tess.n_owned; c++) {
    auto strong = [](const tessera::Tessellation &t, int cell) {
      std::vector<int> nb;
      for (int k = t.cell_offset[cell]; k < t.cell_offset[cell + 1]; k++)
        if (t.edge_length[k] > 1e-8 * t.radius[t.cell_vertex[k]]) nb.push_back(t.cell_neighbor[k]);
      std::sort(nb.begin(), nb.end());
      return nb;
    };
    const double scale = std::sqrt(std::fabs(ref.area[c])) + 1.0;
    if (strong(tess, c) != strong(ref, c) || std::fabs(tess.area[c] - ref.area[c]) > 1e-9 * scale * scale ||
        std::fabs(tess.perimeter[c] - ref.perimeter[c]) > 1e-9 * scale)
      error->one(FLERR,
                 "pair_style vertex/voronoi incremental check: the cell of atom {} differs from a "
                 "from-scratch triangulation at step {} (area {} vs {}, perimeter {} vs {})",
                 atom->tag[c], update->ntimestep, tess.area[c], ref.area[c], tess.perimeter[c],
                 ref.perimeter[c]);
  }
}

void PairVertexVoronoi::compute(int eflag, int vflag)
{
  if (domain->dimension == 3) {
    compute_3d(eflag, vflag);    // pair_vertex_voronoi_3d.cpp
    return;
  }
  ev_init(eflag, vflag);

  const double t0 = MPI_Wtime();
  // Each pass that widens the ghost shell re-acquires the atoms; then the
  // energy/virial accumulators are set up again for the new atom count.
  for (int pass = 0; tessellate(); pass++) {
    if (pass == 8) error->all(FLERR, "pair_style vertex/voronoi: the ghost shell did not converge");
    ev_init(eflag, vflag);
  }
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const double t1 = MPI_Wtime();

  type0.resize(nall);
  const int *type = atom->type;
  for (int i = 0; i < nall; i++) type0[i] = type[i] - 1;
  cell_e.resize(nlocal);

  tessera::Points pts{&atom->x[0][0], nall, 3};
  // Per-atom virial (compute stress/atom): each cell's own energy term's
  // virial, assigned to its atom; the cells' virials add up to the total.
  if (vflag_atom) cell_w.resize(4 * static_cast<size_t>(nlocal));
  const tessera::ForceOutput out =
      tessera::compute_forces(tess, pts, type0.data(), model, &atom->f[0][0], 3, cell_e.data(),
                              vflag_atom ? cell_w.data() : nullptr);
  if (vflag_atom)
    for (int i = 0; i < nlocal; i++) {
      vatom[i][0] += cell_w[4 * i];
      vatom[i][1] += cell_w[4 * i + 1];
      vatom[i][3] += 0.5 * (cell_w[4 * i + 2] + cell_w[4 * i + 3]);
    }

  stats[0] += t1 - t0;
  stats[1] += MPI_Wtime() - t1;
  stats[4] += 1.0;
  if (reference_every > 0 && update->ntimestep % reference_every == 0) {
    // A from-scratch CGAL triangulation of the same points, timed for
    // benchmarks (bench/): the yardstick of the incremental mesh.
    const double r0 = MPI_Wtime();
    tessera::Mesh scratch;
    scratch.build(pts);
    stats[5] += MPI_Wtime() - r0;
    stats[6] += 1.0;
  }
  if (eflag_global) eng_vdwl += out.energy;
  if (eflag_atom)
    for (int i = 0; i < nlocal; i++) eatom[i] += cell_e[i];
  if (vflag_fdotr) virial_fdotr_compute();
}

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
    }
  }
}

void PairVertexVoronoi::read_restart(FILE *fp)
{
  read_restart_settings(fp);
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
      MPI_Bcast(&lambda_set[i][j], 1, MPI_INT, 0, world);
      MPI_Bcast(&lambda[i][j], 1, MPI_DOUBLE, 0, world);
    }
  }
}

void PairVertexVoronoi::write_restart_settings(FILE *fp)
{
  int t = tension == tessera::Tension::Edge ? 0 : 1;
  fwrite(&cut_global, sizeof(double), 1, fp);
  fwrite(&t, sizeof(int), 1, fp);
}

void PairVertexVoronoi::read_restart_settings(FILE *fp)
{
  int t = 0;
  if (comm->me == 0) {
    utils::sfread(FLERR, &cut_global, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &t, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Bcast(&cut_global, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&t, 1, MPI_INT, 0, world);
  tension = t == 0 ? tessera::Tension::Edge : tessera::Tension::Cell;
}

void *PairVertexVoronoi::extract(const char *str, int &dim)
{
  dim = 1;
  if (strcmp(str, "kappa") == 0) return kappa;
  if (strcmp(str, "area0") == 0) return area0;
  if (strcmp(str, "gamma") == 0) return gamma;
  dim = 2;
  if (strcmp(str, "lambda") == 0) return lambda;
  return nullptr;
}

double PairVertexVoronoi::memory_usage()
{
  double bytes = Pair::memory_usage();
  bytes += (double) tess.triangles.capacity() * (3 * sizeof(int) + sizeof(tessera::Vec2) + sizeof(double));
  bytes += (double) tess.cell_vertex.capacity() * (2 * sizeof(int) + sizeof(double));
  bytes += (double) type0.capacity() * sizeof(int) + cell_e.capacity() * sizeof(double);
  return bytes;
}
