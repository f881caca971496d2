// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
#include "tessera/subset_cells.h"


namespace tessera {

void SubsetCells::bind(const CellView &inner, const std::vector<int> &local, int n_owned,
                       int n_points, const Points3 &pts) {
  in_ = &inner;
  local_ = local;
  n_owned_ = n_owned;
  n_points_ = n_points;
  pts_ = pts;
  compact_.assign(n_points, -1);
  for (size_t p = 0; p < local.size(); p++) compact_[local[p]] = static_cast<int>(p);
  const Contacts c = inner.contacts();
  offset_.assign(n_owned + 1, 0);
  for (int i = 0; i < n_owned; i++) {
    const int q = compact_[i];
    offset_[i + 1] = offset_[i] + (q < 0 ? 0 : c.offset[q + 1] - c.offset[q]);
  }
  neighbor_.resize(offset_[n_owned]);
  size_.resize(offset_[n_owned]);
  for (int i = 0; i < n_owned; i++) {
    const int q = compact_[i];
    if (q < 0) continue;
    for (int k = c.offset[q], o = offset_[i]; k < c.offset[q + 1]; k++, o++) {
      neighbor_[o] = local_[c.neighbor[k]];
      size_[o] = c.size[k];
    }
  }
}

void SubsetCells::point(int i, double *x) const {
  if (compact_[i] >= 0) {
    in_->point(compact_[i], x);
    return;
  }
  const double *p = pts_.p(i);
  for (int d = 0; d < space_dimension(); d++) x[d] = p[d];
}

Contacts SubsetCells::contacts() const {
  Contacts c;
  c.n_owned = n_owned();
  c.offset = offset_.data();
  c.neighbor = neighbor_.data();
  c.size = size_.data();
  return c;
}

void SubsetCells::multifold_ring(int g, std::vector<int> &ring) const {
  in_->multifold_ring(g, ring);
  for (int &q : ring) q = local_[q];
}

bool SubsetCells::short_edge_clusters(double min_length, std::vector<int> &offset,
                                      std::vector<int> &members) const {
  if (!in_->short_edge_clusters(min_length, offset, members)) return false;
  for (int &q : members) q = local_[q];
  return true;
}

void SubsetCells::centroid(int c, double *x) const {
  if (compact_[c] >= 0)
    in_->centroid(compact_[c], x);
  else
    point(c, x);
}

void SubsetCells::second_moments(int c, double *m) const {
  const int d = space_dimension();
  if (compact_[c] >= 0) {
    in_->second_moments(compact_[c], m);
    return;
  }
  for (int k = 0; k < d * d; k++) m[k] = 0.0;
}

bool SubsetCells::principal_axis(int c, bool longest, double *x) const {
  return compact_[c] >= 0 && in_->principal_axis(compact_[c], longest, x);
}

}  // namespace tessera
