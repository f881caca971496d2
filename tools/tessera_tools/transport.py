# SPDX-License-Identifier: GPL-2.0-or-later
"""How atoms of any type move: flux through sections, the velocity field, drift and MSD.

All three read a :class:`~tessera_tools.trajectories.Trajectory` of the atoms of the chosen
types (cells, beads, a colloid: :func:`load_atoms`), matched by atom ID across frames and
unwrapped (``xu yu``, or image flags, else by continuity).  Atoms may appear and disappear
(division, death, deposition, atoms leaving an open box): every quantity between two frames
uses the atoms present in both.

* :func:`section_flux`: net crossings per unit time of the lines x = c (or y = c), in the +x
  (+y) direction.  In a periodic direction a section is the family of lines c + m L: an atom
  that moves once around the box crosses it once.  The error is the standard error over
  ``blocks`` equal stretches of the record.
* :func:`velocity_field`: displacement between consecutive frames over their time difference,
  binned by the position at the earlier frame (fractional coordinates of that frame's box)
  and averaged over all atoms and frame pairs; the error is the standard error of the samples
  of a bin.
* :func:`msd`: mean-squared displacement against lag time over all time origins, with and
  without the drift; the drift is the constant velocity V = (sum of displacements) / (sum of
  the time the atoms were followed), and the drift-free MSD is that of d - V tau.  The error
  bars come from the non-overlapping intervals of each lag (independent for a random walk).
"""

import math

import numpy as np

from .trajectories import load_trajectory


def load_atoms(path, types, frames=slice(None)):
    """A Trajectory of the atoms of ``types`` (from dump.parse_types; a OneType for every
    atom of a one-type dump) over the frames of the slice; ``times`` from the dump's TIME,
    else None.  No velocities are read."""
    sl = frames if frames is not None else slice(None)
    if any(v is not None and v < 0 for v in (sl.start, sl.stop, sl.step)):
        raise ValueError("--frames takes non-negative start:stop:step here")
    return load_trajectory(path, sl.start, sl.stop, sl.step, velocity=None, cell_types=types, quiet=True)


def frame_times(traj, dt=None):
    """(times, known): the dump's TIME of each frame, else timestep x dt, else the timesteps
    (known False)."""
    if traj.times is not None:
        return traj.times, True
    if dt:
        return traj.timesteps * float(dt), True
    return traj.timesteps.astype(float), False


def _crossings(u0, u1, c, period):
    """Net crossings of the section(s) at c by steps from u0 to u1 (arrays), in the + direction;
    with a period the section repeats every period."""
    if period:
        return np.floor((u1 - c) / period) - np.floor((u0 - c) / period)
    return (u1 >= c).astype(float) - (u0 >= c).astype(float)


def section_flux(traj, times, axis, sections, blocks=10):
    """Flux of the trajectory's atoms through each section (a list of positions along ``axis``,
    'x' or 'y').  Returns a dict: sections, net (total net crossings), plus / minus (crossings
    each way), duration (the time the record spans), flux (net / duration), flux_err (standard
    error over ``blocks`` stretches of the record; NaN with fewer than 2), length (of a section
    across the box, from the first frame), cumulative ((F, S) net crossings up to each frame)."""
    k = {"x": 0, "y": 1}[axis]
    F = len(traj)
    if F < 2:
        raise ValueError("the flux needs at least two frames")
    sections = np.atleast_1d(np.asarray(sections, dtype=float))
    box0 = traj.boxes[0]
    for b in traj.boxes:
        if axis == "x" and b.xy != 0.0 and b.periodic[1]:
            raise ValueError("sections x = const in a box tilted in xy: the periodic images along y shift "
                             "them by xy, so they are no family of parallel sections; use sections y = "
                             "const, or an orthogonal box")
    per_step = np.zeros((F - 1, len(sections)))
    plus = np.zeros(len(sections))
    minus = np.zeros(len(sections))
    for f in range(F - 1):
        both = traj.present[f] & traj.present[f + 1]
        if not both.any():
            continue
        u0 = traj.positions[f, both, k]
        u1 = traj.positions[f + 1, both, k]
        box = traj.boxes[f]
        period = (box.lx if k == 0 else box.ly) if box.periodic[k] else None
        for s, c in enumerate(sections):
            n = _crossings(u0, u1, c, period)
            per_step[f, s] = n.sum()
            plus[s] += n[n > 0].sum()
            minus[s] -= n[n < 0].sum()
    dts = np.diff(np.asarray(times, dtype=float))
    if np.any(dts <= 0):
        raise ValueError("the frames' times do not increase")
    duration = float(dts.sum())
    net = per_step.sum(axis=0)
    flux = net / duration
    err = np.full(len(sections), np.nan)
    nb = min(int(blocks), F - 1)
    if nb >= 2:
        parts = np.array_split(np.arange(F - 1), nb)
        values = np.array([per_step[p].sum(axis=0) / dts[p].sum() for p in parts])
        err = values.std(axis=0, ddof=1) / math.sqrt(nb)
    length = box0.ly if k == 0 else box0.lx
    cumulative = np.vstack([np.zeros(len(sections)), np.cumsum(per_step, axis=0)])
    return dict(sections=sections, net=net, plus=plus, minus=minus, duration=duration, flux=flux,
                flux_err=err, length=length, blocks=nb, cumulative=cumulative, axis=axis)


def velocity_field(traj, times, bins=(10, 10)):
    """The time-averaged velocity field: for every pair of consecutive frames and every atom in
    both, v = (r1 - r0) / (t1 - t0) in the bin of its position at the earlier frame (bins of
    equal fractional size of that frame's box).  Returns a dict: centres (ny, nx, 2, in the
    first frame's box), vx, vy (means; NaN where a bin has no sample), vx_err, vy_err
    (standard errors of the samples; NaN below 2), count (samples per bin), mean (the mean
    velocity over all samples)."""
    nx, ny = int(bins[0]), int(bins[1])
    if nx < 1 or ny < 1:
        raise ValueError(f"bins must be >= 1, got {nx} x {ny}")
    F = len(traj)
    if F < 2:
        raise ValueError("the velocity field needs at least two frames")
    s1 = np.zeros((ny, nx, 2))
    s2 = np.zeros((ny, nx, 2))
    count = np.zeros((ny, nx))
    total, nall = np.zeros(2), 0
    for f in range(F - 1):
        both = traj.present[f] & traj.present[f + 1]
        if not both.any():
            continue
        dt = float(times[f + 1] - times[f])
        if not dt > 0:
            raise ValueError("the frames' times do not increase")
        v = (traj.positions[f + 1, both] - traj.positions[f, both]) / dt
        frac = traj.boxes[f].to_fractional(traj.wrapped[f, both])
        frac = frac - np.floor(frac) * np.array([traj.boxes[f].periodic[0], traj.boxes[f].periodic[1]])
        ix = np.clip(np.floor(frac[:, 0] * nx).astype(int), 0, nx - 1)
        iy = np.clip(np.floor(frac[:, 1] * ny).astype(int), 0, ny - 1)
        np.add.at(count, (iy, ix), 1.0)
        np.add.at(s1, (iy, ix), v)
        np.add.at(s2, (iy, ix), v * v)
        total += v.sum(axis=0)
        nall += len(v)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = s1 / count[..., None]
        var = (s2 - count[..., None] * mean ** 2) / (count[..., None] - 1)
        err = np.sqrt(np.maximum(var, 0.0) / count[..., None])
    err[count < 2] = np.nan
    fx = (np.arange(nx) + 0.5) / nx
    fy = (np.arange(ny) + 0.5) / ny
    grid = np.stack(np.meshgrid(fx, fy), axis=-1).reshape(-1, 2)
    centres = traj.boxes[0].to_cartesian(grid).reshape(ny, nx, 2)
    return dict(centres=centres, vx=mean[..., 0], vy=mean[..., 1], vx_err=err[..., 0], vy_err=err[..., 1],
                count=count, mean=total / max(nall, 1), samples=nall, bins=(nx, ny))


def msd(traj, times, max_lag=None):
    """Mean-squared displacement against lag time, with and without the drift.

    Returns a dict: lag (frames), tau, count (pairs of frames x atoms per lag), msd, msd_err,
    msd_nodrift, msd_nodrift_err, mean (the mean displacement per lag, (K, 2)), drift (the
    velocity V, (2,)), drift_err (its standard error from the increments between frames,
    independent for a random walk), followed (total time the atoms were followed).  The frames
    must be equally spaced in time."""
    F = len(traj)
    if F < 2:
        raise ValueError("the MSD needs at least two frames")
    t = np.asarray(times, dtype=float)
    steps = np.diff(t)
    if not np.all(steps > 0) or not np.allclose(steps, steps[0], rtol=1e-6, atol=0.0):
        raise ValueError("the MSD over time origins needs frames equally spaced in time; select them "
                         "with --frames (e.g. '100::2')")
    step = float(steps[0])
    K = F - 1 if max_lag is None else max(1, min(int(max_lag), F - 1))
    pos, present = traj.positions, traj.present
    # the drift: the sum of all increments over the time they took
    inc = []
    for f in range(F - 1):
        both = present[f] & present[f + 1]
        inc.append(pos[f + 1, both] - pos[f, both])
    inc = np.vstack(inc) if inc else np.zeros((0, 2))
    if len(inc) == 0:
        raise ValueError("no atom is present in two consecutive frames")
    followed = len(inc) * step
    drift = inc.sum(axis=0) / followed
    drift_err = (inc.std(axis=0, ddof=1) * math.sqrt(len(inc)) / followed if len(inc) > 1
                 else np.full(2, np.nan))
    out = dict(lag=np.arange(1, K + 1), tau=step * np.arange(1, K + 1), count=np.zeros(K, dtype=int),
               msd=np.full(K, np.nan), msd_err=np.full(K, np.nan), msd_nodrift=np.full(K, np.nan),
               msd_nodrift_err=np.full(K, np.nan), mean=np.full((K, 2), np.nan), drift=drift,
               drift_err=drift_err, followed=followed, step=step)
    for k in range(1, K + 1):
        both = present[:-k] & present[k:]
        d = (pos[k:] - pos[:-k])[both]                   # (pairs, 2)
        if len(d) == 0:
            continue
        tau = step * k
        d2 = np.sum(d ** 2, axis=1)
        dn2 = np.sum((d - drift * tau) ** 2, axis=1)
        out["count"][k - 1] = len(d)
        out["msd"][k - 1] = d2.mean()
        out["msd_nodrift"][k - 1] = dn2.mean()
        out["mean"][k - 1] = d.mean(axis=0)
        # non-overlapping intervals: origins 0, k, 2k, ...
        origins = np.arange(0, F - k, k)
        sel = both[origins]
        dd = (pos[origins + k] - pos[origins])[sel]
        if len(dd) >= 2:
            a = np.sum(dd ** 2, axis=1)
            b = np.sum((dd - drift * tau) ** 2, axis=1)
            out["msd_err"][k - 1] = a.std(ddof=1) / math.sqrt(len(a))
            out["msd_nodrift_err"][k - 1] = b.std(ddof=1) / math.sqrt(len(b))
    return out


def diffusion_fit(tau, values, tmax=None, dimension=2):
    """D from the least-squares line MSD = 2 d D tau + c over tau <= tmax (default: the first
    quarter of the lags, at least 3): dict D, D_err (standard error of the slope from the
    scatter about the line, / 2d), intercept, tmax, points."""
    tau = np.asarray(tau, dtype=float)
    values = np.asarray(values, dtype=float)
    ok = np.isfinite(values)
    if tmax is None:
        n = max(3, len(tau) // 4)
        tmax = tau[min(n, len(tau)) - 1]
    sel = ok & (tau <= tmax)
    if sel.sum() < 3:
        raise ValueError(f"need at least 3 lags up to tau = {tmax:g} for a fit with an error, got {int(sel.sum())}")
    (slope, c), cov = np.polyfit(tau[sel], values[sel], 1, cov="unscaled")
    resid = values[sel] - (slope * tau[sel] + c)
    s2 = resid @ resid / max(1, sel.sum() - 2)
    err = math.sqrt(cov[0, 0] * s2)
    return dict(D=slope / (2 * dimension), D_err=err / (2 * dimension), intercept=c, tmax=float(tmax),
                points=int(sel.sum()))
