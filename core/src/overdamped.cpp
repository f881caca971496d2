// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later

#include "tessera/overdamped.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

void overdamped_step_2d_reference(int n, double *x, double *v, const double *f, double drift,
                                  double dt, const int *mask, int bit, double *watch) {
  double dot = 0.0, old2 = 0.0, new2 = 0.0, count = 0.0;
  for (int i = 0; i < n; ++i) {
    if (mask && !(mask[i] & bit)) continue;
    for (int d = 0; d < 2; ++d) {
      const long k = 3 * static_cast<long>(i) + d;
      const double dr = drift * f[k];
      const double before = v[k];
      x[k] += dr;
      v[k] = dr / dt;
      dot += before * v[k];
      old2 += before * before;
      new2 += v[k] * v[k];
    }
    v[3 * static_cast<long>(i) + 2] = 0.0;
    count += 1.0;
  }
  if (watch) {
    watch[0] += dot;
    watch[1] += old2;
    watch[2] += new2;
    watch[3] += count;
  }
}

void overdamped_step_2d(int n, double *x, double *v, const double *f, double drift, double dt,
                        const int *mask, int bit, double *watch) {
#if defined(__SSE2__)
  const __m128d a = _mm_set1_pd(drift), b = _mm_set1_pd(dt);
  if (!watch) {
    for (int i = 0; i < n; ++i) {
      if (mask && !(mask[i] & bit)) continue;
      const long k = 3 * static_cast<long>(i);
      const __m128d dr = _mm_mul_pd(a, _mm_loadu_pd(f + k));
      _mm_storeu_pd(x + k, _mm_add_pd(_mm_loadu_pd(x + k), dr));
      _mm_storeu_pd(v + k, _mm_div_pd(dr, b));
      v[k + 2] = 0.0;
    }
    return;
  }
  // The sums per component (one lane each), added up at the end.
  __m128d dot = _mm_setzero_pd(), old2 = dot, new2 = dot;
  int skipped = 0;
  for (int i = 0; i < n; ++i) {
    if (mask && !(mask[i] & bit)) {
      ++skipped;
      continue;
    }
    const long k = 3 * static_cast<long>(i);
    const __m128d dr = _mm_mul_pd(a, _mm_loadu_pd(f + k));
    const __m128d before = _mm_loadu_pd(v + k);
    const __m128d after = _mm_div_pd(dr, b);
    _mm_storeu_pd(x + k, _mm_add_pd(_mm_loadu_pd(x + k), dr));
    _mm_storeu_pd(v + k, after);
    v[k + 2] = 0.0;
    dot = _mm_add_pd(dot, _mm_mul_pd(before, after));
    old2 = _mm_add_pd(old2, _mm_mul_pd(before, before));
    new2 = _mm_add_pd(new2, _mm_mul_pd(after, after));
  }
  double s[6];
  _mm_storeu_pd(s, dot);
  _mm_storeu_pd(s + 2, old2);
  _mm_storeu_pd(s + 4, new2);
  watch[0] += s[0] + s[1];
  watch[1] += s[2] + s[3];
  watch[2] += s[4] + s[5];
  watch[3] += n > 0 ? n - skipped : 0;
#else
  overdamped_step_2d_reference(n, x, v, f, drift, dt, mask, bit, watch);
#endif
}

}  // namespace tessera
