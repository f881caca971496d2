# SPDX-License-Identifier: GPL-2.0-or-later
import math
import os
import tempfile
import unittest

import numpy as np

from helpers import is_png
from tessera_tools.logplot import parse_log, plot_logs, write_csv

LOG = """LAMMPS (2 Aug 2023 - Update 3)
units           lj
timestep        0.01
pair_style      vertex/voronoi 3.0
thermo_style    custom step pe c_cell[1] f_act[1]
run             300
Neighbor list info ...
Per MPI rank memory allocation (min/avg/max) = 3.1 | 3.1 | 3.1 Mbytes
   Step         PotEng        c_cell[1]      f_act[1]
         0  -1.5            4.10           0.05
       100  -1.9            3.95           0.30
WARNING: Voronoi cell 17 has a multifold vertex (src/somewhere.cpp:12)
       200  -2.1            3.90           0.60
       300  -2.2            3.85           0.80
Loop time of 0.5 on 1 procs for 300 steps with 100 atoms

Performance: 1 tau/day
timestep        0.005
thermo_style    custom step pe c_cell[1] f_act[1] f_act[2]
run             200
   Step         PotEng        c_cell[1]      f_act[1]       f_act[2]
       300  -2.2            3.85           0.80           0.10
       400  -2.3            3.82           0.90           0.20
       500  -nan            3.81           0.95           0.30
Loop time of 0.3 on 1 procs for 200 steps with 100 atoms
run 100
   Step         PotEng        c_cell[1]      f_act[1]       f_act[2]
       500  -2.35           3.81           0.95           0.30
       600  -2.4            3.80           0.97           0.40
ERROR: Lost atoms: original 100 current 99 (src/thermo.cpp:481)
"""


class LogParsing(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.tmp.name, "log.lammps")
        with open(self.path, "w") as f:
            f.write(LOG)

    def tearDown(self):
        self.tmp.cleanup()

    def test_runs_and_columns(self):
        log = parse_log(self.path)
        self.assertEqual(len(log.runs), 3)
        self.assertEqual([len(r) for r in log.runs], [4, 3, 2])  # the warning line is skipped
        self.assertEqual([r.complete for r in log.runs], [True, True, False])
        self.assertEqual([r.dt for r in log.runs], [0.01, 0.005, 0.005])
        self.assertEqual(log.names, ["Step", "PotEng", "c_cell[1]", "f_act[1]", "f_act[2]"])
        np.testing.assert_allclose(log.runs[0]["c_cell[1]"], [4.10, 3.95, 3.90, 3.85])
        self.assertTrue(math.isnan(log.runs[1]["PotEng"][2]))

    def test_concatenation_and_time(self):
        d = parse_log(self.path).combined()
        # the first row of each continuing run repeats the previous last step and is dropped
        np.testing.assert_array_equal(d["Step"], [0, 100, 200, 300, 400, 500, 600])
        np.testing.assert_allclose(d["time"], [0, 1, 2, 3, 3.5, 4.0, 4.5])
        self.assertTrue(np.all(np.isnan(d["f_act[2]"][:4])))
        np.testing.assert_allclose(d["f_act[2]"][4:], [0.2, 0.3, 0.4])
        np.testing.assert_allclose(d["PotEng"][[0, 3, 6]], [-1.5, -2.2, -2.4])

    def test_time_column_wins_and_no_thermo_is_an_error(self):
        other = os.path.join(self.tmp.name, "log.time")
        with open(other, "w") as f:
            f.write("Step Time PotEng\n0 0 1.0\n10 0.25 0.5\nLoop time of 1\n")
        d = parse_log(other).combined()
        np.testing.assert_allclose(d["time"], [0, 0.25])
        empty = os.path.join(self.tmp.name, "log.none")
        with open(empty, "w") as f:
            f.write("LAMMPS\nTotal wall time: 0:00:00\n")
        with self.assertRaises(ValueError):
            parse_log(empty)

    def test_plot_and_csv(self):
        import matplotlib

        matplotlib.use("Agg")
        out = os.path.join(self.tmp.name, "thermo.png")
        log = parse_log(self.path)
        plot_logs([log, log], out, columns=[("PotEng", "energy"), ("c_cell[1]", None)], refs={"c_cell[1]": 3.81})
        self.assertTrue(is_png(out))
        csv = os.path.join(self.tmp.name, "thermo.csv")
        write_csv(log, csv)
        with open(csv) as f:
            lines = f.read().splitlines()
        self.assertEqual(lines[0], "time,Step,PotEng,c_cell[1],f_act[1],f_act[2]")
        self.assertEqual(len(lines), 8)
        with self.assertRaises(KeyError):
            plot_logs([log], out, columns=[("nosuch", None)])


class AgainstLammpsLogFile(unittest.TestCase):
    """parse_log agrees with python3-lammps's own reader (lammps.formats.LogFile) on the
    examples' reference logs.  The tools keep their own parser because LogFile drops a run
    that died before 'Loop time' and the rows of a run whose values print as nan."""

    def test_reference_logs(self):
        try:
            from lammps.formats import LogFile
        except ImportError:
            self.skipTest("python3-lammps is not installed")
        examples = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")
        logs = sorted(os.path.join(examples, d, f) for d in os.listdir(examples)
                      if os.path.isdir(os.path.join(examples, d))
                      for f in os.listdir(os.path.join(examples, d)) if f.startswith("log."))
        self.assertGreater(len(logs), 3)
        for path in logs:
            with self.subTest(log=os.path.relpath(path, examples)):
                ours, theirs = parse_log(path), LogFile(path)
                self.assertEqual(len(ours.runs), len(theirs.runs))
                for run, ref in zip(ours.runs, theirs.runs):
                    self.assertEqual(run.names, list(ref))
                    for name in run.names:
                        np.testing.assert_array_equal(run[name], np.array(ref[name], dtype=float))


if __name__ == "__main__":
    unittest.main()
