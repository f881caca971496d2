// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Voronoi tessellation of 2D cell centres, as the dual of their Delaunay
// triangulation.  This header is free of LAMMPS and of the geometry's
// internals on purpose: they live only in the core's .cpp files, so
// LAMMPS-side code (whose pointers.h defines MIN/MAX macros) can include it
// and builds stay fast.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace tessera {

// Every error the core raises on bad input.  The message names what is wrong
// and, where points are involved, which points (by their index in the input,
// or by the ids the caller supplied).
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct Vec2 {
  double x = 0.0, y = 0.0;
};

// A view of n points stored with a fixed stride (LAMMPS keeps x[i][0..2]
// contiguous, so stride 3 lets us read it without a copy).
struct Points {
  const double *data = nullptr;
  int n = 0;
  int stride = 2;
  double x(int i) const { return data[static_cast<long>(i) * stride]; }
  double y(int i) const { return data[static_cast<long>(i) * stride + 1]; }
};

// A parallelogram: the points o + s a + t b with s, t in [0, 1], where
// a = (ax, 0) runs along x and b = (bx, by) with by > 0: the shape of a
// LAMMPS (sub-)domain, orthogonal when bx = 0.
struct Region {
  double o[2] = {0.0, 0.0};
  double ax = 1.0;
  double bx = 0.0, by = 1.0;

  static Region rect(const double lo[2], const double hi[2]) {
    Region r;
    r.o[0] = lo[0];
    r.o[1] = lo[1];
    r.ax = hi[0] - lo[0];
    r.bx = 0.0;
    r.by = hi[1] - lo[1];
    return r;
  }
  // The smallest rectangle [lo, hi] containing the region grown by margin
  // (perpendicular to each side).
  void bounding_box(double margin, double lo[2], double hi[2]) const;
};

// Periodic simulation box: edge vectors (lx, 0) and (xy, ly) from lo, as in
// LAMMPS (xy = 0: orthogonal; otherwise triclinic).
struct Box {
  double lo[2] = {0.0, 0.0};
  double hi[2] = {1.0, 1.0};
  double xy = 0.0;  // tilt factor

  static Box rect(double xlo, double xhi, double ylo, double yhi) {
    Box b;
    b.lo[0] = xlo;
    b.hi[0] = xhi;
    b.lo[1] = ylo;
    b.hi[1] = yhi;
    return b;
  }
  double length(int d) const { return hi[d] - lo[d]; }
  double area() const { return length(0) * length(1); }
  Region region() const {
    Region r = Region::rect(lo, hi);
    r.bx = xy;
    return r;
  }
  // Throws Error if a length is not positive or not finite, or xy is not finite.
  void validate() const;
};

// The tessellation of n_points points, of which the first n_owned are the
// cells we want; the rest are ghosts (periodic images or other ranks' atoms)
// that only complete the owned cells.
//
// Voronoi vertex v of owned cell c is the circumcentre of Delaunay triangle
// cell_vertex[k] (k = cell_offset[c] + v), listed counter-clockwise.  The edge
// from vertex v to vertex v+1 (cyclically) separates c from point
// cell_neighbor[k] and has length edge_length[k].  Co-circular points give
// several triangles with one circumcentre: those edges have length 0 and are
// kept, so the polygon's topology always matches the triangulation.  The
// triangles of such a multifold vertex (a group, below) all hold the group's
// centre in `vertices` (the mean of their circumcentres, which differ by
// round-off), not each its own circumcentre.
struct Tessellation {
  int n_points = 0;
  int n_owned = 0;

  std::vector<std::array<int, 3>> triangles;  // counter-clockwise point indices
  std::vector<Vec2> vertices;                 // circumcentre of each triangle
  std::vector<double> radius;                 // circumradius of each triangle

  std::vector<int> cell_offset;  // n_owned + 1 entries
  std::vector<int> cell_vertex;
  std::vector<int> cell_neighbor;
  std::vector<double> edge_length;

  std::vector<double> area;       // per owned cell
  std::vector<double> perimeter;  // per owned cell

  // Multifold vertices: several triangles with one circumcentre (co-circular
  // points).  triangle_group[tri] is the vertex's index or -1; the vertex's
  // ring of k >= 4 points, counter-clockwise around it, is
  // group_point[group_offset[g] .. group_offset[g+1]); group_centre[g] is its
  // position.  Triangles at such a vertex that touch no owned cell are added
  // to `triangles` too, so that the ring is always complete.
  std::vector<int> triangle_group;
  std::vector<int> group_offset;
  std::vector<int> group_point;
  std::vector<Vec2> group_centre;


  // Clusters of Voronoi vertices joined by edges shorter than min_length (the
  // "rosettes" of a fluid tissue, nearly multifold vertices): for each
  // cluster of two or more triangles that touches an owned cell, the points
  // around it.  Cluster c's points are members[offset[c] .. offset[c+1]).
  void short_edge_clusters(double min_length, std::vector<int> &offset,
                           std::vector<int> &members) const;

  // An owned cell that touches the convex hull of the points (its region is
  // unbounded, so the ghost shell is missing), or -1.  Only set when
  // tessellate_local was asked not to throw; such cells are left empty and
  // check_coverage reports an infinite needed margin.
  int unbounded_cell = -1;

  // For tessellate_periodic: the owned point each of the n_points is an image
  // of, and the position it was triangulated at (owned points first, then
  // images).  Empty for tessellate_local.
  std::vector<int> origin;
  std::vector<Vec2> position;

  // Set by Mesh::cells()/advance(): which call filled this tessellation (lets
  // Mesh::advance() reuse the cell lists of the previous step).
  unsigned long mesh_stamp = 0;

  int cell_size(int c) const { return cell_offset[c + 1] - cell_offset[c]; }
  // Number of Voronoi neighbours counted over edges longer than tol times the
  // cell's mean edge length (zero-length edges of multifold vertices excluded).
  int coordination_number(int c, double rel_tol = 1e-9) const;
  // Multifold vertices (shared by four or more cells) around the owned cells.
  // multifold_vertex_share() adds 1/k for each owned cell at a k-fold vertex,
  // so that sums over MPI ranks (or over periodic images) count each vertex
  // exactly once; count_multifold_vertices() rounds it for a single owner.
  double multifold_vertex_share() const;
  int count_multifold_vertices() const;
};

// Told by Mesh::advance() about the cells as it reads them, so that work per
// cell can run while the cell's data are in cache (CellPass in energy.h).
struct CellObserver {
  virtual ~CellObserver() = default;
  // t's triangles and Voronoi vertices are final; no cell is read yet.
  virtual void begin(const Tessellation &t) = 0;
  // Cells [c0, c1) are read (polygon, edge lengths, area, perimeter); calls
  // come in order and cover 0..n_owned-1.
  virtual void cells(const Tessellation &t, int c0, int c1) = 0;
  // t is complete (multifold vertices found, t.mesh_stamp set).
  virtual void end(const Tessellation &t) = 0;
};

// Triangulate points (owned first, then ghosts) without periodicity and build
// the owned cells.  ids (optional, n entries) are used in error messages.
// Throws Error on non-finite coordinates, coincident points, or fewer than 3
// non-collinear points; and if an owned cell touches the convex hull (its
// region is unbounded: the ghost shell is missing or far too thin).
Tessellation tessellate_local(const Points &pts, int n_owned, const long *ids = nullptr,
                              bool throw_if_unbounded = true);

// Whether the owned cells of t can be trusted when the given points are all
// the points inside the rectangle [lo, hi] (the region they cover): every
// Delaunay triangle used by an owned cell must have its circumdisk inside it,
// otherwise an unseen point could lie in that disk.  needed_margin is how far
// the rectangle would have to grow on its worst side for the check to pass
// (0 when ok; +infinity if an owned cell is unbounded); the caller adds it to
// its ghost cutoff.
struct Coverage {
  bool ok = true;
  double needed_margin = 0.0;
  int worst_cell = -1;  // an owned cell using the worst triangle, or -1
};
Coverage check_coverage(const Tessellation &t, const double lo[2], const double hi[2]);
// The same for a parallelogram region grown by margin on every side
// (perpendicular distance), e.g. a triclinic sub-domain and its ghost shell.
Coverage check_coverage(const Tessellation &t, const Region &region, double margin = 0.0);

// Tessellate n points in a periodic box.  Builds periodic images within a
// margin of the box, and grows the margin until check_coverage passes, so the
// result is exact for any configuration.  All points must lie in the box
// (wrap them first; wrap_into_box helps).  Any n >= 1 works, also points on
// one line (their images complete the tiling).  Throws Error as
// Mesh::build does for coincident or nearly coincident points and
// coordinates out of range (doc/model.md, "Limits of the input").
Tessellation tessellate_periodic(const Box &box, const Points &pts, const long *ids = nullptr);

// Wrap coordinates (stride 2) into the box (fractional coordinates in [0, 1)).
void wrap_into_box(const Box &box, std::vector<double> &xy);

}  // namespace tessera
