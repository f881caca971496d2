#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Cross-sections of 3D tissues: the plane z = Lz/2 cut through the Voronoi
cells of the last frame of each dump, each cell coloured by its 3D shape
index s = S/V^(2/3) (column c_cell[3] of compute vertex/atom).

    /usr/bin/python3 picture.py dump.3d.5.0 dump.3d.5.8 -o 3d.png
"""

import argparse

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from scipy.spatial import cKDTree


def last_frame(path):
    with open(path) as f:
        lines = f.read().split("\n")
    starts = [i for i, line in enumerate(lines) if line.startswith("ITEM: TIMESTEP")]
    i = starts[-1]
    n = int(lines[i + 3])
    box = np.array([[float(w) for w in lines[i + 5 + k].split()[:2]] for k in range(3)])
    cols = lines[i + 8].split()[2:]
    rows = np.array([[float(w) for w in lines[i + 9 + k].split()] for k in range(n)])
    return int(lines[i + 1]), box, {c: rows[:, k] for k, c in enumerate(cols)}


def section(ax, path, vmin, vmax, pixels=400):
    step, box, fr = last_frame(path)
    lo, L = box[:, 0], box[:, 1] - box[:, 0]
    xyz = np.column_stack([fr["x"], fr["y"], fr["z"]]) - lo
    xyz %= L
    tree = cKDTree(xyz, boxsize=L)
    gx, gy = np.meshgrid((np.arange(pixels) + 0.5) / pixels * L[0],
                         (np.arange(pixels) + 0.5) / pixels * L[1])
    q = np.column_stack([gx.ravel(), gy.ravel(), np.full(gx.size, 0.5 * L[2])])
    owner = tree.query(q)[1].reshape(gx.shape)
    img = fr["c_cell[3]"][owner]
    edge = np.zeros_like(owner, dtype=bool)
    edge[:, 1:] |= owner[:, 1:] != owner[:, :-1]
    edge[1:, :] |= owner[1:, :] != owner[:-1, :]
    im = ax.imshow(np.ma.masked_where(edge, img), origin="lower", cmap="viridis", vmin=vmin,
                   vmax=vmax, extent=(0, L[0], 0, L[1]))
    ax.set_facecolor("black")
    ax.set_xticks([])
    ax.set_yticks([])
    return im, fr["c_cell[3]"].mean(), step


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("dumps", nargs="+")
    p.add_argument("-o", "--output", default="3d.png")
    p.add_argument("--titles", nargs="*")
    a = p.parse_args()
    fig, axes = plt.subplots(1, len(a.dumps), figsize=(4 * len(a.dumps) + 1, 4), squeeze=False)
    for k, (ax, path) in enumerate(zip(axes[0], a.dumps)):
        im, mean_s, step = section(ax, path, 5.2, 6.0)
        title = a.titles[k] if a.titles and k < len(a.titles) else path
        ax.set_title("%s\nmean s = %.3f (step %d)" % (title, mean_s, step), fontsize=10)
    fig.colorbar(im, ax=axes[0].tolist(), label="shape index s = S / V^(2/3)")
    fig.savefig(a.output, dpi=90)


if __name__ == "__main__":
    main()
