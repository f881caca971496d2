# SPDX-License-Identifier: GPL-2.0-or-later
"""The analyses on one real run of tessera-lmp: finite cells (type 1) that divide (fix
cell/divide with an event log) among three particles (type 2, pair soft under
hybrid/overlay), all moving under fix brownian, with compute vertex/loops dumped.  Checked
against what LAMMPS wrote, never against the tools' own earlier output:

* plot wound --cell-types: the open area of every frame is compute vertex/loops' total hole
  area of that step (periodic box), to round-off, and so are --value holes and largest (its
  largest hole);
* holes: the hole found around each particle from the dumped centres is compute
  vertex/loops' row (index, area, length, cells) of the same step, and so is the row that
  compute vertex/loops/atom's index of the particle names (--loop-column): the two ways agree
  on every particle and frame;
* divisions: one row per line of the log; each division's position is the midpoint of the
  two daughters in a dump of its step, and the number of divisions is the growth in cells;
* flux: the net crossings of the particles through x = xlo are the change of their image
  flags ix;
* lineage --start --cell-types: the roots are the cells of the first frame (no particle), the
  living leaves those of the last.
Needs tessera-lmp (skipped otherwise)."""

import csv
import os
import re
import tempfile
import unittest

import numpy as np

from helpers import find_lmp, run_lmp
from test_particles import run
from tessera_tools.dump import parse_types, read_dump
from tessera_tools.holes import read_loops
from tessera_tools.measure import frame_series

R = 0.66
SCRIPT = f"""
dimension 2
units lj
atom_style atomic
boundary p p p
lattice hex 1.0
region box block 0 8 0 6 -0.5 0.5
create_box 2 box
create_atoms 1 box
mass * 1.0
displace_atoms all random 0.05 0.05 0 4821 units box
set atom 20 type 2
set atom 57 type 2
set atom 75 type 2
group cells type 1
pair_style hybrid/overlay vertex/voronoi 1.6 radius {R} soft 0.6
pair_coeff 1 1 vertex/voronoi quadratic 1.0 1.0 0.1 3.8
pair_coeff * 2 soft 1.0 0.6
fix move all brownian 0.05 17 gamma_t 1.0
fix div cells cell/divide rate 0.3 seed 7 max 120 file divisions.log
compute loops all vertex/loops
compute inloop all vertex/loops/atom
timestep 0.01
thermo 10
dump a all custom 5 all.dump id type x y ix iy c_inloop[1]
dump_modify a sort id format float %.17g
dump s all custom 1 steps.dump id type x y
dump_modify s sort id format float %.17g
dump l all local 5 loops.dump c_loops[*]
dump_modify l format float %.17g
run 40
"""


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


@unittest.skipIf(find_lmp() is None, "tessera-lmp is not built (scripts/build)")
class RealRun(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.dir = cls.tmp.name
        run_lmp(SCRIPT, cls.dir)
        cls.dump = os.path.join(cls.dir, "all.dump")
        cls.loops = read_loops(os.path.join(cls.dir, "loops.dump"))
        cls.frames = read_dump(cls.dump)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)

    def test_open_area_is_the_computes_hole_area(self):
        ct = parse_types("1")
        steps, _, area = frame_series(self.dump, "open", radius=R, cell_types=ct)
        _, _, total = frame_series(self.dump, "holes", radius=R, cell_types=ct)
        _, _, largest = frame_series(self.dump, "largest", radius=R, cell_types=ct)
        checked = 0
        for s, a, t, big in zip(steps, area, total, largest):
            if s in self.loops:
                rows = self.loops[s]
                holes = rows[rows[:, 6] == 0, 1]
                self.assertAlmostEqual(a, holes.sum(), delta=1e-9 * holes.sum(), msg=f"step {s}")
                self.assertAlmostEqual(t, holes.sum(), delta=1e-9 * holes.sum(), msg=f"step {s}")
                self.assertAlmostEqual(big, holes.max(), delta=1e-9 * holes.max(), msg=f"step {s}")
                checked += 1
        self.assertEqual(checked, 9)
        code, out, err = run(["plot", "wound", self.dump, "--radius", str(R), "--cell-types", "1",
                              "-o", self.path("wound.png"), "--dpi", "40"])
        self.assertEqual(code, 0, err)
        rows = self.loops[0]
        self.assertAlmostEqual(float(re.search(r"from ([-0-9.e+]+)", out).group(1)),
                               rows[rows[:, 6] == 0, 1].sum(), delta=1e-5)
        code, out, err = run(["plot", "wound", self.dump, "--radius", str(R), "-o", self.path("w.png")])
        self.assertNotEqual(code, 0)
        self.assertIn("--cell-types", err)

    def test_holes_are_the_computes_rows(self):
        code, out, err = run(["holes", self.dump, "--cell-types", "1", "--radius", str(R),
                              "--csv", self.path("holes.csv"), "-o", self.path("holes.png"), "--dpi", "40"])
        self.assertEqual(code, 0, err)
        rows = read_csv(self.path("holes.csv"))
        self.assertEqual(len(rows), 3 * 9)
        self.assertEqual({r["id"] for r in rows}, {"20", "57", "75"})
        inside = [r for r in rows if r["loop"] != "0"]
        self.assertGreater(len(inside), 9)
        for r in inside:
            loops = self.loops[int(r["timestep"])]
            row = loops[loops[:, 0] == int(r["loop"])][0]
            self.assertEqual(row[6], 0)                                  # a hole
            self.assertAlmostEqual(float(r["area"]), row[1], delta=1e-9)
            self.assertAlmostEqual(float(r["length"]), row[2], delta=1e-9)
            self.assertEqual(int(r["cells"]), int(row[3]))
        code, out, err = run(["holes", self.dump, "--cell-types", "1", "--radius", str(R), "--loops",
                              self.path("loops.dump"), "--csv", self.path("holes2.csv")])
        self.assertEqual(code, 0, err)
        self.assertNotIn("warning", out)
        again = read_csv(self.path("holes2.csv"))
        self.assertTrue(all(r["from_compute"] == "1" for r in again if r["loop"] != "0"))
        self.assertEqual([r["area"] for r in again], [r["area"] for r in rows])
        # compute vertex/loops/atom's index: the same holes, no loop rebuilt
        for column in ("c_inloop[1]", "inloop"):
            code, out, err = run(["holes", self.dump, "--cell-types", "1", "--radius", str(R), "--loops",
                                  self.path("loops.dump"), "--loop-column", column, "--csv", self.path("holes3.csv")])
            self.assertEqual(code, 0, err)
            self.assertIn("compute vertex/loops/atom", out)
            indexed = read_csv(self.path("holes3.csv"))
            self.assertEqual(len(indexed), len(again))
            for a, b in zip(indexed, again):
                for key in ("timestep", "id", "covered", "loop", "cells", "from_compute"):
                    self.assertEqual(a[key], b[key], (key, a, b))
                for key in ("area", "length"):
                    self.assertAlmostEqual(float(a[key]), float(b[key]), delta=1e-12, msg=(key, a, b))
        # the particles' index in the dump itself: the hole's row the centres give, or 0 for one
        # the cells cover (a tissue filling a periodic box has no outer loop)
        for f in self.frames:
            part = f["type"] == 2
            for pid, index in zip(f["id"][part], f["c_inloop[1]"][part]):
                r = [r for r in again if r["timestep"] == str(f.timestep) and r["id"] == str(pid)][0]
                self.assertEqual(int(index), int(r["loop"]), r)
                self.assertEqual(r["covered"] == "1", index == 0, r)

    def test_divisions_at_the_daughters_midpoint(self):
        code, out, err = run(["divisions", self.path("divisions.log"), "--csv", self.path("div.csv"),
                              "-o", self.path("div.png"), "--dpi", "40", "--bins", "4"])
        self.assertEqual(code, 0, err)
        rows = read_csv(self.path("div.csv"))
        with open(self.path("divisions.log")) as f:
            events = [line for line in f if line.strip() and not line.startswith("#")]
        self.assertEqual(len(rows), len(events))
        self.assertGreater(len(rows), 3)
        cells = [int(np.sum(f["type"] == 1)) for f in self.frames]
        self.assertEqual(cells[-1] - cells[0], len(rows))
        by_step = {f.timestep: f for f in read_dump(self.path("steps.dump"))}
        for r in rows:
            f = by_step[int(r["step"])]
            pos = f.positions()
            i1 = int(np.nonzero(f["id"] == int(r["daughter1"]))[0][0])
            i2 = int(np.nonzero(f["id"] == int(r["daughter2"]))[0][0])
            mid = pos[i1] + 0.5 * f.box.minimum_image((pos[i2] - pos[i1])[None])[0]
            d = f.box.minimum_image((mid - [float(r["x"]), float(r["y"])])[None])[0]
            self.assertLess(np.hypot(*d), 1e-3, r)     # the log's 10 digits, and the step's motion

    def test_flux_of_the_particles_is_their_image_change(self):
        code, out, err = run(["flux", self.dump, "--types", "2", "--x", str(self.frames[0].box.xlo),
                              "--y", str(self.frames[0].box.ylo), "--csv", self.path("flux.csv")])
        self.assertEqual(code, 0, err)
        rows = read_csv(self.path("flux.csv"))
        first, last = self.frames[0], self.frames[-1]
        p0, p1 = first["type"] == 2, last["type"] == 2
        np.testing.assert_array_equal(first["id"][p0], last["id"][p1])
        self.assertEqual(float(rows[0]["net"]), float(np.sum(last["ix"][p1] - first["ix"][p0])))
        self.assertEqual(float(rows[1]["net"]), float(np.sum(last["iy"][p1] - first["iy"][p0])))
        for command in (["msd", "--max-lag", "10"], ["velocity", "--bins", "2", "2"]):
            code, out, err = run([command[0], self.dump, "--types", "1", "--dt", "0.01", "--csv",
                                  self.path(command[0] + ".csv")] + command[1:])
            self.assertEqual(code, 0, err)

    def test_lineage_roots_are_the_cells(self):
        code, out, err = run(["lineage", self.path("divisions.log"), "--start", self.dump, "--cell-types", "1"])
        self.assertEqual(code, 0, err)
        cells = [int(np.sum(f["type"] == 1)) for f in self.frames]
        self.assertIn(f"{cells[0]} root cells", out)
        self.assertIn(f"{cells[-1]} living at the end", out)
        code, out, err = run(["lineage", self.path("divisions.log"), "--start", self.dump])
        self.assertNotEqual(code, 0)
        self.assertIn("type 1: 93 atoms, type 2: 3 atoms", err)


if __name__ == "__main__":
    unittest.main()
