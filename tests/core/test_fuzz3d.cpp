// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Randomized degenerate input for the 3D path (periodic_forces_3d):
// SC, BCC and FCC lattices (co-spherical centres: four-fold Voronoi edges,
// six-fold vertices) in orthogonal and tilted boxes, exact or jittered by
// 1e-12 .. 1e-3; coplanar sheets of centres; very few cells.  Seeded and of
// fixed size (Fuzz3D.*; TESSERA_FUZZ_SCALE multiplies the counts,
// TESSERA_FUZZ_SEED shifts the seeds).
//
// The rule checked: finite results that are right, or a tessera::Error whose
// reason the input really has.  "Right" is checked against properties of the
// exact answer:
//   * energy, virial, forces, volumes and surfaces finite, volumes > 0;
//   * the cells tile the box: volumes sum to the box volume, and for small
//     lattices every volume equals half-space clipping's (reference3d.h);
//   * forces sum to zero;
//   * on a sample, forces equal central differences of the energy where the
//     energy is smooth within the step (at a four-fold Voronoi edge it has
//     a kink; doc/model.md, "Reliability of the finite and 3D paths").
// On failure the input is printed (generator, seed, box, points).

#include "reference3d.h"
#include "test_util.h"

#include "tessera/voronoi3d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

using testutil::Rng;
using tessera::Box3;
constexpr double kEps = 2.220446049250313e-16;

struct Input3 {
  Box3 box;
  std::vector<double> xyz;
  std::vector<int> type;
  tessera::Model model{2};
  bool reference = false;  // compare each volume with half-space clipping
  int n() const { return static_cast<int>(xyz.size() / 3); }
  tessera::Points3 points() const { return tessera::Points3{xyz.data(), n(), 3}; }
};

std::string reproducer(const Input3 &in) {
  std::ostringstream s;
  s.precision(17);
  s << "box lo (" << in.box.lo[0] << ", " << in.box.lo[1] << ", " << in.box.lo[2] << ") hi ("
    << in.box.hi[0] << ", " << in.box.hi[1] << ", " << in.box.hi[2] << ") tilts " << in.box.xy
    << ' ' << in.box.xz << ' ' << in.box.yz << "; " << in.n() << " points (x y z type):\n";
  for (int i = 0; i < in.n(); ++i)
    s << "  " << in.xyz[3 * i] << ' ' << in.xyz[3 * i + 1] << ' ' << in.xyz[3 * i + 2] << ' '
      << in.type[i] << '\n';
  return s.str();
}

// Wrap by whole edge vectors into the box (false if round-off leaves the
// point on no side of a face: such a site is dropped by the generators).
bool wrap(const Box3 &box, double *x) {
  const tessera::Region3 r = box.region();
  const double *e[3] = {r.a, r.b, r.c};
  for (int pass = 0; pass < 12; ++pass) {
    double s[3];
    box.fractional(x, s);
    int k = 2;
    for (; k >= 0; --k)
      if (s[k] < 0.0 || s[k] >= 1.0) break;
    if (k < 0) return true;
    const double m = std::floor(s[k]);
    for (int d = 0; d < 3; ++d) x[d] -= (m == 0.0 ? 1.0 : m) * e[k][d];
  }
  return false;
}

void set_model(Rng &rng, Input3 &in, double v0) {
  for (auto &t : in.model.types) {
    t.K = rng.uniform(0.5, 1.5) / (v0 * v0);
    t.A0 = v0 * rng.uniform(0.8, 1.2);
    t.Gamma = rng.uniform(0.05, 0.3) / std::pow(v0, 4.0 / 3.0);
  }
  const double a = std::pow(v0, 2.0 / 3.0);
  in.model.set_lambda(0, 0, -rng.uniform(0.5, 1.5) / a);
  in.model.set_lambda(1, 1, -rng.uniform(0.5, 1.5) / a);
  in.model.set_lambda(0, 1, rng.uniform(0.0, 0.5) / a);
  in.type.resize(in.n());
  const bool uniform = rng.below(3) == 0;
  for (int &t : in.type) t = uniform ? 0 : rng.below(2);
}

double energy(const Input3 &in) {
  std::vector<double> f;
  return tessera::periodic_forces_3d(in.box, in.points(), in.type.data(), in.model, f).energy;
}

struct Stats {
  long inputs = 0, refused = 0, failures = 0, fd_checked = 0, fd_kink = 0;
  double worst_volume = 0.0;
  std::map<std::string, long> reasons;
};

bool has_duplicates(const Input3 &in) {
  for (int i = 0; i < in.n(); ++i)
    for (int j = i + 1; j < in.n(); ++j)
      if (in.xyz[3 * i] == in.xyz[3 * j] && in.xyz[3 * i + 1] == in.xyz[3 * j + 1] &&
          in.xyz[3 * i + 2] == in.xyz[3 * j + 2])
        return true;
  return false;
}

std::string check(const Input3 &in, Rng &rng, Stats &st) {
  tessera::Tessellation3 t;
  std::vector<double> f;
  tessera::ForceOutput3 out;
  try {
    t = tessera::tessellate_periodic_3d(in.box, in.points());
    out = tessera::periodic_forces_3d(in.box, in.points(), in.type.data(), in.model, f);
  } catch (const tessera::Error &e) {
    const std::string m = e.what();
    if (m.find("same position") != std::string::npos && has_duplicates(in)) {
      ++st.refused;
      ++st.reasons["coincident centres"];
      return "";
    }
    return "unexpected Error: " + m;
  }
  if (!std::isfinite(out.energy)) return "energy not finite";
  for (double v : out.virial)
    if (!std::isfinite(v)) return "virial not finite";
  const double V = in.box.volume();
  double vsum = 0.0, S = 0.0, fsum[3] = {0, 0, 0}, fabs_sum = 0.0;
  for (int i = 0; i < in.n(); ++i) {
    if (!(t.volume[i] > 0.0) || !std::isfinite(t.volume[i]) || !std::isfinite(t.surface[i])) {
      std::ostringstream s;
      s << "cell " << i << " has volume " << t.volume[i] << ", surface " << t.surface[i];
      return s.str();
    }
    vsum += t.volume[i];
    for (int d = 0; d < 3; ++d) {
      S = std::max(S, std::fabs(in.xyz[3 * i + d]));
      if (!std::isfinite(f[3 * i + d])) return "force not finite";
      fsum[d] += f[3 * i + d];
      fabs_sum += std::fabs(f[3 * i + d]);
    }
  }
  const double L = std::cbrt(V);
  const double cond = 1.0 + S / L;
  const double vtol = V * (1e-11 + 1e3 * kEps * cond);
  st.worst_volume = std::max(st.worst_volume, std::fabs(vsum - V) / vtol);
  if (std::fabs(vsum - V) > vtol) {
    std::ostringstream s;
    s.precision(17);
    s << "volumes sum to " << vsum << ", the box volume is " << V;
    return s.str();
  }
  if (in.reference) {
    const tessera::Region3 r = in.box.region();
    const ref3d::P e[3] = {{r.a[0], r.a[1], r.a[2]}, {r.b[0], r.b[1], r.b[2]}, {r.c[0], r.c[1], r.c[2]}};
    const auto ref = ref3d::cells(in.xyz, e);
    for (int i = 0; i < in.n(); ++i)
      if (std::fabs(t.volume[i] - ref[i].volume) > 1e-9 * V / in.n() * cond) {
        std::ostringstream s;
        s.precision(17);
        s << "cell " << i << " has volume " << t.volume[i] << ", half-space clipping gives "
          << ref[i].volume;
        return s.str();
      }
  }
  const double unit = (std::fabs(out.energy) + in.n()) / L;  // a force scale
  const double ftol = (1e-10 + 1e3 * kEps * cond) * (fabs_sum + unit);
  if (std::fabs(fsum[0]) > ftol || std::fabs(fsum[1]) > ftol || std::fabs(fsum[2]) > ftol) {
    std::ostringstream s;
    s << "forces sum to (" << fsum[0] << ", " << fsum[1] << ", " << fsum[2] << "), sum |F| "
      << fabs_sum;
    return s.str();
  }
  // Central differences (with a second, quarter step: smooth within it).
  const double fscale = fabs_sum / (3 * in.n()) + 1e-12;
  const double h = 1e-6 * L / std::cbrt(in.n());
  for (int k = 0; k < 2; ++k) {
    const int q = rng.below(3 * in.n());
    double e[5];
    bool ok = true;
    for (int j = -2; j <= 2 && ok; ++j) {
      if (j == 0) {
        e[2] = out.energy;
        continue;
      }
      Input3 p = in;
      p.xyz[q] += 0.5 * j * h;
      if (!wrap(p.box, &p.xyz[q - q % 3])) ok = false;
      try {
        if (ok) e[j + 2] = energy(p);
      } catch (const tessera::Error &) {
        ok = false;
      }
    }
    if (!ok) continue;
    const double noise = 64 * kEps * cond * (std::fabs(out.energy) + 1.0) / h;
    const double right = (e[4] - e[2]) / h, left = (e[2] - e[0]) / h;
    const double central = (e[4] - e[0]) / (2 * h), half = (e[3] - e[1]) / h;
    if (std::fabs(right - left) > 1e-4 * fscale + 8 * noise ||
        std::fabs(central - half) > 1e-5 * fscale + 8 * noise) {
      ++st.fd_kink;
      continue;
    }
    ++st.fd_checked;
    if (std::fabs(f[q] + central) > 1e-5 * fscale + 8 * noise) {
      std::ostringstream s;
      s.precision(12);
      s << "force component " << q << " is " << f[q] << ", central difference " << -central
        << " (one-sided " << -right << ", " << -left << "; mean |F| " << fscale << ")";
      return s.str();
    }
  }
  return "";
}

const std::vector<std::array<double, 3>> kBases[3] = {
    {{0, 0, 0}},
    {{0, 0, 0}, {0.5, 0.5, 0.5}},
    {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}}};

// SC, BCC or FCC, m^3 conventional cells of edge a, lower corner at a random
// (often not binary-exact) offset; the box orthogonal, tilted by a lattice
// vector (still a period), or tilted at random; jitter 0 or 1e-12 .. 1e-3.
void gen_lattice(Rng &rng, Input3 &in) {
  const int kind = rng.below(3);
  const int m = 1 + rng.below(kind == 2 ? 2 : 3);
  const double a = rng.below(2) ? 1.0 : rng.uniform(0.5, 2.0);
  const double lo = rng.below(2) ? 0.0 : rng.uniform(-5, 5);
  for (int d = 0; d < 3; ++d) {
    in.box.lo[d] = lo;
    in.box.hi[d] = lo + m * a;
  }
  const int tilt = rng.below(3);
  double *tilts[3] = {&in.box.xy, &in.box.xz, &in.box.yz};
  for (double *tv : tilts) {
    if (tilt == 1 && rng.below(2)) *tv = a * (rng.below(3) - 1);
    if (tilt == 2 && rng.below(2)) *tv = m * a * rng.uniform(-0.5, 0.5);
  }
  const double jitter = rng.below(3) == 0 ? 0.0 : std::pow(10.0, rng.uniform(-12, -3));
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k)
        for (const auto &b : kBases[kind]) {
          double x[3] = {lo + (i + b[0]) * a, lo + (j + b[1]) * a, lo + (k + b[2]) * a};
          for (double &v : x) v += jitter * a * rng.uniform(-1, 1);
          if (wrap(in.box, x)) in.xyz.insert(in.xyz.end(), x, x + 3);
        }
  in.reference = in.n() <= 32 && tilt != 2;
  set_model(rng, in, in.box.volume() / std::max(1, in.n()));
}

// Sheets: 2..4 planes of constant z (exactly equal), random points in each.
void gen_sheets(Rng &rng, Input3 &in) {
  const double L = rng.uniform(1.0, 3.0);
  for (int d = 0; d < 3; ++d) {
    in.box.lo[d] = rng.uniform(-1, 1);
    in.box.hi[d] = in.box.lo[d] + L * (d == 2 ? rng.uniform(0.5, 2.0) : 1.0);
  }
  if (rng.below(2)) in.box.xy = L * rng.uniform(-0.4, 0.4);
  const int sheets = 2 + rng.below(3), per = 2 + rng.below(6);
  for (int s = 0; s < sheets; ++s) {
    const double z = in.box.lo[2] + in.box.length(2) * (s + rng.uniform(0.0, 0.5)) / sheets;
    for (int k = 0; k < per; ++k) {
      double x[3] = {in.box.lo[0] + L * rng.uniform(), in.box.lo[1] + L * rng.uniform(), z};
      if (wrap(in.box, x)) in.xyz.insert(in.xyz.end(), x, x + 3);
    }
  }
  set_model(rng, in, in.box.volume() / std::max(1, in.n()));
}

// 1..6 cells in a box (orthogonal or tilted), possibly flat.
void gen_few(Rng &rng, Input3 &in) {
  for (int d = 0; d < 3; ++d) {
    in.box.lo[d] = rng.uniform(-2, 2);
    in.box.hi[d] = in.box.lo[d] + rng.uniform(0.3, 3.0);
  }
  if (rng.below(2)) {
    in.box.xy = in.box.length(0) * rng.uniform(-0.5, 0.5);
    in.box.xz = in.box.length(0) * rng.uniform(-0.5, 0.5);
    in.box.yz = in.box.length(1) * rng.uniform(-0.5, 0.5);
  }
  const tessera::Region3 r = in.box.region();
  const int n = 1 + rng.below(6);
  for (int i = 0; i < n; ++i) {
    const double s[3] = {rng.uniform(), rng.uniform(), rng.uniform()};
    double x[3];
    for (int d = 0; d < 3; ++d) x[d] = r.o[d] + s[0] * r.a[d] + s[1] * r.b[d] + s[2] * r.c[d];
    if (wrap(in.box, x)) in.xyz.insert(in.xyz.end(), x, x + 3);
  }
  set_model(rng, in, in.box.volume() / std::max(1, in.n()));
}

long count(long n) {
  const char *s = std::getenv("TESSERA_FUZZ_SCALE");
  return s ? std::max(1L, static_cast<long>(n * std::atof(s))) : n;
}
uint64_t seed(uint64_t s) {
  const char *e = std::getenv("TESSERA_FUZZ_SEED");
  return e ? s + 1000 * std::strtoull(e, nullptr, 10) : s;
}

void run(const char *name, void (*gen)(Rng &, Input3 &), long n, uint64_t seed0) {
  Stats st;
  for (long k = 0; k < n; ++k) {
    Rng rng(seed0 * 1000003 + k);
    Input3 in;
    gen(rng, in);
    if (in.n() == 0) continue;
    ++st.inputs;
    const std::string why = check(in, rng, st);
    if (!why.empty()) {
      ++st.failures;
      if (st.failures <= 3)
        ADD_FAILURE() << name << " input " << k << " (seed " << seed0 << "): " << why
                      << "\nreproducer: " << reproducer(in);
    }
  }
  std::printf("%s: %ld inputs, %ld refused with an Error, %ld failures; %ld finite-difference "
              "checks (%ld skipped at kinks); worst volume-sum error %.3g of its tolerance\n",
              name, st.inputs, st.refused, st.failures, st.fd_checked, st.fd_kink,
              st.worst_volume);
  for (const auto &r : st.reasons) std::printf("  refused %6ld x  %s\n", r.second, r.first.c_str());
  EXPECT_EQ(st.failures, 0);
}

}  // namespace

TEST(Fuzz3D, Lattices) { run("3D lattices", gen_lattice, count(40), seed(201)); }
TEST(Fuzz3D, CoplanarSheets) { run("3D coplanar sheets", gen_sheets, count(40), seed(202)); }
TEST(Fuzz3D, FewCells) { run("3D few cells", gen_few, count(80), seed(203)); }
