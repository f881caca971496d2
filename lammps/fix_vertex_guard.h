/* -*- c++ -*- ----------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(VERTEX_VORONOI_GUARD,FixVertexGuard);
// clang-format on
#else

#ifndef LMP_FIX_VERTEX_GUARD_H
#define LMP_FIX_VERTEX_GUARD_H

#include "fix.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairVertexVoronoi;

/* The step guard of pair_style vertex/voronoi, an internal fix the pair style
   adds (style VERTEX_VORONOI_GUARD, not for input scripts).  It keeps each
   owned atom's position from the last force computation and, after the
   integrators have moved the atoms (post_integrate, before atoms migrate),
   compares, in every dimension of the run.  A step that moves an atom by more
   than a cell diameter does not resolve the forces: a warning, once per run.
   A step that moves it so far that LAMMPS would lose it, or to a non-finite
   position, stops the run with an error.  Integrator-independent.
   It also gives atoms made during a run (fix deposit, fix pour) or by
   create_atoms their type's values in the per-cell properties d_area0,
   d_ka, d_kp and d_perim0, which LAMMPS would leave holding whatever the
   memory held (often a ghost atom's value). */

class FixVertexGuard : public Fix {
 public:
  FixVertexGuard(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override { record(); }
  // The positions of the step's last force computation, once the step is
  // complete (not at post_force: fix brownian/heun computes forces twice
  // per step, the first time at its predicted positions).
  void end_of_step() override { record(); }
  void post_integrate() override;
  void set_arrays(int) override;
  PairVertexVoronoi *pair = nullptr;

  // The style name, and the function that makes one (for the pair style,
  // which registers the style on first use).
  static const char *style_name() { return "VERTEX_VORONOI_GUARD"; }
  static Fix *creator(class LAMMPS *, int, char **);

 private:
  std::vector<double> x0;    // dim values per owned atom
  std::vector<tagint> tag0;
  std::vector<double> size2;    // per type: the squared warning limit
  bigint step0 = -1;
  int warned = 0;
  int dim = 2;
  void record();
  double loss_limit() const;
  std::string describe(int i, double moved, double size) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
