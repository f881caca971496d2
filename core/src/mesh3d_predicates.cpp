// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The 3D Delaunay predicates of mesh3d_delaunay.h: the exported filtered
// predicates and the symbolic perturbation of exact ties (the conventions are
// described in mesh3d_delaunay.h).  Apart from the builder
// (mesh3d_delaunay.cpp), which inlines only the filters (mesh3d_filters.h)
// and calls these out of line.

#include "mesh3d_delaunay.h"

#include "exact_predicates.h"
#include "mesh3d_filters.h"

#include <algorithm>

namespace tessera {
namespace detail3 {

int orient3d_filtered(const double *a, const double *b, const double *c, const double *d,
                      long &exact_calls) {
  return orient_impl(a, b, c, d, exact_calls);
}

int insphere_filtered(const double *p0, const double *p1, const double *p2, const double *p3,
                      const double *e, long &exact_calls) {
  return insphere_impl(p0, p1, p2, p3, e, exact_calls);
}

// The perturbation of an exact tie (see the header).
[[gnu::noinline]] int perturbed_tie(const double *const t[4], const double *e, long &exact_calls) {
  // Rank the five points (slot 4 is e); the two highest ranked decide.
  int slot[5] = {0, 1, 2, 3, 4};
  auto point = [&](int k) { return k == 4 ? e : t[k]; };
  std::sort(slot, slot + 5, [&](int x, int y) { return less_xyz(point(x), point(y)); });
  for (int r = 4; r > 2; --r) {
    const int k = slot[r];
    if (k == 4)
      return -1;
    const double *q[4] = {t[0], t[1], t[2], t[3]};
    q[k] = e;
    const int o = orient3d_filtered(q[0], q[1], q[2], q[3], exact_calls);
    if (o != 0)
      return o;
  }
  return -1; // (not reached for a non-flat tetrahedron)
}

int insphere_perturbed(const double *const t[4], const double *e, long &exact_calls) {
  return insphere_perturbed_impl(t, e, exact_calls);
}

bool collinear3(const double *a, const double *b, const double *c) {
  // Collinear in space iff collinear in each coordinate plane.
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;
    const double pa[2] = {a[u], a[v]}, pb[2] = {b[u], b[v]}, pc[2] = {c[u], c[v]};
    if (exact::orient2d(pa, pb, pc) != 0)
      return false;
  }
  return true;
}

} // namespace detail3
} // namespace tessera
