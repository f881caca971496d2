# SPDX-License-Identifier: GPL-2.0-or-later
"""Finite Voronoi cells in the tools: closed-form disc and two-cell values,
a periodic lattice whose cells are whole Voronoi polygons (r large) or
discs (r small), outlines that follow the arcs, and a rendered picture."""

import math
import os
import tempfile
import unittest

import numpy as np

from helpers import Box, frame_from, hex_lattice, is_png  # noqa: F401 (sets the path)

from tessera_tools.finite import finite_voronoi
from tessera_tools.render import render_frame


def open_box(lo=-3.0, hi=8.0):
    return Box(lo, hi, lo, hi, periodic=(False, False, True))


class FiniteCells(unittest.TestCase):
    def test_disc_and_two_cells(self):
        r, d = 0.8, 1.3
        pts = np.array([[0.0, 0.0], [4.0, 4.0], [4.0 + d, 4.0]])
        t = finite_voronoi(pts, open_box(), r)
        self.assertAlmostEqual(t.area[0], math.pi * r * r, places=12)
        self.assertAlmostEqual(t.perimeter[0], 2 * math.pi * r, places=12)
        self.assertAlmostEqual(t.free_length[0], 2 * math.pi * r, places=12)
        alpha = math.acos(d / (2 * r))
        for c in (1, 2):
            self.assertAlmostEqual(t.area[c], r * r * (math.pi - alpha + math.sin(alpha) * math.cos(alpha)),
                                   places=12)
            self.assertAlmostEqual(t.free_length[c], 2 * r * (math.pi - alpha), places=12)
            self.assertAlmostEqual(t.perimeter[c], 2 * r * (math.pi - alpha) + 2 * r * math.sin(alpha),
                                   places=12)
        self.assertEqual([list(n) for n in t.neighbours], [[], [2], [1]])
        self.assertTrue(all(t.at_edge))
        # The outline follows the arc: every sampled point of the free part is at distance r.
        arc = np.vstack(t.arcs[1])
        np.testing.assert_allclose(np.linalg.norm(arc - pts[1], axis=1), r, atol=1e-12)

    def test_periodic_lattice_limits(self):
        pts, box = hex_lattice(6, 6)
        # r beyond the Voronoi vertices (1/sqrt 3): the hexagons, no free arcs.
        t = finite_voronoi(pts, box, 0.6)
        np.testing.assert_allclose(t.area, math.sqrt(3) / 2, rtol=1e-12)
        np.testing.assert_allclose(t.free_length, 0.0, atol=1e-12)
        self.assertTrue(all(len(n) == 6 for n in t.neighbours))
        # r < 1/2: separate discs.
        t = finite_voronoi(pts, box, 0.45)
        np.testing.assert_allclose(t.area, math.pi * 0.45 ** 2, rtol=1e-12)
        # In between: hexagons with rounded corners; area below the hexagon's.
        t = finite_voronoi(pts, box, 0.55)
        self.assertTrue(np.all(t.area < math.sqrt(3) / 2) and np.all(t.free_length > 0))
        np.testing.assert_allclose(t.area, t.area[0], rtol=1e-10)

    def test_render_open_box(self):
        rng = np.random.default_rng(2)
        pts = rng.uniform(0, 4, size=(20, 2))
        frame = frame_from(pts, open_box(-1, 5))
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "cells.png")
            t = render_frame(frame, out, field="free", radius=0.6)
            self.assertTrue(is_png(out))
            self.assertEqual(len(t), 20)


if __name__ == "__main__":
    unittest.main()
