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

   create_vertices: the vertex tissue of the Voronoi polygons of a group of
   cell centres (see create_vertices.h).  Every rank tessellates all centres,
   sorted by atom ID (tessera::vertex_tissue_from_voronoi), creates the vertex
   atoms inside its sub-domain and writes the rings of the cells it owns.
------------------------------------------------------------------------- */

#include "create_vertices.h"

#include "tessera/vertex_model.h"

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "modify.h"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <unordered_map>
#include <vector>

using namespace LAMMPS_NS;

void CreateVertices::command(int narg, char **arg)
{
  if (narg < 2)
    error->all(FLERR,
               "Illegal create_vertices command: expected 'create_vertices group-ID "
               "vertex-type [maxsides W]'");
  if (domain->box_exist == 0)
    error->all(FLERR, "create_vertices command before the simulation box is defined");
  if (domain->dimension != 2 || !domain->xperiodic || !domain->yperiodic)
    error->all(FLERR,
               "create_vertices needs a 2d box periodic in x and y ('dimension 2', "
               "'boundary p p p')");
  if (atom->tag_enable == 0) error->all(FLERR, "create_vertices requires atom IDs");
  if (atom->map_style == 0)
    error->all(FLERR,
               "create_vertices needs an atom map: add 'atom_modify map yes' before the "
               "box is created");
  const int igroup = group->find(arg[0]);
  if (igroup < 0) error->all(FLERR, "create_vertices: no group '{}'", arg[0]);
  const int groupbit = group->bitmask[igroup];
  const int vtype = utils::inumeric(FLERR, arg[1], false, lmp);
  if (vtype < 1 || vtype > atom->ntypes)
    error->all(FLERR, "create_vertices: vertex type {} is not in 1 .. {}", arg[1], atom->ntypes);
  int width = 0;
  for (int iarg = 2; iarg < narg; iarg += 2) {
    if (strcmp(arg[iarg], "maxsides") != 0 || iarg + 2 > narg)
      error->all(FLERR, "create_vertices: unknown keyword '{}' (known: maxsides W)", arg[iarg]);
    width = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
    if (width < 3) error->all(FLERR, "create_vertices: maxsides must be >= 3, got {}", width);
  }

  // The rings' array: fix vring, defined here unless it exists.
  int flag = -1, cols = -1;
  int index = atom->find_custom("vring", flag, cols);
  if (index < 0) {
    if (width == 0) width = 16;
    modify->add_fix(fmt::format("vring all property/atom i2_vring {}", width));
    index = atom->find_custom("vring", flag, cols);
    for (int i = 0; i < atom->nlocal; i++)
      for (int k = 0; k < width; k++) atom->iarray[index][i][k] = 0;
  } else if (flag != 0 || cols <= 0) {
    error->all(FLERR,
               "create_vertices: 'vring' must be an integer array (fix vring all "
               "property/atom i2_vring W)");
  } else if (width > 0 && width != cols) {
    error->all(FLERR,
               "create_vertices: maxsides {} differs from the {} columns of the existing "
               "i2_vring",
               width, cols);
  }
  width = cols;

  // Every cell centre, on every rank, sorted by ID.
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask, *type = atom->type;
  const tagint *tag = atom->tag;
  std::vector<tagint> mytag;
  std::vector<double> myx;
  std::vector<int> mytype;
  tagint maxtag_local = 0;
  for (int i = 0; i < nlocal; i++) {
    maxtag_local = MAX(maxtag_local, tag[i]);
    if (!(mask[i] & groupbit)) continue;
    if (atom->iarray[index][i][0] != 0)
      error->one(FLERR, "create_vertices: atom {} of group {} has a ring already", tag[i], arg[0]);
    mytag.push_back(tag[i]);
    myx.push_back(atom->x[i][0]);
    myx.push_back(atom->x[i][1]);
    mytype.push_back(type[i]);
  }
  tagint maxtag = 0;
  MPI_Allreduce(&maxtag_local, &maxtag, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  const int nprocs = comm->nprocs;
  int n = static_cast<int>(mytag.size());
  std::vector<int> counts(nprocs), displs(nprocs, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  for (int p = 1; p < nprocs; p++) displs[p] = displs[p - 1] + counts[p - 1];
  const int ncell = displs[nprocs - 1] + counts[nprocs - 1];
  if (ncell < 1) error->all(FLERR, "create_vertices: group {} has no atoms", arg[0]);
  std::vector<tagint> alltag(ncell);
  std::vector<int> alltype(ncell);
  MPI_Allgatherv(mytag.data(), n, MPI_LMP_TAGINT, alltag.data(), counts.data(), displs.data(),
                 MPI_LMP_TAGINT, world);
  MPI_Allgatherv(mytype.data(), n, MPI_INT, alltype.data(), counts.data(), displs.data(), MPI_INT,
                 world);
  for (int &c : counts) c *= 2;
  for (int &d : displs) d *= 2;
  std::vector<double> allx(2 * static_cast<size_t>(ncell));
  MPI_Allgatherv(myx.data(), 2 * n, MPI_DOUBLE, allx.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, world);
  std::vector<int> order(ncell);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return alltag[a] < alltag[b];
  });
  std::vector<double> xy(2 * static_cast<size_t>(ncell));
  std::vector<int> t0(ncell);
  std::vector<long> ids(ncell);
  for (int c = 0; c < ncell; c++) {
    xy[2 * c] = allx[2 * order[c]];
    xy[2 * c + 1] = allx[2 * order[c] + 1];
    t0[c] = alltype[order[c]] - 1;
    ids[c] = static_cast<long>(alltag[order[c]]);
  }
  tessera::Box box =
      tessera::Box::rect(domain->boxlo[0], domain->boxhi[0], domain->boxlo[1], domain->boxhi[1]);
  box.xy = domain->triclinic ? domain->xy : 0.0;
  tessera::wrap_into_box(box, xy);
  tessera::VertexTissue tissue;
  try {
    tissue = tessera::vertex_tissue_from_voronoi(box, tessera::Points{xy.data(), ncell, 2},
                                                 t0.data(), ids.data());
  } catch (const tessera::Error &e) {
    error->all(FLERR, "create_vertices: {}", e.what());
  }
  for (int c = 0; c < ncell; c++)
    if (static_cast<int>(tissue.rings[c].size()) > width)
      error->all(FLERR,
                 "create_vertices: the Voronoi polygon of atom {} has {} sides, more than the {} "
                 "columns of i2_vring (use 'maxsides {}' or a wider 'fix vring all property/atom "
                 "i2_vring W')",
                 ids[c], tissue.rings[c].size(), width, tissue.rings[c].size());

  // The vertex atoms inside this rank's sub-domain (over the ghosts, which
  // are dropped as create_atoms drops them).
  if (atom->map_style != 0) atom->map_clear();
  atom->nghost = 0;
  atom->avec->clear_bonus();
  const int nv = tissue.n_vertices();
  const double z = domain->boxlo[2] <= 0.0 && domain->boxhi[2] > 0.0
      ? 0.0
      : 0.5 * (domain->boxlo[2] + domain->boxhi[2]);
  bigint created = 0;
  for (int v = 0; v < nv; v++) {
    double p[3] = {tissue.pos[v].x, tissue.pos[v].y, z};
    domain->remap(p);
    double s[3] = {p[0], p[1], p[2]};
    const double *lo = domain->sublo, *hi = domain->subhi;
    if (domain->triclinic) {
      domain->x2lamda(p, s);
      lo = domain->sublo_lamda;
      hi = domain->subhi_lamda;
    }
    bool mine = true;
    for (int d = 0; d < 2; d++) {
      const bool last = comm->myloc[d] == comm->procgrid[d] - 1;
      const double top = domain->triclinic ? 1.0 : domain->boxhi[d];
      if (!(s[d] >= lo[d] && (s[d] < hi[d] || (last && s[d] == top)))) mine = false;
    }
    if (!mine) continue;
    atom->avec->create_atom(vtype, p);
    const int i = atom->nlocal - 1;
    atom->tag[i] = maxtag + 1 + v;
    for (int k = 0; k < width; k++) atom->iarray[index][i][k] = 0;
    created++;
  }
  bigint all = 0;
  MPI_Allreduce(&created, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (all != nv)
    error->all(FLERR,
               "create_vertices: created {} vertex atoms of {} (some fell between "
               "sub-domains); please report this",
               all, nv);
  atom->natoms += nv;
  if (atom->natoms < 0 || atom->natoms >= MAXBIGINT)
    error->all(FLERR, "create_vertices: too many atoms");
  if (maxtag + nv > MAXTAGINT) error->all(FLERR, "create_vertices: new atom IDs are too large");
  atom->map_init();
  atom->map_set();

  // The rings of the cells this rank owns (the first nlocal atoms).
  std::unordered_map<tagint, int> cell_of;
  for (int c = 0; c < ncell; c++) cell_of[static_cast<tagint>(ids[c])] = c;
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    const std::vector<int> &r = tissue.rings[cell_of[atom->tag[i]]];
    for (int k = 0; k < width; k++)
      atom->iarray[index][i][k] = k < (int) r.size() ? static_cast<int>(maxtag + 1 + r[k]) : 0;
  }
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "create_vertices: {} vertex atoms of type {} for the Voronoi polygons of {} "
                   "cells (group {}); rings in i_vring of fix vring ({} columns)\n",
                   nv, vtype, ncell, arg[0], width);
}
