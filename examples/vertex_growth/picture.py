#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The grown vertex tissue: its polygons (the rings of vertex_growth.data,
unwrapped by the minimum image) coloured by generation (f_div[2] of
cells.dump), and N(t) from the log against 50 exp(R t).

    /usr/bin/python3 picture.py vertex_growth.data cells.dump log.lammps -o vertex_growth.png
"""

import argparse
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from tessera_tools.vertex_data import VertexData  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("data")
    ap.add_argument("dump")
    ap.add_argument("log")
    ap.add_argument("-o", "--output", default="vertex_growth.png")
    ap.add_argument("--rate", type=float, default=0.1)
    args = ap.parse_args()

    data = VertexData(args.data)
    rings = data.rings
    xlo, ylo, lx, ly = data.xlo, data.ylo, data.lx, data.ly
    xhi, yhi = xlo + lx, ylo + ly
    with open(args.dump) as f:
        lines = f.read().split("\n")
    cols = lines[8].split()[2:]
    gen = {}
    for line in lines[9:]:
        w = line.split()
        if len(w) == len(cols):
            gen[int(w[0])] = float(w[cols.index("f_div[2]")])

    polys, colours = [], []
    for c, ring in rings.items():
        p = data.polygon(c)
        # the image whose centroid lies in the box
        shift = np.floor((p.mean(axis=0) - [xlo, ylo]) / [lx, ly]) * [lx, ly]
        for dx in (-lx, 0.0, lx):
            for dy in (-ly, 0.0, ly):
                polys.append(p - shift + [dx, dy])
                colours.append(gen.get(c, 0.0))

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 6.2), gridspec_kw={"width_ratios": [1.1, 1]})
    pc = PolyCollection(polys, array=np.array(colours), cmap="viridis", edgecolors="k",
                        linewidths=0.4)
    ax.add_collection(pc)
    ax.set_xlim(xlo, xhi)
    ax.set_ylim(ylo, yhi)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    fig.colorbar(pc, ax=ax, shrink=0.8, label="generation (divisions since the start)")
    ax.set_title(f"{len(rings)} cells")

    t, n = [], []
    head = None
    with open(args.log) as f:
        for line in f:
            w = line.split()
            if w[:2] == ["Step", "Time"]:
                head = w
                continue
            if head and len(w) == len(head) and w[0].isdigit():
                t.append(float(w[head.index("Time")]))
                n.append(float(w[head.index("v_ncell")]))
            elif head and w[:1] == ["Loop"]:
                head = None
    t, n = np.array(t), np.array(n)
    bx.semilogy(t, n, "o-", ms=3, label="cells")
    bx.semilogy(t, n[0] * np.exp(args.rate * t), "--", label=f"{n[0]:.0f} exp({args.rate} t)")
    bx.set_xlabel("time")
    bx.set_ylabel("cells")
    bx.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)


if __name__ == "__main__":
    main()
