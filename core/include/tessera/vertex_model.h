// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// The vertex model (doc/model.md, "The vertex model"): cells are polygons whose
// corners (vertices) are the degrees of freedom.  Three layers:
//
//  - one polygon: area, perimeter, centroid, the cell's energy under a
//    tessera::Model (the Voronoi model's parameters, shared) and its exact
//    gradient with respect to the polygon's corners, and whether it is a
//    valid cell (vertex_polygon.cpp);
//  - a tissue, or a patch of one: vertices and cells as counter-clockwise
//    rings of vertex indices in a periodic box, its energy and forces, the
//    check that it is a consistent, valid tissue, and the start from the
//    Voronoi polygons of cell centres (vertex_tissue.cpp);
//  - topology: T1 and T2 candidates, the deterministic rule that chooses
//    which are carried out (the same on every rank that sees an event), their
//    application, and division (vertex_topology.cpp).
//
// No LAMMPS type, no CGAL: the LAMMPS side calls the polygon layer for its
// forces and the topology layer on the patch of cells a rank sees.
#pragma once

#include "tessera/cells.h"
#include "tessera/energy.h"
#include "tessera/tessellation.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace tessera {

// ---- One polygon: n corners (stride 2), counter-clockwise, unwrapped ----

struct PolygonMeasures {
  double area = 0.0; // signed: positive when counter-clockwise
  double perimeter = 0.0;
  Vec2 centroid; // of the area (the mean of the corners if the area is 0)
};
PolygonMeasures polygon_measures(const double *xy, int n);

// Energy of cell c (0-based type tc) whose polygon is xy, under model
// (Model::cell_params(c, tc): per-cell values are read at index c), with the
// cell's share w = model.tension_weight() of each junction's tension:
//   K/2 (A - A0)^2 + Gamma/2 P^2 + shift P + w sum_k Lambda(tc, nbr_type[k]) l_k
// where edge k runs from corner k to corner k+1 and nbr_type[k] is the type of
// the cell across it (nullptr: tc on every edge).  The quadratic form's
// constant (Model::quadratic_constant) is not included.  grad (optional, 2n
// values, overwritten) receives dE/dx_k, dE/dy_k; a zero-length edge has no
// direction and contributes no tension gradient (the mean of the two one-sided
// derivatives of its length).
// measures (optional) receives polygon_measures(xy, n), made in the same pass
// (its perimeter from the edges as the energy sums them: the same but for
// round-off).
double polygon_energy(const double *xy, int n, const Model &model, int c, int tc,
                      const int *nbr_type, double *grad, PolygonMeasures *measures = nullptr);

// What makes a polygon an invalid cell (None: valid).  A valid cell has at
// least three corners, no corner ID twice, finite corners, positive area and
// no two non-adjacent edges that cross or overlap (corners that coincide, the
// ends of a zero-length edge, are allowed).
enum class PolygonDefect {
  None,
  TooFewSides,
  RepeatedVertex,
  NotFinite,
  NotPositive,
  SelfIntersecting
};
const char *describe(PolygonDefect d);
// ids: the corners' vertex IDs (optional) for the repeated-vertex test.
// A polygon convex beyond rounding is answered without the pairwise test of
// its edges; polygon_defect_pairwise always makes that test (the slow
// oracle: the two agree but where rounding decides a corner of a convex
// polygon, which the fast answer calls valid).
PolygonDefect polygon_defect(const double *xy, int n, const long *ids = nullptr);
PolygonDefect polygon_defect_pairwise(const double *xy, int n, const long *ids = nullptr);

// ---- A tissue, or a patch of one ----

// Vertices and cells.  Cell c is the polygon rings[c] (vertex indices,
// counter-clockwise); an empty ring is no cell (removed by a T2, or a slot a
// patch does not fill).  Geometry is read through delta(), the minimum image
// of the box when periodic, so positions may be any periodic image.
struct VertexTissue {
  Box box;
  bool periodic = true;
  std::vector<Vec2> pos;
  std::vector<std::vector<int>> rings;
  std::vector<int> type; // per cell, 0-based
  // IDs for messages and the topology rule's tie-breaks (empty: index + 1).
  std::vector<long> vertex_id, cell_id;
  // Patches: whether a vertex's position is known (empty: all known).
  std::vector<char> vertex_known;
  // Vertices a T2 removed (empty: none).
  std::vector<char> vertex_removed;

  int n_vertices() const { return static_cast<int>(pos.size()); }
  int n_cells() const { return static_cast<int>(rings.size()); }
  long vid(int v) const { return vertex_id.empty() ? v + 1L : vertex_id[v]; }
  long cid(int c) const { return cell_id.empty() ? c + 1L : cell_id[c]; }
  bool known(int v) const { return vertex_known.empty() || vertex_known[v]; }
  bool removed(int v) const { return !vertex_removed.empty() && vertex_removed[v]; }
  // A cell with a ring all of whose vertices are known.
  bool complete(int c) const;
  // pos[to] - pos[from], by the minimum image convention when periodic (the
  // box's b vector first, then a: deterministic for any tilt).
  Vec2 delta(int from, int to) const {
    return image(pos[to].x - pos[from].x, pos[to].y - pos[from].y);
  }
  Vec2 image(double dx, double dy) const;
  // image() by the divisions and floors alone (the oracle of its shortcut).
  Vec2 image_reference(double dx, double dy) const;
  // Cell c's corners unwrapped from the position of its first vertex (2 per corner).
  void polygon(int c, std::vector<double> &xy) const;
  PolygonMeasures measures(int c) const;
};

// The cell holding the directed edge (a, b), for every directed edge of the
// tissue's cells: twin(c, k) is the cell across edge k of cell c.  Stored as
// the edges leaving each vertex (about three), in arrays reused by build().
class EdgeMap {
public:
  EdgeMap() = default;
  explicit EdgeMap(const VertexTissue &t) { build(t); }
  void build(const VertexTissue &t);
  // -1 if no cell holds (a, b).
  int cell(int a, int b) const {
    if (a < 0 || a + 1 >= static_cast<int>(first_.size()))
      return -1;
    for (int e = first_[a]; e < first_[a + 1]; ++e)
      if (to_[e] == b)
        return cell_[e];
    return -1;
  }
  // A directed edge held by two cells (a broken map) found by build(), or {-1, -1}.
  int dup_a = -1, dup_b = -1;

private:
  // Edges leaving vertex a: to_[e], cell_[e] for e in [first_[a], first_[a + 1]).
  std::vector<int> first_, to_, cell_, fill_;
};

// The cell across edge k (from ring[k] to ring[k+1]) of cell c, or -1.
int twin_cell(const VertexTissue &t, const EdgeMap &m, int c, int k);

// Energy of the tissue (sum of its cells') and the forces -dE/dr on its
// vertices (f: 2 per vertex, overwritten).  The junction tensions read the
// type across each edge.  cell_energy (optional) per cell; virial (optional)
// W_ab = sum over cells and their corners of x_a F_b with each cell's corners
// unwrapped (xx, yy, xy, yx), so that dE/d(strain_ab) = -W_ab.
double tissue_energy(const VertexTissue &t, const Model &model,
                     std::vector<double> *cell_energy = nullptr);
double tissue_forces(const VertexTissue &t, const Model &model, std::vector<double> &f,
                     double *virial = nullptr);

// Throws Error naming IDs unless the tissue is consistent and valid: every
// ring has at least three vertices that exist and are not removed; every
// directed edge is held by one cell and its twin by another; every vertex
// that is not removed is in exactly three cells; every cell is a valid
// polygon (polygon_defect); with a periodic box, the cells' areas add up to
// the box's (to 1e-9 relative: the rings wind once round the torus).
void check_tissue(const VertexTissue &t);

// The vertex tissue of the Voronoi polygons of n cell centres in a periodic
// box (tessellate_periodic): cell i is centre i (type[i], cell_id ids[i] if
// given), one vertex per Voronoi vertex of the periodic tiling, at positions
// wrapped into the box, numbered in an order that depends only on the
// centres' order and the tiling (the vertex's three centres and their image
// shifts, sorted), not on how the tessellation lists them.  Co-circular
// centres give one vertex per Delaunay triangle, i.e. several vertices at
// one point joined by zero-length edges.
VertexTissue vertex_tissue_from_voronoi(const Box &box, const Points &pts, const int *type,
                                        const long *ids = nullptr);

// ---- Topology ----

struct TopologyParams {
  double t1_length = 0.0; // T1 below this edge length (0: no T1)
  double t1_new = 0.0;    // the new edge's length (> t1_length)
  double t2_area = 0.0;   // T2 of triangles below this area (0: no T2)
};

struct TopologyEvent {
  enum Kind { T2 = 0, T1 = 1 };
  Kind kind = T1;
  double size = 0.0;     // T1: the edge's length; T2: the triangle's area
  long id0 = 0, id1 = 0; // T1: the smaller and the larger vertex ID; T2: the cell's ID, 0
  // T1: a -> b counter-clockwise in cells[0] (a the smaller ID); T2: -1.
  int a = -1, b = -1;
  // T1: X (holds a -> b), Y (b -> a), W (third cell at a), Z (third at b);
  // T2: the triangle, then the cells across its edges 0, 1, 2.  -1: not in
  // the patch.
  int cells[4] = {-1, -1, -1, -1};
  // Every cell of the event and every neighbour of those is complete, so
  // the rule can be evaluated (always, on a whole tissue).
  bool decidable = false;
  // The rule's order: T2 before T1, then size, then the IDs.
  bool before(const TopologyEvent &o) const {
    if (kind != o.kind)
      return kind < o.kind;
    if (size != o.size)
      return size < o.size;
    if (id0 != o.id0)
      return id0 < o.id0;
    return id1 < o.id1;
  }
};

// The candidates of a tissue or patch, each once: edges shorter than
// t1_length between two known cells of four or more sides, enumerated from
// complete cells; with t2_area > 0, also the shortest edge of a complete cell
// of four or more sides and area below t2_area among those whose other cell
// has four or more sides (however long: so that a shrinking cell becomes a
// triangle); complete triangles of area below t2_area.
// The T1 candidates are sought in the cells that a cheap test of their
// edges and corners leaves (the same events in the same order as a look at
// every cell: every_cell = true, the oracle).
std::vector<TopologyEvent> find_events(const VertexTissue &t, const EdgeMap &m,
                                       const TopologyParams &p, bool every_cell = false);

// Status of each candidate under the rule: Carry if it is decidable and
// before every other candidate that shares a cell with it (its cells: for a
// T1 the cells at its two vertices; for a T2 the triangle and its
// neighbours); Wait if another one comes first; Undecidable if the patch
// does not hold what the rule reads.
enum class EventStatus { Carry, Wait, Undecidable };
std::vector<EventStatus> decide_events(const VertexTissue &t, const EdgeMap &m,
                                       const std::vector<TopologyEvent> &events);

// Carries out one event (T1: a and b moved to m +- l_new/2 n about their
// midpoint m (a stays in X, b in Y) and the rings of X, Y, W, Z edited;
// of the directions n tried in turn (from Y's centroid to X's, perpendicular
// to the old edge, perpendicular to the line from W's centroid to Z's, then 24
// evenly spaced ones) the one that leaves the four cells valid with the
// widest sharpest corner at a and b;
// T2: the triangle's ring emptied, its vertex of smallest ID moved to its
// centroid and joined to the three neighbours, the other two marked
// removed).  Returns false and changes nothing if the result would not be
// valid (a T1 next to a three-sided cell, W = Z or W and Z already
// neighbours, a T2 next to a three-sided cell, or any changed cell not a
// valid polygon).  The EdgeMap is not updated (build it again).
bool apply_event(VertexTissue &t, const TopologyEvent &e, const TopologyParams &p);

// One topology step of a whole tissue: find, decide, apply; returns the
// number of events carried out (refused ones counted in *refused).
int topology_step(VertexTissue &t, const TopologyParams &p, int *refused = nullptr);

// Division of cell c by the line through its centroid perpendicular to the
// unit vector axis: the daughter on the side +axis is a new cell (same type,
// ID new_cell_id or the largest ID + 1), the mother keeps the side -axis; two
// new vertices (IDs new_vertex_id, new_vertex_id + 1, or the largest + 1 and
// + 2) on the two edges the line crosses, at least a tenth of an edge from its
// ends.  Returns the new cell's index, or -1 (nothing changed) if the line
// does not cross the boundary exactly twice or a result would not be valid.
int divide_cell(VertexTissue &t, int c, Vec2 axis, long new_cell_id = 0, long new_vertex_id = 0);

// ---- The cells in the view every consumer reads (tessera/cells.h) ----

// The vertex model's cells as a CellView: n_owned slots, owned cell c in
// slot c; a slot without a cell (a vertex atom, in LAMMPS) is an empty cell.
// A cell's pieces are its edges, each with the point (cell) across it and its
// two corners.  Filled by the model at each force computation: clear(), then
// either add_cell() for the slots that hold cells, in increasing order, then
// finish(); or set_rings() once and set_measures() per cell, which copy the
// corners' positions but make the pieces' corners and lengths only when first
// read (the same values: add_cell is the oracle).  Points are the cells'
// positions (LAMMPS: the cell atoms).
class PolygonCells : public CellView {
public:
  void clear(int n_owned, int n_points, const Points &pts);
  // Cell c: corners xy (n, counter-clockwise, unwrapped), the point across
  // each edge k (from corner k to k+1), its area and perimeter.
  void add_cell(int c, const double *xy, int n, const int *neighbor, double area, double perimeter);
  void finish();
  // Every slot at once (after clear()): slot c's corners are the points
  // corner[k] of corners for k in [offset[c], offset[c + 1])
  // (counter-clockwise, each cell's unwrapped), the point across edge k (from
  // corner k to the next) neighbor[k].  All are copied.
  void set_rings(const int *offset, const int *corner, const int *neighbor, const Points &corners);
  void set_measures(int c, double area, double perimeter) {
    area_[c] = area;
    perimeter_[c] = perimeter;
  }

  int dimension() const override { return 2; }
  int n_owned() const override { return n_owned_; }
  int n_points() const override { return n_points_; }
  double measure(int c) const override { return area_[c]; }
  double boundary(int c) const override { return perimeter_[c]; }
  int piece_begin(int c) const override { return offset_[c]; }
  int piece_end(int c) const override { return offset_[c + 1]; }
  int piece_neighbor(int k) const override { return neighbor_[k]; }
  double piece_size(int k) const override {
    if (lazy_)
      fill();
    return length_[k];
  }
  int piece_corners(int k, std::vector<double> &xyz) const override {
    if (lazy_)
      fill();
    xyz.insert(xyz.end(), corners_.begin() + 4 * k, corners_.begin() + 4 * k + 4);
    return 2;
  }
  void point(int i, double *x) const override {
    x[0] = pts_.x(i);
    x[1] = pts_.y(i);
  }
  Contacts contacts() const override;

private:
  int n_owned_ = 0, n_points_ = 0, filled_ = 0;
  Points pts_;
  std::vector<int> offset_, neighbor_;
  std::vector<double> area_, perimeter_;
  // The pieces' corners and lengths; with set_rings, made by fill() from
  // corner_ (per piece, an index into at_: 2 per point) at the first read.
  mutable std::vector<double> corners_, length_;
  mutable bool lazy_ = false;
  std::vector<int> corner_;
  std::vector<double> at_;
  void fill() const;
};

} // namespace tessera
