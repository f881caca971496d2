// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The overdamped (Brownian) position update of fix brownian without noise, as
// a kernel on flat arrays.
#pragma once

namespace tessera {

// One forward Euler step of dr/dt = mobility F in 2D, for each i < n with
// mask[i] & bit (all i when mask is null):
//   dr = drift f_i (x and y, drift = dt mobility),  x_i += dr,  v_i = dr / dt,
//   v_i[2] = 0.
// x, v and f: 3 doubles per atom (LAMMPS's per-atom arrays).  Both components
// at once where the processor has SSE2: the same IEEE operations, so the same
// values bit for bit as overdamped_step_2d_reference.
void overdamped_step_2d(int n, double *x, double *v, const double *f, double drift, double dt,
                        const int *mask, int bit);
void overdamped_step_2d_reference(int n, double *x, double *v, const double *f, double drift,
                                  double dt, const int *mask, int bit);

}  // namespace tessera
