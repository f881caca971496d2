// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Mesh::build: a from-scratch CGAL triangulation exported into flat arrays,
// with the input checks (doc/model.md, "Limits of the input").

#include "mesh_detail.h"

namespace tessera {

void Mesh::throw_too_close(const Points &pts, int i, int j, double scale, const long *ids,
                           const int *report) {
  auto rep = [&](int k) { return report ? report[k] : k; };
  auto name = [&](int k) {
    std::ostringstream s;
    s.precision(17);
    s << point_name(rep(k), ids) << " at (" << pts.x(rep(k)) << ", " << pts.y(rep(k)) << ")";
    if (rep(k) != k) s << " (its periodic image at (" << pts.x(k) << ", " << pts.y(k) << "))";
    return s.str();
  };
  const double d = std::hypot(pts.x(i) - pts.x(j), pts.y(i) - pts.y(j));
  std::ostringstream s;
  s << "tessera: two cell centres nearly coincide: " << name(std::min(i, j)) << " and "
    << name(std::max(i, j)) << " are " << d << " apart, ";
  if (kMinSeparation * scale >= kMinLength)
    s << "closer than " << kMinSeparation << " times the largest coordinate magnitude "
      << scale << " (limit " << kMinSeparation * scale
      << "): double precision cannot resolve the cell boundary between them; move or delete "
         "one of them";
  else
    s << "closer than " << kMinLength
      << ": lengths this small underflow in double precision; rescale the length unit";
  throw Error(s.str());
}

void Mesh::build(const Points &pts, const long *ids, const int *report) {
  valid_ = false;
  collinear_ = false;
  const int n = pts.n;
  auto rep = [&](int i) { return report ? report[i] : i; };
  double scale = 0.0;  // largest coordinate magnitude, for the separation limit
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(pts.x(i)) || !std::isfinite(pts.y(i))) {
      std::ostringstream s;
      s << "tessera: " << point_name(rep(i), ids) << " has a non-finite coordinate (" << pts.x(i)
        << ", " << pts.y(i) << ")";
      throw Error(s.str());
    }
    const double m = std::max(std::fabs(pts.x(i)), std::fabs(pts.y(i)));
    if (m > kMaxCoordinate) {
      std::ostringstream s;
      s.precision(17);
      s << "tessera: " << point_name(rep(i), ids) << " at (" << pts.x(i) << ", " << pts.y(i)
        << ") is beyond " << kMaxCoordinate
        << " in magnitude: the geometry's squares and cubes would overflow double precision; "
           "rescale the length unit (and the box) so that coordinates stay below "
        << kMaxCoordinate;
      throw Error(s.str());
    }
    scale = std::max(scale, m);
  }
  if (n < 3) {
    std::ostringstream s;
    s << "tessera: need at least 3 non-collinear points to tessellate, got " << n;
    throw Error(s.str());
  }
  // The old arrays go first and CGAL's triangulation lives only until it is
  // exported: the peak memory of a rebuild is what limits memory per cell.
  std::vector<int>().swap(v_);
  std::vector<int>().swap(nb_);
  std::vector<int>().swap(vt_);
  std::vector<char>().swap(frozen_);
  std::vector<int>().swap(spare_cv_);
  std::vector<int>().swap(spare_cn_);
  stamp_ = 0;
  int nf = 0;
  {
    Delaunay dt;
    {
      std::vector<std::pair<CPoint, int>> input;
      input.reserve(n);
      for (int i = 0; i < n; ++i)
        input.emplace_back(CPoint(pts.x(i), pts.y(i)), i);
      dt.insert(input.begin(), input.end());
    }

    if (static_cast<int>(dt.number_of_vertices()) != n) {
      std::vector<char> seen(n, 0);
      for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
        seen[v->info()] = 1;
      for (int i = 0; i < n; ++i) {
        if (seen[i])
          continue;
        const int j = dt.nearest_vertex(CPoint(pts.x(i), pts.y(i)))->info();
        std::ostringstream s;
        s << "tessera: two cell centres at the same position (" << pts.x(i) << ", " << pts.y(i)
          << "): " << point_name(rep(j), ids) << " and " << point_name(rep(i), ids)
          << "; move or delete one of them";
        throw Error(s.str());
      }
    }
    if (dt.dimension() < 2) {
      collinear_ = true;
      std::ostringstream s;
      s << "tessera: need at least 3 non-collinear points to tessellate; all " << n
        << " points are on one line";
      throw Error(s.str());
    }
    // Nearly coincident centres (the closest pair of points is always a
    // Delaunay edge, so checking the edges finds it).  One pass over the
    // edges, cheap next to the triangulation itself.
    const double sep2 = min_separation2(scale);
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
      const int i = e->first->vertex(Delaunay::cw(e->second))->info();
      const int j = e->first->vertex(Delaunay::ccw(e->second))->info();
      const double dx = pts.x(i) - pts.x(j), dy = pts.y(i) - pts.y(j);
      if (dx * dx + dy * dy < sep2) throw_too_close(pts, i, j, scale, ids, report);
    }

    // Export, with the infinite vertex as -1 (faces in CGAL's order; they
    // are renumbered below).
    for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f)
      f->info() = nf++;
    v_.assign(3 * static_cast<size_t>(nf), kInfinite);
    nb_.assign(3 * static_cast<size_t>(nf), -1);
    vt_.assign(n, -1);
    const auto inf = dt.infinite_vertex();
    for (auto f = dt.all_faces_begin(); f != dt.all_faces_end(); ++f) {
      const int id = f->info();
      for (int k = 0; k < 3; ++k) {
        const auto vk = f->vertex(k);
        v_[3 * id + k] = vk == inf ? kInfinite : vk->info();
        nb_[3 * id + k] = f->neighbor(k)->info();
        if (vk != inf)
          vt_[vk->info()] = id;
      }
    }
  } // CGAL's triangulation is freed here

  // Renumber the triangles in the order the points' stars visit them, so
  // that reading cells point by point walks memory nearly sequentially (the
  // points themselves are spatially sorted by LAMMPS); the finite triangles
  // first, then those with the point at infinity (see nft_).
  std::vector<int> order(nf, -1);
  auto finite = [&](int m) {
    return v_[3 * m] != kInfinite && v_[3 * m + 1] != kInfinite && v_[3 * m + 2] != kInfinite;
  };
  int next = 0;
  for (int p = 0; p < n; ++p) {
    const int start = vt_[p];
    int m = start;
    do {
      if (order[m] < 0 && finite(m))
        order[m] = next++;
      const int *v = &v_[3 * m];
      const int i = (v[1] == p) + 2 * (v[2] == p);
      m = nb_[3 * m + (i == 2 ? 0 : i + 1)];
    } while (m != start);
  }
  for (int m = 0; m < nf; ++m)
    if (order[m] < 0 && finite(m))
      order[m] = next++;
  nft_ = next;
  for (int m = 0; m < nf; ++m)
    if (order[m] < 0)
      order[m] = next++;
  {
    std::vector<int> tmp(v_.size());
    for (int m = 0; m < nf; ++m)
      for (int k = 0; k < 3; ++k)
        tmp[3 * order[m] + k] = v_[3 * m + k];
    v_.swap(tmp);
    for (int m = 0; m < nf; ++m)
      for (int k = 0; k < 3; ++k)
        tmp[3 * order[m] + k] = order[nb_[3 * m + k]];
    nb_.swap(tmp);
  }
  for (int &t : vt_)
    t = order[t];

  n_points_ = n;
  flips_ = 0;
  dirty_.assign(n, 0);
  dirty_list_.clear();
  flipped_.clear();
  valid_ = true;
}


}  // namespace tessera
