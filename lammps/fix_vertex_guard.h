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
  void setup(int) override
  {
    defer_ok = false;
    record();
  }
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

  // The owned atoms the last move put past a fixed ('f') boundary on this
  // rank (LAMMPS drops them at the next exchange): how many, and of the
  // lowest ID, the ID, the dimension and side (0 lower, 1 upper), its
  // coordinate there and the boundary's; the step (-1: none).  For the
  // lost-atom message.
  struct Left {
    bigint step = -1;
    int count = 0;
    tagint tag = 0;
    int dim = 0, side = 0;
    double x = 0.0, bound = 0.0;
  };
  const Left &left_box() const { return left; }
  static Fix *creator(class LAMMPS *, int, char **);

 private:
  std::vector<double> x0;    // dim values per owned atom
  std::vector<tagint> tag0;
  std::vector<double> size2;    // per type: the squared warning limit
  bigint step0 = -1;
  int warned = 0;
  int dim = 2;
  // The neighbourhood of each owned cell at the step's last force
  // computation, from the cells it computed (record()): what the messages
  // name as the cause.  By local index, like x0.
  struct Around {
    tagint near_tag = 0;
    double near_d = -1.0;     // closest Voronoi neighbour's distance (-1: none)
    double measure = -1.0;    // area (3d: volume; -1: no cell)
    double boundary = 0.0;    // perimeter (3d: surface)
    double force = 0.0;       // |f| then
  };
  std::vector<Around> around;
  Left left;
  void note_left_box();
  std::vector<int> nb_offset;    // owned atom i's neighbours' IDs are
  std::vector<tagint> nb_tag;    // nb_tag[nb_offset[i] .. nb_offset[i+1])
  // The pair style's compute_count() at the last record; whether that
  // record left the neighbourhood to be found when needed, and whether the
  // last step showed that this is safe (no force computation between the
  // end of a step and the next check).
  bigint recorded_count = -1;
  bool deferred = false, defer_ok = false;
  void record();
  // moved: the owned atoms have moved since the cells were computed (their
  // recorded positions are used).
  void record_neighbourhood(bool moved = false);
  void ensure_neighbourhood();
  double loss_limit() const;
  // The message's text for owned atom i of rank root (collective: every
  // rank calls it, and gets the text).
  std::string describe_all(int root, int i, double moved);
  // A cell's state for the messages: its excess over its preferred area or
  // perimeter, and the numbers.
  struct State {
    double excess = -1.0;    // >= 1: far above (see state_of; -1: unknown)
    double A = 0.0, A0 = 0.0, P = 0.0, P0 = 0.0;
    tagint tag = 0;
  };
  State state_of(int i, const double *typical) const;
  // The closest pair of neighbours among all cells at the last record (d <
  // 0: none), set by describe_all() for describe().
  struct {
    double d = -1.0;
    tagint a = 0, b = 0;
  } closest;
  // worst: the cell around i that exceeds its preferred values most;
  // ratio: the largest A/A0 (-1: none known) and P - P0 (-HUGE_VAL) around
  // i; typical: the tissue's mean A/A0 and P - P0, and the count of cells.
  std::string describe(int i, double moved, double size, const State &worst, const double *ratio,
                       const double *typical) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
