// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later

#include "tessera/polarity.h"

#include <algorithm>
#include <cmath>

namespace tessera {

void polarity_torque(const Tessellation &t, const double *theta, const PolarityParams &p,
                     const double *psi, const unsigned char *has_psi, double *tau) {
  for (int c = 0; c < t.n_owned; ++c) {
    const double th = theta[c];
    double neighbours = 0.0;
    if (p.J_S != 0.0) {
      for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
        if (t.edge_length[k] > 0.0) neighbours += std::sin(theta[t.cell_neighbor[k]] - th);
    }
    const double dg = th - p.phi_G;
    double v = p.J_S * neighbours - p.J_G * std::sin(dg) * std::cos(dg);
    if (p.J_V != 0.0 && psi && (!has_psi || has_psi[c])) v -= p.J_V * std::sin(th - psi[c]);
    tau[c] = v;
  }
}

void polarity_torque_vec(const Tessellation &t, const double *n, int n_stride,
                         const PolarityParams &p, const double *vhat, const unsigned char *has_v,
                         double *tau) {
  const double cphi = std::cos(p.phi_G), sphi = std::sin(p.phi_G);
  for (int c = 0; c < t.n_owned; ++c) {
    const double nx = n[static_cast<long>(c) * n_stride], ny = n[static_cast<long>(c) * n_stride + 1];
    double cross = 0.0;
    if (p.J_S != 0.0) {
      double sx = 0.0, sy = 0.0;  // sum of the neighbours' polarities
      for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k) {
        if (!(t.edge_length[k] > 0.0)) continue;
        const long j = static_cast<long>(t.cell_neighbor[k]) * n_stride;
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

void velocity_observables(const Tessellation &t, const double *vel, int vel_stride,
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
      for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k) {
        double wx, wy;
        if (t.edge_length[k] > 0.0 && unit(t.cell_neighbor[k], wx, wy)) {
          sum += ux * wx + uy * wy;
          ++count;
        }
      }
      coordination[c] = count ? sum / count : 0.0;
    }
  }
}

}  // namespace tessera
