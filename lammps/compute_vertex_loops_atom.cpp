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

   compute vertex/loops/atom: the loops of compute vertex/loops (the same
   code, so the same numbering) seen from each atom.  Per-atom array, 3
   columns: the innermost loop whose enclosed region holds the atom (or a
   periodic image of it), the lowest-numbered loop the atom's own free arcs
   lie on, and how many loops they lie on.  A separate style because
   vertex/loops has a global vector: with a per-atom array beside it,
   c_ID[I] in an atom-style variable would read the global element in
   some LAMMPS versions.  Rank 0 chains the loops and broadcasts their
   unwrapped arcs; each rank locates its own atoms (tessera::LoopLocator).
------------------------------------------------------------------------- */

#include "compute_vertex_loops_atom.h"

#include "atom.h"
#include "domain.h"
#include "memory.h"
#include "update.h"

#include "tessera/loops.h"

#include <unordered_map>

using namespace LAMMPS_NS;

namespace {

constexpr int NCOLS = 3;
constexpr int NCOLS_LOOPS = 7;    // compute vertex/loops' table: area is [1], kind [6]

struct OnLoops {
  int lowest = 0;    // the lowest-numbered loop with an arc of the cell
  int count = 0;     // how many loops have one
  int last = 0;      // the loop its last arc seen was on
};

}    // namespace

/* ----------------------------------------------------------------------
   compute ID group vertex/loops/atom
------------------------------------------------------------------------- */

ComputeVertexLoopsAtom::ComputeVertexLoopsAtom(LAMMPS *lmp, int narg, char **arg) :
    ComputeVertexLoops(lmp, narg, arg, true), nmax_atom(0), values(nullptr)
{
  peratom_flag = 1;
  size_peratom_cols = NCOLS;
}

ComputeVertexLoopsAtom::~ComputeVertexLoopsAtom()
{
  memory->destroy(values);
}

void ComputeVertexLoopsAtom::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  find_loops();
  if (atom->nmax > nmax_atom) {
    memory->destroy(values);
    nmax_atom = atom->nmax;
    memory->create(values, nmax_atom, NCOLS, "vertex/loops/atom:values");
    array_atom = values;
  }

  const int nloops = static_cast<int>(chain_begin.size()) - 1;
  tessera::LoopBox box;
  box.lo[0] = domain->boxlo[0];
  box.lo[1] = domain->boxlo[1];
  box.len[0] = domain->xprd;
  box.len[1] = domain->yprd;
  box.xy = domain->triclinic ? domain->xy : 0.0;
  box.periodic[0] = domain->xperiodic != 0;
  box.periodic[1] = domain->yperiodic != 0;
  tessera::LoopLocator where(box);
  std::vector<tessera::FreeArc> arcs;
  std::unordered_map<tagint, OnLoops> on_loops;
  for (int l = 0; l < nloops; l++) {
    arcs.clear();
    for (int k = chain_begin[l]; k < chain_begin[l + 1]; k++) {
      const double *d = &chain_arcs[static_cast<size_t>(k) * CHAIN_DOUBLES];
      tessera::FreeArc a;
      a.cell = static_cast<std::int64_t>(d[0]);
      a.cx = d[1];
      a.cy = d[2];
      a.r = d[3];
      a.phi = d[4];
      a.theta = d[5];
      arcs.push_back(a);
      // (loops come in increasing order, a loop's arcs together)
      OnLoops &c = on_loops[static_cast<tagint>(a.cell)];
      if (c.last != l + 1) {
        if (c.count++ == 0) c.lowest = l + 1;
        c.last = l + 1;
      }
    }
    const double *row = &table[static_cast<size_t>(l) * NCOLS_LOOPS];
    where.add(arcs.data(), static_cast<int>(arcs.size()), row[1], row[6] < 0.0);
  }
  where.finish();

  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  double **x = atom->x;
  for (int i = 0; i < nlocal; i++) {
    double *v = values[i];
    v[0] = v[1] = v[2] = 0.0;
    if (!(mask[i] & groupbit)) continue;
    v[0] = where.innermost(x[i]);
    const auto found = on_loops.find(atom->tag[i]);
    if (found != on_loops.end()) {
      v[1] = found->second.lowest;
      v[2] = found->second.count;
    }
  }
}

double ComputeVertexLoopsAtom::memory_usage()
{
  return ComputeVertexLoops::memory_usage() + (double) nmax_atom * NCOLS * sizeof(double);
}
