// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The 3D Delaunay builder's insertion order (described at the top of
// mesh3d_delaunay.cpp): rounds of random points, each along a Hilbert curve,
// and the random numbers the builder's walk shares.  Apart from the builder,
// which runs it once per triangulation before the insertions; a header
// included by mesh3d_delaunay.cpp alone (internal linkage, as when it was
// part of that file: the compiler inlines it into the builder as before).
// Internal to the core (not installed).
#pragma once

#include "tessera/voronoi3d.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace tessera {
namespace detail3 {
namespace {

// Hilbert index of a point of [0, 2^bits)^3 (J. Skilling's transpose
// algorithm, AIP Conf. Proc. 707, 381, 2004: the coordinates become the
// "transposed" index, whose bits are then interleaved).
uint64_t hilbert_key(uint32_t x, uint32_t y, uint32_t z, int bits) {
  uint32_t X[3] = {x, y, z};
  const uint32_t top = 1u << (bits - 1);
  for (uint32_t q = top; q > 1; q >>= 1) {
    const uint32_t mask = q - 1;
    for (int i = 0; i < 3; ++i) {
      if (X[i] & q) {
        X[0] ^= mask;
      } else {
        const uint32_t t = (X[0] ^ X[i]) & mask;
        X[0] ^= t;
        X[i] ^= t;
      }
    }
  }
  X[1] ^= X[0];
  X[2] ^= X[1];
  uint32_t t = 0;
  for (uint32_t q = top; q > 1; q >>= 1)
    if (X[2] & q)
      t ^= q - 1;
  for (uint32_t &v : X)
    v ^= t;
  uint64_t key = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (int i = 0; i < 3; ++i)
      key = (key << 1) | ((X[i] >> b) & 1u);
  return key;
}

uint64_t splitmix64(uint64_t &s) {
  uint64_t z = (s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// The insertion order of points 0..n-1 (see the top of mesh3d_delaunay.cpp): each
// point draws its round (the last with probability 1/2, the one before with
// 1/4, ...; the first takes what is left, a few dozen points), and one sort
// by (round, Hilbert index) orders them.
void insertion_order(const Points3 &pts, std::vector<int> &order) {
  const int n = pts.n;
  order.resize(n);
  std::iota(order.begin(), order.end(), 0);
  if (n < 2)
    return;
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k)
    lo[k] = hi[k] = pts.p(0)[k];
  for (int i = 1; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], pts.p(i)[k]);
      hi[k] = std::max(hi[k], pts.p(i)[k]);
    }
  const double ext = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  constexpr int kBits = 19; // 57 bits of Hilbert index, 6 of round above
  const double top = double((1u << kBits) - 1);
  const double scale = ext > 0.0 ? top / ext : 0.0;
  int rounds = 1;
  while (rounds < 60 && (n >> rounds) > 64)
    ++rounds;
  // A fixed seed: the same input is always inserted in the same order.
  uint64_t seed = 0x5EED3D5EEDull ^ static_cast<uint64_t>(n);
  struct Rec {
    uint64_t key;
    int i;
  };
  std::vector<Rec> rec(n);
  for (int i = 0; i < n; ++i) {
    uint32_t c[3];
    for (int k = 0; k < 3; ++k) {
      const double s = (pts.p(i)[k] - lo[k]) * scale;
      c[k] = static_cast<uint32_t>(std::min(std::max(s, 0.0), top));
    }
    const uint64_t u = splitmix64(seed) | (uint64_t(1) << 63);
    const int tz = __builtin_ctzll(u);
    const uint64_t round = static_cast<uint64_t>(rounds - 1 - std::min(tz, rounds - 1));
    rec[i] = {round << 57 | hilbert_key(c[0], c[1], c[2], kBits), i};
  }
  std::sort(rec.begin(), rec.end(), [](const Rec &a, const Rec &b) {
    return a.key < b.key || (a.key == b.key && a.i < b.i);
  });
  for (int i = 0; i < n; ++i)
    order[i] = rec[i].i;
}

} // namespace
} // namespace detail3
} // namespace tessera
