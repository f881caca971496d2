/* -*- c++ -*- ----------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later
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
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;

 protected:
  struct Target {
    std::string name;    // property, without d_
    std::string var;     // atom-style variable, without v_
    int index, ivar;
    bool positive;    // a parameter of the pair style: must be > 0
  };
  std::vector<Target> targets;
  std::vector<double> values;
  void apply();
};

}    // namespace LAMMPS_NS

#endif
#endif
