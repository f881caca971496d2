/* -*- c++ -*- ----------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(VERTEX_VORONOI_SPHERE,FixVertexSphere);
// clang-format on
#else

#ifndef LMP_FIX_VERTEX_SPHERE_H
#define LMP_FIX_VERTEX_SPHERE_H

#include "fix.h"

namespace LAMMPS_NS {

class PairVertexVoronoi;

/* The surface constraint of pair_style vertex/voronoi ... surface sphere, an
   internal fix the pair style adds (style VERTEX_VORONOI_SPHERE, not for
   input scripts).  It puts every owned atom back on the sphere by radial
   projection, c + R (x - c)/|x - c|, and turns its dipole moment (the
   polarity) into the tangent plane there, keeping its length: at the setup
   of a run, after the integrators moved the atoms (post_integrate, before
   ghost atoms are updated) and after atoms were added (pre_exchange, e.g.
   fix cell/divide's daughters).  With a radius given by a variable the
   cells follow the sphere as it grows or shrinks. */

class FixVertexSphere : public Fix {
 public:
  FixVertexSphere(class LAMMPS *, int, char **);
  int setmask() override;
  void setup_pre_exchange() override { project(); }
  void pre_exchange() override { project(); }
  void post_integrate() override { project(); }
  PairVertexVoronoi *pair = nullptr;

  static const char *style_name() { return "VERTEX_VORONOI_SPHERE"; }
  static Fix *creator(class LAMMPS *, int, char **);
  // Radial projection of x onto the sphere (c, R) and, when mu is given
  // (4 values, LAMMPS's layout), of mu onto the tangent plane there.
  static void project_one(const double *c, double R, double *x, double *mu);

 private:
  void project();
};

}    // namespace LAMMPS_NS

#endif
#endif
