// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The floating-point filters of the 3D Delaunay predicates, inline: the
// builder (mesh3d_delaunay.cpp) calls them in its innermost loops, and the
// exported predicates (mesh3d_predicates.cpp) wrap them; the rare exact ties
// are broken out of line (perturbed_tie, mesh3d_predicates.cpp).
// Internal to the core (not installed).
#pragma once

#include "exact_predicates.h"

#include <algorithm>
#include <cmath>

namespace tessera {
namespace detail3 {

// Bounds below this may have lost terms to underflow: the exact predicate
// decides.
constexpr double kTiny = 1e-250;

// The filters, inlined into the builder's loops (the exported functions
// of mesh3d_predicates.cpp wrap them).
[[gnu::always_inline]] inline int orient_impl(const double *a, const double *b, const double *c,
                                              const double *d, long &exact_calls) {
  const double bx = b[0] - a[0], by = b[1] - a[1], bz = b[2] - a[2];
  const double cx = c[0] - a[0], cy = c[1] - a[1], cz = c[2] - a[2];
  const double dx = d[0] - a[0], dy = d[1] - a[1], dz = d[2] - a[2];
  const double cydz = cy * dz, czdy = cz * dy, czdx = cz * dx, cxdz = cx * dz, cxdy = cx * dy,
               cydx = cy * dx;
  const double det = bx * (cydz - czdy) + by * (czdx - cxdz) + bz * (cxdy - cydx);
  // First a cheaper bound from the largest differences per axis: the
  // permanent below is at most 6 mx my mz.
  const double mx = std::max({std::fabs(bx), std::fabs(cx), std::fabs(dx)});
  const double my = std::max({std::fabs(by), std::fabs(cy), std::fabs(dy)});
  const double mz = std::max({std::fabs(bz), std::fabs(cz), std::fabs(dz)});
  const double loose = 6e-14 * (mx * my * mz);
  if (loose > kTiny) {
    if (det > loose)
      return 1;
    if (det < -loose)
      return -1;
  }
  const double perm = std::fabs(bx) * (std::fabs(cydz) + std::fabs(czdy)) +
                      std::fabs(by) * (std::fabs(czdx) + std::fabs(cxdz)) +
                      std::fabs(bz) * (std::fabs(cxdy) + std::fabs(cydx));
  // About 13 times the classical bound (7 eps) on the rounding error of det,
  // the subtractions included.
  const double bound = 1e-14 * perm;
  if (bound > kTiny) {
    if (det > bound)
      return 1;
    if (det < -bound)
      return -1;
  }
  ++exact_calls;
  return exact::orient3d(a, b, c, d);
}

[[gnu::always_inline]] inline int insphere_impl(const double *p0, const double *p1,
                                                const double *p2, const double *p3,
                                                const double *e, long &exact_calls) {
  const double ax = p0[0] - e[0], ay = p0[1] - e[1], az = p0[2] - e[2];
  const double bx = p1[0] - e[0], by = p1[1] - e[1], bz = p1[2] - e[2];
  const double cx = p2[0] - e[0], cy = p2[1] - e[1], cz = p2[2] - e[2];
  const double dx = p3[0] - e[0], dy = p3[1] - e[1], dz = p3[2] - e[2];
  const double axby = ax * by, bxay = bx * ay, bxcy = bx * cy, cxby = cx * by;
  const double cxdy = cx * dy, dxcy = dx * cy, dxay = dx * ay, axdy = ax * dy;
  const double axcy = ax * cy, cxay = cx * ay, bxdy = bx * dy, dxby = dx * by;
  const double ab = axby - bxay, bc = bxcy - cxby, cd = cxdy - dxcy, da = dxay - axdy;
  const double ac = axcy - cxay, bd = bxdy - dxby;
  const double abc = az * bc - bz * ac + cz * ab;
  const double bcd = bz * cd - cz * bd + dz * bc;
  const double cda = cz * da + dz * ac + az * cd;
  const double dab = dz * ab + az * bd + bz * da;
  const double al = ax * ax + ay * ay + az * az, bl = bx * bx + by * by + bz * bz;
  const double cl = cx * cx + cy * cy + cz * cz, dl = dx * dx + dy * dy + dz * dz;
  const double det = (dl * abc - cl * dab) + (bl * cda - al * bcd);
  // First a cheaper bound from the largest differences per axis: the
  // permanent below is at most 24 (mx^2 + my^2 + mz^2) mx my mz.
  {
    const double mx = std::max({std::fabs(ax), std::fabs(bx), std::fabs(cx), std::fabs(dx)});
    const double my = std::max({std::fabs(ay), std::fabs(by), std::fabs(cy), std::fabs(dy)});
    const double mz = std::max({std::fabs(az), std::fabs(bz), std::fabs(cz), std::fabs(dz)});
    const double loose = 2.4e-12 * ((mx * mx + my * my + mz * mz) * (mx * my * mz));
    if (loose > kTiny) {
      if (det > loose)
        return -1;
      if (det < -loose)
        return 1;
    }
  }
  const double pab = std::fabs(axby) + std::fabs(bxay), pbc = std::fabs(bxcy) + std::fabs(cxby);
  const double pcd = std::fabs(cxdy) + std::fabs(dxcy), pda = std::fabs(dxay) + std::fabs(axdy);
  const double pac = std::fabs(axcy) + std::fabs(cxay), pbd = std::fabs(bxdy) + std::fabs(dxby);
  const double pabc = std::fabs(az) * pbc + std::fabs(bz) * pac + std::fabs(cz) * pab;
  const double pbcd = std::fabs(bz) * pcd + std::fabs(cz) * pbd + std::fabs(dz) * pbc;
  const double pcda = std::fabs(cz) * pda + std::fabs(dz) * pac + std::fabs(az) * pcd;
  const double pdab = std::fabs(dz) * pab + std::fabs(az) * pbd + std::fabs(bz) * pda;
  const double perm = dl * pabc + cl * pdab + bl * pcda + al * pbcd;
  // About 28 times the classical bound (16 eps), the subtractions included.
  const double bound = 1e-13 * perm;
  // det is the determinant in the orientation convention opposite to CGAL's.
  if (bound > kTiny) {
    if (det > bound)
      return -1;
    if (det < -bound)
      return 1;
  }
  ++exact_calls;
  return exact::insphere(p0, p1, p2, p3, e);
}

// The perturbation of an exact tie (mesh3d_predicates.cpp).
int perturbed_tie(const double *const t[4], const double *e, long &exact_calls);

[[gnu::always_inline]] inline int insphere_perturbed_impl(const double *const t[4], const double *e,
                                                          long &exact_calls) {
  const int s = insphere_impl(t[0], t[1], t[2], t[3], e, exact_calls);
  return s != 0 ? s : perturbed_tie(t, e, exact_calls);
}

} // namespace detail3
} // namespace tessera
