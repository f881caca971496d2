#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""What a split run reproduces (doc/model.md, "Split runs and restarts"):
write_restart at the end of step n and read_restart continue exactly as a
second run command of the same input with the same fixes defined anew
(round-off), also with divisions and fix deform; one uninterrupted run is
reproduced only when nothing changed the box or the positions after the
forces of step n: with fix deform the uninterrupted step n+1 moves the cells
with the forces of the box before deform's change at the end of step n, the
split run with those of the box after it."""

import numpy as np

import lmptest
from feature_models import model_script
from lmptest import LammpsTestCase

DYN = """fix p all polarity 0.3 1.0 neighbor 0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix div all cell/divide rate 2.0 seed 4821 separation 0.1
timestep 0.005
thermo_style custom step atoms pe
"""
DEFORM = "fix def all deform 1 x vel 0.5 y vel -0.3 remap x units box\n"
END = "write_dump all custom end.dump id xu yu zu mux muy muz modify format float %.17g\n"
COLUMNS = ("xu", "yu", "zu", "mux", "muy", "muz")


class SplitRuns(LammpsTestCase):
    def ends(self, deform):
        """The end states of one run of 20 steps, of 10 + 10 steps in one
        input (fix deform defined anew for the second run, as a restarted
        input defines it) and of 10 steps, write_restart, read_restart, 10."""
        head = model_script("confluent") + DYN
        whole = self.run_lmp(head + deform + "run 20\n" + END)
        split = self.run_lmp(head + deform + "run 10\n" + (f"unfix def\n{deform}" if deform else "")
                             + "run 10\n" + END)
        first = self.run_lmp(head + deform + "run 10\nwrite_restart half.restart\n")
        second = self.run_lmp(f"dimension 2\nread_restart {first.path('half.restart')}\n" + DYN
                              + deform + "run 10\n" + END)
        out = []
        for run in (whole, split, second):
            f = run.dump("end.dump")[0]
            out.append(np.column_stack([f[c] for c in COLUMNS]))
        self.assertGreater(len(out[0]), 94)    # cells divided in the second half
        return out

    def test_restart_is_a_second_run_with_deform_and_divisions(self):
        whole, split, restarted = self.ends(DEFORM)
        np.testing.assert_allclose(restarted, split, rtol=0, atol=1e-10)
        # and not the uninterrupted run: the forces of step 11 differ
        self.assertGreater(np.abs(whole - split).max(), 1e-7)

    def test_restart_is_the_uninterrupted_run_without_deform(self):
        whole, split, restarted = self.ends("")
        np.testing.assert_allclose(split, whole, rtol=0, atol=1e-10)
        np.testing.assert_allclose(restarted, whole, rtol=0, atol=1e-10)


if __name__ == "__main__":
    lmptest.main()
