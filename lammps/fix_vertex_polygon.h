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

#ifdef FIX_CLASS
// clang-format off
FixStyle(VERTEX_POLYGON,FixVertexPolygon);
// clang-format on
#else

#ifndef LMP_FIX_VERTEX_POLYGON_H
#define LMP_FIX_VERTEX_POLYGON_H

#include "fix.h"

#include <memory>
#include <string>
#include <vector>

namespace tessera {
struct VertexTissue;
class EdgeMap;
}    // namespace tessera

namespace LAMMPS_NS {

class PairVertexPolygon;

/* The internal fix of pair_style vertex/polygon (style VERTEX_POLYGON, added by
   the pair style, not for input scripts).  It keeps no per-atom state (the
   rings are in fix property/atom 'vring'), so the pair style may define it
   again to keep it last among the fixes with post_force (the steps it has
   scheduled are the pair style's, which restart files carry).
     - pre_neighbor of a step the previous one asked for: the topology step
       (T1, T2) by the rule every rank evaluates alike (doc/model.md, "Topology
       in parallel"); after every re-neighbouring, the ghosts' rings;
     - pre_exchange of the step after a T2: deletes the atoms it removed;
     - post_force: hands each cell atom's force to its vertices (each vertex
       gets a third of each of its cells'), then zeroes it;
     - end_of_step: asks for a topology step at the next step when some owned
       cell is a candidate (one MPI_Allreduce), and gives each cell atom the
       mean velocity of its vertices (the cell's velocity for fix polarity's
       velocity alignment and compute vertex/atom). */

class FixVertexPolygon : public Fix {
 public:
  FixVertexPolygon(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup_pre_exchange() override;
  void setup_pre_neighbor() override;
  void setup(int) override;
  void pre_exchange() override;
  void pre_neighbor() override;
  void min_pre_neighbor() override;
  void post_force(int) override;
  void end_of_step() override;
  void set_arrays(int) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;

  static const char *style_name() { return "VERTEX_POLYGON"; }
  static Fix *creator(class LAMMPS *, int, char **);
  PairVertexPolygon *pair = nullptr;

  // Forward communication of the rings to the ghosts (collective).
  void forward_rings();
  // Sums per-atom counts (one double per local atom) from ghosts onto owners.
  void reverse_counts(std::vector<double> &count);

  // Division of cells by a new edge (fix cell/divide; doc/model.md, "Division
  // and death"), in a pre_exchange, before any deletion: every rank passes
  // the mothers it owns (atom ID, the unit axis, the place in the step's
  // global order); new atom IDs are first_tag + 3 place (the daughter) and
  // + 1, + 2 (the two new vertices).  Returns the (mother, daughter) local
  // indices of the divisions carried out whose mother this rank owns; *done
  // and *refused (optional) count them on all ranks.  Collective.
  struct Division {
    tagint mother;
    double ux, uy;
    bigint place;
  };
  std::vector<std::pair<int, int>> divide(const std::vector<Division> &mothers, tagint first_tag,
                                          bigint *done = nullptr, bigint *refused = nullptr);
  // The step whose pre_exchange divides cells (its deletion of atoms a T2
  // removed waits for the divisions, which need the ghosts).
  bigint division_step = -1;
  void delete_removed();
  void delete_due();    // delete_removed() if this step is the one a T2 asked for

 private:
  enum Mode { RINGS, CANONICAL, SHARE, COUNT, VELOCITY };
  int mode = RINGS;
  std::vector<double> canon, share, *counts = nullptr;
  std::vector<int> patch_of;     // build_patch: patch index at the atom map's index of an ID
  std::vector<int> seen;         // build_patch: complete cells at each patch vertex
  std::vector<char> complete;    // build_patch: per patch cell, every vertex known
  struct Patch;
  std::shared_ptr<Patch> patch;
  int transfer = 1;    // some fix or pair style may put forces on cell atoms
  void request_steps();
  void cell_velocities();
  // One pass of the rule; returns the number of events carried out (all ranks).
  bigint run_topology();
  void build_patch(tessera::VertexTissue &t, tessera::EdgeMap &m);
  bool owned(tagint id) const;
  void thin(const std::string &what) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
