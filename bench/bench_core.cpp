// Tessera benchmark.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Microseconds per cell for the periodic tessellation, the forces on it, and,
// as a yardstick, a from-scratch CGAL Delaunay triangulation of the same
// points (no periodicity, no Voronoi cells), for N random points at density 1
// in a periodic square box.  Median of a few repeats.
//
//   bench_core [max_N]     (default 1000000)
#include "tessera/energy.h"
#include "tessera/tessellation.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using DT = CGAL::Delaunay_triangulation_2<Kernel>;

double now_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

uint64_t splitmix(uint64_t &s) {
  uint64_t z = (s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

int main(int argc, char **argv) {
  long max_n = 1000000;
  if (argc > 1) {
    char *end = nullptr;
    max_n = std::strtol(argv[1], &end, 10);
    if (argc > 2 || end == argv[1] || *end != '\0' || max_n < 3) {
      std::fprintf(stderr, "usage: %s [max_N >= 3]\n", argv[0]);
      return 2;
    }
  }

  tessera::Model model(1);
  model.types[0].K = 1.0;
  model.types[0].A0 = 1.0;
  model.types[0].Gamma = 0.18;
  model.set_lambda(0, 0, -0.1);

  std::printf("Tessera core benchmark: random points, density 1, periodic square box\n");
  std::printf("times in microseconds per cell, median of the repeats\n\n");
  std::printf("%9s %5s %16s %16s %16s %12s\n", "N", "reps", "tessellate", "compute_forces",
              "CGAL DT2", "tess/CGAL");
  double checksum = 0;
  for (long n : {1000L, 10000L, 100000L, 1000000L}) {
    if (n > max_n) break;
    const int reps = n >= 1000000 ? 3 : n >= 100000 ? 5 : 9;
    const double side = std::sqrt(static_cast<double>(n));
    const tessera::Box box = tessera::Box::rect(0, side, 0, side);
    uint64_t seed = 12345 + static_cast<uint64_t>(n);
    std::vector<double> xy(2 * n);
    for (double &v : xy) v = side * static_cast<double>(splitmix(seed) >> 11) * 0x1.0p-53;
    const tessera::Points pts{xy.data(), static_cast<int>(n), 2};
    std::vector<DT::Point> cpts;
    cpts.reserve(n);
    for (long i = 0; i < n; ++i) cpts.emplace_back(xy[2 * i], xy[2 * i + 1]);

    std::vector<double> t_tess, t_force, t_cgal;
    for (int r = 0; r < reps; ++r) {
      double t0 = now_seconds();
      const tessera::Tessellation t = tessera::tessellate_periodic(box, pts);
      double t1 = now_seconds();
      t_tess.push_back(t1 - t0);

      const std::vector<double> pos = tessera::positions_of(t);
      const std::vector<int> type(t.n_points, 0);
      std::vector<double> f(2 * static_cast<size_t>(t.n_points), 0.0);
      t0 = now_seconds();
      const tessera::ForceOutput out = tessera::compute_forces(
          t, tessera::Points{pos.data(), t.n_points, 2}, type.data(), model, f.data(), 2);
      t1 = now_seconds();
      t_force.push_back(t1 - t0);
      checksum += out.energy + f[0];

      t0 = now_seconds();
      DT dt;
      dt.insert(cpts.begin(), cpts.end());
      t1 = now_seconds();
      t_cgal.push_back(t1 - t0);
      checksum += static_cast<double>(dt.number_of_faces());
    }
    const double us = 1e6 / static_cast<double>(n);
    const double mt = median(t_tess), mf = median(t_force), mc = median(t_cgal);
    std::printf("%9ld %5d %16.3f %16.3f %16.3f %12.2f\n", n, reps, mt * us, mf * us, mc * us,
                mt / mc);
    std::fflush(stdout);
  }
  std::printf("\n(checksum %.6g)\n", checksum);
  return 0;
}
