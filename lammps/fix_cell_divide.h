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
FixStyle(cell/divide,FixCellDivide);
// clang-format on
#else

#ifndef LMP_FIX_CELL_DIVIDE_H
#define LMP_FIX_CELL_DIVIDE_H

#include "fix.h"

#include <memory>
#include <string>
#include <array>
#include <unordered_map>
#include <vector>

namespace LAMMPS_NS {

namespace cell_events {
  struct EventCount;
  class EventLog;
}    // namespace cell_events

class FixCellDivide : public Fix {
 public:
  FixCellDivide(class LAMMPS *, int, char **);
  ~FixCellDivide() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void setup_pre_force(int) override;
  void pre_force(int) override;
  void end_of_step() override;
  void pre_exchange() override;
  double compute_scalar() override;
  double compute_vector(int) override;

  void write_restart(FILE *) override;
  void restart(char *) override;
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
  // The division area of 'area Ac' (-1: another trigger), for messages.
  double division_area() const { return trigger == AREA ? area_max : -1.0; }

  // 'growth linear': the fix sets d_area0 before every step's forces.
  bool grows_area0() const { return growth != 0; }

 protected:
  enum Trigger { RATE, CYCLE, AREA };
  enum Axis { RANDOM, LONG, SHORT, POLARITY };
  // Per-atom columns (dump f_ID[c] is column c + 1): new ones are appended.
  enum Col { AGE, GENERATION, CYCLE_TIME, AREA0_BASE, MOTHER, BIRTH, NCOL };
  int trigger, axis, growth;
  double rate, cycle_mean, cycle_spread, area_max, separation, noise;
  bigint max_cells;
  int seed;
  std::string region_id;
  std::string trigger_text;    // the trigger as given, for error messages
  double clock;                // the time of the current step (restarts keep it)
  double decide_time;          // time of the step whose end made the pending decisions
  bool cap_warned;             // the max-with-growth warning was given
  class Region *region;
  class CellSource *pair;
  class FixVertexPolygon *vertex = nullptr;    // the vertex model's internal fix
  std::vector<class FixCellDeath *> deaths;    // a dying cell does not divide
  bool noted_particles = false;
  bool takes(int i) const;    // owned atom i is a cell of the group
  int area0_index;            // d_area0 in atom->dvector, or -1
  std::string rate_name;      // 'rate d_name': each cell's own rate, a per-atom property
  int rate_index = -1;
  double cell_rate(int i) const;
  std::vector<std::string> split_names;    // 'split d_name': halved between the daughters
  std::vector<int> split_index;

  double **cellstate;    // per atom: age, generation, cycle time, base A0, mother ID, birth time
  // Mothers of the next event step: atom ID -> division axis (ux, uy), and
  // the daughters' atom IDs assigned from the global sorted list.
  std::unordered_map<tagint, std::array<double, 3>> pending;    // division axis
  std::unordered_map<tagint, tagint> daughter_tag;
  // The event count and the keyword file's log (cell_event_count.h,
  // cell_event_log.h) in Impl (the .cpp), named by events and log.
  struct Impl;
  std::unique_ptr<Impl> impl;
  cell_events::EventCount &events;
  cell_events::EventLog &log;    // keyword file

  double draw_cycle(tagint, uint64_t) const;
  void cell_axis(int, double *) const;
  void fill_base_area0();
  void set_area0();
  bigint cap_room() const;
  void warn_cap(bigint);
  void decide();
  void born(int i, tagint mother, uint64_t step);
  void divide_vertex_cells();    // fix_cell_divide_vertex.cpp
};

}    // namespace LAMMPS_NS

#endif
#endif
