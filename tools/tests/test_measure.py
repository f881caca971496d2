# SPDX-License-Identifier: GPL-2.0-or-later
"""Measurements and their plots (tessera-tools plot ..., info --local): every expected value is
analytic (hexagonal lattices with known type patterns, exact exponentials and lines, hexagons cut
by discs), never output of the tools captured once."""

import csv
import math
import os
import re
import tempfile
import unittest

import numpy as np

from helpers import frame_from, hex_lattice, is_png
from test_cli import run
from test_vtk import COLS, hex_junctions
from tessera_tools.dump import write_dump
from tessera_tools.measure import demix_series, exponential_fit, frame_series, half_time, shape_samples

Q_HEX = math.sqrt(8 * math.sqrt(3))


def write_local(path, box, frames):
    """A dump local of compute vertex/local: frames = [(timestep, cols)]."""
    with open(path, "w") as f:
        for timestep, cols in frames:
            n = len(cols[COLS[0]])
            f.write(f"ITEM: TIMESTEP\n{timestep}\nITEM: NUMBER OF ENTRIES\n{n}\n"
                    f"ITEM: BOX BOUNDS pp pp pp\n{box.xlo} {box.xhi}\n{box.ylo} {box.yhi}\n-0.5 0.5\n"
                    "ITEM: ENTRIES " + " ".join(COLS) + "\n")
            for row in zip(*(cols[c] for c in COLS)):
                f.write(" ".join("%.17g" % v for v in row) + "\n")


class Demixing(unittest.TestCase):
    """8 x 8 hexagonal lattice, every junction of the same length: 3N junctions.
    Bands of 4 rows: two interfaces, each crossed by 2 junctions per cell of a row: 32 of 192 = 1/6.
    Alternating rows: 4 of 6 junctions per cell heterotypic = 2/3.  One type: 0."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        a = 1.0
        pts, box = hex_lattice(8, 8, a=a)
        row = np.round(pts[:, 1] / (a * math.sqrt(3) / 2)).astype(int)
        types = [np.where(row < 4, 1, 2), row % 2 + 1, np.ones(len(pts), dtype=int)]
        self.expected = [1 / 6, 2 / 3, 0.0]
        atoms = [frame_from(pts, box, timestep=100 * k, type=t) for k, t in enumerate(types)]
        self.cells = os.path.join(self.tmp.name, "cells.dump")
        self.local = os.path.join(self.tmp.name, "junctions.dump")
        write_dump(self.cells, atoms)
        rng = np.random.default_rng(7)
        write_local(self.local, box, [(100 * k, hex_junctions(pts, box, a, shuffle=rng)) for k in range(3)])

    def test_series(self):
        steps, times, frac, het, tot = demix_series(self.cells, self.local)
        np.testing.assert_array_equal(steps, [0, 100, 200])
        self.assertIsNone(times)
        np.testing.assert_allclose(frac, self.expected, atol=1e-12)
        np.testing.assert_allclose(tot, 3 * 64 / math.sqrt(3), rtol=1e-12)    # 3N junctions of a/sqrt 3

    def test_info_prints_every_frame(self):
        code, out, err = run("info", self.cells, "--local", self.local)
        self.assertEqual(code, 0, err)
        rows = [line.split() for line in out.splitlines() if re.match(r"^\d+ ", line)]
        self.assertEqual([int(r[0]) for r in rows], [0, 100, 200])
        np.testing.assert_allclose([float(r[1]) for r in rows], self.expected, atol=1e-6)

    def test_plot_and_csv(self):
        png, table = os.path.join(self.tmp.name, "demix.png"), os.path.join(self.tmp.name, "demix.csv")
        code, out, err = run("plot", "demix", self.cells, self.local, "-o", png, "--csv", table, "--dt", "0.01")
        self.assertEqual(code, 0, err)
        self.assertTrue(is_png(png))
        with open(table) as f:
            rows = list(csv.DictReader(f))
        np.testing.assert_allclose([float(r["heterotypic_fraction"]) for r in rows], self.expected, atol=1e-7)
        np.testing.assert_allclose([float(r["time"]) for r in rows], [0, 1, 2])
        # random mixture of the first frame's types (half and half): 1 - 2 (1/2)^2 = 1/2
        self.assertIn("would give 0.5", out)

    def test_missing_type_column(self):
        pts, box = hex_lattice(8, 8)
        write_dump(self.cells, [frame_from(pts, box)], columns=["id", "x", "y"])
        with self.assertRaisesRegex(KeyError, "no 'type' column"):
            demix_series(self.cells, self.local)


class Growth(unittest.TestCase):

    def test_exact_exponential_with_a_cap(self):
        """N = 50 exp(0.1 t) capped at 500: the plateau is left out, the rate is exact."""
        t = np.arange(0, 40, 2.0)
        n = np.minimum(50 * np.exp(0.1 * t), 500.0)
        fit = exponential_fit(t, n)
        self.assertAlmostEqual(fit["rate"], 0.1, places=12)
        self.assertAlmostEqual(fit["doubling"], math.log(2) / 0.1, places=10)
        self.assertAlmostEqual(fit["N0"], 50.0, places=9)
        self.assertLess(fit["tmax"], math.log(10) / 0.1)

    def test_error_is_the_standard_error_of_the_slope(self):
        rng = np.random.default_rng(11)
        t = np.linspace(0, 20, 41)
        sigma = 0.01
        n = 50 * np.exp(0.1 * t + sigma * rng.standard_normal(len(t)))
        fit = exponential_fit(t, n)
        expected = sigma / math.sqrt(np.sum((t - t.mean()) ** 2))
        self.assertAlmostEqual(fit["rate"], 0.1, delta=5 * expected)
        self.assertGreater(fit["rate_err"], 0.4 * expected)
        self.assertLess(fit["rate_err"], 2.5 * expected)
        self.assertAlmostEqual(fit["doubling_err"], math.log(2) * fit["rate_err"] / fit["rate"] ** 2, places=12)

    def test_plot_from_a_log(self):
        with tempfile.TemporaryDirectory() as d:
            log = os.path.join(d, "log.lammps")
            with open(log, "w") as f:
                f.write("timestep 0.02\nStep Time Atoms f_div[2]\n")
                for step in range(0, 1300, 100):
                    t = step * 0.02
                    f.write(f"{step} {t:g} {min(round(50 * math.exp(0.1 * t)), 500)} 0\n")
                f.write("Loop time of 1 on 1 procs for 1200 steps with 500 atoms\n")
            png = os.path.join(d, "growth.png")
            code, out, err = run("plot", "growth", log, "-o", png, "--cap", "500")
            self.assertEqual(code, 0, err)
            self.assertTrue(is_png(png))
            rate = float(re.search(r"r = ([0-9.e+-]+) \+-", out).group(1))
            self.assertAlmostEqual(rate, 0.1, delta=2e-3)     # N rounded to integers
            code, out, err = run("plot", "growth", log, "-o", png, "-c", "Cells")
            self.assertNotEqual(code, 0)
            self.assertIn("no thermo column 'Cells'", err)


class Wound(unittest.TestCase):

    def test_half_time(self):
        t = np.linspace(0, 10, 11)
        self.assertAlmostEqual(half_time(t, 10 * (1 - t / 8)), 4.0, places=12)
        self.assertAlmostEqual(half_time(t, 7.0 * np.exp(-t / 3)), 3 * math.log(2), delta=0.05)
        self.assertTrue(math.isnan(half_time(t, np.full(11, 3.0) + t)))

    def test_open_area_of_hexagons_cut_by_discs(self):
        """Finite cells of radius r between the apothem h = a/2 and the circumradius: each is the
        disc less six circular segments, the rest of the box is open."""
        a, r = 1.0, 0.55
        pts, box = hex_lattice(6, 4, a=a)
        h = a / 2
        cell = math.pi * r * r - 6 * (r * r * math.acos(h / r) - h * math.sqrt(r * r - h * h))
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "cells.dump")
            write_dump(path, [frame_from(pts, box, timestep=k * 50) for k in range(3)])
            steps, t, y = frame_series(path, "open", dt=0.02, radius=r)
            np.testing.assert_allclose(y, box.area - len(pts) * cell, rtol=1e-6)
            np.testing.assert_allclose(t, [0, 1, 2])
            png = os.path.join(d, "wound.png")
            code, out, err = run("plot", "wound", path, "--radius", str(r), "--dt", "0.02", "-o", png)
            self.assertEqual(code, 0, err)
            self.assertTrue(is_png(png))
            self.assertIn("never", out)      # a constant open area never halves
            code, out, err = run("plot", "wound", path, "-o", png)
            self.assertNotEqual(code, 0)
            self.assertIn("--radius", err)

    def test_log_column(self):
        with tempfile.TemporaryDirectory() as d:
            log = os.path.join(d, "log.lammps")
            with open(log, "w") as f:
                f.write("timestep 0.02\nStep Time v_wound\n")
                for step in range(0, 1100, 100):
                    f.write(f"{step} {step * 0.02:g} {max(14.8 * (1 - step * 0.02 / 16), 0):.6g}\n")
                f.write("Loop time of 1 on 1 procs for 1000 steps with 205 atoms\n")
            png = os.path.join(d, "w.png")
            code, out, err = run("plot", "wound", log, "-c", "v_wound", "-o", png)
            self.assertEqual(code, 0, err)
            self.assertTrue(is_png(png))
            half = float(re.search(r"value at ([0-9.e+-]+) time", out).group(1))
            self.assertAlmostEqual(half, 8.0, places=4)


class Shapes(unittest.TestCase):

    def test_interior_and_rim(self):
        pts, box = hex_lattice(6, 6)
        flag = (np.arange(len(pts)) % 5 == 0).astype(float)
        frame = frame_from(pts, box, **{"c_cell[9]": flag, "c_cell[4]": np.where(flag > 0, 4.0, 6.0)})
        q, z, rim = shape_samples([frame], z_column="c_cell[4]", edge_column="c_cell[9]")
        np.testing.assert_allclose(q, Q_HEX, rtol=1e-10)      # computed: regular hexagons
        np.testing.assert_array_equal(rim, flag > 0)
        np.testing.assert_array_equal(z[rim], 4)
        with tempfile.TemporaryDirectory() as d:
            path, png = os.path.join(d, "cells.dump"), os.path.join(d, "shape.png")
            write_dump(path, [frame])
            code, out, err = run("plot", "shape", path, "--edge", "c_cell[9]", "-o", png)
            self.assertEqual(code, 0, err)
            self.assertTrue(is_png(png))
            self.assertIn(f"rim (free edge): {int(flag.sum())} cells", out)
            self.assertIn(f"interior: {len(pts) - int(flag.sum())} cells, shape index mean 3.72242", out)

    def test_finite_cells_rim_from_free_arcs(self):
        """A hexagonal patch in a large box, radius 0.62 (above the circumradius 0.577 of the
        lattice's hexagons): cells inside the patch are whole hexagons, border cells have free arcs."""
        pts, _ = hex_lattice(6, 6)
        from tessera_tools.dump import Box

        box = Box(-10, 20, -10, 20)
        frame = frame_from(pts, box)
        q, z, rim = shape_samples([frame], radius=0.62)
        centre = np.linalg.norm(pts - pts.mean(axis=0), axis=1)
        # the patch's border is at the rim, its middle is not
        self.assertTrue(rim[np.argmax(centre)])
        self.assertFalse(rim[np.argmin(centre)])
        np.testing.assert_allclose(q[~rim], Q_HEX, rtol=1e-9)


class ModuliPlot(unittest.TestCase):

    def test_rows_drawn_with_their_errors(self):
        from tessera_tools.plots import plot_moduli

        rows = [dict(p0=3.7, route="hessian", G=0.3, G_err=0.01, B=8.0, B_err=0.1),
                dict(p0=3.8, route="hessian", G=0.05, G_err=0.02, B=6.0, B_err=0.4),
                dict(p0=3.6, route="hessian", G=0.55, G_err=float("nan"), B=8.4, B_err=0.05),
                dict(p0=3.7, route="quasistatic", G=0.31, G_err=0.001, B=8.1, B_err=0.01)]
        with tempfile.TemporaryDirectory() as d:
            table = os.path.join(d, "moduli.csv")
            with open(table, "w", newline="") as f:
                w = csv.DictWriter(f, fieldnames=["p0", "route", "states", "G", "G_err", "B", "B_err", "unit"])
                w.writeheader()
                for r in rows:
                    w.writerow(dict(r, states=3, unit="KA A0"))
            png = os.path.join(d, "moduli.png")
            drawn = plot_moduli(rows, png)
            p0, G, Gerr, B, Berr = drawn["hessian"]
            np.testing.assert_array_equal(p0, [3.6, 3.7, 3.8])          # sorted by p0
            np.testing.assert_array_equal(G, [0.55, 0.3, 0.05])
            np.testing.assert_array_equal(Berr, [0.05, 0.1, 0.4])
            code, out, err = run("plot", "moduli", table, "-o", png)
            self.assertEqual(code, 0, err)
            self.assertTrue(is_png(png))
            self.assertIn("hessian: 3 values of p0; quasistatic: 1 values", out)


if __name__ == "__main__":
    unittest.main()
