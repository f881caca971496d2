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

   The topology step of pair_style vertex/polygon's internal fix (doc/model.md,
   "Topology in parallel: every rank decides the same, no messages"): every
   rank builds the patch of cells it sees from the owners' coordinates,
   evaluates the core's rule on it (tessera::find_events, decide_events), and
   applies what it decides to the atoms it owns; then the ghosts are
   refreshed.
------------------------------------------------------------------------- */

#include "fix_vertex_polygon.h"

#include "pair_vertex_polygon.h"
#include "tessera_compat.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "update.h"
#include "tessera/vertex_model.h"

#include <unordered_map>

using namespace LAMMPS_NS;

struct FixVertexPolygon::Patch {
  tessera::VertexTissue tissue;
  tessera::EdgeMap edges;
};

namespace {

const char *kind_name(const tessera::TopologyEvent &e)
{
  return e.kind == tessera::TopologyEvent::T1 ? "T1" : "T2";
}

}    // namespace

/* The patch of cells this rank sees (by ID, with the owners' coordinates,
   so that what the rule computes is the same number on every rank), checked
   to hold whole what this rank owns: its cells and their neighbours, and the
   three cells of each of its vertices.  Collective (forward communication). */

void FixVertexPolygon::build_patch(tessera::VertexTissue &t, tessera::EdgeMap &m)
{
  PairVertexPolygon &p = *pair;
  forward_rings();
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  double **x = atom->x;
  const int *type = atom->type;
  const tagint *tag = atom->tag;
  int **ring = atom->iarray[p.ring_index];

  canon.assign(2 * static_cast<size_t>(nall), 0.0);
  for (int i = 0; i < nlocal; i++) {
    canon[2 * i] = x[i][0];
    canon[2 * i + 1] = x[i][1];
  }
  mode = CANONICAL;
  tessera_compat::forward_comm(comm, this);

  // The patch's cells and vertices by ID, each ID at the atom map's index
  // for it (one per ID, whichever copy), in the order of the local atoms.
  patch_of.assign(nall, -1);
  t.periodic = true;
  t.box =
      tessera::Box::rect(domain->boxlo[0], domain->boxhi[0], domain->boxlo[1], domain->boxhi[1]);
  t.box.xy = domain->triclinic ? domain->xy : 0.0;
  t.pos.clear();
  t.type.clear();
  t.vertex_id.clear();
  t.cell_id.clear();
  t.vertex_known.clear();
  t.vertex_removed.clear();
  std::unordered_map<tagint, int> unknown;
  complete.clear();
  int ncell = 0;
  for (int i = 0; i < nall; i++) {
    if (p.role(type[i]) != PairVertexPolygon::CELL || ring[i][0] <= 0) continue;
    const int ci = atom->map(tag[i]);
    if (patch_of[ci] >= 0) continue;
    patch_of[ci] = ncell;
    const int n = p.ring_length(i);
    if (ncell == t.n_cells()) t.rings.emplace_back();
    std::vector<int> &r = t.rings[ncell++];
    r.resize(n);
    char whole = 1;    // t.complete(): every vertex known
    for (int k = 0; k < n; k++) {
      const tagint v = ring[i][k];
      const int j = v > 0 && v <= atom->map_tag_max ? atom->map(v) : -1;
      if (j < 0) {
        whole = 0;
        // An ID no atom here has: an unknown vertex, one per ID.
        const auto ins = unknown.emplace(v, t.n_vertices());
        if (ins.second) {
          t.pos.push_back(tessera::Vec2{});
          t.vertex_known.push_back(0);
          t.vertex_id.push_back(v);
        }
        r[k] = ins.first->second;
        continue;
      }
      if (patch_of[j] < 0) {
        patch_of[j] = t.n_vertices();
        t.pos.push_back(tessera::Vec2{canon[2 * j], canon[2 * j + 1]});
        t.vertex_known.push_back(1);
        t.vertex_id.push_back(v);
      }
      r[k] = patch_of[j];
    }
    t.type.push_back(type[i] - 1);
    t.cell_id.push_back(tag[i]);
    complete.push_back(n > 0 ? whole : 0);
  }
  t.rings.resize(ncell);
  m.build(t);
  // Each owned cell's neighbours complete, each owned vertex in three
  // complete cells (complete: the flags of t.complete() made above).
  seen.assign(t.n_vertices(), 0);
  for (int c = 0; c < ncell; c++) {
    if (!complete[c]) continue;
    const std::vector<int> &r = t.rings[c];
    const int n = static_cast<int>(r.size());
    for (int v : r) seen[v]++;
    if (!owned(t.cid(c))) continue;
    for (int k = 0; k < n; k++) {
      const int o = m.cell(r[k + 1 == n ? 0 : k + 1], r[k]);
      if (o < 0 || !complete[o]) thin(fmt::format("a neighbour of cell {}", t.cid(c)));
    }
  }
  for (int i = 0; i < nlocal; i++)
    if (p.role(type[i]) == PairVertexPolygon::VERTEX && ring[i][0] == 0) {
      if (patch_of[i] < 0 || seen[patch_of[i]] != 3)
        thin(fmt::format("the set of cells around vertex {}", tag[i]));
    }
}

bool FixVertexPolygon::owned(tagint id) const
{
  const int j = atom->map(id);
  return j >= 0 && j < atom->nlocal;
}

void FixVertexPolygon::thin(const std::string &what) const
{
  error->one(FLERR,
             "pair_style vertex/polygon at step {}: {} is not complete among this rank's atoms: "
             "the cutoff {} is too small for the topology (use about 3.5 cell diameters, e.g. "
             "{:.3g})",
             update->ntimestep, what, pair->cut_global, 1.5 * pair->cut_global);
}

bigint FixVertexPolygon::run_topology()
{
  PairVertexPolygon &p = *pair;
  const int nlocal = atom->nlocal;
  double **x = atom->x;
  int **ring = atom->iarray[p.ring_index];
  const int width = p.ring_width;

  // (kept between steps: the rings' and the edge map's arrays are reused)
  if (!patch) patch = std::make_shared<Patch>();
  tessera::VertexTissue &t = patch->tissue;
  tessera::EdgeMap &m = patch->edges;
  build_patch(t, m);
  const std::vector<tessera::TopologyEvent> events = tessera::find_events(t, m, p.topo);
  const std::vector<tessera::EventStatus> status = tessera::decide_events(t, m, events);
  double counts[3] = {0.0, 0.0, 0.0};    // T1s, T2s, refused (by the owner of the first cell)
  for (size_t e = 0; e < events.size(); e++) {
    const tessera::TopologyEvent &ev = events[e];
    std::vector<int> verts;    // the vertices it changes
    if (ev.kind == tessera::TopologyEvent::T1) {
      verts = {ev.a, ev.b};
    } else if (ev.cells[0] >= 0) {
      verts = t.rings[ev.cells[0]];
    }
    bool mine = false;
    for (int c : ev.cells)
      if (c >= 0 && owned(t.cid(c))) mine = true;
    for (int v : verts)
      if (owned(t.vid(v))) mine = true;
    if (!mine) continue;
    if (status[e] == tessera::EventStatus::Undecidable)
      thin(fmt::format("the neighbourhood of a {} candidate ({} {} {})", kind_name(ev),
                       ev.kind == tessera::TopologyEvent::T1 ? "edge between vertices" : "cell",
                       ev.id0,
                       ev.kind == tessera::TopologyEvent::T1 ? std::to_string(ev.id1) : ""));
    if (status[e] != tessera::EventStatus::Carry) continue;
    const bool counter = ev.cells[0] >= 0 && owned(t.cid(ev.cells[0]));
    // A T1 makes W and Z one side longer: refused if a ring would not fit.
    bool ok = ev.kind == tessera::TopologyEvent::T2 ||
        (ev.cells[2] >= 0 && ev.cells[3] >= 0 &&
         static_cast<int>(t.rings[ev.cells[2]].size()) < width &&
         static_cast<int>(t.rings[ev.cells[3]].size()) < width);
    const std::vector<int> before = ev.cells[0] >= 0 ? t.rings[ev.cells[0]] : std::vector<int>();
    if (ok) ok = tessera::apply_event(t, ev, p.topo);
    if (counter) counts[ok ? (ev.kind == tessera::TopologyEvent::T1 ? 0 : 1) : 2] += 1.0;
    if (!ok) continue;
    // Write what changed into the atoms this rank owns.
    for (int c : ev.cells) {
      if (c < 0) continue;
      const int i = atom->map(t.cid(c));
      if (i < 0 || i >= nlocal) continue;
      const std::vector<int> &r = t.rings[c];
      if (r.empty()) {
        ring[i][0] = -1;    // removed by a T2: deleted at the next step
        for (int k = 1; k < width; k++) ring[i][k] = 0;
        continue;
      }
      for (int k = 0; k < width; k++) ring[i][k] = k < (int) r.size() ? (int) t.vid(r[k]) : 0;
    }
    for (int v : ev.kind == tessera::TopologyEvent::T1 ? verts : before) {
      const int i = atom->map(t.vid(v));
      if (i < 0 || i >= nlocal) continue;
      if (t.removed(v)) {
        ring[i][0] = -1;
      } else {
        x[i][0] = t.pos[v].x;
        x[i][1] = t.pos[v].y;
      }
    }
  }
  double all[3];
  MPI_Allreduce(counts, all, 3, MPI_DOUBLE, MPI_SUM, world);
  p.stats[0] += all[0];
  p.stats[1] += all[1];
  p.stats[2] += all[2];
  p.stats[3] += 1.0;
  // The ghosts: new positions and rings.
  comm->forward_comm();
  forward_rings();
  if (all[1] > 0.0) {
    p.delete_step = update->ntimestep + 1;
    next_reneighbor = update->ntimestep + 1;
  }
  return static_cast<bigint>(all[0] + all[1]);
}
