#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The pulled bead: the tissue around it at the end of each run (the rings of
the data files, unwrapped by the minimum image; the bead and its reach, the
cutoff of pair soft), and its displacement along the force against time
(v_dx of the logs).

    /usr/bin/python3 picture.py vertex_bead_3.7.data log.solid vertex_bead_3.95.data log.fluid \
        -o figures/vertex_bead.png
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
from tessera_tools.vertex_data import VertexData, unwrap  # noqa: E402

REACH = 0.9    # pair soft's cutoff between the bead and the vertices


def displacement(log):
    """(time, v_dx) rows of the pull (the thermo block with v_dx)."""
    rows, cols = [], None
    with open(log) as f:
        for line in f:
            w = line.split()
            if w and w[0] == "Step":
                cols = w if "v_dx" in w else None
                continue
            if cols and len(w) == len(cols):
                try:
                    rows.append((float(w[cols.index("Time")]), float(w[cols.index("v_dx")])))
                except ValueError:
                    cols = None
    return np.array(rows)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("solid_data")
    ap.add_argument("solid_log")
    ap.add_argument("fluid_data")
    ap.add_argument("fluid_log")
    ap.add_argument("-o", "--output", default="vertex_bead.png")
    a = ap.parse_args()
    fig, axes = plt.subplots(1, 3, figsize=(15, 5))
    for ax, data, name in ((axes[0], a.solid_data, "solid, p0 = 3.7"),
                           (axes[1], a.fluid_data, "fluid, p0 = 3.95")):
        d = VertexData(data)
        lx, ly, atoms, rings = d.lx, d.ly, d.atoms, d.rings
        bead = [v[1:] for v in atoms.values() if v[0] == 3][0]
        polys = []
        for cell, ring in rings.items():
            # (the bead first: the ring's images nearest it, then dropped)
            pts = unwrap([bead] + [atoms[v][1:] for v in ring], (lx, ly))[1:]
            if np.linalg.norm(pts.mean(axis=0) - bead) < 4.0:
                polys.append(pts)
        ax.add_collection(PolyCollection(polys, facecolors="#cfe3f3", edgecolors="k",
                                         linewidths=0.8))
        ax.add_patch(plt.Circle(bead, REACH, color="tab:red", alpha=0.35))
        ax.plot(*bead, "o", color="tab:red")
        ax.annotate("", xy=(bead[0] + 1.5, bead[1]), xytext=bead,
                    arrowprops=dict(arrowstyle="->", color="tab:red", lw=2))
        ax.set_xlim(bead[0] - 3.5, bead[0] + 3.5)
        ax.set_ylim(bead[1] - 3.5, bead[1] + 3.5)
        ax.set_aspect("equal")
        ax.set_title(f"{name}: the end of the pull")
    for log, name in ((a.solid_log, "solid, p0 = 3.7"), (a.fluid_log, "fluid, p0 = 3.95")):
        d = displacement(log)
        axes[2].plot(d[:, 0] - d[0, 0], d[:, 1], label=name)
    axes[2].set_xlabel("time since the pull started")
    axes[2].set_ylabel("bead displacement along the force")
    axes[2].legend()
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)


if __name__ == "__main__":
    main()
