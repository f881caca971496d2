// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Counter-based random numbers (used by fix polarity): a value depends only on
// (seed, atom ID, timestep, stream), not on the MPI rank or the order of atoms,
// so runs on any number of ranks and continued runs draw the same numbers.
// splitmix64's finaliser as the hash; Gaussians by Marsaglia and Tsang's
// ziggurat (128 layers) on a counter-based stream per (seed, atom, step).
#pragma once

#include <cmath>
#include <cstdint>

namespace tessera {
namespace rng {

inline uint64_t mix(uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// One uniform number in (0, 1) per (seed, tag, step, stream).
inline double uniform01(uint64_t seed, uint64_t tag, uint64_t step, uint64_t stream) {
  const uint64_t h = mix(mix(mix(mix(seed) ^ tag) ^ step) ^ stream);
  return ((h >> 11) + 0.5) * (1.0 / 9007199254740992.0);  // in (0, 1)
}

// The ziggurat's tables: layer boundaries kn (scaled to 2^31), widths wn and
// the density fn at the layer edges.
struct Ziggurat {
  double kn[128], wn[128], fn[128];
  Ziggurat() {
    const double m1 = 2147483648.0;
    double dn = 3.442619855899, tn = dn;
    const double vn = 9.91256303526217e-3;
    const double q = vn / std::exp(-0.5 * dn * dn);
    kn[0] = (dn / q) * m1;
    kn[1] = 0.0;
    wn[0] = q / m1;
    wn[127] = dn / m1;
    fn[0] = 1.0;
    fn[127] = std::exp(-0.5 * dn * dn);
    for (int i = 126; i >= 1; i--) {
      dn = std::sqrt(-2.0 * std::log(vn / dn + std::exp(-0.5 * dn * dn)));
      kn[i + 1] = (dn / tn) * m1;
      tn = dn;
      fn[i] = std::exp(-0.5 * dn * dn);
      wn[i] = dn / m1;
    }
  }
};

inline const Ziggurat ziggurat;  // built once, when the program or library is loaded

// The stream of one (seed, tag, step): hashes of a counter.
struct Stream {
  uint64_t base, k;
  uint64_t next() { return mix(base ^ (++k * 0x632be59bd9b4e019ULL)); }
  double uniform() { return ((next() >> 11) + 0.5) * (1.0 / 9007199254740992.0); }
};

// One Gaussian number of the stream of (seed, tag, step), written as one
// loop: the definition, and the oracle of gaussian() below.
inline double gaussian_reference(uint64_t seed, uint64_t tag, uint64_t step) {
  const Ziggurat &z = ziggurat;
  Stream s{mix(mix(mix(seed) ^ tag) ^ step), 0};
  for (;;) {
    const int32_t hz = static_cast<int32_t>(static_cast<uint32_t>(s.next()));
    const int iz = hz & 127;
    const double ahz = std::fabs(static_cast<double>(hz));
    if (ahz < z.kn[iz]) return hz * z.wn[iz];
    const double x = hz * z.wn[iz];
    if (iz == 0) {  // the tail beyond r
      const double r = 3.442619855899;
      double xt, y;
      do {
        xt = -std::log(s.uniform()) / r;
        y = -std::log(s.uniform());
      } while (y + y < xt * xt);
      return hz > 0 ? r + xt : -r - xt;
    }
    if (z.fn[iz] + s.uniform() * (z.fn[iz - 1] - z.fn[iz]) < std::exp(-0.5 * x * x)) return x;
  }
}

// The ziggurat after a first draw hz of the stream s that the fast path of
// gaussian_mixed() did not accept (about 1.2 % of the calls): the same steps
// as gaussian_reference from there on.
[[gnu::noinline]] inline double gaussian_rest(Stream s, int32_t hz) {
  const Ziggurat &z = ziggurat;
  for (;;) {
    const int iz = hz & 127;
    const double ahz = std::fabs(static_cast<double>(hz));
    if (ahz < z.kn[iz]) return hz * z.wn[iz];
    const double x = hz * z.wn[iz];
    if (iz == 0) {  // the tail beyond r
      const double r = 3.442619855899;
      double xt, y;
      do {
        xt = -std::log(s.uniform()) / r;
        y = -std::log(s.uniform());
      } while (y + y < xt * xt);
      return hz > 0 ? r + xt : -r - xt;
    }
    if (z.fn[iz] + s.uniform() * (z.fn[iz - 1] - z.fn[iz]) < std::exp(-0.5 * x * x)) return x;
    hz = static_cast<int32_t>(static_cast<uint32_t>(s.next()));
  }
}

// gaussian_reference(seed, tag, step) with mixed_seed = mix(seed) (hoisted
// out of loops over atoms): the first draw inline (a short loop body that a
// processor overlaps between atoms), the rare rest out of line.  The same
// numbers bit for bit.
inline double gaussian_mixed(uint64_t mixed_seed, uint64_t tag, uint64_t step) {
  Stream s{mix(mix(mixed_seed ^ tag) ^ step), 0};
  const int32_t hz = static_cast<int32_t>(static_cast<uint32_t>(s.next()));
  const int iz = hz & 127;
  if (std::fabs(static_cast<double>(hz)) < ziggurat.kn[iz]) return hz * ziggurat.wn[iz];
  return gaussian_rest(s, hz);
}

inline double gaussian(uint64_t seed, uint64_t tag, uint64_t step) {
  return gaussian_mixed(mix(seed), tag, step);
}

}  // namespace rng
}  // namespace tessera
