// Tessera tests.  SPDX-License-Identifier: GPL-2.0-or-later
//
// A slow, independent reference for the periodic Voronoi tessellation and the
// vertex-model energy.  Each cell is built directly from its definition: start
// from a large square around the point and clip it with the perpendicular-
// bisector half-plane of every periodic image (shifts -S..S in x and y) of
// every other point.  O(N^2 S^2) per tessellation; meant for N <= a few hundred.
// It shares no code with the core (no Delaunay triangulation, no CGAL).
#pragma once

#include <array>
#include <vector>

namespace reftess {

struct RefBox {
  double xlo = 0.0, ylo = 0.0;
  double lx = 1.0, ly = 1.0;
};

// One side of a reference cell: the segment from vertex k to vertex k+1 of the
// polygon lies on the bisector between the cell's point and point `nbr`
// shifted by (sx * lx, sy * ly).
struct RefEdge {
  int nbr = -1;
  int sx = 0, sy = 0;
  double length = 0.0;
};

struct RefCell {
  std::vector<std::array<double, 2>> poly;  // counter-clockwise, absolute coordinates
  std::vector<RefEdge> edges;               // edges[k] goes from poly[k] to poly[k+1]
  double area = 0.0;
  double perimeter = 0.0;
};

// Cell of point i (xy: stride 2; points may lie slightly outside the box, only
// their periodic images matter).  Zero-length and tiny edges are kept (they
// arise at co-circular points and from round-off); callers filter by length.
// Throws std::logic_error on coincident points or if the shifts do not suffice.
RefCell voronoi_cell(const RefBox &box, const std::vector<double> &xy, int i, int shifts = 2);
std::vector<RefCell> voronoi(const RefBox &box, const std::vector<double> &xy, int shifts = 2);

// Energy parameters, independent of tessera::Model.
struct RefParams {
  std::vector<double> K, A0, Gamma;  // per type
  std::vector<double> Lambda;        // ntypes * ntypes (symmetric)
  bool cell_tension = false;         // false: each junction once; true: Lambda * l per cell side
  int ntypes() const { return static_cast<int>(K.size()); }
};

// Energy of one cell: K/2 (A - A0)^2 + Gamma/2 P^2 + w * sum_sides Lambda l,
// w = 1/2 (edge convention: the two cells of a junction add up to one Lambda l)
// or 1 (cell convention).
double cell_energy(const RefCell &c, int i, const std::vector<int> &type, const RefParams &p);
double total_energy(const std::vector<RefCell> &cells, const std::vector<int> &type,
                    const RefParams &p);

// Energy of a subset of cells recomputed from scratch for the given positions.
double partial_energy(const RefBox &box, const std::vector<double> &xy,
                      const std::vector<int> &type, const RefParams &p,
                      const std::vector<int> &cells);

// Cells whose polygon can depend on the position of point i: i, its
// neighbours (any edge length) and their neighbours.
std::vector<int> affected_cells(const std::vector<RefCell> &cells, int i);

}  // namespace reftess
