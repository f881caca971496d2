#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Pictures of examples/colony: area, radius of gyration and free perimeter
against time (figures/colony_growth.png) and the colony at three times with
its free arcs in red (figures/colony_sequence.png)."""

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

data = np.loadtxt(os.path.join(HERE, "colony.dat"))
fig, ax = plt.subplots(figsize=(5, 3.2))
ax.plot(data[:, 0], data[:, 1], "k-", label="total cell area")
ax.plot(data[:, 0], data[:, 4], "r--", label="free perimeter")
ax.plot(data[:, 0], 10 * data[:, 2], "b:", label="10 x radius of gyration")
ax.set_xlabel("time")
ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(FIG, "colony_growth.png"), dpi=120)

frames = read_dump(os.path.join(HERE, "dump.colony"))
times = [0.0, 10.0, frames[-1].timestep * DT]
chosen = [min(frames, key=lambda f: abs(f.timestep * DT - t)) for t in times]
tess = [tessellate_frame(f, RADIUS) for f in chosen]
allpts = np.vstack([np.vstack(t.polygons) for t in tess])
lo, hi = allpts.min(axis=0) - 0.5, allpts.max(axis=0) + 0.5
fig, axes = plt.subplots(1, len(chosen), figsize=(3.6 * len(chosen), 3.8))
for ax, frame, t in zip(axes, chosen, tess):
    draw_tessellation(ax, frame, t, field="area", vmin=0.4, vmax=1.2, colorbar=False)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_title("t = %g: %d cells at the rim" % (frame.timestep * DT, int(t.at_edge.sum())))
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_xlabel("")
    ax.set_ylabel("")
fig.tight_layout()
fig.savefig(os.path.join(FIG, "colony_sequence.png"), dpi=80)
print("wrote figures/colony_growth.png, figures/colony_sequence.png")
