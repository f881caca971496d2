#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The incremental triangulation from a disordered start, where triangles fold
over on many steps and the mesh repairs them locally (re-triangulating the
folded region) instead of triangulating from scratch: with 'incremental check'
every step's cells are compared with a fresh CGAL triangulation and the run
stops on any difference.  The start is made here by random sequential
addition (minimum distance 0.5, density 1), on 1 and 2 ranks.  (Measured once
with a counting build: the one-rank run repairs folds on 13 of its 400 steps,
with 13 rebuilds in all.)"""

import math
import random

import lmptest
from lmptest import LammpsTestCase, nprocs


def rsa_data(n, seed, dmin=0.5):
    """A LAMMPS data file (atom style dipole) of n points by random sequential
    addition in a periodic square box of side sqrt(n)."""
    rng = random.Random(seed)
    L = math.sqrt(n)
    pts = []
    while len(pts) < n:
        x, y = rng.uniform(0, L), rng.uniform(0, L)
        ok = True
        for (px, py) in pts:
            dx, dy = abs(x - px), abs(y - py)
            dx, dy = min(dx, L - dx), min(dy, L - dy)
            if dx * dx + dy * dy < dmin * dmin:
                ok = False
                break
        if ok:
            pts.append((x, y))
    lines = [f"random sequential addition, {n} points", "", f"{n} atoms", "1 atom types", "",
             f"0 {L!r} xlo xhi", f"0 {L!r} ylo yhi", "-0.5 0.5 zlo zhi", "", "Masses", "",
             "1 1.0", "", "Atoms # dipole", ""]
    for i, (x, y) in enumerate(pts):
        lines.append(f"{i + 1} 1 0 {x!r} {y!r} 0 0 0 0")
    return "\n".join(lines) + "\n"


SCRIPT = """
dimension 2
units lj
atom_style dipole
boundary p p p
read_data start.data
# a wide skin: the mesh lives through many steps between neighbour-list builds
# (each of which triangulates from scratch), so that folds meet a kept mesh
neighbor 1.5 bin
pair_style vertex/voronoi 3.0 incremental check
pair_coeff * * quadratic 1.0 1.0 1.0 3.9
timestep 0.03
fix move all brownian 1.0 1234 gamma_t 1.0 rng none
fix act all polarity 0.5 1.0 noise 1.0 8821
compute pt all pair vertex/voronoi
thermo_style custom step pe c_pt[3] c_pt[4] c_pt[5]
thermo_modify norm no
thermo 100
run 400
print "STATS $(c_pt[3]) $(c_pt[4]) $(c_pt[5])"
"""


def stats(run):
    line = [l for l in run.stdout.splitlines() if l.startswith("STATS ")][0]
    return [float(w) for w in line.split()[1:]]


class DisorderedStart(LammpsTestCase):

    def check(self, ranks):
        run = self.run_lmp(SCRIPT, nprocs=ranks, files={"start.data": rsa_data(2500, 17)},
                           timeout=600)
        rebuilds, flips, steps = stats(run)
        self.assertGreaterEqual(steps, 400)
        self.assertGreater(flips, 5000, "the run must exercise the flips")
        # far fewer rebuilds than steps: the mesh is kept (and its folds
        # repaired) between neighbour-list builds
        self.assertLess(rebuilds, steps / 4)
        return rebuilds

    def test_one_rank(self):
        self.check(1)

    @nprocs(2)
    def test_two_ranks(self):
        self.check(2)


if __name__ == "__main__":
    lmptest.main()
