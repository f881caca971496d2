// Tessera benchmark.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The triangulation of points on a sphere: Tessera's own convex hull (core/src/
// sphere_hull.cpp, both routes) against CGAL's Delaunay triangulation on the sphere
// (points inserted along CGAL's Hilbert curve on the sphere, each located from the
// last vertex's face: what tessellate_sphere ran before it had its own hull) and
// CGAL's convex_hull_3 (its fallback for points in one hemisphere), on the same
// points; then the whole sphere step, tessellate_sphere and sphere_forces.  The
// triangles of every route are checked to be the same (random points are in general
// position).  Median of a few repeats, in microseconds of this thread's CPU time per
// point.
//
//   bench_sphere [max_N]                  the table, N = 1e3 ... max_N (default 1e6)
//   bench_sphere --only WHAT N [cap]      one run of WHAT (none, own, conflict, cgal,
//                                         cgal-hull, step) on N points, for
//                                         instruction counts: callgrind's count of
//                                         WHAT less that of "none" (the points alone)
//
// Points: uniform random directions (seeded), projected onto the sphere of centre
// (0.3, -0.2, 0.1) and radius 7, in random order (LAMMPS hands them over sorted by
// atom ID); with "cap", only those of z > 0.2 (one hemisphere: the centre lies
// outside their hull).  Built against a core without sphere_hull.h (an older
// checkout), only the CGAL and step columns: the step before and after.
#include "tessera/energy.h"
#include "tessera/sphere.h"

#if __has_include("sphere_hull.h")
#include "sphere_hull.h"
#define BENCH_OWN_HULL 1
#endif

#ifdef TESSERA_BENCH_CGAL
#include <CGAL/Delaunay_triangulation_on_sphere_2.h>
#include <CGAL/Delaunay_triangulation_on_sphere_traits_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Triangulation_on_sphere_face_base_2.h>
#include <CGAL/Triangulation_on_sphere_vertex_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/hilbert_sort_on_sphere.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <unordered_map>
#include <vector>

#include "bench_util.h"

namespace {

using namespace bench_util;

using Tri = std::array<int, 3>;


const tessera::Vec3 kCentre{0.3, -0.2, 0.1};
const double kR = 7.0;

// The points (absolute positions) and their unit directions as tessellate_sphere
// rounds them.
struct Input {
  std::vector<double> xyz, dir;
  int n = 0;
};

Input make_points(long n, bool cap) {
  Input in;
  uint64_t s = 12345 + static_cast<uint64_t>(n) + (cap ? 1 : 0);
  while (in.n < n) {
    const double z = cap ? 0.2 + 0.8 * uniform(s) : 2.0 * uniform(s) - 1.0;
    const double ph = 2.0 * M_PI * uniform(s), r = std::sqrt(1.0 - z * z);
    const double d[3] = {r * std::cos(ph), r * std::sin(ph), z};
    const double p[3] = {kCentre.x + kR * d[0], kCentre.y + kR * d[1], kCentre.z + kR * d[2]};
    in.xyz.insert(in.xyz.end(), p, p + 3);
    ++in.n;
  }
  // Rounded as tessera_sphere does: (p - c) / |p - c|.
  for (int i = 0; i < in.n; ++i) {
    const double d[3] = {in.xyz[3 * i] - kCentre.x, in.xyz[3 * i + 1] - kCentre.y,
                         in.xyz[3 * i + 2] - kCentre.z};
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (double x : d)
      in.dir.push_back((1.0 / r) * x);
  }
  return in;
}

// Triangles, each turned to start at its smallest index, sorted.
std::vector<Tri> canonical(std::vector<Tri> v) {
  for (Tri &f : v)
    while (f[0] > f[1] || f[0] > f[2])
      f = {f[1], f[2], f[0]};
  std::sort(v.begin(), v.end());
  return v;
}

#ifdef BENCH_OWN_HULL
std::vector<Tri> own_hull(const Input &in, bool conflict) {
  using namespace tessera::sphere_detail;
  HullResult r = sphere_hull(in.dir.data(), in.n, conflict ? HullRoute::Conflict : HullRoute::Walk);
  if (r.status != HullResult::Ok) {
    std::fprintf(stderr, "own hull failed: status %d\n", static_cast<int>(r.status));
    std::exit(1);
  }
  return std::move(r.triangles);
}
#endif

#ifdef TESSERA_BENCH_CGAL
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = K::Point_3;
using Traits = CGAL::Delaunay_triangulation_on_sphere_traits_2<K>;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<
    int, Traits, CGAL::Triangulation_on_sphere_vertex_base_2<Traits>>;
using Fb = CGAL::Triangulation_on_sphere_face_base_2<Traits>;
using SDT =
    CGAL::Delaunay_triangulation_on_sphere_2<Traits, CGAL::Triangulation_data_structure_2<Vb, Fb>>;

// CGAL's triangulation on the sphere as tessellate_sphere used it: Hilbert sort on
// the sphere, insertion with the last vertex's face as hint, indices as vertex info
// found through a hash map of the points.
struct KeyHash {
  size_t operator()(const std::array<double, 3> &a) const {
    uint64_t b[3];
    std::memcpy(b, a.data(), sizeof b);
    return std::hash<uint64_t>()(b[0] ^ (b[1] * 0x9E3779B97F4A7C15ull) ^ (b[2] << 1));
  }
};

std::vector<Tri> cgal_on_sphere(const Input &in) {
  std::vector<P3> P(in.n);
  std::unordered_map<std::array<double, 3>, int, KeyHash> index_of;
  index_of.reserve(2 * in.n);
  for (int i = 0; i < in.n; ++i) {
    P[i] = P3(in.dir[3 * i], in.dir[3 * i + 1], in.dir[3 * i + 2]);
    index_of.emplace(std::array<double, 3>{P[i].x(), P[i].y(), P[i].z()}, i);
  }
  CGAL::hilbert_sort_on_sphere(P.begin(), P.end(), 1.0, P3(0.0, 0.0, 0.0));
  SDT dt(Traits(P3(0, 0, 0), 1.0));
  SDT::Face_handle hint;
  for (const P3 &p : P) {
    const SDT::Vertex_handle v = dt.insert(p, hint);
    v->info() = index_of.at({p.x(), p.y(), p.z()});
    hint = v->face();
  }
  std::vector<Tri> t;
  for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f)
    t.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return t;
}

std::vector<Tri> cgal_hull(const Input &in) {
  std::vector<P3> P(in.n);
  for (int i = 0; i < in.n; ++i)
    P[i] = P3(in.dir[3 * i], in.dir[3 * i + 1], in.dir[3 * i + 2]);
  CGAL::Surface_mesh<P3> sm;
  CGAL::convex_hull_3(P.begin(), P.end(), sm);
  // Vertex indices back through a sort of the points (not timed apart).
  std::vector<std::pair<std::array<double, 3>, int>> key(in.n);
  for (int i = 0; i < in.n; ++i)
    key[i] = {{P[i].x(), P[i].y(), P[i].z()}, i};
  std::sort(key.begin(), key.end());
  std::vector<Tri> t;
  for (const auto f : sm.faces()) {
    Tri tri;
    int m = 0;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      const P3 &p = sm.point(v);
      const std::array<double, 3> k{p.x(), p.y(), p.z()};
      tri[m++] = std::lower_bound(key.begin(), key.end(), std::make_pair(k, -1))->second;
    }
    t.push_back(tri);
  }
  return t;
}
#endif

// The sphere step: the tessellation and the forces of a two-type tissue.
double step(const Input &in) {
  const tessera::Points3 pts{in.xyz.data(), in.n, 3};
  const tessera::SphereTessellation t = tessera::tessellate_sphere(kCentre, kR, pts);
  tessera::Model m(2);
  const double a0 = 4.0 * M_PI * kR * kR / in.n;
  m.types[0] = {1.0, a0, 0.2};
  m.types[1] = {1.2, 1.1 * a0, 0.3};
  m.set_lambda(0, 0, -0.1);
  m.set_lambda(0, 1, 0.2);
  m.set_lambda(1, 1, -0.1);
  std::vector<int> type(in.n);
  for (int i = 0; i < in.n; ++i)
    type[i] = i % 2;
  std::vector<double> f(3 * static_cast<size_t>(in.n), 0.0);
  return tessera::sphere_forces(t, pts, type.data(), m, f.data(), 3).energy;
}

template <class F> double time_us_per_point(F &&f, int n) {
  std::vector<double> t;
  double total = 0.0;
  for (int rep = 0; rep < 7 && (rep < 3 || total < 1.0); ++rep) {
    const double t0 = cpu_seconds();
    f();
    const double dt = cpu_seconds() - t0;
    t.push_back(dt);
    total += dt;
  }
  return 1e6 * median(t) / n;
}

int only(const std::string &what, long n, bool cap) {
  const Input in = make_points(n, cap);
  size_t size = 0;
  if (what == "none")
    return 0;
#ifdef BENCH_OWN_HULL
  if (what == "own")
    size = own_hull(in, false).size();
  if (what == "conflict")
    size = own_hull(in, true).size();
#endif
#ifdef TESSERA_BENCH_CGAL
  if (what == "cgal")
    size = cgal_on_sphere(in).size();
  if (what == "cgal-hull")
    size = cgal_hull(in).size();
#endif
  if (what == "step")
    size = step(in) != 0.0 ? 1 : 0;
  if (size == 0) {
    std::fprintf(stderr, "unknown or unbuilt: %s\n", what.c_str());
    return 1;
  }
  std::printf("%s N=%ld: %zu\n", what.c_str(), n, size);
  return 0;
}

} // namespace

int main(int argc, char **argv) {
  if (argc >= 4 && std::string(argv[1]) == "--only")
    return only(argv[2], std::atol(argv[3]), argc > 4 && std::string(argv[4]) == "cap");
  long max_n = 1000000;
  if (argc > 1)
    max_n = std::atol(argv[1]);
  std::printf("CPU microseconds per point, median of 3 to 7 repeats\n");
  std::printf("%-9s %-6s %10s %10s %10s %10s %10s\n", "N", "points", "own", "conflict", "CGAL DToS",
              "CGAL hull", "step");
  for (long n = 1000; n <= max_n; n *= 10)
    for (bool cap : {false, true}) {
      const Input in = make_points(n, cap);
      double own = NAN, conflict = NAN, cgal = NAN, chull = NAN;
#ifdef BENCH_OWN_HULL
      const std::vector<Tri> mine = canonical(own_hull(in, false));
      if (canonical(own_hull(in, true)) != mine)
        std::printf("routes differ at N = %ld\n", n);
      own = time_us_per_point([&] { own_hull(in, false); }, in.n);
      conflict = time_us_per_point([&] { own_hull(in, true); }, in.n);
#endif
#ifdef TESSERA_BENCH_CGAL
      const std::vector<Tri> theirs = canonical(cgal_hull(in));
#ifdef BENCH_OWN_HULL
      if (theirs != mine)
        std::printf("own hull differs from CGAL's at N = %ld\n", n);
#endif
      if (!cap) {
        if (canonical(cgal_on_sphere(in)) != theirs)
          std::printf("CGAL's triangulations differ at N = %ld\n", n);
        cgal = time_us_per_point([&] { cgal_on_sphere(in); }, in.n);
      }
      if (n <= 100000 || cap)
        chull = time_us_per_point([&] { cgal_hull(in); }, in.n);
#endif
      const double st = time_us_per_point([&] { step(in); }, in.n);
      std::printf("%-9ld %-6s %10.3f %10.3f %10.3f %10.3f %10.3f\n", n, cap ? "cap" : "sphere", own,
                  conflict, cgal, chull, st);
      std::fflush(stdout);
    }
  return 0;
}
