# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools divisions on event logs with known answers: divisions placed on a sphere at
chosen latitudes and longitudes come back as those angles, about a centre given with
--centre or named by the log's header; the rate histogram counts them per unit time."""

import csv
import math
import os
import tempfile
import unittest

import numpy as np

from helpers import is_png
from test_particles import run
from tessera_tools.divisions import division_table, rate_histogram, sphere_centre

C = (10.0, 12.0, 9.0)
LAT = [0.0, 45.0, -30.0, 89.0, -89.5, 12.5]
LON = [0.0, 90.0, -120.0, 179.0, -45.0, 33.3]


def write_log(path, header=""):
    with open(path, "w") as f:
        f.write("# Tessera event log of fix div cell/divide (units lj)" + header + "\n")
        f.write("# step time event id daughter1 daughter2 x y z\n")
        for k, (la, lo) in enumerate(zip(LAT, LON)):
            r = 3.0 + 0.5 * k       # the sphere's radius need not be known (it may grow)
            p = np.array(C) + r * np.array([math.cos(math.radians(la)) * math.cos(math.radians(lo)),
                                            math.cos(math.radians(la)) * math.sin(math.radians(lo)),
                                            math.sin(math.radians(la))])
            f.write(f"{10 * (k + 1)} {0.1 * (k + 1):.10g} divide {k + 1} {k + 1} {100 + k} "
                    f"{p[0]:.10g} {p[1]:.10g} {p[2]:.10g}\n")
        f.write("75 0.75 death 3 0 0 1 1 1\n")          # deaths are no divisions


class Divisions(unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.log = os.path.join(self.tmp.name, "div.log")

    def check_angles(self, rows):
        self.assertEqual(len(rows), len(LAT))
        for r, la, lo in zip(rows, LAT, LON):
            self.assertAlmostEqual(float(r["latitude"]), la, delta=1e-6)
            self.assertAlmostEqual(float(r["longitude"]), lo, delta=1e-6)

    def test_centre_given(self):
        write_log(self.log)
        self.assertIsNone(sphere_centre(self.log))
        out = os.path.join(self.tmp.name, "d.csv")
        png = os.path.join(self.tmp.name, "d.png")
        code, text, err = run(["divisions", self.log, "--centre", *map(str, C), "--csv", out, "-o", png,
                               "--dpi", "40"])
        self.assertEqual(code, 0, err)
        with open(out) as f:
            self.check_angles(list(csv.DictReader(f)))
        self.assertTrue(is_png(png))
        self.assertIn("6 divisions", text)
        # without a centre: positions only
        code, text, err = run(["divisions", self.log, "--csv", out])
        self.assertEqual(code, 0, err)
        with open(out) as f:
            self.assertNotIn("latitude", f.readline())

    def test_centre_from_the_header(self):
        write_log(self.log, f" surface sphere {C[0]} {C[1]} {C[2]} 4.5")
        self.assertEqual(sphere_centre(self.log), C)
        out = os.path.join(self.tmp.name, "d.csv")
        code, text, err = run(["divisions", self.log, "--csv", out])
        self.assertEqual(code, 0, err)
        self.assertIn("named by the log's header", text)
        with open(out) as f:
            self.check_angles(list(csv.DictReader(f)))
        other = os.path.join(self.tmp.name, "other.log")
        with open(other, "w") as f:
            f.write("# Tessera event log of fix d2 cell/divide (units lj) surface sphere 0 0 0 4\n")
        with self.assertRaises(ValueError):
            division_table([self.log, other], "header")

    def test_rate(self):
        write_log(self.log)
        t = division_table(self.log)["time"]
        edges, rate, err = rate_histogram(t, bins=3, span=(0.0, 0.6))
        np.testing.assert_allclose(rate, [1 / 0.2, 2 / 0.2, 3 / 0.2])
        np.testing.assert_allclose(err, np.sqrt([1, 2, 3]) / 0.2)


if __name__ == "__main__":
    unittest.main()
