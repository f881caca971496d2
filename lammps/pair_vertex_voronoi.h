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
PairStyle(vertex/voronoi,PairVertexVoronoi);
// clang-format on
#else

#ifndef LMP_PAIR_VERTEX_VORONOI_H
#define LMP_PAIR_VERTEX_VORONOI_H

#include "pair.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

// Tessera's types this header names (tessera/cells.h, energy.h,
// subset_cells.h): declared only, as a LAMMPS style header includes no more
// than its base class; the pair holds the values in Impl (the .cpp).
namespace tessera {
class CellView;
class SubsetCells;
struct Contacts;
struct Model;
enum class Tension;
}    // namespace tessera

namespace LAMMPS_NS {

class CellSource;
class VertexModel;

/* The face of pair_style vertex/voronoi: settings, pair_coeff, the per-type
   table, fix adapt (extract/reinit), restart files, the ghost shell and the
   accumulation of energy and virial.  The cells themselves are computed by
   one unit per model (pair_vertex_voronoi_confluent.cpp, _finite.cpp,
   _3d.cpp, all behind the VertexModel interface), chosen in init_style from
   the dimension and the 'radius' keyword.  Every consumer reads the cells
   through cells(), the model-independent view (tessera/cells.h). */

class PairVertexVoronoi : public Pair {
  friend class VertexModel;
  friend class VertexConfluent;
  friend class VertexFinite;
  friend class Vertex3d;
  friend class VertexSphere;

 public:
  PairVertexVoronoi(class LAMMPS *);
  ~PairVertexVoronoi() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  void *extract(const char *, int &) override;
  void modify_params(int, char **) override;
  void reinit() override;
  double memory_usage() override;

  // This step's owned cells (owned cell c is local atom c; neighbours and
  // rings are local atom indices, owned or ghost), for every model.  Valid
  // for the timestep cells_step() until atoms are exchanged or sorted.
  const tessera::CellView &cells() const;
  bigint cells_step() const { return tess_step; }
  // For every compute or fix that reads cells(), before it reads them
  // (collective: call on every rank; who names the caller, e.g. "compute
  // vertex/atom c1").  Makes cells() describe the current timestep's atoms:
  // when the forces of this timestep were computed but the box or the owned
  // atoms' positions changed since (fix deform at the end of the step), the
  // cells of the current state are computed first, the forces, energy and
  // virial staying those of the step; when the cells are not this step's
  // (no force computation at this step, or atoms created or deleted since)
  // it stops with one error naming who (pair_vertex_voronoi_view.cpp).
  void require_current_cells(const std::string &who);
  // The neighbour lists (and boundaries) of the cells of the last force
  // computation, for what the next step integrates (fix polarity): the
  // view's own, or, once refresh_view() recomputed the cells for output at
  // this step, the copy it made of them just before.  force_count() counts
  // force computations only (not refreshes).
  tessera::Contacts force_contacts() const;
  double force_boundary(int c) const;
  bigint force_count() const { return nforce; }
  // Force computations, and computations of the cells for output after the
  // state changed (require_current_cells()), since the style was created
  // (never reset): tells computes whether the cells changed since they last
  // looked.
  bigint compute_count() const { return ncompute; }
  // Finite Voronoi radius r, or 0 (confluent or 3D cells).
  double finite_radius() const { return radius; }
  // For the step guard: sqrt(A0) of a type (cbrt(V0) in 3D).
  double cell_size(int type) const;
  // What limits the step of an integrator that moved cells too far: a
  // smaller timestep, 'fix dt/reset', and fix brownian/heun unless in use.
  std::string step_advice() const;
  // Set by the step guard after each integration: the largest distance an
  // owned atom moved in it (-1: not measured); the lost-atom error uses it
  // to tell the integrator's losses from the other commands'.
  double step_move_local = -1.0;
  // Two fixes that integrate the positions of the same cells: an error
  // naming both (called by the step guard's init, after the other fixes').
  void check_integrators() const;
  // 'surface sphere cx cy cz R': the cells live on a sphere (the unit of
  // pair_vertex_voronoi_sphere.cpp).  Its centre, and its radius now (an
  // equal-style variable is evaluated at each call).
  bool on_sphere() const { return sphere_on != 0; }
  const double *sphere_centre() const { return sphere_c; }
  double sphere_radius();
  // Stops with an error when the sphere of radius R reaches past the box.
  void check_sphere_box(double R) const;
  // Which atoms are cells: those of the types given cell parameters
  // ('pair_coeff I I ...').  Under pair_style hybrid/overlay the atoms of
  // other types are not cells: never tessellated, an empty cell in cells().
  bool is_cell_type(int type) const { return type_set && type_set[type]; }
  // The values a new cell of this type takes in the per-cell properties
  // d_area0, d_ka, d_kp, d_perim0 (the quadratic form of its type's
  // parameters in use; 0 for a type that is no cell, and d_perim0 0 for a
  // type without a perimeter modulus): what the step guard gives atoms that
  // fix deposit, fix pour or create_atoms make.
  void type_cell_values(int type, double values[4]) const;

 protected:
  void keyword_defaults();    // the pair_style keywords' defaults
  int nofdotr_given = 0;      // 'pair_modify nofdotr' given (init_style sets LAMMPS's flag)
  void check_single_instance() const;    // one vertex/voronoi under pair_style hybrid
  double cut_global;
  bigint ncompute = 0;
  // The Tessera values the pair holds (model, subset), behind one pointer;
  // model and subset name them (bound in the constructor).
  struct Impl;
  std::unique_ptr<Impl> impl;
  std::unique_ptr<CellSource> source;    // what extract("tessera/cell_source") gives
  tessera::Tension tension;
  double *kappa, *area0, *gamma;    // per type, 1-based
  double **lambda;                  // per type pair
  int **lambda_set;                 // 1 if pair_coeff I J gave Lambda_IJ explicitly
  int *type_set;                    // 1 if pair_coeff I I gave the cell parameters
  int *quad_set;                    // 1 if they came in the quadratic form
  double *energy0;                  // per type: the quadratic form's constant (see build_model)
  tessera::Model &model;
  // Model-parameter plumbing for fix adapt and the quadratic heterotypic
  // tension (see build_model() and reinit()).
  double **lambda_extra;    // lambda_set == 2: Lambda_IJ = mean + this (pair_coeff I J quadratic)
  double **adapt_kappa, **adapt_area0, **adapt_gamma;    // type-pair views of the per-type values
  double **lambda_built;     // lambda as build_model() left it: what fix adapt changed since
  int warned_area0 = 0;      // fix adapt changed area0 while d_area0 exists (warned once)
  int warned_percell = 0;    // fix adapt changed kappa/gamma while d_ka/d_kp exists (once)
  void build_model();
  bool adapted() const;
  int read_restart_settings_version(FILE *);
  void print_model() const;

  std::unique_ptr<VertexModel> unit;    // the model's unit, made in init_style
  bigint tess_step;
  int incremental;    // 1: keep the triangulation between steps, 0: rebuild every step, 2: check
  int reference_every;    // time a from-scratch triangulation every this many steps (0: never)
  double stats[8];        // pvector: see the doc (times, rebuilds, flips, steps, reference)
  std::vector<int> type0;
  std::vector<double> cell_e;
  std::vector<double> cell_w;    // per-cell virial (2d: xx, yy, xy, yx; 3d: 9) when asked for

  double radius;                  // finite Voronoi radius (0: confluent model)
  double *free_tension;           // per type: tension of free arcs (internal F)
  int free_set;                   // 1 if some pair_coeff gave 'free'
  std::vector<double> free_t0;    // free_tension, 0-based

  void allocate();
  // The cells among the atoms (pair_vertex_voronoi_cells.cpp).  Every unit
  // tessellates a compact list of points, this step's cell atoms: owned
  // cells first (ncell_local), then ghost cells (ncell_all in all); compact
  // point p is local atom cell_local[p].  When every type is a cell type the
  // list is the atoms themselves (no copies).  gather_cells() makes the list
  // before each tessellation; cell_x() and cell_f() are its positions and
  // the force array the units add to (stride 3), cell_tag() its atom IDs;
  // finish_cells() (from accumulate) adds the forces to the atoms and binds
  // the view that shows the cells in local atom indices.
  int all_cell_types = 1;
  int ncell_local = 0, ncell_all = 0;
  std::vector<int> cell_local, cell_scratch;
  std::vector<double> cell_xbuf, cell_fbuf;
  bigint cell_map_version = 0;    // changes when the list is not the last one
  tessera::SubsetCells &subset;
  std::vector<double> cell_e_atom, cell_pc[4];    // per owned atom; compact per-cell values
  void check_cell_types();
  void gather_cells();
  const double *cell_x() const;
  double *cell_f();
  tagint cell_tag(int p) const;
  int cell_atom(int p) const { return all_cell_types ? p : cell_local[p]; }
  void finish_cells();
  const double *compact_values(const double *per_atom, int k);
  // Shared by the units: this step's 0-based types, cell energy array and
  // per-cell A0 ('fix property/atom d_area0').
  void prepare_atoms();
  void bind_cell_area0();
  // Per-cell KA, KP, P0 ('fix property/atom d_ka d_kp d_perim0').
  void bind_cell_params();
  // The shared tail of every unit: the constant of the quadratic forms, the
  // per-atom energy and virial, the global energy and the f dot r virial.
  // cell_w holds nw values per cell (4 in 2d, 9 in 3d) when vflag_atom.
  void accumulate(double energy, int nw);
  // A cell needs the ghost shell this much wider on some rank (the maximum
  // over ranks is taken here; 0: complete, infinity: a cell is unbounded):
  // widen it and re-acquire the atoms (true: the unit tessellates again) or
  // stop with an error that names the cutoff to use.
  bool ghost_shell_complete(double need_local);
  void grow_ghost_shell(double);
  int grow;                 // widen the ghost shell when a cell needs it (default) or stop
  double cutghost_saved;    // comm->cutghostuser before this style raised it, or -1
  // Closest pair of centres among the owned cells' neighbours at the last
  // force computation (atom IDs, distance, step), to name in errors.
  tagint close_i, close_j;
  double close_d;
  bigint close_step;
  void note_closest_pair();
  void note_closest_pair(int i, int q, double d2);
  void check_lost_atoms();
  bigint natoms_seen = -1;    // the atom count at the last force computation
  // The run's start checks (pair_vertex_voronoi_checks.cpp).
  void check_cutoff_range() const;
  void check_sort_bins() const;
  int incremental_given = 0;    // 1 if the pair_style line gave 'incremental'
  // The ghost shell grew 8 times within one step and still was too thin.
  [[noreturn]] void ghost_shell_failed() const;
  // The state the cells were computed for: box and a hash of the owned
  // atoms' positions (pair_vertex_voronoi_view.cpp).  cells_current():
  // whether the cells are this timestep's (collective, the same answer on
  // every rank), after computing those of the current state if it changed.
  double view_box[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  std::uint64_t view_hash = 0;
  int view_nall = -1;    // owned + ghost atoms then
  void record_view_state();
  std::uint64_t position_hash() const;
  bool cells_current();
  bool view_matches_state();
  void refresh_view();
  bigint nforce = 0;          // force computations (compute()), never reset
  bigint force_saved = -1;    // nforce whose contacts refresh_view() saved below
  std::vector<int> force_offset, force_neighbor;
  std::vector<double> force_size, force_bnd;
  std::string guard_id;
  double ghost_width() const;
  // 'surface sphere' (pair_vertex_voronoi_sphere.cpp: parsing, restart
  // record, the internal fix that keeps the atoms on the sphere)
  int sphere_on = 0;
  double sphere_c[3] = {0.0, 0.0, 0.0};
  double sphere_R = 0.0;     // the radius, when not a variable
  std::string sphere_var;    // name of an equal-style variable for R, or empty
  std::string sphere_fix_id;
  int parse_surface(int iarg, int narg, char **arg);
  void write_sphere_settings(FILE *) const;
  void read_sphere_settings(FILE *);
  void add_sphere_fix();
};

}    // namespace LAMMPS_NS

#endif
#endif
