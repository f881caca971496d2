// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The energy of the Voronoi model on a sphere, its gradient and the polarity
// transport helpers (sphere.h, doc/sphere.md; the geometry is in sphere.cpp).
//
// Gradient.  A and P are functions of the Voronoi vertices only (the fan's
// apex does not change the area), so dE/du_p comes from dE/dv only.  The
// formulas above extend off the unit sphere; only tangent derivatives are
// used, the extension does not matter:
//   dOmega/db = 2 [S (c x a) - D (a + c)] / (S^2 + D^2),
//   dOmega/dc = 2 [S (a x b) - D (a + b)] / (S^2 + D^2),
//   dtheta/da = -(b - (a.b) a) / |a x b|   (theta = angle(a, b)),
// then through v = n/|n|: g_n = (I - v v^T) g_v / |n|, and since
// dn = du_a x (u_b - u_c) + du_b x (u_c - u_a) + du_c x (u_a - u_b),
//   dE/du_a = (u_b - u_c) x g_n  (and cyclically),
// and finally F_p = -(I - u_p u_p^T) dE/du_p / R.
//
// Multifold vertices: the mean over the fan triangulations of the ring, as
// in the plane (energy.cpp), with two changes for the sphere: a zero-length
// edge's direction at V, for the neighbour q, is V x (u_q - u_c) normalised
// (along the bisecting great circle), and the zero-area fan triangles
// (u, V, V) between two poles at V keep their solid angle's derivative
// (+-2 (u x V) / (2 + 2 u.V)), which cancels only between two inner poles.

#include "tessera/sphere.h"

#include "point_name.h"
#include "sphere_vec.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <utility>
#include <vector>

namespace tessera {

using namespace sphere_detail;

namespace {

// Cell c's energy with the parameters in use (Model::cell_params: the
// type's, or the per-cell KA, KP, P0 and A0), as energy.cpp in the plane:
//   K_c/2 (A - A0_c)^2 + Gamma_c/2 P^2 + shift_c P + w sum_k Lambda_{t t_k} l_k.
double cell_energy_of(const SphereTessellation &t, int c, const int *type, const Model &m) {
  const int tc = type[c];
  const Model::CellParams p = m.cell_params(c, tc);
  const double dA = t.area[c] - p.A0;
  const double P = t.perimeter[c];
  double e = 0.5 * p.K * dA * dA + 0.5 * p.Gamma * P * P;
  double lsum = 0.0;
  for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
    lsum += m.lambda_of(tc, type[t.cell_neighbor[k]]) * t.edge_length[k];
  return e + m.tension_weight() * lsum + p.shift * P;
}

void check_types(const SphereTessellation &t, const int *type, const Model &model) {
  model.validate();
  // Every point is a cell: all n_points per-cell values are read.
  model.validate_cells(t.n_points);
  for (int p = 0; p < t.n_points; ++p)
    if (type[p] < 0 || type[p] >= model.ntypes()) {
      std::ostringstream s;
      s << "tessera: point " << p << " has type " << type[p] << ", outside [0, "
        << model.ntypes() << ")";
      throw Error(s.str());
    }
}

// dE/dv at the pole of the counter-clockwise triangle (A, B, C) of unit
// directions, moved onto the three points as forces (appended to fc, fp).
void push_pole(const SphereTessellation &t, int A, int B, int C, V g, std::vector<V> &fc,
               std::vector<int> &fp) {
  const V ua = vv(t.direction[A]), ub = vv(t.direction[B]), uc = vv(t.direction[C]);
  const V nn = cross(ub - ua, uc - ua);
  const double nlen = norm(nn);
  const V v = (1.0 / nlen) * nn;
  const V gn = (1.0 / nlen) * (g - dot(g, v) * v);
  const V du[3] = {cross(ub - uc, gn), cross(uc - ua, gn), cross(ua - ub, gn)};
  const int pq[3] = {A, B, C};
  for (int q = 0; q < 3; ++q) {
    const V up = vv(t.direction[pq[q]]);
    fc.push_back((-1.0 / t.R) * (du[q] - dot(du[q], up) * up));
    fp.push_back(pq[q]);
  }
}

// Multifold vertices: groups of triangles joined by zero-length edges, and
// the ring of points around each, counter-clockwise seen from outside.
struct Multifold {
  std::vector<int> group;   // per triangle: its group, or -1 (alone)
  std::vector<int> offset;  // per group: ring[offset[g] .. offset[g+1])
  std::vector<int> ring;
};

Multifold find_multifold(const SphereTessellation &t) {
  Multifold mf;
  const int nt = static_cast<int>(t.triangles.size());
  PoleSets poles(nt);
  auto root = [&](int x) { return poles.root(x); };
  bool any = false;
  for (int c = 0; c < t.n_points; ++c)
    for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
      if (t.edge_length[k] == 0.0) {
        const int kn = k + 1 == t.cell_offset[c + 1] ? t.cell_offset[c] : k + 1;
        poles.join(t.cell_vertex[k], t.cell_vertex[kn]);
        any = true;
      }
  mf.group.assign(nt, -1);
  if (!any) return mf;
  std::vector<int> size(nt, 0), gid(nt, -1);
  for (int x = 0; x < nt; ++x) ++size[root(x)];
  std::vector<std::vector<int>> members;
  for (int x = 0; x < nt; ++x) {
    const int r = root(x);
    if (size[r] < 2) continue;
    if (gid[r] < 0) {
      gid[r] = static_cast<int>(members.size());
      members.emplace_back();
    }
    mf.group[x] = gid[r];
    members[gid[r]].push_back(x);
  }
  mf.offset.assign(1, 0);
  for (const auto &tris : members) {
    std::vector<int> pts;
    for (int x : tris)
      for (int q : t.triangles[x]) pts.push_back(q);
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    // Counter-clockwise about the pole: angles in the tangent plane.
    const V v = vv(t.vertex_direction[tris[0]]);
    const V d0 = vv(t.direction[pts[0]]);
    const V e1 = (1.0 / norm(d0 - dot(d0, v) * v)) * (d0 - dot(d0, v) * v);
    const V e2 = cross(v, e1);
    std::vector<std::pair<double, int>> by_angle;
    for (int q : pts) {
      const V d = vv(t.direction[q]);
      by_angle.emplace_back(std::atan2(dot(d, e2), dot(d, e1)), q);
    }
    std::sort(by_angle.begin(), by_angle.end());
    for (const auto &aq : by_angle) mf.ring.push_back(aq.second);
    mf.offset.push_back(static_cast<int>(mf.ring.size()));
  }
  return mf;
}

}  // namespace

double sphere_energy(const SphereTessellation &t, const int *type, const Model &model,
                     double *cell_energy) {
  check_types(t, type, model);
  double e = 0.0;
  for (int c = 0; c < t.n_points; ++c) {
    const double ec = cell_energy_of(t, c, type, model);
    if (cell_energy) cell_energy[c] = ec;
    e += ec;
  }
  return e;
}

SphereForceOutput sphere_forces(const SphereTessellation &t, const Points3 &pts, const int *type,
                                const Model &model, double *f, int f_stride, double *cell_energy,
                                double *cell_virial) {
  if (pts.n != t.n_points) {
    std::ostringstream s;
    s << "tessera: sphere_forces got " << pts.n << " points for a tessellation of " << t.n_points;
    throw Error(s.str());
  }
  const V c = vv(t.centre);
  for (int i = 0; i < t.n_points; ++i) {
    const double *p = pts.p(i);
    const V d = V{p[0], p[1], p[2]} - c;
    const double r = norm(d);
    if (!(r > 0.0) || norm((1.0 / r) * d - vv(t.direction[i])) > 1e-12)
      throw Error("tessera: sphere_forces: " + point_name(i, nullptr) +
                  " is not where it was when the sphere was tessellated");
  }
  check_types(t, type, model);

  const double R = t.R;
  const double w = model.tension_weight();
  SphereForceOutput out;
  double rdedr = 0.0;
  std::vector<V> G;    // dE_c/dv per vertex of the cell
  std::vector<V> fc;   // this cell's forces on the points it moves
  std::vector<int> fp;  // and which points
  std::vector<int> spokes;
  const Multifold mf = find_multifold(t);
  for (int cell = 0; cell < t.n_points; ++cell) {
    const int k0 = t.cell_offset[cell], k1 = t.cell_offset[cell + 1], m = k1 - k0;
    const int tc = type[cell];
    // (without per-cell KA, KP, P0: the type's values and shift 0)
    const Model::CellParams ct = model.cell_params(cell, tc);
    const double A = t.area[cell], P = t.perimeter[cell];
    const double dEdA = ct.K * (A - ct.A0);
    const double dEdP = ct.Gamma * P + ct.shift;
    const double ec = cell_energy_of(t, cell, type, model);
    if (cell_energy) cell_energy[cell] = ec;
    out.energy += ec;
    double tension = 0.0;

    G.assign(m, V{0.0, 0.0, 0.0});
    const V u = vv(t.direction[cell]);
    for (int j = 0; j < m; ++j) {
      const int jn = j + 1 == m ? 0 : j + 1;
      const V a = vv(t.vertex_direction[t.cell_vertex[k0 + j]]);
      const V b = vv(t.vertex_direction[t.cell_vertex[k0 + jn]]);
      const double l = t.edge_length[k0 + j];
      if (l <= 0.0) continue;  // inside a multifold vertex: done with its ring below
      // Area of the fan triangle (u, a, b).
      const double D = dot(u, cross(a, b));
      const double S = 1.0 + dot(u, a) + dot(a, b) + dot(b, u);
      const double s = 2.0 * dEdA * R * R / (S * S + D * D);
      add_to(G[j], s * (S * cross(b, u) - D * (u + b)));
      add_to(G[jn], s * (S * cross(u, a) - D * (u + a)));
      // Length of the edge a-b.
      const double lam = model.lambda_of(tc, type[t.cell_neighbor[k0 + j]]);
      tension += w * lam * l;
      const double coef = R * (dEdP + w * lam);
      const double ab = dot(a, b);
      const double sn = norm(cross(a, b));
      add_to(G[j], (-coef / sn) * (b - ab * a));
      add_to(G[jn], (-coef / sn) * (a - ab * b));
    }
    rdedr += 2.0 * dEdA * A + dEdP * P + tension;

    // Through the poles to the points.
    fc.clear();
    fp.clear();
    for (int j = 0; j < m; ++j) {
      const int tri = t.cell_vertex[k0 + j];
      const int g = mf.group[tri];
      if (g < 0) {
        const std::array<int, 3> &pq = t.triangles[tri];
        push_pole(t, pq[0], pq[1], pq[2], G[j], fc, fp);
        continue;
      }
      const int jp = j == 0 ? m - 1 : j - 1;
      if (mf.group[t.cell_vertex[k0 + jp]] == g) continue;  // not the run's first vertex
      // A multifold vertex V shared by the kk >= 4 cells of its ring
      // w_0..w_{kk-1}, of which this cell is w_i.  Each way of triangulating
      // the ring is one smooth branch of the energy; as in the plane
      // (model.md, Geometry) we take the mean of the branch gradients over
      // the kk fan triangulations (from each w_j): for a four-fold vertex
      // the mean of the two one-sided derivatives.  In a branch, the edges
      // at V have length zero and the direction they take on that branch's
      // side: along the bisector of the cell and the neighbour q, at V,
      // V x (u_q - u_c) normalised.
      int run_end = j;
      while (run_end - j + 1 < m && mf.group[t.cell_vertex[k0 + (run_end + 1) % m]] == g) ++run_end;
      const int *ring = &mf.ring[mf.offset[g]];
      const int kk = mf.offset[g + 1] - mf.offset[g];
      int i = 0;
      while (i < kk && ring[i] != cell) ++i;
      const int w_in = ring[(i + 1) % kk], w_out = ring[(i + kk - 1) % kk];
      if (i == kk || t.cell_neighbor[k0 + jp] != w_in || t.cell_neighbor[k0 + run_end % m] != w_out)
        throw Error("tessera: internal error: the ring of a multifold vertex on the sphere does not"
                    " match the cell of " + point_name(cell, nullptr));
      const V hp = vv(t.vertex_direction[t.cell_vertex[k0 + jp]]);
      const V hn = vv(t.vertex_direction[t.cell_vertex[k0 + (run_end + 1) % m]]);
      const V Vp = vv(t.vertex_direction[tri]);
      // Area terms of the two real edges (fan triangles (u, hp, V) and (u, V, hn)).
      V area_in{0, 0, 0}, area_out{0, 0, 0};
      {
        const double D = dot(u, cross(hp, Vp)), S = 1.0 + dot(u, hp) + dot(hp, Vp) + dot(Vp, u);
        area_in = (2.0 * dEdA * R * R / (S * S + D * D)) * (S * cross(u, hp) - D * (u + hp));
      }
      {
        const double D = dot(u, cross(Vp, hn)), S = 1.0 + dot(u, Vp) + dot(Vp, hn) + dot(hn, u);
        area_out = (2.0 * dEdA * R * R / (S * S + D * D)) * (S * cross(hn, u) - D * (u + hn));
      }
      const V zero_in = (2.0 * dEdA * R * R / (2.0 + 2.0 * dot(u, Vp))) * cross(u, Vp);
      auto spoke_dir = [&](int q) {
        const V d = cross(Vp, vv(t.direction[q]) - u);
        return (1.0 / norm(d)) * d;
      };
      auto spoke_coef = [&](int q) { return R * (dEdP + w * model.lambda_of(tc, type[q])); };
      const double inv_k = 1.0 / kk;
      for (int b = 0; b < kk; ++b) {
        spokes.assign(1, w_in);
        if (b == i) {
          for (int q = 2; q <= kk - 2; ++q) spokes.push_back(ring[(i + q) % kk]);
        } else if (b != (i + 1) % kk && b != (i + kk - 1) % kk) {
          spokes.push_back(ring[b]);
        }
        spokes.push_back(w_out);
        const int M = static_cast<int>(spokes.size()) - 1;
        for (int sp = 1; sp <= M; ++sp) {
          V gs = spoke_coef(spokes[sp - 1]) * spoke_dir(spokes[sp - 1]) -
                 spoke_coef(spokes[sp]) * spoke_dir(spokes[sp]);
          // The fan triangles on either side of this pole: the real ones at
          // the ends, else the zero-area (u, V, V), whose solid angle still
          // has a derivative (2 (u x V) / S in its third argument, the
          // opposite in its second); they cancel for inner spokes.
          gs = gs + (sp == 1 ? area_in : zero_in) + (sp == M ? area_out : (-1.0) * zero_in);
          push_pole(t, cell, spokes[sp - 1], spokes[sp], inv_k * gs, fc, fp);
        }
      }
    }
    const V rc = R * u;
    double *cv = cell_virial ? cell_virial + 9L * cell : nullptr;
    if (cv) std::fill(cv, cv + 9, 0.0);
    for (size_t q = 0; q < fc.size(); ++q) {
      const int p = fp[q];
      const V F = fc[q];
      double *fo = f + static_cast<long>(p) * f_stride;
      fo[0] += F.x;
      fo[1] += F.y;
      fo[2] += F.z;
      const V r = R * vv(t.direction[p]);
      const double ra[3] = {r.x, r.y, r.z}, Fb[3] = {F.x, F.y, F.z};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) out.virial[3 * a + b] += ra[a] * Fb[b];
      if (cv) {
        const V d = r - rc;
        const double da[3] = {d.x, d.y, d.z};
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) cv[3 * a + b] += da[a] * Fb[b];
      }
    }
  }
  out.dE_dR = rdedr / R;
  for (int p = 0; p < t.n_points; ++p) {
    const double *fo = f + static_cast<long>(p) * f_stride;
    if (!finite3(fo))
      throw Error("tessera: the force on " + point_name(p, nullptr) +
                  " on the sphere is not finite");
  }
  return out;
}

Vec3 sphere_tangent(const Vec3 &centre, const Vec3 &p, const Vec3 &v) {
  const V d = vv(p) - vv(centre);
  const double r = norm(d);
  if (!(r > 0.0)) throw Error("tessera: sphere_tangent: the point is at the centre of the sphere");
  const V u = (1.0 / r) * d;
  const V x = vv(v);
  return to3(x - dot(x, u) * u);
}

Vec3 sphere_transport(const Vec3 &centre, const Vec3 &a, const Vec3 &b, const Vec3 &v) {
  const V da = vv(a) - vv(centre), db = vv(b) - vv(centre);
  const double ra = norm(da), rb = norm(db);
  if (!(ra > 0.0 && rb > 0.0))
    throw Error("tessera: sphere_transport: a point is at the centre of the sphere");
  const V ua = (1.0 / ra) * da, ub = (1.0 / rb) * db;
  const double cab = dot(ua, ub);
  if (!(1.0 + cab > 1e-12))
    throw Error("tessera: sphere_transport: the two points are antipodal (no unique great-circle"
                " arc between them)");
  V x = vv(v);
  x = x - dot(x, ua) * ua;
  return to3(x - (dot(ub, x) / (1.0 + cab)) * (ua + ub));
}

Vec3 sphere_rotate_tangent(const Vec3 &centre, const Vec3 &p, const Vec3 &v, double angle_rad) {
  const V d = vv(p) - vv(centre);
  const double r = norm(d);
  if (!(r > 0.0))
    throw Error("tessera: sphere_rotate_tangent: the point is at the centre of the sphere");
  const V u = (1.0 / r) * d;
  V x = vv(v);
  x = x - dot(x, u) * u;
  const double cs = std::cos(angle_rad), sn = std::sin(angle_rad);
  return to3(cs * x + sn * cross(u, x));
}

void sphere_alignment_torque(const SphereTessellation &t, const double *n, int n_stride,
                             double J_S, double *tau) {
  auto tangent = [&](int p) {
    const double *q = n + static_cast<long>(p) * n_stride;
    const V u = vv(t.direction[p]), x{q[0], q[1], q[2]};
    return x - dot(x, u) * u;
  };
  for (int i = 0; i < t.n_points; ++i) {
    const V ui = vv(t.direction[i]);
    const V ni = tangent(i);
    double sum = 0.0;
    for (int k = t.cell_offset[i]; k < t.cell_offset[i + 1]; ++k) {
      if (!(t.edge_length[k] > 0.0)) continue;
      const int j = t.cell_neighbor[k];
      const V uj = vv(t.direction[j]);
      const V nj = tangent(j);
      // Transport from j to i (never antipodal: Voronoi neighbours are
      // less than pi apart).
      const V m = nj - (dot(ui, nj) / (1.0 + dot(uj, ui))) * (uj + ui);
      sum += dot(ui, cross(ni, m));
    }
    tau[i] = J_S * sum;
  }
}

}  // namespace tessera
