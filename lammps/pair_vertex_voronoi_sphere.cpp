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

   pair_style vertex/voronoi ... surface sphere cx cy cz R ('dimension 3'):
   cells on the sphere of centre c and radius R (a number, or v_name of an
   equal-style variable, evaluated at every force computation and every
   projection), their spherical Voronoi tessellation (tessera/sphere.h) and
   the energy of the plane with spherical areas and geodesic lengths:
     E = sum_i [ K/2 (A_i - A0)^2 + Gamma/2 P_i^2 ] + sum_junctions Lambda_IJ l_ij
   (both parameter forms, types, junction tensions, per-cell A0, KA, KP,
   P0 from d_area0, d_ka, d_kp, d_perim0).  Every rank gathers every cell's
   position, type and per-cell values sorted by atom ID (MPI_Allgatherv:
   O(N) memory and work per rank, whatever the number of ranks),
   tessellates the whole sphere and keeps the forces and energies of its
   owned atoms: the same numbers on any number of ranks.
   The forces are tangent to the sphere; an internal fix (fix_vertex_sphere.h)
   puts the atoms back on it after each move.  The virial is that about the
   centre, W_ab = sum_i (r_i - c)_a F_i,b: symmetric and traceless.  The
   cell view's neighbour indices are local atoms (owned or ghost): the ghost
   shell grows, as in the plane, until every neighbour of an owned cell is
   a local atom.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi_sphere.h"

#include "fix_vertex_sphere.h"
#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "input.h"
#include "modify.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

using namespace LAMMPS_NS;

/* ---- the face's part: keyword, radius, restart record, internal fix ---- */

/* 'surface sphere cx cy cz R' at arg[iarg]; returns the next argument. */

int PairVertexVoronoi::parse_surface(int iarg, int narg, char **arg)
{
  static const char *syntax = "surface sphere cx cy cz R (R a number or v_name of an equal-style "
                              "variable)";
  if (iarg + 1 >= narg)
    error->all(FLERR, "pair_style vertex/voronoi: keyword 'surface' needs a shape: {}", syntax);
  if (strcmp(arg[iarg + 1], "none") == 0) {
    sphere_on = 0;
    return iarg + 2;
  }
  if (strcmp(arg[iarg + 1], "sphere") != 0)
    error->all(FLERR,
               "pair_style vertex/voronoi: unknown surface '{}'; the surfaces are 'sphere' and "
               "'none' ({})",
               arg[iarg + 1], syntax);
  if (iarg + 6 > narg)
    error->all(FLERR, "pair_style vertex/voronoi: 'surface sphere' needs 4 values: {}", syntax);
  for (int d = 0; d < 3; d++) {
    sphere_c[d] = utils::numeric(FLERR, arg[iarg + 2 + d], false, lmp);
    if (!std::isfinite(sphere_c[d]))
      error->all(FLERR, "pair_style vertex/voronoi: sphere centre coordinate {} is not finite",
                 arg[iarg + 2 + d]);
  }
  const char *r = arg[iarg + 5];
  sphere_var.clear();
  if (strncmp(r, "v_", 2) == 0) {
    sphere_var = r + 2;
    if (sphere_var.empty())
      error->all(FLERR, "pair_style vertex/voronoi: sphere radius 'v_' names no variable");
  } else {
    sphere_R = utils::numeric(FLERR, r, false, lmp);
    if (!(sphere_R > 0.0) || !std::isfinite(sphere_R))
      error->all(FLERR, "pair_style vertex/voronoi: sphere radius R must be > 0, got {}", r);
  }
  sphere_on = 1;
  return iarg + 6;
}

double PairVertexVoronoi::sphere_radius()
{
  if (sphere_var.empty()) return sphere_R;
  const int ivar = input->variable->find(sphere_var.c_str());
  if (ivar < 0)
    error->all(FLERR,
               "pair_style vertex/voronoi: sphere radius variable '{}' does not exist; define it "
               "with 'variable {} equal ...'",
               sphere_var, sphere_var);
  if (!input->variable->equalstyle(ivar))
    error->all(FLERR,
               "pair_style vertex/voronoi: sphere radius variable '{}' must be equal-style (one "
               "number, e.g. 'variable {} equal 10+0.01*time')",
               sphere_var, sphere_var);
  // As fix adapt does: computes the variable reads are evaluated anew (a
  // value cached earlier in the step, or in an earlier step when nothing
  // cleared it, would lag behind divisions or per-atom changes since, and
  // by how much would depend on the output settings).
  modify->clearstep_compute();
  const double R = input->variable->compute_equal(ivar);
  modify->addstep_compute(update->ntimestep + 1);
  if (!(R > 0.0) || !std::isfinite(R))
    error->all(FLERR,
               "pair_style vertex/voronoi: sphere radius v_{} is {} at step {}; it must be > 0",
               sphere_var, R, update->ntimestep);
  return R;
}

void PairVertexVoronoi::write_sphere_settings(FILE *fp) const
{
  fwrite(&sphere_on, sizeof(int), 1, fp);
  fwrite(sphere_c, sizeof(double), 3, fp);
  fwrite(&sphere_R, sizeof(double), 1, fp);
  const int n = static_cast<int>(sphere_var.size());
  fwrite(&n, sizeof(int), 1, fp);
  if (n) fwrite(sphere_var.data(), sizeof(char), n, fp);
}

void PairVertexVoronoi::read_sphere_settings(FILE *fp)
{
  int n = 0;
  if (comm->me == 0) {
    utils::sfread(FLERR, &sphere_on, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, sphere_c, sizeof(double), 3, fp, nullptr, error);
    utils::sfread(FLERR, &sphere_R, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &n, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Bcast(&sphere_on, 1, MPI_INT, 0, world);
  MPI_Bcast(sphere_c, 3, MPI_DOUBLE, 0, world);
  MPI_Bcast(&sphere_R, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&n, 1, MPI_INT, 0, world);
  std::string name(n, ' ');
  if (comm->me == 0 && n) utils::sfread(FLERR, &name[0], sizeof(char), n, fp, nullptr, error);
  if (n) MPI_Bcast(&name[0], n, MPI_CHAR, 0, world);
  sphere_var = name;
}

/* The internal fix that keeps the atoms on the sphere, added once (its
   style registered here on first use, as the step guard's). */

void PairVertexVoronoi::add_sphere_fix()
{
  if (sphere_fix_id.empty())
    sphere_fix_id = std::string("VERTEX_VORONOI_SPHERE_") + std::to_string(instance_me);
  const std::string style = FixVertexSphere::style_name();
  if (modify->fix_map->find(style) == modify->fix_map->end())
    (*modify->fix_map)[style] = &FixVertexSphere::creator;
  if (modify->find_fix(sphere_fix_id) < 0) modify->add_fix(sphere_fix_id + " all " + style);
  auto fix = dynamic_cast<FixVertexSphere *>(modify->fix[modify->find_fix(sphere_fix_id)]);
  if (fix) fix->pair = this;
}

/* The sphere must lie inside the box along every direction that does not
   shrink-wrap: past a periodic boundary its atoms would be wrapped to the
   other side (and past a fixed one lost). */

void PairVertexVoronoi::check_sphere_box(double R) const
{
  const double *centre = sphere_c;
  const double lo[3] = {domain->boxlo[0], domain->boxlo[1], domain->boxlo[2]};
  const double hi[3] = {domain->boxhi[0], domain->boxhi[1], domain->boxhi[2]};
  static const char *axis = "xyz";
  for (int d = 0; d < 3; d++) {
    if (domain->boundary[d][0] >= 2 && domain->boundary[d][1] >= 2) continue;    // s or m
    if (centre[d] - R < lo[d] || centre[d] + R > hi[d]) {
      // how the cells grew there (fix_vertex_sphere.cpp)
      std::string why;
      const int ifix = sphere_fix_id.empty() ? -1 : modify->find_fix(sphere_fix_id);
      if (ifix >= 0)
        if (auto *fix = dynamic_cast<FixVertexSphere *>(modify->fix[ifix]))
          why = fix->growth_note(R);
      error->all(FLERR,
                 "pair_style vertex/voronoi: the sphere (centre {} {} {}, radius {}) at step {} "
                 "reaches past the box along {} ({} to {}){}; enlarge the box (the sphere must "
                 "lie inside it) or use shrink-wrapped boundaries ('boundary s s s')",
                 centre[0], centre[1], centre[2], R, update->ntimestep, axis[d], lo[d], hi[d], why);
    }
  }
  if (domain->triclinic)
    error->all(FLERR, "pair_style vertex/voronoi: 'surface sphere' needs an orthogonal box");
}

/* ---- the unit ---- */

void VertexSphere::init()
{
  if (domain->dimension != 3)
    error->all(FLERR,
               "pair_style vertex/voronoi: 'surface sphere' needs 'dimension 3' (the cells are "
               "two-dimensional, on a sphere in space)");
  if (pair->radius > 0.0)
    error->all(FLERR,
               "pair_style vertex/voronoi: finite cells ('radius') are not available on a sphere; "
               "the cells on a sphere are confluent (they cover it)");
  if (pair->incremental_given)
    error->all(FLERR,
               "pair_style vertex/voronoi: 'incremental' keeps the 2d or 3d triangulation between "
               "steps; on a sphere every step is a from-scratch triangulation, so it would have no "
               "effect: remove 'incremental' from the pair_style line");
  if (pair->reference_every > 0)
    error->all(FLERR,
               "pair_style vertex/voronoi: 'reference' times the incremental 2d triangulation; "
               "on a sphere every step is a from-scratch triangulation already");
  if (atom->natoms > MAXSMALLINT / 8)
    error->all(FLERR, "pair_style vertex/voronoi: too many cells on a sphere ({})", atom->natoms);
  // The virial is the style's own (about the centre), not f dot r.
  pair->no_virial_fdotr_compute = 1;
}

/* Every cell's ID, type, position and per-cell values (d_area0, d_ka,
   d_kp, d_perim0, each when defined) on every rank, sorted by ID.  (The
   owned values are checked by the pair style's prepare_atoms before the
   force computation reads them.)  Cells only: the pair style's list of
   cell atoms (gather_cells), whose indices the view and forces use. */

void VertexSphere::gather()
{
  pair->gather_cells();
  const int nlocal = pair->ncell_local;
  const char *names[NPC] = {"area0", "ka", "kp", "perim0"};
  const double *pc[NPC] = {nullptr, nullptr, nullptr, nullptr};
  for (int k = 0; k < NPC; k++) {
    int flag = -1, cols = -1;
    const int index = atom->find_custom(names[k], flag, cols);
    has_pc[k] = index >= 0 && flag == 1 && cols == 0;
    if (has_pc[k]) pc[k] = atom->dvector[index];
  }
  constexpr int W = 5 + NPC;
  std::vector<double> mine(static_cast<size_t>(W) * nlocal);
  for (int c = 0; c < nlocal; c++) {
    double *m = &mine[static_cast<size_t>(W) * c];
    const int i = pair->cell_atom(c);
    m[0] = static_cast<double>(atom->tag[i]);
    m[1] = atom->type[i] - 1;
    for (int d = 0; d < 3; d++) m[2 + d] = atom->x[i][d];
    for (int k = 0; k < NPC; k++) m[5 + k] = pc[k] ? pc[k][i] : 0.0;
  }
  const int nprocs = comm->nprocs;
  std::vector<int> counts(nprocs), displs(nprocs);
  const int mycount = W * nlocal;
  MPI_Allgather(&mycount, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  int total = 0;
  for (int p = 0; p < nprocs; p++) {
    displs[p] = total;
    total += counts[p];
  }
  std::vector<double> all(total);
  MPI_Allgatherv(mine.data(), mycount, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, world);
  const int n = total / W;
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return all[W * a] < all[W * b];
  });
  xall.resize(3 * static_cast<size_t>(n));
  for (auto &v : pcall) v.resize(n);
  typeall.resize(n);
  ids.resize(n);
  tags.resize(n);
  for (int k = 0; k < n; k++) {
    const double *m = &all[static_cast<size_t>(W) * order[k]];
    tags[k] = static_cast<tagint>(m[0]);
    ids[k] = static_cast<long>(tags[k]);
    typeall[k] = static_cast<int>(m[1]);
    for (int d = 0; d < 3; d++) xall[3 * k + d] = m[2 + d];
    for (int q = 0; q < NPC; q++) pcall[q][k] = m[5 + q];
  }
  // Each owned cell's index in the list, and each listed cell's index in
  // the pair style's list of (owned and ghost) cell atoms.
  owned.resize(nlocal);
  for (int i = 0; i < nlocal; i++)
    owned[i] = static_cast<int>(std::lower_bound(tags.begin(), tags.end(), pair->cell_tag(i)) -
                                tags.begin());
  // (Its own lookup: LAMMPS keeps an atom map only when asked to.)  Owned
  // atoms come first, so an owned atom is never replaced by a ghost image.
  local.assign(n, -1);
  const int nall = pair->ncell_all;
  for (int i = 0; i < nall; i++) {
    const tagint tag = pair->cell_tag(i);
    const auto it = std::lower_bound(tags.begin(), tags.end(), tag);
    if (it != tags.end() && *it == tag && local[it - tags.begin()] < 0)
      local[it - tags.begin()] = i;
  }
}

bool VertexSphere::tessellate()
{
  gather();
  const int n = static_cast<int>(tags.size());
  const tessera::Vec3 c{centre[0], centre[1], centre[2]};
  try {
    tess = tessera::tessellate_sphere(c, R, {xall.data(), n, 3}, ids.data());
  } catch (tessera::Error &e) {
    // Every rank has the same cells, so every rank stops here.
    error->all(FLERR, "pair_style vertex/voronoi (surface sphere) at step {}: {}",
               update->ntimestep, e.what());
  }
  const int nlocal = pair->ncell_local;
  const int nall = pair->ncell_all;
  const double *x = pair->cell_x();
  cells_.bind(tess, owned, local, nall, {x, nall, 3});
  // A neighbour of an owned cell (or a point of a multifold ring around it)
  // that is no local atom: the ghost shell must reach it.
  double need = 0.0;
  const double w = pair->ghost_width();
  for (int p : cells_.missing()) {
    double dmin = std::numeric_limits<double>::max();
    for (int i = 0; i < nlocal; i++) {
      double r2 = 0.0;
      for (int d = 0; d < 3; d++) {
        const double dx = xall[3 * p + d] - x[3 * i + d];
        r2 += dx * dx;
      }
      dmin = std::min(dmin, r2);
    }
    const double dist = std::sqrt(dmin);
    need = std::max(need, std::max(dist - w, 0.0) + 0.05 * dist + 1e-6 * R);
  }
  return !pair->ghost_shell_complete(need);
}

void VertexSphere::compute(int eflag, int vflag)
{
  const double t0 = MPI_Wtime();
  const double *c = pair->sphere_centre();
  for (int d = 0; d < 3; d++) centre[d] = c[d];
  R = pair->sphere_radius();
  pair->check_sphere_box(R);
  for (int pass = 0; tessellate(); pass++) {
    if (pass == 8) pair->ghost_shell_failed();
    pair->ev_init(eflag, vflag);
  }
  const double t1 = MPI_Wtime();
  const int nlocal = pair->ncell_local;
  const int n = static_cast<int>(tags.size());
  pair->prepare_atoms();
  // The energy of every cell needs every cell's A0, KA, KP, P0: the
  // gathered ones, in the gathered order, for the core only.  prepare_atoms
  // bound the local arrays (and checked the owned values); they come back
  // afterwards, for the quadratic forms' constant (accumulate) and whoever
  // reads the model by local index.
  tessera::Model &model = pair->model;
  const double *local_pc[NPC] = {model.cell_area0, model.cell_KA, model.cell_KP, model.cell_P0};
  const double **bound[NPC] = {&model.cell_area0, &model.cell_KA, &model.cell_KP, &model.cell_P0};
  for (int k = 0; k < NPC; k++) *bound[k] = has_pc[k] ? pcall[k].data() : nullptr;
  fall.assign(3 * static_cast<size_t>(n), 0.0);
  eall.assign(n, 0.0);
  std::string failed;
  try {
    tessera::sphere_forces(tess, {xall.data(), n, 3}, typeall.data(), model, fall.data(), 3,
                           eall.data(), nullptr);
  } catch (tessera::Error &e) {
    failed = e.what();
  }
  for (int k = 0; k < NPC; k++) *bound[k] = local_pc[k];
  if (!failed.empty())
    error->all(FLERR, "pair_style vertex/voronoi (surface sphere) at step {}: {}",
               update->ntimestep, failed);
  double *f = pair->cell_f();
  double energy = 0.0;
  if (pair->vflag_atom) pair->cell_w.assign(9 * static_cast<size_t>(nlocal), 0.0);
  double v[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < nlocal; i++) {
    const int k = owned[i];
    const double *fk = &fall[3 * static_cast<size_t>(k)];
    for (int d = 0; d < 3; d++) f[3 * i + d] += fk[d];
    pair->cell_e[i] = eall[k];
    energy += eall[k];
    // The virial about the centre, of the point on the sphere.
    const tessera::Vec3 &u = tess.direction[k];
    const double r[3] = {R * u.x, R * u.y, R * u.z};
    v[0] += r[0] * fk[0];
    v[1] += r[1] * fk[1];
    v[2] += r[2] * fk[2];
    v[3] += r[0] * fk[1];
    v[4] += r[0] * fk[2];
    v[5] += r[1] * fk[2];
    if (pair->vflag_atom) {
      double *wi = &pair->cell_w[9 * static_cast<size_t>(i)];
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) wi[3 * a + b] = r[a] * fk[b];
    }
  }
  if (pair->vflag_global)
    for (int a = 0; a < 6; a++) pair->virial[a] += v[a];
  pair->note_closest_pair();
  pair->stats[0] += t1 - t0;
  pair->stats[1] += MPI_Wtime() - t1;
  pair->stats[2] += 1.0;
  pair->stats[4] += 1.0;
  pair->accumulate(energy, 9);
}

double VertexSphere::memory_usage() const
{
  double pcs = 0.0;
  for (const auto &v : pcall) pcs += (double) v.capacity();
  return (pcs + (double) (xall.capacity() + fall.capacity() + eall.capacity())) * sizeof(double) +
      (double) (typeall.capacity() + owned.capacity() + local.capacity()) * sizeof(int) +
      (double) tess.cell_vertex.capacity() * (2 * sizeof(int) + sizeof(double)) +
      (double) tess.triangles.capacity() * (3 * sizeof(int) + sizeof(tessera::Vec3));
}
