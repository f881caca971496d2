// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Polarity dynamics and velocity observables (doc/model.md, Dynamics and Observables).
#pragma once

#include "tessera/tessellation.h"

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
void polarity_torque(const Tessellation &t, const double *theta, const PolarityParams &p,
                     const double *psi, const unsigned char *has_psi, double *tau);

// The same torque from unit polarity vectors n (stride n_stride, for every
// point of t) instead of angles, without trigonometric functions:
//   sin(th_j - th_i) = n_i x n_j, sin(th - phi) cos(th - phi) = s' c' with
//   (c', s') = n rotated by -phi, sin(th_i - psi_i) = vhat_i x n_i.
// vhat (optional, stride 2, n_owned entries) is the unit velocity; has_v[i]
// == 0 where the velocity is zero.
void polarity_torque_vec(const Tessellation &t, const double *n, int n_stride,
                         const PolarityParams &p, const double *vhat, const unsigned char *has_v,
                         double *tau);

// Coordination C_i = mean over Voronoi neighbours j (non-zero edges) of
// v_i/|v_i| . v_j/|v_j| (in [-1, 1]), and orientation O_i = arccos(v_i/|v_i| . x)
// in [0, pi].  vel: stride-2 velocities of all points of t.  Cells with zero
// velocity get coordination 0 and orientation -1 (a value outside [0, pi], so
// dumps show it and averages are not poisoned by NaN); neighbours with zero
// velocity are left out of the mean.
void velocity_observables(const Tessellation &t, const double *vel, int vel_stride,
                          double *coordination, double *orientation);

}  // namespace tessera
