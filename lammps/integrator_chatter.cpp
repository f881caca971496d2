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

   Period-two oscillation of an explicit overdamped integrator (see
   integrator_chatter.h).
------------------------------------------------------------------------- */

#include "integrator_chatter.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "pair.h"
#include "hybrid_access.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

/* For a mode of stiffness lambda (force -lambda x), forward Euler
   multiplies the displacement by m = 1 - dt lambda / gamma_t per step: for
   dt lambda / gamma_t > 1 successive displacements are anti-parallel, and
   past 2 (|m| > 1) they no longer die out (Heun: m = 1 - z + z^2/2 with
   z = dt lambda / gamma_t, negative only for complex z, i.e. forces that
   also turn).  Where the force jumps (a kink of the energy that the flow
   pushes into from both sides), every explicit step crosses it and the
   next one comes back, at any dt.  The sums are over the fix's group and
   weighted by the displacements' lengths, so a few chattering cells with
   large moves show even when most cells move smoothly. */

void IntegratorChatter::begin(int groupbit)
{
  start(groupbit);
  double **v = atom->v;
  const int *mask = atom->mask;
  nbefore = atom->nlocal;
  before.resize(3 * static_cast<size_t>(nbefore));
  for (int i = 0; i < nbefore; i++)
    for (int d = 0; d < 3; d++) before[3 * i + d] = (mask[i] & groupbit) ? v[i][d] : 0.0;
}

void IntegratorChatter::end(const char *style, const char *id, int groupbit, double dt)
{
  double **v = atom->v;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int ndim = domain->dimension;
  // Atoms exchanged within the step (a pair style that widened its ghost
  // shell) have other indices: nothing to compare on this step.
  int same = nlocal == nbefore ? 1 : 0, all_same;
  MPI_Allreduce(&same, &all_same, 1, MPI_INT, MPI_MIN, world);
  nbefore = -1;
  if (!all_same) return;
  double sums[NSUMS] = {0.0, 0.0, 0.0, 0.0};
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) add(sums, &before[3 * static_cast<size_t>(i)], v[i], ndim);
  observe(style, id, sums, dt);
}

void IntegratorChatter::observe(const char *style, const char *id, const double *sums, double dt)
{
  const int ndim = domain->dimension;
  double all[NSUMS];
  MPI_Allreduce(sums, all, NSUMS, MPI_DOUBLE, MPI_SUM, world);
  const double norm = std::sqrt(all[OLD2] * all[NEW2]);
  corr = norm > 0.0 && std::isfinite(norm) ? all[DOT] / norm : 0.0;
  const double size = dt * dt * all[NEW2];
  // Moves at the round-off of the positions (a converged state) may flip
  // from step to step: they are no chatter.
  double length = std::max(domain->xprd, domain->yprd);
  if (ndim == 3) length = std::max(length, domain->zprd);
  const bool resolved = all[COUNT] > 0.0 && std::sqrt(size / all[COUNT]) > FLOOR * length;
  if (!resolved) {
    corrs.clear();
    sizes.clear();
    return;
  }
  corrs.push_back(corr);
  sizes.push_back(size);
  if (static_cast<int>(corrs.size()) > STEPS) {
    corrs.erase(corrs.begin());
    sizes.erase(sizes.begin());
  }
  if (warned || probing || static_cast<int>(corrs.size()) < STEPS) return;
  double mean = 0.0;
  for (double c : corrs) mean += c / STEPS;
  // Squared displacements of the first and the last tenth of the window.
  const int tenth = STEPS / 10;
  double first = 0.0, last = 0.0;
  for (int k = 0; k < tenth; k++) {
    first += sizes[k];
    last += sizes[STEPS - 1 - k];
  }
  if (!(mean < ANTI) || !(last >= DECAY * first)) return;
  // The oscillation is found: the next steps' start() record it.
  probing = 1;
  fix_style = style;
  fix_id = id;
  first_step = update->ntimestep - STEPS + 1;
  last_step = update->ntimestep;
  mean_corr = mean;
  probe_dt = dt;
  records.clear();
}

void IntegratorChatter::start(int groupbit)
{
  if (!probing) return;
  record_state(groupbit);
  if (++probing > PROBE) {
    warned = report();
    records.clear();
    probing = 0;
    if (!warned) {
      corrs.clear();
      sizes.clear();
    }
  }
}

/* The force on each local atom from each term: every pair sub-style alone
   (or the pair style), then the rest (fixes, bonds: the total less the
   pair styles'), nterms x 3 per atom.  The force array is restored. */

void IntegratorChatter::term_forces(std::vector<double> &forces)
{
  std::vector<Pair *> pairs;
  terms.clear();
  if (force->pair) {
    auto *hybrid = dynamic_cast<PairHybrid *>(force->pair);
    if (hybrid) {
      for (int m = 0; m < HybridAccess::count(hybrid); m++) {
        pairs.push_back(HybridAccess::style(hybrid, m));
        terms.emplace_back(std::string("pair ") + HybridAccess::keyword(hybrid, m));
      }
    } else {
      pairs.push_back(force->pair);
      terms.emplace_back(std::string("pair ") + force->pair_style);
    }
  }
  terms.emplace_back("fixes and bonds");    // the total less the pair styles'
  const int nterms = static_cast<int>(terms.size());
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  double **f = atom->f;
  forces.assign(static_cast<size_t>(nlocal) * nterms * 3, 0.0);
  std::vector<double> keep(3 * static_cast<size_t>(nall)), keep_torque;
  if (nall > 0) std::memcpy(keep.data(), &f[0][0], sizeof(double) * 3 * nall);
  if (atom->torque_flag) {
    keep_torque.resize(3 * static_cast<size_t>(nall));
    if (nall > 0) std::memcpy(keep_torque.data(), &atom->torque[0][0], sizeof(double) * 3 * nall);
  }
  for (int i = 0; i < nlocal; i++)
    for (int d = 0; d < 3; d++) forces[(i * nterms + nterms - 1) * 3 + d] = f[i][d];
  for (size_t m = 0; m < pairs.size(); m++) {
    if (nall > 0) std::memset(&f[0][0], 0, sizeof(double) * 3 * nall);
    if (atom->torque_flag && nall > 0)
      std::memset(&atom->torque[0][0], 0, sizeof(double) * 3 * nall);
    pairs[m]->compute(0, 0);
    if (force->newton_pair) comm->reverse_comm();
    for (int i = 0; i < nlocal; i++)
      for (int d = 0; d < 3; d++) {
        forces[(i * nterms + m) * 3 + d] = f[i][d];
        forces[(i * nterms + nterms - 1) * 3 + d] -= f[i][d];
      }
  }
  if (nall > 0) std::memcpy(&f[0][0], keep.data(), sizeof(double) * 3 * nall);
  if (atom->torque_flag && nall > 0)
    std::memcpy(&atom->torque[0][0], keep_torque.data(), sizeof(double) * 3 * nall);
}

void IntegratorChatter::record_state(int groupbit)
{
  std::vector<double> forces;
  term_forces(forces);
  const int nterms = static_cast<int>(terms.size());
  double **x = atom->x;
  const imageint *image = atom->image;
  const tagint *tag = atom->tag;
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    auto &r = records[tag[i]];
    double xu[3];
    domain->unmap(x[i], image[i], xu);
    r.insert(r.end(), xu, xu + 3);
    r.insert(r.end(), &forces[i * nterms * 3], &forces[(i + 1) * nterms * 3]);
  }
}

/* From the PROBE recorded states: per atom, how much successive moves
   reverse (-mean d_t . d_t+1), the mean move, and per term the amplitude
   of the force's alternating part |sum_t (-1)^t F(t)| / PROBE; the atoms
   that reverse most on all ranks, and the terms' shares on them. */

bool IntegratorChatter::report()
{
  const int nterms = static_cast<int>(terms.size());
  const int rec = 3 + 3 * nterms;
  const int width = 6 + nterms;    // tag, reversal, move, x, y, z, alternating force per term
  std::vector<double> mine;
  double stats[3] = {0.0, 0.0, 0.0};    // moves summed, atoms, atoms reversing at every step
  for (const auto &kv : records) {
    const std::vector<double> &r = kv.second;
    if (static_cast<int>(r.size()) != PROBE * rec) continue;    // joined or left during the probe
    double d[PROBE - 1][3], move = 0.0;
    for (int t = 0; t + 1 < PROBE; t++) {
      double s = 0.0;
      for (int k = 0; k < 3; k++) {
        d[t][k] = r[(t + 1) * rec + k] - r[t * rec + k];
        s += d[t][k] * d[t][k];
      }
      move += std::sqrt(s) / (PROBE - 1);
    }
    double reversal = 0.0;
    int every = 1;
    for (int t = 0; t + 2 < PROBE; t++) {
      const double dot = d[t][0] * d[t + 1][0] + d[t][1] * d[t + 1][1] + d[t][2] * d[t + 1][2];
      reversal -= dot / (PROBE - 2);
      if (!(dot < 0.0)) every = 0;
    }
    stats[0] += move;
    stats[1] += 1.0;
    stats[2] += every;
    std::vector<double> row = {static_cast<double>(kv.first), reversal, move};
    double xw[3] = {r[(PROBE - 1) * rec], r[(PROBE - 1) * rec + 1], r[(PROBE - 1) * rec + 2]};
    imageint im = (static_cast<imageint>(IMGMAX) << IMG2BITS) |
        (static_cast<imageint>(IMGMAX) << IMGBITS) | IMGMAX;
    domain->remap(xw, im);
    row.insert(row.end(), xw, xw + 3);
    for (int m = 0; m < nterms; m++) {
      double a[3] = {0.0, 0.0, 0.0};
      for (int t = 0; t < PROBE; t++)
        for (int k = 0; k < 3; k++) a[k] += ((t % 2) ? -1.0 : 1.0) * r[t * rec + 3 + 3 * m + k];
      row.push_back(std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) / PROBE);
    }
    mine.insert(mine.end(), row.begin(), row.end());
  }
  // This rank's NAMED atoms that reverse most (padded), to rank 0.
  const int nrows = static_cast<int>(mine.size()) / width;
  std::vector<int> order(nrows);
  for (int k = 0; k < nrows; k++) order[k] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return mine[a * width + 1] > mine[b * width + 1];
  });
  std::vector<double> top(static_cast<size_t>(NAMED) * width, 0.0);
  for (int k = 0; k < NAMED; k++) {
    if (k < nrows)
      std::copy(&mine[order[k] * width], &mine[(order[k] + 1) * width], &top[k * width]);
    else
      top[k * width + 1] = -INFINITY;
  }
  double gstats[3];
  MPI_Allreduce(stats, gstats, 3, MPI_DOUBLE, MPI_SUM, world);
  std::vector<double> gathered;
  if (comm->me == 0) gathered.resize(top.size() * comm->nprocs);
  MPI_Gather(top.data(), static_cast<int>(top.size()), MPI_DOUBLE, gathered.data(),
             static_cast<int>(top.size()), MPI_DOUBLE, 0, world);
  // Noise alone can make successive moves anti-parallel on average for a
  // while; an oscillation that no atom keeps up over the probe is none:
  // watch again.
  if (gstats[2] < 1.0) return false;
  if (comm->me != 0) return true;

  const int ng = static_cast<int>(gathered.size()) / width;
  std::vector<int> g(ng);
  for (int k = 0; k < ng; k++) g[k] = k;
  std::sort(g.begin(), g.end(), [&](int a, int b) {
    const double ra = gathered[a * width + 1], rb = gathered[b * width + 1];
    if (ra != rb) return ra > rb;
    return gathered[a * width] < gathered[b * width];
  });
  const double mean_move = gstats[1] > 0.0 ? gstats[0] / gstats[1] : 0.0;
  const int ndim = domain->dimension;
  std::string atoms;
  std::vector<double> share(nterms, 0.0);
  int named = 0;
  for (int k = 0; k < ng && named < NAMED; k++) {
    const double *row = &gathered[g[k] * width];
    if (!(row[1] > 0.0)) break;
    atoms += fmt::format("{}{} at ({:.3g}, {:.3g}{}) moving {:.2g} per step", named ? "; " : "",
                         static_cast<tagint>(row[0]), row[3], row[4],
                         ndim == 3 ? fmt::format(", {:.3g}", row[5]) : std::string(), row[2]);
    for (int m = 0; m < nterms; m++) share[m] += row[6 + m];
    named++;
  }
  double total = 0.0;
  for (double s : share) total += s;
  int main_term = 0;
  for (int m = 1; m < nterms; m++)
    if (share[m] > share[main_term]) main_term = m;
  std::string shares;
  for (int m = 0; m < nterms; m++)
    shares += fmt::format("{}{} {:.0f} %", m ? ", " : "", terms[m],
                          total > 0.0 ? 100.0 * share[m] / total : 0.0);
  std::string who = named
      ? fmt::format("The atoms that alternate most (of {} that reverse their move at "
                    "every one of steps {} to {}; mean move of the group {:.2g}): {}.  "
                    "The force that alternates on them is from {} (shares of the "
                    "alternating force: {}).  ",
                    static_cast<bigint>(gstats[2]), update->ntimestep - PROBE + 1,
                    update->ntimestep, mean_move, atoms, terms[main_term], shares)
      : std::string();
  error->warning(
      FLERR,
      "fix {} {}: the displacements have reversed direction from step to step over steps {} to "
      "{} (mean correlation of successive displacements {:.2f}) without dying out: the "
      "integrator oscillates about the state instead of following it.  {}This happens where a "
      "force is stiffer than 2 gamma_t / dt (here dt = {}) or changes abruptly (cells "
      "co-circular around a particle or a short junction: a kink of the energy), and then a "
      "smaller fixed timestep shrinks the oscillation but need not remove it.  Positions there "
      "are off by about the move per step, and time averages (fluxes, velocities, shapes near "
      "these atoms) can depend on dt: check them at dt, dt/2 and dt/4 ('tessera-tools "
      "converge'), or use 'fix brownian/heun ... adapt tol T', which bounds the error of every "
      "step by T{} (reported once)",
      fix_id, fix_style, first_step, last_step, mean_corr, who, probe_dt, context);
  return true;
}
