// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Polarity dynamics and velocity observables (doc/model.md, Dynamics and Observables).
#pragma once

#include "tessera/cells.h"
#include "tessera/tessellation.h"

#include <cmath>

namespace tessera {

struct PolarityParams {
  double J_S = 0.0;    // alignment with Voronoi neighbours
  double J_G = 0.0;    // nematic alignment with a groove direction
  double phi_G = 0.0;  // groove direction (radians from x)
  double J_V = 0.0;    // alignment with the cell's own velocity
};

// Deterministic torque on each owned cell's polarity angle:
//   tau_i = J_S sum_j sin(th_j - th_i) - J_G sin(th_i - phi) cos(th_i - phi)
//           - J_V sin(th_i - psi_i)
// Sum over Voronoi neighbours with non-zero edge length.  theta holds an angle
// for every point of t (owned and ghost); psi (optional, n_owned entries) is
// the direction of each owned cell's velocity, with has_psi[i] == 0 where the
// velocity is zero (no velocity torque then).  tau gets n_owned values.
void polarity_torque(const Contacts &t, const double *theta, const PolarityParams &p,
                     const double *psi, const unsigned char *has_psi, double *tau);

// The same torque from unit polarity vectors n (stride n_stride, for every
// point of t) instead of angles, without trigonometric functions:
//   sin(th_j - th_i) = n_i x n_j, sin(th - phi) cos(th - phi) = s' c' with
//   (c', s') = n rotated by -phi, sin(th_i - psi_i) = vhat_i x n_i.
// vhat (optional, stride 2, n_owned entries) is the unit velocity; has_v[i]
// == 0 where the velocity is zero.
void polarity_torque_vec(const Contacts &t, const double *n, int n_stride,
                         const PolarityParams &p, const double *vhat, const unsigned char *has_v,
                         double *tau);

// The same torque by the plain loop (any stride): the oracle of the fast path
// above, which takes stride 2 and sums the neighbours two components at a time
// (the same additions in the same order, so the same values bit for bit).
void polarity_torque_vec_reference(const Contacts &t, const double *n, int n_stride,
                                   const PolarityParams &p, const double *vhat,
                                   const unsigned char *has_v, double *tau);

// sin and cos of a small rotation angle by their Taylor series (exact to
// double precision for |x| < 0.25, the usual size of one step's turn),
// std::sin and std::cos otherwise.
inline void sincos_small(double x, double &s, double &c) {
  if (std::fabs(x) < 0.25) {
    const double x2 = x * x;
    s = x * (1.0 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880 +
                                                                             x2 * (-1.0 / 39916800))))));
    c = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320 +
                                                                  x2 * (-1.0 / 3628800 + x2 / 479001600)))));
  } else {
    s = std::sin(x);
    c = std::cos(x);
  }
}

// 1 / std::sqrt(q), bit for bit, from a table of those values for the q
// within 64 units in the last place of 1 (the squared length of a rotated
// unit vector, nearly always), computed otherwise.
double inverse_sqrt(double q);

// One rotation step of 2D polarities stored as dipole moments mu (stride 4:
// mu_x, mu_y, mu_z, |mu|, as LAMMPS's atom_style dipole keeps them): for each
// i < n with active[i] != 0 (all i when active is null), the unit vector
// u_i = (u[2i], u[2i+1]) turned by the angle dth[i] (sincos_small) and
// renormalised, times m = |mu_i| (1 where |mu_i| <= 0):
//   mu_i <- (m r_x / |r|, m r_y / |r|, 0, m),  r = R(dth_i) u_i.
// Inactive entries are not written (their dth may be anything).  Two cells at
// a time where the processor has SSE2, 1/|r| by inverse_sqrt (the same IEEE
// operations per cell or their tabulated results, so the same values bit for
// bit as rotate_polarities_reference).
void rotate_polarities(int n, const double *u, const double *dth, double *mu,
                       const unsigned char *active);
void rotate_polarities_reference(int n, const double *u, const double *dth, double *mu,
                                 const unsigned char *active);

// Coordination C_i = mean over Voronoi neighbours j (non-zero edges) of
// v_i/|v_i| . v_j/|v_j| (in [-1, 1]), and orientation O_i = arccos(v_i/|v_i| . x)
// in [0, pi].  vel: stride-2 velocities of all points of t.  Cells with zero
// velocity get coordination 0 and orientation -1 (a value outside [0, pi], so
// dumps show it and averages are not poisoned by NaN); neighbours with zero
// velocity are left out of the mean.
void velocity_observables(const Contacts &t, const double *vel, int vel_stride,
                          double *coordination, double *orientation);

// The same functions on a confluent tessellation's neighbour lists.
inline Contacts contacts_of(const Tessellation &t) {
  Contacts c;
  c.n_owned = t.n_owned;
  c.offset = t.cell_offset.data();
  c.neighbor = t.cell_neighbor.data();
  c.size = t.edge_length.data();
  return c;
}
inline void polarity_torque(const Tessellation &t, const double *theta, const PolarityParams &p,
                            const double *psi, const unsigned char *has_psi, double *tau) {
  polarity_torque(contacts_of(t), theta, p, psi, has_psi, tau);
}
inline void polarity_torque_vec(const Tessellation &t, const double *n, int n_stride,
                                const PolarityParams &p, const double *vhat,
                                const unsigned char *has_v, double *tau) {
  polarity_torque_vec(contacts_of(t), n, n_stride, p, vhat, has_v, tau);
}
inline void polarity_torque_vec_reference(const Tessellation &t, const double *n, int n_stride,
                                          const PolarityParams &p, const double *vhat,
                                          const unsigned char *has_v, double *tau) {
  polarity_torque_vec_reference(contacts_of(t), n, n_stride, p, vhat, has_v, tau);
}
inline void velocity_observables(const Tessellation &t, const double *vel, int vel_stride,
                                 double *coordination, double *orientation) {
  velocity_observables(contacts_of(t), vel, vel_stride, coordination, orientation);
}

}  // namespace tessera
