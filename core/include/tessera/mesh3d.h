// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// A 3D Delaunay tetrahedralisation kept between time steps in flat arrays.
//
// The 3D counterpart of tessera::Mesh.  build() triangulates from scratch with
// the core's own builder (mesh3d_delaunay); afterwards the points move by a small fraction of a cell per step and
// update() checks every tetrahedron's orientation and every interior
// triangle's in-sphere test (a floating-point filter, the exact predicates
// of exact_predicates.h where it cannot decide) and restores the Delaunay property by 2-3, 3-2 and
// 4-4 flips.  Ties (co-spherical points: BCC, FCC, SC lattices) are broken by
// the same symbolic perturbation as CGAL's Delaunay_triangulation_3 (points
// ranked in lexicographic xyz order), so the triangulation is the one a
// rebuild would give and cells() reproduces tessellate_local_3d's cells
// exactly, zero-area faces included (with a region of interest: the cells
// whose circumspheres lie inside it, see below).
//
// The convex hull is closed by eight fixed points far outside the initial
// bounding box (32 times its largest extent from its centre), so hull changes
// are ordinary flips.  A tetrahedron with one of them belongs to no owned
// cell whose tetrahedra have circumspheres inside the ghost shell (which
// callers check anyway, check_coverage_3d); an owned cell touching one is
// reported unbounded, as tessellate_local_3d reports cells on the hull.
//
// Tetrahedra that invert or go flat during a step (slivers: four nearly
// co-spherical, nearly coplanar points) are first repaired by a flip with a
// neighbour that leaves only positive tetrahedra; if the Delaunay flips then
// get stuck (several events of the continuous motion merged into one step),
// update() starts again from the mesh as it was and moves the points there in
// 2, 4, 8 substeps (straight lines from the last positions), repairing after
// each.
//
// Region of interest.  Without one, every tetrahedron is kept valid and
// Delaunay, the flat hull of a ghost shell included (its slivers invert and
// get stuck often: update() fails more).  With a box [roi_lo, roi_hi] (the
// owned points' domain grown by at least the largest circumradius of their
// tetrahedra), only tetrahedra and triangles not separated from the box grown
// by about one point spacing are checked and flipped, and failures are
// tolerated if they are separated from the box itself.  The mesh is then
// exact for every tetrahedron whose circumsphere lies inside the box (a
// Delaunay tetrahedron is certified by the locally Delaunay triangles its
// circumsphere meets); callers check their cells' circumspheres against the
// box, as check_coverage_3d(t, roi_lo, roi_hi) does.  Tetrahedra outside are
// left as the points carry them (they may invert; that is never looked at).
//
// Per step, as a pair style would use it (ghosts re-listed: build() again):
//
//   if (!mesh.valid() || !mesh.advance(pts, n_owned, lo, hi, t)) {
//     mesh.build(pts, ids);
//     mesh.cells(pts, n_owned, t, ids);
//   }
//   then check_coverage_3d(t, lo, hi) as after tessellate_local_3d.
//
// update() returns false (the caller calls build() again) when an inverted
// tetrahedron or a non-Delaunay triangle that matters has no repairing flip,
// the flips do not end (more flips than tetrahedra), or the input is bad
// (point count changed, non-finite coordinates).
#pragma once

#include "tessera/voronoi3d.h"

#include <array>
#include <cstddef>
#include <vector>

namespace tessera {

class Mesh3 {
public:
  // Triangulates the points (owned first, then ghosts) from scratch.  ids
  // (optional) name points in error messages; report (optional) maps a point
  // to the index reported in them (periodic images report their owner).
  // Throws Error on non-finite coordinates, coincident points, or fewer than
  // 4 non-coplanar points.
  void build(const Points3 &pts, const long *ids = nullptr, const int *report = nullptr);

  // The same points (same number, same order) at new positions: restores the
  // Delaunay property by flips.  Returns false when the mesh cannot follow
  // (see the top of the file); the mesh is then invalid and build() must be
  // called, which names bad points.  roi_lo, roi_hi (both or neither): the
  // region of interest (see the top of the file).
  bool update(const Points3 &pts, const double *roi_lo = nullptr, const double *roi_hi = nullptr);

  // Fills t with the cells of points 0..n_owned-1, as tessellate_local_3d
  // does (same faces, polygons, areas, volumes, surfaces up to round-off; the
  // order of the faces of a cell, of a polygon's starting vertex, and of the
  // tetrahedra may differ).  Reuses t's storage.  An owned cell on the hull:
  // throws Error if throw_if_unbounded, else sets t.unbounded_cell (and the
  // cell has no faces), as tessellate_local_3d.  Throws Error if an owned
  // point lay outside the last update()'s region of interest (grown by the
  // buffer): its tetrahedra were not kept.  When t is the tessellation the
  // previous call filled (t.mesh_stamp), unchanged since, the faces and
  // rings of the cells whose stars no flip touched are kept in it, moved in
  // place (only their geometry is computed again); any other t has every
  // cell walked.  Do not edit the topology of t between calls.  Throws
  // Error for two owned-cell neighbours nearly coincident (as
  // tessellate_local_3d; doc/model.md, "Limits of the input").
  void cells(const Points3 &pts, int n_owned, Tessellation3 &t, const long *ids = nullptr,
             bool throw_if_unbounded = true) const;

  // update() and then cells(): the per-step path.  Returns false when
  // update() does, or when cells() throws (nearly coincident centres, an
  // owned cell outside the region of interest or on the hull: the mesh is
  // then invalid, and build() and cells() with ids name the points); t is
  // then not filled.
  bool advance(const Points3 &pts, int n_owned, const double *roi_lo, const double *roi_hi,
               Tessellation3 &t);
  // Whether the last advance() filled t from the repaired mesh (false after
  // a failed one, and before any).
  bool incremental() const { return incremental_; }

  bool valid() const { return valid_; }
  int n_points() const { return n_points_; }
  long flips_last_update() const { return flips_; }
  // Flips of each kind in the last update(): 2-3, 3-2, 4-4.
  long flips23() const { return f23_; }
  long flips32() const { return f32_; }
  long flips44() const { return f44_; }
  // In-sphere and orientation tests the filter could not decide in the last
  // update() (decided by the exact predicates).
  long exact_tests() const { return exact_; }
  // Inverted or flat tetrahedra repaired by a flip in the last update().
  long untangled() const { return untangled_; }
  // Substeps the last update() took (1: in one go).
  long substeps() const { return substeps_; }
  // Why the last update() returned false (nullptr after a success).
  const char *failure() const { return failure_; }
  // Live tetrahedra (those with a far point included).
  int n_tets() const { return static_cast<int>(tv_.size() / 4) - static_cast<int>(free_.size()); }
  // Bytes held by the mesh's arrays (capacity).
  std::size_t memory_bytes() const;

private:
  bool valid_ = false;
  int n_points_ = 0;
  long flips_ = 0, f23_ = 0, f32_ = 0, f44_ = 0, untangled_ = 0;
  mutable long exact_ = 0;
  const char *failure_ = nullptr;
  bool incremental_ = false;
  double far_[8][3] = {};
  std::vector<int> tv_;    // 4 per tetrahedron: points, positively oriented; -1: free slot
  std::vector<int> tn_;    // 4 per tetrahedron: neighbour across the face opposite vertex k, -1: none
  std::vector<int> free_;  // free tetrahedron slots
  std::vector<int> vt_;    // per point (far points last): one tetrahedron containing it
  std::vector<int> stack_, pending_;
  std::vector<double> prev_;  // positions of the last successful build() or update()
  std::vector<double> mid_;   // positions of a substep
  // The writes of this update()'s flips, to go back to the mesh as it was:
  // {what, index, old value}.
  enum { kUndoTv, kUndoTn, kUndoVt, kUndoFreePop, kUndoFreePush, kUndoGrow };
  std::vector<std::array<int, 3>> undo_;
  double roi_box_[6] = {};  // the region of interest of the running update()
  const double *roi_lo_ = nullptr, *roi_hi_ = nullptr;  // into roi_box_, or none
  long substeps_ = 0;
  double buffer_ = 0.0;
  std::vector<char> skip_;
  std::vector<unsigned short> code_;  // per point: outcodes against the region of interest  // per tetrahedron: free, or outside the region of interest
  mutable std::vector<unsigned> tmark_;  // per tetrahedron: stamp of the last cell that visited it
  mutable std::vector<unsigned> pmark_;  // per point: stamp of the last cell that met it
  mutable std::vector<int> tmap_;        // mesh tetrahedron -> Tessellation3 index, -1
  mutable std::vector<int> tused_, bfs_;
  // Per point: its star changed (a flip) since the last cells().
  mutable std::vector<char> dirty_;
  mutable std::vector<int> dirty_list_;
  // The last cells() left its topology in the Tessellation3 it filled
  // (stamped cache_stamp_), the rings in that tessellation's numbering of
  // the tetrahedra, mapped to mesh tetrahedra by tused_.  The next cells()
  // on it keeps the faces of the cells no flip touched (keep_topology), with
  // these scratch arrays: per owned cell its old ring start and new face and
  // ring starts; the walked cells, their first faces, and their faces (k_nb_,
  // k_fo_, k_fv_ as in a Tessellation3).
  mutable unsigned long cache_stamp_ = 0;
  mutable std::vector<int> k_ring0_, k_fstart_, k_rstart_, k_cells_, k_first_, k_nb_, k_fo_, k_fv_;
  mutable bool cache_ok_ = false;
  mutable int cache_owned_ = -1;
  mutable unsigned stamp_ = 0;

  const double *pos(const Points3 &pts, int i) const {
    return i < n_points_ ? pts.p(i) : far_[i - n_points_];
  }
  int orient(const Points3 &pts, int a, int b, int c, int d) const;
  int insphere(const Points3 &pts, const int *t, int e) const;
  bool less_xyz(const Points3 &pts, int a, int b) const;
  int new_tet();
  void release();
  int triangulate(const Points3 &pts, const long *ids, const int *report);
  void rollback();
  int slot_of(int tet, int v) const;
  int slot_of_nb(int tet, int nb) const;
  bool flip23(const Points3 &pts, int t, int k);
  bool flip32(const Points3 &pts, int t, int k, int edge);
  bool flip44(const Points3 &pts, int t, int k, int edge, bool delaunay);
  bool flip_face(const Points3 &pts, int t, int k);
  bool untangle(const Points3 &pts, int t);
  void outcodes(const Points3 &pts);
  bool outside(const int *v, int m, bool grown) const;
  int scan(const Points3 &pts);
  bool repair(const Points3 &pts);
  Points3 interpolate(const Points3 &pts, double s);
  bool replace(const Points3 &pts, const int *old_tets, int n_old, int (*nv)[4], int n_new);
  void next_stamp() const;
  bool walk_cell(int i, const long *ids, std::vector<int> &nbs, std::vector<int> &offs,
                 std::vector<int> &ring) const;
  void keep_topology(int n_owned, const long *ids, bool throw_if_unbounded, Tessellation3 &t) const;
  void unbounded(int i, const long *ids, bool throw_if_unbounded, Tessellation3 &t) const;
};

// The plain Delaunay tetrahedralisation of points 0..n-1 by Mesh3::build's
// own builder alone (what bench/ times beside CGAL's Delaunay_triangulation_3
// on the same points).  Returns the wall time of the build alone in seconds and, in *cells when given, the number of finite
// tetrahedra.
double time_plain_delaunay_3d(const Points3 &pts, int n, long *cells = nullptr);

}  // namespace tessera
