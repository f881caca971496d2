// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Closed loops of free boundary of a tissue of finite cells: the outer edge
// of each colony, each hole or wound.  The union of finite cells is the union
// of their discs, so its boundary is made of free arcs only; walked with the
// tissue on the left, each arc runs counter-clockwise around its own cell
// and ends at the corner where the next arc, of the neighbour across the
// junction that follows the arc in the cell's boundary, begins.  Chaining
// the arcs end to start gives closed loops; a loop's signed enclosed area
// (arcs included) is positive for an outer boundary (counter-clockwise) and
// negative for a hole (clockwise).  In a periodic box the chain is unwrapped
// by minimum image; a loop that closes only after a whole box vector (the
// edges of a strip spanning the box) encloses no finite area.
#pragma once

#include "tessera/cells.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace tessera {

// One free arc: centred on its cell's point (cx, cy), radius r, from angle
// phi counter-clockwise over theta > 0 radians.  cell: an ID of the cell;
// next: the ID of the neighbour across the junction that follows the arc in
// the cell's counter-clockwise boundary (the cell's own ID when the arc is
// the cell's whole boundary).
struct FreeArc {
  std::int64_t cell = 0;
  std::int64_t next = 0;
  double cx = 0.0, cy = 0.0, r = 0.0, phi = 0.0, theta = 0.0;
};

// Appends the free arcs of the owned cells of a view to arcs, each cell
// named by id[point] (e.g. atom IDs; nullptr: the point index); owned cells
// with skip[c] != 0 are left out (skip may be nullptr).
void append_free_arcs(const CellView &v, const std::int64_t *id, const char *skip,
                      std::vector<FreeArc> &arcs);

enum class LoopKind { Hole = 0, Outer = 1, Wrapping = -1 };

struct FreeLoop {
  LoopKind kind = LoopKind::Outer;
  double area = 0.0;        // enclosed area (0 for a wrapping loop)
  double length = 0.0;      // sum of the arcs' lengths
  int n_cells = 0;          // distinct cells with an arc on the loop
  int n_arcs = 0;
  double cx = 0.0, cy = 0.0;  // centroid of the enclosed region (wrapping: mean of the arc midpoints)
  // Its arcs in walking order (indices into the arcs given to free_loops),
  // and for each the shift (2 values: whole box vectors, 0 in an open box)
  // that puts it on the loop unwrapped from its first arc.
  std::vector<int> arcs;
  std::vector<double> shift;
};

// Maps a difference vector (2 values) to its minimum image in place; an
// empty function for an open box.
using MinimumImage = std::function<void(double *)>;

// The loops of the given arcs, in the order of their first arc.  A corner
// matches when the next arc starts within tol of where an arc ends (after
// minimum image); unmatched counts the chain links that did not (0 for a
// consistent tessellation), and each such chain is closed where it stopped.
std::vector<FreeLoop> free_loops(const std::vector<FreeArc> &arcs, const MinimumImage &image,
                                 double tol, int *unmatched = nullptr);

// A loop's arcs in walking order with their centres shifted onto the loop
// (arcs: those given to free_loops).
std::vector<FreeArc> unwrapped_arcs(const std::vector<FreeArc> &arcs, const FreeLoop &loop);

// The winding number about p of the closed chain of n arcs given unwrapped
// (each arc's centre already shifted onto the chain) in walking order, the
// last ending where the first begins: +1 inside an outer loop, -1 inside a
// hole, 0 outside (p on the chain itself: either).  The chain is its
// polygon of arc ends plus, for each arc, the region between the arc and
// its chord, which the arc runs around counter-clockwise.
int loop_winding(const FreeArc *arcs, int n, const double *p);

// A 2d box for the periodic images of a point: the lower corner lo, edge
// lengths len and the xy tilt (the second edge vector is (xy, len[1])).
struct LoopBox {
  double lo[2] = {0.0, 0.0};
  double len[2] = {1.0, 1.0};
  double xy = 0.0;
  bool periodic[2] = {false, false};
};

// Which loop encloses a point.  Loops are added in their numbering order
// (1, 2, ...) as unwrapped chains of arcs (see loop_winding) with their
// enclosed area; a wrapping loop encloses no point.  innermost(p) is the
// loop of smallest area (the lowest number on a tie) whose region holds p
// or one of its periodic images, 0 if none does.  A bin grid over the box
// finds a point's candidate loops, and each loop bins its arcs in bands of
// y, so that a query reads the few arcs near the point.
class LoopLocator {
public:
  explicit LoopLocator(const LoopBox &box) : box_(box) {}
  void add(const FreeArc *arcs, int n, double area, bool wrapping);
  void finish();  // after the last add, before the first query
  int innermost(const double *p) const;
  int size() const { return static_cast<int>(loops_.size()); }
  // The winding number of loop l (1-based) about p itself (no image).
  int winding(int l, const double *p) const;

private:
  struct Loop {
    std::vector<FreeArc> arcs;
    double area = 0.0;
    bool wrapping = false;
    double lo[2] = {0.0, 0.0}, hi[2] = {0.0, 0.0};  // bounding box
    int nband = 1;
    std::vector<int> band_start, band_arcs;  // arcs touching each band of y
  };
  LoopBox box_;
  std::vector<Loop> loops_;
  int nbin_[2] = {1, 1};
  std::vector<int> bin_start_, bin_loops_;
  void fraction(const double *p, double *s) const;
  void bin_range(double s0, double s1, int d, std::vector<int> &out) const;
};

}  // namespace tessera
