// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The 2D incremental path (Mesh::advance: flips, cells kept from step to
// step) against a from-scratch triangulation on randomized degenerate
// input: a periodic patch of random points or a square grid, with a tight
// cluster or near-duplicates (widths 1e-2 .. 1e-8 of the spacing, above the
// separation limit), moved by small random steps (1e-3 .. 1e-12), possibly
// several times.  After each move the updated mesh's cells must equal a
// rebuild's (same neighbours across edges above round-off, areas and
// perimeters within the conditioning of the input), or advance() must ask
// for a rebuild.  Seeded and bounded
// (TESSERA_FUZZ_SCALE multiplies the count, TESSERA_FUZZ_SEED shifts it).

#include "test_util.h"
#include "tessera/mesh.h"
#include "tessera/tessellation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

namespace {

using testutil::Rng;

using Patch = testutil::PeriodicPatch;

// Neighbours across edges longer than tol, as a sorted list.
std::multiset<int> strong(const tessera::Tessellation &t, int c, double tol) {
  std::multiset<int> s;
  for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
    if (t.edge_length[k] > tol) s.insert(t.cell_neighbor[k]);
  return s;
}

// One input; returns a description of the mismatch, or "".
std::string one(uint64_t seed) {
  Rng rng(seed);
  Patch p;
  const int n0 = 6 + rng.below(30);
  p.L = std::sqrt(static_cast<double>(n0));
  // Random points, or a square grid (co-circular: four-fold vertices).
  const bool grid = rng.below(2);
  const int side = 3 + rng.below(4);
  if (grid) p.L = side;
  for (int i = 0; i < (grid ? side * side : n0); ++i) {
    if (grid) {
      p.own.push_back(i % side + 0.5);
      p.own.push_back(i / side + 0.5);
    } else {
      p.own.push_back(rng.uniform(0.0, p.L));
      p.own.push_back(rng.uniform(0.0, p.L));
    }
  }
  // A cluster of k points round a point, width w, or near-duplicates.
  const double widths[] = {1e-2, 1e-4, 1e-6, 1e-8};
  const double w = widths[rng.below(4)];
  const int k = 1 + rng.below(5);
  // (round a random place, or round one of the points: near-duplicates)
  const int pick = rng.below(static_cast<int>(p.own.size() / 2));
  const double cx = rng.below(2) ? p.own[2 * pick] : rng.uniform(0.2, 0.8) * p.L;
  const double cy = rng.below(2) ? p.own[2 * pick + 1] : rng.uniform(0.2, 0.8) * p.L;
  for (int j = 0; j < k; ++j) {
    p.own.push_back(cx + w * rng.uniform(-1.0, 1.0));
    p.own.push_back(cy + w * rng.uniform(-1.0, 1.0));
  }
  p.n = static_cast<int>(p.own.size() / 2);
  p.images(0.6 * p.L);
  p.fill();
  tessera::Mesh inc;
  try {
    inc.build(p.points());
  } catch (const tessera::Error &) {
    return "";  // refused input (the scratch fuzzer checks those)
  }
  const double lo[2] = {-0.4 * p.L, -0.4 * p.L}, hi[2] = {1.4 * p.L, 1.4 * p.L};
  const double steps[] = {1e-3, 1e-6, 1e-9, 1e-12};
  const int moves = 1 + rng.below(4);
  tessera::Tessellation a;  // kept from move to move (advance()'s per-step path)
  inc.cells(p.points(), p.n, a);
  for (int m = 0; m < moves; ++m) {
    const double s = steps[rng.below(4)] * (rng.below(2) ? w : 1.0);
    for (int i = 0; i < p.n; ++i) {
      double &x = p.own[2 * i], &y = p.own[2 * i + 1];
      x = std::min(std::max(x + s * rng.uniform(-1.0, 1.0), 0.0), p.L);
      y = std::min(std::max(y + s * rng.uniform(-1.0, 1.0), 0.0), p.L);
    }
    p.fill();
    tessera::Mesh fresh;
    try {
      fresh.build(p.points());
    } catch (const tessera::Error &) {
      return "";
    }
    if (!inc.advance(p.points(), p.n, lo, hi, a)) {
      inc.build(p.points());
      inc.cells(p.points(), p.n, a);
      continue;
    }
    tessera::Tessellation b;
    fresh.cells(p.points(), p.n, b);
    if (a.unbounded_cell >= 0 || b.unbounded_cell >= 0) return "";
    if (!tessera::check_coverage(b, lo, hi).ok) continue;
    // Conditioning: S / d_min (periodic images are rounded translates).
    double dmin = p.L;
    for (int i = 0; i < p.n; ++i)
      for (int j = i + 1; j < p.n; ++j)
        dmin = std::min(dmin, std::hypot(p.own[2 * i] - p.own[2 * j], p.own[2 * i + 1] - p.own[2 * j + 1]));
    const double tol = 1e-13 * std::max(1.0, 2.0 * p.L / dmin);
    for (int c = 0; c < p.n; ++c) {
      char msg[256];
      if (strong(a, c, 1e3 * tol) != strong(b, c, 1e3 * tol) ||
          std::fabs(a.area[c] - b.area[c]) > tol * p.L * p.L ||
          std::fabs(a.perimeter[c] - b.perimeter[c]) > tol * p.L) {
        std::snprintf(msg, sizeof msg,
                      "seed %llu move %d cell %d: area %.17g vs %.17g, perimeter %.17g vs %.17g "
                      "(width %g, step %g, n %d)",
                      static_cast<unsigned long long>(seed), m, c, a.area[c], b.area[c],
                      a.perimeter[c], b.perimeter[c], w, s, p.n);
        return msg;
      }
    }
  }
  return "";
}

int count(int base) {
  const char *s = std::getenv("TESSERA_FUZZ_SCALE");
  return s ? static_cast<int>(base * std::atof(s)) : base;
}
uint64_t first_seed() {
  const char *e = std::getenv("TESSERA_FUZZ_SEED");
  return e ? std::strtoull(e, nullptr, 10) : 1;
}

TEST(IncrementalFuzz, NearDuplicateClustersMatchARebuild) {
  const uint64_t s0 = first_seed();
  int failures = 0;
  for (int i = 0; i < count(3000) && failures < 5; ++i) {
    const std::string r = one(s0 + i);
    if (!r.empty()) {
      ADD_FAILURE() << r;
      ++failures;
    }
  }
}

}  // namespace
