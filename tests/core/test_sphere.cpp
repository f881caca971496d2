// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The Voronoi model on a sphere: exact polyhedral configurations (areas and
// perimeters computed here from the solids' own geometry), independent slow
// oracles (empty circumcircle caps, Girard's angle excess), forces against
// central differences along geodesics, rotation invariance (no torque), the
// flat limit against the planar model, and parallel transport (holonomy).
#include "tessera/energy.h"
#include "tessera/sphere.h"
#include "tessera/tessellation.h"
#include "sphere_test_util.h"
#include "test_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace {

using tessera::Vec3;
using testutil::Rng;

using namespace spheretest;

// A random rotation (from a random unit quaternion).
struct Rotation {
  double m[3][3];
  explicit Rotation(Rng &rng) {
    double q[4], s = 0.0;
    do {
      s = 0.0;
      for (double &x : q) {
        x = rng.uniform(-1.0, 1.0);
        s += x * x;
      }
    } while (s > 1.0 || s < 0.01);
    for (double &x : q) x /= std::sqrt(s);
    const double a = q[0], b = q[1], c = q[2], d = q[3];
    const double r[3][3] = {{a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
                            {2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)},
                            {2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d}};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = r[i][j];
  }
  W operator()(W v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
};

// Points c + r_i * dir_i (r_i different from R: the input is projected).
std::vector<double> place(const Vec3 &c, const std::vector<W> &dirs, double R, Rng *rng = nullptr) {
  std::vector<double> xyz;
  for (const W &d : dirs) {
    const double r = rng ? R * rng->uniform(0.5, 2.0) : R;
    const W p = w3(c) + r * unit(d);
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  }
  return xyz;
}

const double kPhi = (1.0 + std::sqrt(5.0)) / 2.0;

// The regular dodecahedron dual to icosahedron(): its vertices are the
// directions of the icosahedron's face centres.
std::vector<W> dodecahedron() {
  std::vector<W> v;
  for (int a : {-1, 1})
    for (int b : {-1, 1}) {
      for (int c : {-1, 1}) v.push_back({1.0 * a, 1.0 * b, 1.0 * c});
      v.push_back({0.0, a * kPhi, b / kPhi});
      v.push_back({a * kPhi, b / kPhi, 0.0});
      v.push_back({b / kPhi, 0.0, a * kPhi});
    }
  return v;
}

// n directions uniform on the sphere, or on the cap z > zmin.
std::vector<W> random_directions(int n, Rng &rng, double zmin = -1.0) {
  std::vector<W> d;
  for (int i = 0; i < n; ++i) {
    const double z = rng.uniform(zmin, 1.0), ph = rng.uniform(0.0, 2.0 * kPi);
    const double s = std::sqrt(1.0 - z * z);
    d.push_back({s * std::cos(ph), s * std::sin(ph), z});
  }
  return d;
}

tessera::Model uniform_model(double K, double A0, double Gamma, double Lambda,
                             tessera::Tension tension = tessera::Tension::Edge) {
  tessera::Model m(1);
  m.types[0] = {K, A0, Gamma};
  m.set_lambda(0, 0, Lambda);
  m.tension = tension;
  return m;
}

tessera::Model random_model(Rng &rng, int ntypes, double A0, tessera::Tension tension) {
  tessera::Model m(ntypes);
  for (int a = 0; a < ntypes; ++a) {
    m.types[a] = {rng.uniform(0.5, 2.0), A0 * rng.uniform(0.7, 1.3), rng.uniform(0.1, 1.0)};
    for (int b = a; b < ntypes; ++b) m.set_lambda(a, b, rng.uniform(-1.0, 1.0));
  }
  m.tension = tension;
  return m;
}

std::string error_of(const std::function<void()> &f) {
  try {
    f();
  } catch (const tessera::Error &e) {
    return e.what();
  }
  return "";
}

tessera::SphereTessellation tess(const Vec3 &c, double R, const std::vector<double> &xyz,
                                 const long *ids = nullptr, bool reference_hull = false) {
  return tessera::tessellate_sphere(c, R, {xyz.data(), static_cast<int>(xyz.size() / 3), 3}, ids,
                                    reference_hull);
}

// The triangles as a sorted list, each rotated to start at its smallest index.
std::vector<std::array<int, 3>> canonical(const tessera::SphereTessellation &t) {
  std::vector<std::array<int, 3>> v;
  for (auto f : t.triangles) {
    while (f[0] > f[1] || f[0] > f[2]) f = {f[1], f[2], f[0]};
    v.push_back(f);
  }
  std::sort(v.begin(), v.end());
  return v;
}

// ---------------------------------------------------------------- errors

TEST(Sphere, ErrorsNameTheProblemAndThePoints) {
  const Vec3 c{0.5, -1.0, 2.0};
  const std::vector<W> ico = icosahedron();
  std::vector<double> xyz = place(c, ico, 1.5);
  const long ids[12] = {101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 111, 112};

  std::vector<double> three(xyz.begin(), xyz.begin() + 9);
  EXPECT_THAT(error_of([&] { tess(c, 1.5, three); }), testing::HasSubstr("at least 4 points, got 3"));

  std::vector<double> bad = xyz;
  bad[3 * 4 + 1] = std::nan("");
  EXPECT_THAT(error_of([&] { tess(c, 1.5, bad, ids); }), testing::HasSubstr("id 105 has a non-finite"));

  bad = xyz;  // point 7 on point 2's ray, farther out: the same projection
  for (int d = 0; d < 3; ++d) bad[3 * 7 + d] = (&c.x)[d] + 3.0 * (xyz[3 * 2 + d] - (&c.x)[d]);
  EXPECT_THAT(error_of([&] { tess(c, 1.5, bad); }),
              testing::HasSubstr("point 2 and point 7 project to the same point"));
  bad = place(Vec3{}, ico, 1.0);  // the same, the projections equal bit for bit
  bad.insert(bad.end(), {2.0 * bad[6], 2.0 * bad[7], 2.0 * bad[8]});
  EXPECT_THAT(error_of([&] { tess(Vec3{}, 1.0, bad); }),
              testing::HasSubstr("point 2 and point 12 project to the same point"));

  bad = xyz;
  bad[3 * 3] = c.x, bad[3 * 3 + 1] = c.y, bad[3 * 3 + 2] = c.z;
  EXPECT_THAT(error_of([&] { tess(c, 1.5, bad, ids); }), testing::HasSubstr("id 104 is at the centre"));

  EXPECT_THAT(error_of([&] { tess(c, -1.0, xyz); }), testing::HasSubstr("radius must be positive"));
  EXPECT_THAT(error_of([&] { tess(Vec3{0.0, std::nan(""), 0.0}, 1.0, xyz); }),
              testing::HasSubstr("centre must be finite"));

  // Eight points on one great circle, and six on a small circle.
  std::vector<W> ring;
  for (int k = 0; k < 8; ++k) ring.push_back({std::cos(0.7 * k + 0.1), std::sin(0.7 * k + 0.1), 0.0});
  EXPECT_THAT(error_of([&] { tess(c, 2.0, place(c, ring, 2.0)); }),
              testing::HasSubstr("all 8 points lie on one circle"));
  {
    // The same circle turned: the rounded directions are no longer exactly
    // coplanar, the hull is flat only to round-off.
    Rng rng(7);
    const Rotation rot(rng);
    std::vector<W> turned;
    for (const W &d : ring) turned.push_back(rot(d));
    EXPECT_THAT(error_of([&] { tess(c, 2.0, place(c, turned, 2.0, &rng)); }),
                testing::HasSubstr("all 8 points lie on one circle"));
  }
  ring.clear();
  for (int k = 0; k < 6; ++k) ring.push_back({0.6 * std::cos(1.0 * k), 0.6 * std::sin(1.0 * k), 0.8});
  EXPECT_THAT(error_of([&] { tess(Vec3{}, 1.0, place(Vec3{}, ring, 1.0)); }),
              testing::HasSubstr("all 6 points lie on one circle"));

  // Two points 1e-12 apart, and 1e-8: refused by both routes (the
  // Delaunay triangulation on the sphere, and the hull, where the point may
  // also be hidden by round-off), naming both.
  for (double gap : {1e-12, 1e-8})
    for (bool hull : {false, true}) {
      bad = place(Vec3{}, ico, 1.0);
      bad.insert(bad.end(), {bad[0], bad[1] + gap, bad[2]});
      EXPECT_THAT(error_of([&] { tess(Vec3{}, 1.0, bad, nullptr, hull); }),
                  testing::HasSubstr("point 0 and point 12 project to the same point"))
          << gap << " " << hull;
    }
  // 1e-6 apart: fine (a tiny cell between them).
  bad = place(Vec3{}, ico, 1.0);
  bad.insert(bad.end(), {bad[0], bad[1] + 1e-6, bad[2]});
  EXPECT_EQ(tess(Vec3{}, 1.0, bad).triangles.size(), 22u);
}

// ---------------------------------------------------------------- exact solids

TEST(Sphere, IcosahedronGivesTwelveRegularPentagonsAndNoForce) {
  Rng rng(11);
  const Vec3 c{0.3, -0.2, 1.7};
  const double R = 2.3;
  const Rotation rot(rng);
  std::vector<W> dirs;
  for (const W &d : icosahedron()) dirs.push_back(rot(d));
  const std::vector<double> xyz = place(c, dirs, R, &rng);
  const auto t = tess(c, R, xyz);

  // The poles are the directions of the dodecahedron's vertices; an edge of
  // a cell subtends the angle an edge of the regular dodecahedron subtends
  // at its centre: the smallest angle between two of its vertices.
  const std::vector<W> dod = dodecahedron();
  double edge_angle = kPi;
  for (size_t i = 0; i < dod.size(); ++i)
    for (size_t j = i + 1; j < dod.size(); ++j) edge_angle = std::min(edge_angle, angle(dod[i], dod[j]));
  EXPECT_NEAR(std::cos(edge_angle), std::sqrt(5.0) / 3.0, 1e-14);  // the textbook value
  // Girard: three cells at each vertex, so each interior angle is 2 pi / 3.
  const double girard = (5 * 2.0 * kPi / 3.0 - 3.0 * kPi) * R * R;

  ASSERT_EQ(t.n_points, 12);
  ASSERT_EQ(t.triangles.size(), 20u);
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ(t.cell_size(i), 5);
    EXPECT_EQ(t.coordination_number(i), 5);
    EXPECT_NEAR(t.area[i], 4.0 * kPi * R * R / 12.0, 1e-13 * R * R);
    EXPECT_NEAR(t.area[i], girard, 1e-13 * R * R);
    EXPECT_NEAR(t.perimeter[i], 5.0 * R * edge_angle, 1e-13 * R);
    for (int k = t.cell_offset[i]; k < t.cell_offset[i + 1]; ++k)
      EXPECT_NEAR(t.edge_length[k], R * edge_angle, 1e-13 * R);
  }
  // Every pole is a rotated dodecahedron vertex.
  for (size_t v = 0; v < t.vertex_direction.size(); ++v) {
    double best = kPi;
    for (const W &d : dod) best = std::min(best, angle(w3(t.vertex_direction[v]), rot(d)));
    EXPECT_LT(best, 1e-14);
  }

  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    const tessera::Model m = uniform_model(1.3, 0.9 * R * R, 0.4, -0.7, tension);
    const std::vector<int> type(12, 0);
    std::vector<double> f(36, 0.0);
    const auto out = tessera::sphere_forces(t, {xyz.data(), 12, 3}, type.data(), m, f.data(), 3);
    for (double x : f) EXPECT_NEAR(x, 0.0, 1e-13);
    EXPECT_NEAR(out.energy, tessera::sphere_energy(t, type.data(), m), 1e-12 * std::fabs(out.energy));
  }
}

TEST(Sphere, PentakisDodecahedronGivesTwelvePentagonsAndTwentyHexagons) {
  Rng rng(12);
  const Vec3 c{-1.0, 0.5, 0.25};
  const double R = 0.8;
  const Rotation rot(rng);
  std::vector<W> dirs;
  for (const W &d : icosahedron()) dirs.push_back(rot(d));
  for (const W &d : dodecahedron()) dirs.push_back(rot(d));
  const std::vector<double> xyz = place(c, dirs, R, &rng);
  const auto t = tess(c, R, xyz);
  ASSERT_EQ(t.triangles.size(), 60u);
  double total = 0.0;
  for (int i = 0; i < 32; ++i) {
    EXPECT_EQ(t.coordination_number(i), i < 12 ? 5 : 6) << i;
    total += t.area[i];
    // Congruent cells (the icosahedral group is transitive on each kind).
    EXPECT_NEAR(t.area[i], t.area[i < 12 ? 0 : 12], 1e-13);
    EXPECT_NEAR(t.perimeter[i], t.perimeter[i < 12 ? 0 : 12], 1e-13);
  }
  EXPECT_NEAR(total, 4.0 * kPi * R * R, 1e-13);
  EXPECT_NE(t.area[0], t.area[12]);
  // Each point lies on a 5- or 3-fold axis: a tangent force would have to be
  // invariant under that rotation, so it vanishes, even with two types.
  tessera::Model m(2);
  m.types[0] = {1.0, 0.1, 0.3};
  m.types[1] = {2.0, 0.12, 0.5};
  m.set_lambda(0, 0, -0.2);
  m.set_lambda(0, 1, 0.4);
  m.set_lambda(1, 1, -0.6);
  std::vector<int> type(32);
  for (int i = 0; i < 32; ++i) type[i] = i < 12 ? 0 : 1;
  std::vector<double> f(96, 0.0);
  tessera::sphere_forces(t, {xyz.data(), 32, 3}, type.data(), m, f.data(), 3);
  for (double x : f) EXPECT_NEAR(x, 0.0, 1e-13);
}

TEST(Sphere, CubeKeepsItsFourfoldVerticesAsZeroLengthEdges) {
  // Axis-aligned, then turned (the rounded directions of a face's four
  // points are then coplanar only to round-off, so the poles of its two
  // triangles differ by round-off, and that edge must still come out 0).
  Rng rng(13);
  for (int turned = 0; turned < 4; ++turned) {
    const Vec3 c{0.0, 0.0, 0.0};
    const double R = 1.7;
    const Rotation rot(rng);
    std::vector<W> dirs;
    for (int a : {-1, 1})
      for (int b : {-1, 1})
        for (int d : {-1, 1}) {
          const W x{1.0 * a, 1.0 * b, 1.0 * d};
          dirs.push_back(turned ? rot(x) : x);
        }
    const auto t = tess(c, R, place(c, dirs, R, turned ? &rng : nullptr));
    ASSERT_EQ(t.triangles.size(), 12u);  // each square face split in two
    for (int i = 0; i < 8; ++i) {
      // A spherical triangle with its corners on three orthogonal axes; a
      // face split through i's corner gives i one more vertex, at the same pole.
      EXPECT_EQ(t.coordination_number(i), 3);
      EXPECT_NEAR(t.area[i], kPi * R * R / 2.0, 1e-14);
      EXPECT_NEAR(t.perimeter[i], 3.0 * kPi / 2.0 * R, 1e-14);
      int zero = 0;
      for (int k = t.cell_offset[i]; k < t.cell_offset[i + 1]; ++k) zero += t.edge_length[k] == 0.0;
      EXPECT_EQ(zero, t.cell_size(i) - 3) << "turned " << turned;
    }
  }
}

// ---------------------------------------------------------------- oracles

// Girard's theorem on the polygon of distinct poles: area = (sum of interior
// angles - (m - 2) pi) R^2, angles from the tangent directions of the edges.
double girard_area(const tessera::SphereTessellation &t, int i) {
  std::vector<W> v;
  for (int k = t.cell_offset[i]; k < t.cell_offset[i + 1]; ++k)
    if (t.edge_length[k] > 0.0) v.push_back(w3(t.vertex_direction[t.cell_vertex[k]]));
  const int m = static_cast<int>(v.size());
  double sum = 0.0;
  for (int k = 0; k < m; ++k) {
    const W p = v[k], prev = v[(k + m - 1) % m], next = v[(k + 1) % m];
    const W to_prev = unit(prev - dot(prev, p) * p), to_next = unit(next - dot(next, p) * p);
    // Counter-clockwise polygon: the interior lies counter-clockwise from
    // the direction to the next vertex to the direction to the previous one.
    double a = std::atan2(dot(p, cross(to_next, to_prev)), dot(to_next, to_prev));
    if (a < 0) a += 2.0 * kPi;
    sum += a;
  }
  return (sum - (m - 2) * kPi) * t.R * t.R;
}

TEST(Sphere, RandomPointsMatchSlowOracles) {
  // The last two: points on a cap, the centre outside their hull (cells
  // reaching round the far side; poles that are not projected circumcentres).
  for (uint64_t seed : {1, 2, 3, 4, 5}) {
    Rng rng(100 + seed);
    const int n = seed == 1 ? 4 : seed == 2 ? 37 : seed == 3 ? 300 : seed == 4 ? 5 : 60;
    const Vec3 c{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)};
    const double R = rng.uniform(0.5, 5.0);
    const std::vector<W> dirs = random_directions(n, rng, seed >= 4 ? 0.6 : -1.0);
    const std::vector<double> xyz = place(c, dirs, R, &rng);
    const auto t = tess(c, R, xyz);
    // The two routes (triangulation on the sphere, or hull when the points
    // are on a cap) against the hull.
    const auto th = tess(c, R, xyz, nullptr, true);
    EXPECT_EQ(canonical(t), canonical(th)) << seed;
    ASSERT_EQ(static_cast<int>(t.triangles.size()), 2 * n - 4);
    double total = 0.0, sum_l = 0.0, sum_p = 0.0;
    for (int i = 0; i < n; ++i) {
      total += t.area[i];
      sum_p += t.perimeter[i];
      EXPECT_NEAR(t.area[i], girard_area(t, i), 1e-11 * R * R) << "seed " << seed << " cell " << i;
      EXPECT_NEAR(angle(w3(t.direction[i]), unit(dirs[i])), 0.0, 1e-15);
      for (int k = t.cell_offset[i]; k < t.cell_offset[i + 1]; ++k) {
        sum_l += t.edge_length[k];
        // The edge lies on the bisector of i and its neighbour.
        const W mid = unit(w3(t.vertex_direction[t.cell_vertex[k]]));
        const W q = w3(t.direction[t.cell_neighbor[k]]);
        EXPECT_NEAR(angle(mid, w3(t.direction[i])), angle(mid, q), 1e-12);
      }
    }
    EXPECT_NEAR(total, 4.0 * kPi * R * R, 1e-12 * R * R);
    EXPECT_NEAR(sum_l, sum_p, 1e-12 * sum_p);
    // Empty circumcircle caps: the pole is equidistant from its three points
    // and no point is closer (brute force).
    for (size_t f = 0; f < t.triangles.size(); ++f) {
      const W v = w3(t.vertex_direction[f]);
      const double r0 = angle(v, w3(t.direction[t.triangles[f][0]]));
      for (int m = 1; m < 3; ++m) EXPECT_NEAR(angle(v, w3(t.direction[t.triangles[f][m]])), r0, 1e-12);
      EXPECT_NEAR(t.circumradius[f], R * r0, 1e-12 * R);
      for (int p = 0; p < n; ++p) EXPECT_GT(angle(v, w3(t.direction[p])), r0 - 1e-12);
      // Counter-clockwise seen from outside: every other point below the facet.
      const W a = w3(t.direction[t.triangles[f][0]]), b = w3(t.direction[t.triangles[f][1]]),
              cc = w3(t.direction[t.triangles[f][2]]);
      const W out = cross(b - a, cc - a);
      for (int p = 0; p < n; ++p) EXPECT_LT(dot(out, w3(t.direction[p]) - a), 1e-14);
      EXPECT_GT(dot(out, v), 0.0);
    }
  }
}

// ---------------------------------------------------------------- forces

// Central differences of E along geodesics through each point, in two
// tangent directions.
void check_forces_fd(uint64_t seed, int n, tessera::Tension tension, bool per_cell_area0,
                     double zmin = -1.0) {
  Rng rng(seed);
  const Vec3 c{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
  const double R = rng.uniform(1.0, 4.0);
  const std::vector<W> dirs = random_directions(n, rng, zmin);
  const std::vector<double> xyz = place(c, dirs, R);
  const double a0 = 4.0 * kPi * R * R / n;
  tessera::Model m = random_model(rng, 2, a0, tension);
  std::vector<double> area0(n);
  for (double &a : area0) a = a0 * rng.uniform(0.5, 1.5);
  if (per_cell_area0) m.cell_area0 = area0.data();
  std::vector<int> type(n);
  for (int &ty : type) ty = rng.below(2);

  const auto t = tess(c, R, xyz);
  std::vector<double> f(3 * n, 0.0), ce(n), cv(9 * n);
  const auto out = tessera::sphere_forces(t, {xyz.data(), n, 3}, type.data(), m, f.data(), 3,
                                          ce.data(), cv.data());
  double esum = 0.0;
  for (double e : ce) esum += e;
  EXPECT_NEAR(esum, out.energy, 1e-12 * std::fabs(out.energy));

  auto energy_at = [&](int i, W dir, double eps) {
    std::vector<double> moved = xyz;
    const W u = unit(dirs[i]);
    const W p = w3(c) + R * (std::cos(eps / R) * u + std::sin(eps / R) * dir);
    moved[3 * i] = p.x, moved[3 * i + 1] = p.y, moved[3 * i + 2] = p.z;
    const auto tm = tess(c, R, moved);
    return tessera::sphere_energy(tm, type.data(), m);
  };
  const double h = 1e-5 * R;
  double fmax = 0.0;
  for (double x : f) fmax = std::max(fmax, std::fabs(x));
  W torque{0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const W u = unit(dirs[i]);
    const W F{f[3 * i], f[3 * i + 1], f[3 * i + 2]};
    EXPECT_NEAR(dot(F, u), 0.0, 1e-13 * fmax) << "force not tangent on " << i;
    torque = torque + cross(R * u, F);
    // Two tangent directions.
    const W e1 = unit(cross(u, std::fabs(u.x) < 0.6 ? W{1, 0, 0} : W{0, 1, 0}));
    const W e2 = cross(u, e1);
    for (const W &dir : {e1, e2}) {
      // Fourth-order central difference (the cells reaching round a cap make
      // third derivatives large).
      const double fd = -(8.0 * (energy_at(i, dir, h) - energy_at(i, dir, -h)) -
                          (energy_at(i, dir, 2.0 * h) - energy_at(i, dir, -2.0 * h))) /
                        (12.0 * h);
      EXPECT_NEAR(dot(F, dir), fd, 3e-7 * (fmax + 1.0)) << "seed " << seed << " point " << i;
    }
  }
  // Rotation invariance: no torque about the centre (the forces do not sum to zero).
  EXPECT_LT(norm(torque), 1e-12 * R * fmax * n);
  W fsum{0, 0, 0};
  for (int i = 0; i < n; ++i) fsum = fsum + W{f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  EXPECT_GT(norm(fsum), 1e-6 * fmax);

  // The virial: traceless (the forces are tangent), symmetric (no torque).
  EXPECT_NEAR(out.virial[0] + out.virial[4] + out.virial[8], 0.0, 1e-12 * R * fmax * n);
  EXPECT_NEAR(out.virial[1], out.virial[3], 1e-12 * R * fmax * n);
  EXPECT_NEAR(out.virial[2], out.virial[6], 1e-12 * R * fmax * n);
  EXPECT_NEAR(out.virial[5], out.virial[7], 1e-12 * R * fmax * n);

  // dE/dR by central differences of the radius.
  const double hr = 1e-5 * R;
  const auto tp = tess(c, R + hr, xyz), tmn = tess(c, R - hr, xyz);
  const double fd_r = (tessera::sphere_energy(tp, type.data(), m) -
                       tessera::sphere_energy(tmn, type.data(), m)) / (2.0 * hr);
  EXPECT_NEAR(out.dE_dR, fd_r, 1e-6 * (std::fabs(fd_r) + 1.0));
}

TEST(Sphere, ForcesMatchCentralDifferencesEdgeTension) { check_forces_fd(201, 30, tessera::Tension::Edge, false); }
TEST(Sphere, ForcesMatchCentralDifferencesCellTension) { check_forces_fd(202, 25, tessera::Tension::Cell, false); }
TEST(Sphere, ForcesMatchCentralDifferencesPerCellArea) { check_forces_fd(203, 20, tessera::Tension::Edge, true); }
TEST(Sphere, ForcesMatchCentralDifferencesFewCells) { check_forces_fd(204, 6, tessera::Tension::Edge, false); }
TEST(Sphere, ForcesMatchCentralDifferencesOnACap) { check_forces_fd(205, 25, tessera::Tension::Cell, true, 0.5); }

TEST(Sphere, QuadraticParametersGiveTheQuadraticEnergy) {
  Rng rng(301);
  const int n = 40;
  const Vec3 c{0.1, 0.2, 0.3};
  const double R = 1.9;
  const std::vector<double> xyz = place(c, random_directions(n, rng), R);
  const auto t = tess(c, R, xyz);
  const tessera::QuadraticParams q{0.7, 4.0 * kPi * R * R / n, 0.3, 3.9 * std::sqrt(4.0 * kPi * R * R / n)};
  for (auto tension : {tessera::Tension::Edge, tessera::Tension::Cell}) {
    tessera::Model m(1);
    m.types[0] = tessera::cell_type_from_quadratic(q);
    m.set_lambda(0, 0, tessera::lambda_from_quadratic(q, tension));
    m.tension = tension;
    const std::vector<int> type(n, 0);
    std::vector<double> ce(n);
    tessera::sphere_energy(t, type.data(), m, ce.data());
    for (int i = 0; i < n; ++i) {
      const double quad = q.KA * std::pow(t.area[i] - q.A0, 2) + q.KP * std::pow(t.perimeter[i] - q.P0, 2);
      EXPECT_NEAR(ce[i], quad - q.KP * q.P0 * q.P0, 1e-12 * (std::fabs(quad) + 1.0));
    }
  }
}

TEST(Sphere, CellVirialIsTheVirialOfTheCellsOwnForces) {
  Rng rng(401);
  const int n = 24;
  const Vec3 c{0.4, 0.0, -0.3};
  const double R = 1.3;
  const std::vector<double> xyz = place(c, random_directions(n, rng), R);
  const auto t = tess(c, R, xyz);
  tessera::Model m = random_model(rng, 2, 4.0 * kPi * R * R / n, tessera::Tension::Edge);
  std::vector<int> type(n);
  for (int &ty : type) ty = rng.below(2);
  std::vector<double> f(3 * n, 0.0), cv(9 * n);
  const auto out = tessera::sphere_forces(t, {xyz.data(), n, 3}, type.data(), m, f.data(), 3,
                                          nullptr, cv.data());
  // Cell i's own forces, by central differences of its energy alone.
  double total[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (int i = 0; i < n; ++i) {
    double wi[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    W fi_sum{0, 0, 0};
    for (int p = 0; p < n; ++p) {
      const W u = w3(t.direction[p]);
      const W e1 = unit(cross(u, std::fabs(u.x) < 0.6 ? W{1, 0, 0} : W{0, 1, 0})), e2 = cross(u, e1);
      W F{0, 0, 0};
      for (const W &dir : {e1, e2}) {
        double e[2];
        for (int s = 0; s < 2; ++s) {
          const double eps = (s ? -1e-5 : 1e-5) * R;
          std::vector<double> moved = xyz;
          const W q = w3(c) + R * (std::cos(eps / R) * u + std::sin(eps / R) * dir);
          moved[3 * p] = q.x, moved[3 * p + 1] = q.y, moved[3 * p + 2] = q.z;
          std::vector<double> ce(n);
          tessera::sphere_energy(tess(c, R, moved), type.data(), m, ce.data());
          e[s] = ce[i];
        }
        F = F + (-(e[0] - e[1]) / (2e-5 * R)) * dir;
      }
      fi_sum = fi_sum + F;
      const W d = R * u - R * w3(t.direction[i]);
      const double da[3] = {d.x, d.y, d.z}, fb[3] = {F.x, F.y, F.z};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) wi[3 * a + b] += da[a] * fb[b];
    }
    for (int ab = 0; ab < 9; ++ab) EXPECT_NEAR(cv[9 * i + ab], wi[ab], 1e-6) << i << " " << ab;
    const W ri = R * w3(t.direction[i]);
    const double ra[3] = {ri.x, ri.y, ri.z}, fs[3] = {fi_sum.x, fi_sum.y, fi_sum.z};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) total[3 * a + b] += cv[9 * i + 3 * a + b] + ra[a] * fs[b];
  }
  for (int ab = 0; ab < 9; ++ab) EXPECT_NEAR(total[ab], out.virial[ab], 1e-6);
}

TEST(Sphere, ForcesRefuseStalePoints) {
  Rng rng(402);
  const Vec3 c{0, 0, 0};
  std::vector<double> xyz = place(c, random_directions(10, rng), 1.0);
  const auto t = tess(c, 1.0, xyz);
  xyz[3 * 4] += 1e-6;
  const tessera::Model m = uniform_model(1, 1, 0.1, 0.0);
  const std::vector<int> type(10, 0);
  std::vector<double> f(30, 0.0);
  EXPECT_THAT(error_of([&] { tessera::sphere_forces(t, {xyz.data(), 10, 3}, type.data(), m, f.data(), 3); }),
              testing::HasSubstr("point 4 is not where it was"));
}

// ---------------------------------------------------------------- flat limit

// A patch of a jittered triangular lattice (spacing 1) in the tangent plane
// at the north pole, put on spheres of growing radius by the inverse gnomonic
// projection.  The cells near the pole approach the planar model's cells of
// the same (x, y) (tessellate_local), as 1/R^2.
TEST(Sphere, FlatLimitApproachesThePlanarModelAsOneOverRSquared) {
  Rng rng(501);
  std::vector<double> xy;
  for (int j = -6; j <= 6; ++j)
    for (int i = -7; i <= 7; ++i) {
      const double x = i + 0.5 * (j & 1) + rng.uniform(-0.12, 0.12);
      const double y = j * std::sqrt(3.0) / 2.0 + rng.uniform(-0.12, 0.12);
      xy.push_back(x);
      xy.push_back(y);
    }
  // Owned cells first (|r| < 3.2) for the planar tessellation.
  std::vector<int> order;
  const int np = static_cast<int>(xy.size() / 2);
  for (int pass = 0; pass < 2; ++pass)
    for (int p = 0; p < np; ++p) {
      const bool in = std::hypot(xy[2 * p], xy[2 * p + 1]) < 3.2;
      if (in == (pass == 0)) order.push_back(p);
    }
  std::vector<double> pl;
  int n_owned = 0;
  for (int p : order) {
    pl.push_back(xy[2 * p]);
    pl.push_back(xy[2 * p + 1]);
    if (std::hypot(xy[2 * p], xy[2 * p + 1]) < 3.2) ++n_owned;
  }
  const tessera::Model m = uniform_model(1.0, 0.8, 0.3, -0.4);
  const std::vector<int> type(np, 0);
  const tessera::Tessellation flat = tessera::tessellate_local({pl.data(), np, 2}, n_owned);
  std::vector<double> ff(2 * np, 0.0);
  tessera::compute_forces(flat, {pl.data(), np, 2}, type.data(), m, ff.data(), 2);

  const Vec3 c{1.0, -2.0, 0.5};
  std::vector<double> err_a, err_p, err_f;
  for (double R : {15.0, 30.0, 60.0, 120.0}) {
    std::vector<W> dirs;
    for (int p = 0; p < np; ++p) dirs.push_back({pl[2 * p], pl[2 * p + 1], R});
    const std::vector<double> xyz = place(c, dirs, R);
    const auto t = tess(c, R, xyz);
    std::vector<double> f(3 * np, 0.0);
    tessera::sphere_forces(t, {xyz.data(), np, 3}, type.data(), m, f.data(), 3);
    double ea = 0, ep = 0, ef = 0;
    for (int p = 0; p < n_owned; ++p) {
      const double r = std::hypot(pl[2 * p], pl[2 * p + 1]);
      if (r < 2.2) {
        ASSERT_EQ(t.coordination_number(p), flat.coordination_number(p)) << "R " << R;
        ea = std::max(ea, std::fabs(t.area[p] - flat.area[p]));
        ep = std::max(ep, std::fabs(t.perimeter[p] - flat.perimeter[p]));
      }
      if (r < 1.6) {
        ef = std::max(ef, std::hypot(f[3 * p] - ff[2 * p], f[3 * p + 1] - ff[2 * p + 1]));
      }
    }
    err_a.push_back(ea);
    err_p.push_back(ep);
    err_f.push_back(ef);
  }
  for (size_t k = 0; k + 1 < err_a.size(); ++k) {
    EXPECT_NEAR(err_a[k] / err_a[k + 1], 4.0, 0.3) << k;
    EXPECT_NEAR(err_p[k] / err_p[k + 1], 4.0, 0.3) << k;
    EXPECT_NEAR(err_f[k] / err_f[k + 1], 4.0, 0.3) << k;
  }
  EXPECT_LT(err_a.back(), 1e-3);
  EXPECT_LT(err_f.back(), 1e-3);
}

// ---------------------------------------------------------------- transport

TEST(Sphere, TransportKeepsLengthAndTheAngleToTheGeodesic) {
  Rng rng(601);
  const Vec3 c{0.5, 0.5, -1.0};
  for (int trial = 0; trial < 50; ++trial) {
    const double R = rng.uniform(0.5, 3.0);
    const std::vector<W> d = random_directions(2, rng);
    const W a = w3(c) + R * d[0], b = w3(c) + rng.uniform(0.5, 2.0) * R * d[1];
    const W v = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    const W va = w3(tessera::sphere_tangent(c, v3(a), v3(v)));
    EXPECT_NEAR(dot(va, d[0]), 0.0, 1e-14);
    const W vb = w3(tessera::sphere_transport(c, v3(a), v3(b), v3(v)));
    EXPECT_NEAR(dot(vb, d[1]), 0.0, 1e-14);
    EXPECT_NEAR(norm(vb), norm(va), 1e-14);
    // Signed angle to the geodesic's direction of travel, at both ends.
    const W ta = unit(d[1] - dot(d[0], d[1]) * d[0]);
    const W tb = unit(dot(d[0], d[1]) * d[1] - d[0]);
    const double at_a = std::atan2(dot(d[0], cross(ta, va)), dot(ta, va));
    const double at_b = std::atan2(dot(d[1], cross(tb, vb)), dot(tb, vb));
    EXPECT_NEAR(std::remainder(at_a - at_b, 2.0 * kPi), 0.0, 1e-12);
    // Rotation about the normal.
    const double phi = rng.uniform(-3.0, 3.0);
    const W vr = w3(tessera::sphere_rotate_tangent(c, v3(a), v3(v), phi));
    EXPECT_NEAR(norm(vr), norm(va), 1e-14);
    EXPECT_NEAR(std::atan2(dot(d[0], cross(va, vr)), dot(va, vr)), phi, 1e-12);
  }
  // Antipodal points have no unique arc.
  EXPECT_THAT(error_of([&] { tessera::sphere_transport(c, Vec3{1.5, 0.5, -1.0}, Vec3{-0.5, 0.5, -1.0}, Vec3{0, 1, 0}); }),
              testing::HasSubstr("antipodal"));
}

TEST(Sphere, TransportAroundAGeodesicTriangleTurnsByItsArea) {
  Rng rng(602);
  const Vec3 c{-0.3, 0.2, 0.9};
  for (int trial = 0; trial < 40; ++trial) {
    const double R = rng.uniform(0.5, 3.0);
    std::vector<W> d = random_directions(3, rng);
    if (dot(d[0], cross(d[1], d[2])) < 0) std::swap(d[1], d[2]);  // counter-clockwise
    const W p[3] = {w3(c) + R * d[0], w3(c) + R * d[1], w3(c) + R * d[2]};
    // Solid angle from Girard: interior angles of the geodesic triangle.
    double excess = -kPi;
    for (int k = 0; k < 3; ++k) {
      const W x = d[k], nx = d[(k + 1) % 3], pv = d[(k + 2) % 3];
      const W t1 = unit(nx - dot(nx, x) * x), t2 = unit(pv - dot(pv, x) * x);
      excess += std::acos(std::max(-1.0, std::min(1.0, dot(t1, t2))));
    }
    const W v0 = w3(tessera::sphere_tangent(c, v3(p[0]), Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)}));
    W v = v0;
    for (int k = 0; k < 3; ++k) v = w3(tessera::sphere_transport(c, v3(p[k]), v3(p[(k + 1) % 3]), v3(v)));
    // Holonomy: turned counter-clockwise (about the outward normal) by the
    // enclosed area over R^2, i.e. by the triangle's solid angle.
    const double turned = std::atan2(dot(d[0], cross(v0, v)), dot(v0, v));
    EXPECT_NEAR(std::remainder(turned - excess, 2.0 * kPi), 0.0, 1e-10) << trial;
    EXPECT_NEAR(norm(v), norm(v0), 1e-13);
  }
}

}  // namespace

namespace {

// Turning the whole configuration about the centre turns the forces with it
// and changes no area, perimeter or energy (the Hilbert order of insertion
// changes, the triangulation must not).
TEST(Sphere, TurningTheConfigurationTurnsTheForces) {
  Rng rng(701);
  const int n = 80;
  const Vec3 c{0.7, -0.1, 0.2};
  const double R = 2.1;
  const std::vector<W> dirs = random_directions(n, rng);
  const Rotation rot(rng);
  std::vector<W> turned;
  for (const W &d : dirs) turned.push_back(rot(d));
  const std::vector<double> xa = place(c, dirs, R), xb = place(c, turned, R);
  const auto ta = tess(c, R, xa), tb = tess(c, R, xb);
  EXPECT_EQ(canonical(ta), canonical(tb));
  tessera::Model m = random_model(rng, 2, 4.0 * kPi * R * R / n, tessera::Tension::Edge);
  std::vector<int> type(n);
  for (int &ty : type) ty = rng.below(2);
  std::vector<double> fa(3 * n, 0.0), fb(3 * n, 0.0);
  const auto oa = tessera::sphere_forces(ta, {xa.data(), n, 3}, type.data(), m, fa.data(), 3);
  const auto ob = tessera::sphere_forces(tb, {xb.data(), n, 3}, type.data(), m, fb.data(), 3);
  EXPECT_NEAR(oa.energy, ob.energy, 1e-12 * std::fabs(oa.energy));
  double fmax = 0.0;
  for (double x : fa) fmax = std::max(fmax, std::fabs(x));
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(ta.area[i], tb.area[i], 1e-12 * R * R);
    EXPECT_NEAR(ta.perimeter[i], tb.perimeter[i], 1e-12 * R);
    const W F = rot(W{fa[3 * i], fa[3 * i + 1], fa[3 * i + 2]});
    EXPECT_NEAR(norm(F - W{fb[3 * i], fb[3 * i + 1], fb[3 * i + 2]}), 0.0, 1e-10 * fmax) << i;
  }
}

TEST(Sphere, ErrorsUseTheCallersIds) {
  std::vector<double> xyz = place(Vec3{}, icosahedron(), 1.0);
  xyz.insert(xyz.end(), {xyz[9], xyz[10], xyz[11] + 1e-10});
  std::vector<long> ids(13);
  for (int i = 0; i < 13; ++i) ids[i] = 1000 + i;
  EXPECT_THAT(error_of([&] { tess(Vec3{}, 1.0, xyz, ids.data()); }),
              testing::HasSubstr("id 1003 and id 1012 project to the same point"));
}

}  // namespace

namespace {

// At a multifold vertex the energy has a kink; the forces are the mean over
// the fan triangulations of the ring, which for a four-fold vertex is the
// mean of the two one-sided derivatives: the central difference.
void check_fourfold_fd(const Vec3 &c, double R, const std::vector<double> &xyz, uint64_t seed,
                       int expect_groups) {
  Rng rng(seed);
  const int n = static_cast<int>(xyz.size() / 3);
  const auto t = tess(c, R, xyz);
  int zero = 0;
  for (double l : t.edge_length) zero += l == 0.0;
  EXPECT_EQ(zero, 2 * expect_groups);  // each four-fold vertex: its two triangles' shared edge, in 2 cells
  tessera::Model m = random_model(rng, 2, 4.0 * kPi * R * R / n, tessera::Tension::Edge);
  std::vector<int> type(n);
  for (int &ty : type) ty = rng.below(2);
  std::vector<double> f(3 * n, 0.0);
  tessera::sphere_forces(t, {xyz.data(), n, 3}, type.data(), m, f.data(), 3);
  double fmax = 0.0;
  for (double x : f) fmax = std::max(fmax, std::fabs(x));
  W torque{0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const W u = w3(t.direction[i]);
    const W F{f[3 * i], f[3 * i + 1], f[3 * i + 2]};
    torque = torque + cross(R * u, F);
    const W e1 = unit(cross(u, std::fabs(u.x) < 0.6 ? W{1, 0, 0} : W{0, 1, 0})), e2 = cross(u, e1);
    for (const W &dir : {e1, e2}) {
      double e[2];
      for (int s = 0; s < 2; ++s) {
        const double eps = (s ? -1e-7 : 1e-7) * R;
        std::vector<double> moved = xyz;
        const W p = w3(c) + R * (std::cos(eps / R) * u + std::sin(eps / R) * dir);
        moved[3 * i] = p.x, moved[3 * i + 1] = p.y, moved[3 * i + 2] = p.z;
        e[s] = tessera::sphere_energy(tess(c, R, moved), type.data(), m);
      }
      const double fd = -(e[0] - e[1]) / (2e-7 * R);
      EXPECT_NEAR(dot(F, dir), fd, 1e-6 * (fmax + 1.0)) << "point " << i;
    }
  }
  EXPECT_LT(norm(torque), 1e-12 * R * (fmax + 1.0) * n);
}

TEST(Sphere, FourfoldVerticesOfTheCubeGiveTheCentralDifference) {
  Rng rng(801);
  for (int turned = 0; turned < 3; ++turned) {
    const Rotation rot(rng);
    std::vector<W> dirs;
    for (int a : {-1, 1})
      for (int b : {-1, 1})
        for (int d : {-1, 1}) {
          const W x{1.0 * a, 1.0 * b, 1.0 * d};
          dirs.push_back(turned ? rot(x) : x);
        }
    const Vec3 c{0.2, 0.1, -0.4};
    check_fourfold_fd(c, 1.4, place(c, dirs, 1.4), 810 + turned, 6);
  }
}

TEST(Sphere, AFourfoldVertexAmongOrdinaryCellsGivesTheCentralDifference) {
  // Four points on a small circle round the north pole (nothing else inside
  // its cap), among random points elsewhere.
  Rng rng(802);
  std::vector<W> dirs;
  const double rho = 0.35;
  for (double a : {0.0, 1.4, 3.3, 4.7})
    dirs.push_back({std::sin(rho) * std::cos(a), std::sin(rho) * std::sin(a), std::cos(rho)});
  for (const W &d : random_directions(40, rng))
    if (d.z < std::cos(rho + 0.25)) dirs.push_back(d);
  const Vec3 c{-0.5, 0.3, 0.8};
  check_fourfold_fd(c, 2.2, place(c, dirs, 2.2), 820, 1);
}

}  // namespace

namespace {

// Five co-circular points (a five-fold vertex) among random points: the
// forces do not depend on which diagonals the triangulation picked (the
// route, or the Hilbert order after turning everything), and have no torque.
TEST(Sphere, FivefoldVertexForcesDoNotDependOnTheTieBreak) {
  Rng rng(901);
  std::vector<W> dirs;
  const double rho = 0.4;
  for (double a : {0.3, 1.5, 2.6, 3.9, 5.1})
    dirs.push_back({std::sin(rho) * std::cos(a), std::sin(rho) * std::sin(a), std::cos(rho)});
  for (const W &d : random_directions(40, rng))
    if (d.z < std::cos(rho + 0.25)) dirs.push_back(d);
  const int n = static_cast<int>(dirs.size());
  const Vec3 c{0.1, 0.2, -0.3};
  const double R = 1.6;
  tessera::Model m = random_model(rng, 2, 4.0 * kPi * R * R / n, tessera::Tension::Cell);
  std::vector<int> type(n);
  for (int &ty : type) ty = rng.below(2);
  auto forces = [&](const std::vector<double> &xyz, bool hull, int *zero) {
    const auto t = tess(c, R, xyz, nullptr, hull);
    *zero = 0;
    for (double l : t.edge_length) *zero += l == 0.0;
    std::vector<double> f(3 * n, 0.0);
    tessera::sphere_forces(t, {xyz.data(), n, 3}, type.data(), m, f.data(), 3);
    return f;
  };
  const std::vector<double> xyz = place(c, dirs, R);
  int z0 = 0, z1 = 0;
  const std::vector<double> f0 = forces(xyz, false, &z0), f1 = forces(xyz, true, &z1);
  EXPECT_EQ(z0, 4);  // a five-fold vertex: three triangles, two zero edges, each in two cells
  EXPECT_EQ(z1, 4);
  double fmax = 0.0;
  for (double x : f0) fmax = std::max(fmax, std::fabs(x));
  for (int k = 0; k < 3 * n; ++k) EXPECT_NEAR(f0[k], f1[k], 1e-12 * fmax);
  W torque{0, 0, 0};
  for (int i = 0; i < n; ++i) torque = torque + cross(R * unit(dirs[i]), W{f0[3 * i], f0[3 * i + 1], f0[3 * i + 2]});
  EXPECT_LT(norm(torque), 1e-12 * R * fmax * n);
  for (int trial = 0; trial < 4; ++trial) {
    const Rotation rot(rng);
    std::vector<W> turned;
    for (const W &d : dirs) turned.push_back(rot(d));
    int z2 = 0;
    const std::vector<double> f2 = forces(place(c, turned, R), false, &z2);
    EXPECT_EQ(z2, 4);
    for (int i = 0; i < n; ++i) {
      const W F = rot(W{f0[3 * i], f0[3 * i + 1], f0[3 * i + 2]});
      EXPECT_NEAR(norm(F - W{f2[3 * i], f2[3 * i + 1], f2[3 * i + 2]}), 0.0, 1e-9 * fmax) << i;
    }
  }
}

}  // namespace

namespace {

// The alignment torque is minus the derivative of the alignment energy
// U = -J_S sum_pairs n_i . T_ji n_j with respect to turning n_i (central
// differences, U computed here from sphere_transport), and in the flat limit
// it is the plane's J_S sum sin(th_j - th_i).
TEST(Sphere, AlignmentTorqueIsTheDerivativeOfTheAlignmentEnergy) {
  Rng rng(1001);
  const int n = 50;
  const Vec3 c{0.3, 0.3, -0.6};
  const double R = 1.8;
  const std::vector<double> xyz = place(c, random_directions(n, rng), R);
  const auto t = tess(c, R, xyz);
  std::vector<double> pol(4 * n);  // stride 4, as LAMMPS's mu
  for (int i = 0; i < n; ++i) {
    const W tv = w3(tessera::sphere_tangent(c, t.point(i), Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)}));
    const W v = unit(tv);
    pol[4 * i] = v.x, pol[4 * i + 1] = v.y, pol[4 * i + 2] = v.z, pol[4 * i + 3] = 1.0;
  }
  const double J = 0.7;
  std::vector<double> tau(n);
  tessera::sphere_alignment_torque(t, pol.data(), 4, J, tau.data());
  auto energy = [&](const std::vector<double> &p) {
    double U = 0.0;
    for (int i = 0; i < n; ++i)
      for (int k = t.cell_offset[i]; k < t.cell_offset[i + 1]; ++k) {
        const int j = t.cell_neighbor[k];
        if (t.edge_length[k] <= 0.0 || j < i) continue;
        const W m = w3(tessera::sphere_transport(c, t.point(j), t.point(i), Vec3{p[4 * j], p[4 * j + 1], p[4 * j + 2]}));
        U -= J * dot(W{p[4 * i], p[4 * i + 1], p[4 * i + 2]}, m);
      }
    return U;
  };
  for (int i = 0; i < n; ++i) {
    double e[2];
    for (int s = 0; s < 2; ++s) {
      std::vector<double> p = pol;
      const W r = w3(tessera::sphere_rotate_tangent(c, t.point(i), Vec3{pol[4 * i], pol[4 * i + 1], pol[4 * i + 2]}, s ? -1e-5 : 1e-5));
      p[4 * i] = r.x, p[4 * i + 1] = r.y, p[4 * i + 2] = r.z;
      e[s] = energy(p);
    }
    EXPECT_NEAR(tau[i], -(e[0] - e[1]) / 2e-5, 1e-8) << i;
  }
}

TEST(Sphere, AlignmentTorqueApproachesThePlanesInTheFlatLimit) {
  Rng rng(1002);
  std::vector<double> xy;
  for (int j = -5; j <= 5; ++j)
    for (int i = -5; i <= 5; ++i) {
      xy.push_back(i + 0.5 * (j & 1) + rng.uniform(-0.1, 0.1));
      xy.push_back(j * std::sqrt(3.0) / 2.0 + rng.uniform(-0.1, 0.1));
    }
  const int np = static_cast<int>(xy.size() / 2);
  std::vector<double> theta(np);
  for (double &th : theta) th = rng.uniform(-kPi, kPi);
  const tessera::Tessellation flat = tessera::tessellate_local({xy.data(), np, 2}, np, nullptr, false);
  const double R = 400.0;
  const Vec3 c{0.0, 0.0, -R};  // tangent plane z = 0 at the north pole
  std::vector<W> dirs;
  for (int p = 0; p < np; ++p) dirs.push_back({xy[2 * p], xy[2 * p + 1], R});
  const std::vector<double> xyz = place(c, dirs, R);
  const auto t = tess(c, R, xyz);
  std::vector<double> pol(3 * np);
  for (int p = 0; p < np; ++p) {
    const W v = w3(tessera::sphere_tangent(c, t.point(p), Vec3{std::cos(theta[p]), std::sin(theta[p]), 0.0}));
    pol[3 * p] = v.x, pol[3 * p + 1] = v.y, pol[3 * p + 2] = v.z;
  }
  std::vector<double> tau(np);
  tessera::sphere_alignment_torque(t, pol.data(), 3, 1.0, tau.data());
  for (int p = 0; p < np; ++p) {
    if (std::hypot(xy[2 * p], xy[2 * p + 1]) > 2.5) continue;
    double plane = 0.0;
    for (int k = flat.cell_offset[p]; k < flat.cell_offset[p + 1]; ++k)
      if (flat.edge_length[k] > 0.0) plane += std::sin(theta[flat.cell_neighbor[k]] - theta[p]);
    EXPECT_NEAR(tau[p], plane, 1e-3) << p;
  }
}

}  // namespace
