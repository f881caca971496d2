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

   The interface of pair_style vertex/voronoi's model units: each unit
   tessellates this step's owned and ghost atoms its own way, adds the
   forces to atom->f, fills the pair's per-cell energies (and per-cell
   virials when asked) and hands the total to PairVertexVoronoi::accumulate.
   It exposes its cells through the model-independent view.
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_VERTEX_VORONOI_MODEL_H
#define LMP_PAIR_VERTEX_VORONOI_MODEL_H

#include "pointers.h"

#include "tessera/cells.h"

namespace LAMMPS_NS {

class PairVertexVoronoi;

class VertexModel : protected Pointers {
 public:
  VertexModel(LAMMPS *lmp, PairVertexVoronoi *p) : Pointers(lmp), pair(p) {}
  virtual ~VertexModel() = default;
  // Its name in messages ("confluent 2d", "finite 2d", "3d").
  virtual const char *name() const = 0;
  // Checks of the settings and the box that only this model needs.
  virtual void init() {}
  // This step's cells and forces (ev_init done by the caller).
  virtual void compute(int eflag, int vflag) = 0;
  // The unit's view of its cells (bound to its tessellation by compute()).
  virtual tessera::CellView &view() = 0;
  const tessera::CellView &cells() const { return const_cast<VertexModel *>(this)->view(); }
  virtual double memory_usage() const { return 0.0; }

 protected:
  PairVertexVoronoi *pair;
};

}    // namespace LAMMPS_NS

#endif
