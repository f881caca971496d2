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

// The event counter that fix cell/divide and fix cell/death share.

#ifndef TESSERA_CELL_EVENT_COUNT_H
#define TESSERA_CELL_EVENT_COUNT_H

#include "lmptype.h"

#include <cstdio>

namespace LAMMPS_NS {
namespace cell_events {

  // The events of a fix: the cumulative count, the count of the last event step
  // (thermo: compute_scalar and compute_vector), and their restart record.
  struct EventCount {
    bigint total = 0;
    int last = 0;
    bigint last_step = -1;

    void record(int n, bigint step)
    {
      total += n;
      last = n;
      last_step = step;
    }
    // element 0: events on this step; element 1: all events so far
    double vector(int n, bigint step) const
    {
      if (n == 0) return last_step == step ? last : 0.0;
      return (double) total;
    }
    // The global restart record, with the fix's clock (its time, kept across
    // runs): a marker -1 (older files start with the event count, which is
    // >= 0), the event count, the step of the last event, the clock.
    void write_restart(FILE *fp, double clock) const
    {
      double list[4] = {-1.0, (double) total, (double) last_step, clock};
      const int size = sizeof(list);
      fwrite(&size, sizeof(int), 1, fp);
      fwrite(list, sizeof(double), 4, fp);
    }
    // An older file (count and step, no clock) leaves the clock as it is.
    void restart(const char *buf, double &clock)
    {
      const double *list = reinterpret_cast<const double *>(buf);
      const int k = list[0] >= 0.0 ? 0 : 1;
      total = static_cast<bigint>(list[k]);
      last_step = static_cast<bigint>(list[k + 1]);
      if (k) clock = list[3];
    }
  };

}    // namespace cell_events
}    // namespace LAMMPS_NS

#endif
