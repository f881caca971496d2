#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""A stand-in for a segmented microscopy image: the label image of a
periodic patch of 80 cells elongated along x (the Voronoi cells of random
centres in a metric that stretches x by 1.6, as in a tissue pulled along x),
rasterised at 160 x 120 pixels, with the one-pixel boundaries between cells
set to label 0, as a watershed segmentation draws them.  Row 0 is the top of
the image (as image files store it).

    /usr/bin/python3 make_labels.py -o labels.txt [--png labels.png]
"""

import argparse

import numpy as np


def labels(n=80, nx=160, ny=120, stretch=1.6, seed=4821):
    rng = np.random.default_rng(seed)
    centres = rng.random((n, 2)) * [nx, ny]
    yy, xx = np.mgrid[0:ny, 0:nx] + 0.5
    best = np.full((ny, nx), np.inf)
    lab = np.zeros((ny, nx), dtype=int)
    for k, (cx, cy) in enumerate(centres):
        dx = xx - cx
        dx -= nx * np.round(dx / nx)
        dy = yy - cy
        dy -= ny * np.round(dy / ny)
        d = (dx / stretch) ** 2 + dy ** 2
        closer = d < best
        best[closer] = d[closer]
        lab[closer] = k + 1
    # Watershed lines: a pixel whose right or upper neighbour (periodic) is
    # another cell becomes boundary (0).
    edge = (np.roll(lab, -1, axis=1) != lab) | (np.roll(lab, -1, axis=0) != lab)
    lab[edge] = 0
    return lab


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-o", "--output", default="labels.txt")
    ap.add_argument("--png", help="also draw the label image")
    a = ap.parse_args()
    lab = labels()
    with open(a.output, "w") as f:
        f.write("# labels of a segmented periodic patch: 0 = boundary, 1..80 = cells; "
                "row 0 = top\n")
        for row in lab:
            f.write(" ".join(map(str, row)) + "\n")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        rng = np.random.default_rng(1)
        colours = rng.random((lab.max() + 1, 3)) * 0.6 + 0.4
        colours[0] = 0.0
        plt.imsave(a.png, colours[lab])


if __name__ == "__main__":
    main()
