/* ----------------------------------------------------------------------
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

#include "cell_event_log.h"

#include "comm.h"
#include "domain.h"
#include "error.h"
#include "lammps.h"
#include "update.h"

#include <mpi.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

using namespace LAMMPS_NS;
using namespace cell_events;

namespace {

// The paths the event logs of each LAMMPS instance write: path -> (log, fix ID).
struct Owner {
  const EventLog *log;
  std::string fix_id;
};
std::map<const LAMMPS *, std::map<std::string, Owner>> &registry()
{
  static std::map<const LAMMPS *, std::map<std::string, Owner>> paths;
  return paths;
}

const int NCOL = 7;    // kind, cell, daughter1, daughter2, x, y, z

}    // namespace

EventLog::~EventLog()
{
  if (fp) fclose(fp);
  if (!lmp) return;
  auto &mine = registry()[lmp];
  const auto found = mine.find(path);
  if (found != mine.end() && found->second.log == this) mine.erase(found);
  if (mine.empty()) registry().erase(lmp);
}

void EventLog::configure(LAMMPS *lmp_in, const std::string &id, const std::string &style_in,
                         const std::string &path_in)
{
  lmp = lmp_in;
  fix_id = id;
  style = style_in;
  path = path_in;
  auto &mine = registry()[lmp];
  const auto found = mine.find(path);
  // A fix defined again with the same ID replaces the old one (which is
  // deleted after this constructor): that is the same log.
  if (found != mine.end() && found->second.fix_id != fix_id)
    lmp->error->all(FLERR,
                    "fix {} {}: file {} is already the event log of fix {}; give each fix its own "
                    "file (tessera-tools lineage reads several)",
                    fix_id, style, path, found->second.fix_id);
  mine[path] = Owner{this, fix_id};
}

void EventLog::open()
{
  if (!active() || fp || lmp->comm->me != 0) return;
  const bigint step = lmp->update->ntimestep;
  std::string kept;
  bool have_header = false;
  if (resume) {
    // Continue the log of the run that wrote the restart file: keep what
    // happened up to its step.
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      if (line[0] == '#') {
        have_header = true;
      } else {
        std::istringstream words(line);
        bigint s = 0;
        if (!(words >> s) || s > step) continue;
      }
      kept += line + "\n";
    }
  }
  fp = fopen(path.c_str(), "w");
  if (!fp)
    lmp->error->one(FLERR, "fix {} {}: cannot open event log file {}: {}", fix_id, style, path,
                    strerror(errno));
  if (!have_header) {
    fprintf(fp, "# Tessera event log of fix %s %s (units %s)\n", fix_id.c_str(), style.c_str(),
            lmp->update->unit_style);
    fprintf(fp, "# step time event id daughter1 daughter2 x y z\n");
  }
  fputs(kept.c_str(), fp);
  fflush(fp);
}

void EventLog::add(const char *kind, tagint cell, tagint daughter1, tagint daughter2,
                   const double *x)
{
  if (!active()) return;
  const double row[NCOL] = {strcmp(kind, "divide") == 0 ? 0.0 : 1.0,
                            (double) cell,
                            (double) daughter1,
                            (double) daughter2,
                            x[0],
                            x[1],
                            lmp->domain->dimension == 3 ? x[2] : 0.0};
  rows.insert(rows.end(), row, row + NCOL);
}

void EventLog::flush(double time)
{
  if (!active()) return;
  MPI_Comm world = lmp->world;
  int nprocs = 1, me = 0;
  MPI_Comm_size(world, &nprocs);
  MPI_Comm_rank(world, &me);
  const int n = static_cast<int>(rows.size());
  std::vector<int> counts(nprocs), displs(nprocs);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, world);
  int total = 0;
  for (int p = 0; p < nprocs; p++) {
    displs[p] = total;
    total += counts[p];
  }
  std::vector<double> all(me == 0 ? total : 0);
  MPI_Gatherv(rows.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0,
              world);
  rows.clear();
  if (me != 0 || total == 0) return;
  if (!fp) open();
  const int nev = total / NCOL;
  std::vector<int> order(nev);
  for (int k = 0; k < nev; k++) order[k] = k;
  // By cell ID: each cell has one event per step, whatever rank owned it.
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return all[a * NCOL + 1] < all[b * NCOL + 1];
  });
  const Update *u = lmp->update;
  for (const int k : order) {
    const double *r = &all[k * NCOL];
    fprintf(fp, "%lld %.10g %s %lld %lld %lld %.10g %.10g %.10g\n", (long long) u->ntimestep, time,
            r[0] == 0.0 ? "divide" : "death", (long long) r[1], (long long) r[2], (long long) r[3],
            r[4], r[5], r[6]);
  }
  fflush(fp);
}
