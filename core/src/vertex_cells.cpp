// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The vertex model's cells in the model-independent view (tessera::CellView).

#include "tessera/vertex_model.h"

#include <cmath>

namespace tessera {

void PolygonCells::clear(int n_owned, int n_points, const Points &pts) {
  n_owned_ = n_owned;
  n_points_ = n_points;
  pts_ = pts;
  filled_ = 0;
  lazy_ = false;
  offset_.assign(n_owned + 1, 0);
  area_.assign(n_owned, 0.0);
  perimeter_.assign(n_owned, 0.0);
  neighbor_.clear();
  corners_.clear();
  length_.clear();
}

void PolygonCells::add_cell(int c, const double *xy, int n, const int *neighbor, double area,
                            double perimeter) {
  // Empty slots up to c.
  for (; filled_ <= c; ++filled_)
    offset_[filled_] = static_cast<int>(neighbor_.size());
  for (int k = 0; k < n; ++k) {
    const int k1 = k + 1 == n ? 0 : k + 1;
    neighbor_.push_back(neighbor[k]);
    corners_.insert(corners_.end(), {xy[2 * k], xy[2 * k + 1], xy[2 * k1], xy[2 * k1 + 1]});
    // (sqrt, not hypot: see polygon_measures)
    const double dx = xy[2 * k1] - xy[2 * k], dy = xy[2 * k1 + 1] - xy[2 * k + 1];
    length_.push_back(std::sqrt(dx * dx + dy * dy));
  }
  area_[c] = area;
  perimeter_[c] = perimeter;
}

void PolygonCells::finish() {
  for (; filled_ <= n_owned_; ++filled_)
    offset_[filled_] = static_cast<int>(neighbor_.size());
}

void PolygonCells::set_rings(const int *offset, const int *corner, const int *neighbor,
                             const Points &corners) {
  const int np = offset[n_owned_];
  offset_.assign(offset, offset + n_owned_ + 1);
  neighbor_.assign(neighbor, neighbor + np);
  corner_.assign(corner, corner + np);
  at_.resize(2 * static_cast<size_t>(corners.n));
  for (int i = 0; i < corners.n; ++i) {
    at_[2 * i] = corners.x(i);
    at_[2 * i + 1] = corners.y(i);
  }
  filled_ = n_owned_ + 1;
  lazy_ = true;
}

// add_cell's corners and lengths, from the copied positions.
void PolygonCells::fill() const {
  const int np = offset_[n_owned_];
  corners_.resize(4 * static_cast<size_t>(np));
  length_.resize(np);
  for (int c = 0; c < n_owned_; ++c) {
    const int b = offset_[c], e = offset_[c + 1];
    for (int k = b; k < e; ++k) {
      const double *p = &at_[2 * static_cast<size_t>(corner_[k])];
      const double *q = &at_[2 * static_cast<size_t>(corner_[k + 1 == e ? b : k + 1])];
      double *o = &corners_[4 * static_cast<size_t>(k)];
      o[0] = p[0];
      o[1] = p[1];
      o[2] = q[0];
      o[3] = q[1];
      const double dx = q[0] - p[0], dy = q[1] - p[1];
      length_[k] = std::sqrt(dx * dx + dy * dy);
    }
  }
  lazy_ = false;
}

Contacts PolygonCells::contacts() const {
  if (lazy_)
    fill();
  Contacts c;
  c.n_owned = n_owned_;
  c.offset = offset_.data();
  c.neighbor = neighbor_.data();
  c.size = length_.data();
  return c;
}

} // namespace tessera
