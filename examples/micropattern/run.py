#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""examples/micropattern: run in.micropattern for several cell numbers N and
measure how persistently each colony rotates.

    ./run.py                      N = 1 2 3 4 5 6 8 10, 3 seeds, t = 2000 each (about 2 min)
    ./run.py --n 2 6 --tend 500   fewer and shorter runs

Each run's log, rot.dat (Omega, phi against time) and dump go to out/ (as
out/log.micropattern.N<N>.<k>, out/rot_<N>_<k>.dat, out/dump.micropattern.N<N>.<k>);
persistence.dat gets N, the mean |phi| (how rotational the motion is), the
correlation times of phi and of Omega (the lag where the autocorrelation falls
below 1/e: how long a rotation keeps its sense) and the number of reversals per unit
time (sign changes of phi averaged over a window of 10 time units), each the mean
over runs with different seeds (start and noise; min and max of tau(phi) too).
The figure figures/micropattern.png shows phi(t) for a few N and tau, |phi|
against N.
"""

import argparse
import os
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
LMP = os.environ.get("LMP", os.path.join(HERE, "..", "..", "build", "lammps", "tessera-lmp"))


def correlation_time(series, dt):
    """The lag where the autocorrelation <s(t) s(t+lag)> / <s^2> (about zero, not about the
    mean: a reversal is a change of sign) first falls below 1/e."""
    n = len(series)
    acf = np.correlate(series, series, "full")[n - 1:] / np.arange(n, 0, -1)
    acf /= acf[0]
    below = np.nonzero(acf < np.exp(-1.0))[0]
    return below[0] * dt if len(below) else float("inf")


def measure(data, window=10.0):
    """(mean |phi|, tau of phi, tau of Omega, reversals per unit time) of a rot.dat table."""
    t, omega, phi = data[:, 0], data[:, 1], data[:, 2]
    dt = t[1] - t[0]
    tau_phi, tau = correlation_time(phi, dt), correlation_time(omega, dt)
    k = max(1, int(round(window / dt)))
    smooth = np.convolve(phi, np.ones(k) / k, mode="valid")
    signs = np.sign(smooth[smooth != 0])
    reversals = np.count_nonzero(np.diff(signs)) / (t[-1] - t[0])
    return float(np.mean(np.abs(phi))), float(tau_phi), float(tau), float(reversals)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, nargs="+", default=[1, 2, 3, 4, 5, 6, 8, 10])
    ap.add_argument("--tend", type=float, default=2000.0)
    ap.add_argument("--seeds", type=int, nargs="+", default=[4821, 5113, 7919],
                    help="one run per seed and N (starts, noise); the table gives mean, min and max")
    ap.add_argument("--no-run", action="store_true", help="only measure and plot the rot_N.dat files")
    args = ap.parse_args()
    os.chdir(HERE)
    rows = []
    for n in args.n:
        per_seed = []
        for k, seed in enumerate(args.seeds):
            name = os.path.join("out", f"rot_{n}_{k}.dat")
            if not args.no_run:
                os.makedirs("out", exist_ok=True)
                cmd = [os.path.abspath(LMP), "-in", "../in.micropattern", "-log", f"log.micropattern.N{n}.{k}",
                       "-screen", "none", "-var", "N", str(n), "-var", "tend", str(args.tend),
                       "-var", "seed", str(seed)]
                done = subprocess.run(cmd, cwd="out")
                if done.returncode != 0:
                    sys.exit(f"run.py: {' '.join(cmd)} (in out/) failed")
                shutil.move(os.path.join("out", "rot.dat"), name)
                shutil.move(os.path.join("out", "dump.micropattern"),
                            os.path.join("out", f"dump.micropattern.N{n}.{k}"))
            per_seed.append(measure(np.loadtxt(name)))
        m = np.array(per_seed)
        rows.append((n, m[:, 0].mean(), m[:, 1].mean(), m[:, 1].min(), m[:, 1].max(), m[:, 2].mean(),
                     m[:, 3].mean()))
        print(f"N = {n:2d}: mean |phi| {m[:, 0].mean():.3f}, tau(phi) {m[:, 1].mean():7.1f} "
              f"({m[:, 1].min():.1f} .. {m[:, 1].max():.1f}), tau(Omega) {m[:, 2].mean():7.1f}, "
              f"reversals per unit time {m[:, 3].mean():.4f}  ({len(m)} runs)")
    np.savetxt("persistence.dat", np.array(rows), fmt=["%d", "%.4f", "%.2f", "%.2f", "%.2f", "%.2f", "%.5f"],
               header="N mean|phi| tau_phi(mean) tau_phi(min) tau_phi(max) tau_Omega(mean) "
                      "reversals_per_time, means over the seeds' runs (examples/micropattern/run.py)")
    plot(rows)


def plot(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    os.makedirs("figures", exist_ok=True)
    shown = [r[0] for r in rows if r[0] in (2, 5, 10)] or [rows[0][0]]
    fig = plt.figure(figsize=(10, 4.2))
    grid = fig.add_gridspec(len(shown), 2)
    for k, n in enumerate(shown):
        a = fig.add_subplot(grid[k, 0])
        d = np.loadtxt(os.path.join("out", f"rot_{n}_0.dat"))
        keep = d[:, 0] <= min(d[-1, 0], 1000.0)
        a.plot(d[keep, 0], d[keep, 2], lw=0.5, color=f"C{k}")
        a.set_ylim(-1.1, 1.1)
        a.set_ylabel(r"$\phi$")
        a.text(0.01, 0.05, f"N = {n}", transform=a.transAxes, fontsize=8)
        if k < len(shown) - 1:
            a.set_xticklabels([])
        else:
            a.set_xlabel("time")
    b = fig.add_subplot(grid[:, 1])
    ns = np.array([r[0] for r in rows])
    taus = np.array([r[2] for r in rows])
    err = np.clip(np.array([[r[2] - r[3] for r in rows], [r[4] - r[2] for r in rows]]), 0.0, None)
    b.errorbar(ns, taus, yerr=err, fmt="o-", capsize=3, label=r"$\tau_\phi$ (mean, min..max of the runs)")
    b.set_yscale("log")
    b.semilogy(ns, [r[5] for r in rows], "^:", color="C2", label=r"$\tau_\Omega$")
    b.set_xlabel("cells on the island N")
    b.set_ylabel(r"correlation time of $\phi$, $\Omega$")
    c = b.twinx()
    c.plot(ns, [r[1] for r in rows], "s--", color="C1", label=r"mean $|\phi|$")
    c.set_ylabel(r"mean $|\phi|$", color="C1")
    c.set_ylim(0, 1)
    b.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig("figures/micropattern.png", dpi=150)
    print("wrote figures/micropattern.png, persistence.dat")
    snapshots(shown)


def snapshots(ns, radius=0.8):
    """The last dumped frame of the first seed's run for each N: finite cells (tessera-tools),
    polarity arrows, the island's edge dashed."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle

    sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
    from tessera_tools.dump import read_frame
    from tessera_tools.render import draw_tessellation, tessellate_frame

    ns = [n for n in ns if os.path.exists(os.path.join("out", f"dump.micropattern.N{n}.0"))]
    if not ns:
        return
    fig, axes = plt.subplots(1, len(ns), figsize=(3.3 * len(ns), 3.4))
    for ax, n in zip(np.atleast_1d(axes), ns):
        frame = read_frame(os.path.join("out", f"dump.micropattern.N{n}.0"))
        tess = tessellate_frame(frame, radius)
        draw_tessellation(ax, frame, tess, field="none", arrows=("mux", "muy"), colorbar=False)
        big = np.sqrt(n / np.pi)
        ax.add_patch(Circle((0, 0), big, fill=False, ls="--", color="0.4"))
        ax.set_xlim(-big - 1, big + 1)
        ax.set_ylim(-big - 1, big + 1)
        ax.set_aspect("equal")
        ax.set_title(f"N = {n}, t = {frame.timestep * 0.01:g}", fontsize=9)
    fig.tight_layout()
    fig.savefig("figures/micropattern_cells.png", dpi=150)
    print("wrote figures/micropattern_cells.png")


if __name__ == "__main__":
    main()
