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
//
// With watch given, the same pass also adds to watch[0..3], over the atoms
// it moves (x and y), the sums that the integrators' chatter watch compares
// from step to step (fix brownian): sum v_old . v_new, sum |v_old|^2,
// sum |v_new|^2 and the number of atoms, v_old being v before the step
// (the previous step's displacement over dt).  The sums are the same up to
// their order of summation in both versions.
void overdamped_step_2d(int n, double *x, double *v, const double *f, double drift, double dt,
                        const int *mask, int bit, double *watch = nullptr);
void overdamped_step_2d_reference(int n, double *x, double *v, const double *f, double drift,
                                  double dt, const int *mask, int bit, double *watch = nullptr);

}  // namespace tessera
