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

   The few LAMMPS C++ APIs that changed between the releases Tessera builds
   against (29 Sep 2021, Debian 12's, and current ones such as 4 Jul 2026),
   behind one spelling that compiles against either set of headers.  Every
   other LAMMPS API our styles use is the same in both.

     tessera_compat::FixStorePerAtom     per-atom storage fix: FixStore (2021),
                                          FixStoreAtom (2026); members astore/vstore
     tessera_compat::store_peratom(n, restart)
                                          the style and arguments that create it:
                                          "STORE peratom r n" / "STORE/ATOM n 0 0 r"
     tessera_compat::forward_comm(comm, this), reverse_comm(comm, this)
                                          for a Pair, Fix or Compute: forward_comm_pair/
                                          _fix/_compute (2021), forward_comm(this) (2026)
     tessera_compat::abort_universe(e)   LAMMPSAbortException's communicator:
                                          public member (2021), get_universe() (2026)

   The storage fix is told apart by its header (one #if); the rest by which
   member function exists (overload resolution), so no LAMMPS version number
   is compared anywhere.
------------------------------------------------------------------------- */

#ifndef TESSERA_COMPAT_H
#define TESSERA_COMPAT_H

#include "comm.h"
#include "exceptions.h"

#include <string>
#include <utility>

#if __has_include("fix_store_atom.h")
#include "fix_store_atom.h"
#define TESSERA_COMPAT_STORE_ATOM 1
#else
#include "fix_store.h"
#define TESSERA_COMPAT_STORE_ATOM 0
#endif

namespace LAMMPS_NS {
namespace tessera_compat {

#if TESSERA_COMPAT_STORE_ATOM
  using FixStorePerAtom = FixStoreAtom;
#else
  using FixStorePerAtom = FixStore;
#endif

  // "<style> <args>" for Modify::add_fix("ID group " + store_peratom(...)):
  // ncols doubles per atom (astore if ncols > 1, vstore if ncols == 1), not
  // communicated to ghosts, written to restart files if restart is true.
  inline std::string store_peratom(int ncols, bool restart)
  {
    const std::string r = restart ? "1" : "0";
    if (TESSERA_COMPAT_STORE_ATOM) return "STORE/ATOM " + std::to_string(ncols) + " 0 0 " + r;
    return "STORE peratom " + r + " " + std::to_string(ncols);
  }

  namespace detail {

    // The first overload exists only where the 2021 name does (rank int beats long).
    template <class C, class P>
    auto forward(C *comm, P *p, int) -> decltype(comm->forward_comm_pair(p), void())
    {
      comm->forward_comm_pair(p);
    }
    template <class C, class F>
    auto forward(C *comm, F *f, int) -> decltype(comm->forward_comm_fix(f), void())
    {
      comm->forward_comm_fix(f);
    }
    template <class C, class X>
    auto forward(C *comm, X *x, int) -> decltype(comm->forward_comm_compute(x), void())
    {
      comm->forward_comm_compute(x);
    }
    template <class C, class T> void forward(C *comm, T *t, long)
    {
      comm->forward_comm(t);
    }

    template <class C, class P>
    auto reverse(C *comm, P *p, int) -> decltype(comm->reverse_comm_pair(p), void())
    {
      comm->reverse_comm_pair(p);
    }
    template <class C, class F>
    auto reverse(C *comm, F *f, int) -> decltype(comm->reverse_comm_fix(f), void())
    {
      comm->reverse_comm_fix(f);
    }
    template <class C, class X>
    auto reverse(C *comm, X *x, int) -> decltype(comm->reverse_comm_compute(x), void())
    {
      comm->reverse_comm_compute(x);
    }
    template <class C, class T> void reverse(C *comm, T *t, long)
    {
      comm->reverse_comm(t);
    }

    template <class E> auto universe(const E &e, int) -> decltype(e.get_universe())
    {
      return e.get_universe();
    }
    template <class E> MPI_Comm universe(const E &e, long)
    {
      return e.universe;
    }

  }    // namespace detail

  // Forward communication of a style's pack/unpack_forward_comm to ghosts;
  // `self` is a Pair *, Fix * or Compute * (pass `this`).
  template <class T> void forward_comm(Comm *comm, T *self)
  {
    detail::forward(comm, self, 0);
  }

  // Reverse communication (ghosts to owners) of pack/unpack_reverse_comm.
  template <class T> void reverse_comm(Comm *comm, T *self)
  {
    detail::reverse(comm, self, 0);
  }

  inline MPI_Comm abort_universe(const LAMMPSAbortException &e)
  {
    return detail::universe(e, 0);
  }

}    // namespace tessera_compat
}    // namespace LAMMPS_NS

#endif
