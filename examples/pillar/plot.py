#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Pictures of examples/pillar: the area of the holes against time
(figures/pillar_hole.png) and the tissue at four times with the pillar's
range of repulsion dashed (figures/pillar_sequence.png)."""

import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tessera_tools.dump import read_dump  # noqa: E402
from tessera_tools.render import draw_tessellation, tessellate_frame  # noqa: E402

RADIUS = 0.8
RP = 1.5
DT = 0.02
FIG = os.path.join(HERE, "figures")
os.makedirs(FIG, exist_ok=True)

data = np.loadtxt(os.path.join(HERE, "hole.dat"))
fig, ax = plt.subplots(figsize=(5, 3.2))
ax.plot(data[:, 0], data[:, 2], "k-", label="hole area (compute vertex/loops)")
ax.plot(data[:, 0], data[:, 3], "r--", label="free perimeter")
ax.set_xlabel("time")
ax.set_ylabel("area, length (cell units)")
ax.legend()
fig.tight_layout()
fig.savefig(os.path.join(FIG, "pillar_hole.png"), dpi=120)

# The dump holds the cells only (the pillar is no cell): the pillar sits at
# the centre of the box.
frames = read_dump(os.path.join(HERE, "dump.pillar"))
times = [0.0, 4.0, 10.0, 30.0]
chosen = [min(frames, key=lambda f: abs(f.timestep * DT - t)) for t in times]
fig, axes = plt.subplots(1, len(chosen), figsize=(3.3 * len(chosen), 3.5))
for ax, frame in zip(axes, chosen):
    tess = tessellate_frame(frame, RADIUS)
    draw_tessellation(ax, frame, tess, field="c_cell[8]", vmin=0.0, vmax=3.0, colorbar=False)
    b = frame.box
    c = (0.5 * (b.xlo + b.xhi), 0.5 * (b.ylo + b.yhi))
    ax.plot(*c, "ko", ms=6)
    ax.add_patch(plt.Circle(c, RP, fill=False, ls="--", color="k"))
    ax.set_title("t = %g" % (frame.timestep * DT))
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_xlabel("")
    ax.set_ylabel("")
fig.tight_layout()
fig.savefig(os.path.join(FIG, "pillar_sequence.png"), dpi=80)
print("wrote figures/pillar_hole.png, figures/pillar_sequence.png")
