// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The 3D energy and its exact gradient (forces on the centres, the virial),
// from the cells of voronoi3d.cpp: the chain rule through the circumcentres
// (doc/model.md, "Three dimensions").

#include "tessera/voronoi3d.h"

#include "fourfold3d.h"
#include "vec3_detail.h"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace tessera {

using namespace detail3;

namespace {

// Energies or forces beyond double's range: an Error naming the cell (its
// owner for a periodic image) and the value, never inf or NaN.
[[noreturn]] void throw_overflow_3d(const Tessellation3 &t, int c, const char *what, double value) {
  std::ostringstream s;
  s.precision(17);
  s << "tessera: the " << what;
  if (c >= 0) {
    const int o = t.origin.empty() ? c : t.origin[c];
    s << (std::string(what).find("force") == 0 ? " of point " : " of the cell of point ") << o;
  }
  s << " is not finite (" << value << ")";
  if (c >= 0 && c < t.n_owned)
    s << "; the cell has volume " << t.volume[c] << " and surface " << t.surface[c];
  s << ": the parameters are far outside reduced units; rescale the units (length, energy) "
       "so that K V0^2, Gamma S^2 and Lambda S stay well below 1e300";
  throw Error(s.str());
}

// Per-cell energies and their sum.
double energy_3d(const Tessellation3 &t, const int *type, const Model &model, double *cell_energy) {
  const double w = model.tension_weight();
  double total = 0.0;
  for (int c = 0; c < t.n_owned; ++c) {
    const Model::CellParams ct = model.cell_params(c, type[c]);
    double tension = 0.0;
    for (int f = t.cell_offset[c]; f < t.cell_offset[c + 1]; ++f)
      tension += model.lambda_of(type[c], type[t.face_neighbor[f]]) * t.face_area[f];
    const double dv = t.volume[c] - ct.A0;
    const double e = 0.5 * ct.K * dv * dv + 0.5 * ct.Gamma * t.surface[c] * t.surface[c] +
                     w * tension + ct.shift * t.surface[c];
    if (!std::isfinite(e)) throw_overflow_3d(t, c, "energy", e);
    if (cell_energy) cell_energy[c] = e;
    total += e;
  }
  if (!std::isfinite(total)) throw_overflow_3d(t, -1, "total energy", total);
  return total;
}

}  // namespace

double compute_energy_3d(const Tessellation3 &t, const int *type, const Model &model,
                         double *cell_energy) {
  return energy_3d(t, type, model, cell_energy);
}

namespace {

// (dh/dp)^T g for the four points of tetrahedron v: calls add(point, force).
template <class Add>
void chain_rule(const Tessellation3 &t, const Points3 &pts, int v, V3 gv, Add add) {
  const auto &q = t.tets[v];
  const V3 p0 = load(pts, q[0]);
  const V3 e[3] = {load(pts, q[1]) - p0, load(pts, q[2]) - p0, load(pts, q[3]) - p0};
  const V3 col[3] = {cross(e[1], e[2]), cross(e[2], e[0]), cross(e[0], e[1])};
  const double det = dot(e[0], col[0]);
  const V3 h = vv(t.vertices[v]);
  V3 sum{0, 0, 0};
  for (int m = 0; m < 3; ++m) {
    // (dh/dp_m)^T g = (p_m - h) (A^{-1}[:, m] . g)
    const V3 df = (dot(col[m], gv) / det) * (load(pts, q[m + 1]) - h);
    add(q[m + 1], -1.0 * df);
    sum = sum + df;
  }
  // dh/dp0 = I - sum_m dh/dp_m
  add(q[0], -1.0 * (gv - sum));
}

}  // namespace

ForceOutput3 compute_forces_3d(const Tessellation3 &t, const Points3 &pts, const int *type,
                               const Model &model, double *f, int f_stride, double *cell_energy,
                               double *cell_virial) {
  ForceOutput3 out;
  std::vector<double> ce(t.n_owned);
  out.energy = energy_3d(t, type, model, ce.data());
  if (cell_energy) std::copy(ce.begin(), ce.end(), cell_energy);

  const double w = model.tension_weight();
  std::vector<V3> g(t.tets.size(), V3{0, 0, 0});
  std::vector<V3> u;
  // Forces sent to the points directly (the four-fold edges' triangle
  // routes), as the chain rule below adds them.
  std::vector<V3> force(t.n_points, V3{0, 0, 0});
  const FourFoldIndex ff(t, pts);
  std::vector<int> ring;
  // With cell_virial: each cell's dE_c/dh on its own tetrahedra, then its
  // forces and their virial about the cell's centre.
  std::vector<int> own;
  std::vector<V3> gc;
  std::vector<int> stamp(cell_virial ? t.tets.size() : 0, -1);
  if (cell_virial) gc.assign(t.tets.size(), V3{0, 0, 0});
  for (int c = 0; c < t.n_owned; ++c) {
    own.clear();
    // (per-cell KV, KS, S0: Model::cell_params, shift_c S)
    const Model::CellParams ct = model.cell_params(c, type[c]);
    const double dedv = ct.K * (t.volume[c] - ct.A0);
    const double deds = ct.Gamma * t.surface[c] + ct.shift;
    const V3 xc = load(pts, c);
    double *wc = cell_virial ? cell_virial + 9 * static_cast<long>(c) : nullptr;
    if (wc)
      for (int a = 0; a < 9; ++a) wc[a] = 0.0;
    // A force on point p from this cell's term, sent directly.
    auto direct = [&](int p, V3 fp) {
      force[p] = force[p] + fp;
      if (wc) {
        const V3 r = load(pts, p) - xc;
        const double ra[3] = {r.x, r.y, r.z}, fb[3] = {fp.x, fp.y, fp.z};
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) wc[3 * a + b] += ra[a] * fb[b];
      }
    };
    auto to_tet = [&](int v, V3 dg) {
      g[v] = g[v] + dg;
      if (cell_virial) {
        if (stamp[v] != c) {
          stamp[v] = c;
          gc[v] = V3{0, 0, 0};
          own.push_back(v);
        }
        gc[v] = gc[v] + dg;
      }
    };
    for (int f = t.cell_offset[c]; f < t.cell_offset[c + 1]; ++f) {
      const int o = t.face_offset[f], m = t.face_offset[f + 1] - o;
      const int nb = t.face_neighbor[f];
      const double dedsf = deds + w * model.lambda_of(type[c], type[nb]);
      V3 d = load(pts, nb) - xc;
      const V3 nrm = (1.0 / std::sqrt(dot(d, d))) * d;
      if (!ff.empty()) {
        int nr = 0;
        const FourFoldIndex::Role *roles = ff.roles(c, nb, &nr);
        if (nr > 0) {
          // A diagonal of a four-fold edge: replaced by the mean over both
          // diagonals below.  A side: the ring without the edges' slivers,
          // each four-fold stretch one Voronoi edge whose gradient goes
          // half through each triangle of the square on this side.
          bool diagonal = false;
          for (int r = 0; r < nr; ++r) diagonal = diagonal || roles[r].diagonal;
          if (diagonal) continue;
          ring.clear();
          for (int k = 0; k < m; ++k) {
            const int v = t.face_vertex[o + k];
            bool drop = false;
            for (int r = 0; r < nr && !drop; ++r) drop = ff.is_square_tet(roles[r].edge, v);
            if (!drop) ring.push_back(v);
          }
          const int mr = static_cast<int>(ring.size());
          if (mr >= 2) {
            u.resize(mr);
            V3 av{0, 0, 0}, q{0, 0, 0};
            for (int k = 0; k < mr; ++k) u[k] = vv(t.vertices[ring[k]]) - xc;
            for (int k = 0; k < mr; ++k) {
              av = av + 0.5 * cross(u[k], u[k + 1 < mr ? k + 1 : 0]);
              q = q + u[k];
            }
            q = (1.0 / mr) * q;
            for (int k = 0; k < mr; ++k) {
              const int k1 = k + 1 < mr ? k + 1 : 0;
              const V3 de = u[k1] - u[k];
              const V3 piece = dedsf * (0.5 * cross(de, nrm)) +
                               dedv * ((1.0 / 3.0) * (0.5 * cross(de, q) + (0.5 / mr) * av));
              int edge = -1;
              for (int r = 0; r < nr && edge < 0; ++r) {
                const int e = roles[r].edge;
                if (std::sqrt(dot(de, de)) > ff.tol(e) && ff.on_axis(e, u[k] + xc) &&
                    ff.on_axis(e, u[k1] + xc))
                  edge = r;
              }
              if (edge < 0) {
                to_tet(ring[k], piece);
                to_tet(ring[k1], piece);
                continue;
              }
              // The square's two points other than c and nb.
              const auto &sq = t.fourfold[roles[edge].edge].p;
              int others[2], no = 0;
              for (const int p : sq)
                if (p != c && p != nb) others[no++] = p;
              for (const V3 P : {u[k] + xc, u[k1] + xc})
                for (const int p : others)
                  triangle_route(pts, piece, P, c, nb, p, 0.5, direct);
            }
            continue;
          }
        }
      }
      u.resize(m);
      V3 av{0, 0, 0}, q{0, 0, 0};
      for (int k = 0; k < m; ++k) u[k] = vv(t.vertices[t.face_vertex[o + k]]) - xc;
      // Neighbours in the ring without a modulo (an integer division each, a
      // large share of this loop); the same terms in the same order.
      for (int k = 0; k < m; ++k) {
        av = av + 0.5 * cross(u[k], u[k + 1 < m ? k + 1 : 0]);
        q = q + u[k];
      }
      q = (1.0 / m) * q;
      for (int k = 0; k < m; ++k) {
        const V3 diff = u[k + 1 < m ? k + 1 : 0] - u[k > 0 ? k - 1 : m - 1];
        const V3 dS = 0.5 * cross(diff, nrm);
        const V3 dV = (1.0 / 3.0) * (0.5 * cross(diff, q) + (1.0 / m) * av);
        const int v = t.face_vertex[o + k];
        to_tet(v, dedsf * dS + dedv * dV);
      }
    }
    if (!ff.empty()) {
      // Each diagonal of each four-fold edge at c with weight 1/2: the
      // 2-gon end[0], end[1] (area 0) whose two Voronoi edges are dual to
      // the two triangles on the diagonal.
      int nr = 0;
      const FourFoldIndex::Role *roles = ff.corners_of(c, &nr);
      for (int r = 0; r < nr; ++r) {
        const FourFoldEdge3 &e = t.fourfold[roles[r].edge];
        const int ci = roles[r].corner;
        const int nb = e.p[(ci + 2) % 4];
        const double dedsf = deds + w * model.lambda_of(type[c], type[nb]);
        const V3 dx = load(pts, nb) - xc;
        const V3 nrm = (1.0 / std::sqrt(dot(dx, dx))) * dx;
        const V3 X = vv(e.end[0]), Y = vv(e.end[1]);
        const V3 q = 0.5 * ((X - xc) + (Y - xc));
        const V3 de = Y - X;
        const V3 piece = dedsf * (0.5 * cross(de, nrm)) + dedv * ((1.0 / 6.0) * cross(de, q));
        // Going from X to Y (counter-clockwise about dx) crosses the
        // triangle whose third point lies beyond the edge X Y, along its
        // outward normal de x dx.
        const int p1 = e.p[(ci + 1) % 4], p3 = e.p[(ci + 3) % 4];
        const bool first = dot(load(pts, p1) - xc, cross(de, dx)) > 0.0;
        const int pxy = first ? p1 : p3, pyx = first ? p3 : p1;
        for (const V3 P : {X, Y}) {
          triangle_route(pts, piece, P, c, nb, pxy, 0.5, direct);
          triangle_route(pts, -1.0 * piece, P, c, nb, pyx, 0.5, direct);
        }
      }
    }
    if (cell_virial) {
      for (int v : own)
        chain_rule(t, pts, v, gc[v], [&](int p, V3 fp) {
          const V3 r = load(pts, p) - xc;
          const double ra[3] = {r.x, r.y, r.z}, fb[3] = {fp.x, fp.y, fp.z};
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) wc[3 * a + b] += ra[a] * fb[b];
        });
    }
  }
  // Chain rule through the circumcentres.
  for (size_t v = 0; v < t.tets.size(); ++v) {
    const V3 gv = g[v];
    if (gv.x == 0.0 && gv.y == 0.0 && gv.z == 0.0) continue;
    chain_rule(t, pts, static_cast<int>(v), gv, [&](int p, V3 fp) { force[p] = force[p] + fp; });
  }
  for (int p = 0; p < t.n_points; ++p)
    if (!std::isfinite(force[p].x) || !std::isfinite(force[p].y) || !std::isfinite(force[p].z))
      throw_overflow_3d(t, p, "force on the centre",
                        !std::isfinite(force[p].x) ? force[p].x
                        : !std::isfinite(force[p].y) ? force[p].y : force[p].z);
  for (int p = 0; p < t.n_points; ++p) {
    double *fp = f + static_cast<long>(p) * f_stride;
    fp[0] += force[p].x;
    fp[1] += force[p].y;
    fp[2] += force[p].z;
    const V3 r = load(pts, p);
    const double ra[3] = {r.x, r.y, r.z}, fb[3] = {force[p].x, force[p].y, force[p].z};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) out.virial[3 * a + b] += ra[a] * fb[b];
  }
  for (double v : out.virial)
    if (!std::isfinite(v)) throw_overflow_3d(t, -1, "virial", v);
  return out;
}

ForceOutput3 periodic_forces_3d(const Box3 &box, const Points3 &pts, const int *type,
                                const Model &model, std::vector<double> &f,
                                std::vector<double> *cell_energy) {
  const Tessellation3 t = tessellate_periodic_3d(box, pts);
  std::vector<int> ty(t.n_points);
  for (int p = 0; p < t.n_points; ++p) ty[p] = type[t.origin[p]];
  std::vector<double> fall(3 * static_cast<size_t>(t.n_points), 0.0);
  if (cell_energy) cell_energy->assign(t.n_owned, 0.0);
  const Points3 all{t.position.data(), t.n_points, 3};
  ForceOutput3 out = compute_forces_3d(t, all, ty.data(), model, fall.data(), 3,
                                       cell_energy ? cell_energy->data() : nullptr);
  f.assign(3 * static_cast<size_t>(pts.n), 0.0);
  for (int p = 0; p < t.n_points; ++p)
    for (int d = 0; d < 3; ++d) f[3 * t.origin[p] + d] += fall[3 * p + d];
  return out;
}

}  // namespace tessera

