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

   compute vertex/local: the boundary of each owned cell of the group, from
   the cells pair_style vertex/voronoi computed for the forces of this
   timestep, for every model.  2d: one row per junction (edge of non-zero
   length) and per free arc (finite cells; neighbour ID 0): cell ID,
   neighbour ID, the piece's two ends (counter-clockwise) and its length.
   3d: one row per edge of each face polygon (faces of non-zero area): cell
   ID, neighbour ID, the edge's two ends (counter-clockwise seen from the
   neighbour) and the face's area.
------------------------------------------------------------------------- */

#include "compute_vertex_local.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "cell_source.h"
#include "update.h"

#include "tessera/cells.h"

#include <cstring>

using namespace LAMMPS_NS;

namespace {

constexpr int NCOLS_2D = 7;
constexpr int NCOLS_3D = 9;

}    // namespace

/* ----------------------------------------------------------------------
   compute ID group vertex/local
------------------------------------------------------------------------- */

ComputeVertexLocal::ComputeVertexLocal(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0), rows(nullptr), pair(nullptr)
{
  if (narg > 3)
    error->all(FLERR,
               "Illegal compute vertex/local command: unexpected argument '{}' (it takes none: "
               "'compute ID group vertex/local')",
               arg[3]);
  if (atom->tag_enable == 0)
    error->all(FLERR, "compute vertex/local requires atom IDs (atom_modify id yes)");

  local_flag = 1;
  size_local_rows = 0;
  size_local_cols = domain->dimension == 3 ? NCOLS_3D : NCOLS_2D;
}

ComputeVertexLocal::~ComputeVertexLocal()
{
  memory->destroy(rows);
}

void ComputeVertexLocal::init()
{
  pair = CellSource::find(lmp);
  if (!pair)
    error->all(FLERR,
               "compute vertex/local {} reads the cells of pair_style vertex/voronoi or "
               "vertex/polygon, but the pair style is '{}'; define one of them (vertex/voronoi "
               "alone or as one sub-style of hybrid)",
               id, force->pair_style ? force->pair_style : "none");
}

/* ---------------------------------------------------------------------- */

void ComputeVertexLocal::compute_local()
{
  invoked_local = update->ntimestep;

  // (read before any run, e.g. through the library interface: no pair style yet)
  if (!pair)
    error->all(FLERR,
               "compute vertex/local {}: no cells yet: it reads the cells of pair_style "
               "vertex/voronoi or vertex/polygon, which exist after a run (e.g. 'run 0')",
               id);
  pair->require_current_cells(fmt::format("compute vertex/local {}", id));

  const tessera::CellView &v = pair->cells();
  // Cells on a sphere: edges (2d cells) with corners in space: 3d rows.
  const int dim = v.space_dimension();
  const int ncols = dim == 3 ? NCOLS_3D : NCOLS_2D;
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;

  // The rows, appended to a flat buffer first (their number is known only
  // after the faces' polygons are read).
  std::vector<double> &buf = flat;
  buf.clear();
  std::vector<double> xyz;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    if (dim == 2) {
      // Pieces of zero length (the edges of a multifold vertex) are not
      // junctions: they are left out, and a row ends where the next row
      // starts, so that a cell's rows close exactly into its boundary.
      const size_t first = buf.size();
      for (int k = v.piece_begin(i); k < v.piece_end(i); k++) {
        if (!(v.piece_size(k) > 0.0)) continue;
        xyz.clear();
        v.piece_corners(k, xyz);
        const int j = v.piece_neighbor(k);
        if (buf.size() > first) {
          buf[buf.size() - 3] = xyz[0];
          buf[buf.size() - 2] = xyz[1];
        }
        buf.insert(buf.end(),
                   {static_cast<double>(tag[i]), j >= 0 ? static_cast<double>(tag[j]) : 0.0, xyz[0],
                    xyz[1], xyz[2], xyz[3], v.piece_size(k)});
      }
      if (buf.size() > first) {
        buf[buf.size() - 3] = buf[first + 2];
        buf[buf.size() - 2] = buf[first + 3];
      }
      continue;
    }
    const double floor = 1e-9 * v.boundary(i);
    for (int k = v.piece_begin(i); k < v.piece_end(i); k++) {
      if (!(v.piece_size(k) > floor)) continue;
      xyz.clear();
      const int m = v.piece_corners(k, xyz);
      const int nrows = m == 2 ? 1 : m;    // an edge (sphere) is one row, a face m
      const double jd = static_cast<double>(tag[v.piece_neighbor(k)]);
      for (int q = 0; q < nrows; q++) {
        const double *a = &xyz[3 * q], *b = &xyz[3 * ((q + 1) % m)];
        // Repeated corners (several tetrahedra with one circumcentre) are
        // one corner of the polygon.
        if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) continue;
        buf.insert(
            buf.end(),
            {static_cast<double>(tag[i]), jd, a[0], a[1], a[2], b[0], b[1], b[2], v.piece_size(k)});
      }
    }
  }
  const int n = static_cast<int>(buf.size() / ncols);
  if (n > nmax) {
    memory->destroy(rows);
    nmax = MAX(n, 1);
    memory->create(rows, nmax, ncols, "vertex/local:rows");
  }
  for (int r = 0; r < n; r++)
    for (int c = 0; c < ncols; c++) rows[r][c] = buf[static_cast<size_t>(r) * ncols + c];
  size_local_rows = n;
  array_local = rows;
}

/* ---------------------------------------------------------------------- */

double ComputeVertexLocal::memory_usage()
{
  return (double) nmax * size_local_cols * sizeof(double) + flat.capacity() * sizeof(double);
}
