# SPDX-License-Identifier: GPL-2.0-or-later
"""Figures of measurements (``tessera-tools plot ...``), in the style of the studies' figures:
axes labelled with the model's reduced units, print resolution (300 dpi) and an optional
vector copy.  Each function takes numbers (see :mod:`tessera_tools.measure`), writes one file
and returns what it drew, so tests can check the data."""

import math
import os

import numpy as np

#: axis labels in the model's reduced units (doc/model.md, Units)
TIME = r"time $t$ ($\gamma_T/(K A_0)$)"
STEP = "timestep"
AREA = r"($A_0$)"
LENGTH2 = r"($A_0$)"
Q_HEX = math.sqrt(8 * math.sqrt(3))
Q_STAR = 3.81


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save(fig, out, dpi=300, vector=None):
    """Write ``out`` (tight bounding box) and, with ``vector`` ('pdf' or 'svg'), a copy next to it."""
    plt = _plt()
    fig.savefig(out, dpi=dpi, bbox_inches="tight", pad_inches=0.05)
    if vector:
        ext = vector.lower().lstrip(".")
        if ext not in ("pdf", "svg", "eps"):
            raise ValueError(f"--vector {vector}: use pdf, svg or eps")
        fig.savefig(os.path.splitext(out)[0] + "." + ext, dpi=dpi, bbox_inches="tight", pad_inches=0.05)
    plt.close(fig)


def panel_letters(axes):
    for k, ax in enumerate(axes):
        ax.text(-0.02, 1.02, "abcdefgh"[k], transform=ax.transAxes, fontweight="bold", fontsize=12,
                ha="right", va="bottom")


def time_label(known):
    return TIME if known else STEP


def _plain_log_ticks(axis):
    """Ticks at 1, 2, 5 x 10^k written as plain numbers on a log axis."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    axis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_formatter(NullFormatter())


def plot_msd(t, msd, count, out, time_label=TIME, dpi=300, vector=None):
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.2, 3.6))
    ok = (t > 0) & np.isfinite(msd) & (msd > 0)
    ax.loglog(t[ok], msd[ok], "o-", ms=3, color="tab:blue")
    _plain_log_ticks(ax.xaxis)
    _plain_log_ticks(ax.yaxis)
    ax.set_xlabel(time_label)
    ax.set_ylabel(r"MSD $\langle |\Delta r|^2\rangle$ " + LENGTH2)
    if count.min() != count.max():
        ax.set_title(f"over cells present at both times ({int(count.min())}-{int(count.max())})", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    save(fig, out, dpi, vector)
    return t[ok], msd[ok]


def plot_wound(t, area, out, ylabel, xlabel=TIME, half=None, dpi=300, vector=None, title=None):
    """Open (wound, hole) area against time, the half-closure time marked."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.2, 3.6))
    ax.plot(t, area, "-", color="k", lw=1.4)
    ax.axhline(0.0, color="0.6", lw=0.8)
    if half is not None and np.isfinite(half):
        ax.axvline(half, color="tab:red", ls="--", lw=1.0, label=f"half closed at t = {half:.3g}")
        ax.plot([half], [0.5 * area[0]], "o", color="tab:red", ms=5)
        ax.legend(frameon=False)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_xlim(t[0], t[-1])
    if title:
        ax.set_title(title, fontsize=11)
    save(fig, out, dpi, vector)
    return t, area


def plot_growth(t, n, fit, out, xlabel=TIME, dpi=300, vector=None, title=None):
    """N(t) on a log axis with the fitted exponential over its range."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.2, 3.6))
    ax.semilogy(t, n, "o", ms=3.5, color="tab:blue", label="cells $N$")
    tt = np.linspace(fit["tmin"], fit["tmax"], 100)
    label = (f"fit $N_0 e^{{rt}}$, $r$ = {fit['rate']:.4g} $\\pm$ {fit['rate_err']:.2g}\n"
             f"doubling time {fit['doubling']:.3g} $\\pm$ {fit['doubling_err']:.2g}")
    ax.semilogy(tt, fit["N0"] * np.exp(fit["rate"] * tt), "-", color="tab:red", lw=1.4, label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("number of cells $N$")
    _plain_log_ticks(ax.yaxis)
    # growth runs from lower left to upper right: the upper left is free
    ax.legend(frameon=False, fontsize=9, loc="upper left")
    ax.grid(alpha=0.3, which="both")
    if title:
        ax.set_title(title, fontsize=11)
    save(fig, out, dpi, vector)
    return tt, fit["N0"] * np.exp(fit["rate"] * tt)


def plot_shape(q, z, rim, out, dpi=300, vector=None, bins=40, title=None):
    """Histograms of the shape index and of the neighbour number, interior and rim apart when
    there is a rim.  Returns {group: (q, z)}."""
    plt = _plt()
    groups = {"all cells": np.ones(len(q), dtype=bool)} if not rim.any() else \
        {"interior": ~rim, "rim (free edge)": rim}
    colours = {"all cells": "tab:blue", "interior": "tab:blue", "rim (free edge)": "tab:orange"}
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    lo = min(3.5, float(np.nanmin(q)))
    hi = max(4.4, float(np.nanmax(q)))
    for name, sel in groups.items():
        if not sel.any():
            continue
        axes[0].hist(q[sel], bins=bins, range=(lo, hi), density=True, histtype="stepfilled", alpha=0.45,
                     color=colours[name], edgecolor=colours[name],
                     label=f"{name}: {int(sel.sum())}, mean {np.mean(q[sel]):.4g}")
    axes[0].axvline(Q_HEX, color="0.3", ls=":", lw=1.0, label=f"hexagon {Q_HEX:.4f}")
    axes[0].axvline(Q_STAR, color="0.3", ls="--", lw=1.0, label="3.81")
    axes[0].set_xlabel(r"shape index $q = P/\sqrt{A}$")
    axes[0].set_ylabel("probability density")
    axes[0].legend(frameon=False, fontsize=8)
    zs = np.arange(max(3, int(np.nanmin(z))), int(np.nanmax(z)) + 1)
    width = 0.8 / len(groups)
    for k, (name, sel) in enumerate(groups.items()):
        if not sel.any():
            continue
        frac = np.array([np.mean(z[sel] == v) for v in zs])
        axes[1].bar(zs + (k - (len(groups) - 1) / 2) * width, frac, width=width, color=colours[name],
                    alpha=0.8, label=f"{name}: mean {np.mean(z[sel]):.3g}")
    axes[1].set_xticks(zs)
    axes[1].set_xlabel("number of neighbours $z$")
    axes[1].set_ylabel("fraction of cells")
    axes[1].legend(frameon=False, fontsize=8)
    panel_letters(axes)
    if title:
        fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    save(fig, out, dpi, vector)
    return {name: (q[sel], z[sel]) for name, sel in groups.items()}


def plot_demix(series, out, xlabel=TIME, dpi=300, vector=None, reference=None, title=None):
    """Heterotypic junction fraction against time; ``series``: list of (label, t, fraction);
    ``reference``: a horizontal line (e.g. the fraction of a random mixture)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.2, 3.6))
    for label, t, f in series:
        ax.plot(t, f, "-", lw=1.4, label=label)
    if reference is not None:
        ax.axhline(reference, color="0.4", ls="--", lw=1.0, label=f"random mixture {reference:.3g}")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("heterotypic junction fraction")
    ax.set_ylim(bottom=0)
    if len(series) > 1 or reference is not None:
        ax.legend(frameon=False, fontsize=9)
    if title:
        ax.set_title(title, fontsize=11)
    save(fig, out, dpi, vector)
    return series


def plot_moduli(rows, out, unit=r"$K_A A_0$", dpi=300, vector=None, title=None):
    """G and B against p0 with error bars, one line per route; ``rows``: dicts with p0, route,
    G, G_err, B, B_err (reduced units).  Returns {route: (p0, G, G_err, B, B_err)} as drawn."""
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    drawn = {}
    # the routes agree closely: open circles with a line, crosses without, so both stay visible
    styles = {"hessian": (dict(fmt="o-", ms=8, mfc="none", mew=1.4, lw=1.2, capsize=4), "tab:blue", "exact Hessian"),
              "quasistatic": (dict(fmt="x", ms=6, mew=1.4, capsize=2, elinewidth=0.8), "k", "quasistatic steps")}
    for route in ("hessian", "quasistatic"):
        rs = sorted((r for r in rows if r["route"] == route), key=lambda r: r["p0"])
        if not rs:
            continue
        p0 = np.array([r["p0"] for r in rs])
        cols = {k: np.array([r[k] for r in rs], dtype=float) for k in ("G", "G_err", "B", "B_err")}
        style, colour, label = styles[route]
        for ax, key in zip(axes, ("G", "B")):
            err = np.nan_to_num(cols[key + "_err"], nan=0.0)
            ax.errorbar(p0, cols[key], yerr=err, color=colour, label=label, **style)
        drawn[route] = (p0, cols["G"], cols["G_err"], cols["B"], cols["B_err"])
    for ax, name in zip(axes, ("shear modulus $G$", "bulk modulus $B$")):
        ax.axvline(Q_STAR, color="0.4", ls="--", lw=0.9, label=r"$p_0 = 3.81$")
        ax.set_xlabel(r"target shape index $p_0$")
        ax.set_ylabel(f"{name} ({unit})")
        ax.legend(frameon=False, fontsize=9)
    axes[0].axhline(0.0, color="0.6", lw=0.8)
    panel_letters(axes)
    if title:
        fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    save(fig, out, dpi, vector)
    return drawn


def plot_kymograph(kymo, out, dpi=300, vector=None, title=None, cmap="viridis"):
    """Two panels against time (vertical) and position along the axis (horizontal): the binned
    column and the cell density (cells per unit area), each with its colour bar; empty bins
    are grey.  Returns the two images (matplotlib QuadMesh)."""
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 4.2), sharey=True)
    t = kymo.times
    if len(t) > 1:
        tedges = np.concatenate([[t[0] - 0.5 * (t[1] - t[0])], 0.5 * (t[1:] + t[:-1]),
                                 [t[-1] + 0.5 * (t[-1] - t[-2])]])
    else:
        tedges = np.array([t[0] - 0.5, t[0] + 0.5])
    drawn = []
    for ax, data, label, cm in ((axes[0], kymo.values, kymo.column, cmap),
                                (axes[1], kymo.density, r"density (cells per unit area)", "magma")):
        colours = plt.get_cmap(cm).copy()
        colours.set_bad("0.75")
        mesh = ax.pcolormesh(kymo.edges, tedges, np.ma.masked_invalid(data), cmap=colours, shading="flat")
        fig.colorbar(mesh, ax=ax, label=label)
        ax.set_xlabel(f"${kymo.axis}$ " + r"($\sqrt{A_0}$)")
        drawn.append(mesh)
    axes[0].set_ylabel(time_label(kymo.time_known))
    panel_letters(axes)
    if title:
        fig.suptitle(title)
    save(fig, out, dpi, vector)
    return drawn


def plot_field(frame, tess, column, out, view="box", cmap=None, vmin=None, vmax=None, dpi=300, vector=None,
               title=None):
    """The cells of one frame (``tess``: their polygons) coloured by a per-atom ``column`` (e.g. a
    species ``d_delta``) on a colour scale with its bar, drawn by the tessellation renderer.
    Returns (values of each cell, the PolyCollection, the index of the cell of each polygon)."""
    from .render import _figure, _tiles, _title, cell_field, draw_tessellation

    plt = _plt()
    values, _ = cell_field(frame, tess, column)
    fig, ax = _figure(frame.box, view)
    coll = draw_tessellation(ax, frame, tess, field=column, view=view, cmap=cmap or "viridis", vmin=vmin,
                             vmax=vmax, label=column, categorical=False)
    ax.set_title(_title(frame, column, title))
    fig.tight_layout()
    fig.canvas.draw()
    _, owner = _tiles(tess, view)
    fig.savefig(out, dpi=dpi)
    if vector:
        from .render import vector_path

        fig.savefig(vector_path(out, vector))
    plt.close(fig)
    return values, coll, owner
