/* ----------------------------------------------------------------------
   Tessera: active Voronoi vertex model in LAMMPS.
   SPDX-License-Identifier: GPL-2.0-or-later

   fix cell/signal ... implicit yes: one backward-Euler step per timestep
   for exchange, bath and degradation, the productions taken at the start
   of the step.  For each species the symmetric positive definite system
     x_i + dt [ (k + Pb F_i) x_i + P sum_j s_ij (x_i - x_j) ] = u_i + dt (R_i + Pb F_i cb)
   is solved by conjugate gradients (ghost values by forward communication,
   dot products over the owned cells); the amounts are then moved by the
   fluxes of the solution, P s_ij (x_j - x_i) on one side and its negative
   on the other, so the exchange conserves the total to round-off however
   closely the solver converged.
------------------------------------------------------------------------- */

#include "fix_cell_signal.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "tessera_compat.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

namespace {
constexpr double CG_TOL = 1e-13;    // relative residual
constexpr int CG_MAX = 2000;
}    // namespace

double FixCellSignal::dot(const double *a, const double *b)
{
  double local = 0.0, all = 0.0;
  for (int i = 0; i < atom->nlocal; i++) local += a[i] * b[i];
  MPI_Allreduce(&local, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return all;
}

/* out = M x on the owned cells (x: owned values; its ghost values are sent
   here).  Cells outside the group have identity rows. */

void FixCellSignal::apply_matrix(const Field &f, double dt, double *x, double *out)
{
  comm_vector = x;
  tessera_compat::forward_comm(comm, this);
  comm_vector = nullptr;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) {
      out[i] = x[i];
      continue;
    }
    double ex = 0.0;
    for (int k = row_offset[i]; k < row_offset[i + 1]; k++)
      ex += row_size[k] * (x[i] - x[row_index[k]]);
    out[i] = x[i] + dt * ((f.k + f.Pb * freelen[i]) * x[i] + f.P * ex);
  }
}

void FixCellSignal::implicit_step(double dt)
{
  comm_vector = nullptr;
  tessera_compat::forward_comm(comm, this);
  productions();    // from the values at the start of the step
  const int nlocal = atom->nlocal;
  const size_t nall = atom->nmax;
  const int *mask = atom->mask;
  cg_x.assign(nall, 0.0);
  cg_r.assign(nall, 0.0);
  cg_p.assign(nall, 0.0);
  cg_q.assign(nall, 0.0);
  cg_b.assign(nall, 0.0);
  // Every species' new values are computed (into next) before any changes,
  // so that all read the same start.
  std::vector<double> next(fields.size() * static_cast<size_t>(nlocal), 0.0);
  for (size_t f = 0; f < fields.size(); f++) {
    const Field &fd = fields[f];
    if (!fd.species) continue;
    const double *u = atom->dvector[fd.index];
    const double *prod = &rate[f * nlocal];
    for (int i = 0; i < nlocal; i++) {
      const bool in = mask[i] & groupbit;
      cg_b[i] = in ? u[i] + dt * (prod[i] + fd.Pb * freelen[i] * fd.cb) : u[i];
      cg_x[i] = u[i];
    }
    apply_matrix(fd, dt, cg_x.data(), cg_q.data());
    for (int i = 0; i < nlocal; i++) cg_p[i] = cg_r[i] = cg_b[i] - cg_q[i];
    const double bb = dot(cg_b.data(), cg_b.data());
    double rr = dot(cg_r.data(), cg_r.data());
    int it = 0;
    while (rr > CG_TOL * CG_TOL * bb && it < CG_MAX) {
      apply_matrix(fd, dt, cg_p.data(), cg_q.data());
      const double alpha = rr / dot(cg_p.data(), cg_q.data());
      for (int i = 0; i < nlocal; i++) {
        cg_x[i] += alpha * cg_p[i];
        cg_r[i] -= alpha * cg_q[i];
      }
      const double rr_new = dot(cg_r.data(), cg_r.data());
      for (int i = 0; i < nlocal; i++) cg_p[i] = cg_r[i] + (rr_new / rr) * cg_p[i];
      rr = rr_new;
      it++;
    }
    if (!(rr <= CG_TOL * CG_TOL * bb))
      error->all(FLERR,
                 "fix cell/signal {}: the implicit step of d_{} did not converge at step {} "
                 "(relative residual {} after {} iterations); use explicit substeps",
                 id, fd.name, update->ntimestep, std::sqrt(rr / (bb > 0.0 ? bb : 1.0)), it);
    // The amounts move by the fluxes of the solution.
    comm_vector = cg_x.data();
    tessera_compat::forward_comm(comm, this);
    comm_vector = nullptr;
    double *out = &next[f * nlocal];
    for (int i = 0; i < nlocal; i++) {
      out[i] = u[i];
      if (!(mask[i] & groupbit)) continue;
      double ex = 0.0;
      for (int k = row_offset[i]; k < row_offset[i + 1]; k++)
        ex += row_size[k] * (cg_x[row_index[k]] - cg_x[i]);
      out[i] = u[i] +
          dt * (fd.P * ex + fd.Pb * freelen[i] * (fd.cb - cg_x[i]) - fd.k * cg_x[i] + prod[i]);
      if (!(out[i] >= 0.0) || !std::isfinite(out[i]))
        fail(f, i, out[i], "the implicit step gives a negative value", nullptr, 1);
    }
  }
  for (size_t f = 0; f < fields.size(); f++) {
    if (!fields[f].species) continue;
    double *u = atom->dvector[fields[f].index];
    const double *out = &next[f * nlocal];
    for (int i = 0; i < nlocal; i++) u[i] = out[i];
  }
}
