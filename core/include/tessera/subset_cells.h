// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The cells of some of the caller's points, seen in the caller's numbering.
// A model tessellates only the points that are cells (say, the atoms of the
// cell types among other atoms): a compact list whose point p is the
// caller's point local[p], its first n_owned_cells points the owned cells.
// This view wraps the model's view of that list so that every consumer keeps
// reading "owned cell c" as the caller's owned point c: a caller's point
// that is no cell has an empty cell (no pieces, measure and boundary 0, no
// neighbours, its centroid its own position) and is never a neighbour.
#pragma once

#include "tessera/cells.h"

#include <vector>

namespace tessera {

class SubsetCells : public CellView {
public:
  // inner: the model's view of the compact list; local[p]: the caller's
  // index of compact point p (p < inner.n_points()); n_owned, n_points: the
  // caller's counts; pts: the caller's positions (for points that are no
  // cells).  The caller's owned points must include every owned cell:
  // local[c] < n_owned for c < inner.n_owned().
  void bind(const CellView &inner, const std::vector<int> &local, int n_owned, int n_points,
            const Points3 &pts);
  // The compact index of the caller's point i, or -1 when it is no cell.
  int cell_of(int i) const { return compact_[i]; }
  const CellView &inner() const { return *in_; }

  int dimension() const override { return in_ ? in_->dimension() : 2; }
  int space_dimension() const override { return in_ ? in_->space_dimension() : 2; }
  int n_owned() const override { return in_ ? n_owned_ : 0; }
  int n_points() const override { return in_ ? n_points_ : 0; }
  double measure(int c) const override { return compact_[c] < 0 ? 0.0 : in_->measure(compact_[c]); }
  double boundary(int c) const override {
    return compact_[c] < 0 ? 0.0 : in_->boundary(compact_[c]);
  }
  double free_length(int c) const override {
    return compact_[c] < 0 ? 0.0 : in_->free_length(compact_[c]);
  }
  int piece_begin(int c) const override { return compact_[c] < 0 ? 0 : in_->piece_begin(compact_[c]); }
  int piece_end(int c) const override { return compact_[c] < 0 ? 0 : in_->piece_end(compact_[c]); }
  int piece_neighbor(int k) const override {
    const int q = in_->piece_neighbor(k);
    return q < 0 ? q : local_[q];
  }
  double piece_size(int k) const override { return in_->piece_size(k); }
  int piece_corners(int k, std::vector<double> &xyz) const override {
    return in_->piece_corners(k, xyz);
  }
  bool piece_arc(int k, double &phi, double &theta) const override {
    return in_->piece_arc(k, phi, theta);
  }
  double arc_radius() const override { return in_->arc_radius(); }
  void point(int i, double *x) const override;
  Contacts contacts() const override;
  int multifold_count() const override { return in_ ? in_->multifold_count() : 0; }
  void multifold_ring(int g, std::vector<int> &ring) const override;
  bool short_edge_clusters(double min_length, std::vector<int> &offset,
                           std::vector<int> &members) const override;
  void centroid(int c, double *x) const override;
  void second_moments(int c, double *m) const override;
  bool principal_axis(int c, bool longest, double *x) const override;

private:
  const CellView *in_ = nullptr;
  std::vector<int> local_, compact_;
  int n_owned_ = 0, n_points_ = 0;
  Points3 pts_;
  // The inner contacts in the caller's numbering (compressed rows).
  std::vector<int> offset_, neighbor_;
  std::vector<double> size_;
};

}  // namespace tessera
