#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Pictures of examples/wound: the wound area against time (figures/wound_area.png)
and the tissue at four times with the free arcs in red (figures/wound_sequence.png)."""

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
DT = 0.02
FIG = os.path.join(HERE, "figures")
os.makedirs(FIG, exist_ok=True)

data = np.loadtxt(os.path.join(HERE, "wound.dat"))
fig, ax = plt.subplots(figsize=(5, 3.2))
ax.plot(data[:, 0], data[:, 1], "k-", label="wound area")
ax.plot(data[:, 0], data[:, 3], "r--", label="free perimeter")
ax.set_xlabel("time")
ax.set_ylabel("area, length (cell units)")
ax.legend()
fig.tight_layout()
fig.savefig(os.path.join(FIG, "wound_area.png"), dpi=120)

frames = read_dump(os.path.join(HERE, "dump.wound"))
times = [0.0, 4.0, 8.0, 16.0]
chosen = [min(frames, key=lambda f: abs(f.timestep * DT - t)) for t in times]
fig, axes = plt.subplots(1, len(chosen), figsize=(3.3 * len(chosen), 3.5))
for ax, frame in zip(axes, chosen):
    tess = tessellate_frame(frame, RADIUS)
    draw_tessellation(ax, frame, tess, field="c_cell[8]", vmin=0.0, vmax=3.0, colorbar=False)
    ax.set_title("t = %g, wound area %.2f" % (frame.timestep * DT, frame.box.area - tess.area.sum()))
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_xlabel("")
    ax.set_ylabel("")
fig.tight_layout()
fig.savefig(os.path.join(FIG, "wound_sequence.png"), dpi=80)
print("wrote figures/wound_area.png, figures/wound_sequence.png")
