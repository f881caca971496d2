/* -*- c++ -*- ----------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(vertex/voronoi,PairVertexVoronoi);
// clang-format on
#else

#ifndef LMP_PAIR_VERTEX_VORONOI_H
#define LMP_PAIR_VERTEX_VORONOI_H

#include "pair.h"

#include "tessera/energy.h"
#include "tessera/finite.h"
#include "tessera/mesh.h"
#include "tessera/tessellation.h"
#include "tessera/voronoi3d.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairVertexVoronoi : public Pair {
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
  void reinit() override;
  double memory_usage() override;

  // The tessellation of the last force computation: owned cells are the local
  // atoms 0..nlocal-1, cell_neighbor entries are local atom indices (owned or
  // ghost).  Valid for the timestep tessellation_step() until atoms are
  // exchanged or sorted.  Used by fix polarity and compute vertex/atom.
  const tessera::Tessellation &tessellation() const { return tess; }
  bigint tessellation_step() const { return tess_step; }
  const std::vector<double> &cell_energy() const { return cell_e; }
  // Whether the tessellation was computed at the current timestep.
  bool tessellation_current() const;
  // Force computations since the style was created (never reset): tells
  // computes whether the tessellation changed since they last looked.
  bigint compute_count() const { return ncompute; }
  // dimension 3: the same for the 3D cells (pair_vertex_voronoi_3d.cpp).
  const tessera::Tessellation3 &tessellation3() const { return tess3; }
  bigint tessellation3_step() const { return tess3_step; }
  bool tessellation3_current() const;
  // For the step guard: sqrt(A0) of a type, and owned atom i's closest
  // Voronoi neighbour (ID, distance) at the last force computation.
  double cell_size(int type) const;
  bool closest_neighbour(int i, const double *owned_xy, tagint &j, double &d) const;
  // Finite Voronoi cells ('radius r'): r, or 0 for the confluent model; the
  // cells of the last force computation (tessellation() then holds their
  // contact edges only).
  double finite_radius() const { return radius; }
  const tessera::FiniteTessellation &finite_cells() const { return ftess; }

 protected:
  double cut_global;
  bigint ncompute = 0;
  tessera::Tension tension;
  double *kappa, *area0, *gamma;  // per type, 1-based
  double **lambda;                // per type pair
  int **lambda_set;               // 1 if pair_coeff I J gave Lambda_IJ explicitly
  int *type_set;                  // 1 if pair_coeff I I gave the cell parameters
  tessera::Model model;
  // Model-parameter plumbing for fix adapt and the quadratic heterotypic
  // tension (see build_model() and reinit()).
  double **lambda_extra;  // lambda_set == 2: Lambda_IJ = mean + this (pair_coeff I J quadratic)
  double **adapt_kappa, **adapt_area0, **adapt_gamma;  // type-pair views of the per-type values
  double **lambda_built;  // lambda as build_model() left it: what fix adapt changed since
  void build_model();
  int read_restart_settings_version(FILE *);
  void print_model() const;

  tessera::Tessellation tess;
  bigint tess_step;
  tessera::Mesh mesh;
  tessera::CellPass cell_pass;   // the forces' per-cell half, run by Mesh::advance
  bool fuse_cells = false;       // hand cell_pass to the next Mesh::advance
  int incremental;      // 1: keep the triangulation between steps, 0: rebuild every step, 2: check
  bigint mesh_ncalls;   // neighbor->ncalls when the mesh was built: atoms re-ordered since?
  int reference_every;  // time a from-scratch triangulation every this many steps (0: never)
  double stats[8];      // pvector: see the doc (times, rebuilds, flips, steps, reference)
  std::vector<int> type0;
  std::vector<double> cell_e;
  std::vector<double> cell_w;  // per-cell virial (2d: xx, yy, xy, yx; 3d: 9) when asked for

  double radius;                 // finite Voronoi radius (0: confluent model)
  double *free_tension;          // per type: tension of free arcs (internal F)
  int free_set;                  // 1 if some pair_coeff gave 'free'
  tessera::FiniteTessellation ftess;
  std::vector<double> free_t0;   // free_tension, 0-based
  void compute_finite();
  void bind_cell_area0();

  void allocate();
  bool tessellate();  // true if the ghost shell had to grow (atoms re-acquired)
  void grow_ghost_shell(double);
  int grow;             // widen the ghost shell when a cell needs it (default) or stop
  double cutghost_saved;  // comm->cutghostuser before this style raised it, or -1
  // Closest pair of centres among the owned cells' Voronoi neighbours at the
  // last force computation (atom IDs, distance, step), to name in errors.
  tagint close_i, close_j;
  double close_d;
  bigint close_step;
  void note_closest_pair();
  void note_closest_pair(int i, int q, double d2);
  void check_lost_atoms();
  std::string guard_id;
  void check_against_scratch(const tessera::Points &, const tessera::Region &, double);
  tessera::Region subdomain() const;
  double ghost_width() const;

  // dimension 3 (pair_vertex_voronoi_3d.cpp): a CGAL rebuild every step.
  tessera::Tessellation3 tess3;
  bigint tess3_step = -1;
  void init_style_3d();
  void compute_3d(int, int);
  bool tessellate_3d();  // true if the ghost shell had to grow
};

}    // namespace LAMMPS_NS

#endif
#endif
