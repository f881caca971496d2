/* -*- c++ -*- ----------------------------------------------------------
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

   The junction-weighted mean of a per-atom value over a cell's neighbours,
   shared by compute cell/neighbor/mean and fix cell/signal (Hill inputs
   'mean d_name'):  <u>_i = sum_j s_ij u_j / sum_j s_ij  over the pieces of
   owned cell i shared with a neighbour j in the group (s_ij: the junction's
   length in 2d and on the sphere, the face area in 3d).  A neighbour seen
   across several pieces (a cell touching its periodic image, a 3d cell
   with two faces on one neighbour) counts with the sum of their sizes.
   Returns 0 for a cell with no neighbour in the group.
------------------------------------------------------------------------- */

#ifndef LMP_TESSERA_JUNCTION_MEAN_H
#define LMP_TESSERA_JUNCTION_MEAN_H

#include "tessera/cells.h"

namespace LAMMPS_NS {

inline double junction_mean(const tessera::CellView &v, int i, const double *value, const int *mask,
                            int groupbit)
{
  double sum = 0.0, weight = 0.0;
  for (int k = v.piece_begin(i); k < v.piece_end(i); k++) {
    const int j = v.piece_neighbor(k);
    if (j < 0 || !(mask[j] & groupbit)) continue;
    const double s = v.piece_size(k);
    sum += s * value[j];
    weight += s;
  }
  return weight > 0.0 ? sum / weight : 0.0;
}

}    // namespace LAMMPS_NS

#endif
