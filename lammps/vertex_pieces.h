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
------------------------------------------------------------------------- */

// Which pieces of a cell's boundary (2d: edges, 3d: faces) are neighbour
// relations: what compute vertex/atom and compute vertex/tissue share.

#ifndef LMP_TESSERA_VERTEX_PIECES_H
#define LMP_TESSERA_VERTEX_PIECES_H

#include "tessera/cells.h"

namespace LAMMPS_NS {
namespace vertex_pieces {

  // A shared piece counts as a neighbour relation if it exceeds this fraction
  // of the cell's mean edge length (2d) or of its surface (3d), so that the
  // zero-length edges and zero-area faces of multifold vertices do not
  // (tessera::CellView::coordination_number).
  constexpr double REL_TOL = 1e-9;

  // The size below which cell c's pieces are no neighbour relation.
  inline double piece_floor(const tessera::CellView &v, int c)
  {
    if (v.dimension() == 3) return REL_TOL * v.boundary(c);
    double mean = 0.0;
    int m = 0;
    for (int k = v.piece_begin(c); k < v.piece_end(c); k++)
      if (v.piece_neighbor(k) >= 0) {
        mean += v.piece_size(k);
        m++;
      }
    return m ? REL_TOL * mean / m : 0.0;
  }

}    // namespace vertex_pieces
}    // namespace LAMMPS_NS

#endif
