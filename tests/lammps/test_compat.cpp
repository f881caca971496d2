// Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Compiles every wrapper of tessera_compat.h for a Pair, a Fix and a Compute
// against the LAMMPS headers of this build (2021 in the default build, the
// plugin's LAMMPS in a TESSERA_PLUGIN build): a wrapper that picks a member
// function the headers lack fails the build.  Built, never run.

#include "tessera_compat.h"

#include "compute.h"
#include "fix.h"
#include "pair.h"

#include <string>

using namespace LAMMPS_NS;

void tessera_compat_uses(Comm *comm, Pair *pair, Fix *fix, Compute *compute,
                         tessera_compat::FixStorePerAtom *store, const LAMMPSAbortException &e)
{
  tessera_compat::forward_comm(comm, pair);
  tessera_compat::forward_comm(comm, fix);
  tessera_compat::forward_comm(comm, compute);
  tessera_compat::reverse_comm(comm, pair);
  tessera_compat::reverse_comm(comm, fix);
  tessera_compat::reverse_comm(comm, compute);
  double **a = store->astore;
  (void) a;
  const std::string style = tessera_compat::store_peratom(3, true);
  (void) style;
  MPI_Comm universe = tessera_compat::abort_universe(e);
  (void) universe;
}
