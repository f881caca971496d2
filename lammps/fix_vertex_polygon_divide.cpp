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

   Division of vertex-model cells for fix cell/divide (doc/model.md,
   "Division and death"): the owner of each mother cuts it on the patch of
   cells it sees (tessera::divide_cell: the line through the centroid normal
   to the axis, two new vertices on the two edges it crosses and a new edge
   between them) and describes the result in one fixed-size record; every
   rank gathers all records, keeps them in the step's global order, drops a
   division that changes a cell an earlier one changes (the two would not
   commute), and writes what it owns: the mother's ring, the neighbours' rings
   with the new vertex inserted, and the new atoms whose template it owns (the
   daughter: a copy of the mother; a new vertex: a copy of the vertex at one
   end of its edge).  The same divisions, with the same IDs and numbers,
   on any number of ranks.
------------------------------------------------------------------------- */

#include "fix_vertex_polygon.h"

#include "pair_vertex_polygon.h"

#include "tessera/vertex_model.h"

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "error.h"
#include "update.h"

#include <algorithm>
#include <set>

using namespace LAMMPS_NS;

namespace {

// A division's record (doubles; IDs below 2^53 are exact).
enum Slot {
  PLACE,
  MOTHER,
  OK,
  N1,
  N1_PREV,
  N1_NEXT,
  N2,
  N2_PREV,
  N2_NEXT,
  X1,
  Y1,
  X2,
  Y2,
  MX,
  MY,
  DX,
  DY,
  LEN_M,
  LEN_D,
  HEAD
};

}    // namespace

std::vector<std::pair<int, int>> FixVertexPolygon::divide(const std::vector<Division> &mothers,
                                                          tagint first_tag, bigint *done,
                                                          bigint *refused)
{
  PairVertexPolygon &p = *pair;
  const int width = p.ring_width;
  const int rec = HEAD + 2 * width;
  tessera::VertexTissue t;
  tessera::EdgeMap m;
  build_patch(t, m);
  std::unordered_map<tagint, int> cell_of;
  for (int c = 0; c < t.n_cells(); c++) cell_of[t.cid(c)] = c;

  // The owners cut their mothers, each on its own copy of the patch.
  std::vector<double> mine;
  for (const Division &d : mothers) {
    std::vector<double> r(rec, 0.0);
    r[PLACE] = (double) d.place;
    r[MOTHER] = (double) d.mother;
    const auto it = cell_of.find(d.mother);
    const int i = atom->map(d.mother);
    if (it == cell_of.end() || i < 0 || i >= atom->nlocal)
      error->one(FLERR, "fix cell/divide: mother cell {} is not a cell this rank owns at step {}",
                 d.mother, update->ntimestep);
    const int c = it->second;
    tessera::VertexTissue tc = t;
    const tagint id_c = first_tag + 3 * d.place;
    const int nd = tessera::divide_cell(tc, c, tessera::Vec2{d.ux, d.uy}, id_c, id_c + 1);
    if (nd >= 0) {
      const int v1 = t.n_vertices(), v2 = v1 + 1;
      int n1 = -1, n2 = -1;
      for (int k = 0; k < (int) t.rings[c].size(); k++) {
        const int nb = tessera::twin_cell(t, m, c, k);
        const std::vector<int> &rr = tc.rings[nb];
        if (std::find(rr.begin(), rr.end(), v1) != rr.end()) n1 = nb;
        if (std::find(rr.begin(), rr.end(), v2) != rr.end()) n2 = nb;
      }
      auto around = [&](int nb, int v, int slot) {
        const std::vector<int> &rr = tc.rings[nb];
        const int n = (int) rr.size();
        const int j = (int) (std::find(rr.begin(), rr.end(), v) - rr.begin());
        r[slot] = (double) t.cid(nb);
        r[slot + 1] = (double) tc.vid(rr[(j + n - 1) % n]);
        r[slot + 2] = (double) tc.vid(rr[(j + 1) % n]);
        return n <= width;
      };
      bool ok = n1 >= 0 && n2 >= 0 && around(n1, v1, N1) && around(n2, v2, N2);
      const std::vector<int> &rm = tc.rings[c], &rd = tc.rings[nd];
      ok = ok && (int) rm.size() <= width && (int) rd.size() <= width;
      // A corner of either half close to the new edge (a reflex corner of a
      // concave mother next to the cut) would cross it within a few steps:
      // such a division is refused.  Close: within a fifth of the new edge's
      // length; the corners joined to its ends (along the old edges) do not
      // count.
      if (ok) {
        const tessera::Vec2 e = tc.delta(v1, v2);
        const double le2 = e.x * e.x + e.y * e.y;
        for (const std::vector<int> *half : {&rm, &rd}) {
          const int n = (int) half->size();
          for (int k = 0; k < n; k++) {
            const int v = (*half)[k], prev = (*half)[(k + n - 1) % n], next = (*half)[(k + 1) % n];
            if (v == v1 || v == v2 || prev == v1 || prev == v2 || next == v1 || next == v2)
              continue;
            const tessera::Vec2 a = tc.delta(v1, v);
            const double s = std::min(1.0, std::max(0.0, (a.x * e.x + a.y * e.y) / le2));
            const double dx = a.x - s * e.x, dy = a.y - s * e.y;
            if (dx * dx + dy * dy < 0.04 * le2) ok = false;
          }
        }
      }
      if (ok) {
        r[OK] = 1.0;
        r[X1] = tc.pos[v1].x;
        r[Y1] = tc.pos[v1].y;
        r[X2] = tc.pos[v2].x;
        r[Y2] = tc.pos[v2].y;
        // The two cell atoms at their centroids, the image next to the mother's.
        double **x = atom->x;
        const tessera::Vec2 cm = tc.measures(c).centroid, cd = tc.measures(nd).centroid;
        const tessera::Vec2 dm = t.image(cm.x - x[i][0], cm.y - x[i][1]);
        const tessera::Vec2 dd = t.image(cd.x - x[i][0], cd.y - x[i][1]);
        r[MX] = x[i][0] + dm.x;
        r[MY] = x[i][1] + dm.y;
        r[DX] = x[i][0] + dd.x;
        r[DY] = x[i][1] + dd.y;
        r[LEN_M] = (double) rm.size();
        r[LEN_D] = (double) rd.size();
        for (size_t k = 0; k < rm.size(); k++) r[HEAD + k] = (double) tc.vid(rm[k]);
        for (size_t k = 0; k < rd.size(); k++) r[HEAD + width + k] = (double) tc.vid(rd[k]);
      }
    }
    mine.insert(mine.end(), r.begin(), r.end());
  }

  // Every rank gets every record, in the step's order.
  int nmine = (int) mine.size();
  std::vector<int> counts(comm->nprocs), displs(comm->nprocs, 0);
  MPI_Allgather(&nmine, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  int total = 0;
  for (int k = 0; k < comm->nprocs; k++) {
    displs[k] = total;
    total += counts[k];
  }
  std::vector<double> all(total);
  MPI_Allgatherv(mine.data(), nmine, MPI_DOUBLE, all.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, world);
  const int nrec = total / rec;
  std::vector<const double *> recs(nrec);
  for (int k = 0; k < nrec; k++) recs[k] = all.data() + (size_t) k * rec;
  std::sort(recs.begin(), recs.end(), [](const double *a, const double *b) {
    return a[PLACE] < b[PLACE];
  });

  // A division that changes a cell an earlier one changes waits: dropped.
  std::set<tagint> changed;
  std::vector<const double *> go;
  bigint nrefused = 0;
  for (const double *r : recs) {
    const tagint cells[3] = {(tagint) r[MOTHER], (tagint) r[N1], (tagint) r[N2]};
    bool ok = r[OK] > 0.0;
    for (tagint c : cells)
      if (ok && changed.count(c)) ok = false;
    if (!ok) {
      nrefused++;
      continue;
    }
    changed.insert(cells, cells + 3);
    go.push_back(r);
  }
  if (done) *done = (bigint) go.size();
  if (refused) *refused = nrefused;

  // The rings of the atoms this rank owns.
  int **ring = atom->iarray[p.ring_index];
  auto set_ring = [&](int i, const double *ids, int n) {
    for (int k = 0; k < width; k++) ring[i][k] = k < n ? (int) ids[k] : 0;
  };
  auto insert = [&](tagint cell, tagint prev, tagint next, tagint v) {
    const int i = atom->map(cell);
    if (i < 0 || i >= atom->nlocal) return;
    const int n = p.ring_length(i);
    int j = 0;
    while (j < n && ring[i][j] != prev) j++;
    if (j == n || ring[i][(j + 1) % n] != next || n + 1 > width)
      error->one(FLERR,
                 "fix cell/divide at step {}: the ring of cell {} has no edge from vertex {} to "
                 "vertex {} for the new vertex {} (an internal inconsistency)",
                 update->ntimestep, cell, prev, next, v);
    for (int k = n; k > j + 1; k--) ring[i][k] = ring[i][k - 1];
    ring[i][j + 1] = (int) v;
  };
  for (const double *r : go) {
    const tagint id_c = first_tag + 3 * (tagint) r[PLACE];
    const int i = atom->map((tagint) r[MOTHER]);
    if (i >= 0 && i < atom->nlocal) {
      set_ring(i, r + HEAD, (int) r[LEN_M]);
      atom->x[i][0] = r[MX];
      atom->x[i][1] = r[MY];
    }
    insert((tagint) r[N1], (tagint) r[N1_PREV], (tagint) r[N1_NEXT], id_c + 1);
    insert((tagint) r[N2], (tagint) r[N2_PREV], (tagint) r[N2_NEXT], id_c + 2);
  }

  // The new atoms, each made by the owner of its template.  The ghosts go
  // (this step re-neighbours): their slots take the new atoms.
  std::vector<int> templ(3 * go.size(), -1);
  for (size_t k = 0; k < go.size(); k++) {
    const double *r = go[k];
    for (int a = 0; a < 3; a++) {
      const tagint id = a == 0 ? (tagint) r[MOTHER] : (tagint) r[a == 1 ? N1_PREV : N2_PREV];
      const int j = atom->map(id);
      if (j >= 0 && j < atom->nlocal) templ[3 * k + a] = j;
    }
  }
  atom->nghost = 0;
  std::vector<std::pair<int, int>> made;
  int ncreated = 0;
  for (size_t k = 0; k < go.size(); k++) {
    const double *r = go[k];
    const tagint id_c = first_tag + 3 * (tagint) r[PLACE];
    for (int a = 0; a < 3; a++) {
      const int from = templ[3 * k + a];
      if (from < 0) continue;
      if (atom->nlocal == atom->nmax) atom->avec->grow(0);
      const int j = atom->nlocal;
      atom->avec->copy(from, j, 0);
      atom->nlocal++;
      ncreated++;
      atom->tag[j] = id_c + a;
      double **x = atom->x;
      int **rg = atom->iarray[p.ring_index];
      if (a == 0) {
        x[j][0] = r[DX];
        x[j][1] = r[DY];
        for (int c = 0; c < width; c++)
          rg[j][c] = c < (int) r[LEN_D] ? (int) r[HEAD + width + c] : 0;
        made.emplace_back(from, j);
      } else {
        // Next to its template, by the minimum image.
        const tessera::Vec2 d =
            t.image(r[a == 1 ? X1 : X2] - x[from][0], r[a == 1 ? Y1 : Y2] - x[from][1]);
        x[j][0] = x[from][0] + d.x;
        x[j][1] = x[from][1] + d.y;
        for (int c = 0; c < width; c++) rg[j][c] = 0;
      }
    }
  }
  bigint mine_new = ncreated, all_new = 0;
  MPI_Allreduce(&mine_new, &all_new, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (all_new != 3 * (bigint) go.size())
    error->all(FLERR, "fix cell/divide at step {}: {} new atoms for {} divisions (expected {})",
               update->ntimestep, all_new, go.size(), 3 * go.size());
  atom->natoms += all_new;
  if (atom->map_style != 0) {
    atom->map_init();
    atom->map_set();
  }
  p.stats[2] += (double) nrefused;
  return made;
}
