// Tessera benchmark.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The 3D per-step path: a jittered BCC tissue (lattice constant 1, so one
// cell per 1/2 volume, cell size s = 2^(-1/3) = 0.79; jitter 0.1 s) of N owned
// points in a periodic box, with their periodic images within 2.5 of the box
// as ghosts, whose centres take random steps of about 0.01 s per step.  Per
// step and per owned cell, in microseconds (median over the steps):
//
//   rebuild   tessellate_local_3d (Tessera's Delaunay tetrahedralisation of
//             owned and ghost points from scratch, then the cells);
//   update    Mesh3::update (the flips), region of interest the box grown
//             by 1.5;
//   cells     Mesh3::cells (the Tessellation3 from the kept tetrahedra);
//   mesh3     update + cells, with a build() + cells() when update fails;
//   forces    compute_forces_3d on it (the same for both, for scale);
//   plain     one plain Delaunay tetrahedralisation of the N owned points
//             alone (time_plain_delaunay_3d, Tessera's own), the yardstick.
//
// Also flips per step, exact predicate calls per step, rebuilds, and memory
// per owned cell: the Mesh3 arrays and the Tessellation3 (capacities).
//
// Times are CPU times of the thread (clock_gettime(CLOCK_THREAD_CPUTIME_ID)),
// the plain triangulation's included.
//
//   bench_core3d [max_N] [steps] [--mesh-only]   (default 100000; steps 20)
//   bench_core3d --build [max_N] [repeats]       (bench_build3d.cpp: the
//                                                 from-scratch build against CGAL's)
#include "tessera/energy.h"
#include "tessera/mesh3d.h"
#include "tessera/voronoi3d.h"

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_util.h"

namespace {

using namespace bench_util;

// CPU time of this thread: the machine may be shared, wall time would count
// the other processes' share.
double now_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double gauss(uint64_t &s) {
  const double u = std::max(uniform(s), 1e-300), v = uniform(s);
  return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v);
}

size_t tess_bytes(const tessera::Tessellation3 &t) {
  return t.tets.capacity() * sizeof(t.tets[0]) + t.vertices.capacity() * sizeof(t.vertices[0]) +
         t.radius.capacity() * sizeof(double) +
         (t.cell_offset.capacity() + t.face_neighbor.capacity() + t.face_offset.capacity() +
          t.face_vertex.capacity()) *
             sizeof(int) +
         (t.face_area.capacity() + t.volume.capacity() + t.surface.capacity()) * sizeof(double);
}

}  // namespace

int bench_build3d(int argc, char **argv);  // bench_build3d.cpp

int main(int argc, char **argv) {
  if (argc > 1 && (std::string(argv[1]) == "--build" || std::string(argv[1]) == "--build-one"))
    return bench_build3d(argc - 1, argv + 1);
  long max_n = argc > 1 ? std::atol(argv[1]) : 100000;
  const int steps_arg = argc > 2 ? std::atoi(argv[2]) : 20;
  // --mesh-only: no rebuild column (for profiling Mesh3 alone).
  const bool mesh_only = argc > 3 && std::string(argv[3]) == "--mesh-only";
  if (max_n < 16 || steps_arg < 1) {
    std::fprintf(stderr, "usage: %s [max_N >= 16] [steps >= 1]\n", argv[0]);
    return 1;
  }
  tessera::Model model;
  model.types[0].K = 1.0;
  model.types[0].A0 = 0.5;
  model.types[0].Gamma = 0.1;
  const double cell = std::cbrt(0.5), margin = 2.5, roi = 1.5;
  std::printf("Tessera 3D per-step benchmark: jittered BCC (jitter 0.1 s), steps of 0.01 s, "
              "images within %.1f, region of interest +%.1f\n",
              margin, roi);
  std::printf("microseconds per owned cell and step, median over the steps\n\n");
  std::printf("%8s %8s %5s %9s %9s %9s %9s %9s %9s %8s %8s %6s %9s %9s\n", "N", "points", "steps",
              "rebuild", "update", "cells", "mesh3", "forces", "plain", "flips", "exact", "rebld",
              "mesh B/c", "tess B/c");
  double checksum = 0.0;
  for (long target = 1000; target <= max_n; target *= 10) {
    const int m = static_cast<int>(std::lround(std::cbrt(target / 2.0)));
    const double L = m;
    uint64_t seed = 12345 + target;
    std::vector<double> own;
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b)
        for (int c = 0; c < m; ++c)
          for (int q = 0; q < 2; ++q) {
            const double base[3] = {a + 0.5 * q + 0.25, b + 0.5 * q + 0.25, c + 0.5 * q + 0.25};
            for (int d = 0; d < 3; ++d) own.push_back(base[d] + 0.1 * cell * (2.0 * uniform(seed) - 1.0));
          }
    const int n = static_cast<int>(own.size() / 3);
    // Images: owner and shift, fixed for the run (the moves are small).
    std::vector<int> origin;
    std::vector<double> shift;
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        for (int c = -1; c <= 1; ++c) {
          if (a == 0 && b == 0 && c == 0) continue;
          const double s[3] = {a * L, b * L, c * L};
          for (int i = 0; i < n; ++i) {
            bool in = true;
            for (int d = 0; d < 3; ++d) {
              const double x = own[3 * i + d] + s[d];
              if (x < -margin || x > L + margin) in = false;
            }
            if (!in) continue;
            origin.push_back(i);
            shift.insert(shift.end(), s, s + 3);
          }
        }
    std::vector<double> xyz;
    auto positions = [&]() {
      xyz.assign(own.begin(), own.end());
      for (size_t g = 0; g < origin.size(); ++g)
        for (int d = 0; d < 3; ++d) xyz.push_back(own[3 * origin[g] + d] + shift[3 * g + d]);
    };
    positions();
    const int np = static_cast<int>(xyz.size() / 3);
    std::vector<int> type(np, 0);
    std::vector<double> f(3 * static_cast<size_t>(np));
    const double lo[3] = {-roi, -roi, -roi}, hi[3] = {L + roi, L + roi, L + roi};

    tessera::Mesh3 mesh;
    tessera::Tessellation3 t;
    mesh.build(tessera::Points3{xyz.data(), np, 3});
    mesh.cells(tessera::Points3{xyz.data(), np, 3}, n, t);
    const int steps = target >= 100000 ? std::max(3, steps_arg / 4) : steps_arg;
    std::vector<double> t_reb, t_upd, t_cel, t_mesh, t_for;
    long flips = 0, exact = 0;
    int rebuilds = 0;
    double max_dv = 0.0;
    for (int s = 0; s < steps; ++s) {
      for (double &x : own) x += 0.01 * cell / std::sqrt(3.0) * gauss(seed);
      positions();
      const tessera::Points3 pts{xyz.data(), np, 3};
      double t0 = now_seconds();
      const tessera::Tessellation3 ref =
          mesh_only ? tessera::Tessellation3() : tessera::tessellate_local_3d(pts, n);
      double t1 = now_seconds();
      t_reb.push_back(t1 - t0);
      t0 = now_seconds();
      const bool ok = mesh.update(pts, lo, hi);
      t1 = now_seconds();
      if (ok) {
        mesh.cells(pts, n, t);
      } else {
        ++rebuilds;
        mesh.build(pts);
        mesh.cells(pts, n, t);
      }
      const double t2 = now_seconds();
      if (ok) {
        t_upd.push_back(t1 - t0);
        t_cel.push_back(t2 - t1);
      }
      t_mesh.push_back(t2 - t0);
      flips += mesh.flips_last_update();
      exact += mesh.exact_tests();
      std::fill(f.begin(), f.end(), 0.0);
      t0 = now_seconds();
      const tessera::ForceOutput3 out = tessera::compute_forces_3d(t, pts, type.data(), model, f.data(), 3);
      t_for.push_back(now_seconds() - t0);
      checksum += out.energy;
      if (!mesh_only)
        for (int c = 0; c < n; ++c) max_dv = std::max(max_dv, std::fabs(t.volume[c] - ref.volume[c]));
    }
    std::vector<double> t_plain;
    for (int r = 0; r < 3; ++r) {
      const double t0 = now_seconds();
      tessera::time_plain_delaunay_3d(tessera::Points3{own.data(), n, 3}, n);
      t_plain.push_back(now_seconds() - t0);
    }
    const double us = 1e6 / n;
    std::printf("%8d %8d %5d %9.2f %9.2f %9.2f %9.2f %9.2f %9.2f %8.1f %8.1f %6d %9.0f %9.0f\n", n, np,
                steps, median(t_reb) * us, median(t_upd) * us, median(t_cel) * us,
                median(t_mesh) * us, median(t_for) * us, median(t_plain) * us,
                static_cast<double>(flips) / steps, static_cast<double>(exact) / steps, rebuilds,
                static_cast<double>(mesh.memory_bytes()) / n, static_cast<double>(tess_bytes(t)) / n);
    if (max_dv > 1e-10) std::printf("  WARNING: largest volume difference to the rebuild %.3g\n", max_dv);
  }
  std::printf("\n(checksum %.6g)\n", checksum);
  return 0;
}
