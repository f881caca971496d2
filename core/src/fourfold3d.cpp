// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Four-fold Voronoi edges in 3D: finding them (shared by tessellate_local_3d
// and Mesh3::cells through the TetGraph adjacency) and the index the forces
// use (fourfold3d.h; doc/model.md, "Four-fold edges (3D)").

#include "fourfold3d.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

namespace tessera {
namespace detail3 {

namespace {

double magnitude(V3 x) { return std::max({std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)}); }

// The distance tolerance for a sphere of centre h and radius r.
double tolerance(V3 h, double r) { return kFourFoldTol * r + kFourFoldUlps * (magnitude(h) + r); }

bool on_sphere(const Points3 &pts, int p, V3 h, double r, double tol) {
  const V3 d = load(pts, p) - h;
  return std::fabs(std::sqrt(dot(d, d)) - r) <= tol;
}

// The tetrahedra reachable from g across facets whose opposite corner lies
// on the sphere (h, r): a cluster of co-spherical points; their corners
// appended to pts_out.  false if the cluster is larger than cap.
bool cluster_points(TetGraph &graph, const Points3 &pts, long g, V3 h, double r, double tol,
                    std::vector<int> &out) {
  constexpr size_t cap = 64;
  std::vector<long> seen{g};
  for (size_t k = 0; k < seen.size(); ++k) {
    int q[4];
    graph.corners(seen[k], q);
    for (int s = 0; s < 4; ++s)
      if (q[s] >= 0) out.push_back(q[s]);
    for (int s = 0; s < 4; ++s) {
      const int o = graph.opposite(seen[k], s);
      if (o < 0 || !on_sphere(pts, o, h, r, tol)) continue;
      const long nb = graph.neighbor(seen[k], s);
      if (nb < 0 || std::find(seen.begin(), seen.end(), nb) != seen.end()) continue;
      if (seen.size() >= cap) return false;
      seen.push_back(nb);
    }
  }
  return true;
}

// Circumcentre of graph tetrahedron g if it is well-shaped and has no far
// corner.
bool centre_of(TetGraph &graph, const Points3 &pts, long g, V3 *h) {
  int q[4];
  graph.corners(g, q);
  for (int s = 0; s < 4; ++s)
    if (q[s] < 0) return false;
  const V3 p0 = load(pts, q[0]), p1 = load(pts, q[1]), p2 = load(pts, q[2]), p3 = load(pts, q[3]);
  if (!(flatness(p0, p1, p2, p3) >= kFourFoldSliver)) return false;
  *h = circumcentre(p0, p1, p2, p3);
  return true;
}

}  // namespace

void find_fourfold_edges(Tessellation3 &t, const Points3 &pts, TetGraph &g) {
  t.fourfold.clear();
  const int nt = static_cast<int>(t.tets.size());
  // Tetrahedra with a facet neighbour on their circumsphere (the same
  // circumcentre).  A facet with an owned corner lies between consecutive
  // tetrahedra of an owned cell's ring; the only other facets of t's
  // tetrahedra are those opposite the owned corner of a tetrahedron with
  // just one, asked of the builder's adjacency.
  std::vector<char> flag(nt, 0);
  bool any = false;
  {
    // A first filter with one bound for all: tolerance(h, r) is below
    // 1.1e-8 (r + |h|).
    double big = 0.0;
    for (int v = 0; v < nt; ++v)
      if (std::isfinite(t.radius[v])) big = std::max(big, t.radius[v] + magnitude(vv(t.vertices[v])));
    const double bound = 1.1e-8 * big;
    const int nf = t.cell_offset[t.n_owned];
    const int *fv = t.face_vertex.data();
    const Vec3 *hv = t.vertices.data();
    for (int f = 0; f < nf; ++f) {
      const int o = t.face_offset[f], e = t.face_offset[f + 1];
      int a = fv[e - 1];
      double xa = hv[a].x;
      for (int k = o; k < e; ++k) {
        const int b = fv[k];
        const double xb = hv[b].x;
        if (std::fabs(xa - xb) <= bound && a != b) {  // (rare: then the full test)
          const V3 d = vv(hv[a]) - vv(hv[b]);
          const double tol = tolerance(vv(hv[a]), t.radius[a]);
          if (dot(d, d) <= tol * tol) {
            flag[a] = flag[b] = 1;
            any = true;
          }
        }
        a = b;
        xa = xb;
      }
    }
  }
  for (int v = 0; v < nt; ++v) {
    int owned = 0, k = -1;
    for (int s = 0; s < 4; ++s)
      if (t.tets[v][s] < t.n_owned) {
        ++owned;
        k = s;
      }
    if (owned != 1 || flag[v]) continue;
    const double r = t.radius[v];
    if (!std::isfinite(r)) continue;
    const V3 h = vv(t.vertices[v]);
    const double tol = tolerance(h, r);
    const int w = g.t_neighbor(v, k);
    bool on = false;
    if (w >= 0) {
      const V3 d = vv(t.vertices[w]) - h;
      on = dot(d, d) <= tol * tol;
    } else if (w == -1) {
      const int o = g.opposite(g.id(v), k);
      on = o >= 0 && on_sphere(pts, o, h, r, tol);
    }
    if (on) {
      flag[v] = 1;
      if (w >= 0) flag[w] = 1;
      any = true;
    }
  }
  if (!any) return;
  std::set<std::array<int, 4>> found;
  std::vector<int> ca, cb, circle;
  for (int c = 0; c < t.n_owned; ++c)
    for (int f = t.cell_offset[c]; f < t.cell_offset[c + 1]; ++f) {
      const int o = t.face_offset[f], m = t.face_offset[f + 1] - o;
      for (int k = 0; k < m; ++k) {
        const int a = t.face_vertex[o + k], b = t.face_vertex[o + (k + 1) % m];
        if (a == b || !(flag[a] || flag[b])) continue;
        const V3 ha = vv(t.vertices[a]), hb = vv(t.vertices[b]);
        const double ra = t.radius[a], rb = t.radius[b];
        const double ta = tolerance(ha, ra), tb = tolerance(hb, rb);
        const V3 dh = ha - hb;
        if (!(std::sqrt(dot(dh, dh)) > std::max(ta, tb))) continue;
        ca.clear();
        cb.clear();
        if (!cluster_points(g, pts, g.id(a), ha, ra, ta, ca)) continue;
        if (!cluster_points(g, pts, g.id(b), hb, rb, tb, cb)) continue;
        ca.insert(ca.end(), cb.begin(), cb.end());
        std::sort(ca.begin(), ca.end());
        ca.erase(std::unique(ca.begin(), ca.end()), ca.end());
        circle.clear();
        for (const int p : ca)
          if (on_sphere(pts, p, ha, ra, ta) && on_sphere(pts, p, hb, rb, tb)) circle.push_back(p);
        // Three: an ordinary triangle; five or more: a co-circular polygon
        // this rule leaves alone.
        if (circle.size() != 4) continue;
        std::array<int, 4> key{circle[0], circle[1], circle[2], circle[3]};
        if (found.count(key)) continue;
        // The ends: two distinct well-shaped circumcentres equidistant from
        // the four points, from a, b and the neighbours of either (a
        // sliver's neighbours on the far side).
        V3 p4[4];
        for (int s = 0; s < 4; ++s) p4[s] = load(pts, circle[s]);
        auto axis = [&](V3 h) {
          const V3 d0 = p4[0] - h;
          const double r0 = std::sqrt(dot(d0, d0)), tol = tolerance(h, r0);
          for (int s = 1; s < 4; ++s) {
            const V3 d = p4[s] - h;
            if (!(std::fabs(std::sqrt(dot(d, d)) - r0) <= tol)) return -1.0;
          }
          return tol;
        };
        std::vector<V3> ends;
        std::vector<double> end_tol;
        auto consider = [&](V3 h) {
          const double tol = axis(h);
          if (tol < 0.0) return;
          for (size_t e = 0; e < ends.size(); ++e) {
            const V3 d = ends[e] - h;
            if (std::sqrt(dot(d, d)) <= std::max(tol, end_tol[e])) return;
          }
          ends.push_back(h);
          end_tol.push_back(tol);
        };
        for (const int v : {a, b}) {
          V3 h;
          const long id = g.id(v);
          if (centre_of(g, pts, id, &h)) consider(vv(t.vertices[v]));
          for (int s = 0; s < 4; ++s) {
            const long nb = g.neighbor(id, s);
            if (nb >= 0 && centre_of(g, pts, nb, &h)) consider(h);
          }
        }
        if (ends.size() != 2) continue;
        found.insert(key);
        // Cyclic order round the circle's centre (the mean of the four).
        const V3 mid = 0.25 * (p4[0] + p4[1] + p4[2] + p4[3]);
        const V3 nrm = cross(p4[1] - p4[0], p4[2] - p4[0]);
        const V3 ex = p4[0] - mid, ey = cross(nrm, ex);
        std::array<std::pair<double, int>, 4> ang;
        for (int s = 0; s < 4; ++s) {
          const V3 d = p4[s] - mid;
          ang[s] = {std::atan2(dot(d, ey), dot(d, ex)), circle[s]};
        }
        std::sort(ang.begin(), ang.end());
        FourFoldEdge3 e;
        for (int s = 0; s < 4; ++s) e.p[s] = ang[s].second;
        e.end[0] = {ends[0].x, ends[0].y, ends[0].z};
        e.end[1] = {ends[1].x, ends[1].y, ends[1].z};
        t.fourfold.push_back(e);
      }
    }
}

FourFoldIndex::FourFoldIndex(const Tessellation3 &t, const Points3 &pts) : t_(t), pts_(pts) {
  const int ne = static_cast<int>(t.fourfold.size());
  tol_.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const FourFoldEdge3 &s = t.fourfold[e];
    const V3 h = vv(s.end[0]), d = load(pts, s.p[0]) - h;
    tol_[e] = tolerance(h, std::sqrt(dot(d, d)));
    for (int i = 0; i < 4; ++i) {
      const int c = s.p[i];
      if (c >= t.n_owned) continue;
      for (int j = 1; j < 4; ++j) {
        const Role r{e, i, j == 2};
        roles_[static_cast<long long>(c) * t.n_points + s.p[(i + j) % 4]].push_back(r);
      }
      corners_[c].push_back(Role{e, i, false});
    }
  }
}

const FourFoldIndex::Role *FourFoldIndex::roles(int c, int nb, int *n) const {
  const auto it = roles_.find(static_cast<long long>(c) * t_.n_points + nb);
  if (it == roles_.end()) {
    *n = 0;
    return nullptr;
  }
  *n = static_cast<int>(it->second.size());
  return it->second.data();
}

const FourFoldIndex::Role *FourFoldIndex::corners_of(int c, int *n) const {
  const auto it = corners_.find(c);
  if (it == corners_.end()) {
    *n = 0;
    return nullptr;
  }
  *n = static_cast<int>(it->second.size());
  return it->second.data();
}

bool FourFoldIndex::on_axis(int e, V3 h) const {
  const FourFoldEdge3 &s = t_.fourfold[e];
  const V3 d0 = load(pts_, s.p[0]) - h;
  const double r0 = std::sqrt(dot(d0, d0));
  for (int i = 1; i < 4; ++i) {
    const V3 d = load(pts_, s.p[i]) - h;
    if (!(std::fabs(std::sqrt(dot(d, d)) - r0) <= tol_[e])) return false;
  }
  return true;
}

bool FourFoldIndex::is_square_tet(int e, int v) const {
  const auto &q = t_.tets[v];
  const auto &p = t_.fourfold[e].p;
  for (int k = 0; k < 4; ++k)
    if (std::find(p.begin(), p.end(), q[k]) == p.end()) return false;
  return true;
}

}  // namespace detail3
}  // namespace tessera
