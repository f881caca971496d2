#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Pictures of examples/vertex_shear: stress and T1 count against strain
(figures/vertex_shear_stress.png) and the tissue before and after each yield, coloured
by shape index (figures/vertex_shear_tissue.png).  Reads log.vertex_shear.1 (or the log
given as argument), dump.vertex_shear and dump.vertex_shear.edges."""

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
RATE, DT = 0.02, 0.01
log = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "log.vertex_shear.1")

run = parse_log(log).runs[-1]
strain, stress, t1 = run["v_strain"], run["v_stress"], run["c_t1[1]"]
fig, ax = plt.subplots(figsize=(5.5, 3.4))
ax.plot(strain, stress, "k-", label="shear stress -pxy")
ax.set_xlabel("shear strain (rate x time)")
ax.set_ylabel("shear stress (K_A A0)")
ax2 = ax.twinx()
ax2.plot(strain, t1, "r--", label="T1s (cumulative)")
ax2.set_ylabel("T1s", color="r")
ax.legend(loc="upper left", fontsize=8)
ax2.legend(loc="lower right", fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(FIG, "vertex_shear_stress.png"), dpi=120)

pairs = paired_frames(os.path.join(HERE, "dump.vertex_shear"),
                      os.path.join(HERE, "dump.vertex_shear.edges"))
wanted = [0.0, 1.1, 1.2, 1.6]
chosen = [min(pairs, key=lambda p: abs(p[0].timestep * DT * RATE - s)) for s in wanted]
fig, axes = plt.subplots(1, len(chosen), figsize=(3.4 * len(chosen), 3.4))
for ax, (atoms, local) in zip(axes, chosen):
    tess = junction_tessellation(atoms, local)
    draw_tessellation(ax, atoms, tess, field="shape", vmin=3.7, vmax=4.3, colorbar=False)
    ax.set_title("strain %.2f" % (atoms.timestep * DT * RATE))
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_xlabel("")
    ax.set_ylabel("")
fig.tight_layout()
fig.savefig(os.path.join(FIG, "vertex_shear_tissue.png"), dpi=80)
print("wrote figures/vertex_shear_stress.png, figures/vertex_shear_tissue.png")
