#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""examples/python still runs and still agrees with its analytic value."""

import math
import os

import lmptest
from lmptest import LammpsTestCase, nprocs

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "python")


class BrownianMsdExample(LammpsTestCase):

    def check(self, nranks):
        atoms = 4000
        run = self.run_python(script=os.path.join(EXAMPLES, "brownian_msd.py"), nprocs=nranks,
                              args=["--atoms", str(atoms), "--steps", "300", "--blocks", "3"])
        rows = [line.split() for line in run.stdout.splitlines() if not line.startswith("#")]
        rows = [r for r in rows if r]
        self.assertEqual(len(rows), 3, run.output)
        time, msd, einstein, ratio = (float(w) for w in rows[-1])
        self.assertAlmostEqual(time, 3.0)
        self.assertAlmostEqual(einstein, 4 * 0.5 * 3.0)
        # |dr|^2 / (2 D t) is chi^2 with 2 degrees of freedom: relative std 1/sqrt(N)
        self.assertLess(abs(ratio - 1), 5 / math.sqrt(atoms), run.stdout)

    def test_serial(self):
        self.check(1)

    @nprocs(2)
    def test_two_ranks(self):
        self.check(2)


class TissueExample(LammpsTestCase):
    """tissue.py: the shape index and polar order Python computes from the
    gathered per-cell arrays equal LAMMPS's own (compute vertex/tissue's mean,
    fix polarity's vector)."""

    def check(self, nranks):
        run = self.run_python(script=os.path.join(EXAMPLES, "tissue.py"), nprocs=nranks,
                              args=["--blocks", "2", "--steps", "50"])
        rows = [line.split() for line in run.stdout.splitlines() if line and not line.startswith("#")]
        self.assertEqual(len(rows), 2, run.output)
        for step, q_py, q_lmp, p_py, p_lmp in ([float(w) for w in r] for r in rows):
            self.assertAlmostEqual(q_py, q_lmp, delta=2e-6)
            self.assertAlmostEqual(p_py, p_lmp, delta=2e-6)
            self.assertGreater(q_py, 3.7)

    def test_serial(self):
        self.check(1)

    @nprocs(2)
    def test_two_ranks(self):
        self.check(2)


if __name__ == "__main__":
    lmptest.main()
