#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The segmented image, the vertex tissue made from it, and the tissue after
relaxing (one panel per data file given), with each cell's elongation: the
ratio of the long to the short axis of its polygon's second moments, whose
mean over the cells is printed and shown.

    /usr/bin/python3 picture.py labels.txt tissue.data relaxed_3.7.data relaxed_3.95.data \
        -o figures/vertex_segmented.png
"""

import argparse
import math

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection
import numpy as np


def read_data(path):
    """Box lengths, positions {id: (type, x, y)} and rings {cell: [vertices]}."""
    with open(path) as f:
        lines = f.read().split("\n")
    box = {}
    for line in lines:
        w = line.split()
        if line.endswith("xlo xhi") or line.endswith("ylo yhi"):
            box[w[2]] = float(w[1]) - float(w[0])

    def section(name):
        i = [k for k, l in enumerate(lines) if l.split("#")[0].strip() == name][0] + 2
        rows = []
        while i < len(lines) and lines[i].strip():
            rows.append(lines[i].split())
            i += 1
        return rows

    atoms = {int(r[0]): (int(r[1]), float(r[2]), float(r[3])) for r in section("Atoms")}
    rings = {int(r[0]): [int(v) for v in r[1:] if int(v) > 0] for r in section("vring")}
    return box["xlo"], box["ylo"], atoms, {c: r for c, r in rings.items() if r}


def polygons(path):
    lx, ly, atoms, rings = read_data(path)
    out = []
    for ring in rings.values():
        pts = [np.array(atoms[ring[0]][1:])]
        for v in ring[1:]:
            d = np.array(atoms[v][1:]) - pts[-1]
            d -= np.array([lx, ly]) * np.round(d / np.array([lx, ly]))
            pts.append(pts[-1] + d)
        out.append(np.array(pts))
    return lx, ly, out


def elongation(p):
    """Long over short axis of the polygon's second moments about its centroid."""
    x, y = p[:, 0], p[:, 1]
    x1, y1 = np.roll(x, -1), np.roll(y, -1)
    cr = x * y1 - x1 * y
    a = cr.sum() / 2
    cx, cy = ((x + x1) * cr).sum() / (6 * a), ((y + y1) * cr).sum() / (6 * a)
    x, y, x1, y1 = x - cx, y - cy, x1 - cx, y1 - cy
    ixx = ((x * x + x * x1 + x1 * x1) * cr).sum() / 12
    iyy = ((y * y + y * y1 + y1 * y1) * cr).sum() / 12
    ixy = ((x * y1 + 2 * x * y + 2 * x1 * y1 + x1 * y) * cr).sum() / 24
    w = np.linalg.eigvalsh([[ixx, ixy], [ixy, iyy]])
    return math.sqrt(w[1] / w[0])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("labels")
    ap.add_argument("data", nargs="+")
    ap.add_argument("-o", "--output", default="vertex_segmented.png")
    a = ap.parse_args()
    lab = np.loadtxt(a.labels, dtype=int)
    fig, axes = plt.subplots(1, 1 + len(a.data), figsize=(4.6 * (1 + len(a.data)), 4))
    rng = np.random.default_rng(1)
    colours = rng.random((lab.max() + 1, 3)) * 0.6 + 0.4
    colours[0] = 0.0
    axes[0].imshow(colours[lab])
    axes[0].set_title("segmented image (labels, 0 = boundary)")
    axes[0].set_axis_off()
    for ax, path in zip(axes[1:], a.data):
        lx, ly, polys = polygons(path)
        e = np.mean([elongation(p) for p in polys])
        print(f"{path}: {len(polys)} cells, mean elongation {e:.3f}")
        ax.add_collection(PolyCollection(polys, facecolors="#cfe3f3", edgecolors="k",
                                         linewidths=0.7))
        ax.set_xlim(0, lx)
        ax.set_ylim(0, ly)
        ax.set_aspect("equal")
        ax.set_title(f"{path}\nmean elongation {e:.2f}", fontsize=9)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)


if __name__ == "__main__":
    main()
