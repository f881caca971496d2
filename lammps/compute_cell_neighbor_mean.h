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

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(cell/neighbor/mean,ComputeCellNeighborMean);
// clang-format on
#else

#ifndef LMP_COMPUTE_CELL_NEIGHBOR_MEAN_H
#define LMP_COMPUTE_CELL_NEIGHBOR_MEAN_H

#include "compute.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class ComputeCellNeighborMean : public Compute {
 public:
  ComputeCellNeighborMean(class LAMMPS *, int, char **);
  ~ComputeCellNeighborMean() override;
  void init() override;
  void compute_peratom() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double memory_usage() override;

 protected:
  enum Kind { DNAME, COMPUTE, FIX, VARIABLE };
  struct Input {
    std::string text;    // as given (d_name, c_ID, c_ID[I], f_ID, f_ID[I], v_name)
    int kind;
    std::string name;
    int column;    // 0: a per-atom vector; I >= 1: column I of a per-atom array
    int index;     // dvector index, or the compute, fix or variable index
  };
  std::vector<Input> inputs;
  int nmax;
  double *vout;
  double **aout;
  std::vector<double> work;    // one input's values on owned and ghost atoms
  class CellSource *pair;

  void resolve(Input &);
  void owned_values(Input &, double *);
};

}    // namespace LAMMPS_NS

#endif
#endif
