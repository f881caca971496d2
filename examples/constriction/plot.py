#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""The velocity field of examples/constriction.

Reads a dump of in.constriction (id type x y xu yu, with its times), takes
each cell's displacement between successive frames over the time between
them (what a PIV of the centres measures: single steps of the cells beside
the particles alternate, displacements over many steps are what the tissue
does), places it at the midpoint and averages it in 0.5 x 0.5 bins over the
frames from t0 on.  Draws the speed as colour with streamlines, the
particles as discs of their soft range, and the flux through each section
x = const (from the unwrapped coordinates) beside it:

    ./plot.py [DUMP] [-o figures/velocity_field.png] [--t0 50]
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
from matplotlib.patches import Circle  # noqa: E402
from mpl_toolkits.axes_grid1 import make_axes_locatable  # noqa: E402

from tessera_tools.dump import iter_dump  # noqa: E402

BIN = 0.5
RP = 0.8    # the particles' soft range (in.constriction's Rp)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dump", nargs="?", default=os.path.join(HERE, "dump.constriction"))
    ap.add_argument("-o", "--output", default=os.path.join(HERE, "figures", "velocity_field.png"))
    ap.add_argument("--t0", type=float, default=50.0, help="average from this time on")
    args = ap.parse_args()

    prev = None
    count = svx = svy = None
    sections = None
    crossings = None
    elapsed = 0.0
    walls = None
    for f in iter_dump(args.dump):
        if f.time is None:
            raise SystemExit(f"{args.dump}: frames without time (dump_modify ... time yes)")
        cell = f["type"] == 1
        if walls is None:
            walls = np.column_stack([f["x"][~cell], f["y"][~cell]])
            box = f.box
            nbx, nby = int(round(box.lx / BIN)), int(round(box.ly / BIN))
            count, svx, svy = np.zeros((nbx, nby)), np.zeros((nbx, nby)), np.zeros((nbx, nby))
            sections = box.xlo + (np.arange(nbx) + 0.5) * box.lx / nbx
            crossings = np.zeros(nbx)
        cur = (f.time, f["id"][cell], f["xu"][cell], f["yu"][cell])
        if prev is not None and prev[0] >= args.t0:
            tau = cur[0] - prev[0]
            same = np.array_equal(prev[1], cur[1])
            if not same:
                raise SystemExit("cells changed between frames")
            dx, dy = cur[2] - prev[2], cur[3] - prev[3]
            mx = box.xlo + np.mod(0.5 * (cur[2] + prev[2]) - box.xlo, box.lx)
            my = box.ylo + np.mod(0.5 * (cur[3] + prev[3]) - box.ylo, box.ly)
            i = np.minimum((mx - box.xlo) / box.lx * nbx, nbx - 1).astype(int)
            j = np.minimum((my - box.ylo) / box.ly * nby, nby - 1).astype(int)
            np.add.at(count, (i, j), 1)
            np.add.at(svx, (i, j), dx / tau)
            np.add.at(svy, (i, j), dy / tau)
            for k, xs in enumerate(sections):
                crossings[k] += np.sum(np.floor((cur[2] - xs) / box.lx) - np.floor((prev[2] - xs) / box.lx))
            elapsed += tau
        prev = cur
    if elapsed == 0.0:
        raise SystemExit(f"no two frames after t = {args.t0}")
    seen = count > 0
    vx = np.where(seen, svx / np.maximum(count, 1), np.nan)
    vy = np.where(seen, svy / np.maximum(count, 1), np.nan)
    speed = np.hypot(vx, vy)

    fig, (ax, axf) = plt.subplots(2, 1, figsize=(8.5, 7.2), gridspec_kw={"height_ratios": [3, 1.2]},
                                  sharex=True)
    xs = box.xlo + (np.arange(nbx) + 0.5) * BIN
    ys = box.ylo + (np.arange(nby) + 0.5) * BIN
    im = ax.imshow(speed.T, origin="lower", extent=(box.xlo, box.xhi, box.ylo, box.yhi),
                   cmap="viridis", vmin=0, interpolation="nearest")
    ax.streamplot(xs, ys, np.nan_to_num(vx.T), np.nan_to_num(vy.T), color="w", density=1.3,
                  linewidth=0.8, arrowsize=0.8)
    for x, y in walls:
        for sx in (-1, 0, 1):
            for sy in (-1, 0, 1):
                ax.add_patch(Circle((x + sx * box.lx, y + sy * box.ly), RP, color="0.6", alpha=0.5,
                                    lw=0))
    ax.set_xlim(box.xlo, box.xhi)
    ax.set_ylim(box.ylo, box.yhi)
    ax.set_aspect("equal")
    ax.set_ylabel("y")
    ax.set_title(f"mean velocity of the cell centres, t = {args.t0:g} to {prev[0]:.0f} "
                 "(grey: the particles' range)", fontsize=10)
    # colour bar beside the field, an empty slot of the same width beside the
    # flux, so that the two share their x axis
    cax = make_axes_locatable(ax).append_axes("right", size="3%", pad=0.1)
    fig.colorbar(im, cax=cax, label="speed")
    make_axes_locatable(axf).append_axes("right", size="3%", pad=0.1).axis("off")
    flux = crossings / elapsed
    axf.plot(sections, flux, "k.-")
    axf.axhline(flux.mean(), color="0.5", lw=1)
    axf.set_xlabel("x")
    axf.set_ylabel("cells crossing\nper unit time")
    axf.set_ylim(0, 1.2 * flux.max())
    axf.grid(alpha=0.3)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}; flux through the sections {flux.min():.3f} .. {flux.max():.3f}, "
          f"mean {flux.mean():.3f}")


if __name__ == "__main__":
    main()
