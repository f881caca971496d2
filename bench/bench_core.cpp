// Tessera benchmark.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Microseconds per cell for the periodic tessellation, the forces on it, and,
// as a yardstick, a from-scratch CGAL Delaunay triangulation of the same
// points (no periodicity, no Voronoi cells), for N random points at density 1
// in a periodic square box.  Median of a few repeats.
//
// Then the from-scratch triangulation alone, the core's against CGAL's, on
// the same points: random points, and a run's owned and ghost points (the
// jittered hexagonal tissue below with its images): the core's plain
// triangulator (time_plain_delaunay: spatial sort and insertion), the full
// Mesh::build (with the input checks and the renumbering for the cells),
// and CGAL's Delaunay_triangulation_2 (range insert, which sorts spatially
// too).  This thread's CPU time, median of the repeats.
//
// Then the per-step path of a run: a jittered hexagonal tissue (points in
// lattice order, i.e. spatially sorted as LAMMPS keeps atoms, plus their
// periodic images within 3 as ghosts) whose centres take random steps of
// 0.003 (the benchmark fluid's flip rate); each step Mesh::advance() (flips
// and cells) and compute_forces(), and the slow path update() + cells() on a
// second mesh for comparison.
//
// Then a step with forced folds (k cells jump): advance() with the local fold
// repair against the rebuild from scratch that every fold cost before.
//
//   bench_core [max_N] [--steps-only]     (default 1000000)
//   bench_core [max_N] --build-only       the from-scratch triangulation table
//       alone (own plain and Mesh::build against CGAL's Delaunay_triangulation_2)
//   bench_core --triangulate WHAT KIND N  (one triangulation, for instruction
//       counts under valgrind --tool=callgrind: WHAT = none (the points
//       only), plain, build or cgal; KIND = random or tissue)
#include "tessera/energy.h"
#include "tessera/mesh.h"
#include "tessera/tessellation.h"

#ifdef TESSERA_BENCH_CGAL
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <ctime>
#include <vector>

#include "bench_util.h"

namespace {

using namespace bench_util;


double now_seconds() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

#ifdef TESSERA_BENCH_CGAL
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using DT = CGAL::Delaunay_triangulation_2<Kernel>;

// CGAL's plain triangulation of points 0..n-1 (the copy into CGAL's points
// not timed); returns CPU seconds, the number of finite faces in *faces.
double cgal_seconds(const std::vector<double> &xy, int n, long *faces) {
  std::vector<DT::Point> cp;
  cp.reserve(n);
  for (int i = 0; i < n; ++i) cp.emplace_back(xy[2 * i], xy[2 * i + 1]);
  const double t0 = cpu_seconds();
  DT dt;
  dt.insert(cp.begin(), cp.end());
  const double t = cpu_seconds() - t0;
  *faces = static_cast<long>(dt.number_of_faces());
  return t;
}
#endif


// A jittered hexagonal tissue of about `target` cells at density 1 in lattice
// order (spatially sorted, as LAMMPS keeps atoms), with its periodic images
// within `margin` as ghosts (xy: owned, then images; fill() after moving own).
struct HexTissue {
  std::vector<double> own, shift, xy;
  std::vector<int> origin;
  int n = 0;
  double lx = 0, ly = 0, margin = 3.0;
  uint64_t seed;  // the random stream, after the jitter (the steps go on with it)
  explicit HexTissue(long target) : seed(777 + static_cast<uint64_t>(target)) {
    const int ny = std::max(1, static_cast<int>(std::lround(std::sqrt(target / (2 * std::sqrt(3.0))))));
    const int nx = std::max(1, static_cast<int>(std::lround(target / (2.0 * ny))));
    const double a = std::sqrt(2.0 / std::sqrt(3.0));  // density 1
    lx = nx * a;
    ly = ny * a * std::sqrt(3.0);
    auto uni = [&]() { return static_cast<double>(splitmix(seed) >> 11) * 0x1.0p-53; };
    for (int j = 0; j < 2 * ny; ++j)
      for (int i = 0; i < nx; ++i) {
        own.push_back((i + 0.5 * (j % 2)) * a + 0.2 * (2 * uni() - 1));
        own.push_back(j * a * std::sqrt(3.0) / 2 + 0.2 * (2 * uni() - 1));
      }
    n = static_cast<int>(own.size() / 2);
    for (int sj = -1; sj <= 1; ++sj)
      for (int si = -1; si <= 1; ++si)
        for (int p = 0; p < n; ++p) {
          if (si == 0 && sj == 0) continue;
          const double x = own[2 * p] + si * lx, y = own[2 * p + 1] + sj * ly;
          if (x < -margin || x > lx + margin || y < -margin || y > ly + margin) continue;
          origin.push_back(p);
          shift.push_back(si * lx);
          shift.push_back(sj * ly);
        }
    fill();
  }
  void fill() {
    xy.assign(own.begin(), own.end());
    for (size_t k = 0; k < origin.size(); ++k) {
      xy.push_back(own[2 * origin[k]] + shift[2 * k]);
      xy.push_back(own[2 * origin[k] + 1] + shift[2 * k + 1]);
    }
  }
};

// The per-step table (see the top of the file).
double incremental_steps(long max_n, const tessera::Model &model) {
  std::printf("\nPer step of a moving tissue (hexagonal lattice, jitter 0.2, steps of 0.012, "
              "images within 3): microseconds per cell, median over the steps\n\n");
  std::printf("%9s %6s %12s %12s %12s %16s %10s %9s\n", "N", "steps", "advance", "forces",
              "sum", "update+cells", "flips", "rebuilds");
  double checksum = 0.0;
  for (long target : {1000L, 10000L, 100000L, 1000000L}) {
    if (target > max_n) break;
    HexTissue tissue(target);
    std::vector<double> &own = tissue.own, &xy = tissue.xy;
    const int n = tissue.n;
    const double margin = tissue.margin, lx = tissue.lx, ly = tissue.ly;
    uint64_t &seed = tissue.seed;
    auto uni = [&]() { return static_cast<double>(splitmix(seed) >> 11) * 0x1.0p-53; };
    auto fill = [&]() { tissue.fill(); };
    const int nall = static_cast<int>(xy.size() / 2);
    const tessera::Points pts{xy.data(), nall, 2};
    const double lo[2] = {-0.6 * margin, -0.6 * margin}, hi[2] = {lx + 0.6 * margin, ly + 0.6 * margin};
    tessera::Mesh fast, slow;
    tessera::Tessellation tf, ts;
    fast.build(pts);
    fast.cells(pts, n, tf);
    slow.build(pts);
    slow.cells(pts, n, ts);
    const std::vector<int> type(nall, 0);
    std::vector<double> f(2 * static_cast<size_t>(nall));
    const int warm = 10, steps = target >= 1000000 ? 20 : 50;
    std::vector<double> t_adv, t_force, t_slow;
    long flips = 0, rebuilds = 0;
    for (int step = 0; step < warm + steps; ++step) {
      for (double &c : own) c += 0.012 * (2 * uni() - 1) * std::sqrt(3.0);
      fill();
      double t0 = now_seconds();
      if (!fast.advance(pts, n, lo, hi, tf)) {
        ++rebuilds;
        fast.build(pts);
        fast.cells(pts, n, tf);
      }
      double t1 = now_seconds();
      std::fill(f.begin(), f.end(), 0.0);
      const tessera::ForceOutput out = tessera::compute_forces(tf, pts, type.data(), model, f.data(), 2);
      double t2 = now_seconds();
      if (!slow.update(pts, lo, hi)) slow.build(pts);
      slow.cells(pts, n, ts);
      double t3 = now_seconds();
      checksum += out.energy + ts.area[0];
      if (step < warm) continue;
      flips += fast.flips_last_update();
      t_adv.push_back(t1 - t0);
      t_force.push_back(t2 - t1);
      t_slow.push_back(t3 - t2);
    }
    const double us = 1e6 / n;
    std::printf("%9d %6d %12.3f %12.3f %12.3f %16.3f %10.1f %9ld\n", n, steps, median(t_adv) * us,
                median(t_force) * us, (median(t_adv) + median(t_force)) * us, median(t_slow) * us,
                static_cast<double>(flips) / steps, rebuilds);
    std::fflush(stdout);
  }
  return checksum;
}

// A step with forced folds: the tissue of incremental_steps() takes its small
// random steps and, in addition, k owned cells (k = 1, 10, 100) jump by 1 (one
// cell size) in a random direction, which folds triangles around each of them.
// Per step: Mesh::advance() with the local fold repair, and on a second mesh
// the same step with the repair off (advance() refuses, then build() + cells()
// from scratch, what every fold cost before).  CPU milliseconds per step (this
// thread's CPU time, steadier than wall time on a shared machine), median.
double fold_steps(long max_n) {
  std::printf("\nA step with k cells jumping (folds): CPU milliseconds per step (advance with "
              "local repair | repair off: advance refuses, build + cells), median over the "
              "steps\n\n");
  std::printf("%9s %5s %6s %12s %14s %10s %10s %9s %9s\n", "N", "k", "steps", "repair ms",
              "rebuild ms", "ratio", "repairs", "tri/rep", "rebuilds");
  double checksum = 0.0;
  for (long target : {10000L, 100000L, 1000000L}) {
    if (target > max_n) break;
    for (int k : {1, 10, 100}) {
      HexTissue tissue(target);
      uint64_t &seed = tissue.seed;
      auto uni = [&]() { return static_cast<double>(splitmix(seed) >> 11) * 0x1.0p-53; };
      const int n = tissue.n;
      const tessera::Points pts{tissue.xy.data(), static_cast<int>(tissue.xy.size() / 2), 2};
      const double m = 0.6 * tissue.margin;
      const double lo[2] = {-m, -m}, hi[2] = {tissue.lx + m, tissue.ly + m};
      tessera::Mesh fast, slow;
      slow.set_fold_repair(false);
      tessera::Tessellation tf, ts;
      fast.build(pts);
      fast.cells(pts, n, tf);
      slow.build(pts);
      slow.cells(pts, n, ts);
      const int steps = target >= 1000000 ? 5 : 15;
      std::vector<double> t_fast, t_slow;
      long repairs = 0, repaired = 0, rebuilds = 0;
      for (int step = 0; step < steps; ++step) {
        for (double &c : tissue.own) c += 0.012 * (2 * uni() - 1) * std::sqrt(3.0);
        // jumpers away from the box's edges (their images would jump too)
        for (int j = 0; j < k; ++j) {
          const int p = static_cast<int>(uni() * n);
          const double x = tissue.own[2 * p], y = tissue.own[2 * p + 1];
          if (std::min({x, y, tissue.lx - x, tissue.ly - y}) < 4.0) continue;
          const double phi = 6.283185307179586 * uni();  // a jump of one cell size
          tissue.own[2 * p] += std::cos(phi);
          tissue.own[2 * p + 1] += std::sin(phi);
        }
        tissue.fill();
        double t0 = cpu_seconds();
        if (!fast.advance(pts, n, lo, hi, tf)) {
          ++rebuilds;
          fast.build(pts);
          fast.cells(pts, n, tf);
        }
        double t1 = cpu_seconds();
        repairs += fast.repairs_last_update();
        repaired += fast.repaired_triangles_last_update();
        if (!slow.advance(pts, n, lo, hi, ts)) {
          slow.build(pts);
          slow.cells(pts, n, ts);
        }
        double t2 = cpu_seconds();
        checksum += tf.area[0] + ts.area[0];
        t_fast.push_back(t1 - t0);
        t_slow.push_back(t2 - t1);
      }
      if (t_fast.empty()) continue;
      std::printf("%9d %5d %6zu %12.3f %14.3f %10.3f %10.1f %9.1f %9ld\n", n, k, t_fast.size(),
                  median(t_fast) * 1e3, median(t_slow) * 1e3, median(t_fast) / median(t_slow),
                  static_cast<double>(repairs) / t_fast.size(),
                  repairs ? static_cast<double>(repaired) / repairs : 0.0, rebuilds);
      std::fflush(stdout);
    }
  }
  return checksum;
}

// The points of one benchmark case: n random points at density 1, or the
// hexagonal tissue of about n cells with its images (all of them, as
// Mesh::build sees them in a run).
std::vector<double> case_points(const std::string &kind, long n) {
  if (kind == "tissue") return HexTissue(n).xy;
  const double side = std::sqrt(static_cast<double>(n));
  uint64_t seed = 12345 + static_cast<uint64_t>(n);
  std::vector<double> xy(2 * n);
  for (double &v : xy) v = side * static_cast<double>(splitmix(seed) >> 11) * 0x1.0p-53;
  return xy;
}

// The from-scratch table (see the top of the file).
double build_table(long max_n) {
  std::printf("\nFrom-scratch triangulation of the same points: CPU microseconds per point, "
              "median of the repeats\n\n");
  std::printf("%9s %7s %5s %12s %12s %12s %12s %10s\n", "points", "kind", "reps", "plain",
              "Mesh::build", "CGAL DT2", "plain/CGAL", "triangles");
  double checksum = 0.0;
  for (long target : {1000L, 10000L, 100000L, 1000000L}) {
    if (target > max_n) break;
    for (const std::string kind : {"random", "tissue"}) {
      const std::vector<double> xy = case_points(kind, target);
      const int n = static_cast<int>(xy.size() / 2);
      const tessera::Points pts{xy.data(), n, 2};
      const int reps = n >= 1000000 ? 3 : n >= 100000 ? 5 : 15;
      std::vector<double> t_plain, t_build, t_cgal;
      long faces = 0, cgal_faces = 0;
      for (int r = 0; r < reps; ++r) {
        double t0 = cpu_seconds();
        tessera::time_plain_delaunay(pts, n, &faces);
        t_plain.push_back(cpu_seconds() - t0);
        t0 = cpu_seconds();
        {
          tessera::Mesh mesh;
          mesh.build(pts);
          checksum += mesh.n_points();
        }
        t_build.push_back(cpu_seconds() - t0);
#ifdef TESSERA_BENCH_CGAL
        t_cgal.push_back(cgal_seconds(xy, n, &cgal_faces));
#else
        t_cgal.push_back(std::nan(""));
        cgal_faces = faces;
#endif
      }
      if (faces != cgal_faces)
        std::printf("(triangle counts differ: %ld, CGAL %ld)\n", faces, cgal_faces);
      const double us = 1e6 / n;
      std::printf("%9d %7s %5d %12.3f %12.3f %12.3f %12.3f %10ld\n", n, kind.c_str(), reps,
                  median(t_plain) * us, median(t_build) * us, median(t_cgal) * us,
                  median(t_plain) / median(t_cgal), faces);
      std::fflush(stdout);
      checksum += static_cast<double>(faces);
    }
  }
  return checksum;
}

// One triangulation (--triangulate), for instruction counts.
int triangulate_once(const std::string &what, const std::string &kind, long n) {
  const std::vector<double> xy = case_points(kind, n);
  const int m = static_cast<int>(xy.size() / 2);
  const tessera::Points pts{xy.data(), m, 2};
  long faces = 0;
  if (what == "plain") {
    tessera::time_plain_delaunay(pts, m, &faces);
  } else if (what == "build") {
    tessera::Mesh mesh;
    mesh.build(pts);
    faces = mesh.n_points();
#ifdef TESSERA_BENCH_CGAL
  } else if (what == "cgal") {
    cgal_seconds(xy, m, &faces);
#endif
  } else if (what != "none") {
    std::fprintf(stderr, "--triangulate: WHAT is none, plain, build or cgal, got %s\n",
                 what.c_str());
    return 2;
  }
  std::printf("%s %s: %d points (%ld)\n", what.c_str(), kind.c_str(), m, faces);
  return 0;
}

}  // namespace

int main(int argc, char **argv) {
  if (argc == 5 && std::string(argv[1]) == "--triangulate")
    return triangulate_once(argv[2], argv[3], std::strtol(argv[4], nullptr, 10));
  long max_n = 1000000;
  bool steps_only = false, build_only = false;
  if (argc > 1 && std::string(argv[argc - 1]) == "--steps-only") {
    steps_only = true;
    --argc;
  } else if (argc > 1 && std::string(argv[argc - 1]) == "--build-only") {
    build_only = true;
    --argc;
  }
  if (argc > 1) {
    char *end = nullptr;
    max_n = std::strtol(argv[1], &end, 10);
    if (argc > 2 || end == argv[1] || *end != '\0' || max_n < 3) {
      std::fprintf(stderr, "usage: %s [max_N >= 3] [--steps-only | --build-only]\n", argv[0]);
      return 2;
    }
  }

  tessera::Model model(1);
  model.types[0].K = 1.0;
  model.types[0].A0 = 1.0;
  model.types[0].Gamma = 0.18;
  model.set_lambda(0, 0, -0.1);

  double checksum = 0;
  if (build_only) {
    std::printf("\n(checksum %.6g)\n", build_table(max_n));
    return 0;
  }
  if (!steps_only) {
  std::printf("Tessera core benchmark: random points, density 1, periodic square box\n");
  std::printf("times in microseconds per cell, median of the repeats\n\n");
  std::printf("%9s %5s %16s %16s %16s %12s\n", "N", "reps", "tessellate", "compute_forces",
              "CGAL DT2", "tess/CGAL");
  for (long n : {1000L, 10000L, 100000L, 1000000L}) {
    if (n > max_n) break;
    const int reps = n >= 1000000 ? 3 : n >= 100000 ? 5 : 9;
    const double side = std::sqrt(static_cast<double>(n));
    const tessera::Box box = tessera::Box::rect(0, side, 0, side);
    uint64_t seed = 12345 + static_cast<uint64_t>(n);
    std::vector<double> xy(2 * n);
    for (double &v : xy) v = side * static_cast<double>(splitmix(seed) >> 11) * 0x1.0p-53;
    const tessera::Points pts{xy.data(), static_cast<int>(n), 2};

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

#ifdef TESSERA_BENCH_CGAL
      long faces = 0;
      t_cgal.push_back(cgal_seconds(xy, static_cast<int>(n), &faces));
      checksum += static_cast<double>(faces);
#else
      t_cgal.push_back(std::nan(""));
#endif
    }
    const double us = 1e6 / static_cast<double>(n);
    const double mt = median(t_tess), mf = median(t_force), mc = median(t_cgal);
    std::printf("%9ld %5d %16.3f %16.3f %16.3f %12.2f\n", n, reps, mt * us, mf * us, mc * us,
                mt / mc);
    std::fflush(stdout);
  }
  }
  if (!steps_only) checksum += build_table(max_n);
  checksum += incremental_steps(max_n, model);
  checksum += fold_steps(max_n);
  std::printf("\n(checksum %.6g)\n", checksum);
  return 0;
}
