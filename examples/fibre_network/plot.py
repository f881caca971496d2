#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Measurements and pictures of examples/fibre_network, from the runs with
(dump.fibre_network.1, msd.1.dat) and without fibres (.0):

* figures/fibre_network.png: the cells (finite Voronoi cells, free arcs red)
  with the fibres (bonds as lines, crosslinked beads in blue, anchored ends
  as black squares) at the start and at the end of the run with fibres;
* figures/fibre_measures.png: the cells' mean speed against time with and
  without fibres, and the network's nematic order along the cells'
  migration axis x, S = <cos 2 theta> over the fibre bonds, and its rms bead
  displacement, against time.

Prints the numbers the README quotes.  ``plot.py --numbers`` prints them
without drawing; ``plot.py DIR`` reads the runs from DIR (default: here)."""

import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))

from tessera_tools.dump import read_dump  # noqa: E402

RADIUS = 0.8
NB = 17            # beads per fibre (make_network.py: length 8, bead spacing 0.5)
FIG = os.path.join(HERE, "figures")
T0 = 20.0          # speeds are averaged from here (after the start, when cells first meet fibres)


def read_bonds(path):
    """Bonds of the data file: array of (type, i, j) atom ids."""
    with open(path) as f:
        lines = f.read().split("\n")
    start = lines.index("Bonds") + 2
    rows = []
    for line in lines[start:]:
        if not line.strip():
            break
        rows.append([int(w) for w in line.split()[1:4]])
    return np.array(rows)


def bond_vectors(frame, bonds, types=(1,)):
    """Minimum-image vectors of the bonds of the given types, from a frame
    holding every atom (ids 1..N in order)."""
    pos = frame.unwrapped()
    index = {int(a): k for k, a in enumerate(frame.ids)}
    sel = bonds[np.isin(bonds[:, 0], types)]
    i = np.array([index[a] for a in sel[:, 1]])
    j = np.array([index[a] for a in sel[:, 2]])
    return frame.box.minimum_image(pos[j] - pos[i]), pos[i]


def nematic_x(vectors):
    """S = <cos 2 theta> of the bond directions (theta from the x axis)."""
    t = np.arctan2(vectors[:, 1], vectors[:, 0])
    return float(np.mean(np.cos(2 * t)))


def max_strain(frame, bonds):
    """Largest |length / 0.5 - 1| of the fibre bonds in a frame."""
    v, _ = bond_vectors(frame, bonds)
    return float(np.max(np.abs(np.linalg.norm(v, axis=1) / 0.5 - 1.0)))


def measures(dump, bonds):
    """Time, S along x, rms bead displacement from the start and mean bond
    length of the fibres, per frame."""
    frames = read_dump(dump)
    first = frames[0]
    beads0 = first.unwrapped()[first["type"] == 2]
    out = []
    for fr in frames:
        v, _ = bond_vectors(fr, bonds)
        beads = fr.unwrapped()[fr["type"] == 2]
        rms = math.sqrt(np.mean(np.sum((beads - beads0) ** 2, axis=1)))
        out.append((fr.timestep, nematic_x(v), rms, float(np.mean(np.linalg.norm(v, axis=1)))))
    return np.array(out), frames


def draw_state(ax, frame, bonds, title):
    from matplotlib.collections import LineCollection
    from tessera_tools.dump import split_cells
    from tessera_tools.render import draw_tessellation, tessellate_frame

    cells = split_cells(frame, {1})
    beads = cells.particles
    cells.particles = None            # the beads are drawn below, smaller than render's discs
    tess = tessellate_frame(cells, RADIUS)
    draw_tessellation(ax, cells, tess, field="none", colorbar=False, linewidth=0.4)
    box = frame.box
    pos = frame.box.wrap(frame.unwrapped())
    index = {int(a): k for k, a in enumerate(frame.ids)}
    sel = bonds[bonds[:, 0] == 1]
    i = np.array([index[a] for a in sel[:, 1]])
    j = np.array([index[a] for a in sel[:, 2]])
    d = box.minimum_image(pos[j] - pos[i])
    segs = [np.array([p, p + dd]) for p, dd in zip(pos[i], d)]
    # a bond across the periodic edge is drawn from both of its ends
    segs += [np.array([q - dd, q]) for p, q, dd in zip(pos[i], pos[j], d)
             if np.any(np.abs(q - (p + dd)) > 1e-6)]
    ax.add_collection(LineCollection(segs, colors="#6b4226", linewidths=1.3, zorder=5))
    # crosslinks (rest length 0): their beads in blue
    linked = [index[a] for a in bonds[bonds[:, 0] == 2][:, 1:].ravel()]
    ax.plot(pos[linked, 0], pos[linked, 1], "o", ms=3.5, color="#1f5fbf", zorder=7)
    q = beads.positions()
    ax.plot(q[:, 0], q[:, 1], "o", ms=1.6, color="#6b4226", zorder=6)
    ends = ((beads.ids - frame.ids[frame["type"] == 1].max() - 1) % NB == 0) | \
           ((beads.ids - frame.ids[frame["type"] == 1].max()) % NB == 0)
    ax.plot(q[ends, 0], q[ends, 1], "s", ms=3.5, color="k", zorder=7)
    ax.set_xlim(box.xlo, box.xhi)
    ax.set_ylim(box.ylo, box.yhi)
    ax.set_title(title)
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_xlabel("")
    ax.set_ylabel("")


def main():
    numbers_only = "--numbers" in sys.argv
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    where = args[0] if args else HERE
    bonds = read_bonds(os.path.join(where, "fibres.data"))
    dt = 0.005
    net, frames = measures(os.path.join(where, "dump.fibre_network.1"), bonds)
    m1 = np.loadtxt(os.path.join(where, "msd.1.dat"))
    m0 = np.loadtxt(os.path.join(where, "msd.0.dat"))
    t = net[:, 0] * dt
    tend = m1[-1, 0]
    late1, late0 = m1[m1[:, 0] >= T0], m0[m0[:, 0] >= T0]
    print("cells' mean speed over t = %g .. %g: %.3f with fibres, %.3f without (ratio %.2f)"
          % (T0, tend, late1[:, 7].mean(), late0[:, 7].mean(),
             late1[:, 7].mean() / late0[:, 7].mean()))
    print("t = %g: cells' msd %.4g with fibres, %.4g without; msd_x / msd_y %.3g with, %.3g without"
          % (tend, m1[-1, 3], m0[-1, 3], m1[-1, 1] / m1[-1, 2], m0[-1, 1] / m0[-1, 2]))
    print("network: S = <cos 2 theta> %.3f at t = 0, %.3f at t = %g (max %.3f); rms bead "
          "displacement %.3g; fibre bonds: mean length %.4f, largest strain %.2f (rest 0.5)"
          % (net[0, 1], net[-1, 1], t[-1], net[:, 1].max(), net[-1, 2], net[-1, 3],
             max_strain(frames[-1], bonds)))
    if numbers_only:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    os.makedirs(FIG, exist_ok=True)

    fig, axes = plt.subplots(1, 2, figsize=(10, 5))
    draw_state(axes[0], frames[0], bonds, "t = 0")
    draw_state(axes[1], frames[-1], bonds, "t = %g" % t[-1])
    fig.tight_layout()
    fig.savefig(os.path.join(FIG, "fibre_network.png"), dpi=90)

    fig, (a, b, c) = plt.subplots(1, 3, figsize=(12, 3.4))
    a.plot(m0[:, 0], m0[:, 7], "-", lw=0.8, color="0.55", label="without fibres")
    a.plot(m1[:, 0], m1[:, 7], "k-", lw=0.8, label="with fibres")
    a.set_xlabel("time")
    a.set_ylabel("cells' mean speed")
    a.set_ylim(0, None)
    a.legend()
    b.plot(t, net[:, 1], "b-")
    b.axhline(0.0, color="0.6", lw=0.8)
    b.set_xlabel("time")
    b.set_ylabel(r"fibre order along x, $S = \langle\cos 2\theta\rangle$")
    c.plot(t, net[:, 2], "r-")
    c.set_xlabel("time")
    c.set_ylabel("rms bead displacement")
    fig.tight_layout()
    fig.savefig(os.path.join(FIG, "fibre_measures.png"), dpi=110)
    print("wrote figures/fibre_network.png, figures/fibre_measures.png")


if __name__ == "__main__":
    main()
