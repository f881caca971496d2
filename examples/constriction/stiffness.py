#!/usr/bin/python3
# Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
"""Why the constriction chatters at every fixed timestep: a measurement.

For each timestep dt, in.constriction runs with fix brownian (forward Euler)
to t = 20, then 40 more steps are dumped every step.  From those steps:

* the cells whose successive displacements reverse (mean correlation of
  d_t . d_t+1 below -0.9), how far they move per step against the mean,
  where they are (distance to the nearest particle), and their perimeter
  tension 2 KP (P - p0) (compute vertex/atom);
* the Delaunay triangulation of the cell centres (scipy, periodic images) at
  each step: how many triangles change from one step to the next, and where
  the flipping triangles' circumcentres (Voronoi vertices) lie (distance to
  the nearest particle);
* how close the chattering cells' centres are to another cell's centre,
  the largest curvature of the Voronoi energy of the closest pair alone
  (times d^2: constant if it grows like 1/d^2), and the smallest angle of
  the flipping triangles;
* the linearisation of the force: the largest eigenvalue of the exact
  Hessian of the Voronoi energy (tessera-hessian, the cells alone, as the
  pair style tessellates them), of pair soft's (analytic: cells against the
  fixed particles) and of their sum, at six of the steps, against forward
  Euler's stability limit 2 gamma_t / dt.

Run from a copy of this directory (it writes probe_<dt>/):
    ./stiffness.py [--lmp ../../build/lammps/tessera-lmp] [--dt 0.01 0.005 0.0025 0.00125]
Prints a Markdown table (doc/model.md, "Chatter near stiff contacts", quotes it)."""

import argparse
import os
import subprocess
import sys

import numpy as np
from scipy.spatial import Delaunay

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))

from tessera_tools.dump import read_dump  # noqa: E402
from tessera_tools.moduli import Model, run_hessian  # noqa: E402

KA, KP, P0, RP, AP, GAMMA = 1.0, 1.0, 3.9, 0.8, 5.0, 1.0
PROBE = """include in.constriction
unfix stop
compute c cells vertex/atom
dump p all custom 1 probe.dump id type x y xu yu c_c[2]
dump_modify p sort id format float %.17g
run 40
"""


def run(lmp, dt, directory):
    os.makedirs(directory, exist_ok=True)
    for name in ("in.constriction",):
        with open(os.path.join(HERE, name)) as f, open(os.path.join(directory, name), "w") as g:
            g.write(f.read())
    with open(os.path.join(directory, "in.probe"), "w") as f:
        f.write(PROBE)
    subprocess.run([lmp, "-in", "in.probe", "-var", "tol", "0", "-var", "dt", repr(dt), "-var", "tend",
                    "20", "-var", "every", "0", "-log", "log.probe", "-screen", "none"],
                   cwd=directory, check=True)
    return read_dump(os.path.join(directory, "probe.dump"))


def periodic(d, lx, ly):
    d = np.array(d, dtype=float)
    d[..., 0] -= lx * np.round(d[..., 0] / lx)
    d[..., 1] -= ly * np.round(d[..., 1] / ly)
    return d


def triangles(p, lx, ly):
    """Delaunay triangles (sorted index triples) with a corner among the
    original points, and a map triple -> circumcentre (near that corner)."""
    n = len(p)
    shifts = [(sx, sy) for sx in (-1, 0, 1) for sy in (-1, 0, 1)]
    q = np.vstack([p + [sx * lx, sy * ly] for sx, sy in shifts])
    owner = np.tile(np.arange(n), len(shifts))
    centre = shifts.index((0, 0))
    out = {}
    for simp in Delaunay(q).simplices:
        if not (simp // n == centre).any():
            continue
        key = tuple(sorted(owner[simp]))
        if key in out:
            continue
        a, b, c = q[simp]
        bx, by = b - a
        cx, cy = c - a
        d = 2 * (bx * cy - by * cx)
        ux = (cy * (bx * bx + by * by) - by * (cx * cx + cy * cy)) / d
        uy = (bx * (cx * cx + cy * cy) - cx * (bx * bx + by * by)) / d
        out[key] = a + [ux, uy]
    return out


def soft_hessian(p, walls, lx, ly):
    """Hessian of sum over (cell, particle) of Ap (1 + cos(pi r / Rp)), r < Rp."""
    h = np.zeros((2 * len(p), 2 * len(p)))
    k = np.pi / RP
    for i, x in enumerate(p):
        d = periodic(x - walls, lx, ly)
        r = np.hypot(d[:, 0], d[:, 1])
        for dd, rr in zip(d[r < RP], r[r < RP]):
            u = dd / rr
            e1 = -AP * k * np.sin(k * rr)
            e2 = -AP * k * k * np.cos(k * rr)
            h[2 * i:2 * i + 2, 2 * i:2 * i + 2] += e2 * np.outer(u, u) + e1 / rr * (np.eye(2) - np.outer(u, u))
    return h


def analyse(frames, dt):
    box = frames[0].box
    lx, ly = box.lx, box.ly
    cell = frames[0]["type"] == 1
    walls = np.column_stack([frames[0]["x"][~cell], frames[0]["y"][~cell]])
    xu = np.array([np.column_stack([f["xu"][cell], f["yu"][cell]]) for f in frames])
    d = np.diff(xu, axis=0)
    size = np.linalg.norm(d, axis=2)
    corr = (np.einsum("tnk,tnk->tn", d[1:], d[:-1]) / (size[1:] * size[:-1] + 1e-300)).mean(axis=0)
    chat = np.where(corr < -0.9)[0]
    pos = [np.column_stack([f["x"][cell], f["y"][cell]]) for f in frames]
    to_wall = np.array([np.hypot(*periodic(pos[0][i] - walls, lx, ly).T).min() for i in chat])
    perim = frames[0]["c_c[2]"][cell]
    tension = 2 * KP * (perim[chat] - P0)
    # triangulation flips between successive steps
    tris = [triangles(p, lx, ly) for p in pos[:9]]
    changed, centre_to_wall = [], []
    for t in range(8):
        gone = set(tris[t]) - set(tris[t + 1])
        changed.append(len(gone ^ (set(tris[t + 1]) - set(tris[t]))))
        for key in gone:
            centre_to_wall.append(np.hypot(*periodic(tris[t][key] - walls, lx, ly).T).min())
    # how close the chattering cells' centres come to another centre, and
    # the smallest angle of the triangles that flip
    nearest = []
    for i in chat:
        dd = periodic(pos[0] - pos[0][i], lx, ly)
        r = np.hypot(dd[:, 0], dd[:, 1])
        r[i] = np.inf
        nearest.append((r.min(), i, int(np.argmin(r))))
    nearest.sort()
    angles = []
    for t in range(8):
        for key in set(tris[t]) - set(tris[t + 1]):
            q = pos[t][list(key)].copy()
            q[1:] = q[0] + periodic(q[1:] - q[0], lx, ly)
            for k in range(3):
                u, v = q[(k + 1) % 3] - q[k], q[(k + 2) % 3] - q[k]
                angles.append(np.degrees(np.arccos(np.dot(u, v) / np.linalg.norm(u) / np.linalg.norm(v))))
    angles = np.array(angles).reshape(-1, 3).min(axis=1)
    # the force's linearisation
    model = Model.quadratic(KA, 1.0, KP, P0)
    dof = np.ravel(np.column_stack([2 * chat, 2 * chat + 1]))
    lam = {"vertex": [], "soft": [], "total": [], "vertex on them": []}
    for t in range(6):
        hv = run_hessian(box, pos[t], model).H.toarray()
        hs = soft_hessian(pos[t], walls, lx, ly)
        lam["vertex"].append(np.linalg.eigvalsh(hv)[-1])
        lam["soft"].append(np.linalg.eigvalsh(hs)[-1])
        lam["total"].append(np.linalg.eigvalsh(hv + hs)[-1])
        lam["vertex on them"].append(np.linalg.eigvalsh(hv[np.ix_(dof, dof)])[-1])
        if t == 0:    # the closest pair alone: its curvature times d^2
            d0, i, j = nearest[0]
            pair = [2 * i, 2 * i + 1, 2 * j, 2 * j + 1]
            pair_curv = np.linalg.eigvalsh(hv[np.ix_(pair, pair)])[-1] * d0 * d0
    return {
        "dt": dt, "limit": 2 * GAMMA / dt, "cells": int(cell.sum()), "chattering": len(chat),
        "move ratio": size[:, chat].mean() / size.mean(), "to particle": np.median(to_wall),
        "tension": np.mean(tension), "changed": np.mean(changed),
        "nearest": np.median([n[0] for n in nearest]), "closest": nearest[0][0],
        "pair": pair_curv, "angle": np.median(angles),
        "centre to particle": np.median(centre_to_wall) if centre_to_wall else float("nan"),
        **{k: float(np.mean(v)) for k, v in lam.items()}}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lmp", default=os.path.join(HERE, "..", "..", "build", "lammps", "tessera-lmp"))
    ap.add_argument("--dt", nargs="+", type=float, default=[0.01, 0.005, 0.0025, 0.00125])
    args = ap.parse_args()
    # each run starts in its own probe_<dt>/: a path relative to here would miss
    args.lmp = os.path.abspath(args.lmp) if os.sep in args.lmp else args.lmp
    rows = [analyse(run(args.lmp, dt, f"probe_{dt:g}"), dt) for dt in args.dt]
    cols = [("dt", "{:g}"), ("limit", "{:.0f}"), ("chattering", "{:d}"), ("move ratio", "{:.1f}"),
            ("to particle", "{:.2f}"), ("tension", "{:.2f}"), ("changed", "{:.1f}"),
            ("nearest", "{:.3f}"), ("closest", "{:.3f}"), ("pair", "{:.3f}"), ("angle", "{:.1f}"), ("centre to particle", "{:.2f}"), ("vertex", "{:.0f}"),
            ("vertex on them", "{:.0f}"), ("soft", "{:.0f}"), ("total", "{:.0f}")]
    heads = ["dt", "2 gamma/dt", "chattering cells", "their move / mean move",
             "cell to nearest particle", "their tension 2KP(P-p0)", "triangles changed per step",
             "their nearest centre (median)", "closest pair d", "its curvature x d^2",
             "smallest angle of flipping triangles (deg)", "their circumcentres to nearest particle",
             "lambda_max vertex", "lambda_max vertex (chattering cells)", "lambda_max soft",
             "lambda_max total"]
    print("| " + " | ".join(heads) + " |")
    print("|---" * len(heads) + "|")
    for r in rows:
        print("| " + " | ".join(fmt.format(r[c]) for c, fmt in cols) + " |")


if __name__ == "__main__":
    main()
