// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// A Delaunay triangulation kept between time steps in flat arrays.
//
// Cells move a small fraction of their size per step, so the triangulation of
// step n is almost always the triangulation of step n+1, or a few edge flips
// away from it.  update() checks every edge with exact (filtered) in-circle
// tests and restores the Delaunay property by Lawson flips, in O(N) with a
// small constant.  The point at infinity closes the convex hull, so hull
// changes are flips too.  A triangle that folds over (a point crossed an
// edge) is repaired locally: the folded region and its ring are
// re-triangulated (exact predicates), and the flips then restore the
// Delaunay property there; only when that fails (the region touches the hull
// or a frozen triangle, or grows past a bound) does the caller need build()
// again, which triangulates from scratch (mesh_build.cpp: points in a
// multiscale Hilbert order, each located by a walk from the last and
// inserted by Lawson flips).  Co-circular points are ordinary input: their
// tie is broken by a symbolic perturbation (doc/model.md, "Exact geometry"),
// so the triangulation is unique, and build() and update() give the same
// triangles, each with its smallest point index first.
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
  // Delaunay property by flips, after re-triangulating the regions where a
  // triangle folded over (see set_fold_repair).  Returns false when the mesh
  // cannot follow (a fold that the local repair could not mend, or the point
  // count changed) or the input is bad
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
  // Regions re-triangulated by the last update()/advance() because a
  // triangle folded over, and the triangles they held.
  long repairs_last_update() const { return repairs_; }
  long repaired_triangles_last_update() const { return repaired_triangles_; }
  // Local fold repair on (the default) or off (a fold then makes update()
  // and advance() return false, as a from-scratch rebuild is needed): for
  // tests and benchmarks that compare the two.
  void set_fold_repair(bool on) { fold_repair_ = on; }
  bool fold_repair() const { return fold_repair_; }
  // Whether the last cells() or advance() call took advance()'s per-step path.
  bool incremental() const { return last_incremental_; }

private:
  static constexpr int kInfinite = -1;
  bool valid_ = false;
  bool collinear_ = false;
  // Some coordinate is nonzero and below kTinyCoordinate (mesh_detail.h):
  // the in-circle tests skip their floating-point filter.
  bool tiny_ = false;
  int n_points_ = 0;
  long flips_ = 0;
  long repairs_ = 0;
  long repaired_triangles_ = 0;
  bool fold_repair_ = true;
  std::vector<int> folded_;  // triangles found folded (inside the region) by the scan
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
  // Rotates triangle t's corners (and neighbours) so that its smallest
  // point index comes first (-1, the point at infinity, in an infinite one):
  // a triangle's corners are then in the same order however it was made,
  // and so are the bits of its circumcentre.
  void canonical(int t);
  int corner(int t, int p) const { return (v_[3 * t + 1] == p) + 2 * (v_[3 * t + 2] == p); }
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
  // Local repair of the triangles in folded_ (mesh_repair.cpp): false when a
  // region cannot be mended (the mesh is then invalid).
  bool repair_folds(const Points &pts, double sep2);
  bool repair_one(const Points &pts, double sep2, int f);
  template <class Compact, class MeshOf>
  void find_groups(const Points &pts, Tessellation &t, Compact compact, MeshOf mesh_of) const;
  bool flip_needed(const Points &pts, int p, int q, int r, int s) const;
};

// The pair style's 'reference' yardstick: the plain Delaunay triangulation of
// points 0..n-1 by build()'s triangulator alone (the spatial sort, the
// insertion and nothing else: no input checks, no separation test, no
// renumbering for the cells).  Returns its wall time in seconds and, in
// *faces when given, the number of finite triangles (2 n - 2 - hull
// vertices for n points in general position).  The benchmarks compare it
// with CGAL's Delaunay_triangulation_2 (bench/bench_core.cpp).
double time_plain_delaunay(const Points &pts, int n, long *faces = nullptr);

}  // namespace tessera
