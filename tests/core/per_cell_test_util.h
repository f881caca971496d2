// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Shared by the per-cell parameter tests (test_per_cell.cpp in the plane and
// in 3D, test_per_cell_sphere.cpp): a random two-type model and random
// per-cell KA, KP, P0, A0 bound to it.
#pragma once

#include "test_util.h"
#include "tessera/energy.h"

#include <cstdint>
#include <vector>

namespace testutil {

// Two types with heterotypic tension, K, Gamma > 0, Lambda < 0.
inline tessera::Model two_types(uint64_t seed, tessera::Tension tension) {
  Rng rng(seed);
  tessera::Model m(2);
  m.tension = tension;
  for (auto &t : m.types) {
    t.K = rng.uniform(0.5, 2.0);
    t.A0 = rng.uniform(0.8, 1.2);
    t.Gamma = rng.uniform(0.1, 0.4);
  }
  m.set_lambda(0, 0, -rng.uniform(0.5, 1.5));
  m.set_lambda(1, 1, -rng.uniform(0.5, 1.5));
  m.set_lambda(0, 1, rng.uniform(-0.8, 0.3));
  return m;
}

struct PerCell {
  std::vector<double> ka, kp, p0, a0;
  // n more cells: KA in [0.3, 1.5], KP in [0.02, 0.3], P0 in [p0_lo, p0_hi],
  // A0 in [0.7, 1.3].
  void draw(Rng &rng, int n, double p0_lo, double p0_hi) {
    for (int i = 0; i < n; ++i) {
      ka.push_back(rng.uniform(0.3, 1.5));
      kp.push_back(rng.uniform(0.02, 0.3));
      p0.push_back(rng.uniform(p0_lo, p0_hi));
      a0.push_back(rng.uniform(0.7, 1.3));
    }
  }
  // which: bit 0 KA, 1 KP, 2 P0, 3 A0
  void bind(tessera::Model &m, int which) const {
    m.cell_KA = which & 1 ? ka.data() : nullptr;
    m.cell_KP = which & 2 ? kp.data() : nullptr;
    m.cell_P0 = which & 4 ? p0.data() : nullptr;
    m.cell_area0 = which & 8 ? a0.data() : nullptr;
  }
};

}  // namespace testutil
