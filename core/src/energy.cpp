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

void Model::validate_cells(int n_owned) const {
  auto check = [&](const double *v, const char *what, bool zero_ok) {
    if (!v) return;
    for (int c = 0; c < n_owned; ++c)
      if (!std::isfinite(v[c]) || v[c] < 0.0 || (v[c] == 0.0 && !zero_ok)) {
        std::ostringstream s;
        s.precision(17);
        s << "tessera: cell " << c << ": per-cell " << what << " must be "
          << (zero_ok ? ">= 0" : "> 0") << " and finite, got " << v[c];
        throw Error(s.str());
      }
  };
  check(cell_area0, "preferred area A0", false);
  check(cell_KA, "area modulus KA", false);
  check(cell_KP, "perimeter modulus KP", true);
  if (cell_P0)
    for (int c = 0; c < n_owned; ++c)
      if (!std::isfinite(cell_P0[c])) {
        std::ostringstream s;
        s << "tessera: cell " << c << ": per-cell preferred perimeter P0 must be finite, got "
          << cell_P0[c];
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
  const Model::CellParams p = m.cell_params(c, type[c]);
  const double dA = t.area[c] - p.A0;
  double e = 0.5 * p.K * dA * dA + 0.5 * p.Gamma * t.perimeter[c] * t.perimeter[c];
  double tension = 0.0;
  for (int k = t.cell_offset[c]; k < t.cell_offset[c + 1]; ++k)
    tension += m.lambda_of(type[c], type[t.cell_neighbor[k]]) * t.edge_length[k];
  return e + m.tension_weight() * tension + p.shift * t.perimeter[c];
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

namespace {

// The error for non-finite results (compute_forces' last check).
[[noreturn]] void throw_not_finite(const Tessellation &t, const Points &pts, double energy,
                                   const double *f, int f_stride) {
  std::ostringstream s;
  s.precision(17);
  s << "tessera: the energy or forces are not finite (energy " << energy << ")";
  int bad = -1;
  for (int p = 0; p < t.n_points && bad < 0; ++p)
    if (!std::isfinite(f[static_cast<long>(p) * f_stride]) ||
        !std::isfinite(f[static_cast<long>(p) * f_stride + 1]))
      bad = p;
  int cell = -1;
  for (int c = 0; c < t.n_owned && cell < 0; ++c)
    if (!std::isfinite(t.area[c]) || !std::isfinite(t.perimeter[c])) cell = c;
  if (bad >= 0) {
    const int o = t.origin.empty() ? bad : t.origin[bad];
    s << "; first at point " << o << " (" << pts.x(bad) << ", " << pts.y(bad) << "), force ("
      << f[static_cast<long>(bad) * f_stride] << ", " << f[static_cast<long>(bad) * f_stride + 1]
      << ")";
  }
  if (cell >= 0)
    s << "; the cell of point " << cell << " has area " << t.area[cell] << " and perimeter "
      << t.perimeter[cell];
  s << ": the moduli and lengths overflow double precision; rescale the units (length, "
       "energy) so that K A0^2, Gamma P^2 and Lambda P stay well below 1e300";
  throw Error(s.str());
}

}  // namespace

namespace {

// The closest pair of Voronoi neighbours so far (best2 < 0: none yet); the
// first of equal pairs stays.
inline void note_pair(const Points &pts, int c, double cx, double cy, int q, double &best2,
                      int &best_c, int &best_q) {
  const double dx = pts.x(q) - cx, dy = pts.y(q) - cy;
  const double d2 = dx * dx + dy * dy;
  if (best2 < 0.0 || d2 < best2) {
    best2 = d2;
    best_c = c;
    best_q = q;
  }
}

// The lean per-cell loop (no multifold vertex, no per-cell virial) over
// cells [c0, c1): each cell's energy and dE/dh added into grad, the energy
// sum and the closest pair of Voronoi neighbours carried in the references.
// PerCell: the model has per-cell KA, KP or P0 (Model::has_cell_params());
// without them the loop reads the types' values only (chosen once per call).
template <bool PerCell>
void lean_cells_t(const Tessellation &t, const Points &pts, const int *type, const Model &model,
                  double *cell_energy, Vec2 *grad, int c0, int c1, double &energy,
                  double &best2, int &best_c, int &best_q) {
  const double w = model.tension_weight();
  const int ntypes = model.ntypes();
  auto near_pair = [&](int c, double cx, double cy, int q) {
    note_pair(pts, c, cx, cy, q, best2, best_c, best_q);
  };
    const Vec2 *const H = t.vertices.data();
    for (int c = c0; c < c1; ++c) {
      const int o = t.cell_offset[c], m = t.cell_offset[c + 1] - o;
      const int tc = type[c];
      double K, A0, Gamma, shift = 0.0;
      if constexpr (PerCell) {
        const Model::CellParams p = model.cell_params(c, tc);
        K = p.K;
        A0 = p.A0;
        Gamma = p.Gamma;
        shift = p.shift;
      } else {
        const CellType &ct = model.types[tc];
        K = ct.K;
        A0 = model.area0_of(c, tc);
        Gamma = ct.Gamma;
      }
      const double dA = t.area[c] - A0;
      const double dEdA = K * dA;
      double dEdP = Gamma * t.perimeter[c];
      if constexpr (PerCell) dEdP += shift;
      const double *lam_row = &model.lambda[static_cast<size_t>(tc) * ntypes];
      double tension = 0.0;
      if (m > 0) {
        const int *cv = &t.cell_vertex[o];
        const int *cn = &t.cell_neighbor[o];
        const double *el = &t.edge_length[o];
        Vec2 hp = H[cv[m - 1]], hc = H[cv[0]];
        double in_x = 0.0, in_y = 0.0;
        if (el[m - 1] > 0.0) {
          const double inv = 1.0 / el[m - 1];
          in_x = (hc.x - hp.x) * inv;
          in_y = (hc.y - hp.y) * inv;
        }
        double in_lam = w * lam_row[type[cn[m - 1]]];
        const double pcx = pts.x(c), pcy = pts.y(c);
        for (int k = 0; k < m; ++k) {
          near_pair(c, pcx, pcy, cn[k]);
          const Vec2 hn = H[cv[k + 1 == m ? 0 : k + 1]];
          const double l = el[k];
          double out_x = 0.0, out_y = 0.0;
          if (l > 0.0) {
            const double inv = 1.0 / l;
            out_x = (hn.x - hc.x) * inv;
            out_y = (hn.y - hc.y) * inv;
          }
          const double lam = lam_row[type[cn[k]]];
          const double out_lam = w * lam;
          tension += lam * l;
          const double gx =
              0.5 * dEdA * (hn.y - hp.y) + (dEdP + in_lam) * in_x - (dEdP + out_lam) * out_x;
          const double gy =
              0.5 * dEdA * (hp.x - hn.x) + (dEdP + in_lam) * in_y - (dEdP + out_lam) * out_y;
          Vec2 &gr = grad[cv[k]];
          gr.x += gx;
          gr.y += gy;
          hp = hc;
          hc = hn;
          in_x = out_x;
          in_y = out_y;
          in_lam = out_lam;
        }
      }
      double ec = 0.5 * K * dA * dA + 0.5 * Gamma * t.perimeter[c] * t.perimeter[c] +
                  (m > 0 ? w * tension : 0.0);
      if constexpr (PerCell) ec += shift * t.perimeter[c];
      if (cell_energy) cell_energy[c] = ec;
      energy += ec;
    }
  }

void lean_cells(const Tessellation &t, const Points &pts, const int *type, const Model &model,
                double *cell_energy, Vec2 *grad, int c0, int c1, double &energy, double &best2,
                int &best_c, int &best_q) {
  if (model.has_cell_params())
    lean_cells_t<true>(t, pts, type, model, cell_energy, grad, c0, c1, energy, best2, best_c,
                       best_q);
  else
    lean_cells_t<false>(t, pts, type, model, cell_energy, grad, c0, c1, energy, best2, best_c,
                        best_q);
}

}  // namespace

ForceOutput compute_forces(const Tessellation &t, const Points &pts, const int *type,
                           const Model &model, double *f, int f_stride, double *cell_energy,
                           double *cell_virial, bool want_virial, const CellPass *pass) {
  ForceOutput out;
  const int nt = static_cast<int>(t.triangles.size());
  // dE/dh per Voronoi vertex; kept between calls so that a time step
  // allocates nothing once sizes have settled.
  thread_local std::vector<Vec2> grad_buffer;
  const bool use_pass = pass && t.group_centre.empty() && !cell_virial && pass->covers(t);
  if (!use_pass) grad_buffer.assign(nt, Vec2{});
  // one TLS lookup, not one per access
  Vec2 *const grad = use_pass ? const_cast<Vec2 *>(pass->grad.data()) : grad_buffer.data();
  const double w = model.tension_weight();
  // Sums kept in locals, not in `out` (the caller's return slot, which the
  // stores into f might alias, so every += would go through memory).
  double vir[4] = {0.0, 0.0, 0.0, 0.0};
  double energy = 0.0, fsum = 0.0;
  // The closest pair of Voronoi neighbours, found on the way.
  double best2 = -1.0;
  int best_c = -1, best_q = -1;
  auto near_pair = [&](int c, double cx, double cy, int q) {
    note_pair(pts, c, cx, cy, q, best2, best_c, best_q);
  };

  // F_p = -(dh/dr_p)^T g for the three corners of a triangle whose
  // circumcentre h has energy gradient g, and the virial of those forces.
  // Forces -(dh/dr_p)^T g on the corners a, b, c of a triangle whose
  // circumcentre h has energy gradient g: F[0..5] = (fa, fb, fc).
  auto corner_forces = [&](int ia, int ib, int ic, double gx, double gy, double *F) {
    const double ax = pts.x(ia), ay = pts.y(ia);
    const double bx = pts.x(ib) - ax, by = pts.y(ib) - ay;
    const double cx = pts.x(ic) - ax, cy = pts.y(ic) - ay;
    const double iD = 0.5 / (bx * cy - by * cx);  // 1 / D, D = 2 (b' x c')
    const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    const double ux = (cy * b2 - by * c2) * iD, uy = (bx * c2 - cx * b2) * iD;
    // u = N / D with u = h - a; Jacobians with respect to b' = b - a, c' = c - a:
    //   du/db' = (dN/db' - u (dD/db')^T) / D, dD/db' = 2 (cy, -cx), dD/dc' = 2 (-by, bx).
    const double Jb_xx = 2.0 * cy * (bx - ux) * iD;
    const double Jb_xy = (2.0 * (cy * by + ux * cx) - c2) * iD;
    const double Jb_yx = (c2 - 2.0 * (cx * bx + uy * cy)) * iD;
    const double Jb_yy = 2.0 * cx * (uy - by) * iD;
    const double Jc_xx = 2.0 * by * (ux - cx) * iD;
    const double Jc_xy = (b2 - 2.0 * (by * cy + ux * bx)) * iD;
    const double Jc_yx = (2.0 * (bx * cx + uy * by) - b2) * iD;
    const double Jc_yy = 2.0 * bx * (cy - uy) * iD;
    // F = -J^T g for b and c; a takes the rest (the three Jacobians sum to I).
    const double fbx = -(Jb_xx * gx + Jb_yx * gy), fby = -(Jb_xy * gx + Jb_yy * gy);
    const double fcx = -(Jc_xx * gx + Jc_yx * gy), fcy = -(Jc_xy * gx + Jc_yy * gy);
    const double fax = -gx - fbx - fcx, fay = -gy - fby - fcy;
    F[0] = fax;
    F[1] = fay;
    F[2] = fbx;
    F[3] = fby;
    F[4] = fcx;
    F[5] = fcy;
  };

  auto push = [&](int ia, int ib, int ic, double gx, double gy) {
    double F[6];
    corner_forces(ia, ib, ic, gx, gy, F);
    const double ax = pts.x(ia), ay = pts.y(ia);
    const double bx = pts.x(ib) - ax, by = pts.y(ib) - ay;
    const double cx = pts.x(ic) - ax, cy = pts.y(ic) - ay;
    const double fax = F[0], fay = F[1], fbx = F[2], fby = F[3], fcx = F[4], fcy = F[5];
    f[static_cast<long>(ia) * f_stride] += fax;
    f[static_cast<long>(ia) * f_stride + 1] += fay;
    f[static_cast<long>(ib) * f_stride] += fbx;
    f[static_cast<long>(ib) * f_stride + 1] += fby;
    f[static_cast<long>(ic) * f_stride] += fcx;
    f[static_cast<long>(ic) * f_stride + 1] += fcy;
    // Virial sum r (x) F over the corners, written relative to a plus a's
    // share: sum_p r_p F_p = sum_p (r_p - a) F_p + a (sum_p F_p), sum_p F_p = -g.
    if (want_virial) {
      vir[0] += bx * fbx + cx * fcx - ax * gx;
      vir[1] += by * fby + cy * fcy - ay * gy;
      vir[2] += bx * fby + cx * fcy - ax * gy;
      vir[3] += by * fbx + cy * fcx - ay * gx;
    } else {
      // Non-finite forces propagate into this sum (checked at the end).
      fsum += ((fax + fay) + (fbx + fby)) + (fcx + fcy);
    }
  };

  // Per-cell virial (optional): cell c's own energy term moves the corners
  // of its triangles; sum (r_p - r_c) (x) F_p over them.  Translation
  // invariance of each cell's energy makes this independent of the origin,
  // and the cells' virials add up to the total.
  double *wc = nullptr;
  auto cell_part = [&](int c, int ia, int ib, int ic, double gx, double gy) {
    if (!wc) return;
    double F[6];
    corner_forces(ia, ib, ic, gx, gy, F);
    const int corner[3] = {ia, ib, ic};
    for (int q = 0; q < 3; ++q) {
      const double rx = pts.x(corner[q]) - pts.x(c), ry = pts.y(corner[q]) - pts.y(c);
      wc[0] += rx * F[2 * q];
      wc[1] += ry * F[2 * q + 1];
      wc[2] += rx * F[2 * q + 1];
      wc[3] += ry * F[2 * q];
    }
  };

  thread_local std::vector<int> spokes;
  const int ntypes = model.ntypes();
  // Without multifold vertices and per-cell virials (every step of a run, in
  // practice) a lean loop does the same arithmetic in the same order (so the
  // same bits): each vertex loaded once and carried along the polygon, no
  // vertex-group look-ups.  The general loop below is its oracle.
  const bool lean = t.group_centre.empty() && !cell_virial;
  if (use_pass) {  // (implies lean)
    // The per-cell half was done while the cells were read (CellPass).
    energy = pass->energy;
    best2 = pass->best2;
    best_c = pass->best_c;
    best_q = pass->best_q;
  } else if (lean) {
    lean_cells(t, pts, type, model, cell_energy, grad, 0, t.n_owned, energy, best2, best_c,
               best_q);
  }
  for (int c = 0; !lean && c < t.n_owned; ++c) {
    if (cell_virial) {
      wc = cell_virial + 4 * static_cast<long>(c);
      wc[0] = wc[1] = wc[2] = wc[3] = 0.0;
    }
    const int o = t.cell_offset[c], m = t.cell_size(c);
    const int tc = type[c];
    // (without per-cell KA, KP, P0: the types' values and shift 0, which
    // leaves every sum below bit for bit as without it)
    const Model::CellParams ct = model.cell_params(c, tc);
    const double dA = t.area[c] - ct.A0;
    const double dEdA = ct.K * dA;
    const double dEdP = ct.Gamma * t.perimeter[c] + ct.shift;
    const double *lam_row = &model.lambda[static_cast<size_t>(tc) * ntypes];
    if (m == 0) {
      const double ec = 0.5 * ct.K * dA * dA + 0.5 * ct.Gamma * t.perimeter[c] * t.perimeter[c] +
                        ct.shift * t.perimeter[c];
      if (cell_energy) cell_energy[c] = ec;
      energy += ec;
      continue;
    }
    const int *cv = &t.cell_vertex[o];
    const int *cn = &t.cell_neighbor[o];
    const double *el = &t.edge_length[o];
    for (int k = 0; k < m; ++k) near_pair(c, pts.x(c), pts.y(c), cn[k]);
    auto wrap = [m](int k) { return k < 0 ? k + m : (k >= m ? k - m : k); };
    auto group_at = [&](int k) { return t.triangle_group[cv[wrap(k)]]; };

    // Unit vector of edge k (vertex k -> k+1); zero for a zero-length edge,
    // which only occurs inside a multifold vertex, handled below.
    auto unit = [&](int k, double &ux, double &uy) {
      const double l = el[k];
      if (l > 0.0) {
        const Vec2 &a = t.vertices[cv[k]], &b = t.vertices[cv[wrap(k + 1)]];
        const double inv = 1.0 / l;
        ux = (b.x - a.x) * inv;
        uy = (b.y - a.y) * inv;
      } else {
        ux = uy = 0.0;
      }
    };

    double tension = 0.0;
    double in_x, in_y;
    unit(m - 1, in_x, in_y);
    double in_lam = w * lam_row[type[cn[m - 1]]];
    for (int k = 0; k < m; ++k) {
      double out_x, out_y;
      unit(k, out_x, out_y);
      const double lam = lam_row[type[cn[k]]];
      const double out_lam = w * lam;
      tension += lam * el[k];
      const int g = t.triangle_group[cv[k]];
      if (g < 0) {
        const Vec2 &hp = t.vertices[cv[k == 0 ? m - 1 : k - 1]];
        const Vec2 &hn = t.vertices[cv[k + 1 == m ? 0 : k + 1]];
        // dA/dh_k = 1/2 (h_{k+1} - h_{k-1}) x z ; dP/dh_k = u_in - u_out.
        const double gx =
            0.5 * dEdA * (hn.y - hp.y) + (dEdP + in_lam) * in_x - (dEdP + out_lam) * out_x;
        const double gy =
            0.5 * dEdA * (hp.x - hn.x) + (dEdP + in_lam) * in_y - (dEdP + out_lam) * out_y;
        Vec2 &gr = grad[cv[k]];
        gr.x += gx;
        gr.y += gy;
        if (wc) {
          const auto &tri = t.triangles[cv[k]];
          cell_part(c, tri[0], tri[1], tri[2], gx, gy);
        }
      } else if (group_at(k - 1) != g || m == 1) {
        // A multifold vertex V, shared by the k >= 4 cells of the group's ring
        // w_0..w_{k-1}.  The energy has a kink there: each way of
        // triangulating the ring is one smooth branch.  We take the mean of
        // the branches' gradients over the k fan triangulations (from each
        // w_j), which for a four-fold vertex is exactly the mean of the two
        // one-sided derivatives, i.e. the central difference.  In each branch
        // the edges around V have length zero but the direction they take on
        // that branch's side: perpendicular to the Delaunay edge, rot90(q - c).
        int run_end = k;  // last polygon position at V
        while (run_end - k + 1 < m && group_at(run_end + 1) == g) ++run_end;
        const Vec2 &hp = t.vertices[cv[wrap(k - 1)]];
        const Vec2 &hn = t.vertices[cv[(run_end + 1) % m]];
        const Vec2 V = t.group_centre[g];
        const int *ring = &t.group_point[t.group_offset[g]];
        const int kk = t.group_offset[g + 1] - t.group_offset[g];
        int i = 0;
        while (i < kk && ring[i] != c) ++i;
        if (i == kk) throw Error("tessera: internal error: cell missing from its vertex ring");
        const double cxp = pts.x(c), cyp = pts.y(c);
        auto spoke_dir = [&](int q, double &ux, double &uy, double &lam) {
          const double dx = pts.x(q) - cxp, dy = pts.y(q) - cyp;
          const double d = std::hypot(dx, dy);
          ux = -dy / d;
          uy = dx / d;
          lam = w * model.lambda_of(type[c], type[q]);
        };
        const double inv_k = 1.0 / kk;
        for (int j = 0; j < kk; ++j) {
          // Spokes of c at V in branch j, from the in-edge's neighbour
          // w_{i+1} to the out-edge's neighbour w_{i-1}.
          spokes.assign(1, ring[(i + 1) % kk]);
          if (j == i) {
            for (int q = 2; q <= kk - 2; ++q) spokes.push_back(ring[(i + q) % kk]);
          } else if (j != (i + 1) % kk && j != (i + kk - 1) % kk) {
            spokes.push_back(ring[j]);
          }
          spokes.push_back(ring[(i + kk - 1) % kk]);
          const int M = static_cast<int>(spokes.size()) - 1;
          for (int s = 1; s <= M; ++s) {
            double ax, ay, al, bx, by, bl;
            spoke_dir(spokes[s - 1], ax, ay, al);
            spoke_dir(spokes[s], bx, by, bl);
            // The cell's in- and out-edges at V take the directions their
            // other ends use (the same up to the round-off of V, which far
            // from the origin is not small), so that the cell's gradients
            // add up to zero and the forces sum to zero.
            if (s == 1 && el[wrap(k - 1)] > 0.0) ax = in_x, ay = in_y;
            if (s == M && el[wrap(run_end)] > 0.0) unit(wrap(run_end), bx, by);
            double gx = (dEdP + al) * ax - (dEdP + bl) * bx;
            double gy = (dEdP + al) * ay - (dEdP + bl) * by;
            if (s == 1) {
              gx += 0.5 * dEdA * (V.y - hp.y);
              gy += 0.5 * dEdA * (hp.x - V.x);
            }
            if (s == M) {
              gx += 0.5 * dEdA * (hn.y - V.y);
              gy += 0.5 * dEdA * (V.x - hn.x);
            }
            push(c, spokes[s - 1], spokes[s], gx * inv_k, gy * inv_k);
            cell_part(c, c, spokes[s - 1], spokes[s], gx * inv_k, gy * inv_k);
          }
        }
      }
      in_x = out_x;
      in_y = out_y;
      in_lam = out_lam;
    }
    const double ec = 0.5 * ct.K * dA * dA + 0.5 * ct.Gamma * t.perimeter[c] * t.perimeter[c] +
                      w * tension + ct.shift * t.perimeter[c];
    if (cell_energy) cell_energy[c] = ec;
    energy += ec;
  }

  for (int tri = 0; tri < nt; ++tri) {
    const Vec2 g = grad[tri];
    if (g.x == 0.0 && g.y == 0.0) continue;
    push(t.triangles[tri][0], t.triangles[tri][1], t.triangles[tri][2], g.x, g.y);
  }
  out.energy = energy;
  for (int k = 0; k < 4; ++k) out.virial[k] = vir[k];
  out.closest_cell = best_c;
  out.closest_neighbor = best_q;
  out.closest_distance2 = best2;
  // Never return NaN or infinity silently.  The virial sums r (x) F over
  // every force contribution (a non-finite force makes it non-finite, also
  // at r = 0 where 0 * inf is NaN), so checking it and the energy costs
  // O(1) (without the virial the plain sum of the force components, fsum,
  // does the same); the search for the point to name runs only on failure.  With the
  // tessellation's input limits this is reached when the energy itself
  // overflows (moduli times lengths beyond double's range).
  if (!std::isfinite(out.energy) || !std::isfinite(fsum) || !std::isfinite(out.virial[0]) ||
      !std::isfinite(out.virial[1]) || !std::isfinite(out.virial[2]) ||
      !std::isfinite(out.virial[3]))
    throw_not_finite(t, pts, out.energy, f, f_stride);
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

void CellPass::begin(const Tessellation &t) {
  grad.assign(t.triangles.size(), Vec2{});
  energy = 0.0;
  best2 = -1.0;
  best_c = best_q = -1;
  done_ = 0;
  stamp_ = 0;
}

void CellPass::cells(const Tessellation &t, int c0, int c1) {
  if (!model_ || c0 != done_ || grad.size() != t.triangles.size()) {
    done_ = -1;  // out of order: never covers anything
    return;
  }
  lean_cells(t, pts_, type_, *model_, cell_energy_, grad.data(), c0, c1, energy, best2, best_c,
             best_q);
  done_ = c1;
}

void CellPass::end(const Tessellation &t) { stamp_ = done_ == t.n_owned ? t.mesh_stamp : 0; }

bool CellPass::covers(const Tessellation &t) const {
  return stamp_ != 0 && stamp_ == t.mesh_stamp && done_ == t.n_owned &&
         grad.size() == t.triangles.size();
}

}  // namespace tessera
