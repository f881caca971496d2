// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later

#include "tessera/overdamped.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

void overdamped_step_2d_reference(int n, double *x, double *v, const double *f, double drift,
                                  double dt, const int *mask, int bit) {
  for (int i = 0; i < n; ++i) {
    if (mask && !(mask[i] & bit)) continue;
    for (int d = 0; d < 2; ++d) {
      const double dr = drift * f[3 * static_cast<long>(i) + d];
      x[3 * static_cast<long>(i) + d] += dr;
      v[3 * static_cast<long>(i) + d] = dr / dt;
    }
    v[3 * static_cast<long>(i) + 2] = 0.0;
  }
}

void overdamped_step_2d(int n, double *x, double *v, const double *f, double drift, double dt,
                        const int *mask, int bit) {
#if defined(__SSE2__)
  const __m128d a = _mm_set1_pd(drift), b = _mm_set1_pd(dt);
  for (int i = 0; i < n; ++i) {
    if (mask && !(mask[i] & bit)) continue;
    const long k = 3 * static_cast<long>(i);
    const __m128d dr = _mm_mul_pd(a, _mm_loadu_pd(f + k));
    _mm_storeu_pd(x + k, _mm_add_pd(_mm_loadu_pd(x + k), dr));
    _mm_storeu_pd(v + k, _mm_div_pd(dr, b));
    v[k + 2] = 0.0;
  }
#else
  overdamped_step_2d_reference(n, x, v, f, drift, dt, mask, bit);
#endif
}

}  // namespace tessera
