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
FixStyle(polarity,FixPolarity);
// clang-format on
#else

#ifndef LMP_FIX_POLARITY_H
#define LMP_FIX_POLARITY_H

#include "fix.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

// Tessera's types this header names (tessera/polarity.h, tessellation.h):
// declared only, as a LAMMPS style header includes no more than its base
// class; the fix holds the values in Impl (the .cpp).
namespace tessera {
struct Contacts;
struct PolarityParams;
struct Tessellation;
}    // namespace tessera

namespace LAMMPS_NS {

class CoupledDof;

class FixPolarity : public Fix {
 public:
  FixPolarity(class LAMMPS *, int, char **);
  ~FixPolarity() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  void initial_integrate(int) override;
  double compute_vector(int) override;
  void *extract(const char *, int &) override;

 protected:
  double f_active, gamma_r;
  std::string fa_name;    // 'd_name' given for f_a: each cell's own active force
  int fa_index = -1;      // its index in atom->dvector (init)
  double active_force(int i) const;
  struct Impl;
  std::unique_ptr<Impl> impl;
  std::unique_ptr<CoupledDof> coupled_dof;    // what extract(CoupledDof::extract_name) gives
  tessera::PolarityParams &params;
  double d_rot;
  int seed;
  class CellSource *pair;
  std::vector<double> tau, vhat, unit;
  tessera::Tessellation &none;    // an empty tessellation when no neighbours are needed
  std::vector<unsigned char> has_v;
  std::vector<unsigned char> in_group;    // 1 for atoms of the fix group (when it is not all)
  // Cells on a sphere: positions of the owned and ghost atoms at the last
  // force computation (post_force), the state whose tessellation the
  // alignment reads, whatever an integrator defined earlier did since.
  std::vector<double> state_x;
  void record_state_positions();
  const double *state_position(int i) const;
  // The Voronoi neighbours (and, 3d, each cell's surface) of the owned cells
  // at the last force computation, copied then from the pair style's view:
  // the pair style may tessellate again for output after fix deform changed
  // the box at the end of a step, and the next angle update must still use
  // the state whose forces move the cells (fix_polarity.cpp).
  // The pair style's cells at the last force computation (step, count,
  // owned cells): it keeps their neighbour lists for us (force_contacts).
  bigint rec_step = -1, rec_force = -1;
  int rec_n = 0;
  void record_contacts();
  tessera::Contacts recorded_contacts(bigint state_step);

  void init_angles();
  void fresh_angles(int from, int to);    // fresh_angle() of the atoms from..to-1 that need one
  void fresh_angle(int i);                // a random angle for atom i (mu = 0 in the plane)
  void unit_polarities();                 // fills unit (owned and ghost atoms)
  void polar_orders(double &polar, double &nematic);

  // dimension 3: a unit vector per cell (fix_polarity_3d.cpp)
  void init_angles_3d();
  void post_force_3d();
  void initial_integrate_3d();
  void polar_orders_3d(double &polar, double &nematic);
  // Integration by a predictor-corrector integrator (fix brownian/heun, see
  // coupled_dof.h): the angle of each cell is its degree of freedom.
 public:
  // 2d: the angle; 3d: the rotation vector (three components).
  int coupled_size() const;
  void coupled_rate(double *, int, bigint);
  void coupled_noise(double *, int);
  void coupled_advance(const double *, int);
  // For an adaptive step (rejected steps): mu is the state; the noise is
  // sqrt(2 D_r) dW (2d: one angle; 3d: a rotation vector; on a sphere: a
  // rotation about the normal).
  int coupled_state_size() const { return 4; }
  void coupled_save(double *, int);
  void coupled_restore(const double *, int);
  int coupled_wiener_size() const;
  void coupled_wiener_increment(const double *, int, double *, int);

 protected:
  int driven = 0;    // 1: a CoupledIntegrator advances the angles, not initial_integrate
  void find_driver();
  void angle_torques(bigint state_step);
  void rotate(int i, double dth);
  // 3d: the field each polarity turns towards (tau, 3 per atom) at state_step.
  void field_3d(bigint state_step);
  void field_sphere(bigint state_step);    // cells on a sphere: transported neighbours
  template <class Term> void for_each_neighbour(bigint state_step, Term &&term);
  void noise_3d(int i, double scale, bigint step, double *w) const;
  void rotate_3d(int i, const double *w);
};

}    // namespace LAMMPS_NS

#endif
#endif
