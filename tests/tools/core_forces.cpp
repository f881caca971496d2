// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The core library's energy, virial and forces for a periodic configuration,
// for tests that compare the LAMMPS styles against the core.
//
// stdin:  xlo xhi ylo yhi xy n ntypes tension(edge|cell)
//         ntypes lines: K A0 Gamma
//         ntypes lines of ntypes Lambda values
//         n lines: x y type(1-based)
// stdout: energy E, virial Wxx Wyy Wxy, then n lines fx fy (input order)
#include "tessera/energy.h"

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

int main() {
  double xlo, xhi, ylo, yhi, tilt;
  int n, ntypes;
  std::string tension;
  if (!(std::cin >> xlo >> xhi >> ylo >> yhi >> tilt >> n >> ntypes >> tension)) return 2;
  tessera::Model model(ntypes);
  model.tension = tension == "cell" ? tessera::Tension::Cell : tessera::Tension::Edge;
  for (auto &t : model.types) std::cin >> t.K >> t.A0 >> t.Gamma;
  for (int i = 0; i < ntypes; ++i)
    for (int j = 0; j < ntypes; ++j) std::cin >> model.lambda[i * ntypes + j];
  std::vector<double> xy(2 * n);
  std::vector<int> type(n);
  for (int i = 0; i < n; ++i) {
    std::cin >> xy[2 * i] >> xy[2 * i + 1] >> type[i];
    type[i] -= 1;
  }
  std::vector<double> f;
  try {
    tessera::Box box = tessera::Box::rect(xlo, xhi, ylo, yhi);
    box.xy = tilt;
    const auto out = tessera::periodic_forces(box,
                                              tessera::Points{xy.data(), n, 2}, type.data(),
                                              model, f);
    std::printf("energy %.17g\nvirial %.17g %.17g %.17g\n", out.energy, out.virial[0],
                out.virial[1], out.virial[2]);
    for (int i = 0; i < n; ++i) std::printf("%.17g %.17g\n", f[2 * i], f[2 * i + 1]);
  } catch (const tessera::Error &e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
