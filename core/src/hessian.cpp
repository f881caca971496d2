// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Exact Hessian of the energy.  For each owned cell c the energy
//   e_c = K/2 (A - A0)^2 + Gamma/2 P^2 + w sum_k Lambda_k l_k
// is a function of the cell's centre and its m Voronoi neighbours (local
// coordinates X, 2 (m + 1) of them): its vertices h_k are circumcentres of
// (c, n_{k-1}, n_k), its area the shoelace sum of the h_k, and its edge k the
// projection l_k = (h_{k+1} - h_k) . nhat_k on the unit normal of the Delaunay
// edge (c, n_k).  We carry the value, the gradient and the Hessian in X of
// every vertex (first and second derivatives of the circumcentre), of A and of
// each l_k, combine them by the chain rule into the cell's dim x dim Hessian
// and scatter it onto the global points.

#include "tessera/hessian.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace tessera {

void SparseMatrix::compress() {
  const size_t nnz = val.size();
  std::vector<size_t> order(nnz);
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return row[a] != row[b] ? row[a] < row[b] : col[a] < col[b];
  });
  std::vector<int> r, c;
  std::vector<double> v;
  r.reserve(nnz);
  c.reserve(nnz);
  v.reserve(nnz);
  for (size_t k : order) {
    if (!r.empty() && r.back() == row[k] && c.back() == col[k]) {
      v.back() += val[k];
    } else {
      r.push_back(row[k]);
      c.push_back(col[k]);
      v.push_back(val[k]);
    }
  }
  row.swap(r);
  col.swap(c);
  val.swap(v);
}

namespace {

// Circumcentre h of the triangle (a, b, c), p = (ax, ay, bx, by, cx, cy), with
// its Jacobian J[alpha * 6 + i] = dh_alpha/dp_i and second derivatives
// H[alpha * 36 + i * 6 + j].  With q = (b - a, c - a) = (bx', by', cx', cy'),
// h = a + N(q) / D(q), D = 2 (bx' cy' - by' cx'),
// N = (cy' |b'|^2 - by' |c'|^2, bx' |c'|^2 - cx' |b'|^2): polynomials, so the
// derivatives of u = N / D follow from the quotient rule.
void circumcentre_derivatives(const double p[6], double h[2], double J[12], double H[72]) {
  const double bx = p[2] - p[0], by = p[3] - p[1], cx = p[4] - p[0], cy = p[5] - p[1];
  const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const double D = 2.0 * (bx * cy - by * cx);
  const double dD[4] = {2.0 * cy, -2.0 * cx, -2.0 * by, 2.0 * bx};
  double d2D[4][4] = {};
  d2D[0][3] = d2D[3][0] = 2.0;
  d2D[1][2] = d2D[2][1] = -2.0;
  const double N[2] = {cy * b2 - by * c2, bx * c2 - cx * b2};
  const double dN[2][4] = {{2.0 * bx * cy, 2.0 * by * cy - c2, -2.0 * by * cx, b2 - 2.0 * by * cy},
                           {c2 - 2.0 * cx * bx, -2.0 * cx * by, 2.0 * bx * cx - b2, 2.0 * bx * cy}};
  double d2N[2][4][4] = {};
  // N_x
  d2N[0][0][0] = 2.0 * cy;
  d2N[0][0][3] = d2N[0][3][0] = 2.0 * bx;
  d2N[0][1][1] = 2.0 * cy;
  d2N[0][1][2] = d2N[0][2][1] = -2.0 * cx;
  d2N[0][1][3] = d2N[0][3][1] = 2.0 * by - 2.0 * cy;
  d2N[0][2][2] = -2.0 * by;
  d2N[0][3][3] = -2.0 * by;
  // N_y
  d2N[1][0][0] = -2.0 * cx;
  d2N[1][0][2] = d2N[1][2][0] = 2.0 * cx - 2.0 * bx;
  d2N[1][0][3] = d2N[1][3][0] = 2.0 * cy;
  d2N[1][1][1] = -2.0 * cx;
  d2N[1][1][2] = d2N[1][2][1] = -2.0 * by;
  d2N[1][2][2] = 2.0 * bx;
  d2N[1][3][3] = 2.0 * bx;

  const double iD = 1.0 / D, iD2 = iD * iD, iD3 = iD2 * iD;
  double du[2][4], d2u[2][4][4];
  for (int a = 0; a < 2; ++a) {
    for (int i = 0; i < 4; ++i) du[a][i] = dN[a][i] * iD - N[a] * dD[i] * iD2;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        d2u[a][i][j] = d2N[a][i][j] * iD - (dN[a][i] * dD[j] + dD[i] * dN[a][j]) * iD2 +
                       2.0 * N[a] * dD[i] * dD[j] * iD3 - N[a] * d2D[i][j] * iD2;
  }
  h[0] = p[0] + N[0] * iD;
  h[1] = p[1] + N[1] * iD;
  // q = L p: bx' = p2 - p0, by' = p3 - p1, cx' = p4 - p0, cy' = p5 - p1.
  static const double L[4][6] = {{-1, 0, 1, 0, 0, 0},
                                 {0, -1, 0, 1, 0, 0},
                                 {-1, 0, 0, 0, 1, 0},
                                 {0, -1, 0, 0, 0, 1}};
  for (int a = 0; a < 2; ++a) {
    for (int i = 0; i < 6; ++i) {
      double s = (i == a) ? 1.0 : 0.0;
      for (int k = 0; k < 4; ++k) s += du[a][k] * L[k][i];
      J[a * 6 + i] = s;
    }
    double tmp[4][6];
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 6; ++j) {
        double s = 0.0;
        for (int l = 0; l < 4; ++l) s += d2u[a][k][l] * L[l][j];
        tmp[k][j] = s;
      }
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        double s = 0.0;
        for (int k = 0; k < 4; ++k) s += L[k][i] * tmp[k][j];
        H[a * 36 + i * 6 + j] = s;
      }
  }
}

}  // namespace

void compute_hessian(const Tessellation &t, const Points &pts, const int *type,
                     const Model &model, SparseMatrix &hm) {
  hm.n = 2 * t.n_points;
  const double w = model.tension_weight();
  std::vector<int> loc;              // local point -> global point
  std::vector<double> Jv, Hv, hv;    // per vertex: 2 x dim, 2 x dim x dim, 2
  std::vector<double> gA, HA, gP, He, Dd, NX, gl, Hl;
  for (int c = 0; c < t.n_owned; ++c) {
    const int m = t.cell_size(c);
    if (m == 0) continue;
    const int o = t.cell_offset[c];
    const int *cv = &t.cell_vertex[o];
    const int *cn = &t.cell_neighbor[o];
    loc.assign(1, c);
    for (int k = 0; k < m; ++k) loc.push_back(cn[k]);
    const int np = m + 1, dim = 2 * np;
    auto nb = [m](int j) { return 1 + ((j % m) + m) % m; };  // local index of neighbour j

    // Vertices: circumcentres of (c, n_{k-1}, n_k).
    Jv.assign(static_cast<size_t>(m) * 2 * dim, 0.0);
    Hv.assign(static_cast<size_t>(m) * 2 * dim * dim, 0.0);
    hv.assign(2 * static_cast<size_t>(m), 0.0);
    for (int k = 0; k < m; ++k) {
      const int tri = cv[k];
      if (t.triangle_group[tri] >= 0) {
        const Vec2 &V = t.vertices[tri];
        std::ostringstream s;
        s << "tessera: the Hessian is not defined at a multifold vertex: cell " << c
          << " has a vertex at (" << V.x << ", " << V.y << ") shared by "
          << t.group_offset[t.triangle_group[tri] + 1] - t.group_offset[t.triangle_group[tri]]
          << " cells (co-circular centres, e.g. a square lattice); the energy has a kink there. "
             "Perturb the positions, or measure moduli by finite strain steps";
        throw Error(s.str());
      }
      const int corner[3] = {0, nb(k - 1), nb(k)};
      const auto &tv = t.triangles[tri];
      for (int s = 0; s < 3; ++s) {
        const int g = loc[corner[s]];
        if (tv[0] != g && tv[1] != g && tv[2] != g)
          throw Error("tessera: internal error: a cell's vertex triangle misses its neighbour");
      }
      double p[6], h[2], J[12], H[72];
      for (int s = 0; s < 3; ++s) {
        p[2 * s] = pts.x(loc[corner[s]]);
        p[2 * s + 1] = pts.y(loc[corner[s]]);
      }
      circumcentre_derivatives(p, h, J, H);
      hv[2 * k] = h[0];
      hv[2 * k + 1] = h[1];
      double *Jk = &Jv[static_cast<size_t>(k) * 2 * dim];
      double *Hk = &Hv[static_cast<size_t>(k) * 2 * dim * dim];
      for (int a = 0; a < 2; ++a)
        for (int s = 0; s < 3; ++s)
          for (int b = 0; b < 2; ++b) {
            const int i = 2 * corner[s] + b;
            Jk[a * dim + i] += J[a * 6 + 2 * s + b];
            for (int s2 = 0; s2 < 3; ++s2)
              for (int b2 = 0; b2 < 2; ++b2) {
                const int j = 2 * corner[s2] + b2;
                Hk[(static_cast<size_t>(a) * dim + i) * dim + j] +=
                    H[a * 36 + (2 * s + b) * 6 + 2 * s2 + b2];
              }
          }
    }
    auto Jat = [&](int k, int a) { return &Jv[(static_cast<size_t>(k) * 2 + a) * dim]; };
    auto Hat = [&](int k, int a) { return &Hv[(static_cast<size_t>(k) * 2 + a) * dim * dim]; };

    // Area A = 1/2 sum_k h_k x h_{k+1}.
    double A = 0.0;
    gA.assign(dim, 0.0);
    HA.assign(static_cast<size_t>(dim) * dim, 0.0);
    for (int k = 0; k < m; ++k) {
      const int kn = (k + 1) % m, kp = (k + m - 1) % m;
      A += 0.5 * (hv[2 * k] * hv[2 * kn + 1] - hv[2 * kn] * hv[2 * k + 1]);
      const double ax = 0.5 * (hv[2 * kn + 1] - hv[2 * kp + 1]);
      const double ay = 0.5 * (hv[2 * kp] - hv[2 * kn]);
      const double *Jx = Jat(k, 0), *Jy = Jat(k, 1);
      const double *Hx = Hat(k, 0), *Hy = Hat(k, 1);
      for (int i = 0; i < dim; ++i) gA[i] += ax * Jx[i] + ay * Jy[i];
      for (size_t ij = 0; ij < HA.size(); ++ij) HA[ij] += ax * Hx[ij] + ay * Hy[ij];
      // d2A/dx_k dy_{k+1} = 1/2, d2A/dy_k dx_{k+1} = -1/2 (and transposes).
      const double *Jnx = Jat(kn, 0), *Jny = Jat(kn, 1);
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j) {
          const double v = 0.5 * (Jx[i] * Jny[j] - Jy[i] * Jnx[j]);
          HA[static_cast<size_t>(i) * dim + j] += v;
          HA[static_cast<size_t>(j) * dim + i] += v;
        }
    }

    const int tc = type[c];
    // The cell's K, A0, Gamma in use and the per-cell shift of its linear
    // perimeter term (Model::cell_params; 0 without per-cell KA, KP, P0).
    const Model::CellParams ct = model.cell_params(c, tc);
    He.assign(static_cast<size_t>(dim) * dim, 0.0);
    gP.assign(dim, 0.0);
    double P = 0.0;
    // Edge k (h_k -> h_{k+1}) against neighbour n_k: l = d . nhat with
    // d = h_{k+1} - h_k and nhat = rot90(e) / |e|, e = r_{n_k} - r_c.
    // First pass: P (needed for the coefficients); keep nothing.
    std::vector<double> lk(m);
    for (int k = 0; k < m; ++k) {
      const int kn = (k + 1) % m, q = loc[nb(k)];
      const double ex = pts.x(q) - pts.x(c), ey = pts.y(q) - pts.y(c);
      const double r = std::hypot(ex, ey);
      const double nx = -ey / r, ny = ex / r;
      lk[k] = (hv[2 * kn] - hv[2 * k]) * nx + (hv[2 * kn + 1] - hv[2 * k + 1]) * ny;
      P += lk[k];
    }
    for (int k = 0; k < m; ++k) {
      const int kn = (k + 1) % m, ql = nb(k), q = loc[ql];
      const double ex = pts.x(q) - pts.x(c), ey = pts.y(q) - pts.y(c);
      const double r = std::hypot(ex, ey);
      const double s[2] = {ex / r, ey / r};
      const double nh[2] = {-s[1], s[0]};
      const double d[2] = {hv[2 * kn] - hv[2 * k], hv[2 * kn + 1] - hv[2 * k + 1]};
      // ds_a/de_b and d2s_a/de_b de_g; nhat_x = -s_y, nhat_y = s_x.
      double ds[2][2], d2s[2][2][2];
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
          ds[a][b] = ((a == b) - s[a] * s[b]) / r;
          for (int g = 0; g < 2; ++g)
            d2s[a][b][g] = -((a == g) * s[b] + (b == g) * s[a] + (a == b) * s[g] -
                             3.0 * s[a] * s[b] * s[g]) /
                           (r * r);
        }
      double dn[2][2], d2n[2][2][2];
      for (int b = 0; b < 2; ++b) {
        dn[0][b] = -ds[1][b];
        dn[1][b] = ds[0][b];
        for (int g = 0; g < 2; ++g) {
          d2n[0][b][g] = -d2s[1][b][g];
          d2n[1][b][g] = d2s[0][b][g];
        }
      }
      // Derivatives of d and nhat in X.
      Dd.assign(2 * static_cast<size_t>(dim), 0.0);
      NX.assign(2 * static_cast<size_t>(dim), 0.0);
      for (int a = 0; a < 2; ++a) {
        const double *J1 = Jat(kn, a), *J0 = Jat(k, a);
        for (int i = 0; i < dim; ++i) Dd[a * dim + i] = J1[i] - J0[i];
        for (int b = 0; b < 2; ++b) {
          NX[a * dim + 2 * ql + b] += dn[a][b];
          NX[a * dim + b] -= dn[a][b];
        }
      }
      gl.assign(dim, 0.0);
      for (int i = 0; i < dim; ++i)
        for (int a = 0; a < 2; ++a) gl[i] += Dd[a * dim + i] * nh[a] + NX[a * dim + i] * d[a];
      Hl.assign(static_cast<size_t>(dim) * dim, 0.0);
      for (int a = 0; a < 2; ++a) {
        const double *H1 = Hat(kn, a), *H0 = Hat(k, a);
        for (size_t ij = 0; ij < Hl.size(); ++ij) Hl[ij] += nh[a] * (H1[ij] - H0[ij]);
      }
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j) {
          double v = 0.0;
          for (int a = 0; a < 2; ++a)
            v += Dd[a * dim + i] * NX[a * dim + j] + NX[a * dim + i] * Dd[a * dim + j];
          Hl[static_cast<size_t>(i) * dim + j] += v;
        }
      // sum_a d_a d2nhat_a/dX dX: e = r_q - r_c, so the (c, q) blocks carry signs.
      const int pidx[2] = {0, ql};
      const double sgn[2] = {-1.0, 1.0};
      for (int u = 0; u < 2; ++u)
        for (int v = 0; v < 2; ++v)
          for (int b = 0; b < 2; ++b)
            for (int g = 0; g < 2; ++g) {
              double val = 0.0;
              for (int a = 0; a < 2; ++a) val += d[a] * d2n[a][b][g];
              Hl[static_cast<size_t>(2 * pidx[u] + b) * dim + 2 * pidx[v] + g] +=
                  sgn[u] * sgn[v] * val;
            }
      const double coef = ct.Gamma * P + ct.shift + w * model.lambda_of(tc, type[cn[k]]);
      for (size_t ij = 0; ij < He.size(); ++ij) He[ij] += coef * Hl[ij];
      for (int i = 0; i < dim; ++i) gP[i] += gl[i];
    }
    const double dA = A - ct.A0;
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) {
        const size_t ij = static_cast<size_t>(i) * dim + j;
        He[ij] += ct.K * (gA[i] * gA[j] + dA * HA[ij]) + ct.Gamma * gP[i] * gP[j];
      }
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) {
        const double v = He[static_cast<size_t>(i) * dim + j];
        if (v == 0.0) continue;
        hm.row.push_back(2 * loc[i / 2] + i % 2);
        hm.col.push_back(2 * loc[j / 2] + j % 2);
        hm.val.push_back(v);
      }
  }
}

void affine_terms(const Tessellation &t, const SparseMatrix &full, const double D[4],
                  double &born, std::vector<double> &xi) {
  const int np = t.n_points;
  std::vector<double> v(2 * static_cast<size_t>(np)), Hv(2 * static_cast<size_t>(np), 0.0);
  for (int p = 0; p < np; ++p) {
    const Vec2 &r = t.position[p];
    v[2 * p] = D[0] * r.x + D[1] * r.y;
    v[2 * p + 1] = D[2] * r.x + D[3] * r.y;
  }
  for (size_t k = 0; k < full.val.size(); ++k) Hv[full.row[k]] += full.val[k] * v[full.col[k]];
  born = 0.0;
  for (size_t i = 0; i < v.size(); ++i) born += v[i] * Hv[i];
  xi.assign(2 * static_cast<size_t>(t.n_owned), 0.0);
  for (int p = 0; p < np; ++p) {
    xi[2 * t.origin[p]] += Hv[2 * p];
    xi[2 * t.origin[p] + 1] += Hv[2 * p + 1];
  }
}

PeriodicHessian periodic_hessian(const Box &box, const Points &pts, const int *type,
                                 const Model &model) {
  model.validate();
  const Tessellation t = tessellate_periodic(box, pts);
  const std::vector<double> xy = positions_of(t);
  const Points all{xy.data(), t.n_points, 2};
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
  PeriodicHessian out;
  out.n = pts.n;
  out.area = box.area();
  std::vector<double> fall(2 * static_cast<size_t>(t.n_points), 0.0);
  const ForceOutput fo = compute_forces(t, all, all_type.data(), model, fall.data(), 2);
  out.energy = fo.energy;
  for (int k = 0; k < 4; ++k) out.virial[k] = fo.virial[k];
  out.force.assign(2 * static_cast<size_t>(pts.n), 0.0);
  for (int p = 0; p < t.n_points; ++p) {
    out.force[2 * t.origin[p]] += fall[2 * p];
    out.force[2 * t.origin[p] + 1] += fall[2 * p + 1];
  }
  SparseMatrix full;
  compute_hessian(t, all, all_type.data(), model, full);
  const double shear[4] = {0.0, 1.0, 0.0, 0.0}, dilation[4] = {1.0, 0.0, 0.0, 1.0};
  affine_terms(t, full, shear, out.born_shear, out.xi_shear);
  affine_terms(t, full, dilation, out.born_dilation, out.xi_dilation);
  out.hessian.n = 2 * pts.n;
  out.hessian.row.resize(full.val.size());
  out.hessian.col.resize(full.val.size());
  out.hessian.val = full.val;
  for (size_t k = 0; k < full.val.size(); ++k) {
    out.hessian.row[k] = 2 * t.origin[full.row[k] / 2] + full.row[k] % 2;
    out.hessian.col[k] = 2 * t.origin[full.col[k] / 2] + full.col[k] % 2;
  }
  out.hessian.compress();
  return out;
}

}  // namespace tessera
