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

   pair_style vertex/voronoi in 'dimension 3': the 3D Voronoi cells of the
   atoms (tessera/voronoi3d.h), energy
     E = sum_i [ K/2 (V_i - V0)^2 + Gamma/2 S_i^2 ] + sum_faces Lambda_IJ a_f
   with the pair_coeff values of 2D read as K, V0, Gamma, Lambda (and
   'quadratic KV V0 KS S0' for Merkel & Manning's form); per-cell V0 from
   'd_area0' as in 2D.  Each rank tetrahedralises its owned and ghost atoms,
   from scratch after a neighbor-list build and repaired by flips in between
   (tessera::Mesh3); every circumsphere of an owned cell must lie inside the
   ghost shell, checked every step, and the shell grows as in 2D when it
   does not.  'reference N' times from-scratch triangulations every N steps
   (compute pair values 6-8), as in 2D, with CGAL's Delaunay_triangulation_3.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi_3d.h"

#include "pair_vertex_voronoi.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using namespace LAMMPS_NS;

void Vertex3d::init()
{
  if (!domain->xperiodic || !domain->yperiodic || !domain->zperiodic)
    error->all(FLERR,
               "pair_style vertex/voronoi in 3d requires periodic x, y and z boundaries "
               "('boundary p p p'): a 3d tissue of Voronoi polyhedra has no free surface in "
               "this model");
  if (pair->radius > 0.0)
    error->all(FLERR,
               "pair_style vertex/voronoi: finite cells ('radius') are for 2d tissues; in 3d "
               "the cells are confluent Voronoi polyhedra");
  mesh_ncalls = -1;
}

/* check_coverage_3d(t, lo, hi).ok, visiting each tetrahedron once instead
   of once per face corner (about 13 times fewer): every tetrahedron of t is
   a corner of an owned cell's face (a sliver dropped from the polygons
   carries the sphere of a neighbour that is). */

static bool spheres_inside(const tessera::Tessellation3 &t, const double lo[3], const double hi[3])
{
  if (t.unbounded_cell >= 0) return false;
  const size_t nt = t.vertices.size();
  const tessera::Vec3 *h = t.vertices.data();
  const double *r = t.radius.data();
  bool ok = true;
  for (size_t v = 0; v < nt; v++)
    ok &= (h[v].x - r[v] >= lo[0]) & (h[v].x + r[v] <= hi[0]) & (h[v].y - r[v] >= lo[1]) &
        (h[v].y + r[v] <= hi[1]) & (h[v].z - r[v] >= lo[2]) & (h[v].z + r[v] <= hi[2]);
  return ok;
}

/* incremental check: the repaired mesh's cells against a from-scratch
   tetrahedralisation of the same atoms: the same neighbours across faces
   larger than a round-off threshold, the same volumes and surfaces. */

void Vertex3d::check_against_scratch(const tessera::Points3 &pts, const tessera::Region3 &sub,
                                     double w)
{
  const tessera::Tessellation3 ref =
      tessera::tessellate_local_3d(pts, tess3.n_owned, nullptr, false);
  if (!tessera::check_coverage_3d(ref, sub, w).ok) return;    // the shell grows or the run stops
  auto strong = [](const tessera::Tessellation3 &t, int c) {
    std::vector<int> nb;
    for (int f = t.cell_offset[c]; f < t.cell_offset[c + 1]; f++)
      if (t.face_area[f] > 1e-9 * t.surface[c]) nb.push_back(t.face_neighbor[f]);
    std::sort(nb.begin(), nb.end());
    return nb;
  };
  for (int c = 0; c < tess3.n_owned; c++) {
    const double scale = std::cbrt(std::fabs(ref.volume[c])) + 1.0;
    if (strong(tess3, c) != strong(ref, c) ||
        std::fabs(tess3.volume[c] - ref.volume[c]) > 1e-9 * scale * scale * scale ||
        std::fabs(tess3.surface[c] - ref.surface[c]) > 1e-9 * scale * scale)
      error->one(FLERR,
                 "pair_style vertex/voronoi incremental check: the cell of atom {} differs from a "
                 "from-scratch tetrahedralisation at step {} (volume {} vs {}, surface {} vs {})",
                 pair->cell_tag(c), update->ntimestep, tess3.volume[c], ref.volume[c],
                 tess3.surface[c], ref.surface[c]);
  }
}

/* This rank's sub-domain: a box, or for a triclinic box the parallelepiped
   of its lamda range, whose ghost shell is bounded by planes parallel to
   its faces at the ghost cutoff. */

tessera::Region3 Vertex3d::subdomain() const
{
  tessera::Region3 sub;
  if (!domain->triclinic) {
    for (int d = 0; d < 3; d++) {
      sub.o[d] = domain->sublo[d];
      sub.a[d] = sub.b[d] = sub.c[d] = 0.0;
    }
    sub.a[0] = domain->subhi[0] - domain->sublo[0];
    sub.b[1] = domain->subhi[1] - domain->sublo[1];
    sub.c[2] = domain->subhi[2] - domain->sublo[2];
    return sub;
  }
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
  return sub;
}

bool Vertex3d::tessellate()
{
  // The owned and ghost cells (the pair style's list of cell atoms).
  pair->gather_cells();
  const int nlocal = pair->ncell_local;
  const int nall = pair->ncell_all;
  const tessera::Points3 pts{pair->cell_x(), nall, 3};
  // Fewer than 4 points, or all in one plane (a few cells in a large box
  // with a thin ghost shell): the cells are unbounded, so the shell must grow.
  bool flat = nall < 4;
  if (!flat && nlocal > 0) {
    // Coplanar: every point on the plane of the first three non-collinear ones.
    const double *p0 = pts.p(0);
    int i1 = -1, i2 = -1;
    double nrm[3] = {0, 0, 0};
    for (int i = 1; i < nall && i1 < 0; i++) {
      const double *p = pts.p(i);
      if (p[0] != p0[0] || p[1] != p0[1] || p[2] != p0[2]) i1 = i;
    }
    for (int i = 1; i1 >= 0 && i < nall && i2 < 0; i++) {
      const double *a = pts.p(i1), *b = pts.p(i);
      const double u[3] = {a[0] - p0[0], a[1] - p0[1], a[2] - p0[2]};
      const double v[3] = {b[0] - p0[0], b[1] - p0[1], b[2] - p0[2]};
      nrm[0] = u[1] * v[2] - u[2] * v[1];
      nrm[1] = u[2] * v[0] - u[0] * v[2];
      nrm[2] = u[0] * v[1] - u[1] * v[0];
      if (nrm[0] != 0.0 || nrm[1] != 0.0 || nrm[2] != 0.0) i2 = i;
    }
    flat = i2 < 0;
    for (int i = 1; !flat && i < nall; i++) {
      const double *p = pts.p(i);
      if ((p[0] - p0[0]) * nrm[0] + (p[1] - p0[1]) * nrm[1] + (p[2] - p0[2]) * nrm[2] != 0.0) break;
      if (i == nall - 1) flat = true;
    }
  }
  if (flat && nlocal > 0) {
    tess3 = tessera::Tessellation3();
    return !pair->ghost_shell_complete(std::numeric_limits<double>::infinity());
  }
  // Between neighbor-list builds the atoms keep their local indices: the
  // tetrahedralisation of the previous step is repaired by flips
  // (tessera::Mesh3, the same cells as a rebuild); after a rebuild of the
  // lists (atoms exchanged or sorted, a new run) it is built from scratch.
  // The repaired mesh is certified inside the sub-domain's bounding box grown
  // by 0.8 of the ghost shell, where the owned cells' circumspheres lie.  (At
  // 0.6 a relaxing random start rebuilt on every step: some owned
  // circumsphere reached past it; at 0.8 the repair kept the mesh on all but
  // a few steps, and at 0.95 the tetrahedra near the ghost shell's hull made
  // it fail more often.)
  const tessera::Region3 sub = subdomain();
  const double w = pair->ghost_width(), wi = 0.8 * w;
  double lo[3], hi[3];
  for (int d = 0; d < 3; d++) {
    // Bounding box of the parallelepiped o + s a + t b + u c.
    double mn = sub.o[d], mx = sub.o[d];
    for (int k = 1; k < 8; k++) {
      const double v = sub.o[d] + ((k & 1) ? sub.a[d] : 0.0) + ((k & 2) ? sub.b[d] : 0.0) +
          ((k & 4) ? sub.c[d] : 0.0);
      mn = MIN(mn, v);
      mx = MAX(mx, v);
    }
    lo[d] = mn - wi;
    hi[d] = mx + wi;
  }
  bool fresh = false;
  auto build = [&]() {
    tess3 = tessera::Tessellation3();
    try {
      mesh.build(pts);
      mesh.cells(pts, nlocal, tess3, nullptr, false);
    } catch (tessera::Error &) {
      // Redo with atom IDs so that the message names them.
      std::vector<long> ids(nall);
      for (int i = 0; i < nall; i++) ids[i] = pair->cell_tag(i);
      try {
        mesh.build(pts, ids.data());
        mesh.cells(pts, nlocal, tess3, ids.data(), false);
      } catch (tessera::Error &e) {
        error->one(FLERR,
                   "pair_style vertex/voronoi at step {}: {} (during a run two centres come "
                   "this close when the timestep does not resolve their forces: use a smaller "
                   "timestep, 'fix dt/reset' or fix brownian/heun)",
                   update->ntimestep, e.what());
      }
      error->one(FLERR, "pair_style vertex/voronoi: tessellation failed");
    }
    mesh_ncalls = neighbor->ncalls;
    mesh_cells = pair->cell_map_version;
    fresh = true;
    pair->stats[2] += 1.0;
  };
  if (nlocal == 0) {
    tess3 = tessera::tessellate_local_3d(pts, 0);
    mesh_ncalls = -1;
  } else if (!pair->incremental || mesh_ncalls != neighbor->ncalls || !mesh.valid() ||
             mesh.n_points() != nall || mesh_cells != pair->cell_map_version) {
    build();
  } else if (mesh.advance(pts, nlocal, lo, hi, tess3)) {
    pair->stats[3] += mesh.flips_last_update();
    if (!spheres_inside(tess3, lo, hi)) build();
  } else {
    build();
  }
  // incremental check: every step's cells, repaired or built (both come
  // from Mesh3::cells, which treats slivers of co-spherical points as
  // tessellate_local_3d does), against tessellate_local_3d.
  if (pair->incremental == 2 && nlocal > 0) check_against_scratch(pts, sub, w);
  tessera::Coverage cov;
  if (fresh) cov = tessera::check_coverage_3d(tess3, sub, w);
  if (!pair->ghost_shell_complete(cov.needed_margin)) return true;
  cells_.bind(tess3, pts);
  return false;
}

void Vertex3d::compute(int eflag, int vflag)
{
  const double t0 = MPI_Wtime();
  for (int pass = 0; tessellate(); pass++) {
    if (pass == 8) pair->ghost_shell_failed();
    pair->ev_init(eflag, vflag);
  }
  const double t1 = MPI_Wtime();
  const int nlocal = pair->ncell_local;
  const int nall = pair->ncell_all;
  pair->prepare_atoms();
  const tessera::Points3 pts{pair->cell_x(), nall, 3};
  // Per-atom virial (compute stress/atom): each cell's own energy term's
  // virial, assigned to its atom; the cells' virials add up to the total
  // (the global virial under 'pair_modify nofdotr').
  const bool cell_virial = pair->vflag_atom || pair->vflag_global;
  if (cell_virial) pair->cell_w.resize(9 * static_cast<size_t>(nlocal));
  tessera::ForceOutput3 out;
  try {
    out = tessera::compute_forces_3d(tess3, pts, pair->type0.data(), pair->model, pair->cell_f(), 3,
                                     pair->cell_e.data(),
                                     cell_virial ? pair->cell_w.data() : nullptr);
  } catch (tessera::Error &e) {
    error->one(FLERR, "pair_style vertex/voronoi at step {}: {}", update->ntimestep, e.what());
  }
  pair->note_closest_pair();
  pair->stats[0] += t1 - t0;
  pair->stats[1] += MPI_Wtime() - t1;
  pair->stats[4] += 1.0;
  if (pair->reference_every > 0 && update->ntimestep % pair->reference_every == 0 && nlocal > 0) {
    // Timed from-scratch triangulations of the same points for benchmarks
    // (bench/run3d): the style's own rebuild (CGAL of owned and ghost
    // atoms, then the cells; value 6) and the yardstick, a plain CGAL
    // Delaunay_triangulation_3 of the owned atoms alone (value 8).  Run
    // one after the other, so that they never coexist in memory.
    try {
      {
        const double r0 = MPI_Wtime();
        tessera::Mesh3 scratch;
        tessera::Tessellation3 t;
        scratch.build(pts);
        scratch.cells(pts, nlocal, t, nullptr, false);
        pair->stats[5] += MPI_Wtime() - r0;
        pair->stats[6] += 1.0;
      }
      pair->stats[7] += tessera::time_plain_delaunay_3d(pts, nlocal);
    } catch (tessera::Error &e) {
      error->one(FLERR, "pair_style vertex/voronoi 'reference' at step {}: {}", update->ntimestep,
                 e.what());
    }
  }
  pair->accumulate(out.energy, 9);
}

double Vertex3d::memory_usage() const
{
  return (double) tess3.tets.capacity() *
      (4 * sizeof(int) + sizeof(tessera::Vec3) + sizeof(double)) +
      (double) tess3.face_vertex.capacity() * sizeof(int) +
      (double) tess3.face_neighbor.capacity() * (sizeof(int) + sizeof(double));
}
