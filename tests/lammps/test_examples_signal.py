#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The signalling examples, run briefly: examples/morphogen_organoid (a
morphogen from one pole of a tissue on a sphere steers growth and division)
to t = 20, checked against what its README says: the morphogen falls from
the source pole, each cell's preferred area is the README's function of its
morphogen, cells divide near the source and not at the far pole, and the
sphere's area is the sum of the preferred areas."""

import math
import os

import numpy as np

import lmptest
from lmptest import LammpsTestCase

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")


class MorphogenOrganoid(LammpsTestCase):

    def test_growth_follows_the_gradient(self):
        with open(os.path.join(EXAMPLES, "morphogen_organoid", "in.morphogen_organoid")) as f:
            script = f.read()
        script = script.replace("dump            cells all custom 2500",
                                "dump            cells all custom 500")
        script = script.replace("dump_modify     cells sort id format float %.10g",
                                "dump_modify     cells sort id format float %.17g")
        script = script.replace("dump            edges", "# dump edges").replace(
            "dump_modify     edges", "# dump_modify edges")
        run = self.run_lmp(script, args=["-var", "tend", "20"])
        last = run.dump("dump.cells")[-1]
        self.assertEqual(last["step"], 1000)
        h, m, a0, gen = last["v_h"], last["c_sm"], last["d_area0"], last["f_div[2]"]
        # the preferred area is 1 + m / (0.5 + m), set at this step from this m
        np.testing.assert_allclose(a0, 1 + m / (0.5 + m), rtol=0, atol=1e-12)
        # the morphogen falls from the source pole to the far one
        self.assertGreater(m[h > 0.8].mean(), 20 * m[h < -0.8].mean())
        self.assertTrue(np.all(m > 0))
        # divisions near the source only: the far half keeps its first cells
        n = len(last["id"])
        self.assertGreater(n, 240)
        self.assertTrue(np.all(gen[h < -0.3] == 0))
        self.assertGreater(gen[h > 0.5].mean(), 2.0)
        # the cells lie on one sphere, whose area is the sum of the preferred
        # areas the cells had when they were placed on it (this step's
        # d_area0 were set after that, at the end of the step: 1e-3)
        r = np.linalg.norm(np.column_stack([last["x"], last["y"], last["z"]]) - 10.0, axis=1)
        np.testing.assert_allclose(r, r.mean(), rtol=1e-9)
        self.assertAlmostEqual(4 * math.pi * r.mean() ** 2 / a0.sum(), 1.0, delta=1e-3)
        self.assertGreater(r.mean(), 1.1 * math.sqrt(200 / (4 * math.pi)))

if __name__ == "__main__":
    lmptest.main()
