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

   pair_style vertex/voronoi: the cells that output reads describe the
   state output shows.  In a LAMMPS step the forces are computed before the
   end of the step, where fix deform changes the box and remaps the
   positions; output (dumps, thermo) comes after it.  The pair style
   records the state its cells were computed for (the box and a hash of the
   owned atoms' positions); when a consumer asks for the cells of this step
   (require_current_cells()) and that state changed since, the cells of the
   current state are computed again, without changing the forces, the
   energy or the virial of the step.
------------------------------------------------------------------------- */

#include "pair_vertex_voronoi.h"

#include "pair_vertex_voronoi_model.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "update.h"

#include <cstring>
#include <vector>

using namespace LAMMPS_NS;

namespace {

inline std::uint64_t mix64(std::uint64_t z)
{
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}    // namespace

/* A hash of the bits of the owned atoms' positions, in their order,
   computed at every force computation and at every consumer's check, so
   kept cheap: mix(n + C sum_k (bits_k ^ k)) over the coordinates k that
   the cells depend on (x and y in 2d, where z plays no part; all three in
   3d, on the sphere too), k = 3 i + d for coordinate d of owned atom i,
   with C odd and the sum modulo 2^64.  The sum is one xor and one add per
   coordinate, independent of each other, which the compiler vectorizes;
   multiplying once by C gives the same value as multiplying every term
   (multiplication distributes over the sum modulo 2^64).  A change of one
   coordinate always changes the hash (the sum changes, and multiplying by
   an odd C is invertible modulo 2^64); changes of several coordinates
   leave it unchanged only when the changes of their xored bit patterns
   cancel modulo 2^64.  atom->x is one block (rows of memory->create). */

std::uint64_t PairVertexVoronoi::position_hash() const
{
  const std::uint64_t C = 0xd1b54a32d192ed03ULL;
  const std::uint64_t nlocal = atom->nlocal;
  const double *x = nlocal > 0 ? &atom->x[0][0] : nullptr;
  std::uint64_t sum = 0;
  if (domain->dimension == 2) {
    for (std::uint64_t k = 0; k < 3 * nlocal; k += 3) {
      std::uint64_t b[2];
      std::memcpy(b, &x[k], sizeof b);
      sum += (b[0] ^ k) + (b[1] ^ (k + 1));
    }
  } else {
    for (std::uint64_t k = 0; k < 3 * nlocal; k++) {
      std::uint64_t b;
      std::memcpy(&b, &x[k], sizeof b);
      sum += b ^ k;
    }
  }
  return mix64(nlocal + C * sum);
}

void PairVertexVoronoi::record_view_state()
{
  for (int d = 0; d < 3; d++) {
    view_box[d] = domain->boxlo[d];
    view_box[3 + d] = domain->boxhi[d];
  }
  view_box[6] = domain->xy;
  view_box[7] = domain->xz;
  view_box[8] = domain->yz;
  view_hash = position_hash();
  view_nall = atom->nlocal + atom->nghost;
}

/* Whether the box and, on every rank, the owned positions are those the
   cells were computed for (collective). */

bool PairVertexVoronoi::view_matches_state()
{
  const double now[9] = {domain->boxlo[0], domain->boxlo[1], domain->boxlo[2],
                         domain->boxhi[0], domain->boxhi[1], domain->boxhi[2],
                         domain->xy,       domain->xz,       domain->yz};
  int same = std::memcmp(now, view_box, sizeof now) == 0 && position_hash() == view_hash;
  int all = 0;
  MPI_Allreduce(&same, &all, 1, MPI_INT, MPI_MIN, world);
  return all != 0;
}

/* The cells can be computed again for the current state when this step's
   are there and the atoms are those they were computed for, ghost atoms
   included: a command between runs that redistributes the atoms
   (create_atoms, delete_atoms, displace_atoms) drops the ghost atoms,
   which only the next run acquires again. */

bool PairVertexVoronoi::cells_current()
{
  int ok = unit && tess_step == update->ntimestep && cells().n_owned() == atom->nlocal &&
      atom->nlocal + atom->nghost == view_nall;
  int all = 0;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, world);
  if (!all) return false;
  if (!view_matches_state()) refresh_view();
  return true;
}

/* The one check of every consumer of the cells, and its one message.  The
   reason is the same on every rank: unit and tess_step are, so when both
   are right some rank's atoms changed. */

void PairVertexVoronoi::require_current_cells(const std::string &who)
{
  if (cells_current()) return;
  std::string why;
  if (!unit || tess_step < 0)
    why = "the pair style has computed no cells yet";
  else if (tess_step != update->ntimestep)
    why = fmt::format("its cells are those of step {}", tess_step);
  else
    why = "the atoms changed since it computed them (between runs: atoms created, deleted or "
          "redistributed, e.g. by create_atoms, delete_atoms or displace_atoms)";
  error->all(FLERR,
             "{} reads the cells of pair_style vertex/voronoi at step {}, but {}; invoke it on a "
             "timestep when pair vertex/voronoi computed forces, after them: at the end of a "
             "step of a run (thermo, dumps, fix ave/*) or right after 'run 0' with no command "
             "in between that changes the atoms or the timestep, not from a fix that evaluates "
             "it before the forces of a step (e.g. through fix move's variables)",
             who, update->ntimestep, why);
}

/* The cells of the current state: ghost atoms brought to the owners'
   positions in the current box, the model's unit run again without energy
   or virial tallies, and the forces of the step put back (the next step
   moves the cells with them).  The cells count as new for the computes
   that keep results per force computation (compute_count()), so the
   neighbour-exchange count compares the new cells with the ones it saw
   last, once. */

void PairVertexVoronoi::refresh_view()
{
  // What the step integrates next are the cells of its forces: keep their
  // neighbour lists before the cells of the shown state replace them (once
  // per force computation: a second refresh at the same step must not
  // overwrite them with the first refresh's cells).
  if (force_saved != nforce) {
    const tessera::CellView &v = cells();
    const tessera::Contacts t = v.contacts();
    const int n = t.n_owned;
    force_offset.assign(t.offset, t.offset + n + 1);
    const int m = n > 0 ? t.offset[n] : 0;
    force_neighbor.assign(t.neighbor, t.neighbor + m);
    force_size.assign(t.size, t.size + m);
    force_bnd.resize(n);
    for (int c = 0; c < n; c++) force_bnd[c] = v.boundary(c);
    force_saved = nforce;
  }
  comm->forward_comm();
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  std::vector<double> f_step(3 * static_cast<size_t>(nall));
  std::vector<tagint> tags(atom->tag, atom->tag + nall);
  double **f = atom->f;
  for (int i = 0; i < nall; i++)
    for (int d = 0; d < 3; d++) f_step[3 * i + d] = f[i][d];
  for (int i = 0; i < nall; i++) f[i][0] = f[i][1] = f[i][2] = 0.0;
  ncompute++;
  ev_init(0, 0);
  unit->compute(0, 0);
  int moved = atom->nlocal != nlocal || atom->nlocal + atom->nghost != nall;
  for (int i = 0; !moved && i < nall; i++) moved = atom->tag[i] != tags[i];
  int any = 0;
  MPI_Allreduce(&moved, &any, 1, MPI_INT, MPI_MAX, world);
  if (any)
    error->all(FLERR,
               "pair_style vertex/voronoi at step {}: the box or the positions changed after "
               "this step's forces (e.g. fix deform), and the cells of the new state needed a "
               "wider ghost shell, which cannot be acquired before the next step; use a larger "
               "cutoff in pair_style vertex/voronoi",
               update->ntimestep);
  f = atom->f;
  for (int i = 0; i < nall; i++)
    for (int d = 0; d < 3; d++) f[i][d] = f_step[3 * i + d];
}

tessera::Contacts PairVertexVoronoi::force_contacts() const
{
  if (force_saved != nforce) return cells().contacts();
  tessera::Contacts t;
  t.n_owned = static_cast<int>(force_bnd.size());
  t.offset = force_offset.data();
  t.neighbor = force_neighbor.data();
  t.size = force_size.data();
  return t;
}

double PairVertexVoronoi::force_boundary(int c) const
{
  return force_saved != nforce ? cells().boundary(c) : force_bnd[c];
}
