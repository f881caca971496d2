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

Contacts PolygonCells::contacts() const {
  Contacts c;
  c.n_owned = n_owned_;
  c.offset = offset_.data();
  c.neighbor = neighbor_.data();
  c.size = length_.data();
  return c;
}

} // namespace tessera
