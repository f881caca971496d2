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
FixStyle(cell/death,FixCellDeath);
// clang-format on
#else

#ifndef LMP_FIX_CELL_DEATH_H
#define LMP_FIX_CELL_DEATH_H

#include "fix.h"

#include <memory>
#include <string>
#include <unordered_map>

namespace LAMMPS_NS {

namespace cell_events {
  struct EventCount;
  class EventLog;
}    // namespace cell_events

class FixCellDeath : public Fix {
 public:
  FixCellDeath(class LAMMPS *, int, char **);
  ~FixCellDeath() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  void pre_exchange() override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  // Per atom: whether the cell is dying (the vertex model: it shrinks until
  // a T2 takes it; fix_cell_death_vertex.cpp).
  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  bool dying(int i) const { return dying_since && dying_since[i] > 0.0; }

 protected:
  enum Trigger { RATE, AREA };
  int trigger, seed;
  double rate, area_min;
  double clock;        // the time of the current step, kept by restart files (for the event log)
  bigint min_cells;    // the floor in use (min N, or the model's default)
  bigint min_user = -1;    // min N as given, or -1
  int warned_floor = 0;    // the floor held back deaths (said once per run)
  std::string region_id;
  class Region *region;
  class CellSource *pair;
  bool vertex = false;    // the vertex model (pair_style vertex/polygon)
  int area0_index = -1, perim0_index = -1;
  double *dying_since = nullptr;    // per atom: 0, or the time the cell began to die
  bool noted_particles = false;
  bool takes(int i) const;    // owned atom i is a cell of the group
  bigint floor_room() const;
  // Cells that die at the next step -> their place in the sorted list (min N).
  std::unordered_map<tagint, bigint> pending;
  // The event count and the keyword file's log (cell_event_count.h,
  // cell_event_log.h) in Impl (the .cpp), named by events and log.
  struct Impl;
  std::unique_ptr<Impl> impl;
  cell_events::EventCount &events;
  cell_events::EventLog &log;    // keyword file

  void decide();
  void init_vertex();    // fix_cell_death_vertex.cpp
  void start_dying();
  bigint count_dying() const;
};

}    // namespace LAMMPS_NS

#endif
#endif
