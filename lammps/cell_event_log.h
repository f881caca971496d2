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

   The event log of fix cell/divide and fix cell/death (keyword file): one
   line per division or death, gathered to rank 0 and written in a fixed
   order, so that the file is the same on any number of ranks.  A fix
   restored from a restart file continues the log: the lines after the
   restart's step (written by a run that went on past it) are dropped, the
   new events appended.
------------------------------------------------------------------------- */

#ifndef LMP_TESSERA_CELL_EVENT_LOG_H
#define LMP_TESSERA_CELL_EVENT_LOG_H

#include "lmptype.h"

#include <cstdio>
#include <string>
#include <vector>

namespace LAMMPS_NS {
class LAMMPS;
namespace cell_events {

  class EventLog {
   public:
    EventLog() = default;
    ~EventLog();
    EventLog(const EventLog &) = delete;
    EventLog &operator=(const EventLog &) = delete;

    // Called by the fix's constructor for its keyword 'file path'; fails (an
    // error naming the other fix) when another fix of this LAMMPS instance
    // writes the same path.  style: "cell/divide" or "cell/death".
    void configure(LAMMPS *lmp, const std::string &fix_id, const std::string &style,
                   const std::string &path);
    bool active() const { return !path.empty(); }
    // The fix was restored from a restart file: continue the log (see above).
    void continuing() { resume = true; }
    // Opens the file at the first call (rank 0); call from the fix's init().
    void open();
    // One event of this rank: its kind ("divide" or "death"), the cell's ID,
    // the daughters' IDs (0 for a death) and the cell's position.
    void add(const char *kind, tagint cell, tagint daughter1, tagint daughter2, const double *x);
    // Collective: gathers every rank's events of this step to rank 0, which
    // writes them sorted by cell ID with the time given (the fix's own clock,
    // which restart files keep), then forgets them.
    void flush(double time);

   private:
    LAMMPS *lmp = nullptr;
    std::string path, fix_id, style;
    FILE *fp = nullptr;
    bool resume = false;
    std::vector<double> rows;    // kind, cell, daughter1, daughter2, x, y, z per event
  };

}    // namespace cell_events
}    // namespace LAMMPS_NS

#endif
