/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   compute vertex/atom in 'dimension 3': the same 7 columns for the 3D cells
   of pair_style vertex/voronoi (volume, surface, s = S/V^(2/3), number of
   faces, energy, coordination, orientation) and the global vector.
------------------------------------------------------------------------- */

#include "compute_vertex_atom.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "memory.h"
#include "pair_vertex_voronoi.h"
#include "update.h"

#include "tessera/voronoi3d.h"

#include <algorithm>
#include <cmath>

using namespace LAMMPS_NS;

namespace {

// A face counts as a neighbour relation if its area exceeds this fraction of
// the cell's surface (co-spherical centres give faces of area exactly 0).
constexpr double REL_TOL_3D = 1e-9;

}    // namespace

void ComputeVertexAtom::compute_peratom_3d()
{
  if (atom->nmax > nmax) {
    memory->destroy(values);
    nmax = atom->nmax;
    memory->create(values, nmax, 7, "vertex/atom:values");
    array_atom = values;
  }
  communicate_velocities();
  const tessera::Tessellation3 &t = pair->tessellation3();
  const std::vector<double> &energy = pair->cell_energy();
  const int *mask = atom->mask;
  auto unit = [&](int i, double u[3]) {
    const double *v = &vel[3 * static_cast<size_t>(i)];
    const double s = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(s > 0.0)) return false;
    for (int d = 0; d < 3; d++) u[d] = v[d] / s;
    return true;
  };
  for (int i = 0; i < atom->nlocal; i++) {
    double *row = values[i];
    for (int k = 0; k < 7; k++) row[k] = 0.0;
    if (!(mask[i] & groupbit)) continue;
    row[0] = t.volume[i];
    row[1] = t.surface[i];
    row[2] = t.volume[i] > 0.0 ? t.shape_index(i) : 0.0;
    row[3] = t.face_count(i, REL_TOL_3D);
    row[4] = energy[i];
    double ui[3], uj[3];
    if (!unit(i, ui)) {
      row[6] = -1.0;
      continue;
    }
    row[6] = std::acos(std::max(-1.0, std::min(1.0, ui[0])));
    double sum = 0.0;
    int count = 0;
    for (int f = t.cell_offset[i]; f < t.cell_offset[i + 1]; f++)
      if (t.face_area[f] > REL_TOL_3D * t.surface[i] && unit(t.face_neighbor[f], uj)) {
        sum += ui[0] * uj[0] + ui[1] * uj[1] + ui[2] * uj[2];
        count++;
      }
    row[5] = count ? sum / count : 0.0;
  }
}

/* Global vector in 3d: mean s; the number of pairs of group cells whose
   Delaunay edge has a Voronoi face of zero area (they touch at a vertex
   shared by more than four cells: co-spherical centres), each pair counted
   once by the owner of the lower ID; neighbour exchanges since the last
   call (pairs of cells that share a face of non-zero area now but did not). */

void ComputeVertexAtom::compute_vector_3d()
{
  const tessera::Tessellation3 &t = pair->tessellation3();
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  double local[3] = {0.0, 0.0, 0.0}, all[3];
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit) || !(t.volume[i] > 0.0)) continue;
    local[0] += t.shape_index(i);
    local[1] += 1.0;
    for (int f = t.cell_offset[i]; f < t.cell_offset[i + 1]; f++) {
      const int j = t.face_neighbor[f];
      if (!(t.face_area[f] > REL_TOL_3D * t.surface[i]) && (mask[j] & groupbit) && tag[j] > tag[i])
        local[2] += 1.0;
    }
  }
  MPI_Allreduce(local, all, 3, MPI_DOUBLE, MPI_SUM, world);
  vector[0] = all[1] > 0.0 ? all[0] / all[1] : 0.0;
  vector[1] = all[2];
  vector[2] = count_new_neighbors();
}

void ComputeVertexAtom::neighbor_tags_3d(int c, std::vector<tagint> &out)
{
  const tessera::Tessellation3 &t = pair->tessellation3();
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  out.clear();
  for (int f = t.cell_offset[c]; f < t.cell_offset[c + 1]; f++) {
    if (!(t.face_area[f] > REL_TOL_3D * t.surface[c])) continue;
    const int j = t.face_neighbor[f];
    if ((mask[j] & groupbit) && tag[j] > tag[c]) out.push_back(tag[j]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}
