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

   pair_style vertex/polygon: the rings after each re-neighbouring
   (refresh()): each owned cell's vertices as their closest local copies,
   the cells across its edges, and the tissue's consistency checks with the
   errors that name the atoms.  Apart from the per-step energy and forces
   (pair_vertex_polygon.cpp), which only read what it builds.
------------------------------------------------------------------------- */

#include "pair_vertex_polygon.h"

#include "fix_vertex_polygon.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

void PairVertexPolygon::missing_atom(int i, tagint id, const char *what) const
{
  error->one(FLERR,
             "pair_style vertex/polygon: {} {} of cell {} is not among this rank's atoms: it "
             "does not exist (the ring in i_vring names a wrong ID), or the cutoff {} is too "
             "small for this cell (use about 3.5 cell diameters)",
             what, id, atom->tag[i], cut_global);
}

bool PairVertexPolygon::surely_inside_ghosts(const double *x, double margin) const
{
  if (domain->triclinic) return false;
  const double width = MAX(neighbor->cutneighmax, comm->cutghostuser) - 0.5 * neighbor->skin;
  for (int d = 0; d < 2; d++)
    if (x[d] < domain->sublo[d] - width + margin || x[d] > domain->subhi[d] + width - margin)
      return false;
  return true;
}

/* After every re-neighbouring: the ghosts' rings, each owned cell's ring as
   local copies (closest to the cell atom) and its neighbours across its
   edges, and the tissue's consistency (every edge has a cell on its other
   side, every vertex is in three cells). */

void PairVertexPolygon::refresh()
{
  fix->forward_rings();
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  const int *type = atom->type;
  const tagint *tag = atom->tag;
  int **ring = atom->iarray[ring_index];
  double **x = atom->x;

  // Directed edges (a, b) of every local cell, owned copies first (the
  // first copy of an edge keeps it), filed under the atom map's copy of a.
  // Edges whose ends are not here are left out: an owned cell's are here
  // (checked below), and only those are looked up.  Each cell once, by its
  // atom map's copy: its first (the map lists an ID's copies from the
  // lowest index, an owned one first), which the others' edges would only
  // repeat.
  auto vertex_index = [&](tagint id) {
    return id > 0 && id <= atom->map_tag_max ? atom->map(id) : -1;
  };
  edge_first.assign(nall + 1, 0);
  for (int i = 0; i < nall; i++) {
    if (role(type[i]) != CELL || (i >= nlocal && atom->map(tag[i]) != i)) continue;
    const int n = ring_length(i);
    for (int k = 0; k < n; k++) {
      const int ja = vertex_index(ring[i][k]);
      if (ja >= 0) edge_first[ja + 1]++;
    }
  }
  for (int j = 0; j < nall; j++) edge_first[j + 1] += edge_first[j];
  edge_to.resize(edge_first[nall]);
  edge_cell.resize(edge_first[nall]);
  edge_fill.assign(edge_first.begin(), edge_first.end() - 1);
  for (int i = 0; i < nall; i++) {
    if (role(type[i]) != CELL || (i >= nlocal && atom->map(tag[i]) != i)) continue;
    const int n = ring_length(i);
    for (int k = 0; k < n; k++) {
      const tagint a = ring[i][k], b = ring[i][k + 1 == n ? 0 : k + 1];
      const int ja = vertex_index(a);
      if (ja < 0) continue;
      int e = edge_first[ja];
      while (e < edge_fill[ja] && edge_to[e] != b) e++;
      if (e == edge_fill[ja]) {
        edge_to[e] = static_cast<int>(b);
        edge_cell[e] = i;
        edge_fill[ja]++;
      } else if (tag[edge_cell[e]] != tag[i] && i < nlocal)
        error->one(FLERR,
                   "pair_style vertex/polygon: cells {} and {} both hold the edge from vertex {} "
                   "to vertex {} in the same direction (a ring runs clockwise, or two cells "
                   "overlap)",
                   tag[i], tag[edge_cell[e]], a, b);
    }
  }
  // A copy of an atom less than a quarter of the box's shortest period from
  // atom i is the closest image to i (every other image of it is more than
  // three quarters away), which closest_image() finds by a search of the
  // copies; beyond, that search.
  const double quarter = 0.25 * MIN(domain->xprd, domain->yprd);
  const double near2 = quarter * quarter;
  auto closest = [&](int i, int j) {
    const double dx = x[i][0] - x[j][0], dy = x[i][1] - x[j][1], dz = x[i][2] - x[j][2];
    return dx * dx + dy * dy + dz * dz < near2 ? j : domain->closest_image(i, j);
  };
  off.assign(nlocal + 1, 0);
  // (sized ahead, grown by doubling: the entries are written, not appended)
  int nring = 0;
  if (ring_local.size() < 8) ring_local.resize(8);
  std::vector<int> ring_map;    // the atom map's index of each entry's vertex
  ring_map.resize(ring_local.size());
  double reach2 = 0.0;
  // (a square below this has its root within the cutoff: no root taken)
  const double below_cut2 = 0.99 * cut_global * cut_global;
  for (int i = 0; i < nlocal; i++) {
    off[i] = nring;
    const int t = role(type[i]);
    if (t == VERTEX) {
      if (ring[i][0] > 0)
        error->one(FLERR,
                   "pair_style vertex/polygon: atom {} of vertex type {} has a ring in i_vring: "
                   "only cell atoms have rings (vertex and cell types mixed up?)",
                   tag[i], type[i]);
      continue;
    }
    if (t == NONE && ring[i][0] > 0)
      error->one(FLERR,
                 "pair_style vertex/polygon: atom {} of type {}, which is no type of this style "
                 "(a particle), has a ring in i_vring: give type {} cell parameters, or write "
                 "zeros in its ring (a particle is in no cell and has no polygon)",
                 tag[i], type[i], type[i]);
    if (t != CELL || ring[i][0] < 0) continue;
    const int n = ring_length(i);
    if (n < 3)
      error->one(FLERR,
                 "pair_style vertex/polygon: cell {} (type {}) has {} vertices in its ring "
                 "(i_vring); a cell needs at least three (a cell atom without a polygon?)",
                 tag[i], type[i], n);
    if (nring + n > static_cast<int>(ring_local.size())) {
      ring_local.resize(2 * static_cast<size_t>(nring + n));
      ring_map.resize(ring_local.size());
    }
    for (int k = 0; k < n; k++) {
      // (atom->map reads past its array for IDs beyond the largest)
      const tagint id = ring[i][k];
      int j = id > 0 && id <= atom->map_tag_max ? atom->map(id) : -1;
      if (j < 0) missing_atom(i, id, "vertex");
      if (role(type[j]) != VERTEX)
        error->one(FLERR,
                   "pair_style vertex/polygon: cell {} lists atom {} in its ring, which is not a "
                   "vertex (its type {} is {}; vertex and cell types mixed up?)",
                   tag[i], ring[i][k], type[j],
                   role(type[j]) == CELL ? "a cell type" : "no vertex type");
      ring_map[nring] = j;
      j = closest(i, j);
      ring_local[nring++] = j;
      const double dx = x[j][0] - x[i][0], dy = x[j][1] - x[i][1];
      const double d2 = dx * dx + dy * dy;
      // Only copies within the ghost shell are sure to be the right image.
      if (d2 > below_cut2 && std::sqrt(d2) > cut_global)
        error->one(FLERR,
                   "pair_style vertex/polygon: vertex {} of cell {} is {:.4g} from the cell atom, "
                   "beyond the cutoff {}: use a cutoff of at least 3.5 cell diameters (a cell "
                   "atom far from its polygon, or cells larger than the cutoff)",
                   ring[i][k], tag[i], std::sqrt(d2), cut_global);
      // (the largest distance is the root of the largest square: one root)
      reach2 = MAX(reach2, d2);
    }
    // A vertex twice in a ring: an invalid cell, found here once per
    // re-neighbouring (rings change only then), not at each force computation.
    for (int k = 0; k < n; k++)
      for (int q = k + 1; q < n; q++)
        if (ring[i][k] == ring[i][q])
          error->one(FLERR,
                     "pair_style vertex/polygon at step {}: cell {} lists vertex {} twice in its "
                     "ring (i_vring); a cell's polygon visits each of its vertices once",
                     update->ntimestep, tag[i], ring[i][k]);
  }
  off[nlocal] = nring;
  ring_local.resize(nring);
  const double reach_local = std::sqrt(reach2);
  // Then, with every ring's vertices known to exist, the cells across edges.
  nbr_local.resize(nring);
  for (int i = 0; i < nlocal; i++) {
    const int n = off[i + 1] - off[i];
    for (int k = 0; k < n; k++) {
      const int k1 = k + 1 == n ? 0 : k + 1;
      const tagint a = ring[i][k], b = ring[i][k1];
      // The cell holding (b, a); b is here (its copy is in ring_local).
      const int jb = ring_map[off[i] + k1];
      int e = edge_first[jb];
      while (e < edge_fill[jb] && edge_to[e] != a) e++;
      if (e == edge_fill[jb]) {
        const double *xa = x[ring_local[off[i] + k]];
        if (surely_inside_ghosts(xa, 2.0 * reach_local + neighbor->skin))
          error->one(FLERR,
                     "pair_style vertex/polygon: the edge from vertex {} to vertex {} of cell {} "
                     "has no cell on its other side: the rings do not close (a ring lists a "
                     "wrong vertex, or runs clockwise)",
                     a, b, tag[i]);
        error->one(FLERR,
                   "pair_style vertex/polygon: the edge from vertex {} to vertex {} of cell {} "
                   "has no cell on its other side among this rank's atoms: the rings do not "
                   "close, or the cutoff {} is too small (use about 3.5 cell diameters)",
                   a, b, tag[i], cut_global);
      }
      nbr_local[off[i] + k] = closest(i, edge_cell[e]);
    }
  }
  MPI_Allreduce(&reach_local, &reach, 1, MPI_DOUBLE, MPI_MAX, world);

  // Every vertex in exactly three cells: each owned cell counts itself at
  // its vertices' local copies, ghosts' counts go home.
  std::vector<double> count(nall, 0.0);
  for (int j : ring_local) count[j] += 1.0;
  fix->reverse_counts(count);
  for (int i = 0; i < nlocal; i++)
    if (role(type[i]) == VERTEX && ring[i][0] == 0 && count[i] != 3.0)
      error->one(FLERR,
                 "pair_style vertex/polygon: vertex {} is in {} cells; every vertex is in exactly "
                 "three (check the rings in i_vring{})",
                 tag[i], static_cast<int>(count[i]),
                 count[i] == 0.0 ? ": a vertex in no cell" : "");
  cache_epoch = epoch;
}
