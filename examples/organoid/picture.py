#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Cells on a sphere: the first and last frames of a run, each cell drawn as
the polygon of its Voronoi vertices (from the dump local of compute
vertex/local) and coloured by its number of neighbours (5: the topological
defects every tissue on a sphere has, at least 12 of them net).  Only the
hemisphere facing the viewer is drawn.

    /usr/bin/python3 picture.py dump.organoid.cells dump.organoid.edges -o figures/organoid.png
"""

import argparse
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from tessera_tools.dump import iter_dump  # noqa: E402


def frames(path):
    """Frames of a dump file (atoms or local): (step, {column: array})."""
    return [(f.timestep, f.columns) for f in iter_dump(path)]


def draw(ax, cells, edges, view):
    ids = cells["id"].astype(int)
    pos = np.column_stack([cells["x"], cells["y"], cells["z"]])
    # the sphere through the centres (least squares of |p|^2 = 2 c.p + k)
    sol = np.linalg.lstsq(np.column_stack([2 * pos, np.ones(len(pos))]), (pos * pos).sum(1), rcond=None)[0]
    centre = sol[:3]
    z = dict(zip(ids, cells["c_cell[4]"].astype(int)))
    cols = sorted(k for k in edges if k.startswith("c_edges["))
    owner = edges[cols[0]].astype(int)
    start = np.column_stack([edges[cols[2]], edges[cols[3]], edges[cols[4]]])
    polys, colours = [], []
    for cid in np.unique(owner):
        p = start[owner == cid]
        if (p.mean(axis=0) - centre) @ view < 0:
            continue
        polys.append(p)
        colours.append(min(max(z[cid], 4), 8))
    cmap = ListedColormap(["#7b3294", "#d7191c", "#dddddd", "#2c7bb6", "#1a9641"])
    pc = Poly3DCollection(polys, facecolors=cmap((np.array(colours) - 4) / 4.0), edgecolors="k",
                          linewidths=0.4)
    ax.add_collection3d(pc)
    r = float(np.sqrt(sol[3] + centre @ centre))
    for k, set_lim in enumerate((ax.set_xlim, ax.set_ylim, ax.set_zlim)):
        set_lim(centre[k] - r, centre[k] + r)
    ax.set_box_aspect((1, 1, 1))
    ax.set_axis_off()
    return r


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("cells")
    p.add_argument("edges")
    p.add_argument("-o", "--output", default="organoid.png")
    a = p.parse_args()
    cf, ef = frames(a.cells), frames(a.edges)
    steps = dict(ef)
    chosen = [cf[0], cf[-1]]
    elev, azim = 20.0, 35.0
    view = np.array([np.cos(np.radians(elev)) * np.cos(np.radians(azim)),
                     np.cos(np.radians(elev)) * np.sin(np.radians(azim)), np.sin(np.radians(elev))])
    fig = plt.figure(figsize=(10, 5))
    radii = []
    for k, (step, cells) in enumerate(chosen):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        ax.view_init(elev=elev, azim=azim)
        radii.append(draw(ax, cells, steps[step], view))
        n = len(cells["id"])
        defects = int((6 - cells["c_cell[4]"]).sum())
        ax.set_title(f"step {step}: {n} cells, R = {radii[-1]:.2f}\nsum (6 - z) = {defects}")
    handles = [plt.Rectangle((0, 0), 1, 1, color=c)
               for c in ("#7b3294", "#d7191c", "#dddddd", "#2c7bb6", "#1a9641")]
    fig.legend(handles, ["4 or fewer neighbours", "5", "6", "7", "8 or more"], loc="lower center", ncol=5)
    fig.savefig(a.output, dpi=110, bbox_inches="tight")


if __name__ == "__main__":
    main()
