#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Lineage of fix cell/divide (per-atom columns 5 = mother ID, 6 = birth
time, with 2 = generation): checked against the positions alone.  With a
tiny separation every daughter that appears at step n+1 lies next to the
centre her mother had at step n, so the mother found by nearest position
must be the one the fix wrote; the daughter that keeps the mother's atom
ID names herself; generations add one; the birth time is the time of step
n (whose end decided the division), so age = t - birth.  The runs go
through write_restart / read_restart on 2 ranks, with the atoms migrating
between the ranks."""

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

DT = 0.02
SEP = 0.05

HEAD = """
dimension 2
units lj
atom_style dipole
boundary p p p
"""

PAIR = """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.12 -0.45
thermo_modify norm no
"""

FIXES = f"""
fix move all brownian 1.0 1 gamma_t 1.0 rng none
fix act all polarity 0.3 1.0 neighbor 0.5 noise 0.5 4821
fix div all cell/divide rate 0.4 seed 7 separation {SEP}
thermo_style custom step atoms f_div[2]
thermo 10
"""

DUMP = """
dump d all custom 1 {name} id proc x y f_div[1] f_div[2] f_div[5] f_div[6]
dump_modify d sort id format float %.17g
"""


def data_file(test):
    """A displaced lattice written once, so that the atom IDs of the runs
    reading it do not depend on their number of ranks."""
    return test.run_lmp(HEAD + """
lattice hex 1.0
region box block 0 6 0 4 -0.5 0.5
create_box 1 box
create_atoms 1 box
mass * 1.0
displace_atoms all random 0.15 0.15 0 4821 units box
write_data cfg.data
""").text("cfg.data")


def min_image(d, box):
    length = box[:2, 1] - box[:2, 0]
    return d - length * np.round(d / length)


class Lineage(LammpsTestCase):

    def check_step(self, before, after):
        """The lineage columns of the cells of frame `after` (step n+1)
        against frame `before` (step n).  Returns the number of divisions."""
        n = before["step"]
        self.assertEqual(after["step"], n + 1)
        old = {int(i): k for k, i in enumerate(before["id"])}
        xb = np.column_stack([before["x"], before["y"]])
        xa = np.column_stack([after["x"], after["y"]])
        new = [k for k, i in enumerate(after["id"]) if int(i) not in old]
        for k in new:
            # her mother: a cell of step n next to her (SEP/2 plus a step's
            # motion, ~0.01, away), which at step n+1 lies exactly SEP from
            # her (her sister keeps the mother's ID); one such cell only
            dist = np.hypot(*min_image(xb - xa[k], before["box"]).T)
            found = []
            for m in np.where(dist < 0.1)[0]:
                s = np.where(after["id"] == before["id"][m])[0]
                if len(s) and abs(np.hypot(*min_image(xa[s[0]] - xa[k], before["box"])) - SEP) < 1e-9:
                    found.append((int(m), int(s[0])))
            self.assertEqual(len(found), 1, "step %d cell %d" % (n + 1, after["id"][k]))
            m, s = found[0]
            mother = int(before["id"][m])
            self.assertEqual(int(after["f_div[5]"][k]), mother, "step %d" % (n + 1))
            self.assertEqual(int(after["f_div[5]"][s]), mother)
            for d in (k, s):
                self.assertEqual(after["f_div[2]"][d], before["f_div[2]"][m] + 1)
                self.assertAlmostEqual(after["f_div[6]"][d], n * DT, delta=1e-12)
                self.assertAlmostEqual(after["f_div[1]"][d], DT, delta=1e-12)
        # every other cell keeps its lineage
        sisters = {int(after["f_div[5]"][k]) for k in new}
        for k, i in enumerate(after["id"]):
            i = int(i)
            if i in old and i not in sisters:
                b = old[i]
                for col in ("f_div[2]", "f_div[5]", "f_div[6]"):
                    self.assertEqual(after[col][k], before[col][b], "cell %d %s" % (i, col))
        # age = t - birth for every cell born in a division
        born = after["f_div[5]"] > 0
        np.testing.assert_allclose(after["f_div[1]"][born],
                                   (n + 1) * DT - after["f_div[6]"][born], rtol=0, atol=1e-9)
        return len(new)

    @nprocs(2)
    def test_through_restart_two_ranks(self):
        data = data_file(self)
        first = self.run_lmp(HEAD + "read_data cfg.data\nmass * 1.0\n" + PAIR + f"""
timestep {DT}
""" + FIXES + DUMP.format(name="a.dump") + """
run 50
write_restart r.restart
""", nprocs=2, files={"cfg.data": data})
        second = self.run_lmp("read_restart %s\n" % first.path("r.restart") + FIXES
                              + DUMP.format(name="b.dump") + "run 50\n", nprocs=2)
        frames = first.dump("a.dump") + second.dump("b.dump")[1:]
        self.assertEqual([f["step"] for f in frames], list(range(101)))
        # the first cells: generation 0, no mother, born at time 0
        start = frames[0]
        self.assertEqual(len(start["id"]), 48)
        np.testing.assert_array_equal(start["f_div[2]"], 0)
        np.testing.assert_array_equal(start["f_div[5]"], 0)
        np.testing.assert_array_equal(start["f_div[6]"], 0)
        # the restart kept every cell's lineage
        a, b = first.dump("a.dump")[-1], second.dump("b.dump")[0]
        np.testing.assert_array_equal(a["id"], b["id"])
        for col in ("f_div[1]", "f_div[2]", "f_div[5]", "f_div[6]"):
            np.testing.assert_array_equal(a[col], b[col], err_msg=col)
        # some cells moved from one rank to the other during a run
        moved = 0
        for run in (first.dump("a.dump"), second.dump("b.dump")):
            for f, g in zip(run[:-1], run[1:]):
                common, i, j = np.intersect1d(f["id"], g["id"], return_indices=True)
                moved += int(np.sum(f["proc"][i] != g["proc"][j]))
        self.assertGreater(moved, 0)
        counts = [self.check_step(frames[k], frames[k + 1]) for k in range(100)]
        self.assertGreater(sum(counts[:50]), 10)       # divisions before the restart
        self.assertGreater(sum(counts[50:]), 10)       # and after it
        self.assertGreater(frames[-1]["f_div[2]"].max(), 1)    # granddaughters


lmptest.main()
