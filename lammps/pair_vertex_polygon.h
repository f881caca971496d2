/* -*- c++ -*- ----------------------------------------------------------
   TESSERA package for LAMMPS: vertex models of cell tissues
   LAMMPS: https://www.lammps.org/

   Copyright (2026) the Tessera developers.  This software is distributed
   under the GNU General Public License, version 2 or (at your option) any
   later version.
   SPDX-License-Identifier: GPL-2.0-or-later

   See the README file in the package's directory (src/TESSERA).
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing authors: the Tessera developers
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(vertex/polygon,PairVertexPolygon);
// clang-format on
#else

#ifndef LMP_PAIR_VERTEX_POLYGON_H
#define LMP_PAIR_VERTEX_POLYGON_H

#include "pair.h"

#include <memory>
#include <string>
#include <vector>

// Tessera's types this header names (tessera/cells.h, vertex_model.h):
// declared only, as a LAMMPS style header includes no more than its base
// class; the pair holds the values in Impl (the .cpp).
namespace tessera {
class CellView;
class PolygonCells;
struct Contacts;
struct Model;
struct TopologyParams;
}    // namespace tessera

namespace LAMMPS_NS {

class CellSource;
class FixVertexPolygon;

/* pair_style vertex/polygon: the vertex model (doc/model.md, "The vertex
   model").  Atoms of the vertex types are the polygons' corners; each atom of
   a cell type is a cell whose ring of vertex atom IDs lives in the per-atom
   array i_vring of 'fix vring all property/atom i2_vring W'.  The owner of a
   cell atom computes the cell's energy and the forces on its vertices' local
   copies closest to it (reverse communication sums them), and moves the cell
   atom to the cell's centroid.  Topology (T1, T2) and the hand-over of the
   cell atoms' forces to their vertices are the internal fix's
   (fix_vertex_polygon.cpp); the parameters are vertex/voronoi's
   (tessera::Model). */

class PairVertexPolygon : public Pair {
  friend class FixVertexPolygon;

 public:
  PairVertexPolygon(class LAMMPS *);
  ~PairVertexPolygon() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  double memory_usage() override;
  void *extract(const char *, int &) override;
  void reinit() override;

  // The cells for the computes and fixes that read them (CellSource): owned
  // cell c is local atom c, vertex atoms are empty cells; neighbours are the
  // local copies of the cell atoms across each edge, closest to the cell.
  // Filled at each force computation.
  const tessera::CellView &cells() const;
  bigint cells_step() const { return view_step; }
  void require_current_cells(const std::string &who);
  tessera::Contacts force_contacts() const;
  double force_boundary(int c) const;
  bigint force_count() const { return nforce; }
  bigint compute_count() const { return nforce; }
  bool is_cell_type(int type) const { return role(type) == CELL; }
  bool cells_are_vertices() const { return true; }

  enum Role { NONE = 0, CELL = 1, VERTEX = 2 };
  int role(int type) const { return type >= 1 && type < (int) roles.size() ? roles[type] : NONE; }
  // The rings' fix property/atom: its ID, the array's name, and a ring's
  // length (entries before the first 0; 0 for a removed atom, marked -1).
  static const char *ring_fix_id() { return "vring"; }
  const tessera::TopologyParams &topology() const { return topo; }
  int ring_length(int i) const;

 protected:
  double cut_global = 0.0;
  // The Tessera values the pair holds (topo, model, view, shown), behind one
  // pointer; the references name them (bound in the constructor).
  struct Impl;
  std::unique_ptr<Impl> impl;
  std::unique_ptr<CellSource> source;    // what extract("tessera/cell_source") gives
  tessera::TopologyParams &topo;
  tessera::Model &model;
  // Per type (1-based): role, cell parameters as given.
  std::vector<int> roles, quad;
  std::vector<double> kappa, area0, gamma, energy0;
  // Per type pair: Lambda_IJ and how it was given (0: the mean of the two
  // same-type values, 1: given, 2: the mean plus a quadratic sigma).
  std::vector<std::vector<double>> lambda, sigma;
  std::vector<std::vector<int>> lambda_set;
  // Type-pair arrays for fix adapt (extract): the values in use, filled by
  // build_model, read back by reinit (per-type values from the diagonal).
  double **adapt_kappa = nullptr, **adapt_area0 = nullptr, **adapt_gamma = nullptr;
  double **adapt_lambda = nullptr, **built_lambda = nullptr;
  void allocate();
  void build_model();
  void print_model() const;
  void bind_cell_values();

  // The rings (fix property/atom i2_vring): index into atom->iarray and width.
  int ring_index = -1, ring_width = 0;
  int restart_ring_width = 0;    // from a restart file: define the fix again
  void find_rings();

  // Per owned cell (local index i): the local copies of its ring's vertices
  // closest to it, and the local index of the cell across each edge, at
  // offsets off[i] .. off[i+1]; rebuilt after every re-neighbouring
  // (refresh()), valid until the next one.
  std::vector<int> off, ring_local, nbr_local;
  // refresh(): the directed edges of the local cells, as those leaving each
  // vertex's atom-map copy (edge_first), each with its end's ID and its cell.
  std::vector<int> edge_first, edge_fill, edge_to, edge_cell;
  int gather_ring(int i, std::vector<double> &xy, std::vector<int> &nt) const;
  bigint epoch = 0, cache_epoch = -1;    // re-neighbourings seen / the caches'
  void refresh();
  // The largest distance from a cell atom to one of its vertices (global),
  // at the last refresh: how far a cell reaches.
  double reach = 0.0;
  bool surely_inside_ghosts(const double *x, double margin) const;

  // Counts since the style was defined (the same on every rank): T1s, T2s,
  // refused events, topology steps.  The pair style's global vector, which
  // compute pair sums over ranks, holds them on rank 0 (pvec).
  double stats[4] = {0.0, 0.0, 0.0, 0.0};
  double pvec[4] = {0.0, 0.0, 0.0, 0.0};
  void publish_stats();
  int request = 0;    // some owned cell is a topology candidate
  // The steps the internal fix scheduled: a topology step (asked for at the
  // end of the step before) and the deletion of atoms a T2 removed.
  bigint topology_step = -1, delete_step = -1;
  tessera::PolygonCells &view;
  std::vector<double> cell_energy;    // per local atom, for the view
  bigint view_step = -1, nforce = 0;
  bigint view_natoms = -1;    // atom count of the view's step
  double view_box[8] = {};    // the box (h, boxlo) of the cells shown
  // The cells of a box changed after the forces (fix deform), for output.
  tessera::PolygonCells &shown;
  std::vector<double> shown_energy;
  bool show_shown = false;
  std::string fix_id;
  FixVertexPolygon *fix = nullptr;
  void check_integrators() const;
  void check_hybrid() const;
  bool box_changed() const;
  void cells_of_changed_box();
  void missing_atom(int i, tagint id, const char *what) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
