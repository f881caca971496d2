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

#ifdef FIX_CLASS
// clang-format off
FixStyle(cell/adapt,FixCellAdapt);
// clang-format on
#else

#ifndef LMP_FIX_CELL_ADAPT_H
#define LMP_FIX_CELL_ADAPT_H

#include "fix.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class FixCellAdapt : public Fix {
 public:
  FixCellAdapt(class LAMMPS *, int, char **);
  ~FixCellAdapt() override;
  int setmask() override;
  void init() override;
  void setup_pre_force(int) override;
  void setup(int) override;
  void end_of_step() override;

  void write_restart(FILE *) override;
  void restart(char *) override;
  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

 protected:
  struct Target {
    std::string name;    // property, without d_
    std::string var;     // atom-style variable, without v_
    int index, ivar;
    bool positive;    // a parameter of the pair style: must be > 0
  };
  std::vector<Target> targets;
  std::vector<double> values;
  class CellSource *pair = nullptr;    // the cells (nullptr: every atom is one)
  bool noted_particles = false;
  bool warned_growth = false;
  // Per atom and target: the value the property held before this fix last
  // set it (NaN: never set), i.e. the value the forces of that step used.
  double **before = nullptr;
  // The step at whose end this fix last set the properties (-1: never).
  bigint applied_step = -1;
  bool foreign = false;    // the restart file's state is for other properties
  double names_key() const;
  // setup_pre_force -> setup: the properties as the last step left them,
  // per owned atom and target, while the setup's forces use `before`.
  std::vector<double> held;
  std::vector<char> restored;
  bool takes(int i) const;
  void apply(bool only_new);
  void check_growth();
};

}    // namespace LAMMPS_NS

#endif
#endif
