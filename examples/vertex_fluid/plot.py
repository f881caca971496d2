#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Pictures of examples/vertex_fluid: the cells' mean squared displacement, the mean
shape index and the T1 count against time for the fluid (log.vertex_fluid.1, p0 = 3.9)
and, when present, the solid (log.vertex_fluid.solid.1, -var p0 3.6)
(figures/vertex_fluid_msd.png); the fluid tissue at the end, coloured by shape index
(figures/vertex_fluid_tissue.png, from dump.vertex_fluid and dump.vertex_fluid.edges)."""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tessera_tools.junctions import junction_tessellation, paired_frames  # noqa: E402
from tessera_tools.logplot import parse_log  # noqa: E402
from tessera_tools.render import draw_tessellation  # noqa: E402

FIG = os.path.join(HERE, "figures")
os.makedirs(FIG, exist_ok=True)

fig, axes = plt.subplots(1, 3, figsize=(11, 3.2))
for name, label, colour in (("log.vertex_fluid.1", "p0 = 3.9 (fluid)", "C0"),
                            ("log.vertex_fluid.solid.1", "p0 = 3.6 (solid)", "C3")):
    path = os.path.join(HERE, name)
    if not os.path.exists(path):
        continue
    run = parse_log(path).runs[-1]
    t = run["Time"]
    axes[0].loglog(t[1:], run["c_msd[4]"][1:], color=colour, label=label)
    axes[1].plot(t, run["c_q"], color=colour, label=label)
    axes[2].plot(t, run["c_t1[1]"], color=colour, label=label)
tt = axes[0].get_xlim()
axes[0].set_xlabel("time")
axes[0].set_ylabel("MSD of the cells")
axes[1].axhline(3.81, color="grey", ls="--", lw=1, label="3.81")
axes[1].set_xlabel("time")
axes[1].set_ylabel("mean shape index q")
axes[2].set_xlabel("time")
axes[2].set_ylabel("T1s (cumulative)")
for ax in axes:
    ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(os.path.join(FIG, "vertex_fluid_msd.png"), dpi=110)

atoms, local = paired_frames(os.path.join(HERE, "dump.vertex_fluid"),
                             os.path.join(HERE, "dump.vertex_fluid.edges"))[-1]
fig, ax = plt.subplots(figsize=(4.6, 4))
draw_tessellation(ax, atoms, junction_tessellation(atoms, local), field="shape", vmin=3.6,
                  vmax=4.6)
ax.set_title("p0 = 3.9, t = %g" % (atoms.timestep * 0.01))
fig.tight_layout()
fig.savefig(os.path.join(FIG, "vertex_fluid_tissue.png"), dpi=90)
print("wrote figures/vertex_fluid_msd.png, figures/vertex_fluid_tissue.png")
