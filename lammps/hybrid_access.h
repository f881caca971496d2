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

   What pair_style hybrid (and hybrid/overlay, hybrid/scaled) holds: its
   sub-styles and which of them a type pair is given to.  LAMMPS keeps these
   protected; a pointer to member formed in a derived class reaches them
   without an instance of that class.  Included by .cpp files only.
------------------------------------------------------------------------- */

#ifndef LMP_TESSERA_HYBRID_ACCESS_H
#define LMP_TESSERA_HYBRID_ACCESS_H

#include "pair_hybrid.h"

namespace LAMMPS_NS {

struct HybridAccess : PairHybrid {
  static int count(PairHybrid *h) { return h->*(&HybridAccess::nstyles); }
  static Pair *style(PairHybrid *h, int m) { return (h->*(&HybridAccess::styles))[m]; }
  static const char *keyword(PairHybrid *h, int m) { return (h->*(&HybridAccess::keywords))[m]; }
  // Whether type pair (i, j) is given to sub-style m (as pair_coeff set it;
  // pairs left to mixing are resolved later, at init_one).
  static bool gives(PairHybrid *h, int i, int j, int m)
  {
    int **nmap = h->*(&HybridAccess::nmap);
    int ***map = h->*(&HybridAccess::map);
    for (int k = 0; k < nmap[i][j]; k++)
      if (map[i][j][k] == m) return true;
    return false;
  }
};

}    // namespace LAMMPS_NS

#endif
