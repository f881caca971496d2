# SPDX-License-Identifier: GPL-2.0-or-later
"""Measurements on runs, as numbers (the plots of :mod:`tessera_tools.plots` draw them).

* :func:`demix_series`: heterotypic junction fraction of every frame that a
  per-atom dump (with ``type``) and a dump local of ``compute vertex/local``
  both hold;
* :func:`exponential_fit`: N(t) = N0 exp(r t) fitted to ln N by least squares,
  with the doubling time ln 2 / r and standard errors;
* :func:`half_time`: when a decreasing series (a wound's area) first reaches
  half its initial value;
* :func:`shape_samples`: shape index and neighbour number of the cells of
  frames, interior and rim apart;
* :func:`frame_series`: a per-frame value of a dump (sum or mean of a column,
  cell count, open area of finite cells) against time.
"""

import math

import numpy as np

from .dump import iter_dump


def demix_series(atoms_path, local_path, compute=None, column="type", cell_types=None):
    """For each timestep both dumps hold: (timesteps, times or None, heterotypic fraction,
    heterotypic length, total length).  The fraction is the junction length between cells of
    different ``column`` values over the total junction length (each junction counted once).
    ``cell_types``: as for :func:`tessera_tools.junctions.paired_frames`."""
    from .junctions import contact_lengths, paired_frames

    steps, times, frac, het, tot = [], [], [], [], []
    for atoms, local in paired_frames(atoms_path, local_path, cell_types=cell_types):
        if column not in atoms:
            raise KeyError(f"{atoms_path} has no '{column}' column: dump the cell type, e.g. "
                           "'dump ... custom N cells.dump id type x y'")
        c = contact_lengths(atoms, local, compute, column)
        total = sum(c.values())
        hetero = sum(v for (a, b), v in c.items() if a != b)
        steps.append(atoms.timestep)
        times.append(atoms.time)
        het.append(hetero)
        tot.append(total)
        frac.append(hetero / total if total else float("nan"))
    has_time = all(t is not None for t in times)
    return (np.array(steps), np.array(times, dtype=float) if has_time else None, np.array(frac),
            np.array(het), np.array(tot))


def exponential_fit(t, n, tmin=None, tmax=None, cap=None):
    """Least-squares fit of ln N = ln N0 + r t over tmin <= t <= tmax (default: from the start to
    the first time N reaches its maximum, or to the point before a plateau at the maximum) and
    N < cap (the 'max' of fix cell/divide: a sample at the cap is usually capped).  Returns a dict with
    rate, rate_err, N0, doubling = ln 2 / rate, doubling_err, and the fitted range; the errors
    are the standard errors of the slope from the scatter about the line (the points of one run
    are correlated in time, so they are a lower bound on the run-to-run spread)."""
    t = np.asarray(t, dtype=float)
    n = np.asarray(n, dtype=float)
    if tmax is None:
        top = int(np.argmax(n))
        # a plateau at the maximum (the 'max' cap of fix cell/divide) is not growth: stop before it
        tmax = t[top] if np.sum(n == n[top]) == 1 else t[max(top - 1, 0)]
    if tmin is None:
        tmin = t[0]
    sel = (t >= tmin) & (t <= tmax) & (n > 0)
    if cap is not None:
        sel &= n < cap
    if sel.sum() < 3:
        raise ValueError(f"need at least 3 points with N > 0 between t = {tmin:g} and {tmax:g} for a fit "
                         f"with an error, got {int(sel.sum())}: widen the range (--tmin/--tmax)")
    x, y = t[sel], np.log(n[sel])
    (rate, ln_n0), cov = np.polyfit(x, y, 1, cov="unscaled")
    resid = y - (rate * x + ln_n0)
    s2 = resid @ resid / max(1, len(x) - 2)
    rate_err = float(math.sqrt(cov[0, 0] * s2))
    out = dict(rate=float(rate), rate_err=rate_err, N0=float(math.exp(ln_n0)), tmin=float(x[0]),
               tmax=float(x[-1]), points=int(sel.sum()))
    if rate > 0:
        out["doubling"] = math.log(2) / rate
        out["doubling_err"] = math.log(2) * rate_err / rate ** 2
    else:
        out["doubling"] = out["doubling_err"] = float("nan")
    return out


def half_time(t, y, fraction=0.5):
    """First time at which y falls to ``fraction`` of its first value (linear interpolation
    between the two samples around it); NaN if it never does."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    target = fraction * y[0]
    below = np.nonzero(y <= target)[0]
    if len(below) == 0:
        return float("nan")
    k = below[0]
    if k == 0:
        return float(t[0])
    t0, t1, y0, y1 = t[k - 1], t[k], y[k - 1], y[k]
    return float(t0 + (target - y0) * (t1 - t0) / (y1 - y0)) if y1 != y0 else float(t1)


def frame_time(frame, dt):
    """The frame's time: the dump's TIME item, else timestep x dt, else the timestep."""
    if frame.time is not None:
        return frame.time
    return frame.timestep * dt if dt else float(frame.timestep)


def frame_series(path, value, dt=None, radius=None, cell_types=None):
    """(timesteps, times, values) of a per-frame value of a dump.

    value: 'count' (cells in the frame), 'open' (box area minus the area of the finite Voronoi
    cells of radius ``radius``: holes and wounds), 'holes' (the total area of the holes of those
    cells, compute vertex/loops' value 2 with min_area 0, in any box), 'largest' (the largest
    hole, its value 5), 'sum:COL' or 'mean:COL' (a per-atom column over the cells).  ``cell_types`` (see :func:`tessera_tools.dump.iter_dump`): the atoms of
    other types are no cells: they cover no area (as for compute vertex/loops, whose total
    hole area is the open area of a periodic box) and are not counted."""
    steps, times, vals = [], [], []
    kind, _, col = value.partition(":")
    if kind not in ("count", "open", "holes", "largest", "sum", "mean") or (kind in ("sum", "mean") and not col):
        raise ValueError(f"per-frame value '{value}': use count, open, holes or largest (these need --radius), "
                         "sum:COLUMN or mean:COLUMN, e.g. sum:c_cell[8]")
    if kind in ("open", "holes", "largest") and not radius:
        raise ValueError(f"per-frame value '{kind}' (of the finite cells) needs --radius R, the "
                         "radius of pair_style vertex/voronoi ... radius R")
    for frame in iter_dump(path, cell_types):
        steps.append(frame.timestep)
        times.append(frame_time(frame, dt))
        if kind == "count":
            vals.append(float(frame.natoms))
        elif kind in ("open", "holes", "largest"):
            from .finite import finite_voronoi

            if frame.natoms == 0:
                vals.append(frame.box.area if kind == "open" else 0.0)
                continue
            tess = finite_voronoi(frame.positions(), frame.box, radius, frame.ids)
            if kind == "open":
                vals.append(frame.box.area - float(tess.area.sum()))
            else:
                from .holes import free_loops

                holes = [lp.area for lp in free_loops(tess) if lp.kind == 0]
                vals.append(float(sum(holes)) if kind == "holes" else float(max(holes, default=0.0)))
        else:
            v = np.asarray(frame[col], dtype=float)
            vals.append(float(v.sum() if kind == "sum" else v.mean()))
    if not steps:
        raise ValueError(f"{path}: no frames")
    return np.array(steps), np.array(times), np.array(vals)


def shape_samples(frames, q_column=None, z_column=None, edge_column=None, radius=None):
    """Shape index q and neighbour number z of every cell of ``frames`` (pooled) and whether it
    is at the rim (has a free edge).  From dump columns when named (e.g. c_cell[3], c_cell[4],
    c_cell[9] of compute vertex/atom), else from the Voronoi tessellation of each frame (finite
    cells of ``radius`` when given: a cell with a free arc is at the rim).  Returns q, z, rim
    (bool; all False for a confluent periodic tissue without an edge column)."""
    qs, zs, rims = [], [], []
    for frame in frames:
        tess = None
        if q_column is None or z_column is None or (edge_column is None and radius):
            if radius:
                from .finite import finite_voronoi

                tess = finite_voronoi(frame.positions(), frame.box, radius, frame.ids)
            else:
                from .voronoi import tessellate_frame

                tess = tessellate_frame(frame)
        q = np.asarray(frame[q_column], dtype=float) if q_column else tess.shape_index
        z = np.asarray(frame[z_column], dtype=float) if z_column else tess.sides.astype(float)
        if edge_column:
            rim = np.asarray(frame[edge_column], dtype=float) > 0.5
        elif radius:
            rim = tess.free_length > 1e-12
        else:
            rim = np.zeros(len(q), dtype=bool)
        qs.append(q)
        zs.append(z)
        rims.append(rim)
    return np.concatenate(qs), np.concatenate(zs), np.concatenate(rims)
