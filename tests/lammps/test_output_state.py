#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Output at a step where fix deform changed the box after the forces
(doc/model.md, "What a step's output shows"): the pair style computes the
cells of the state shown, without changing the trajectory, and the
neighbour-exchange count of compute vertex/tissue counts each exchange once
(against the new neighbour pairs of the vertex/local rows of every step,
counted by numpy)."""

import numpy as np

import lmptest
from feature_models import local_rows, model_script
from lmptest import LammpsTestCase

ACTIVE = """fix p all polarity 1.5 1.0 neighbor 0.5 noise 1.0 77
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix def all deform 1 x erate 0.4 y erate -0.3 remap x
timestep 0.01
"""
STEPS = 120


class OutputAfterDeform(LammpsTestCase):
    def test_exchanges_counted_once(self):
        script = model_script("confluent") + ACTIVE + f"""compute c all vertex/tissue
compute l all vertex/local
thermo_style custom step pe c_c[3]
thermo 1
dump d all local 1 pairs.dump c_l[1] c_l[2] c_l[7]
dump_modify d format float %.17g
run {STEPS}
"""
        run = self.run_lmp(script)
        rows = [line.split() for line in run.stdout.splitlines()]
        t1 = {int(r[0]): float(r[2]) for r in rows
              if len(r) == 3 and r[0].isdigit() and 0 <= int(r[0]) <= STEPS}
        frames = local_rows(run, "pairs.dump")
        self.assertEqual(len(frames), STEPS + 1)
        pairs = []
        for f in frames:
            keep = f[:, 2] > 1e-7 * f[:, 2].mean()
            a, b = f[keep, 0].astype(int), f[keep, 1].astype(int)
            pairs.append({(min(x, y), max(x, y)) for x, y in zip(a, b)})
        new = [len(pairs[n] - pairs[n - 1]) for n in range(1, STEPS + 1)]
        got = [t1[n] for n in range(1, STEPS + 1)]
        self.assertGreater(sum(new), 0, "no exchange: the check checks nothing")
        self.assertEqual(got, new)

    def test_output_does_not_change_the_trajectory(self):
        """Per-cell output every step (the cells computed again after each
        deform) or never: the same end state, bitwise."""
        end = "write_dump all custom end.dump id x y mux muy modify format float %.17g\n"
        quiet = model_script("confluent") + ACTIVE
        loud = quiet + """compute c all vertex/atom
dump d all custom 1 cells.dump id c_c[1]
"""
        a = self.run_lmp(quiet + "run 30\n" + end).dump("end.dump")[0]
        b = self.run_lmp(loud + "run 30\n" + end).dump("end.dump")[0]
        for col in ("x", "y", "mux", "muy"):
            np.testing.assert_array_equal(a[col], b[col], err_msg=col)


if __name__ == "__main__":
    lmptest.main()
