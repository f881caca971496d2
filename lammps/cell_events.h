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

   What fix cell/divide and fix cell/death share: counter-based random
   numbers (a value depends only on seed, atom ID, timestep and a stream
   number, so decisions are the same on any number of ranks), the region
   lookup of both LAMMPS APIs, and the global list of this step's events.
------------------------------------------------------------------------- */

#ifndef LMP_TESSERA_CELL_EVENTS_H
#define LMP_TESSERA_CELL_EVENTS_H

#include "domain.h"
#include "dump.h"
#include "lmptype.h"
#include "output.h"
#include "region.h"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace LAMMPS_NS {
namespace cell_events {

  inline uint64_t mix(uint64_t z)
  {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  // Uniform in (0, 1) from (seed, atom ID, step, stream).
  inline double uniform01(uint64_t seed, uint64_t tag, uint64_t step, uint64_t stream)
  {
    const uint64_t h = mix(mix(mix(mix(seed) ^ tag) ^ step) ^ (stream * 0x632be59bd9b4e019ULL));
    return ((h >> 11) + 0.5) * (1.0 / 9007199254740992.0);
  }

  // Streams (one per kind of decision, so that they are independent).
  enum Stream : uint64_t {
    DIVIDE = 1,
    AXIS = 2,
    PRIORITY = 3,
    NOISE = 4,
    CYCLE = 5,
    PHASE = 6,
    DIRECTION = 7,
    AXIS_Z = 8,    // 3d: the second coordinate of a random direction
    DIRECTION_Z = 9,
    NOISE_AXIS = 10,    // 3d: the axis about which the noise turns a polarity
    DEATH = 11,
    DEATH_PRIORITY = 12
  };

  // Step value used for draws made when a fix is created (initial cycle times).
  constexpr uint64_t CREATION = ~0ULL;

  // Region by ID: Domain::get_region_by_id (LAMMPS since 2022) or
  // Domain::find_region (older); nullptr if there is none.
  template <class D>
  auto find_region_impl(D *domain, const std::string &id, int)
      -> decltype(domain->get_region_by_id(id))
  {
    return domain->get_region_by_id(id);
  }
  template <class D> Region *find_region_impl(D *domain, const std::string &id, long)
  {
    const int i = domain->find_region(id);
    return i < 0 ? nullptr : domain->regions[i];
  }
  inline Region *find_region(Domain *domain, const std::string &id)
  {
    return find_region_impl(domain, id, 0);
  }

  // Every rank's candidates (atom ID, priority) gathered on all ranks and
  // sorted by priority then ID: the same list on any number of ranks.
  inline std::vector<std::pair<double, tagint>>
  gather_sorted(const std::vector<std::pair<double, tagint>> &mine, MPI_Comm world)
  {
    int nprocs = 1;
    MPI_Comm_size(world, &nprocs);
    const int n = static_cast<int>(mine.size());
    std::vector<int> counts(nprocs), displs(nprocs);
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
    int total = 0;
    for (int p = 0; p < nprocs; p++) {
      displs[p] = total;
      total += counts[p];
    }
    std::vector<double> prio(n), prio_all(total);
    std::vector<tagint> tags(n), tags_all(total);
    for (int k = 0; k < n; k++) {
      prio[k] = mine[k].first;
      tags[k] = mine[k].second;
    }
    MPI_Allgatherv(prio.data(), n, MPI_DOUBLE, prio_all.data(), counts.data(), displs.data(),
                   MPI_DOUBLE, world);
    MPI_Allgatherv(tags.data(), n, MPI_LMP_TAGINT, tags_all.data(), counts.data(), displs.data(),
                   MPI_LMP_TAGINT, world);
    std::vector<std::pair<double, tagint>> all(total);
    for (int k = 0; k < total; k++) all[k] = {prio_all[k], tags_all[k]};
    std::sort(all.begin(), all.end());
    return all;
  }

  // After atoms were added or removed mid-run: let every dump re-check the
  // atom IDs.  A dump sorted by ID decides at its init (the start of a run)
  // whether the IDs are 1..N and then places atoms by ID directly; once cells
  // have divided and died, N can be back at its start value with other IDs,
  // and that shortcut would write out of bounds.  Dump::init() recomputes it
  // (the output file stays open).
  inline void refresh_dumps(Output *output)
  {
    for (int i = 0; i < output->ndump; i++) output->dump[i]->init();
  }

}    // namespace cell_events
}    // namespace LAMMPS_NS

#endif
