// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Energy and exact forces.  For every owned cell c we accumulate dE_c/dh_v on
// its Voronoi vertices h_v (one gradient per Delaunay triangle, summed over the
// owned cells that share it), then push each triangle's gradient onto its three
// corners through the Jacobian of the circumcentre.

#include "tessera/energy.h"

#include <cmath>
#include <sstream>

namespace tessera {

Model::Model(int ntypes) : types(ntypes), lambda(static_cast<size_t>(ntypes) * ntypes, 0.0) {}

void Model::set_lambda(int ti, int tj, double value) {
  lambda[ti * ntypes() + tj] = value;
  lambda[tj * ntypes() + ti] = value;
}

void Model::validate() const {
  for (int t = 0; t < ntypes(); ++t) {
    const CellType &c = types[t];
    std::ostringstream s;
    if (!(std::isfinite(c.K) && c.K > 0.0))
      s << "tessera: cell type " << t << ": area modulus K must be positive and finite, got "
        << c.K;
    else if (!(std::isfinite(c.A0) && c.A0 > 0.0))
      s << "tessera: cell type " << t << ": preferred area A0 must be positive and finite, got "
        << c.A0;
    else if (!std::isfinite(c.Gamma))
      s << "tessera: cell type " << t << ": Gamma must be finite, got " << c.Gamma;
    if (!s.str().empty()) throw Error(s.str());
  }
  for (int i = 0; i < ntypes(); ++i)
    for (int j = 0; j < ntypes(); ++j)
      if (!std::isfinite(lambda_of(i, j))) {
        std::ostringstream s;
        s << "tessera: Lambda between types " << i << " and " << j << " must be finite";
        throw Error(s.str());
      }
}

CellType cell_type_from_quadratic(const QuadraticParams &q) {
  return CellType{2.0 * q.KA, q.A0, 2.0 * q.KP};
}

double lambda_from_quadratic(const QuadraticParams &q, Tension tension) {
  // Per cell, Gamma/2 P^2 + w Lambda P is minimal at P = -w Lambda / Gamma.
  const double w = tension == Tension::Edge ? 0.5 : 1.0;
  return -(2.0 * q.KP) * q.P0 / w;
}

namespace {

inline double cell_energy_of(const Tessellation &t, int c, const int *type, const Model &m) {
  const CellType &ct = m.types[type[c]];
  const double dA = t.area[c] - ct.A0;
  double e = 0.5 * ct.K * dA * dA + 0.5 * ct.Gamma * t.perimeter[c] * t.perimeter[c];
  double tension = 0.0;
  for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
    tension += m.lambda_of(type[c], type[t.cell_neighbor[k]]) * t.edge_length[k];
  return e + m.tension_weight() * tension;
}

}  // namespace

double compute_energy(const Tessellation &t, const int *type, const Model &model,
                      double *cell_energy) {
  double e = 0.0;
  for (int c = 0; c < t.n_owned; ++c) {
    const double ec = cell_energy_of(t, c, type, model);
    if (cell_energy) cell_energy[c] = ec;
    e += ec;
  }
  return e;
}

ForceOutput compute_forces(const Tessellation &t, const Points &pts, const int *type,
                           const Model &model, double *f, int f_stride, double *cell_energy) {
  ForceOutput out;
  const int nt = static_cast<int>(t.triangles.size());
  std::vector<Vec2> grad(nt);  // dE/dh per Voronoi vertex
  const double w = model.tension_weight();

  for (int c = 0; c < t.n_owned; ++c) {
    const double ec = cell_energy_of(t, c, type, model);
    if (cell_energy) cell_energy[c] = ec;
    out.energy += ec;

    const CellType &ct = model.types[type[c]];
    const double dEdA = ct.K * (t.area[c] - ct.A0);
    const double dEdP = ct.Gamma * t.perimeter[c];
    const int o = t.cell_offset[c], m = t.cell_size(c);
    if (m == 0) continue;

    // Unit vector and tension coefficient of each edge k (vertex k -> k+1).
    auto edge = [&](int k, double &ux, double &uy, double &lam) {
      const int a = t.cell_vertex[o + k], b = t.cell_vertex[o + (k + 1) % m];
      const double l = t.edge_length[o + k];
      if (l > 0.0) {
        ux = (t.vertices[b].x - t.vertices[a].x) / l;
        uy = (t.vertices[b].y - t.vertices[a].y) / l;
      } else {
        ux = uy = 0.0;  // a zero-length edge has no direction and contributes nothing
      }
      lam = w * model.lambda_of(type[c], type[t.cell_neighbor[o + k]]);
    };

    double in_x, in_y, in_lam;
    edge(m - 1, in_x, in_y, in_lam);
    for (int k = 0; k < m; ++k) {
      double out_x, out_y, out_lam;
      edge(k, out_x, out_y, out_lam);
      const Vec2 &hp = t.vertices[t.cell_vertex[o + (k + m - 1) % m]];
      const Vec2 &hn = t.vertices[t.cell_vertex[o + (k + 1) % m]];
      // dA/dh_k = 1/2 (h_{k+1} - h_{k-1}) x z ; dP/dh_k = u_in - u_out.
      Vec2 &g = grad[t.cell_vertex[o + k]];
      g.x += 0.5 * dEdA * (hn.y - hp.y) + (dEdP + in_lam) * in_x - (dEdP + out_lam) * out_x;
      g.y += 0.5 * dEdA * (hp.x - hn.x) + (dEdP + in_lam) * in_y - (dEdP + out_lam) * out_y;
      in_x = out_x;
      in_y = out_y;
      in_lam = out_lam;
    }
  }

  // Push dE/dh onto the triangle corners: F_p = -(dh/dr_p)^T dE/dh.
  for (int tri = 0; tri < nt; ++tri) {
    const Vec2 g = grad[tri];
    if (g.x == 0.0 && g.y == 0.0) continue;
    const int ia = t.triangles[tri][0], ib = t.triangles[tri][1], ic = t.triangles[tri][2];
    const double ax = pts.x(ia), ay = pts.y(ia);
    const double bx = pts.x(ib) - ax, by = pts.y(ib) - ay;
    const double cx = pts.x(ic) - ax, cy = pts.y(ic) - ay;
    const double D = 2.0 * (bx * cy - by * cx);
    const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const double ux = (cy * b2 - by * c2) / D, uy = (bx * c2 - cx * b2) / D;
    // u = N / D with u = h - a; Jacobians with respect to b' = b - a, c' = c - a:
    //   du/db' = (dN/db' - u (dD/db')^T) / D, dD/db' = 2 (cy, -cx), dD/dc' = 2 (-by, bx).
    const double Jb_xx = (2.0 * cy * bx - ux * 2.0 * cy) / D;
    const double Jb_xy = (2.0 * cy * by - c2 + ux * 2.0 * cx) / D;
    const double Jb_yx = (c2 - 2.0 * cx * bx - uy * 2.0 * cy) / D;
    const double Jb_yy = (-2.0 * cx * by + uy * 2.0 * cx) / D;
    const double Jc_xx = (-2.0 * by * cx + ux * 2.0 * by) / D;
    const double Jc_xy = (b2 - 2.0 * by * cy - ux * 2.0 * bx) / D;
    const double Jc_yx = (2.0 * bx * cx - b2 + uy * 2.0 * by) / D;
    const double Jc_yy = (2.0 * bx * cy - uy * 2.0 * bx) / D;
    // F = -J^T g for b and c; a takes the rest (the three Jacobians sum to I).
    const double fbx = -(Jb_xx * g.x + Jb_yx * g.y), fby = -(Jb_xy * g.x + Jb_yy * g.y);
    const double fcx = -(Jc_xx * g.x + Jc_yx * g.y), fcy = -(Jc_xy * g.x + Jc_yy * g.y);
    const double fax = -g.x - fbx - fcx, fay = -g.y - fby - fcy;
    f[static_cast<long>(ia) * f_stride] += fax;
    f[static_cast<long>(ia) * f_stride + 1] += fay;
    f[static_cast<long>(ib) * f_stride] += fbx;
    f[static_cast<long>(ib) * f_stride + 1] += fby;
    f[static_cast<long>(ic) * f_stride] += fcx;
    f[static_cast<long>(ic) * f_stride + 1] += fcy;
    // Virial sum r (x) F over the corners, written relative to a plus a's
    // share: sum_p r_p F_p = sum_p (r_p - a) F_p + a (sum_p F_p), sum_p F_p = -g.
    out.virial[0] += bx * fbx + cx * fcx - ax * g.x;
    out.virial[1] += by * fby + cy * fcy - ay * g.y;
    out.virial[2] += bx * fby + cx * fcy - ax * g.y;
    out.virial[3] += by * fbx + cy * fcx - ay * g.x;
  }
  return out;
}

std::vector<double> positions_of(const Tessellation &t) {
  std::vector<double> xy(2 * t.position.size());
  for (size_t p = 0; p < t.position.size(); ++p) {
    xy[2 * p] = t.position[p].x;
    xy[2 * p + 1] = t.position[p].y;
  }
  return xy;
}

ForceOutput periodic_forces(const Box &box, const Points &pts, const int *type,
                            const Model &model, std::vector<double> &f,
                            std::vector<double> *cell_energy) {
  model.validate();
  const Tessellation t = tessellate_periodic(box, pts);
  const std::vector<double> xy = positions_of(t);
  std::vector<int> all_type(t.n_points);
  for (int p = 0; p < t.n_points; ++p) {
    const int ty = type[t.origin[p]];
    if (ty < 0 || ty >= model.ntypes()) {
      std::ostringstream s;
      s << "tessera: point " << t.origin[p] << " has type " << ty << ", outside [0, "
        << model.ntypes() << ")";
      throw Error(s.str());
    }
    all_type[p] = ty;
  }
  std::vector<double> fall(2 * static_cast<size_t>(t.n_points), 0.0);
  if (cell_energy) cell_energy->assign(t.n_owned, 0.0);
  const ForceOutput out = compute_forces(t, Points{xy.data(), t.n_points, 2}, all_type.data(),
                                         model, fall.data(), 2,
                                         cell_energy ? cell_energy->data() : nullptr);
  f.assign(2 * static_cast<size_t>(pts.n), 0.0);
  for (int p = 0; p < t.n_points; ++p) {
    f[2 * t.origin[p]] += fall[2 * p];
    f[2 * t.origin[p] + 1] += fall[2 * p + 1];
  }
  return out;
}

}  // namespace tessera
