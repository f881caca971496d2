#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Analysis and pictures of examples/flow_pillars.

From dump.flow (cells and pillar, every 50 steps from t = 50 on): the
time-averaged velocity field on a grid (the mean velocity of the cell
centres found in each bin), drawn as streamlines over the tissue
(figures/flow_field.png) with its profiles: the velocity across the gap
beside the pillar and midway between pillars, along the line through the
pillar (its wake), and the number flux through each cross-section
(figures/flow_profiles.png).  From out/sweep_*.dat (./run's runs at other
forces and p0), the mean velocity against the drive
(figures/flow_mobility.png).  The numbers are printed and written to
flow_summary.txt."""

import glob
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

GAMMA = 1.0      # fix brownian ... gamma_t 1.0
BIN = 0.5        # grid spacing of the coarse-grained field


def read_params(log):
    """F, Rp, p0 and dt as the run used them (the line in.flow prints)."""
    with open(log) as f:
        for line in f:
            if line.startswith("PARAMS "):
                w = line.split()[1:]
                return {k: float(v) for k, v in zip(w[::2], w[1::2])}
    raise SystemExit(f"{log}: no PARAMS line (run in.flow first)")


def coarse_grain(frames, nbx, nby, dt):
    """Sums over successive pairs of frames of the time the cells spent in
    each bin (at the midpoint of their step) and of their displacements
    between the frames, whose quotient is the velocity (what a PIV of the
    centres measures; single steps can be fast where two centres nearly
    meet, the displacement over many steps is what the tissue does); and the
    total time.  The time between two frames is from the dump's times
    (dump_modify time yes: an adaptive step gives uneven times), or steps
    times dt."""
    b = frames[0].box
    lx, ly = b.xhi - b.xlo, b.yhi - b.ylo
    count = np.zeros((nbx, nby))
    svx = np.zeros((nbx, nby))
    svy = np.zeros((nbx, nby))
    total = 0.0
    for a, c in zip(frames[:-1], frames[1:]):
        if a.time is not None and c.time is not None:
            tau = c.time - a.time
        else:
            tau = (c.timestep - a.timestep) * dt
        total += tau
        ddx = c["x"] - a["x"]
        ddy = c["y"] - a["y"]
        ddx -= lx * np.round(ddx / lx)
        ddy -= ly * np.round(ddy / ly)
        x = np.mod(a["x"] + 0.5 * ddx - b.xlo, lx)
        y = np.mod(a["y"] + 0.5 * ddy - b.ylo, ly)
        i = np.minimum((x / lx * nbx).astype(int), nbx - 1)
        j = np.minimum((y / ly * nby).astype(int), nby - 1)
        np.add.at(count, (i, j), tau)
        np.add.at(svx, (i, j), ddx)
        np.add.at(svy, (i, j), ddy)
    return count, svx, svy, total


def main():
    params = read_params(os.path.join(HERE, "log.flow.1"))
    F, rp = params["F"], params["Rp"]
    v0 = F / GAMMA                      # the speed of a tissue without pillars
    frames = read_dump(os.path.join(HERE, "dump.flow"), cell_types={1})
    b = frames[0].box
    lx, ly = b.xhi - b.xlo, b.yhi - b.ylo
    pillar = frames[0].particles
    xp, yp = pillar["x"][0] - b.xlo, pillar["y"][0] - b.ylo
    ncell = len(frames[0])
    nf = len(frames)
    t0, t1 = frames[0].timestep, frames[-1].timestep
    moved = max(np.max(np.abs(fr.particles["x"] - pillar["x"])) + np.max(np.abs(fr.particles["y"] - pillar["y"]))
                for fr in frames)

    nbx, nby = int(round(lx / BIN)), int(round(ly / BIN))
    dx, dy = lx / nbx, ly / nby
    count, svx, svy, total = coarse_grain(frames, nbx, nby, params["dt"])
    nf = len(frames) - 1
    # bins the cell centres hardly reach (inside the pillar's range) are left out
    sparse = count < 0.2 * np.median(count)
    with np.errstate(invalid="ignore", divide="ignore"):
        vx = np.where(sparse, np.nan, svx / count)   # mean velocity of the cells in a bin
        vy = np.where(sparse, np.nan, svy / count)
    jx = svx / (total * dx * dy)      # number flux density (cells per length per time)
    xs = (np.arange(nbx) + 0.5) * dx
    ys = (np.arange(nby) + 0.5) * dy

    vmean = svx.sum() / count.sum()
    # flux through each cross-section x = const: cells per unit time
    flux = jx.sum(axis=1) * dy
    flux_exact = ncell * vmean / lx    # its mean along x, exactly
    # the gap beside the pillar (the cells within one bin of the pillar's
    # cross-section) and midway between two pillars
    ip = int(xp // dx)
    im = int(((xp + 0.5 * lx) % lx) // dx)

    def slab_mean(i):
        s = [(i - 1) % nbx, i, (i + 1) % nbx]
        return svx[s].sum() / count[s].sum(), count[s].sum() / (total * 3 * dx * ly)

    v_gap, n_gap = slab_mean(ip)
    v_mid, n_mid = slab_mean(im)
    # beside the pillar (the cells within two cell sizes of its range, on its
    # cross-section), and ahead of it and in its wake: the cells within half
    # a cell size of the line through it, in windows one cell size long
    rx = (xs - xp + 0.5 * lx) % lx - 0.5 * lx
    ry = (ys - yp + 0.5 * ly) % ly - 0.5 * ly

    def region_mean(mx, my):
        m = np.outer(mx, my) & ~sparse
        return svx[m].sum() / count[m].sum()

    on_line = np.abs(ry) < 0.5
    across = np.abs(rx) < 0.75
    v_flank = region_mean(across, (np.abs(ry) > rp) & (np.abs(ry) < rp + 2.0))
    axis = [(lo, region_mean((rx > lo) & (rx < lo + 1.0), on_line))
            for lo in [-rp - 4.0 + k for k in range(4)] + [rp + k for k in range(4)]]
    with np.errstate(invalid="ignore", divide="ignore"):
        line = np.where(sparse[:, on_line].all(axis=1), np.nan,
                        svx[:, on_line].sum(axis=1) / count[:, on_line].sum(axis=1))
    # how close the cells came to the pillar
    dmin = min(np.min(np.hypot((fr["x"] - fr.particles["x"][0] + 0.5 * lx) % lx - 0.5 * lx,
                               (fr["y"] - fr.particles["y"][0] + 0.5 * ly) % ly - 0.5 * ly)) for fr in frames)

    flow = np.loadtxt(os.path.join(HERE, "flow.dat"))
    start = frames[0].time if frames[0].time is not None else t0 * params["dt"]
    fp = np.mean(flow[flow[:, 0] >= start - 1e-9, 3])   # the pillar's drag over the same times

    lines = [
        f"# examples/flow_pillars: N = {ncell} cells, box {lx:.3f} x {ly:.3f}, pillar range Rp = {rp}, "
        f"drive F = {F} (free speed F/gamma = {v0})",
        f"# time average over {nf} frames (steps {t0} to {t1})",
        f"pillar_moved {moved:.3g}",
        f"closest_cell_to_pillar {dmin:.4f}",
        f"mean_vx {vmean:.5f}",
        f"mobility_fraction {vmean / v0:.4f}",
        f"pillar_drag_fraction {fp / (ncell * F):.4f}",
        f"force_balance_fraction {1 - fp / (ncell * F):.4f}",
        f"flux_mean {flux_exact:.5f}",
        f"flux_spread {np.ptp(flux) / flux_exact:.4f}",
        f"v_gap {v_gap:.5f}",
        f"v_midway {v_mid:.5f}",
        f"gap_speedup {v_gap / v_mid:.4f}",
        f"density_gap_over_midway {n_gap / n_mid:.4f}",
        f"continuity_prediction {ly / (ly - 2 * rp):.4f}",
        f"v_flank {v_flank:.5f}",
        f"flank_speedup {v_flank / vmean:.4f}",
    ]
    lines += [f"axis_vx_over_mean x-x_pillar {lo:+.1f} {lo + 1:+.1f} {v / vmean:.4f}" for lo, v in axis]

    sweep = []
    for path in sorted(glob.glob(os.path.join(HERE, "out", "sweep_*.dat"))):
        p0, f = (float(w) for w in os.path.basename(path)[len("sweep_"):-len(".dat")].split("_"))
        d = np.loadtxt(path)
        d = d[d[:, 0] >= 0.5 * d[-1, 0]]
        sweep.append((p0, f, np.mean(d[:, 1]) / (f / GAMMA)))
    for p0, f, m in sorted(sweep):
        lines.append(f"sweep p0 {p0} F {f} mobility_fraction {m:.4f}")
    text = "\n".join(lines) + "\n"
    print(text, end="")
    with open(os.path.join(HERE, "flow_summary.txt"), "w") as out:
        out.write(text)

    fig_dir = os.path.join(HERE, "figures")
    os.makedirs(fig_dir, exist_ok=True)

    # 1. the streamlines of the time-averaged field over the last frame's cells
    last = frames[-1]
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    tess = tessellate_frame(last)
    draw_tessellation(ax, last, tess, field="none", colorbar=False, edgecolor="0.6")
    speed = np.ma.masked_invalid(np.hypot(vx, vy) / v0)
    X, Y = np.meshgrid(xs + b.xlo, ys + b.ylo)
    strm = ax.streamplot(X, Y, np.ma.masked_invalid(vx).T, np.ma.masked_invalid(vy).T, color=speed.T, cmap="viridis",
                         density=1.6, linewidth=1.2, arrowsize=0.9)
    fig.colorbar(strm.lines, ax=ax, label=r"time-averaged speed $|\bar v|\,/\,(F/\gamma)$", shrink=0.8)
    ax.add_patch(plt.Circle((xp + b.xlo, yp + b.ylo), rp, color="k", alpha=0.25))
    ax.plot(xp + b.xlo, yp + b.ylo, "ko", ms=7)
    ax.set_xlim(b.xlo, b.xhi)
    ax.set_ylim(b.ylo, b.yhi)
    ax.set_aspect("equal")
    ax.set_title(f"cells driven along +x past a pillar (periodic box: an array of pillars), "
                 f"$\\langle v_x\\rangle$ = {vmean / v0:.2f} F/$\\gamma$", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(fig_dir, "flow_field.png"), dpi=110)
    plt.close(fig)

    # 2. profiles
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.6))
    ax = axes[0]
    for i, lab, c in ((ip, "beside the pillar (gap)", "C3"), (im, "midway between pillars", "C0")):
        s = [(i - 1) % nbx, i, (i + 1) % nbx]
        with np.errstate(invalid="ignore", divide="ignore"):
            prof = np.where(sparse[s].all(axis=0), np.nan, svx[s].sum(axis=0) / count[s].sum(axis=0))
        ax.plot(ys - yp, prof / v0, "o-", ms=3, color=c, label=lab)
    ax.axvspan(-rp, rp, color="0.85")
    ax.axhline(vmean / v0, color="k", ls=":", label="mean")
    ax.set_xlabel("y - y(pillar)")
    ax.set_ylabel(r"$\bar v_x\,/\,(F/\gamma)$")
    ax.legend(fontsize=8)
    ax = axes[1]
    ax.plot(rx, line / v0, "o-", ms=3, color="C2", label="on the line through the pillar")
    ax.axvspan(-rp, rp, color="0.85")
    ax.axhline(vmean / v0, color="k", ls=":", label="mean")
    ax.set_xlabel("x - x(pillar)   (flow →)")
    ax.set_ylabel(r"$\bar v_x\,/\,(F/\gamma)$")
    ax.legend(fontsize=8)
    ax = axes[2]
    ax.plot(xs - xp, flux / flux_exact, "o-", ms=3, color="k", label="flux through x = const")
    with np.errstate(invalid="ignore", divide="ignore"):
        slab_v = svx.sum(axis=1) / count.sum(axis=1)
    ax.plot(xs - xp, slab_v / vmean, "s-", ms=3, color="C3", label=r"mean $v_x$ of the cells at x")
    ax.axvspan(-rp, rp, color="0.85")
    ax.set_xlabel("x - x(pillar)")
    ax.set_ylabel("relative to the mean")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(fig_dir, "flow_profiles.png"), dpi=100)
    plt.close(fig)

    # 3. mobility against drive
    if sweep:
        fig, ax = plt.subplots(figsize=(5, 3.5))
        for p0 in sorted({p0 for p0, _, _ in sweep}, reverse=True):
            pts = sorted((f, m) for q, f, m in sweep if q == p0)
            phase = "fluid" if p0 > 3.81 else "solid"
            ax.plot(*zip(*pts), "o-", label=f"p0 = {p0} ({phase})")
        ax.set_xscale("log")
        forces = sorted({f for _, f, _ in sweep})
        ax.set_xticks(forces)
        ax.set_xticklabels([f"{f:g}" for f in forces])
        ax.minorticks_off()
        ax.set_xlabel(r"drive per cell $F$")
        ax.set_ylabel(r"$\langle v_x\rangle\,/\,(F/\gamma)$")
        ax.set_ylim(0, 1)
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(fig_dir, "flow_mobility.png"), dpi=100)
        plt.close(fig)
    print("wrote flow_summary.txt, figures/flow_field.png, figures/flow_profiles.png"
          + (", figures/flow_mobility.png" if sweep else ""))


if __name__ == "__main__":
    main()
