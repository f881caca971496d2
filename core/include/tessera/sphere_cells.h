// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The cell view (tessera/cells.h) of cells on a sphere (tessera/sphere.h):
// two-dimensional cells (measure = spherical area, boundary = geodesic
// perimeter, pieces = geodesic edges) whose positions have three
// coordinates (space_dimension() == 3).  A piece's corners are its two
// Voronoi vertices on the sphere (the geodesic between them is the edge).
//
// Centroid: the centre of mass of the cell's surface, c + integral of
// (r - c) dA / A, lies inside the sphere; the view returns its radial
// projection onto the sphere, c + R w/|w| with w = sum over edges of
// theta_k m_k (theta_k the edge's angle, m_k the unit normal of its great
// circle's plane, from v_k x v_k+1: the identity
// integral of n dA = 1/2 sum theta_k m_k for a spherical polygon).
// Second moments and principal axes: those of the cell's gnomonic image
// (central projection onto the tangent plane at the cell's point, which maps
// the geodesic edges to straight ones: an exact polygon, with the plane's
// area element, which differs from the sphere's by a relative (d/R)^2 for a
// cell of size d), embedded in space through an orthonormal basis of that
// tangent plane; the axes are tangent to the sphere at the cell's point.
#pragma once

#include "tessera/cells.h"
#include "tessera/sphere.h"

#include <vector>

namespace tessera {

class SphereCells : public CellView {
public:
  // All points of t are owned cells, in t's order; neighbours are t's indices
  // and positions are t's projected points.
  void bind(const SphereTessellation &t);
  // Owned cell c (c < owned.size()) is point owned[c] of t; point_index[p]
  // is the caller's index (< n_points) of point p of t, or -1 when the
  // caller does not have it (such points are reported by missing()).
  // pts: the caller's n_points positions, reported by point() after radial
  // projection onto the sphere.
  void bind(const SphereTessellation &t, const std::vector<int> &owned,
            const std::vector<int> &point_index, int n_points, const Points3 &pts);
  // Points of t that owned cells' neighbour lists or multifold rings need
  // but point_index lacked (t's indices, no repeats).
  const std::vector<int> &missing() const { return missing_; }

  int dimension() const override { return 2; }
  int space_dimension() const override { return 3; }
  int n_owned() const override { return t_ ? static_cast<int>(owned_.size()) : 0; }
  int n_points() const override { return t_ ? n_points_ : 0; }
  double measure(int c) const override { return t_->area[owned_[c]]; }
  double boundary(int c) const override { return t_->perimeter[owned_[c]]; }
  int piece_begin(int c) const override { return offset_[c]; }
  int piece_end(int c) const override { return offset_[c + 1]; }
  int piece_neighbor(int k) const override { return neighbor_[k]; }
  double piece_size(int k) const override { return size_[k]; }
  int piece_corners(int k, std::vector<double> &xyz) const override;
  void point(int i, double *x) const override;
  Contacts contacts() const override;
  int multifold_count() const override;
  void multifold_ring(int g, std::vector<int> &ring) const override;
  // Clusters of Voronoi vertices joined by edges shorter than min_length
  // around the owned cells (two or more triangles each), as in the plane;
  // points the caller lacks are left out of a cluster.
  bool short_edge_clusters(double min_length, std::vector<int> &offset,
                           std::vector<int> &members) const override;

  void centroid(int c, double *x) const override;
  void second_moments(int c, double *m) const override;
  bool principal_axis(int c, bool longest, double *x) const override;

  const SphereTessellation &tessellation() const { return *t_; }
  // The point of t that owned cell c is.
  int tess_index(int c) const { return owned_[c]; }

private:
  const SphereTessellation *t_ = nullptr;
  std::vector<int> owned_;
  int n_points_ = 0;
  Points3 pts_;
  bool own_points_ = true;  // positions are t's (bind(t))
  // Owned cells' edges in compressed rows: neighbour (caller's index), length,
  // start and end Voronoi vertex (t's triangle indices).
  std::vector<int> offset_, neighbor_, v0_, v1_;
  std::vector<double> size_;
  // Multifold vertices around the owned cells: rings of caller's indices.
  std::vector<int> ring_offset_, ring_;
  std::vector<int> missing_;
  std::vector<int> index_;  // the caller's index of each point of t
  // Clusters of triangles joined by edges of length < below (or == 0 when
  // below is 0) that touch an owned cell and have at least min_triangles
  // triangles; each one's points (t's indices, ascending).
  void clusters(double below, int min_triangles, std::vector<std::vector<int>> &out) const;
  void build(const std::vector<int> &point_index);
  // Second moments of cell c's gnomonic image in its tangent basis (e1, e2).
  bool planar_moments(int c, double m2[3], double e1[3], double e2[3]) const;
};

}  // namespace tessera
