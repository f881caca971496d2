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

   fix cell/signal ... implicit yes: one backward-Euler step per timestep
   for exchange, bath and degradation, the productions taken at the start
   of the step.  For each species the symmetric positive definite system
     (1 + dt d_i) x_i + dt P sum_j s_ij (x_i - x_j) = b_i,
     d_i = k + Pb F_i,  b_i = u_i + dt (R_i + Pb F_i cb)
   is solved by conjugate gradients (ghost values by forward
   communication, dot products over the owned cells).

   Stiff exchange (dt P s_ij far above 1) makes the solution nearly uniform
   over each connected patch of cells, and the fluxes dt P s_ij (x_j - x_i)
   that the step moves are then large multiples of differences far below
   the values themselves: a solution held in one double per cell loses
   them (relative error about dt P s_ij times 1e-16).  So the solution is
   kept as a sum x = x1 + xd, refined until its residual stops falling:
   x1 from the first solve, xd the sum of the corrections, each solved
   from the residual b - M (x1 + xd) in which the differences x1_j - x1_i
   and xd_j - xd_i are taken apart.  The new amounts are then
     u_i' = (u_i + dt (R_i + Pb F_i cb) + e_i) / (1 + dt d_i),
     e_i = dt P sum_j s_ij ((x1_j - x1_i) + (xd_j - xd_i)),
   which is x_i in exact arithmetic; e_i is antisymmetric between the two
   cells of a junction, so the exchange conserves the total to round-off
   however closely the solver converged, and the new amount is not
   negative whenever the cell's inflow and own sources are not.
------------------------------------------------------------------------- */

#include "fix_cell_signal.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "tessera_compat.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <limits>

using namespace LAMMPS_NS;

namespace {
constexpr double CG_TOL = 1e-13;    // relative residual of each solve (its own recurrence)
constexpr int CG_MAX = 2000;
// Refinement ends at round-off (this fraction of the right-hand side), or
// when a correction no longer halves the residual (the better solution is
// kept) ...
constexpr int REFINE_MAX = 12;
constexpr double ROUND_OFF = 1e-13;
// The new amounts are the solution plus the residual: above this fraction
// of the right-hand side the step warns, above the next it stops.
constexpr double REFINED_TOL = 1e-12;
constexpr double FAILED_TOL = 1e-6;
// Above this dt P W_i / (1 + dt d_i) (largest over the cells) the solves
// start from a uniform value: from the old values they would carry the
// uniform part through iterations whose round-off grows with dt P.
constexpr double STIFF = 1e6;
}    // namespace

double FixCellSignal::dot(const double *a, const double *b)
{
  double local = 0.0, all = 0.0;
  for (int i = 0; i < atom->nlocal; i++) local += a[i] * b[i];
  MPI_Allreduce(&local, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return all;
}

/* Ghost values of x (and of x2 when given) from their owners. */

void FixCellSignal::forward_vectors(double *x, double *x2)
{
  comm_vector = x;
  comm_vector2 = x2;
  tessera_compat::forward_comm(comm, this);
  comm_vector = comm_vector2 = nullptr;
}

/* out = M x on the owned cells (x: owned values; its ghost values are sent
   here).  Cells outside the group, and particles, have identity rows.
   Returns this rank's sum of x_i out_i. */

double FixCellSignal::apply_matrix(const Field &f, double dt, double *x, double *out)
{
  forward_vectors(x, nullptr);
  double xout = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!taken[i]) {
      out[i] = x[i];
    } else {
      double ex = 0.0;
      for (int k = row_offset[i]; k < row_offset[i + 1]; k++)
        ex += row_size[k] * (x[i] - x[row_index[k]]);
      out[i] = x[i] + dt * ((f.k + f.Pb * freelen[i]) * x[i] + f.P * ex);
    }
    xout += x[i] * out[i];
  }
  return xout;
}

/* The exchange of owned cell i for the solution x1 + xd (ghost values
   current): sum_j s_ij ((x1_j - x1_i) + (xd_j - xd_i)). */

double FixCellSignal::exchange_of(int i, const double *x1, const double *xd) const
{
  double ex = 0.0;
  for (int k = row_offset[i]; k < row_offset[i + 1]; k++) {
    const int j = row_index[k];
    ex += row_size[k] * ((x1[j] - x1[i]) + (xd[j] - xd[i]));
  }
  return ex;
}

/* r = b - M (x1 + xd) on the owned cells, the exchange from the differences
   of x1 and of xd apart.  Returns |r|. */

double FixCellSignal::residual(const Field &f, double dt, const double *b, double *x1, double *xd,
                               double *r)
{
  forward_vectors(x1, xd);
  for (int i = 0; i < atom->nlocal; i++) {
    if (!taken[i]) {
      r[i] = 0.0;
      continue;
    }
    const double x = x1[i] + xd[i];
    r[i] = b[i] - (x + dt * (f.k + f.Pb * freelen[i]) * x) + dt * f.P * exchange_of(i, x1, xd);
  }
  return std::sqrt(dot(r, r));
}

/* Conjugate gradients for M x = rhs from x = 0 (owned values), until the
   recurrence's residual is CG_TOL scale.  Returns the iterations, or -1
   if CG_MAX did not reach it; `reached` gets the recurrence's residual over
   scale.  (The diagonal as preconditioner took more iterations on
   disordered tissues, by up to a half.) */

int FixCellSignal::cg(const Field &f, double dt, const double *rhs, double *x, double scale,
                      double &reached)
{
  const int nlocal = atom->nlocal;
  double *r = cg_r.data(), *p = cg_p.data(), *q = cg_q.data();
  for (int i = 0; i < nlocal; i++) {
    x[i] = 0.0;
    p[i] = r[i] = rhs[i];
  }
  const double bb = scale * scale;
  double rr = dot(r, r);
  int it = 0;
  while (rr > CG_TOL * CG_TOL * bb && it < CG_MAX) {
    double local = apply_matrix(f, dt, p, q), pq = 0.0;
    MPI_Allreduce(&local, &pq, 1, MPI_DOUBLE, MPI_SUM, world);
    if (!(pq > 0.0)) break;    // exactly solved (p = 0), or lost to round-off
    const double alpha = rr / pq;
    local = 0.0;
    for (int i = 0; i < nlocal; i++) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      local += r[i] * r[i];
    }
    double rr_new = 0.0;
    MPI_Allreduce(&local, &rr_new, 1, MPI_DOUBLE, MPI_SUM, world);
    for (int i = 0; i < nlocal; i++) p[i] = r[i] + (rr_new / rr) * p[i];
    rr = rr_new;
    it++;
  }
  reached = bb > 0.0 ? std::sqrt(rr / bb) : 0.0;
  return rr <= CG_TOL * CG_TOL * bb ? it : -1;
}

void FixCellSignal::implicit_step(double dt)
{
  comm_vector = comm_vector2 = nullptr;
  tessera_compat::forward_comm(comm, this);
  productions();    // from the values at the start of the step
  const int nlocal = atom->nlocal;
  const size_t nall = std::max(atom->nmax, 1);
  for (std::vector<double> *v : {&cg_x, &cg_xd, &cg_d, &cg_r, &cg_p, &cg_q, &cg_b, &cg_res})
    v->assign(nall, 0.0);
  // Every species' new values are computed (into next) before any changes,
  // so that all read the same start.
  std::vector<double> next(fields.size() * static_cast<size_t>(nlocal), 0.0);
  for (size_t f = 0; f < fields.size(); f++) {
    const Field &fd = fields[f];
    if (!fd.species) continue;
    const double *u = atom->dvector[fd.index];
    const double *prod = &rate[f * nlocal];
    // sums over the cells taken: b, 1 + dt d, b^2; and the largest
    // dt P W_i / (1 + dt d_i)
    double sums[3] = {0.0, 0.0, 0.0}, all[3] = {0.0, 0.0, 0.0}, most = 0.0, most_all = 0.0;
    for (int i = 0; i < nlocal; i++) {
      cg_xd[i] = 0.0;
      if (!taken[i]) {
        cg_b[i] = cg_x[i] = u[i];
        continue;
      }
      double w = 0.0;
      for (int k = row_offset[i]; k < row_offset[i + 1]; k++) w += row_size[k];
      const double own = 1.0 + dt * (fd.k + fd.Pb * freelen[i]);
      cg_b[i] = u[i] + dt * (prod[i] + fd.Pb * freelen[i] * fd.cb);
      sums[0] += cg_b[i];
      sums[1] += own;
      sums[2] += cg_b[i] * cg_b[i];
      most = std::max(most, dt * fd.P * w / own);
    }
    MPI_Allreduce(sums, all, 3, MPI_DOUBLE, MPI_SUM, world);
    MPI_Allreduce(&most, &most_all, 1, MPI_DOUBLE, MPI_MAX, world);
    // The start: the old values, or where exchange is so fast that the
    // solution is nearly uniform, the uniform value that balances the
    // sources of all cells taken (the solution on one patch), so that the
    // solves do not carry the uniform part of the solution, which their
    // round-off would spread over the differences.
    const bool stiff = most_all > STIFF;
    const double start = all[1] > 0.0 ? all[0] / all[1] : 0.0;
    for (int i = 0; i < nlocal; i++)
      if (taken[i]) cg_x[i] = stiff ? start : u[i];
    const double bnorm = std::sqrt(all[2]);
    double *x1 = cg_x.data();
    double reached = 0.0;
    double res = residual(fd, dt, cg_b.data(), cg_x.data(), cg_xd.data(), cg_res.data());
    for (int pass = 0; pass < REFINE_MAX && res > ROUND_OFF * bnorm; pass++) {
      // (each solve to CG_TOL of the right-hand side b: the corrections
      // need no more than the solution itself)
      const int it = cg(fd, dt, cg_res.data(), cg_d.data(), bnorm, reached);
      if (it < 0) {
        if (pass == 0)
          error->all(FLERR,
                     "fix cell/signal {}: the implicit step of d_{} did not converge at step {} "
                     "(relative residual {} after {} iterations); use explicit substeps",
                     id, fd.name, update->ntimestep, reached, CG_MAX);
        break;
      }
      // x1 + xd + d as x1 + xd again: x1 takes the rounded sum, xd its
      // rounding error (Knuth's two-sum, exact), so that the part of d
      // below x1's last bit is not lost.
      cg_keep.assign(cg_x.begin(), cg_x.begin() + nlocal);
      cg_keep.insert(cg_keep.end(), cg_xd.begin(), cg_xd.begin() + nlocal);
      for (int i = 0; i < nlocal; i++) {
        const double sum = x1[i] + cg_d[i];
        const double back = sum - x1[i];
        cg_xd[i] += (x1[i] - (sum - back)) + (cg_d[i] - back);
        x1[i] = sum;
      }
      const double before = res;
      res = residual(fd, dt, cg_b.data(), cg_x.data(), cg_xd.data(), cg_res.data());
      if (!(res < before)) {
        std::copy(cg_keep.begin(), cg_keep.begin() + nlocal, cg_x.begin());
        std::copy(cg_keep.begin() + nlocal, cg_keep.end(), cg_xd.begin());
        forward_vectors(cg_x.data(), cg_xd.data());
        res = before;
        break;
      }
      if (!(res < 0.5 * before)) break;
    }
    if (res > REFINED_TOL * bnorm) inaccurate(fd, dt, res / bnorm);
    // The new amounts from the fluxes of the solution (ghosts of x1 and xd
    // are current: residual() sent them).
    double *out = &next[f * nlocal];
    for (int i = 0; i < nlocal; i++) {
      out[i] = u[i];
      if (!taken[i]) continue;
      const double e = dt * fd.P * exchange_of(i, cg_x.data(), cg_xd.data());
      out[i] = (u[i] + dt * (prod[i] + fd.Pb * freelen[i] * fd.cb) + e) /
          (1.0 + dt * (fd.k + fd.Pb * freelen[i]));
      if (!(out[i] >= 0.0) || !std::isfinite(out[i]))
        fail(f, i, out[i],
             fmt::format("the implicit step gives a negative value (round-off of a step "
                         "dt P = {} times the exchange time per unit junction); use a shorter "
                         "step or explicit substeps",
                         dt * fd.P),
             nullptr, 1);
    }
  }
  for (size_t f = 0; f < fields.size(); f++) {
    if (!fields[f].species) continue;
    double *u = atom->dvector[fields[f].index];
    const double *out = &next[f * nlocal];
    for (int i = 0; i < nlocal; i++)
      if (taken[i]) u[i] = out[i];
  }
}

/* The refined solution's residual stays above REFINED_TOL: a warning
   (once per run and species), or above FAILED_TOL an error.  This happens
   when the step is so many exchange times long that the differences the
   fluxes need fall below double precision: beyond dt P s_ij of about 1e16
   when the cells taken form several unconnected patches (far beyond on
   one patch, whose uniform part the solver's start takes out). */

void FixCellSignal::inaccurate(const Field &f, double dt, double rel)
{
  const std::string what = fmt::format(
      "fix cell/signal {}: the implicit step of d_{} at step {} leaves a relative residual "
      "{:.3g}: the new values are that far from the backward-Euler solution, the limit of "
      "double precision for a step dt P = {:.3g} times the exchange time per unit junction "
      "size; use a shorter step, or explicit substeps",
      id, f.name, update->ntimestep, rel, dt * f.P);
  if (rel > FAILED_TOL) error->all(FLERR, what);
  const size_t index = &f - fields.data();
  if (warned_implicit.size() < fields.size()) warned_implicit.assign(fields.size(), 0);
  if (warned_implicit[index]) return;
  warned_implicit[index] = 1;
  if (comm->me == 0) error->warning(FLERR, what + " (said once per run)");
}
