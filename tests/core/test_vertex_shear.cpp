// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The honeycomb's energy after relaxation under a deformation F of the box,
// against its closed form (doc/model.md, "The hexagonal tissue's shear
// modulus"):
//   e(F) = KA (A det F - A0)^2 + KP max(0, P_min(F) - P0)^2,
//   P_min(F)^2 = 2 sqrt3 A [tr(F^T F) + 2 det F],
// and the shear modulus G = KP P_h (P_h - P0) / (2 A) (0 for P0 >= P_h),
// which vanishes at p0 = sqrt(8 sqrt3) = 3.7224.  The relaxed energies come
// from minimising the vertex positions of a periodic honeycomb of 24 cells.
#include "vertex_test_util.h"
#include "tessera/vertex_model.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

const double KA = 1.0, A0 = 1.0, KP = 0.6;

double closed_form(double A, double f11, double f12, double f22, double P0) {
  const double det = f11 * f22, tr = f11 * f11 + f12 * f12 + f22 * f22;
  const double pmin = std::sqrt(2.0 * std::sqrt(3.0) * A * (tr + 2.0 * det));
  const double dp = std::max(0.0, pmin - P0);
  return KA * (A * det - A0) * (A * det - A0) + KP * dp * dp;
}

// Relaxed energy per cell of the honeycomb of cell area A deformed by F.
double relaxed(double A, double f11, double f12, double f22, double P0) {
  tessera::VertexTissue t = vtest::honeycomb(6, 4, A);
  vtest::deform(t, f11, f12, f22);
  // A small disorder, so that the minimiser does the relaxation.
  for (int v = 0; v < t.n_vertices(); ++v) {
    t.pos[v].x += 0.01 * std::sin(1.7 * v);
    t.pos[v].y += 0.01 * std::cos(2.3 * v);
  }
  const tessera::Model m = vtest::quadratic_model(KA, A0, KP, P0);
  const double e = vtest::minimise(t, m, 1e-10);
  EXPECT_NO_THROW(tessera::check_tissue(t));
  // The quadratic form's constant KP P0^2 per cell.
  return e / t.n_cells() + KP * P0 * P0;
}

TEST(VertexShear, RelaxedEnergyIsTheClosedForm) {
  struct F {
    double f11, f12, f22;
  };
  for (double p0 : {3.4, 3.65, 3.8, 4.0})
    for (const F &f : {F{1, 0, 1}, F{1, 0.08, 1}, F{1, -0.15, 1}, F{1.06, 0.05, 0.97},
                       F{0.95, 0, 0.95}, F{1.08, 0, 1.02}}) {
      const double A = 1.05;
      const double want = closed_form(A, f.f11, f.f12, f.f22, p0 * std::sqrt(A0));
      const double got = relaxed(A, f.f11, f.f12, f.f22, p0 * std::sqrt(A0));
      EXPECT_NEAR(got, want, 1e-8 * (1.0 + want))
          << "p0 " << p0 << " F " << f.f11 << " " << f.f12 << " " << f.f22;
    }
}

// G from the second difference of the relaxed energy against the formula,
// on both sides of p0 = 3.7224.
TEST(VertexShear, ShearModulusVanishesAtHexagonShapeIndex) {
  const double A = 1.0, g = 0.02;
  const double ph = std::sqrt(8.0 * std::sqrt(3.0) * A);
  EXPECT_NEAR(ph, 3.7224, 1e-4);
  for (double p0 : {3.3, 3.5, 3.65, 3.75, 3.9}) {
    const double e0 = relaxed(A, 1, 0, 1, p0), ep = relaxed(A, 1, g, 1, p0),
                 em = relaxed(A, 1, -g, 1, p0);
    const double G = (ep + em - 2 * e0) / (g * g) / A;
    const double want = p0 < ph ? KP * ph * (ph - p0) / (2 * A) : 0.0;
    // The second difference of the closed form itself differs from its
    // curvature at 0 by O(g^2).
    EXPECT_NEAR(G, want, 2e-3 * (1.0 + want)) << "p0 " << p0;
  }
}

} // namespace
