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

   compute cell/neighbor/mean: for each cell of the group, the mean of
   per-atom values over its neighbouring cells in the group, each neighbour
   weighted by the size of the junction it shares (edge length in 2d and on
   the sphere, face area in 3d): Collier et al.'s <d> for a lateral
   inhibition law.  The values (d_name, c_ID, c_ID[I], f_ID, f_ID[I],
   v_name) are taken on the owned cells and sent to the ghost cells.
------------------------------------------------------------------------- */

#include "compute_cell_neighbor_mean.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "input.h"
#include "junction_mean.h"
#include "memory.h"
#include "modify.h"
#include "cell_source.h"
#include "tessera_compat.h"
#include "update.h"
#include "variable.h"

#include <cstring>

using namespace LAMMPS_NS;

static const char SYNTAX[] =
    "compute ID group cell/neighbor/mean value ... (value: d_name, c_ID, c_ID[I], f_ID, "
    "f_ID[I] or v_name, each per-atom)";

ComputeCellNeighborMean::ComputeCellNeighborMean(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0), vout(nullptr), aout(nullptr), pair(nullptr)
{
  if (narg < 4)
    error->all(FLERR, "compute cell/neighbor/mean: give at least one value; syntax: {}", SYNTAX);
  for (int iarg = 3; iarg < narg; iarg++) {
    Input in;
    in.text = arg[iarg];
    in.column = 0;
    in.index = -1;
    const std::string &t = in.text;
    std::string body;
    if (t.rfind("d_", 0) == 0) {
      in.kind = DNAME;
      in.name = t.substr(2);
    } else if (t.rfind("c_", 0) == 0 || t.rfind("f_", 0) == 0) {
      in.kind = t[0] == 'c' ? COMPUTE : FIX;
      body = t.substr(2);
      const size_t open = body.find('[');
      if (open != std::string::npos) {
        if (body.back() != ']')
          error->all(FLERR, "compute cell/neighbor/mean: value '{}' lacks its closing ']'", t);
        in.column = utils::inumeric(FLERR, body.substr(open + 1, body.size() - open - 2).c_str(),
                                    false, lmp);
        if (in.column < 1)
          error->all(FLERR, "compute cell/neighbor/mean: column in '{}' must be >= 1", t);
        body = body.substr(0, open);
      }
      in.name = body;
    } else if (t.rfind("v_", 0) == 0) {
      in.kind = VARIABLE;
      in.name = t.substr(2);
    } else {
      error->all(FLERR, "compute cell/neighbor/mean: unknown value '{}'; syntax: {}", t, SYNTAX);
    }
    if (in.name.empty()) error->all(FLERR, "compute cell/neighbor/mean: value '{}' has no name", t);
    resolve(in);
    inputs.push_back(in);
  }
  peratom_flag = 1;
  size_peratom_cols = inputs.size() == 1 ? 0 : static_cast<int>(inputs.size());
  comm_forward = 1;
}

ComputeCellNeighborMean::~ComputeCellNeighborMean()
{
  memory->destroy(vout);
  memory->destroy(aout);
}

/* Finds the input's property, compute, fix or variable now (at the command
   and again at each init: they may have been re-defined), with an error that
   says what to define. */

void ComputeCellNeighborMean::resolve(Input &in)
{
  if (in.kind == DNAME) {
    int flag = -1, cols = -1;
    in.index = atom->find_custom(in.name.c_str(), flag, cols);
    if (in.index < 0 || flag != 1 || cols != 0)
      error->all(FLERR,
                 "compute cell/neighbor/mean: value '{}' names no per-atom floating-point "
                 "property; define it with 'fix ID all property/atom d_{}'",
                 in.text, in.name);
  } else if (in.kind == COMPUTE) {
    in.index = modify->find_compute(in.name);
    if (in.index < 0)
      error->all(FLERR, "compute cell/neighbor/mean: value '{}': no compute with ID '{}'", in.text,
                 in.name);
    Compute *c = modify->compute[in.index];
    if (!c->peratom_flag)
      error->all(FLERR,
                 "compute cell/neighbor/mean: value '{}': compute {} gives no per-atom values",
                 in.text, in.name);
    if ((in.column == 0) != (c->size_peratom_cols == 0) || in.column > c->size_peratom_cols)
      error->all(FLERR, "compute cell/neighbor/mean: value '{}': compute {} gives {}; use {}",
                 in.text, in.name,
                 c->size_peratom_cols ? fmt::format("{} per-atom columns", c->size_peratom_cols)
                                      : std::string("a per-atom vector"),
                 c->size_peratom_cols
                     ? fmt::format("c_{}[I] with 1 <= I <= {}", in.name, c->size_peratom_cols)
                     : "c_" + in.name);
  } else if (in.kind == FIX) {
    in.index = modify->find_fix(in.name);
    if (in.index < 0)
      error->all(FLERR, "compute cell/neighbor/mean: value '{}': no fix with ID '{}'", in.text,
                 in.name);
    Fix *f = modify->fix[in.index];
    if (!f->peratom_flag)
      error->all(FLERR, "compute cell/neighbor/mean: value '{}': fix {} gives no per-atom values",
                 in.text, in.name);
    if ((in.column == 0) != (f->size_peratom_cols == 0) || in.column > f->size_peratom_cols)
      error->all(FLERR, "compute cell/neighbor/mean: value '{}' does not match fix {}'s {} columns",
                 in.text, in.name, f->size_peratom_cols);
  } else {
    in.index = input->variable->find(in.name.c_str());
    if (in.index < 0)
      error->all(FLERR, "compute cell/neighbor/mean: value '{}': no variable named '{}'", in.text,
                 in.name);
    if (!input->variable->atomstyle(in.index))
      error->all(FLERR, "compute cell/neighbor/mean: value '{}': variable {} is not atom-style",
                 in.text, in.name);
  }
}

void ComputeCellNeighborMean::init()
{
  pair = CellSource::find(lmp);
  if (!pair)
    error->all(FLERR,
               "compute cell/neighbor/mean {} reads the cells of pair_style vertex/voronoi or "
               "vertex/polygon, but the pair style is '{}'; define one of them (vertex/voronoi "
               "alone or in hybrid)",
               id, force->pair_style ? force->pair_style : "none");
  for (Input &in : inputs) resolve(in);
}

/* The input's values on the owned atoms of the group (0 elsewhere). */

void ComputeCellNeighborMean::owned_values(Input &in, double *out)
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  if (in.kind == DNAME) {
    const double *d = atom->dvector[in.index];
    for (int i = 0; i < nlocal; i++) out[i] = (mask[i] & groupbit) ? d[i] : 0.0;
  } else if (in.kind == COMPUTE) {
    Compute *c = modify->compute[in.index];
    if (c->invoked_peratom != update->ntimestep) c->compute_peratom();
    for (int i = 0; i < nlocal; i++)
      out[i] = !(mask[i] & groupbit) ? 0.0
          : in.column                ? c->array_atom[i][in.column - 1]
                                     : c->vector_atom[i];
  } else if (in.kind == FIX) {
    Fix *f = modify->fix[in.index];
    if (update->ntimestep % f->peratom_freq)
      error->all(FLERR,
                 "compute cell/neighbor/mean {}: fix {} gives per-atom values every {} steps, "
                 "not at step {}",
                 id, in.name, f->peratom_freq, update->ntimestep);
    for (int i = 0; i < nlocal; i++)
      out[i] = !(mask[i] & groupbit) ? 0.0
          : in.column                ? f->array_atom[i][in.column - 1]
                                     : f->vector_atom[i];
  } else {
    input->variable->compute_atom(in.index, igroup, out, 1, 0);
  }
}

void ComputeCellNeighborMean::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  // (read before any run, e.g. through the library interface: no pair style yet)
  if (!pair)
    error->all(FLERR,
               "compute cell/neighbor/mean {}: no cells yet: it reads the cells of pair_style "
               "vertex/voronoi or vertex/polygon, which exist after a run (e.g. 'run 0')",
               id);
  pair->require_current_cells(fmt::format("compute cell/neighbor/mean {}", id));
  if (atom->nmax > nmax) {
    memory->destroy(vout);
    memory->destroy(aout);
    nmax = atom->nmax;
    if (size_peratom_cols) {
      memory->create(aout, nmax, size_peratom_cols, "cell/neighbor/mean:array");
      array_atom = aout;
    } else {
      memory->create(vout, nmax, "cell/neighbor/mean:vector");
      vector_atom = vout;
    }
  }
  const tessera::CellView &v = pair->cells();
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask;
  work.assign(atom->nmax, 0.0);
  for (size_t m = 0; m < inputs.size(); m++) {
    owned_values(inputs[m], work.data());
    tessera_compat::forward_comm(comm, this);
    for (int i = 0; i < nlocal; i++) {
      const double mean = (mask[i] & groupbit) ? junction_mean(v, i, work.data(), mask, groupbit)
                                               : 0.0;
      if (size_peratom_cols)
        aout[i][m] = mean;
      else
        vout[i] = mean;
    }
  }
}

int ComputeCellNeighborMean::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/,
                                               int * /*pbc*/)
{
  for (int k = 0; k < n; k++) buf[k] = work[list[k]];
  return n;
}

void ComputeCellNeighborMean::unpack_forward_comm(int n, int first, double *buf)
{
  for (int k = 0; k < n; k++) work[first + k] = buf[k];
}

double ComputeCellNeighborMean::memory_usage()
{
  return (double) nmax * (size_peratom_cols ? size_peratom_cols : 1) * sizeof(double) +
      (double) work.capacity() * sizeof(double);
}
