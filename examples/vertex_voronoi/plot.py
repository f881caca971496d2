#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Pictures of examples/vertex_voronoi: the energy per cell and the mean shape index of
both models against time (figures/vertex_voronoi_energy.png, from log.vertex_voronoi.1 or
the log given as argument) and both tissues at the start and at the end, coloured by
shape index (figures/vertex_voronoi_tissues.png, from the dumps)."""

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
MODELS = (("voronoi", "Voronoi model", "C3"), ("vertex", "vertex model", "C0"))
log = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "log.vertex_voronoi.1")

# the two dynamics runs: the thermo blocks with v_epc over more than one line, in order
runs = [r for r in parse_log(log).runs if "v_epc" in r and len(r) > 2]
fig, axes = plt.subplots(1, 2, figsize=(9, 3.3))
for run, (_, label, colour) in zip(runs, MODELS):
    t = run["Time"]
    axes[0].loglog(t[1:], run["v_epc"][1:], color=colour, label=label)
    axes[1].plot(t, run["c_q"], color=colour, label=label)
axes[0].set_xlabel("time")
axes[0].set_ylabel("energy per cell")
axes[1].set_xlabel("time")
axes[1].set_ylabel("mean shape index q")
axes[1].axhline(3.9, color="grey", ls=":", lw=1, label="p0 = 3.9")
for ax in axes:
    ax.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(FIG, "vertex_voronoi_energy.png"), dpi=110)

fig, axes = plt.subplots(2, 2, figsize=(7.6, 7.2))
for row, (model, label, _) in zip(axes, MODELS):
    pairs = paired_frames(os.path.join(HERE, "dump.vertex_voronoi." + model),
                          os.path.join(HERE, "dump.vertex_voronoi.%s.edges" % model))
    for ax, (atoms, local) in zip(row, (pairs[0], pairs[-1])):
        draw_tessellation(ax, atoms, junction_tessellation(atoms, local), field="shape",
                          vmin=3.6, vmax=4.4, colorbar=False)
        ax.set_title("%s, t = %g" % (label, atoms.timestep * 0.01))
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_xlabel("")
        ax.set_ylabel("")
fig.tight_layout()
fig.savefig(os.path.join(FIG, "vertex_voronoi_tissues.png"), dpi=80)
print("wrote figures/vertex_voronoi_energy.png, figures/vertex_voronoi_tissues.png")
