// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// tessera-hessian: the exact Hessian of the energy of a periodic configuration
// and its affine-strain terms (core/include/tessera/hessian.h), for
// tools/tessera_tools/moduli.py (elastic moduli, vibrational spectrum).
//
// stdin:  xlo xhi ylo yhi xy n ntypes tension(edge|cell) [cells NAME...]
//         ntypes lines: K A0 Gamma
//         ntypes lines of ntypes Lambda values
//         n lines: x y type(1-based) [one value per NAME]
//         The optional per-cell parameters NAME are any of area0, ka, kp,
//         perim0 (LAMMPS's d_area0, d_ka, d_kp, d_perim0; Model::cell_area0,
//         cell_KA, cell_KP, cell_P0), in the order named on the first line.
// stdout: lines "n N", "area A", "energy E", "virial Wxx Wyy Wxy Wyx",
//         "born_shear B", "born_dilation B", then "force", "xi_shear",
//         "xi_dilation" each followed by 2N values (x0 y0 x1 y1 ...), then
//         "hessian NNZ" and NNZ lines "row col value" (0-based, row = 2 i + component,
//         both triangles of the symmetric matrix).
// Exit status 1 with the error on stderr on bad input (e.g. a multifold vertex).
#include "tessera/hessian.h"

#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

int main() {
  double xlo, xhi, ylo, yhi, tilt;
  int n, ntypes;
  std::string tension, first;
  std::getline(std::cin, first);
  std::istringstream head(first);
  if (!(head >> xlo >> xhi >> ylo >> yhi >> tilt >> n >> ntypes >> tension) || n <= 0 ||
      ntypes <= 0 || (tension != "edge" && tension != "cell")) {
    std::fprintf(stderr, "tessera-hessian: expected 'xlo xhi ylo yhi xy n ntypes edge|cell "
                         "[cells NAME...]' on the first line of stdin\n");
    return 2;
  }
  // Optional per-cell parameters: "cells" and the names of the extra columns.
  std::vector<std::string> names;
  std::string word;
  if (head >> word) {
    if (word != "cells") {
      std::fprintf(stderr, "tessera-hessian: unknown word '%s' after the tension; expected 'cells'\n",
                   word.c_str());
      return 2;
    }
    while (head >> word) {
      if (word != "area0" && word != "ka" && word != "kp" && word != "perim0") {
        std::fprintf(stderr,
                     "tessera-hessian: unknown per-cell parameter '%s'; expected area0, ka, kp or "
                     "perim0\n",
                     word.c_str());
        return 2;
      }
      names.push_back(word);
    }
  }
  std::map<std::string, std::vector<double>> cell;
  for (const auto &name : names) cell[name].resize(n);
  tessera::Model model(ntypes);
  model.tension = tension == "cell" ? tessera::Tension::Cell : tessera::Tension::Edge;
  for (auto &t : model.types) std::cin >> t.K >> t.A0 >> t.Gamma;
  for (int i = 0; i < ntypes; ++i)
    for (int j = 0; j < ntypes; ++j) std::cin >> model.lambda[i * ntypes + j];
  std::vector<double> xy(2 * static_cast<size_t>(n));
  std::vector<int> type(n);
  for (int i = 0; i < n; ++i) {
    std::cin >> xy[2 * i] >> xy[2 * i + 1] >> type[i];
    type[i] -= 1;
    for (const auto &name : names) std::cin >> cell[name][i];
  }
  if (!std::cin) {
    std::fprintf(stderr, "tessera-hessian: input ended early (expected %d points)\n", n);
    return 2;
  }
  // The points keep their order (tessellate_periodic's owned points are the
  // input points), so the per-cell arrays are indexed like type.
  if (cell.count("area0")) model.cell_area0 = cell["area0"].data();
  if (cell.count("ka")) model.cell_KA = cell["ka"].data();
  if (cell.count("kp")) model.cell_KP = cell["kp"].data();
  if (cell.count("perim0")) model.cell_P0 = cell["perim0"].data();
  try {
    model.validate_cells(n);
    tessera::Box box = tessera::Box::rect(xlo, xhi, ylo, yhi);
    box.xy = tilt;
    box.validate();
    tessera::wrap_into_box(box, xy);
    const auto h = tessera::periodic_hessian(box, tessera::Points{xy.data(), n, 2}, type.data(),
                                             model);
    std::printf("n %d\narea %.17g\nenergy %.17g\nvirial %.17g %.17g %.17g %.17g\n", n, h.area,
                h.energy, h.virial[0], h.virial[1], h.virial[2], h.virial[3]);
    std::printf("born_shear %.17g\nborn_dilation %.17g\n", h.born_shear, h.born_dilation);
    auto vec = [](const char *name, const std::vector<double> &v) {
      std::printf("%s\n", name);
      for (size_t i = 0; i < v.size(); ++i) std::printf("%.17g%c", v[i], i % 2 ? '\n' : ' ');
    };
    vec("force", h.force);
    vec("xi_shear", h.xi_shear);
    vec("xi_dilation", h.xi_dilation);
    std::printf("hessian %zu\n", h.hessian.val.size());
    for (size_t k = 0; k < h.hessian.val.size(); ++k)
      std::printf("%d %d %.17g\n", h.hessian.row[k], h.hessian.col[k], h.hessian.val[k]);
  } catch (const tessera::Error &e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
