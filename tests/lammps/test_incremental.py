#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The incremental triangulation of pair_style vertex/voronoi (mesh kept
between steps, repaired by flips) against the from-scratch one: with
'incremental check' every step's cells are compared with a fresh CGAL
triangulation and the run stops on any difference.  Long fluid runs with many
neighbour exchanges, on 1 and 2 ranks, and a start on a degenerate lattice."""

import lmptest
from lmptest import LammpsTestCase, nprocs


def fluid_script(lattice="hex", nx=12, ny=6, steps=1500, tilt=None):
    return lmptest.tissue(nx, ny, lattice, 1, tilt) + f"""
pair_style vertex/voronoi 4.0 incremental check
pair_coeff * * quadratic 1.0 1.0 1.0 4.2
timestep 0.01
fix move all brownian 1.0 1234 gamma_t 1.0 rng none
fix act all polarity 1.0 1.0 noise 1.0 8821
compute tissue all vertex/tissue
compute pt all pair vertex/voronoi
thermo_style custom step pe c_tissue[3] c_pt[3] c_pt[4] c_pt[5]
thermo_modify norm no
thermo {steps // 10}
run {steps}
variable t1 equal c_tissue[3]
print "STATS $(c_pt[3]) $(c_pt[4]) $(c_pt[5])"
"""


def stats(run):
    line = [l for l in run.stdout.splitlines() if l.startswith("STATS ")][0]
    return [float(w) for w in line.split()[1:]]


def t1_total(run):
    """Sum of the T1 counts printed by thermo (column c_tissue[3])."""
    lines = run.stdout.split("Step")[1].split("Loop time")[0].strip().splitlines()[1:]
    # (skipping the style's messages, such as its warning about a step longer than a cell)
    return sum(float(l.split()[2]) for l in lines if l.split()[0].isdigit())


class Check(LammpsTestCase):

    def check(self, nprocs, lattice="hex", ny=6, tilt=None):
        run = self.run_lmp(fluid_script(lattice=lattice, ny=ny, tilt=tilt), nprocs=nprocs)
        _, flips, steps = stats(run)
        self.assertGreaterEqual(steps, 1500)
        self.assertGreater(flips, 500, "the run must exercise the flips")
        self.assertGreater(t1_total(run), 50, "the run must have neighbour exchanges")

    def test_fluid_one_rank(self):
        self.check(1)

    @nprocs(2)
    def test_fluid_two_ranks(self):
        self.check(2)

    @nprocs(2)
    def test_fluid_triclinic_two_ranks(self):
        self.check(2, tilt=3)

    def test_from_square_lattice(self):
        # every vertex of the start is four-fold
        self.check(1, lattice="sq", ny=12)


if __name__ == "__main__":
    lmptest.main()
