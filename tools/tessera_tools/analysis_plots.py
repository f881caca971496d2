# SPDX-License-Identifier: GPL-2.0-or-later
"""Figures of the commands flux, velocity, msd, holes and divisions (in the style of
:mod:`tessera_tools.plots`: reduced units, 300 dpi, an optional vector copy)."""

import numpy as np

from .plots import STEP, TIME, _plt, panel_letters, save

LENGTH = r"($\sqrt{A_0}$)"


def plot_flux(res, times, out, known=True, dpi=300, vector=None, title=None, label="atoms"):
    """Cumulative net crossings of each section against time, and the flux against the
    sections' positions with error bars."""
    plt = _plt()
    fig, (a, b) = plt.subplots(1, 2, figsize=(9.0, 3.4))
    for s, c in enumerate(res["sections"]):
        a.plot(times, res["cumulative"][:, s], lw=1.2, label=f"{res['axis']} = {c:g}")
    a.axhline(0.0, color="0.6", lw=0.6)
    a.set_xlabel(TIME if known else STEP)
    a.set_ylabel(f"net crossings in +{res['axis']}")
    if len(res["sections"]) <= 8:
        a.legend(frameon=False, fontsize=8)
    err = np.where(np.isfinite(res["flux_err"]), res["flux_err"], 0.0)
    b.errorbar(res["sections"], res["flux"], yerr=err, fmt="o", ms=4, capsize=3, color="C0")
    b.axhline(0.0, color="0.6", lw=0.6)
    b.set_xlabel(f"section {res['axis']} {LENGTH}")
    b.set_ylabel(f"{label} per unit {'time' if known else 'timestep'}")
    panel_letters([a, b])
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    save(fig, out, dpi, vector)


def plot_velocity_field(field, box, out, dpi=300, vector=None, title=None):
    """Arrows of the binned mean velocity on the box outline, coloured by speed."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.4, 5.0 * box.ly / max(box.lx, box.ly) + 0.6))
    c = box.corners()
    ax.plot(np.append(c[:, 0], c[0, 0]), np.append(c[:, 1], c[0, 1]), color="0.5", lw=0.8)
    ok = field["count"] > 0
    x, y = field["centres"][..., 0][ok], field["centres"][..., 1][ok]
    u, v = field["vx"][ok], field["vy"][ok]
    speed = np.hypot(u, v)
    q = ax.quiver(x, y, u, v, speed, cmap="viridis", angles="xy", pivot="mid")
    cb = fig.colorbar(q, ax=ax, shrink=0.8)
    cb.set_label("speed")
    ax.set_aspect("equal")
    ax.set_xlabel(f"$x$ {LENGTH}")
    ax.set_ylabel(f"$y$ {LENGTH}")
    if title:
        ax.set_title(title)
    save(fig, out, dpi, vector)


def plot_msd_drift(res, fit, out, known=True, dpi=300, vector=None, title=None):
    """MSD with and without the drift against lag time (log axes, error bars, the fitted
    4 D tau), and the mean displacement with the drift line V tau."""
    plt = _plt()
    fig, (a, b) = plt.subplots(1, 2, figsize=(9.0, 3.6))
    tau = res["tau"]
    ok = np.isfinite(res["msd"]) & (res["msd"] > 0)
    a.errorbar(tau[ok], res["msd"][ok], yerr=np.nan_to_num(res["msd_err"][ok]), fmt="o", ms=3, capsize=2,
               label="MSD")
    ok2 = np.isfinite(res["msd_nodrift"]) & (res["msd_nodrift"] > 0)
    a.errorbar(tau[ok2], res["msd_nodrift"][ok2], yerr=np.nan_to_num(res["msd_nodrift_err"][ok2]), fmt="s",
               ms=3, capsize=2, label="drift removed")
    if fit is not None and fit["D"] > 0:
        a.plot(tau, 4 * fit["D"] * tau, "k--", lw=0.8, label=f"$4 D \\tau$, D = {fit['D']:.3g}")
    a.set_xscale("log")
    a.set_yscale("log")
    a.set_xlabel(r"lag $\tau$ " + ("" if known else "(timesteps)"))
    a.set_ylabel(r"MSD ($A_0$)")
    a.legend(frameon=False, fontsize=8)
    for k, name in enumerate(("x", "y")):
        b.plot(tau, res["mean"][:, k], "o", ms=3, color=f"C{k}", label=fr"$\langle \Delta {name} \rangle$")
        b.plot(tau, res["drift"][k] * tau, "-", lw=0.8, color=f"C{k}")
    b.axhline(0.0, color="0.6", lw=0.6)
    b.set_xlabel(r"lag $\tau$")
    b.set_ylabel(f"mean displacement {LENGTH}")
    b.legend(frameon=False, fontsize=8)
    panel_letters([a, b])
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    save(fig, out, dpi, vector)


def plot_holes(rows, out, known=True, dpi=300, vector=None, title=None):
    """Area and length of the hole around each particle against time, one line per particle."""
    plt = _plt()
    fig, (a, b) = plt.subplots(1, 2, figsize=(9.0, 3.4))
    ids = sorted({r["id"] for r in rows})
    for i in ids:
        mine = [r for r in rows if r["id"] == i]
        t = [r["time"] for r in mine]
        a.plot(t, [r["area"] for r in mine], "-o", ms=2, lw=1.0, label=f"{i}")
        b.plot(t, [r["length"] for r in mine], "-o", ms=2, lw=1.0)
    a.set_xlabel(TIME if known else STEP)
    a.set_ylabel(r"hole area ($A_0$)")
    b.set_xlabel(TIME if known else STEP)
    b.set_ylabel(f"hole boundary length {LENGTH}")
    if len(ids) <= 10:
        a.legend(title="particle", frameon=False, fontsize=7)
    panel_letters([a, b])
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    save(fig, out, dpi, vector)


def plot_divisions(table, hist, out, known=True, dpi=300, vector=None, title=None):
    """Where the divisions happened (x-y, or longitude-latitude on a sphere), coloured by time,
    and the division rate against time with Poisson error bars."""
    plt = _plt()
    fig, (a, b) = plt.subplots(1, 2, figsize=(9.4, 3.6))
    if table["centre"] is not None:
        px, py = table["longitude"], table["latitude"]
        a.set_xlim(-180, 180)
        a.set_ylim(-90, 90)
        a.set_xlabel("longitude (degrees)")
        a.set_ylabel("latitude (degrees)")
    else:
        px, py = table["x"], table["y"]
        a.set_aspect("equal")
        a.set_xlabel(f"$x$ {LENGTH}")
        a.set_ylabel(f"$y$ {LENGTH}")
    sc = a.scatter(px, py, c=table["time"], s=8, cmap="viridis")
    cb = fig.colorbar(sc, ax=a, shrink=0.85)
    cb.set_label("time" if known else "timestep")
    edges, rate, err = hist
    b.errorbar(0.5 * (edges[1:] + edges[:-1]), rate, yerr=err, fmt="o", ms=3, capsize=2)
    b.set_xlabel(TIME)
    b.set_ylabel("divisions per unit time")
    panel_letters([a, b])
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    save(fig, out, dpi, vector)
