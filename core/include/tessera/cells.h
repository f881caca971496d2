// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// One read-only view of a step's owned cells, whatever the model: confluent
// 2D Voronoi polygons (Tessellation), finite 2D cells with free arcs
// (FiniteTessellation), 3D Voronoi polyhedra (Tessellation3).  Every
// consumer (computes, fixes, tools) reads cells through this view and nothing
// else, so a feature written once works for every model (doc/model.md, "One
// view of the cells").
//
// A cell's boundary is a list of pieces.  A piece is shared with one
// neighbouring point (2D: a junction, the edge between two Voronoi vertices;
// 3D: a face polygon) or free (finite cells: an arc of the cell's circle,
// neighbour -1).  Piece sizes are lengths in 2D and areas in 3D.  The views
// do not copy the tessellation: they read the model's arrays, so they are
// valid as long as the tessellation they were bound to is unchanged.
#pragma once

#include "tessera/finite.h"
#include "tessera/tessellation.h"
#include "tessera/voronoi3d.h"

#include <vector>

namespace tessera {

// Neighbour lists of the owned cells (compressed rows, no copy): cell c's
// neighbours are neighbor[offset[c] .. offset[c+1]), each across a shared
// piece of size size[k] (0 for the zero-length edges / zero-area faces of
// multifold vertices, which are not neighbours).  Free pieces are not listed.
struct Contacts {
  int n_owned = 0;
  const int *offset = nullptr;
  const int *neighbor = nullptr;
  const double *size = nullptr;
};

class CellView {
public:
  virtual ~CellView() = default;

  // 2 (area, perimeter, edges) or 3 (volume, surface, faces).
  virtual int dimension() const = 0;
  // Coordinates per position (points, corners, centroid, axes): dimension(),
  // except for cells on a curved surface in space (the sphere: 2-dimensional
  // cells, 3 coordinates; SphereCells in tessera/sphere_cells.h).
  virtual int space_dimension() const { return dimension(); }
  virtual int n_owned() const = 0;
  // Owned and ghost points the tessellation used; point indices in the view
  // (neighbours, multifold rings) are < n_points.
  virtual int n_points() const = 0;

  // Area (2D) or volume (3D) of owned cell c.
  virtual double measure(int c) const = 0;
  // Perimeter (2D) or surface (3D), free arcs included.
  virtual double boundary(int c) const = 0;
  // Length of the free (cell-medium) boundary: finite cells' arcs; 0 otherwise.
  virtual double free_length(int /*c*/) const { return 0.0; }
  bool at_edge(int c) const { return free_length(c) > 0.0; }

  // The pieces of cell c are k = piece_begin(c) .. piece_end(c) - 1, in
  // boundary order (2D: counter-clockwise).
  virtual int piece_begin(int c) const = 0;
  virtual int piece_end(int c) const = 0;
  // The point across piece k, or -1 for a free arc.
  virtual int piece_neighbor(int k) const = 0;
  // Length (2D edge or arc) or area (3D face) of piece k.
  virtual double piece_size(int k) const = 0;
  // Appends piece k's corners to xyz (space_dimension() coordinates each) and
  // returns how many: 2D, its start and end point (consecutive pieces of a
  // cell share a corner, so the ends close into the cell's boundary); 3D,
  // the face polygon, counter-clockwise seen from the neighbour.
  virtual int piece_corners(int k, std::vector<double> &xyz) const = 0;
  // A free arc (finite cells): centred on the cell's point, radius
  // arc_radius(), from angle phi over theta > 0 radians.  false otherwise.
  virtual bool piece_arc(int /*k*/, double & /*phi*/, double & /*theta*/) const { return false; }
  virtual double arc_radius() const { return 0.0; }
  // Position of point i as the tessellation used it (space_dimension() values).
  virtual void point(int i, double *x) const = 0;

  // The neighbour lists in compressed rows, for per-step loops.
  virtual Contacts contacts() const = 0;

  // Vertices shared by more cells than the dimension's generic count (2D:
  // four or more cells at one Voronoi vertex, co-circular points): their
  // number, and each one's ring of points (owned and ghost).  Models without
  // such vertices (finite cells, and 3D today) have none.
  virtual int multifold_count() const { return 0; }
  virtual void multifold_ring(int /*g*/, std::vector<int> &ring) const { ring.clear(); }
  // Clusters of Voronoi vertices joined by edges shorter than min_length
  // (nearly multifold vertices, the rosettes of a fluid tissue) and the
  // points around each: cluster g's points are members[offset[g] ..
  // offset[g+1]).  false when the model has no Voronoi vertices to cluster.
  virtual bool short_edge_clusters(double /*min_length*/, std::vector<int> & /*offset*/,
                                   std::vector<int> & /*members*/) const {
    return false;
  }

  // Per-cell energy of the last force computation (set by the caller that
  // computed it, e.g. the pair style), or nullptr.
  const double *energy = nullptr;

  // ---- Derived from the pieces, the same for every model ----

  // Voronoi neighbours: shared pieces (free arcs not counted) larger than
  // rel_tol times the distance d between the two centres (2D and the
  // sphere, by length) or d^2 (3D, by area): a property of the pair, so
  // that neighbours agree.
  int coordination_number(int c, double rel_tol = 1e-9) const;
  // 2D: P / sqrt(A); 3D: S / V^(2/3).  0 for an empty cell.
  double shape_index(int c) const;
  // Centroid of the cell (space_dimension() values).
  virtual void centroid(int c, double *x) const;
  // Second moments about the centroid, integral of (x - xc)_a (x - xc)_b
  // over the cell, row-major space_dimension() x space_dimension().
  virtual void second_moments(int c, double *m) const;
  // Unit vector along the cell's longest (longest = true) or shortest
  // principal axis of the second moments (space_dimension() values); false
  // (and x untouched) when the cell is isotropic to round-off or empty.
  virtual bool principal_axis(int c, bool longest, double *x) const;
};

// The views of the three models.  Each binds to a tessellation and the
// positions it was computed from (Points / Points3 of all n_points points).
class ConfluentCells : public CellView {
public:
  void bind(const Tessellation &t, const Points &pts) { t_ = &t; pts_ = pts; }
  int dimension() const override { return 2; }
  int n_owned() const override { return t_ ? t_->n_owned : 0; }
  int n_points() const override { return t_ ? t_->n_points : 0; }
  double measure(int c) const override { return t_->area[c]; }
  double boundary(int c) const override { return t_->perimeter[c]; }
  int piece_begin(int c) const override { return t_->cell_offset[c]; }
  int piece_end(int c) const override { return t_->cell_offset[c + 1]; }
  int piece_neighbor(int k) const override { return t_->cell_neighbor[k]; }
  double piece_size(int k) const override { return t_->edge_length[k]; }
  int piece_corners(int k, std::vector<double> &xyz) const override;
  void point(int i, double *x) const override { x[0] = pts_.x(i); x[1] = pts_.y(i); }
  Contacts contacts() const override;
  int multifold_count() const override;
  void multifold_ring(int g, std::vector<int> &ring) const override;
  bool short_edge_clusters(double min_length, std::vector<int> &offset,
                           std::vector<int> &members) const override;
  const Tessellation &tessellation() const { return *t_; }

private:
  const Tessellation *t_ = nullptr;
  Points pts_;
};

class FiniteCells : public CellView {
public:
  // contacts: finite_contacts(t, ...) of the same cells (the neighbour lists).
  void bind(const FiniteTessellation &t, const Tessellation &contacts, const Points &pts) {
    t_ = &t;
    c_ = &contacts;
    pts_ = pts;
  }
  int dimension() const override { return 2; }
  int n_owned() const override { return t_ ? t_->n_owned : 0; }
  int n_points() const override { return t_ ? t_->n_points : 0; }
  double measure(int c) const override { return t_->area[c]; }
  double boundary(int c) const override { return t_->perimeter[c]; }
  double free_length(int c) const override { return t_->free_length[c]; }
  int piece_begin(int c) const override { return t_->cell_offset[c]; }
  int piece_end(int c) const override { return t_->cell_offset[c + 1]; }
  int piece_neighbor(int k) const override { return t_->pieces[k].neighbor; }
  double piece_size(int k) const override { return t_->pieces[k].length; }
  int piece_corners(int k, std::vector<double> &xyz) const override;
  bool piece_arc(int k, double &phi, double &theta) const override;
  double arc_radius() const override { return t_->radius; }
  void point(int i, double *x) const override { x[0] = pts_.x(i); x[1] = pts_.y(i); }
  Contacts contacts() const override;

private:
  const FiniteTessellation *t_ = nullptr;
  const Tessellation *c_ = nullptr;
  Points pts_;
  int cell_of(int k) const;
};

class Cells3 : public CellView {
public:
  void bind(const Tessellation3 &t, const Points3 &pts) { t_ = &t; pts_ = pts; }
  int dimension() const override { return 3; }
  int n_owned() const override { return t_ ? t_->n_owned : 0; }
  int n_points() const override { return t_ ? t_->n_points : 0; }
  double measure(int c) const override { return t_->volume[c]; }
  double boundary(int c) const override { return t_->surface[c]; }
  int piece_begin(int c) const override { return t_->cell_offset[c]; }
  int piece_end(int c) const override { return t_->cell_offset[c + 1]; }
  int piece_neighbor(int k) const override { return t_->face_neighbor[k]; }
  double piece_size(int k) const override { return t_->face_area[k]; }
  int piece_corners(int k, std::vector<double> &xyz) const override;
  void point(int i, double *x) const override {
    const double *p = pts_.p(i);
    x[0] = p[0];
    x[1] = p[1];
    x[2] = p[2];
  }
  Contacts contacts() const override;

private:
  const Tessellation3 *t_ = nullptr;
  Points3 pts_;
};

}  // namespace tessera
