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

   pair_style vertex/voronoi: which atoms are cells.  The cells are the
   atoms of the types given cell parameters (pair_coeff I I ...); under
   pair_style hybrid/overlay the other types' atoms (obstacles, beads,
   fibre beads, walls) are no cells: no unit ever sees them.  Before each
   tessellation gather_cells() lists this step's cell atoms, owned first,
   then ghosts, with their positions; the units tessellate that list, add
   forces to its own array and name its atoms by cell_tag(); finish_cells()
   adds those forces to the atoms and binds the view (tessera/subset_cells.h)
   that shows the cells by local atom index, a non-cell atom an empty cell.
   When every type is a cell type the list is the atoms themselves.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"

#include "pair_vertex_voronoi_model.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "pair_hybrid.h"
#include "tessera/subset_cells.h"

#include <cstring>

using namespace LAMMPS_NS;

/* Called by init_style: the cell types, and the rules of what may be no cell. */

void PairVertexVoronoi::check_cell_types()
{
  const int n = atom->ntypes;
  all_cell_types = 1;
  int ncell = 0;
  for (int i = 1; i <= n; i++) {
    if (type_set[i])
      ncell++;
    else
      all_cell_types = 0;
  }
  if (!all_cell_types && force->pair == this) {
    int t = 1;
    while (type_set[t]) t++;
    error->all(FLERR,
               "pair_style vertex/voronoi: no cell parameters for atom type {}; add 'pair_coeff "
               "{} {} K A0 Gamma Lambda' to make its atoms cells, or, for atoms that are not "
               "cells (obstacles, beads), use 'pair_style hybrid/overlay vertex/voronoi ... "
               "<style> ...' with 'pair_coeff I I vertex/voronoi ...' for the cell types only "
               "and the other style for type {}",
               t, t, t, t);
  }
  if (ncell == 0)
    error->all(FLERR,
               "pair_style vertex/voronoi: no atom type has cell parameters; give them with "
               "'pair_coeff I I vertex/voronoi K A0 Gamma Lambda' for the cell types");
  // A junction tension names two cell types.
  for (int i = 1; i <= n; i++)
    for (int j = i + 1; j <= n; j++)
      if (lambda_set[i][j] && (!type_set[i] || !type_set[j]))
        error->all(FLERR,
                   "pair_coeff {} {} vertex/voronoi: a junction tension between types {} and {}, "
                   "but type {} has no cell parameters (its atoms are not cells and have no "
                   "junctions); give it cell parameters with 'pair_coeff {} {} vertex/voronoi "
                   "...' or remove this pair_coeff",
                   i, j, i, j, type_set[i] ? j : i, type_set[i] ? j : i, type_set[i] ? j : i);
  // Every two cells share the tessellation, whatever their types, so a pair of
  // cell types stays this style's.  pair_style hybrid (not hybrid/overlay,
  // which adds styles to a pair) gives a pair to the style its last pair_coeff
  // names alone: that would leave the pair's junctions in the tessellation
  // while hybrid says the pair is another style's.
  if (force->pair != this && strcmp(force->pair_style, "hybrid") == 0) {
    auto *hybrid = static_cast<PairHybrid *>(force->pair);
    char name[] = "vertex/voronoi";
    for (int i = 1; i <= n; i++)
      for (int j = i; j <= n; j++)
        if (type_set[i] && type_set[j] && hybrid->setflag[i][j] &&
            !hybrid->check_ijtype(i, j, name))
          error->all(FLERR,
                     "pair_style hybrid: pair_coeff {} {} gives the type pair {} {}, both cell "
                     "types, to another style alone, but their cells still share junctions "
                     "(every two neighbouring cells do); to add a style to cells use 'pair_style "
                     "hybrid/overlay', which keeps the pair with vertex/voronoi; if type {}'s "
                     "atoms are no cells, give cell parameters to the cell types only "
                     "('pair_coeff I I vertex/voronoi ...' instead of '* *')",
                     i, j, i, j, j);
  }
}

void PairVertexVoronoi::gather_cells()
{
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  if (all_cell_types) {
    ncell_local = nlocal;
    ncell_all = nall;
    return;
  }
  const int *type = atom->type;
  cell_scratch.clear();
  for (int i = 0; i < nall; i++) {
    if (i == nlocal) ncell_local = static_cast<int>(cell_scratch.size());
    if (type_set[type[i]]) cell_scratch.push_back(i);
  }
  if (nall == nlocal) ncell_local = static_cast<int>(cell_scratch.size());
  ncell_all = static_cast<int>(cell_scratch.size());
  // A different list (atoms exchanged or sorted, types changed): the units
  // that keep their triangulation between steps start afresh.
  if (cell_scratch != cell_local) {
    cell_local.swap(cell_scratch);
    cell_map_version++;
  }
  double **x = atom->x;
  cell_xbuf.resize(3 * static_cast<size_t>(ncell_all));
  for (int p = 0; p < ncell_all; p++)
    for (int d = 0; d < 3; d++) cell_xbuf[3 * p + d] = x[cell_local[p]][d];
  cell_fbuf.assign(3 * static_cast<size_t>(ncell_all), 0.0);
}

const double *PairVertexVoronoi::cell_x() const
{
  return all_cell_types ? &atom->x[0][0] : cell_xbuf.data();
}

double *PairVertexVoronoi::cell_f()
{
  return all_cell_types ? &atom->f[0][0] : cell_fbuf.data();
}

tagint PairVertexVoronoi::cell_tag(int p) const
{
  return atom->tag[cell_atom(p)];
}

/* A per-atom array's values of the owned cells, in the list's order
   (slot k of four), or the array itself when every atom is a cell. */

const double *PairVertexVoronoi::compact_values(const double *per_atom, int k)
{
  if (all_cell_types || !per_atom) return per_atom;
  std::vector<double> &v = cell_pc[k];
  v.resize(ncell_local);
  for (int c = 0; c < ncell_local; c++) v[c] = per_atom[cell_local[c]];
  return v.data();
}

/* The units are done: their forces go to the atoms, the per-cell energies
   to owned atoms, and the view shows the cells by local atom index. */

void PairVertexVoronoi::finish_cells()
{
  unit->view().energy = cell_e.data();
  if (all_cell_types) return;
  double **f = atom->f;
  for (int p = 0; p < ncell_all; p++) {
    double *fi = f[cell_local[p]];
    const double *fp = &cell_fbuf[3 * static_cast<size_t>(p)];
    fi[0] += fp[0];
    fi[1] += fp[1];
    fi[2] += fp[2];
  }
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  cell_e_atom.assign(nlocal, 0.0);
  for (int c = 0; c < ncell_local; c++) cell_e_atom[cell_local[c]] = cell_e[c];
  subset.bind(unit->view(), cell_local, nlocal, nall, tessera::Points3{&atom->x[0][0], nall, 3});
  subset.energy = cell_e_atom.data();
}

/* A new cell is a cell of its type: A0, KA = K/2, KP = Gamma/2 and
   P0 = -w Lambda_tt / Gamma (tessera::Model's quadratic form), as the type's
   cells have without per-cell properties. */

void PairVertexVoronoi::type_cell_values(int type, double values[4]) const
{
  for (int k = 0; k < 4; k++) values[k] = 0.0;
  if (!is_cell_type(type) || type < 1 || type > model.ntypes()) return;
  const tessera::CellType &c = model.types[type - 1];
  values[0] = c.A0;
  values[1] = 0.5 * c.K;
  values[2] = 0.5 * c.Gamma;
  if (c.Gamma > 0.0)
    values[3] = -model.tension_weight() * model.lambda_of(type - 1, type - 1) / c.Gamma;
}
