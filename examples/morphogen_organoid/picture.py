#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The morphogen organoid: the first and last frames, each cell drawn as the
polygon of its Voronoi vertices (from the dump local of compute vertex/local)
and coloured by its morphogen (log scale), seen from the side with the source
pole up; and, below, the morphogen, preferred area and generation of the
cells of the last frame against their height over the sphere's centre.

    /usr/bin/python3 picture.py dump.cells dump.edges -o figures/morphogen_organoid.png
"""

import argparse
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import LogNorm
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from tessera_tools.dump import iter_dump  # noqa: E402


def frames(path):
    """Frames of a dump file (atoms or local): (step, {column: array})."""
    return [(f.timestep, f.columns) for f in iter_dump(path)]


NORM = LogNorm(vmin=1e-3, vmax=3.0)
CMAP = plt.get_cmap("viridis")


def draw(ax, cells, edges, view, centre):
    m = dict(zip(cells["id"].astype(int), cells["c_sm"]))
    cols = sorted(k for k in edges if k.startswith("c_edges["))
    owner = edges[cols[0]].astype(int)
    start = np.column_stack([edges[cols[2]], edges[cols[3]], edges[cols[4]]])
    polys, colours = [], []
    for cid in np.unique(owner):
        p = start[owner == cid]
        if (p.mean(axis=0) - centre) @ view < 0:
            continue
        polys.append(p)
        colours.append(CMAP(NORM(max(m[cid], 1e-3))))
    ax.add_collection3d(Poly3DCollection(polys, facecolors=colours, edgecolors="k",
                                         linewidths=0.3))
    r = np.linalg.norm(start - centre, axis=1).max()
    for k, set_lim in enumerate((ax.set_xlim, ax.set_ylim, ax.set_zlim)):
        set_lim(centre[k] - r, centre[k] + r)
    ax.set_box_aspect((1, 1, 1))
    ax.set_axis_off()


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("cells")
    p.add_argument("edges")
    p.add_argument("-o", "--output", default="morphogen_organoid.png")
    p.add_argument("--centre", type=float, default=10.0, help="the sphere's centre (c c c)")
    a = p.parse_args()
    cf, ef = frames(a.cells), frames(a.edges)
    steps = dict(ef)
    centre = np.full(3, a.centre)
    elev, azim = 10.0, 30.0
    view = np.array([np.cos(np.radians(elev)) * np.cos(np.radians(azim)),
                     np.cos(np.radians(elev)) * np.sin(np.radians(azim)), np.sin(np.radians(elev))])
    fig = plt.figure(figsize=(10, 9))
    for k, (step, cells) in enumerate((cf[0], cf[-1])):
        ax = fig.add_subplot(2, 2, k + 1, projection="3d")
        ax.view_init(elev=elev, azim=azim)
        draw(ax, cells, steps[step], view, centre)
        ax.set_title(f"step {step}: {len(cells['id'])} cells")
    sm = plt.cm.ScalarMappable(norm=NORM, cmap=CMAP)
    fig.colorbar(sm, ax=fig.axes[:2], shrink=0.6, label="morphogen m")
    last = cf[-1][1]
    h = last["v_h"]
    ax = fig.add_subplot(2, 2, 3)
    ax.semilogy(h, np.maximum(last["c_sm"], 1e-4), ".", ms=3)
    ax.set_xlabel("height (z - c) / R")
    ax.set_ylabel("morphogen m")
    ax = fig.add_subplot(2, 2, 4)
    ax.plot(h, last["d_area0"], ".", ms=3, label="preferred area")
    ax.plot(h, last["c_cell[1]"], ".", ms=3, label="area")
    ax.plot(h, last["f_div[2]"] / 10, ".", ms=3, label="generation / 10")
    ax.set_xlabel("height (z - c) / R")
    ax.legend()
    fig.savefig(a.output, dpi=100, bbox_inches="tight")


if __name__ == "__main__":
    main()
