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

   compute vertex/loops: the closed loops of free boundary of a tissue of
   finite cells (pair_style vertex/voronoi ... radius r): the outer edge of
   each colony and each hole or wound.  The free arcs of the owned cells are
   gathered to rank 0 with their cells' atom IDs and chained there
   (tessera::free_loops), unwrapped by minimum image in periodic
   directions.  Local array (rank 0): loop index, enclosed area, length,
   number of cells, centroid x y, kind (1 outer, 0 hole, -1 wraps around a
   periodic direction).  Global vector: holes, total hole area, loops,
   wrapping loops, and the largest hole (area, centroid x y, length, cells);
   with 'min_area A' holes smaller than A (the gaps at three-cell corners)
   are left out of the global values.  compute vertex/loops/atom
   (compute_vertex_loops_atom.cpp) is this compute with per-atom output.
------------------------------------------------------------------------- */

#include "compute_vertex_loops.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "cell_source.h"
#include "update.h"

#include "tessera/cells.h"
#include "tessera/loops.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {

constexpr int NCOLS = 7;
constexpr int NVALUES = 9;
constexpr int ARC_DOUBLES = 7;    // cell ID, next ID, cx, cy, r, phi, theta

}    // namespace

/* ----------------------------------------------------------------------
   compute ID all vertex/loops [min_area A]
------------------------------------------------------------------------- */

ComputeVertexLoops::ComputeVertexLoops(LAMMPS *lmp, int narg, char **arg) :
    ComputeVertexLoops(lmp, narg, arg, false)
{
}

ComputeVertexLoops::ComputeVertexLoops(LAMMPS *lmp, int narg, char **arg, bool per_atom) :
    Compute(lmp, narg, arg), nmax(0), rows(nullptr), pair(nullptr), loops_of(-1), warned(0),
    min_area(0.0), want_chains(per_atom)
{
  int iarg = 3;
  if (per_atom && iarg < narg)
    error->all(FLERR,
               "Illegal compute vertex/loops/atom command: unexpected argument '{}' (it takes "
               "none: 'compute ID group vertex/loops/atom')",
               arg[iarg]);
  while (iarg < narg) {
    if (strcmp(arg[iarg], "min_area") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR,
                   "compute vertex/loops {}: keyword 'min_area' needs an area A (holes smaller "
                   "than A are not counted), e.g. 'min_area 0.1'",
                   id);
      min_area = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (!(min_area >= 0.0) || !std::isfinite(min_area))
        error->all(FLERR, "compute vertex/loops {}: min_area must be a finite area >= 0, got '{}'",
                   id, arg[iarg + 1]);
      iarg += 2;
    } else {
      error->all(FLERR,
                 "Illegal compute vertex/loops command: unexpected argument '{}' (known: "
                 "min_area A; 'compute ID all vertex/loops [min_area A]')",
                 arg[iarg]);
    }
  }
  if (igroup != 0 && !per_atom)
    error->all(FLERR,
               "compute vertex/loops {}: the loops are those of the whole tissue; use group "
               "'all', not '{}'",
               id, group->names[igroup]);
  if (atom->tag_enable == 0)
    error->all(FLERR, "compute {} requires atom IDs (atom_modify id yes)", style);
  if (domain->dimension != 2) {
    auto *p = CellSource::find(lmp);
    if (p && p->on_sphere()) sphere_error();
    error->all(FLERR,
               "compute {} is for 2d finite cells; a 3d tissue has no free boundary loops (nor "
               "have cells on a sphere)",
               style);
  }
  if (per_atom) return;    // (its output: compute_vertex_loops_atom.cpp)

  local_flag = 1;
  size_local_rows = 0;
  size_local_cols = NCOLS;
  vector_flag = 1;
  size_vector = NVALUES;
  extvector = 0;
  vector = new double[size_vector];
  for (int k = 0; k < size_vector; k++) vector[k] = 0.0;
}

ComputeVertexLoops::~ComputeVertexLoops()
{
  delete[] vector;
  memory->destroy(rows);
}

void ComputeVertexLoops::init()
{
  pair = CellSource::find(lmp);
  if (!pair)
    error->all(FLERR,
               "compute {} {} reads the cells of pair_style vertex/voronoi, but the pair style "
               "is '{}'; define 'pair_style vertex/voronoi CUT radius r'",
               style, id, force->pair_style ? force->pair_style : "none");
  // (again here: the pair style may have changed since the compute was defined)
  if (pair->on_sphere()) sphere_error();
  if (!(pair->finite_radius() > 0.0))
    error->all(FLERR,
               "compute {} {} needs finite cells (pair_style vertex/voronoi CUT radius r): a "
               "confluent tissue has no free boundary",
               style, id);
}

void ComputeVertexLoops::sphere_error()
{
  error->all(FLERR,
             "compute {} {}: cells on a sphere (surface sphere) close the surface, so there is "
             "no free boundary to follow",
             style, id);
}

/* The loops of this step's cells, once per pair computation. */

void ComputeVertexLoops::find_loops()
{
  // (read before any run, e.g. through the library interface: no pair style yet)
  if (!pair)
    error->all(FLERR,
               "compute {} {}: no cells yet: it reads the cells of pair_style vertex/voronoi, "
               "which exist after a run (e.g. 'run 0')",
               style, id);
  pair->require_current_cells(fmt::format("compute {} {}", style, id));
  if (pair->compute_count() == loops_of) return;
  loops_of = pair->compute_count();

  const tessera::CellView &v = pair->cells();
  const tagint *tag = atom->tag;
  std::vector<std::int64_t> ids(v.n_points());
  for (int i = 0; i < v.n_points(); i++) ids[i] = static_cast<std::int64_t>(tag[i]);
  std::vector<tessera::FreeArc> arcs;
  tessera::append_free_arcs(v, ids.data(), nullptr, arcs);

  // Gather the arcs to rank 0 (IDs as doubles: exact below 2^53).
  std::vector<double> mine;
  mine.reserve(arcs.size() * ARC_DOUBLES);
  for (const auto &a : arcs)
    mine.insert(mine.end(),
                {static_cast<double>(a.cell), static_cast<double>(a.next), a.cx, a.cy, a.r, a.phi,
                 a.theta});
  const int nprocs = comm->nprocs, me = comm->me;
  int count = static_cast<int>(mine.size());
  std::vector<int> counts(nprocs), displs(nprocs, 0);
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, world);
  std::vector<double> all;
  if (me == 0) {
    for (int p = 1; p < nprocs; p++) displs[p] = displs[p - 1] + counts[p - 1];
    all.resize(displs[nprocs - 1] + counts[nprocs - 1]);
  }
  MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
              0, world);

  int nloops = 0, unmatched = 0;
  if (me == 0) {
    std::vector<tessera::FreeArc> every(all.size() / ARC_DOUBLES);
    for (size_t k = 0; k < every.size(); k++) {
      const double *d = &all[k * ARC_DOUBLES];
      tessera::FreeArc &a = every[k];
      a.cell = static_cast<std::int64_t>(d[0]);
      a.next = static_cast<std::int64_t>(d[1]);
      a.cx = d[2];
      a.cy = d[3];
      a.r = d[4];
      a.phi = d[5];
      a.theta = d[6];
    }
    // A difference less whole box vectors (y first, then x, so that the xy
    // tilt of a triclinic box is taken along): any box vector reduces to 0.
    Domain *dom = domain;
    tessera::MinimumImage image;
    if (dom->xperiodic || dom->yperiodic) {
      const bool px = dom->xperiodic, py = dom->yperiodic;
      const double lx = dom->xprd, ly = dom->yprd, xy = dom->triclinic ? dom->xy : 0.0;
      image = [px, py, lx, ly, xy](double *x) {
        if (py) {
          const double m = std::round(x[1] / ly);
          x[1] -= m * ly;
          x[0] -= m * xy;
        }
        if (px) x[0] -= std::round(x[0] / lx) * lx;
      };
    }
    // The same order on any number of ranks: by cell ID, then angle.
    std::sort(every.begin(), every.end(), [](const tessera::FreeArc &a, const tessera::FreeArc &b) {
      return a.cell != b.cell ? a.cell < b.cell : a.phi < b.phi;
    });
    const auto loops = tessera::free_loops(every, image, 1e-6 * pair->finite_radius(), &unmatched);
    nloops = static_cast<int>(loops.size());
    if (want_chains) {
      chain_arcs.clear();
      chain_begin.assign(1, 0);
      for (const auto &loop : loops) {
        for (const auto &a : tessera::unwrapped_arcs(every, loop))
          chain_arcs.insert(chain_arcs.end(),
                            {static_cast<double>(a.cell), a.cx, a.cy, a.r, a.phi, a.theta});
        chain_begin.push_back(static_cast<int>(chain_arcs.size() / CHAIN_DOUBLES));
      }
    }
    table.assign(static_cast<size_t>(nloops) * NCOLS, 0.0);
    for (int l = 0; l < nloops; l++) {
      double *row = &table[static_cast<size_t>(l) * NCOLS];
      double c[3] = {loops[l].cx, loops[l].cy, 0.0};
      if (loops[l].kind != tessera::LoopKind::Wrapping) dom->remap(c);
      row[0] = l + 1;
      row[1] = loops[l].area;
      row[2] = loops[l].length;
      row[3] = loops[l].n_cells;
      row[4] = c[0];
      row[5] = c[1];
      row[6] = static_cast<double>(static_cast<int>(loops[l].kind));
    }
  }
  MPI_Bcast(&nloops, 1, MPI_INT, 0, world);
  MPI_Bcast(&unmatched, 1, MPI_INT, 0, world);
  table.resize(static_cast<size_t>(nloops) * NCOLS);
  if (nloops) MPI_Bcast(table.data(), nloops * NCOLS, MPI_DOUBLE, 0, world);
  if (want_chains) {
    chain_begin.resize(nloops + 1, 0);
    MPI_Bcast(chain_begin.data(), nloops + 1, MPI_INT, 0, world);
    chain_arcs.resize(static_cast<size_t>(chain_begin[nloops]) * CHAIN_DOUBLES);
    if (!chain_arcs.empty())
      MPI_Bcast(chain_arcs.data(), static_cast<int>(chain_arcs.size()), MPI_DOUBLE, 0, world);
  }
  if (unmatched && !warned && me == 0) {
    error->warning(FLERR,
                   "compute {} {}: {} free arc(s) at step {} found no arc continuing the "
                   "boundary; their loops were closed where they stopped",
                   style, id, unmatched, update->ntimestep);
    warned = 1;
  }

  if (want_chains) return;    // (no global values)

  // The holes (at least min_area), and the largest of them (the first in
  // the table's order on a tie): 0 for each of its values if there is none.
  double holes = 0.0, hole_area = 0.0, wrapping = 0.0;
  const double *largest = nullptr;
  for (int l = 0; l < nloops; l++) {
    const double *row = &table[static_cast<size_t>(l) * NCOLS];
    if (row[6] == 0.0 && row[1] >= min_area) {
      holes += 1.0;
      hole_area += row[1];
      if (!largest || row[1] > largest[1]) largest = row;
    } else if (row[6] < 0.0) {
      wrapping += 1.0;
    }
  }
  vector[0] = holes;
  vector[1] = hole_area;
  vector[2] = nloops;
  vector[3] = wrapping;
  vector[4] = largest ? largest[1] : 0.0;    // area
  vector[5] = largest ? largest[4] : 0.0;    // centroid x
  vector[6] = largest ? largest[5] : 0.0;    // centroid y
  vector[7] = largest ? largest[2] : 0.0;    // length
  vector[8] = largest ? largest[3] : 0.0;    // cells on it
}

void ComputeVertexLoops::compute_vector()
{
  invoked_vector = update->ntimestep;
  find_loops();
}

void ComputeVertexLoops::compute_local()
{
  invoked_local = update->ntimestep;
  find_loops();
  // The rows are on rank 0 only, so that a dump local lists each loop once.
  const int n = comm->me == 0 ? static_cast<int>(table.size() / NCOLS) : 0;
  if (n > nmax) {
    memory->destroy(rows);
    nmax = n;
    memory->create(rows, nmax, NCOLS, "vertex/loops:rows");
  }
  for (int r = 0; r < n; r++)
    for (int c = 0; c < NCOLS; c++) rows[r][c] = table[static_cast<size_t>(r) * NCOLS + c];
  size_local_rows = n;
  array_local = rows;
}

double ComputeVertexLoops::memory_usage()
{
  return (double) nmax * NCOLS * sizeof(double) + table.capacity() * sizeof(double) +
      chain_arcs.capacity() * sizeof(double) + chain_begin.capacity() * sizeof(int);
}
