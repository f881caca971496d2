# SPDX-License-Identifier: GPL-2.0-or-later
"""Shared pieces of the tools tests: import path, synthetic lattices and dumps."""

import math
import os
import sys

import numpy as np

TOOLS = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if TOOLS not in sys.path:
    sys.path.insert(0, TOOLS)

import matplotlib  # noqa: E402

matplotlib.use("Agg")

from tessera_tools.dump import Box, Frame  # noqa: E402


def hex_lattice(nx, ny, a=1.0, origin=(0.0, 0.0)):
    """nx * ny centres of a hexagonal lattice (ny even) and the periodic box that fits it."""
    assert ny % 2 == 0
    h = a * math.sqrt(3.0) / 2.0
    pts = np.array([((i + 0.5 * (j % 2)) * a, j * h) for j in range(ny) for i in range(nx)])
    box = Box(origin[0], origin[0] + nx * a, origin[1], origin[1] + ny * h)
    return pts + np.asarray(origin), box


def square_lattice(n, a=1.0):
    pts = (np.array([(i, j) for j in range(n) for i in range(n)], dtype=float) + 0.5) * a
    return pts, Box(0.0, n * a, 0.0, n * a)


def frame_from(points, box, timestep=0, **columns):
    """A Frame with id, type, x, y and any extra per-atom columns."""
    n = len(points)
    cols = {"id": np.arange(1, n + 1), "type": np.ones(n, dtype=np.int64),
            "x": points[:, 0].astype(float), "y": points[:, 1].astype(float)}
    cols.update({k: np.asarray(v) for k, v in columns.items()})
    return Frame(timestep, box, cols, list(cols))


def is_png(path):
    with open(path, "rb") as f:
        head = f.read(8)
    return head == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 1000


def find_lmp():
    """tessera-lmp of $TESSERA_LMP, else of the build ($TESSERA_BUILD or build/), else None."""
    repo = os.path.dirname(TOOLS)
    build = os.environ.get("TESSERA_BUILD") or os.path.join(repo, "build")
    for path in (os.environ.get("TESSERA_LMP"), os.path.join(build, "lammps", "tessera-lmp")):
        if path and os.access(path, os.X_OK):
            return path
    return None


def run_lmp(script, directory, timeout=120):
    """Run tessera-lmp on the text ``script`` in ``directory``; returns its stdout (the log's
    'print' lines are there).  Raises AssertionError with the log's tail when it fails."""
    import subprocess

    path = os.path.join(directory, "in.test")
    with open(path, "w") as f:
        f.write(script)
    proc = subprocess.run([find_lmp(), "-in", "in.test", "-log", "log.lammps", "-nocite"], cwd=directory,
                          capture_output=True, text=True, timeout=timeout)
    if proc.returncode != 0:
        raise AssertionError("tessera-lmp failed:\n" + proc.stdout[-3000:] + proc.stderr[-2000:])
    return proc.stdout


def printed(stdout, key):
    """The numbers of the lines 'key v1 v2 ...' of a LAMMPS run's output."""
    return [[float(v) for v in line.split()[1:]] for line in stdout.splitlines() if line.startswith(key + " ")]
