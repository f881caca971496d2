// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later

#include "tessera/polarity.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tessera {

void polarity_torque(const Contacts &t, const double *theta, const PolarityParams &p,
                     const double *psi, const unsigned char *has_psi, double *tau) {
  for (int c = 0; c < t.n_owned; ++c) {
    const double th = theta[c];
    double neighbours = 0.0;
    if (p.J_S != 0.0) {
      for (int k = t.offset[c]; k < t.offset[c + 1]; ++k)
        if (t.size[k] > 0.0) neighbours += std::sin(theta[t.neighbor[k]] - th);
    }
    const double dg = th - p.phi_G;
    double v = p.J_S * neighbours - p.J_G * std::sin(dg) * std::cos(dg);
    if (p.J_V != 0.0 && psi && (!has_psi || has_psi[c])) v -= p.J_V * std::sin(th - psi[c]);
    tau[c] = v;
  }
}

void polarity_torque_vec_reference(const Contacts &t, const double *n, int n_stride,
                                   const PolarityParams &p, const double *vhat,
                                   const unsigned char *has_v, double *tau) {
  const double cphi = std::cos(p.phi_G), sphi = std::sin(p.phi_G);
  for (int c = 0; c < t.n_owned; ++c) {
    const double nx = n[static_cast<long>(c) * n_stride], ny = n[static_cast<long>(c) * n_stride + 1];
    double cross = 0.0;
    if (p.J_S != 0.0) {
      double sx = 0.0, sy = 0.0;  // sum of the neighbours' polarities
      for (int k = t.offset[c]; k < t.offset[c + 1]; ++k) {
        if (!(t.size[k] > 0.0)) continue;
        const long j = static_cast<long>(t.neighbor[k]) * n_stride;
        sx += n[j];
        sy += n[j + 1];
      }
      cross = nx * sy - ny * sx;
    }
    const double cg = nx * cphi + ny * sphi, sg = ny * cphi - nx * sphi;
    double v = p.J_S * cross - p.J_G * sg * cg;
    if (p.J_V != 0.0 && vhat && (!has_v || has_v[c]))
      v -= p.J_V * (vhat[2 * c] * ny - vhat[2 * c + 1] * nx);
    tau[c] = v;
  }
}

// Fast path of polarity_torque_vec for stride 2 with SSE2: (sx, sy) in one
// register, a neighbour behind a zero-length edge adds +0.0 instead of being
// skipped (no branch).  That is the same value: the sums start at +0.0 and
// round-to-nearest never produces -0.0 from a sum with a +0.0 term, so adding
// +0.0 leaves every partial sum unchanged.
void polarity_torque_vec(const Contacts &t, const double *n, int n_stride,
                         const PolarityParams &p, const double *vhat, const unsigned char *has_v,
                         double *tau) {
#if defined(__SSE2__)
  if (n_stride == 2 && p.J_S != 0.0) {
    const double cphi = std::cos(p.phi_G), sphi = std::sin(p.phi_G);
    const int *offset = t.offset;
    const int *nbr = t.neighbor;
    const double *len = t.size;
    const __m128d zero = _mm_setzero_pd();
    const bool use_v = p.J_V != 0.0 && vhat;
    for (int c = 0; c < t.n_owned; ++c) {
      __m128d sum = _mm_setzero_pd();  // (sx, sy)
      for (int k = offset[c]; k < offset[c + 1]; ++k) {
        const __m128d keep = _mm_cmpgt_pd(_mm_set1_pd(len[k]), zero);  // all ones where > 0
        const __m128d nj = _mm_loadu_pd(n + 2 * static_cast<long>(nbr[k]));
        sum = _mm_add_pd(sum, _mm_and_pd(keep, nj));
      }
      const double sx = _mm_cvtsd_f64(sum), sy = _mm_cvtsd_f64(_mm_unpackhi_pd(sum, sum));
      const double nx = n[2 * static_cast<long>(c)], ny = n[2 * static_cast<long>(c) + 1];
      const double cross = nx * sy - ny * sx;
      const double cg = nx * cphi + ny * sphi, sg = ny * cphi - nx * sphi;
      double v = p.J_S * cross - p.J_G * sg * cg;
      if (use_v && (!has_v || has_v[c])) v -= p.J_V * (vhat[2 * c] * ny - vhat[2 * c + 1] * nx);
      tau[c] = v;
    }
    return;
  }
#endif
  polarity_torque_vec_reference(t, n, n_stride, p, vhat, has_v, tau);
}

namespace {

// 1 / sqrt(q) for the 2 H doubles next to 1 (bit patterns of 1.0 - H ...
// 1.0 + H - 1), computed once by the same two IEEE operations.
constexpr int64_t kInvSqrtHalf = 64;
constexpr uint64_t kOneBits = 0x3ff0000000000000ULL;

struct InverseSqrtTable {
  double r[2 * kInvSqrtHalf];
  InverseSqrtTable() {
    for (int64_t k = -kInvSqrtHalf; k < kInvSqrtHalf; ++k) {
      const uint64_t b = kOneBits + static_cast<uint64_t>(k);
      double q;
      std::memcpy(&q, &b, sizeof q);
      r[k + kInvSqrtHalf] = 1.0 / std::sqrt(q);
    }
  }
};
const InverseSqrtTable inverse_sqrt_table;

}  // namespace

double inverse_sqrt(double q) {
  uint64_t b;
  std::memcpy(&b, &q, sizeof b);
  const uint64_t k = b - kOneBits + static_cast<uint64_t>(kInvSqrtHalf);  // wraps if q < 1 - H ulp
  if (k < static_cast<uint64_t>(2 * kInvSqrtHalf)) return inverse_sqrt_table.r[k];
  return 1.0 / std::sqrt(q);
}

void rotate_polarities_reference(int n, const double *u, const double *dth, double *mu,
                                 const unsigned char *active) {
  for (int i = 0; i < n; ++i) {
    if (active && !active[i]) continue;
    double s, c;
    sincos_small(dth[i], s, c);
    double *m_i = mu + 4 * static_cast<long>(i);
    const double m = m_i[3] > 0.0 ? m_i[3] : 1.0;
    const double nx = u[2 * static_cast<long>(i)], ny = u[2 * static_cast<long>(i) + 1];
    // Renormalise so that round-off in the rotations does not drift |mu|.
    const double rx = c * nx - s * ny, ry = s * nx + c * ny;
    const double r = 1.0 / std::sqrt(rx * rx + ry * ry);
    m_i[0] = m * rx * r;
    m_i[1] = m * ry * r;
    m_i[2] = 0.0;
    m_i[3] = m;
  }
}

// Two cells per iteration, lane 0 = cell i, lane 1 = cell i + 1: the Taylor
// polynomials of sincos_small (the same constants and order of operations),
// with std::sin/std::cos for a lane whose |dth| >= 0.25 (or NaN), the
// rotation, and 1/|r| by inverse_sqrt (on this class of processors sqrt and
// division were half the cost of the step).
void rotate_polarities(int n, const double *u, const double *dth, double *mu,
                       const unsigned char *active) {
  int i = 0;
#if defined(__SSE2__)
  const __m128d quarter = _mm_set1_pd(0.25);
  const __m128d absmask = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
  const __m128d one = _mm_set1_pd(1.0), zero = _mm_setzero_pd();
  for (; i + 1 < n; i += 2) {
    const bool act0 = !active || active[i], act1 = !active || active[i + 1];
    if (!act0 && !act1) continue;
    const __m128d x = _mm_loadu_pd(dth + i);
    const __m128d x2 = _mm_mul_pd(x, x);
    // s = x (1 + x2 (-1/6 + x2 (1/120 + x2 (-1/5040 + x2 (1/362880 + x2 (-1/39916800))))))
    __m128d ps = _mm_mul_pd(x2, _mm_set1_pd(-1.0 / 39916800));
    ps = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(1.0 / 362880), ps));
    ps = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(-1.0 / 5040), ps));
    ps = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(1.0 / 120), ps));
    ps = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(-1.0 / 6), ps));
    __m128d sv = _mm_mul_pd(x, _mm_add_pd(one, ps));
    // c = 1 + x2 (-1/2 + x2 (1/24 + x2 (-1/720 + x2 (1/40320 + x2 (-1/3628800 + x2 / 479001600)))))
    __m128d pc = _mm_div_pd(x2, _mm_set1_pd(479001600.0));
    pc = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(-1.0 / 3628800), pc));
    pc = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(1.0 / 40320), pc));
    pc = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(-1.0 / 720), pc));
    pc = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(1.0 / 24), pc));
    pc = _mm_mul_pd(x2, _mm_add_pd(_mm_set1_pd(-0.5), pc));
    __m128d cv = _mm_add_pd(one, pc);
    const int small = _mm_movemask_pd(_mm_cmplt_pd(_mm_and_pd(x, absmask), quarter));
    if (small != 3) {  // a large turn (or NaN) in one lane: the library functions there
      alignas(16) double s2[2], c2[2];
      _mm_store_pd(s2, sv);
      _mm_store_pd(c2, cv);
      for (int l = 0; l < 2; ++l)
        if (!(small & (1 << l))) {
          s2[l] = std::sin(dth[i + l]);
          c2[l] = std::cos(dth[i + l]);
        }
      sv = _mm_load_pd(s2);
      cv = _mm_load_pd(c2);
    }
    double *m0 = mu + 4 * static_cast<long>(i), *m1 = m0 + 4;
    const __m128d len = _mm_set_pd(m1[3], m0[3]);
    const __m128d m = _mm_or_pd(_mm_and_pd(_mm_cmpgt_pd(len, zero), len),
                                _mm_andnot_pd(_mm_cmpgt_pd(len, zero), one));
    const __m128d u0 = _mm_loadu_pd(u + 2 * static_cast<long>(i));  // (nx0, ny0)
    const __m128d u1 = _mm_loadu_pd(u + 2 * static_cast<long>(i) + 2);  // (nx1, ny1)
    const __m128d nx = _mm_unpacklo_pd(u0, u1), ny = _mm_unpackhi_pd(u0, u1);
    const __m128d rx = _mm_sub_pd(_mm_mul_pd(cv, nx), _mm_mul_pd(sv, ny));
    const __m128d ry = _mm_add_pd(_mm_mul_pd(sv, nx), _mm_mul_pd(cv, ny));
    alignas(16) double q[2];
    _mm_store_pd(q, _mm_add_pd(_mm_mul_pd(rx, rx), _mm_mul_pd(ry, ry)));
    const __m128d r = _mm_set_pd(inverse_sqrt(q[1]), inverse_sqrt(q[0]));
    const __m128d ox = _mm_mul_pd(_mm_mul_pd(m, rx), r), oy = _mm_mul_pd(_mm_mul_pd(m, ry), r);
    if (act0) {
      _mm_storeu_pd(m0, _mm_unpacklo_pd(ox, oy));
      _mm_storeu_pd(m0 + 2, _mm_unpacklo_pd(zero, m));
    }
    if (act1) {
      _mm_storeu_pd(m1, _mm_unpackhi_pd(ox, oy));
      _mm_storeu_pd(m1 + 2, _mm_unpackhi_pd(zero, m));
    }
  }
#endif
  if (i < n) rotate_polarities_reference(n - i, u + 2 * static_cast<long>(i), dth + i,
                                         mu + 4 * static_cast<long>(i), active ? active + i : nullptr);
}

void velocity_observables(const Contacts &t, const double *vel, int vel_stride,
                          double *coordination, double *orientation) {
  auto unit = [&](int i, double &ux, double &uy) {
    const double vx = vel[static_cast<long>(i) * vel_stride];
    const double vy = vel[static_cast<long>(i) * vel_stride + 1];
    const double s = std::hypot(vx, vy);
    if (!(s > 0.0)) return false;
    ux = vx / s;
    uy = vy / s;
    return true;
  };
  for (int c = 0; c < t.n_owned; ++c) {
    double ux, uy;
    if (!unit(c, ux, uy)) {
      if (coordination) coordination[c] = 0.0;
      if (orientation) orientation[c] = -1.0;
      continue;
    }
    if (orientation) orientation[c] = std::acos(std::max(-1.0, std::min(1.0, ux)));
    if (coordination) {
      double sum = 0.0;
      int count = 0;
      for (int k = t.offset[c]; k < t.offset[c + 1]; ++k) {
        double wx, wy;
        if (t.size[k] > 0.0 && unit(t.neighbor[k], wx, wy)) {
          sum += ux * wx + uy * wy;
          ++count;
        }
      }
      coordination[c] = count ? sum / count : 0.0;
    }
  }
}

}  // namespace tessera
