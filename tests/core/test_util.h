// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Shared helpers for the core tests: reproducible random configurations,
// random energy parameters, and conversions between the reference and the core.
#pragma once

#include "reference.h"
#include "tessera/energy.h"
#include "tessera/tessellation.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <set>
#include <string>
#include <vector>

namespace testutil {

// Points in a periodic square box of side L (own: x y of the n points) and
// their images within a margin outside it (origin: whose image; shift: by how
// much); xy is the owned points then the images, as the core takes them.
struct PeriodicPatch {
  double L = 0.0;
  int n = 0;
  std::vector<double> own, shift, xy;
  std::vector<int> origin;
  void images(double margin) {
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int p = 0; p < n; ++p) {
          if (i == 0 && j == 0) continue;
          const double x = own[2 * p] + i * L, y = own[2 * p + 1] + j * L;
          if (x < -margin || x > L + margin || y < -margin || y > L + margin) continue;
          origin.push_back(p);
          shift.push_back(i * L);
          shift.push_back(j * L);
        }
  }
  // xy from own, the images rigidly attached to their owners.
  void fill() {
    xy.assign(own.begin(), own.end());
    for (size_t k = 0; k < origin.size(); ++k) {
      xy.push_back(own[2 * origin[k]] + shift[2 * k]);
      xy.push_back(own[2 * origin[k] + 1] + shift[2 * k + 1]);
    }
  }
  tessera::Points points() const { return {xy.data(), static_cast<int>(xy.size() / 2), 2}; }
};

// Small, fully specified generator (splitmix64) so that configurations do not
// depend on the standard library's distributions.
class Rng {
public:
  explicit Rng(uint64_t seed) : s_(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {}
  uint64_t next() {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  int below(int n) { return static_cast<int>(next() % static_cast<uint64_t>(n)); }

private:
  uint64_t s_;
};

struct Config {
  tessera::Box box;
  std::vector<double> xy;  // stride 2, inside [lo, hi)
  std::vector<int> type;
  int n() const { return static_cast<int>(xy.size() / 2); }
  tessera::Points points() const { return tessera::Points{xy.data(), n(), 2}; }
  reftess::RefBox refbox() const {
    reftess::RefBox b;
    b.xlo = box.lo[0];
    b.ylo = box.lo[1];
    b.lx = box.length(0);
    b.ly = box.length(1);
    return b;
  }
};

inline double min_image_dist2(const tessera::Box &box, double ax, double ay, double bx, double by) {
  const double lx = box.length(0), ly = box.length(1);
  double dx = ax - bx, dy = ay - by;
  dx -= lx * std::round(dx / lx);
  dy -= ly * std::round(dy / ly);
  return dx * dx + dy * dy;
}

// n random points in the box with pairwise (periodic) distance >= dmin; if
// near_edges, the first points are placed within 1e-9..1e-3 of the box faces
// and corners (some exactly on the lower faces).  Types are random in [0, ntypes).
inline Config random_config(int n, double xlo, double ylo, double lx, double ly, uint64_t seed,
                            double dmin, bool near_edges = true, int ntypes = 2) {
  Rng rng(seed);
  Config c;
  c.box = tessera::Box::rect(xlo, xlo + lx, ylo, ylo + ly);
  const double d2min = dmin * dmin;
  auto accept = [&](double x, double y) {
    if (!(x >= xlo && x < xlo + lx && y >= ylo && y < ylo + ly)) return false;
    for (int j = 0; j < c.n(); ++j) {
      if (min_image_dist2(c.box, x, y, c.xy[2 * j], c.xy[2 * j + 1]) < d2min) return false;
    }
    c.xy.push_back(x);
    c.xy.push_back(y);
    return true;
  };
  if (near_edges) {
    const double e[] = {0.0, 1e-9, 1e-6, 1e-3};
    for (int k = 0; k < 12 && c.n() < n; ++k) {
      const double d = e[k % 4];
      const double u = rng.uniform(), v = rng.uniform();
      switch (k % 6) {
        case 0: accept(xlo + d, ylo + u * ly); break;
        case 1: accept(xlo + lx - d - (d == 0 ? 1e-12 * lx : 0), ylo + u * ly); break;
        case 2: accept(xlo + u * lx, ylo + d); break;
        case 3: accept(xlo + u * lx, ylo + ly - d - (d == 0 ? 1e-12 * ly : 0)); break;
        case 4: accept(xlo + d, ylo + ly - 1e-7 * ly * v - 1e-12 * ly); break;
        default: accept(xlo + lx - 1e-7 * lx * v - 1e-12 * lx, ylo + d); break;
      }
    }
  }
  for (long tries = 0; c.n() < n; ++tries) {
    if (tries > 1000000L) break;
    accept(xlo + rng.uniform() * lx, ylo + rng.uniform() * ly);
  }
  c.type.resize(c.n());
  for (int &t : c.type) t = rng.below(ntypes);
  return c;
}

// Condition number of the geometry: box size over the smallest (periodic)
// distance between two points.  Periodic images are rounded translates, so a
// Voronoi vertex of two points at distance d is only defined to about
// eps * L / d times the vertex's distance from them; tolerances scale with it.
inline double conditioning(const Config &c) {
  double d2 = 1e300;
  for (int i = 0; i < c.n(); ++i)
    for (int j = i + 1; j < c.n(); ++j)
      d2 = std::min(d2, min_image_dist2(c.box, c.xy[2 * i], c.xy[2 * i + 1], c.xy[2 * j],
                                        c.xy[2 * j + 1]));
  const double L = std::max({c.box.length(0), c.box.length(1), std::abs(c.box.lo[0]),
                             std::abs(c.box.lo[1]), std::abs(c.box.hi[0]), std::abs(c.box.hi[1])});
  return L / std::sqrt(d2);
}

// Smallest non-zero feature of the reference tessellation: the shortest edge.
inline double shortest_edge(const std::vector<reftess::RefCell> &cells) {
  double m = 1e300;
  for (const auto &c : cells)
    for (const auto &e : c.edges) m = std::min(m, e.length);
  return m;
}

// Random 2-type parameters: K, A0, Gamma > 0 per type, Lambda of either sign per pair.
inline reftess::RefParams random_params(uint64_t seed, bool cell_tension, int ntypes = 2) {
  Rng rng(seed ^ 0xABCDEFull);
  reftess::RefParams p;
  p.cell_tension = cell_tension;
  for (int t = 0; t < ntypes; ++t) {
    p.K.push_back(rng.uniform(0.5, 1.5));
    p.A0.push_back(rng.uniform(0.7, 1.3));
    p.Gamma.push_back(rng.uniform(0.05, 0.5));
  }
  p.Lambda.assign(ntypes * ntypes, 0.0);
  for (int a = 0; a < ntypes; ++a)
    for (int b = a; b < ntypes; ++b) {
      double l = rng.uniform(-1.0, 1.0);
      if (a == 0 && b == 0) l = -std::abs(l) - 0.1;  // make sure both signs occur
      if (a == 0 && b == ntypes - 1 && ntypes > 1) l = std::abs(l) + 0.1;
      p.Lambda[a * ntypes + b] = p.Lambda[b * ntypes + a] = l;
    }
  return p;
}

inline tessera::Model to_model(const reftess::RefParams &p) {
  tessera::Model m(p.ntypes());
  for (int t = 0; t < p.ntypes(); ++t) {
    m.types[t].K = p.K[t];
    m.types[t].A0 = p.A0[t];
    m.types[t].Gamma = p.Gamma[t];
  }
  for (int a = 0; a < p.ntypes(); ++a)
    for (int b = a; b < p.ntypes(); ++b) m.set_lambda(a, b, p.Lambda[a * p.ntypes() + b]);
  m.tension = p.cell_tension ? tessera::Tension::Cell : tessera::Tension::Edge;
  return m;
}

// Owned points of cfg, then their periodic images (shifts -1..1) that lie
// within w of the box.
inline std::vector<double> with_images(const Config &cfg, double w, std::vector<int> *origin = nullptr) {
  std::vector<double> out = cfg.xy;
  if (origin) {
    origin->resize(cfg.n());
    std::iota(origin->begin(), origin->end(), 0);
  }
  const double lx = cfg.box.length(0), ly = cfg.box.length(1);
  for (int sx = -1; sx <= 1; ++sx)
    for (int sy = -1; sy <= 1; ++sy) {
      if (sx == 0 && sy == 0) continue;
      for (int i = 0; i < cfg.n(); ++i) {
        const double x = cfg.xy[2 * i] + sx * lx, y = cfg.xy[2 * i + 1] + sy * ly;
        if (x >= cfg.box.lo[0] - w && x <= cfg.box.hi[0] + w && y >= cfg.box.lo[1] - w &&
            y <= cfg.box.hi[1] + w) {
          out.push_back(x);
          out.push_back(y);
          if (origin) origin->push_back(i);
        }
      }
    }
  return out;
}

inline std::string lower(std::string s) {
  for (char &ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

inline double max_abs(const std::vector<double> &v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// The triangles of a tessellation as a set, each rotated to start at its
// smallest index (orientation kept): equal sets are the same triangulation.
inline std::set<std::array<int, 3>> triangle_set(const tessera::Tessellation &t) {
  std::set<std::array<int, 3>> s;
  for (auto tri : t.triangles) {
    const int k = static_cast<int>(std::min_element(tri.begin(), tri.end()) - tri.begin());
    s.insert({tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]});
  }
  return s;
}

// Two cell types with face tensions of both signs, fixed values (the 3D
// four-fold and reliability tests): K 1 and 0.8, Gamma 0.2 and 0.15, Lambda
// -0.6 (0-0), -0.4 (1-1) and 0.3 (0-1); the preferred volumes a0, a1 fit each
// test's cell size.
inline tessera::Model two_types_fixed(double a0, double a1) {
  tessera::Model m(2);
  m.types[0].K = 1.0;
  m.types[0].A0 = a0;
  m.types[0].Gamma = 0.2;
  m.types[1].K = 0.8;
  m.types[1].A0 = a1;
  m.types[1].Gamma = 0.15;
  m.set_lambda(0, 0, -0.6);
  m.set_lambda(1, 1, -0.4);
  m.set_lambda(0, 1, 0.3);
  return m;
}

}  // namespace testutil
