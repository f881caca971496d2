# SPDX-License-Identifier: GPL-2.0-or-later
"""Smoke tests of the commands: they run and write real pictures."""

import contextlib
import io
import math
import os
import subprocess
import tempfile
import unittest

import numpy as np

from helpers import TOOLS, frame_from, hex_lattice, is_png
from tessera_tools.cli import main
from tessera_tools.dump import write_dump
from tessera_tools.render import render_frame


def run(*argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(list(argv))
        except SystemExit as stop:
            code = stop.code if isinstance(stop.code, int) else 1
            err.write(str(stop.code))
    return code, out.getvalue(), err.getvalue()


class Commands(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        rng = np.random.default_rng(4)
        pts, box = hex_lattice(8, 8)
        n = len(pts)
        theta = rng.uniform(0, 2 * math.pi, n)
        # two anti-parallel streams along x plus a little noise
        stream = np.where(pts[:, 1] < box.ly / 2, 1.0, -1.0)
        frames, r = [], pts + rng.normal(0, 0.1, pts.shape)
        unwrapped = r.copy()
        for k in range(8):
            v = np.column_stack([stream, np.zeros(n)]) + rng.normal(0, 0.3, (n, 2))
            wrapped = box.wrap(unwrapped)
            frames.append(frame_from(wrapped, box, timestep=50 * k, xu=unwrapped[:, 0], yu=unwrapped[:, 1],
                                     vx=v[:, 0], vy=v[:, 1], mux=np.cos(theta), muy=np.sin(theta),
                                     **{"c_cell[1]": rng.uniform(0.5, 1.5, n)}))
            unwrapped = unwrapped + 0.2 * v
        cls.dump = os.path.join(cls.tmp.name, "dump.cells")
        write_dump(cls.dump, frames)
        cls.log = os.path.join(cls.tmp.name, "log.lammps")
        with open(cls.log, "w") as f:
            f.write("timestep 0.01\nStep PotEng c_cell[3] f_act[1]\n0 1.0 4.2 0.1\n100 0.5 4.0 0.5\n"
                    "Loop time of 1.0\n")

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def out(self, name):
        return os.path.join(self.tmp.name, name)

    def test_render_fields_and_views(self):
        for field, extra in (("area", []), ("shape", ["--centres"]), ("polarity", ["--arrows", "mux", "muy"]),
                             ("c_cell[1]", ["--view", "cells", "--highlight", "3", "9"]),
                             ("coordination", ["--frame", "2"]), ("orientation", ["--timestep", "100"]),
                             ("sides", []), ("none", [])):
            name = self.out(f"render_{field.replace('[', '_').replace(']', '')}.png")
            code, text, err = run("render", self.dump, "-o", name, "-f", field, *extra)
            self.assertEqual(code, 0, err)
            self.assertTrue(is_png(name), field)
            self.assertIn("cells", text)

    def test_render_series_as_pngs_and_gif(self):
        code, text, err = run("render", self.dump, "-o", self.out("f_{timestep:04d}.png"), "--frames", "0:6:2")
        self.assertEqual(code, 0, err)
        for t in (0, 100, 200):
            self.assertTrue(is_png(self.out(f"f_{t:04d}.png")))
        from matplotlib import animation

        gif = self.out("movie.gif")
        code, text, err = run("render", self.dump, "-o", gif, "--frames", "::3")
        if animation.writers.is_available("pillow"):
            self.assertEqual(code, 0, err)
            with open(gif, "rb") as f:
                self.assertEqual(f.read(4), b"GIF8")
        else:
            self.assertNotEqual(code, 0)
            self.assertIn("python3-pil", err)

    def test_render_errors_are_messages(self):
        code, _, err = run("render", self.dump, "-o", self.out("x.png"), "-f", "nosuchfield")
        self.assertEqual(code, 1)
        self.assertIn("unknown field", err)
        code, _, err = run("render", self.dump, "-o", self.out("x.png"), "--frames", "0:3")
        self.assertNotEqual(code, 0)
        self.assertIn("several frames", err)

    def test_traj_and_histogram(self):
        png, hist = self.out("traj.png"), self.out("hist.png")
        code, text, err = run("traj", self.dump, "-o", png, "--hist", hist)
        self.assertEqual(code, 0, err)
        self.assertTrue(is_png(png) and is_png(hist))
        self.assertIn("mean coordination", text)
        code, text, err = run("traj", self.dump, "-o", self.out("traj_o.png"), "--kind", "orientation", "--wrap",
                              "--orientation-column", "c_cell[1]")
        self.assertEqual(code, 0, err)
        self.assertTrue(is_png(self.out("traj_o.png")))

    def test_log(self):
        png = self.out("log.png")
        code, text, err = run("log", self.log, "-o", png, "--ref", "c_cell[3]=3.81")
        self.assertEqual(code, 0, err)
        self.assertTrue(is_png(png))
        code, text, err = run("log", self.log, "--list")
        self.assertIn("PotEng c_cell[3] f_act[1]", text)

    def test_info_and_executable(self):
        code, text, err = run("info", self.dump, "--stats")
        self.assertEqual(code, 0, err)
        self.assertIn("8 frame(s)", text)
        self.assertIn("mean area 0.866025 (box area / N = 0.866025)", text)
        script = os.path.join(TOOLS, "tessera-tools")
        done = subprocess.run([script, "render", "--help"], capture_output=True, text=True, timeout=60)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("--field", done.stdout)

    def test_render_hexagonal_lattice_picture(self):
        pts, box = hex_lattice(6, 4)
        png = self.out("hex.png")
        tess = render_frame(frame_from(pts, box), png, field="shape")
        self.assertTrue(is_png(png))
        np.testing.assert_allclose(tess.shape_index, math.sqrt(8 * math.sqrt(3)), rtol=1e-9)

    def test_colour_scale_of_a_relaxed_lattice(self):
        """Round-off-level spread is not stretched over the whole colormap; real spread is."""
        import matplotlib.pyplot as plt

        from tessera_tools.render import draw_tessellation
        from tessera_tools.voronoi import tessellate_frame

        pts, box = hex_lattice(6, 4)
        rng = np.random.default_rng(1)
        for noise, uniform in ((1e-7, True), (0.05, False)):
            frame = frame_from(pts + rng.normal(0, noise, pts.shape), box)
            tess = tessellate_frame(frame)
            fig, ax = plt.subplots()
            lo, hi = draw_tessellation(ax, frame, tess, field="area").get_clim()
            plt.close(fig)
            if uniform:
                self.assertAlmostEqual(lo, 0.95 * math.sqrt(3) / 2, places=5)
                self.assertAlmostEqual(hi, 1.05 * math.sqrt(3) / 2, places=5)
            else:
                self.assertAlmostEqual(lo, tess.area.min())
                self.assertAlmostEqual(hi, tess.area.max())


if __name__ == "__main__":
    unittest.main()
