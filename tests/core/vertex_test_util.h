// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Vertex tissues for the vertex model's tests: disordered ones from the
// Voronoi polygons of random centres, honeycombs from a triangular lattice,
// and a plain nonlinear conjugate-gradient minimiser of the energy.
#pragma once

#include "test_util.h"
#include "tessera/vertex_model.h"

#include <cmath>
#include <functional>
#include <vector>

namespace vtest {

// n random centres in an L x L box (tilt xy), kept at least dmin apart so
// that cells are not tiny, ntypes types at random; then the Voronoi vertex
// tissue of them.
inline tessera::VertexTissue random_tissue(uint64_t seed, int n, double L, int ntypes = 1,
                                           double xy = 0.0) {
  testutil::Rng rng(seed);
  tessera::Box box = tessera::Box::rect(0.0, L, 0.0, L);
  box.xy = xy;
  std::vector<double> pts;
  std::vector<int> type;
  const double dmin = 0.5 * L / std::sqrt(static_cast<double>(n));
  int tries = 0;
  while (static_cast<int>(type.size()) < n && tries++ < 100000) {
    const double s = rng.uniform(), u = rng.uniform();
    const double x = s * L + u * xy, y = u * L;
    bool ok = true;
    for (size_t k = 0; k < type.size() && ok; ++k) {
      double dx = x - pts[2 * k], dy = y - pts[2 * k + 1];
      const double j = std::floor(dy / L + 0.5);
      dx -= j * xy;
      dy -= j * L;
      dx -= L * std::floor(dx / L + 0.5);
      ok = dx * dx + dy * dy >= dmin * dmin;
    }
    if (!ok)
      continue;
    pts.push_back(x);
    pts.push_back(y);
    type.push_back(rng.below(ntypes));
  }
  std::vector<double> wrapped = pts;
  tessera::wrap_into_box(box, wrapped);
  const tessera::Points p{wrapped.data(), static_cast<int>(type.size()), 2};
  return tessera::vertex_tissue_from_voronoi(box, p, type.data());
}

// A regular honeycomb of nx x ny cells of area A (ny even): the Voronoi
// polygons of a triangular lattice.
inline tessera::VertexTissue honeycomb(int nx, int ny, double A = 1.0) {
  const double a = std::sqrt(2.0 * A / std::sqrt(3.0));
  const double lx = nx * a, ly = ny * a * std::sqrt(3.0) / 2.0;
  const tessera::Box box = tessera::Box::rect(0.0, lx, 0.0, ly);
  std::vector<double> pts;
  std::vector<int> type;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      pts.push_back((i + 0.5 * (j % 2) + 0.25) * a);
      pts.push_back((j + 0.5) * a * std::sqrt(3.0) / 2.0);
      type.push_back(0);
    }
  const tessera::Points p{pts.data(), nx * ny, 2};
  return tessera::vertex_tissue_from_voronoi(box, p, type.data());
}

// Applies the upper-triangular deformation [[f11, f12], [0, f22]] to the box
// (kept with its lower corner at the origin) and to every vertex position.
inline void deform(tessera::VertexTissue &t, double f11, double f12, double f22) {
  const double lx = t.box.length(0), ly = t.box.length(1);
  for (tessera::Vec2 &p : t.pos) {
    const double x = p.x - t.box.lo[0], y = p.y - t.box.lo[1];
    p.x = t.box.lo[0] + f11 * x + f12 * y;
    p.y = t.box.lo[1] + f22 * y;
  }
  t.box.xy = f11 * t.box.xy + f12 * ly;
  t.box.hi[0] = t.box.lo[0] + f11 * lx;
  t.box.hi[1] = t.box.lo[1] + f22 * ly;
}

// Minimises E over the vertex positions (Polak-Ribiere+ conjugate gradients
// with a secant line search on the directional derivative) until the largest
// force is below ftol; returns the energy.
inline double minimise(tessera::VertexTissue &t, const tessera::Model &model, double ftol,
                       int max_iter = 20000) {
  const int nv = t.n_vertices();
  std::vector<double> f, fnew, d(2 * nv);
  double e = tessera::tissue_forces(t, model, f);
  d = f;
  auto fmax = [](const std::vector<double> &g) {
    double m = 0.0;
    for (double v : g)
      m = std::max(m, std::fabs(v));
    return m;
  };
  for (int it = 0; it < max_iter && fmax(f) > ftol; ++it) {
    const std::vector<tessera::Vec2> x0 = t.pos;
    auto slope_at = [&](double s, double &energy) {
      for (int v = 0; v < nv; ++v) {
        t.pos[v].x = x0[v].x + s * d[2 * v];
        t.pos[v].y = x0[v].y + s * d[2 * v + 1];
      }
      energy = tessera::tissue_forces(t, model, fnew);
      double g = 0.0;
      for (int k = 0; k < 2 * nv; ++k)
        g -= fnew[k] * d[k];
      return g; // dE/ds
    };
    double g0 = 0.0;
    for (int k = 0; k < 2 * nv; ++k)
      g0 -= f[k] * d[k];
    if (g0 >= 0.0) { // not a descent direction: restart along the force
      d = f;
      g0 = 0.0;
      for (int k = 0; k < 2 * nv; ++k)
        g0 -= f[k] * d[k];
    }
    // Bracket the zero of dE/ds, then secant/bisection steps.
    double s0 = 0.0, s1 = 1e-3 / std::max(1e-12, fmax(d)), e1 = e;
    double g1 = slope_at(s1, e1);
    int grow = 0;
    while (g1 < 0.0 && grow++ < 60) {
      s0 = s1;
      g0 = g1;
      s1 *= 2.0;
      g1 = slope_at(s1, e1);
    }
    double s = s1, es = e1;
    for (int k = 0; k < 40; ++k) {
      double sm = s0 - g0 * (s1 - s0) / (g1 - g0);
      if (!(sm > s0 && sm < s1))
        sm = 0.5 * (s0 + s1);
      const double gm = slope_at(sm, es);
      s = sm;
      if (std::fabs(gm) < 1e-3 * std::fabs(g0) || s1 - s0 < 1e-15 * s1)
        break;
      if (gm < 0.0) {
        s0 = sm;
        g0 = gm;
      } else {
        s1 = sm;
        g1 = gm;
      }
    }
    (void)s;
    e = es;
    double num = 0.0, den = 0.0;
    for (int k = 0; k < 2 * nv; ++k) {
      num += fnew[k] * (fnew[k] - f[k]);
      den += f[k] * f[k];
    }
    const double beta = den > 0.0 ? std::max(0.0, num / den) : 0.0;
    f = fnew;
    for (int k = 0; k < 2 * nv; ++k)
      d[k] = f[k] + beta * d[k];
  }
  return tessera::tissue_forces(t, model, f);
}

inline tessera::Model quadratic_model(double KA, double A0, double KP, double P0) {
  tessera::Model m(1);
  const tessera::QuadraticParams q{KA, A0, KP, P0};
  m.types[0] = tessera::cell_type_from_quadratic(q);
  m.set_lambda(0, 0, tessera::lambda_from_quadratic(q, tessera::Tension::Edge));
  return m;
}

} // namespace vtest
