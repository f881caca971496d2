// Tessera benchmark.  SPDX-License-Identifier: GPL-2.0-or-later
//
// bench_core3d --build: Tessera's own 3D Delaunay tetrahedralisation against
// CGAL's Delaunay_triangulation_3 on the same points (CGAL only here, when
// the benchmarks are built with it).  Two point sets per N (1e3 ... 1e6):
//
//   random   uniform in the unit cube, indices in random order;
//   BCC      the bench's tissue, a BCC lattice jittered by 0.1 s, in lattice
//            order (spatially sorted, as LAMMPS keeps atoms).
//
// Columns, CPU time of the thread per point in microseconds (median over
// the repeats):
//
//   own        time_plain_delaunay_3d: the tetrahedralisation of the points
//              (biased randomised Hilbert order, Bowyer-Watson) and its
//              finite tetrahedra in flat arrays, in the builder's order;
//   CGAL       a plain Delaunay_triangulation_3<Epick> (range insert, which
//              sorts the points spatially; no info, nothing exported);
//   Mesh3      Mesh3::build: the points and eight far points, tetrahedra
//              numbered by their smallest point (what a 3D rebuild does);
//   Mesh3-CGAL the same with CGAL's triangulation (with vertex and cell
//              info, then the same export), as Mesh3::build was before.
//
// Also the tetrahedra counts (own and CGAL's must agree).  For instruction
// counts, one build alone: bench_core3d --build-one WHAT SET N (WHAT: own,
// cgal, mesh3, mesh3-cgal or none; SET: random or bcc) under
// valgrind --tool=callgrind, less the same with WHAT = none.

#include "tessera/mesh3d.h"

#ifdef TESSERA_BENCH_CGAL
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "bench_util.h"

namespace {

using namespace bench_util;

uint64_t mix(uint64_t &s) {
  uint64_t z = (s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
double unit(uint64_t &s) { return (mix(s) >> 11) * (1.0 / 9007199254740992.0); }

std::vector<double> point_set(const std::string &set, long target) {
  uint64_t seed = 777 + target;
  std::vector<double> x;
  if (set == "random") {
    x.resize(3 * static_cast<size_t>(target));
    for (double &v : x) v = unit(seed);
    return x;
  }
  const int m = static_cast<int>(std::lround(std::cbrt(target / 2.0)));
  const double s = std::cbrt(0.5);
  for (int a = 0; a < m; ++a)
    for (int b = 0; b < m; ++b)
      for (int c = 0; c < m; ++c)
        for (int q = 0; q < 2; ++q) {
          const double base[3] = {a + 0.5 * q, b + 0.5 * q, c + 0.5 * q};
          for (int d = 0; d < 3; ++d) x.push_back(base[d] + 0.1 * s * (2.0 * unit(seed) - 1.0));
        }
  return x;
}

#ifdef TESSERA_BENCH_CGAL
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

long cgal_plain(const std::vector<double> &x) {
  std::vector<K::Point_3> p;
  const size_t n = x.size() / 3;
  p.reserve(n);
  for (size_t i = 0; i < n; ++i) p.emplace_back(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
  CGAL::Delaunay_triangulation_3<K> dt(p.begin(), p.end());
  return static_cast<long>(dt.number_of_finite_cells());
}

// Mesh3::build as it was with CGAL: far points as Mesh3 places them, the
// triangulation with info, tetrahedra numbered by their smallest point.
long cgal_mesh3(const std::vector<double> &x) {
  using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
  using Cb = CGAL::Triangulation_cell_base_with_info_3<int, K,
                                                       CGAL::Delaunay_triangulation_cell_base_3<K>>;
  using DT = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb, Cb>>;
  const int n = static_cast<int>(x.size() / 3);
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) lo[d] = hi[d] = x[d];
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], x[3 * i + d]);
      hi[d] = std::max(hi[d], x[3 * i + d]);
    }
  const double ext = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  std::vector<std::pair<K::Point_3, int>> in(n + 8);
  for (int i = 0; i < n; ++i) in[i] = {K::Point_3(x[3 * i], x[3 * i + 1], x[3 * i + 2]), i};
  for (int k = 0; k < 8; ++k) {
    double f[3];
    for (int d = 0; d < 3; ++d) f[d] = 0.5 * (lo[d] + hi[d]) + ((k >> d) & 1 ? 32.0 : -32.0) * ext;
    in[n + k] = {K::Point_3(f[0], f[1], f[2]), n + k};
  }
  DT dt(in.begin(), in.end());
  std::vector<int> first(n + 9, 0);
  auto smallest = [](DT::Cell_handle c) {
    return std::min(std::min(c->vertex(0)->info(), c->vertex(1)->info()),
                    std::min(c->vertex(2)->info(), c->vertex(3)->info()));
  };
  long nt = 0;
  for (auto c = dt.all_cells_begin(); c != dt.all_cells_end(); ++c) {
    c->info() = -1;
    if (!dt.is_infinite(c)) {
      ++first[smallest(c) + 1];
      ++nt;
    }
  }
  for (int i = 0; i < n + 8; ++i) first[i + 1] += first[i];
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c)
    c->info() = first[smallest(c)]++;
  std::vector<int> tv, tn, vt(n + 8, -1);
  tv.reserve(4 * nt + 4 * nt / 32 + 256);
  tn.reserve(4 * nt + 4 * nt / 32 + 256);
  tv.assign(4 * nt, -1);
  tn.assign(4 * nt, -1);
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    const int t = c->info();
    for (int k = 0; k < 4; ++k) {
      const int v = c->vertex(k)->info();
      tv[4 * t + k] = v;
      tn[4 * t + k] = c->neighbor(k)->info();
      vt[v] = t;
    }
  }
  return nt;
}
#endif

// One build of x by `what`; returns its tetrahedra (-1: not available).
long build(const std::string &what, const std::vector<double> &x) {
  const int n = static_cast<int>(x.size() / 3);
  const tessera::Points3 pts{x.data(), n, 3};
  if (what == "own") {
    long cells = 0;
    tessera::time_plain_delaunay_3d(pts, n, &cells);
    return cells;
  }
  if (what == "mesh3") {
    tessera::Mesh3 m;
    m.build(pts);
    return m.n_tets();
  }
#ifdef TESSERA_BENCH_CGAL
  if (what == "cgal") return cgal_plain(x);
  if (what == "mesh3-cgal") return cgal_mesh3(x);
#endif
  return -1;
}

}  // namespace

int bench_build3d(int argc, char **argv) {
  // argv[0] is "--build" or "--build-one".
  if (std::strcmp(argv[0], "--build-one") == 0) {
    if (argc < 4) {
      std::fprintf(stderr, "usage: bench_core3d --build-one WHAT SET N\n");
      return 1;
    }
    const std::vector<double> x = point_set(argv[2], std::atol(argv[3]));
    const long cells = std::string(argv[1]) == "none" ? 0 : build(argv[1], x);
    std::printf("%s %s %zu points: %ld tetrahedra\n", argv[1], argv[2], x.size() / 3, cells);
    return cells < 0;
  }
  const long max_n = argc > 1 ? std::atol(argv[1]) : 1000000;
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  std::printf("Tessera 3D Delaunay build against CGAL's: CPU microseconds per point, median of "
              "%d\n\n",
              repeats);
  std::printf("%-7s %8s %9s %9s %9s %11s %10s %10s\n", "set", "N", "own", "CGAL", "Mesh3",
              "Mesh3-CGAL", "tets", "CGAL tets");
  for (const std::string set : {"random", "bcc"})
    for (long target = 1000; target <= max_n; target *= 10) {
      const std::vector<double> x = point_set(set, target);
      const double n = static_cast<double>(x.size() / 3);
      double us[4] = {0, 0, 0, 0};
      long cells[2] = {0, -1};
      const char *what[4] = {"own", "cgal", "mesh3", "mesh3-cgal"};
      for (int w = 0; w < 4; ++w) {
        std::vector<double> t;
        for (int r = 0; r < repeats; ++r) {
          const double t0 = cpu_seconds();
          const long c = build(what[w], x);
          t.push_back(cpu_seconds() - t0);
          if (w < 2) cells[w] = c;
          if (c < 0) break;
        }
        us[w] = cells[w < 2 ? w : 1] < 0 && (w == 1 || w == 3) ? -1.0 : 1e6 * median(t) / n;
      }
      std::printf("%-7s %8.0f %9.3f %9.3f %9.3f %11.3f %10ld %10ld\n", set.c_str(), n, us[0], us[1],
                  us[2], us[3], cells[0], cells[1]);
      std::fflush(stdout);
    }
  std::printf("\n(-1: CGAL not built in)\n");
  return 0;
}
