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
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from tessera_tools.vertex_data import VertexData  # noqa: E402
from tessera_tools.voronoi import polygon_elongation  # noqa: E402


def polygons(path):
    d = VertexData(path)
    return d.lx, d.ly, [d.polygon(c) for c in d.rings]


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
        e = np.mean([polygon_elongation(p) for p in polys])
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
