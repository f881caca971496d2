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

   pair_style vertex/voronoi, confluent 2D cells: each rank triangulates its
   owned and ghost atoms; the ghost shell (pair cutoff) must cover every
   circumcircle of an owned cell, which is checked every step.  Between
   neighbor-list builds the mesh of the previous step is updated by flips.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi_confluent.h"

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

void VertexConfluent::init()
{
  if (!domain->xperiodic || !domain->yperiodic)
    error->all(FLERR,
               "pair_style vertex/voronoi requires periodic x and y boundaries ('boundary p p "
               "p'); a confluent tissue has no free edge in this model (for tissue edges use "
               "finite cells: 'pair_style vertex/voronoi cutoff radius r')");
  mesh_ncalls = -1;
}

/* This rank's sub-domain as a parallelogram in box coordinates (a rectangle
   for orthogonal boxes; tilted sides for triclinic ones, whose ghost shell
   is bounded by planes parallel to the sides). */

tessera::Region VertexConfluent::subdomain() const
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

/* Types and preferred areas of this step's atoms, for the forces' per-cell
   half, which Mesh::advance runs while it reads the cells (tessera::CellPass). */

void VertexConfluent::prepare()
{
  pair->gather_cells();
  pair->prepare_atoms();
  cell_pass.set(tessera::Points{pair->cell_x(), pair->ncell_all, 3}, pair->type0.data(),
                pair->model, pair->cell_e.data());
}

/* Triangulation of owned + ghost cells (the pair style's list of cell
   atoms).  Between neighbor list builds the atoms keep their local indices,
   so the mesh of the previous step is updated by flips; after a rebuild
   (atoms exchanged, sorted, or a new run) it is triangulated from scratch. */

bool VertexConfluent::tessellate()
{
  const int nlocal = pair->ncell_local;
  const int nall = pair->ncell_all;
  tessera::Points pts{pair->cell_x(), nall, 3};
  const double w = pair->ghost_width();
  const tessera::Region sub = subdomain();
  // The updated mesh is certified inside a smaller region: thin triangles on
  // the hull of the ghost shell fold over often, and outside this region
  // they are frozen rather than forcing a rebuild.  Owned cells' circumdisks
  // reach about one cell beyond the sub-domain, well inside it; from a
  // disordered start some reach farther (at 0.6 of the ghost width half the
  // rebuilds of the first steps were such cells, at 0.8 almost none).
  const double wi = 0.8 * w;
  double lo_inc[2], hi_inc[2];
  sub.bounding_box(wi, lo_inc, hi_inc);

  // A rank that owns no cell has nothing to compute (its ghosts are other
  // ranks' cells); it only takes part in the collective check below.
  if (nlocal == 0) {
    tess = tessera::Tessellation();
    tess.n_points = nall;
    tess.cell_offset.assign(1, 0);
    mesh_ncalls = -1;    // triangulate from scratch when cells arrive
  }

  bool fresh = false;
  // Fewer than 3 points, or all on one line (one cell in a large box, or a
  // row of cells, with a ghost shell that holds too few of their images):
  // the cells are unbounded, so the ghost shell must grow, not the run stop.
  bool too_few = false;
  double *stats = pair->stats;
  auto build = [&]() {
    // The cells are read afresh after a rebuild: their arrays go first, so
    // that they and CGAL's triangulation never hold memory at the same time
    // (the peak memory per cell is a rebuild's).
    tess = tessera::Tessellation();
    try {
      mesh.build(pts);
    } catch (tessera::Error &) {
      if (nall < 3 || mesh.collinear()) {
        too_few = true;
        mesh_ncalls = -1;
        return;
      }
      // Redo with atom IDs so that the message names them.
      std::vector<long> ids(nall);
      for (int i = 0; i < nall; i++) ids[i] = pair->cell_tag(i);
      try {
        mesh.build(pts, ids.data());
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
    stats[2] += 1.0;
  };
  // Between rebuilds Mesh::advance() updates the mesh by flips and reads the
  // cells in one go (the same cells as update() + cells(), faster).
  bool have_cells = false;
  if (nlocal == 0)
    ;
  else if (!pair->incremental || mesh_ncalls != neighbor->ncalls || !mesh.valid() ||
           mesh.n_points() != nall || mesh_cells != pair->cell_map_version)
    build();
  else if (mesh.advance(pts, nlocal, lo_inc, hi_inc, tess, fuse_cells ? &cell_pass : nullptr)) {
    stats[3] += mesh.flips_last_update();
    have_cells = true;
  } else
    build();
  if (too_few) {
    if (pair->ghost_shell_complete(std::numeric_limits<double>::infinity())) return false;
    return true;
  }
  if (nlocal > 0 && !have_cells) mesh.cells(pts, nlocal, tess);

  tessera::Coverage cov;    // ok unless checked below
  if (nlocal > 0 && !fresh && !tessera::check_coverage(tess, sub, wi).ok) {
    // A cell reaches past the region where the updated mesh is certified:
    // triangulate from scratch, then check against the full ghost shell.
    build();
    if (too_few) return !pair->ghost_shell_complete(std::numeric_limits<double>::infinity());
    mesh.cells(pts, nlocal, tess);
  }
  if (pair->incremental == 2 && !fresh && nlocal > 0) check_against_scratch(pts, sub, w);
  // An updated mesh that passed the smaller region passes the full one.
  if (fresh) cov = tessera::check_coverage(tess, sub, w);
  if (!pair->ghost_shell_complete(cov.needed_margin)) return true;
  cells_.bind(tess, pts);
  return false;
}

/* incremental check: the updated mesh's cells against a from-scratch
   triangulation of the same atoms.  Every Voronoi neighbour across an edge
   longer than a round-off threshold must be found by both; areas and
   perimeters must agree.  For tests of the incremental path. */

void VertexConfluent::check_against_scratch(const tessera::Points &pts, const tessera::Region &sub,
                                            double w)
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
    if (strong(tess, c) != strong(ref, c) ||
        std::fabs(tess.area[c] - ref.area[c]) > 1e-9 * scale * scale ||
        std::fabs(tess.perimeter[c] - ref.perimeter[c]) > 1e-9 * scale)
      error->one(FLERR,
                 "pair_style vertex/voronoi incremental check: the cell of atom {} differs from a "
                 "from-scratch triangulation at step {} (area {} vs {}, perimeter {} vs {})",
                 pair->cell_tag(c), update->ntimestep, tess.area[c], ref.area[c], tess.perimeter[c],
                 ref.perimeter[c]);
  }
}

void VertexConfluent::compute(int eflag, int vflag)
{
  const double t0 = MPI_Wtime();
  prepare();
  // Without per-cell virials (per-atom, or the global one under 'pair_modify
  // nofdotr'; they need the general loop), the per-cell half of the forces
  // runs inside Mesh::advance; its time counts as tessellation in the
  // statistics (values 1 and 2).
  const bool cell_virial = pair->vflag_atom || pair->vflag_global;
  fuse_cells = !cell_virial;
  // Each pass that widens the ghost shell re-acquires the atoms; then the
  // energy/virial accumulators are set up again for the new atom count.
  for (int pass = 0; tessellate(); pass++) {
    if (pass == 8) pair->ghost_shell_failed();
    pair->ev_init(eflag, vflag);
    prepare();
  }
  fuse_cells = false;
  const int nlocal = pair->ncell_local;
  const int nall = pair->ncell_all;
  const double t1 = MPI_Wtime();

  tessera::Points pts{pair->cell_x(), nall, 3};
  // Per-atom virial (compute stress/atom): each cell's own energy term's
  // virial, assigned to its atom; the cells' virials add up to the total.
  if (cell_virial) pair->cell_w.resize(4 * static_cast<size_t>(nlocal));
  tessera::ForceOutput out;
  try {
    // The global virial comes from LAMMPS's f dot r (virial_fdotr_compute),
    // or under 'pair_modify nofdotr' from the cells' virials (accumulate).
    out = tessera::compute_forces(tess, pts, pair->type0.data(), pair->model, pair->cell_f(), 3,
                                  pair->cell_e.data(), cell_virial ? pair->cell_w.data() : nullptr,
                                  false, &cell_pass);
  } catch (tessera::Error &e) {
    // Energy or virial overflow (parameters or lengths far outside the
    // model's reduced units); the core names the local point.
    error->one(FLERR, "pair_style vertex/voronoi at step {}: {}", update->ntimestep, e.what());
  }
  // The closest pair of Voronoi neighbours, for the message of lost atoms
  // (compute_forces finds it on the way).
  pair->note_closest_pair(out.closest_cell, out.closest_neighbor, out.closest_distance2);
  double *stats = pair->stats;
  stats[0] += t1 - t0;
  stats[1] += MPI_Wtime() - t1;
  stats[4] += 1.0;
  if (pair->reference_every > 0 && update->ntimestep % pair->reference_every == 0) {
    // A from-scratch CGAL triangulation of the same points, timed for
    // benchmarks (bench/): the yardstick of the incremental mesh.
    {
      const double r0 = MPI_Wtime();
      tessera::Mesh scratch;
      scratch.build(pts);
      stats[5] += MPI_Wtime() - r0;
      stats[6] += 1.0;
    }
    // And the plain yardstick: CGAL's own Delaunay triangulation of the
    // owned points alone (no ghosts, no flat arrays), timed inside the core
    // after the scratch mesh is freed (the two never coexist in memory).
    stats[7] += tessera::time_plain_delaunay(pts, nlocal);
  }
  pair->accumulate(out.energy, 4);
}

double VertexConfluent::memory_usage() const
{
  double bytes = (double) tess.triangles.capacity() *
      (3 * sizeof(int) + sizeof(tessera::Vec2) + sizeof(double));
  bytes += (double) tess.cell_vertex.capacity() * (2 * sizeof(int) + sizeof(double));
  return bytes;
}
