#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Microrheology of examples/spheroid_beads: the mean-squared displacement
of the beads and of the cells against the lag time in the solid and the
fluid tissue (msd.dat, figures/spheroid_beads.png), and a section of each
tissue through its middle plane z = Lz/2 with the beads' paths.

The MSD is averaged over every time origin of the dump (one frame per unit
of time) and over the atoms of each kind, with the displacement measured
against the cells' centre of mass (the tissue's own frame: the whole box
drifts by a random walk of diffusion coefficient T/N under fix brownian).
The long-time diffusion coefficient D is the slope of MSD = 6 D t + c
fitted over the lags from a fifth of the longest to the longest (20 to 100
for the default run to t = 200).

    /usr/bin/python3 plot.py [--dumps SOLID FLUID] [--rb 0.8] [--temp 0.005]
"""

import argparse
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from scipy.spatial import cKDTree  # noqa: E402

from tessera_tools.dump import read_dump  # noqa: E402


def trajectory(path):
    """Unwrapped positions (frames x atoms x 3), types, times, the last frame."""
    frames = read_dump(path)
    xyz = np.stack([np.column_stack([f["xu"], f["yu"], f["zu"]]) for f in frames])
    steps = np.array([f.timestep for f in frames], dtype=float)
    return xyz, frames[0]["type"], steps, frames[-1]


def msd(xyz, cells, lags):
    """MSD of the cells and of the other atoms at each lag (in frames),
    averaged over all time origins, relative to the cells' centre of mass."""
    rel = xyz - xyz[:, cells].mean(axis=1, keepdims=True)
    out = []
    for lag in lags:
        d2 = np.sum((rel[lag:] - rel[:-lag]) ** 2, axis=2).mean(axis=0)
        out.append((d2[cells].mean(), d2[~cells].mean()))
    return np.array(out)


def fit_range(t):
    return t[-1] / 5.0, t[-1]


def diffusion(t, m):
    """D from MSD = 6 D t + c, and the exponent alpha of MSD ~ t^alpha,
    both fitted over the lags of fit_range."""
    lo, hi = fit_range(t)
    sel = (t >= lo) & (t <= hi)
    return (np.polyfit(t[sel], m[sel], 1)[0] / 6.0,
            np.polyfit(np.log(t[sel]), np.log(m[sel]), 1)[0])


def section(ax, frame, xyz, cells, rb, pixels=300):
    """The cells cut by the plane z = Lz/2 (each pixel belongs to the
    nearest cell centre: the Voronoi section of the cells alone, the beads
    left out), coloured by the 3D shape index; the beads within rb of the
    plane at the end as white discs of radius rb/2 (two beads repel each
    other closer than rb; a bead repels cell centres closer than rb), with
    their paths over the whole run projected on the plane."""
    b = frame.box
    lo = np.array([b.xlo, b.ylo, b.zlo])
    L = np.array([b.xhi - b.xlo, b.yhi - b.ylo, b.zhi - b.zlo])
    last = (xyz[-1] - lo) % L
    tree = cKDTree(last[cells], boxsize=L)
    gx, gy = np.meshgrid((np.arange(pixels) + 0.5) / pixels * L[0],
                         (np.arange(pixels) + 0.5) / pixels * L[1])
    q = np.column_stack([gx.ravel(), gy.ravel(), np.full(gx.size, 0.5 * L[2])])
    owner = tree.query(q)[1].reshape(gx.shape)
    shape = frame["c_cell[3]"][cells][owner]
    edge = np.zeros_like(owner, dtype=bool)
    edge[:, 1:] |= owner[:, 1:] != owner[:, :-1]
    edge[1:, :] |= owner[1:, :] != owner[:-1, :]
    im = ax.imshow(np.ma.masked_where(edge, shape), origin="lower", cmap="viridis",
                   vmin=5.2, vmax=6.0, extent=(0, L[0], 0, L[1]))
    ax.set_facecolor("black")
    beads = np.flatnonzero(~cells)
    near = beads[np.abs(last[beads, 2] - 0.5 * L[2]) < rb]
    for i in near:
        # the path, shifted by whole box lengths so that it ends at the bead
        path = xyz[:, i, :2] - xyz[-1, i, :2] + last[i, :2]
        ax.plot(path[:, 0], path[:, 1], "-", color="red", lw=0.8)
        for sx in (-L[0], 0, L[0]):
            for sy in (-L[1], 0, L[1]):
                ax.add_patch(plt.Circle((last[i, 0] + sx, last[i, 1] + sy), 0.5 * rb,
                                        fc="white", ec="black", alpha=0.8, lw=0.5))
    ax.set_xlim(0, L[0])
    ax.set_ylim(0, L[1])
    ax.set_xticks([])
    ax.set_yticks([])
    return im, len(near)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--dumps", nargs=2, default=[os.path.join(HERE, "dump.spheroid_beads.5.2"),
                                                os.path.join(HERE, "dump.spheroid_beads.5.7")])
    p.add_argument("--labels", nargs=2, default=["solid, s0 = 5.2", "fluid, s0 = 5.7"])
    p.add_argument("--rb", type=float, default=0.8, help="range of the beads' soft repulsion")
    p.add_argument("--temp", type=float, default=0.005, help="temperature of fix brownian")
    p.add_argument("--dt", type=float, default=0.02, help="timestep")
    a = p.parse_args()

    runs = []
    for path in a.dumps:
        xyz, types, steps, last = trajectory(path)
        cells = types == 1
        t_frame = (steps[1] - steps[0]) * a.dt
        nmax = len(steps) - 1
        # lags up to half the run: at least half of the frames are origins
        lags = np.unique(np.round(np.logspace(0, np.log10(max(nmax // 2, 1)), 30)).astype(int))
        runs.append((xyz, cells, last, lags * t_frame, msd(xyz, cells, lags)))

    # msd.dat: one row per lag of the first run (both runs have the same frames)
    t = runs[0][3]
    table = np.column_stack([t] + [r[4][: len(t), k] for r in runs for k in (0, 1)])
    header = ("lag_time  cells_%s  beads_%s  cells_%s  beads_%s" %
              tuple(lbl.split(",")[0] for lbl in a.labels for _ in (0, 1)))
    np.savetxt(os.path.join(HERE, "msd.dat"), table, fmt="%.6g", header=header)

    fig = plt.figure(figsize=(12.5, 4.2))
    ax = fig.add_axes([0.06, 0.13, 0.3, 0.78])
    colours = ("tab:blue", "tab:orange")
    for (xyz, cells, last, tl, m), lbl, c in zip(runs, a.labels, colours):
        (dc, ac), (db, ab) = diffusion(tl, m[:, 0]), diffusion(tl, m[:, 1])
        print("%s: %d cells, %d beads; MSD at lag %g: cells %.3g, beads %.3g; "
              "lags %g-%g: D cells %.2g, beads %.2g (free %g), MSD ~ t^alpha with alpha "
              "cells %.2f, beads %.2f"
              % ((lbl, cells.sum(), (~cells).sum(), tl[-1], m[-1, 0], m[-1, 1]) + fit_range(tl)
                 + (dc, db, a.temp, ac, ab)))
        ax.loglog(tl, m[:, 0], "-", color=c, label="cells, %s" % lbl)
        ax.loglog(tl, m[:, 1], "--o", ms=3, color=c, label="beads, %s" % lbl)
    ax.loglog(t, 6 * a.temp * t, ":", color="grey", label="free particle, 6 T t")
    ax.set_xlabel("lag time")
    ax.set_ylabel("mean-squared displacement")
    ax.legend(fontsize=8)

    for k, ((xyz, cells, last, tl, m), lbl) in enumerate(zip(runs, a.labels)):
        ax = fig.add_axes([0.40 + 0.27 * k, 0.05, 0.25, 0.84])
        im, nnear = section(ax, last, xyz, cells, a.rb)
        ax.set_title("%s: section z = Lz/2 at t = %g\n%d beads within %g of the plane, their paths"
                     % (lbl, last.timestep * a.dt, nnear, a.rb), fontsize=9)
    cax = fig.add_axes([0.94, 0.1, 0.012, 0.75])
    fig.colorbar(im, cax=cax, label="cell shape index s = S / V^(2/3)")
    os.makedirs(os.path.join(HERE, "figures"), exist_ok=True)
    fig.savefig(os.path.join(HERE, "figures", "spheroid_beads.png"), dpi=110)


if __name__ == "__main__":
    main()
