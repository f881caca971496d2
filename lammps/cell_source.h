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

#ifndef LMP_CELL_SOURCE_H
#define LMP_CELL_SOURCE_H

#include "lmptype.h"

#include "tessera/cells.h"

#include <memory>
#include <string>

namespace LAMMPS_NS {

class LAMMPS;
class PairVertexVoronoi;
class PairVertexPolygon;

/* What the computes and fixes that read cells need from the pair style that
   makes them: pair_style vertex/voronoi (cells around atoms) and
   pair_style vertex/polygon (the vertex model) both implement it, so a
   consumer written once works with either.  cells() is the model-independent
   view (tessera/cells.h): owned cell c is local atom c (an atom that is no
   cell is an empty cell), neighbours are local atom indices. */

class CellSource {
 public:
  // This step's cells; valid for cells_step() until atoms are exchanged or
  // sorted.  Readers call require_current_cells(who) first (collective).
  virtual const tessera::CellView &cells() const = 0;
  virtual bigint cells_step() const = 0;
  virtual void require_current_cells(const std::string &who) = 0;
  // The neighbour lists and perimeters of the last force computation (for
  // what the next step integrates: fix polarity), and how many force
  // computations (and computations of cells for output) there have been.
  virtual tessera::Contacts force_contacts() const = 0;
  virtual double force_boundary(int c) const = 0;
  virtual bigint force_count() const = 0;
  virtual bigint compute_count() const = 0;
  // Which atom types are cells.
  virtual bool is_cell_type(int type) const = 0;
  // Model details some consumers check.
  virtual double finite_radius() const { return 0.0; }
  virtual bool on_sphere() const { return false; }
  virtual const double *sphere_centre() const { return nullptr; }
  // Whether the cells' atoms move by themselves (vertex/voronoi) or follow
  // their polygon's corners (vertex/polygon: no velocity of their own).
  virtual bool cells_are_vertices() const { return false; }

  // The pair style that makes cells (alone, or a sub-style of hybrid), or
  // nullptr.
  static CellSource *find(LAMMPS *lmp);
  // Its name for messages: "pair_style vertex/voronoi or vertex/polygon".
  static const char *styles() { return "pair_style vertex/voronoi or vertex/polygon"; }
  // What the pair styles' extract() hands out under this name (their headers
  // hold no Tessera type, as LAMMPS's style headers; see cell_source.cpp).
  static constexpr const char *extract_name = "tessera/cell_source";
  static std::unique_ptr<CellSource> of(PairVertexVoronoi &);
  static std::unique_ptr<CellSource> of(PairVertexPolygon &);

  virtual ~CellSource() = default;
};

}    // namespace LAMMPS_NS

#endif
