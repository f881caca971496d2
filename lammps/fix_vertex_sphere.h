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
FixStyle(VERTEX_VORONOI_SPHERE,FixVertexSphere);
// clang-format on
#else

#ifndef LMP_FIX_VERTEX_SPHERE_H
#define LMP_FIX_VERTEX_SPHERE_H

#include "fix.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairVertexVoronoi;

/* The surface constraint of pair_style vertex/voronoi ... surface sphere, an
   internal fix the pair style adds (style VERTEX_VORONOI_SPHERE, not for
   input scripts).  It puts every owned atom back on the sphere by radial
   projection, c + R (x - c)/|x - c|, and turns its dipole moment (the
   polarity) into the tangent plane there, keeping its length: at the setup
   of a run, after the integrators moved the atoms (post_integrate, before
   ghost atoms are updated) and after atoms were added (pre_exchange, e.g.
   fix cell/divide's daughters).  After a move the polarity is carried from
   the atom's direction at the end of the previous step to its new one by
   parallel transport along the great circle (second-order accurate, where
   a projection onto the new tangent plane would turn it by O(step^2)).
   With a radius given by a variable the cells follow the sphere as it
   grows or shrinks.  During an energy minimisation (minimize) the owned
   atoms are put back on the sphere at its setup and before every force
   evaluation (min_pre_force: the minimisers move them along the tangent
   forces, off the sphere at second order), so the minimum found is on the
   sphere; the geometry uses the owned atoms gathered by the pair style, not
   the ghosts' positions.  The minimisers also see each cell's force
   without its radial part (min_post_force): the cells' own forces are
   tangent, but another sub-style's (particles pressing on the cells) is
   not, and its radial part, which the constraint holds and no step can
   lower, would spoil the line searches (cg, sd: "linesearch alpha is
   zero" far from the minimum) and keep fnorm above any tolerance. */

class FixVertexSphere : public Fix {
 public:
  FixVertexSphere(class LAMMPS *, int, char **);
  int setmask() override;
  void setup_pre_exchange() override { project(false); }
  void pre_exchange() override { project(false); }
  void post_integrate() override { project(true); }
  void min_pre_exchange() override { project(false); }
  void min_pre_force(int) override { project(false); }
  void min_post_force(int) override;
  void setup(int) override
  {
    record();
    check_time();
  }
  void end_of_step() override { record(); }
  PairVertexVoronoi *pair = nullptr;

  static const char *style_name() { return "VERTEX_VORONOI_SPHERE"; }
  static Fix *creator(class LAMMPS *, int, char **);
  // Radial projection of x onto the sphere (c, R) and, when mu is given
  // (4 values, LAMMPS's layout), of mu onto the tangent plane there.
  // With u0 (the unit direction before the move), mu is transported from
  // u0 to the new direction first.
  static void project_one(const double *c, double R, double *x, double *mu,
                          const double *u0 = nullptr);
  // For the error when the sphere of radius R reaches past the box
  // (collective): how the cells and the radius grew since this fix first
  // placed them, and, for each fix cell/divide with an area trigger, that
  // trigger against the cells' area and preferred area.
  std::string growth_note(double R) const;

 private:
  void project(bool transport);
  // Each owned atom's ID and unit direction at the end of the last step
  // (by local index: atoms are not exchanged between then and the move).
  void record();
  std::vector<tagint> tag0;
  std::vector<double> u0;
  // At the first run: a warning when the radius reads LAMMPS's time and
  // that time restarted at 0 (read_restart on LAMMPS 29 Sep 2021).
  void check_time();
  int time_checked = 0;
  // The cell count, radius and step when this fix first placed the cells.
  bigint start_natoms = -1, start_step = 0;
  double start_R = 0.0;
};

}    // namespace LAMMPS_NS

#endif
#endif
