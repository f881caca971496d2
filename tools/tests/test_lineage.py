# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools lineage on a hand-written event log whose tree is known: generations,
ancestry, living leaves = cells at the end, Newick leaves, the table and the drawing; the
errors for a log that does not fit its start.  (The logs of real runs on 1, 2 and 4 ranks,
and the tree against the dumps, are tested in tests/lammps/test_event_log.py.)"""

import csv
import os
import re
import tempfile
import unittest

from helpers import frame_from, hex_lattice, is_png
from test_cli import run
from tessera_tools.dump import write_dump
from tessera_tools.lineage import Lineage, LineageError, read_events

HEADER = "# Tessera event log of fix div cell/divide (units lj)\n# step time event id daughter1 daughter2 x y z\n"
# cells 1..4 at the start; 1 divides (5 new), 5 divides (6 new), 3 dies, 1 divides again (7 new)
DIVIDE = """5 0.1 divide 1 1 5 0.5 0.5 0
7 0.14 divide 5 5 6 1.5 0.5 0
9 0.18 divide 1 1 7 0.5 0.6 0
"""
DEATH = "# Tessera event log of fix die cell/death (units lj)\n7 0.14 death 3 0 0 2.5 0.5 0\n"


class Tree(unittest.TestCase):

    def setUp(self):
        tmp = tempfile.TemporaryDirectory()
        self.addCleanup(tmp.cleanup)
        self.dir = tmp.name
        self.div = self.path("div.log")
        self.die = self.path("die.log")
        with open(self.div, "w") as f:
            f.write(HEADER + DIVIDE)
        with open(self.die, "w") as f:
            f.write(DEATH)

    def path(self, name):
        return os.path.join(self.dir, name)

    def test_known_tree(self):
        tree = Lineage(read_events([self.div, self.die]), start_ids=[1, 2, 3, 4])
        self.assertEqual(sorted(tree.leaves()), sorted(["1@9", "7@9", "5@7", "6@7", "2", "4"]))
        self.assertEqual(len(tree.leaves()), 4 + 3 - 1)
        self.assertEqual(sorted(tree.leaves(alive_only=False)), sorted(tree.leaves() + ["3"]))
        self.assertEqual(tree.cells["7@9"].generation, 2)
        self.assertEqual(tree.cells["6@7"].generation, 2)
        self.assertEqual(tree.ancestry("6@7"), ["6@7", "5@5", "1"])
        self.assertEqual(tree.cells["3"].fate, "death")
        self.assertEqual(tree.cells["5@5"].birth_time, 0.1)
        self.assertEqual(tree.cells["5@5"].end_time, 0.14)
        self.assertEqual(sorted(tree.alive_by_id()), [1, 2, 4, 5, 6, 7])
        newick = tree.newick(end_time=0.2)
        self.assertEqual(newick.count(";"), 4)
        # every leaf of the trees, living or dead, once
        labels = re.findall(r"[(,]([0-9_at+]+):", "," + newick.replace("\n", ","))
        self.assertEqual(sorted(labels), sorted(["1_at_9", "7_at_9", "5_at_7", "6_at_7", "2", "4", "3+"]))
        # branch lengths are life times: cell 5@5 lived from 0.1 to 0.14
        self.assertIn(")5_at_5:0.04", newick)
        self.assertIn("2:0.2;", newick)

    def test_without_start_only_cells_with_events(self):
        tree = Lineage(read_events([self.div, self.die]))
        self.assertFalse(tree.complete)
        self.assertEqual(sorted(tree.roots), ["1", "3"])

    def test_event_of_a_cell_that_is_not_alive(self):
        with open(self.path("bad.log"), "w") as f:
            f.write(HEADER + "3 0.06 divide 5 5 9 0 0 0\n")
        with self.assertRaisesRegex(LineageError, r"bad.log:3: cell 5 \(divide at step 3\) is not alive"):
            Lineage(read_events(self.path("bad.log")), start_ids=[1, 2])

    def test_bad_line(self):
        with open(self.path("junk.log"), "w") as f:
            f.write(HEADER + "3 0.06 split 5 5 9 0 0 0\n")
        with self.assertRaisesRegex(LineageError, r"junk.log:3: expected 'step time divide\|death"):
            read_events(self.path("junk.log"))

    def test_command(self):
        pts, box = hex_lattice(2, 2)
        write_dump(self.path("start.dump"), [frame_from(pts, box)])
        table, newick, png = self.path("cells.csv"), self.path("tree.nwk"), self.path("tree.png")
        code, out, err = run("lineage", self.div, self.die, "--start", self.path("start.dump"), "--table", table,
                             "--newick", newick, "-o", png, "--ancestry", "6")
        self.assertEqual(code, 0, err)
        self.assertIn("4 events (3 divisions, 1 deaths)", out)
        self.assertIn("6 living at the end", out)
        self.assertIn("cell 6: generation 2, ancestry 6@7 <- 5@5 <- 1", out)
        with open(table) as f:
            rows = {r["cell"]: r for r in csv.DictReader(f)}
        self.assertEqual(len(rows), 4 + 2 * 3)
        self.assertEqual(rows["7@9"]["mother"], "1@5")
        self.assertEqual(rows["7@9"]["root"], "1")
        self.assertEqual(rows["3"]["fate"], "death")
        self.assertTrue(os.path.getsize(newick) > 0)
        self.assertTrue(is_png(png))
        code, out, err = run("lineage", self.div, "--ancestry", "3")
        self.assertNotEqual(code, 0)


if __name__ == "__main__":
    unittest.main()
