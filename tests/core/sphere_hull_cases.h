// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// A table of point sets on the unit sphere for the tests of the sphere's own convex
// hull (test_sphere_hull.cpp: exact brute-force checks; test_sphere_cgal.cpp: against
// CGAL): random points on the sphere and on caps, the Platonic solids and the
// cuboctahedron axis-aligned (co-planar faces exactly) and turned (co-planar to
// round-off), co-circular points (drums: two circles as faces; one circle turned,
// whose near-flat hull leaves no double-precision point strictly inside the first
// tetrahedron), near duplicates, clusters, and jitter from 1e-15 to 1e-6.
// Directions as the core rounds them, except where a circle must keep one z.
#pragma once

#include "sphere_test_util.h"
#include "test_util.h"

#include <cmath>
#include <string>
#include <vector>

namespace spherehull {

using spheretest::W;

struct HullCase {
  std::string name;
  std::vector<double> dir;  // unit directions, 3 per point
  bool may_be_flat = false; // points of one circle: on one plane unless rounding lifts them
  int n() const { return static_cast<int>(dir.size() / 3); }
};

inline W random_dir(testutil::Rng &rng, double zmin = -1.0, double zmax = 1.0) {
  const double z = rng.uniform(zmin, zmax), ph = rng.uniform(0.0, 2.0 * spheretest::kPi);
  const double s = std::sqrt(1.0 - z * z);
  return {s * std::cos(ph), s * std::sin(ph), z};
}

// Turn by three angles about the axes (all zero: unchanged, bit for bit).
inline W turn(W v, const double a[3]) {
  if (a[0] == 0.0 && a[1] == 0.0 && a[2] == 0.0)
    return v;
  v = {v.x, std::cos(a[0]) * v.y - std::sin(a[0]) * v.z,
       std::sin(a[0]) * v.y + std::cos(a[0]) * v.z};
  v = {std::cos(a[1]) * v.x + std::sin(a[1]) * v.z, v.y,
       -std::sin(a[1]) * v.x + std::cos(a[1]) * v.z};
  return {std::cos(a[2]) * v.x - std::sin(a[2]) * v.y, std::sin(a[2]) * v.x + std::cos(a[2]) * v.y,
          v.z};
}

// Unit directions, each turned, jittered and normalised as tessellate_sphere does
// ((p - c) / |p - c| with c = 0); with normalise false as they are, so that the
// points of a latitude circle keep one z exactly.
inline std::vector<double> directions(const std::vector<W> &v, const double a[3], double jitter,
                                      testutil::Rng &rng, bool normalise = true) {
  std::vector<double> d;
  for (const W &x : v) {
    W u = turn(x, a);
    if (jitter > 0.0)
      u = u + W{rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter),
                rng.uniform(-jitter, jitter)};
    const double r = normalise ? spheretest::norm(u) : 1.0;
    d.insert(d.end(), {(1.0 / r) * u.x, (1.0 / r) * u.y, (1.0 / r) * u.z});
  }
  return d;
}

inline std::vector<W> solid(int which) {
  std::vector<W> v;
  if (which == 0) { // cube
    for (int a : {-1, 1})
      for (int b : {-1, 1})
        for (int c : {-1, 1})
          v.push_back({1.0 * a, 1.0 * b, 1.0 * c});
  } else if (which == 1) { // octahedron
    for (int s : {-1, 1}) {
      v.push_back({1.0 * s, 0.0, 0.0});
      v.push_back({0.0, 1.0 * s, 0.0});
      v.push_back({0.0, 0.0, 1.0 * s});
    }
  } else {
    v = spheretest::icosahedron();
  }
  return v;
}

// A drum: circles of k points at z = h and z = -h (each exactly one plane, its
// points sharing one z), offset by half a step or aligned, and m random points
// between them: the circles are faces of the hull, k-gons.
inline std::vector<W> drum(int k, double h, bool offset, int m, testutil::Rng &rng) {
  std::vector<W> v;
  const double s = std::sqrt(1.0 - h * h);
  for (int c = 0; c < 2; ++c)
    for (int q = 0; q < k; ++q) {
      const double ph = 2.0 * spheretest::kPi * (q + (offset && c ? 0.5 : 0.0)) / k;
      v.push_back({s * std::cos(ph), s * std::sin(ph), c ? -h : h});
    }
  for (int q = 0; q < m; ++q)
    v.push_back(random_dir(rng, -0.9 * h, 0.9 * h));
  return v;
}

// The table.  All cases have distinct directions and points off one plane, so each
// is a proper hull unless a near duplicate is hidden by round-off (only the
// "duplicate" cases come that close).
inline std::vector<HullCase> hull_cases() {
  std::vector<HullCase> cases;
  testutil::Rng rng(4242);
  const double none[3] = {0.0, 0.0, 0.0};
  auto angles = [&](double *a) {
    for (int k = 0; k < 3; ++k)
      a[k] = rng.uniform(0.0, 6.3);
  };
  for (int n : {4, 5, 9, 40, 150}) {
    std::vector<W> v;
    for (int i = 0; i < n; ++i)
      v.push_back(random_dir(rng));
    cases.push_back({"random " + std::to_string(n), directions(v, none, 0.0, rng)});
  }
  for (double zmin : {0.3, 0.99, 1.0 - 1e-5}) {
    std::vector<W> v;
    for (int i = 0; i < 40; ++i)
      v.push_back(random_dir(rng, zmin));
    cases.push_back({"cap z > " + std::to_string(zmin), directions(v, none, 0.0, rng)});
  }
  const char *solids[] = {"cube", "octahedron", "icosahedron"};
  for (int s = 0; s < 3; ++s)
    for (double jitter : {0.0, 1e-15, 1e-12, 1e-9, 1e-6}) {
      double a[3] = {0.0, 0.0, 0.0};
      if (jitter > 0.0)
        angles(a);
      cases.push_back({std::string(solids[s]) + " jitter " + std::to_string(jitter),
                       directions(solid(s), a, jitter, rng)});
      if (jitter == 0.0) {
        angles(a);
        cases.push_back({std::string(solids[s]) + " turned", directions(solid(s), a, 0.0, rng)});
      }
    }
  // The cuboctahedron ((+-1, +-1, 0) and permutations): squares and triangles.
  {
    std::vector<W> v;
    for (int a : {-1, 1})
      for (int b : {-1, 1}) {
        v.push_back({1.0 * a, 1.0 * b, 0.0});
        v.push_back({1.0 * a, 0.0, 1.0 * b});
        v.push_back({0.0, 1.0 * a, 1.0 * b});
      }
    cases.push_back({"cuboctahedron", directions(v, none, 0.0, rng)});
  }
  for (bool offset : {false, true})
    for (int m : {0, 30}) {
      double a[3];
      const std::string name = "drum " + std::to_string(offset) + " " + std::to_string(m);
      cases.push_back({name, directions(drum(8, 0.6, offset, m, rng), none, 0.0, rng, false)});
      angles(a);
      cases.push_back({name + " turned", directions(drum(8, 0.6, offset, m, rng), a, 0.0, rng)});
    }
  // One circle turned: flat to round-off, a hull with almost no inside.
  for (int trial = 0; trial < 6; ++trial) {
    std::vector<W> v;
    const double h = trial < 3 ? 0.0 : 0.6;
    for (int m = 0; m < 10; ++m) {
      const double ph = 0.6 * m + 0.1, s = std::sqrt(1.0 - h * h);
      v.push_back({s * std::cos(ph), s * std::sin(ph), h});
    }
    double a[3];
    angles(a);
    cases.push_back(
        {"circle of 10 trial " + std::to_string(trial), directions(v, a, 0.0, rng), true});
  }
  // One circle, turned, plus one or two points off it (a cone, or a double cone, on
  // a near-flat polygon), and two circles close together.
  for (int extra = 1; extra <= 2; ++extra)
    for (int trial = 0; trial < 4; ++trial) {
      std::vector<W> v;
      const double h = trial < 2 ? 0.0 : 0.6;
      for (int m = 0; m < 12; ++m) {
        const double ph = 0.5 * m + 0.1, s = std::sqrt(1.0 - h * h);
        v.push_back({s * std::cos(ph), s * std::sin(ph), h});
      }
      v.push_back(spheretest::unit(W{0.1, 0.2, 1.0}));
      if (extra == 2)
        v.push_back(spheretest::unit(W{-0.1, 0.3, -1.0}));
      double a[3];
      angles(a);
      cases.push_back(
          {"circle of 12 + " + std::to_string(extra) + " trial " + std::to_string(trial),
           directions(v, a, 0.0, rng)});
    }
  for (double gap : {1e-4, 1e-6}) {
    std::vector<W> v;
    for (int i = 0; i < 30; ++i)
      v.push_back(random_dir(rng));
    v.push_back(
        spheretest::unit(v[3] + gap * spheretest::unit(spheretest::cross(v[3], W{0.2, 0.9, 0.1}))));
    cases.push_back({"near duplicate " + std::to_string(gap), directions(v, none, 0.0, rng)});
  }
  {
    std::vector<W> v;
    for (int i = 0; i < 30; ++i)
      v.push_back(random_dir(rng));
    for (int q = 0; q < 8; ++q)
      v.push_back(spheretest::unit(
          v[0] + 1e-3 * W{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)}));
    cases.push_back({"cluster", directions(v, none, 0.0, rng)});
  }
  return cases;
}

} // namespace spherehull
