#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Input that used to be accepted without a word or answered with a
misleading message: each now stops with an error naming the argument, the
value and the fix (or prints the settings that apply)."""

import lmptest
from lmptest import LammpsTestCase

BASE = lmptest.tissue(6, 3) + "pair_style vertex/voronoi 3.0\n"


class Messages(LammpsTestCase):
    def test_free_without_value(self):
        run = self.run_lmp(BASE + "pair_coeff * * 1 1 0.1 -0.5 free\nrun 0\n", ok=False)
        self.assertLammpsError(run, "pair_coeff * *", "'free' needs a value")

    def test_negative_gamma(self):
        run = self.run_lmp(BASE + "pair_coeff * * 1 1 -0.1 0.18\nrun 0\n", ok=False)
        self.assertLammpsError(run, "Gamma must be >= 0", "-0.1")

    def test_nonpositive_timestep(self):
        # (timestep 0 with 'run 0' is fine: no step is taken)
        for dt in ("-0.01", "0"):
            run = self.run_lmp(BASE + f"""pair_coeff * * 1 1 0.1 -0.5
fix p all polarity 0.3 1.0 noise 0.1 7
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep {dt}
run 2
""", ok=False)
            self.assertLammpsError(run, "timestep must be > 0")
            self.assertNotIn("nan", run.output.lower().split("error")[0][-2000:])

    def test_settings_line_of_finite_cells(self):
        run = self.run_lmp(lmptest.tissue(6, 3).replace("boundary p p p", "boundary f f p") +
                           "pair_style vertex/voronoi 1.5 radius 0.7\n"
                           "pair_coeff * * quadratic 1 1 0.1 3.8 free 0.2\nrun 0\n")
        line = [l for l in run.stdout.splitlines() if l.startswith("pair_style vertex/voronoi: cutoff")][0]
        self.assertIn("radius 0.7", line)
        self.assertNotIn("incremental", line)
        self.assertIn("free F", run.stdout)

    def test_adapt_area0_with_d_area0(self):
        run = self.run_lmp(BASE + """pair_coeff * * 1 1 0.1 -0.5
fix a0 all property/atom d_area0
set group all d_area0 1.0
variable v equal 1.5
fix ad all adapt 1 pair vertex/voronoi area0 * * v_v
run 1
""")
        self.assertIn("adapt d_area0 instead", run.output)


lmptest.main()
