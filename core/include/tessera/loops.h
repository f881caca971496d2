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

}  // namespace tessera
