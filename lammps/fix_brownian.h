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

   fix brownian: overdamped (Brownian) dynamics of point particles, with the
   syntax and semantics of upstream LAMMPS's BROWNIAN package, for a host
   LAMMPS built without that package.  Documentation: doc/fix_brownian.rst.

   The class is called FixBrownianTessera, not FixBrownian, so that it stays
   distinct from upstream's class when the host liblammps.so has one; the
   registration (tessera_styles.cpp) then keeps the host's `fix brownian`.
------------------------------------------------------------------------- */

#ifndef TESSERA_FIX_BROWNIAN_H
#define TESSERA_FIX_BROWNIAN_H

#include "fix.h"

#include <memory>

namespace LAMMPS_NS {

class IntegratorChatter;

class FixBrownianTessera : public Fix {
 public:
  FixBrownianTessera(class LAMMPS *, int, char **);
  ~FixBrownianTessera() override;
  int setmask() override;
  void init() override;
  void initial_integrate(int) override;
  void reset_dt() override;

 protected:
  // Shared with fix brownian/heun (fix_brownian_heun.h), which parses the
  // same arguments and draws the same noise.
  enum Noise { NOISE_UNIFORM, NOISE_GAUSSIAN, NOISE_NONE };

  double temperature;    // T, in temperature units
  int seed;
  double gamma_t;    // translational friction, mass/time
  int noise;         // one of Noise

  double dt;
  double mobility;       // velocity per unit force: ftm2v / gamma_t
  double noise_scale;    // multiplies one random number to give one displacement component
  class RanMars *random;
  std::unique_ptr<IntegratorChatter> chatter;    // warns once when the steps oscillate (period two)

  double parse_number(const char *what, const char *text);
  void set_step();
  template <int NOISE, int THREE_D> void move(double *watch);
};

}    // namespace LAMMPS_NS

#endif
