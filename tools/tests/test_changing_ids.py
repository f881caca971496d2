# SPDX-License-Identifier: GPL-2.0-or-later
"""Dividing and dying tissues: frames whose atom IDs change.  traj follows every cell while it
is present and takes the MSD over the cells present in both frames; render draws each frame as
it is.  Displacements are set by hand, so the MSD is known exactly."""

import os
import tempfile
import unittest

import numpy as np

from helpers import hex_lattice, is_png
from test_cli import run
from tessera_tools.dump import Frame, write_dump
from tessera_tools.trajectories import load_trajectory


def changing_frames(d=(0.1, 0.05)):
    """Frame k: the 16 cells of a 4 x 4 lattice moved by k d, except that cell 5 dies after
    frame 0 and cell 17 is born (next to cell 1) in frame 1."""
    pts, box = hex_lattice(4, 4)
    d = np.asarray(d)
    frames = []
    for k in range(3):
        p = pts + k * d
        ids = np.arange(1, 17)
        keep = ids != 5 if k > 0 else np.ones(16, dtype=bool)
        p, ids = p[keep], ids[keep]
        if k > 0:
            p = np.vstack([p, pts[0] + k * d + [0.3, 0.2]])
            ids = np.append(ids, 17)
        cols = {"id": ids, "type": np.ones(len(ids), dtype=np.int64), "x": p[:, 0], "y": p[:, 1],
                "vx": np.full(len(ids), d[0]), "vy": np.full(len(ids), d[1])}
        frames.append(Frame(10 * k, box, cols, list(cols)))
    return frames, box, d


class ChangingIDs(unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.frames, self.box, self.d = changing_frames()
        self.path = os.path.join(self.tmp.name, "cells.dump")
        write_dump(self.path, self.frames)

    def test_trajectory_over_the_union_of_ids(self):
        traj = load_trajectory(self.path, quiet=True)
        np.testing.assert_array_equal(traj.ids, np.arange(1, 18))
        self.assertTrue(traj.changing)
        np.testing.assert_array_equal(traj.present[:, 4], [True, False, False])     # ID 5 died
        np.testing.assert_array_equal(traj.present[:, 16], [False, True, True])     # ID 17 born
        self.assertTrue(np.isnan(traj.positions[1, 4]).all())
        # continuity unwrapping follows the cells across the periodic boundary
        step = traj.positions[2] - traj.positions[1]
        np.testing.assert_allclose(step[traj.present[1] & traj.present[2]], np.tile(self.d, (16, 1)), atol=1e-12)

    def test_msd_over_cells_present_in_both_frames(self):
        traj = load_trajectory(self.path, quiet=True)
        msd, count = traj.msd()
        d2 = float(self.d @ self.d)
        np.testing.assert_allclose(msd, [0.0, d2, 4 * d2], atol=1e-12)
        np.testing.assert_array_equal(count, [16, 15, 15])

    def test_traj_command(self):
        png, msd = os.path.join(self.tmp.name, "traj.png"), os.path.join(self.tmp.name, "msd.dat")
        code, out, err = run("traj", self.path, "-o", png, "--msd", msd, "--dt", "0.5")
        self.assertEqual(code, 0, err)
        self.assertTrue(is_png(png))
        self.assertIn("17 cell IDs (16 in the first frame, 16 in the last)", out)
        self.assertIn("present in both frames", out)
        table = np.loadtxt(msd)
        np.testing.assert_allclose(table[:, 1], [0, 5, 10])      # time = timestep x dt
        np.testing.assert_allclose(table[:, 2], np.array([0, 1, 4]) * float(self.d @ self.d), atol=1e-12)
        np.testing.assert_array_equal(table[:, 3], [16, 15, 15])
        self.assertIn("different atom IDs", err)
        png2 = os.path.join(self.tmp.name, "msd.png")
        code, out, err = run("traj", self.path, "--msd", png2)
        self.assertEqual(code, 0, err)
        self.assertTrue(is_png(png2))

    def test_render_draws_each_frame_as_it_is(self):
        from tessera_tools.render import render_frame

        for frame in self.frames:
            tess = render_frame(frame, os.path.join(self.tmp.name, f"f{frame.timestep}.png"))
            self.assertEqual(len(tess), frame.natoms)
            self.assertAlmostEqual(tess.area.sum(), self.box.area, places=9)
        pattern = os.path.join(self.tmp.name, "frame_{index}.png")
        code, out, err = run("render", self.path, "-o", pattern, "--frames", "all", "-q", "-f", "shape")
        self.assertEqual(code, 0, err)
        for k in range(3):
            self.assertTrue(is_png(pattern.format(index=k)))
        try:
            from PIL import Image
        except ImportError:
            return
        gif = os.path.join(self.tmp.name, "movie.gif")
        code, out, err = run("render", self.path, "-o", gif, "--frames", "all", "-q")
        self.assertEqual(code, 0, err)
        with Image.open(gif) as im:
            self.assertEqual(im.n_frames, 3)


if __name__ == "__main__":
    unittest.main()
