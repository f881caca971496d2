# SPDX-License-Identifier: GPL-2.0-or-later
"""Every tessera-tools command that reads cells from a dump, on a hexagonal tissue that shares
its box with particles (types 2 and 3, one of them on a cell centre): without --cell-types the
dump is refused with the types found and the option named; with --cell-types 1 the command
sees the cells alone, checked against the lattice's analytic values (hexagon area and shape
index, number of cells, open area of finite cells, density).  One table of cases, one driver."""

import csv
import math
import os
import re
import tempfile
import unittest

from test_particles import run, tissue_with_particles
from test_vtk import hex_junctions, local_frame
from tessera_tools.dump import write_dump

A = 1.2
N = 24                                  # cells of tissue_with_particles
HEX = math.sqrt(3.0) / 2.0 * A ** 2     # their area
Q_HEX = math.sqrt(8.0 * math.sqrt(3.0))
R_FINITE = 0.65                         # between the inradius A/2 and the circumradius A/sqrt 3


def finite_hexagon_area(r=R_FINITE, d=A / 2.0):
    """A disc of radius r cut by the six edges of the hexagon at distance d (< r < circumradius)."""
    return math.pi * r * r - 6.0 * (r * r * math.acos(d / r) - d * math.sqrt(r * r - d * d))


def number(pattern):
    def get(out, files):
        return float(re.search(pattern, out).group(1))
    return get


def kymograph_counts(out, files):
    with open(files["out"] + ".csv") as f:
        rows = list(csv.DictReader(f))
    first = [r for r in rows if r["timestep"] == "0"]
    return sum(int(r["count"]) for r in first)


BOX = 6 * A * 4 * A * math.sqrt(3.0) / 2.0

# name, arguments ({dump}, {local}, {log}, {out} are filled in), what to read from the output, expected
CASES = [
    ("info --stats", ["info", "{dump}", "--stats"], number(r"mean area ([-0-9.e+]+)"), HEX),
    ("info --local", ["info", "{dump}", "--local", "{local}", "--stats"], number(r"mean area ([-0-9.e+]+)"), HEX),
    ("render", ["render", "{dump}", "-o", "{out}.png", "--dpi", "30"], number(r"(\d+) cells"), N),
    ("render shape", ["render", "{dump}", "-o", "{out}.png", "--dpi", "30", "-f", "shape"],
     number(r"mean shape index ([-0-9.e+]+)"), Q_HEX),
    ("render --local", ["render", "{dump}", "--local", "{local}", "-o", "{out}.png", "--dpi", "30"],
     number(r"mean area ([-0-9.e+]+)"), HEX),
    ("vtk", ["vtk", "{dump}", "-o", "{out}/v", "-q", "--frames", "0"], number(r"wrote (\d+) frame"), 1),
    ("vtk --radius", ["vtk", "{dump}", "-o", "{out}/v", "-q", "--radius", str(R_FINITE)],
     number(r"wrote (\d+) frame"), 3),
    ("traj", ["traj", "{dump}", "-o", "{out}.png", "--dpi", "30"], number(r"frames, (\d+) cells"), N),
    ("plot wound", ["plot", "wound", "{dump}", "--radius", str(R_FINITE), "-o", "{out}.png", "--dpi", "30"],
     number(r"from ([-0-9.e+]+)"), BOX - N * finite_hexagon_area()),
    ("plot growth", ["plot", "growth", "{dump}", "-o", "{out}.png", "--dpi", "30", "--tmax", "20"],
     number(r"N from (\d+)"), N),
    ("plot shape", ["plot", "shape", "{dump}", "-o", "{out}.png", "--dpi", "30"],
     number(r"shape index mean ([-0-9.e+]+)"), Q_HEX),
    ("plot demix", ["plot", "demix", "{dump}", "{local}", "-o", "{out}.png", "--dpi", "30"],
     number(r"fraction ([-0-9.e+]+) ->"), 0.0),
    ("plot kymograph", ["plot", "kymograph", "{dump}", "-c", "c_f[1]", "--bins", "3", "--csv", "{out}.csv"],
     kymograph_counts, N),
    ("plot field", ["plot", "field", "{dump}", "-c", "c_f[1]", "-o", "{out}.png", "--dpi", "30"],
     number(r"(\d+) cells"), N),
    ("plot field --local", ["plot", "field", "{dump}", "--local", "{local}", "-c", "c_f[1]", "-o", "{out}.png",
                            "--dpi", "30", "--frame", "0"], number(r"(\d+) cells"), N),
    ("lineage --start", ["lineage", "{log}", "--start", "{dump}"], number(r"(\d+) root cells"), N),
]

REFUSED = "type 1: 24 atoms, type 2: 3 atoms, type 3: 2 atoms"


class EveryCommand(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        d = cls.tmp.name
        frames = [tissue_with_particles(a=A, timestep=t, shift=0.01 * t)[0] for t in (0, 10, 20)]
        cls.files = {"dump": os.path.join(d, "all.dump"), "local": os.path.join(d, "cells.local"),
                     "log": os.path.join(d, "divisions.log")}
        write_dump(cls.files["dump"], frames)
        locals_ = []
        for f in frames:
            cells = f.subset(f["type"] == 1)
            cols = hex_junctions(cells.positions(), cells.box, A)
            for c in ("c_junc[1]", "c_junc[2]"):
                cols[c] = cells["id"][cols[c].astype(int) - 1]
            locals_.append(local_frame(cells.box, cols, f.timestep))
        write_dump(cls.files["local"], locals_)
        with open(cls.files["local"]) as fh:
            text = fh.read().replace("NUMBER OF ATOMS", "NUMBER OF ENTRIES").replace("ITEM: ATOMS", "ITEM: ENTRIES")
        with open(cls.files["local"], "w") as fh:
            fh.write(text)
        with open(cls.files["log"], "w") as fh:
            fh.write("# step time event id daughter1 daughter2 x y z\n5 0.5 divide 2 2 100 1.0 1.0 0\n")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_every_command(self):
        for k, (name, argv, read, expected) in enumerate(CASES):
            with self.subTest(command=name):
                files = dict(self.files, out=os.path.join(self.tmp.name, f"out{k}"))
                args = [a.format(**files) for a in argv]
                code, out, err = run(args)
                self.assertNotEqual(code, 0, f"{name} took the particles for cells:\n{out}")
                self.assertIn(REFUSED if "--local" not in name and "demix" not in name else "have no rows", err)
                self.assertIn("--cell-types", err)
                code, out, err = run(args + ["--cell-types", "1"])
                self.assertEqual(code, 0, err)
                self.assertAlmostEqual(read(out, files), expected, delta=1e-5 * max(1.0, abs(expected)), msg=out)

    def test_all_taken_for_cells_on_request(self):
        # --cell-types naming every type: the particles are cells (one sits on a cell centre)
        code, out, err = run(["info", self.files["dump"], "--stats", "--cell-types", "1*"])
        self.assertNotEqual(code, 0)
        self.assertIn("coincident cell centres", err)


if __name__ == "__main__":
    unittest.main()
