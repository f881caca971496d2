// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// A Delaunay triangulation kept between time steps in flat arrays.
//
// Cells move a small fraction of their size per step, so the triangulation of
// step n is almost always the triangulation of step n+1, or a few edge flips
// away from it.  update() checks every edge with exact (filtered) in-circle
// tests and restores the Delaunay property by Lawson flips, in O(N) with a
// small constant; only when a triangle folds over (a point crossed an edge)
// does the caller need build() again, which triangulates from scratch with
// CGAL.  The point at infinity closes the convex hull, so hull changes are
// flips too.  CGAL stays inside mesh.cpp.
#pragma once

#include "tessera/tessellation.h"

#include <vector>

namespace tessera {

class Mesh {
public:
  // Triangulates the points from scratch.  ids (optional) name points in
  // error messages; report (optional) maps a point to the index reported in
  // them, itself an index into pts (periodic images report their owner).
  // Throws Error on non-finite coordinates, coordinates beyond 1e100 in
  // magnitude, coincident points or points closer than 1e-10 times the
  // largest coordinate magnitude (or than 1e-100), or fewer than 3
  // non-collinear points (doc/model.md, "Limits of the input").
  void build(const Points &pts, const long *ids = nullptr, const int *report = nullptr);

  // The same points (same number, same order) at new positions: restores the
  // Delaunay property by flips.  Returns false when the mesh cannot follow
  // (a triangle folded over, or the point count changed) or the input is bad
  // (non-finite or out-of-range coordinates, two points joined by an edge
  // closer than the separation limit); the mesh is then invalid and build()
  // must be called, which names the bad points.
  //
  // With a region of interest [roi_lo, roi_hi], triangles that fold over
  // entirely outside it (thin triangles on the convex hull of a ghost shell)
  // are frozen instead: they and their edges are left alone, and the mesh is
  // exact for every triangle whose circumdisk lies inside the region (a
  // Delaunay triangle is certified by locally Delaunay edges along any path
  // inside its circumdisk).  Callers then check their cells' circumdisks
  // against the region, as check_coverage() does.
  bool update(const Points &pts, const double *roi_lo = nullptr, const double *roi_hi = nullptr);

  // Fills t with the Voronoi cells of points 0..n_owned-1 (and the
  // circumcentres of all finite triangles).  Reuses t's storage.
  void cells(const Points &pts, int n_owned, Tessellation &t) const;

  // update() and then cells() in one go, the per-step path of a run.  When t
  // was filled by this mesh's last cells() or advance() (since no other call
  // changed the mesh), for the same n_owned, the circumcentres are computed in
  // the pass that checks for folds, the in-circle tests of that pass use them
  // (with a floating-point filter that falls back to the exact predicate), and
  // only the cells whose triangles a flip touched are walked again: the others
  // keep their lists.  The result is the same as update() followed by cells(),
  // bit for bit.  Otherwise it runs update() and cells()
  // (incremental() then says false).  Returns false when update() would (t is
  // then not filled; call build() and cells()).
  // observer (optional) is told about the cells as they are read, on the
  // per-step path only.
  bool advance(const Points &pts, int n_owned, const double *roi_lo, const double *roi_hi,
               Tessellation &t, CellObserver *observer = nullptr);

  bool valid() const { return valid_; }
  // Whether the last build() failed because all points lie on one line.
  bool collinear() const { return collinear_; }
  int n_points() const { return n_points_; }
  long flips_last_update() const { return flips_; }
  // Whether the last cells() or advance() call took advance()'s per-step path.
  bool incremental() const { return last_incremental_; }

private:
  static constexpr int kInfinite = -1;
  bool valid_ = false;
  bool collinear_ = false;
  int n_points_ = 0;
  long flips_ = 0;
  // Triangles [0, nft_) are finite, [nft_, n) have the point at infinity as
  // a corner; build() numbers them so and update()/advance() keep it (flips
  // only turn infinite triangles finite; they are then moved to nft_), so
  // that finite triangle k of a Tessellation is mesh triangle k.
  int nft_ = 0;
  // Stamp of the Tessellation the last cells()/advance() filled (0: none, or
  // the mesh changed since).
  mutable unsigned long stamp_ = 0;
  mutable bool last_incremental_ = false;
  std::vector<int> flipped_;      // triangles whose corners changed in this update
  std::vector<char> dirty_;       // per point: its star changed in this update
  std::vector<int> dirty_list_;   // the points with dirty_ set
  std::vector<int> spare_cv_, spare_cn_;  // the other buffer of advance()'s cell lists
  std::vector<int> v_;   // 3 per triangle: point indices, counter-clockwise; -1 = infinity
  std::vector<int> nb_;  // 3 per triangle: neighbour across the edge opposite vertex k
  std::vector<int> vt_;  // per point: one triangle containing it
  mutable std::vector<int> stack_;
  std::vector<char> frozen_;
  mutable std::vector<int> seeds_;  // finite triangle index -> mesh triangle

  [[noreturn]] static void throw_too_close(const Points &pts, int i, int j, double scale,
                                           const long *ids, const int *report);
  void flip(int t, int k, int u, int j);
  void mark_dirty(int p) {
    if (p >= 0 && !dirty_[p]) {
      dirty_[p] = 1;
      dirty_list_.push_back(p);
    }
  }
  void swap_slots(int a, int b);
  void restore_partition();
  bool start_update(const Points &pts, double &sep2);
  void cell_geometry(const Points &pts, const std::array<int, 3> *TRI, double cx, double cy,
                     const int *cv, int len, const Vec2 *H, const double *RAD, double *el,
                     double &area, double &perimeter) const;
  bool stack_edges(const Points &pts, int t, double sep2);
  bool flip_pass(const Points &pts, double sep2);
  template <class Compact, class MeshOf>
  void find_groups(const Points &pts, Tessellation &t, Compact compact, MeshOf mesh_of) const;
  bool flip_needed(const Points &pts, int p, int q, int r, int s) const;
};

// The benchmarks' yardstick: a plain CGAL Delaunay_triangulation_2 (default
// kernel and data structure, no info, no periodic images) of points 0..n-1,
// inserted by CGAL's range insert, which sorts them spatially first.  Returns
// the wall time of the insert alone in seconds (the copy into CGAL's point
// type comes before the clock starts) and, in *faces when given, the number of
// finite triangles (2 n - 2 - hull vertices for n points in general position).
double time_plain_delaunay(const Points &pts, int n, long *faces = nullptr);

}  // namespace tessera
