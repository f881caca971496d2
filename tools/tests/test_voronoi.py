# SPDX-License-Identifier: GPL-2.0-or-later
import math
import unittest

import numpy as np
from scipy.spatial import Voronoi

from helpers import hex_lattice, square_lattice
from tessera_tools.dump import Box
from tessera_tools.voronoi import HEXAGON_SHAPE_INDEX, VoronoiError, periodic_voronoi


def brute_force_areas(points, box, reach=2):
    """Oracle: Voronoi of the centres and all (2 reach + 1)^2 images, no margin logic."""
    frac = box.to_fractional(points)
    frac -= np.floor(frac)
    shifts = [(i, j) for i in range(-reach, reach + 1) for j in range(-reach, reach + 1)]
    shifts.remove((0, 0))
    allfrac = np.vstack([frac] + [frac + s for s in shifts])
    vor = Voronoi(box.to_cartesian(allfrac))
    areas = []
    for k in range(len(points)):
        verts = vor.vertices[vor.regions[vor.point_region[k]]]
        c = verts.mean(axis=0)
        verts = verts[np.argsort(np.arctan2(*(verts - c).T[::-1]))]
        x, y = verts.T
        areas.append(0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)))
    return np.array(areas)


class PeriodicVoronoi(unittest.TestCase):
    def test_hexagonal_lattice(self):
        a = 1.3
        pts, box = hex_lattice(8, 6, a=a, origin=(-2.0, 1.0))
        # a rigid shift moves some centres across the boundary; nothing may change
        pts = pts + np.array([0.37, -0.61])
        tess = periodic_voronoi(pts, box)
        self.assertAlmostEqual(HEXAGON_SHAPE_INDEX, 3.7224, places=4)
        np.testing.assert_allclose(tess.area, math.sqrt(3) / 2 * a * a, rtol=1e-10)
        np.testing.assert_allclose(tess.shape_index, HEXAGON_SHAPE_INDEX, rtol=1e-10)
        np.testing.assert_allclose(tess.perimeter, 6 * a / math.sqrt(3), rtol=1e-10)
        np.testing.assert_array_equal(tess.sides, 6)
        self.assertTrue(all(len(nb) == 6 for nb in tess.neighbours))
        np.testing.assert_allclose(tess.elongation(), 1.0, atol=1e-9)

    def test_square_lattice_degenerate_vertices(self):
        """Four co-circular centres per vertex: every cell is a unit square with four neighbours."""
        pts, box = square_lattice(6)
        tess = periodic_voronoi(pts, box)
        np.testing.assert_allclose(tess.area, 1.0, rtol=1e-12)
        np.testing.assert_allclose(tess.perimeter, 4.0, rtol=1e-12)
        np.testing.assert_array_equal(tess.sides, 4)
        for i, nb in enumerate(tess.neighbours):
            d = box.minimum_image(pts[nb] - pts[i])
            np.testing.assert_allclose(np.sort(np.linalg.norm(d, axis=1)), 1.0, rtol=1e-12)
        for poly in tess.polygons:
            self.assertEqual(len(poly), 4)

    def test_random_points_tile_the_box(self):
        rng = np.random.default_rng(3)
        for box in (Box(-1.0, 6.0, 2.0, 5.0), Box(0.0, 5.0, 0.0, 4.0, xy=1.7), Box(0.0, 3.0, 0.0, 9.0, xy=-2.2)):
            for n in (1, 2, 5, 60):
                # centres scattered well outside the box are wrapped in
                pts = rng.uniform(-10, 10, size=(n, 2))
                tess = periodic_voronoi(pts, box)
                self.assertAlmostEqual(tess.area.sum(), box.area, places=9, msg=f"{box} n={n}")
                self.assertTrue(np.all(tess.area > 0))
                if n >= 5:
                    np.testing.assert_allclose(np.sort(tess.area), np.sort(brute_force_areas(pts, box)),
                                               rtol=1e-9)

    def test_neighbours_symmetric_and_translation_invariant(self):
        rng = np.random.default_rng(11)
        box = Box(0.0, 8.0, 0.0, 6.0, xy=0.9)
        pts = rng.uniform(0, 1, size=(80, 2)) @ box.matrix.T
        tess = periodic_voronoi(pts, box)
        for i, nb in enumerate(tess.neighbours):
            for j in nb:
                self.assertIn(i, tess.neighbours[j])
        self.assertAlmostEqual(tess.sides.mean(), 6.0, places=9)  # Euler: mean z = 6 on a torus
        moved = periodic_voronoi(pts + np.array([3.3, -7.1]), box)
        np.testing.assert_allclose(moved.area, tess.area, rtol=1e-9)
        np.testing.assert_allclose(moved.perimeter, tess.perimeter, rtol=1e-9)
        self.assertEqual([list(n) for n in moved.neighbours], [list(n) for n in tess.neighbours])

    def test_polygons_counter_clockwise_around_their_centres(self):
        rng = np.random.default_rng(5)
        box = Box(0.0, 5.0, 0.0, 5.0)
        pts = rng.uniform(0, 5, size=(30, 2))
        tess = periodic_voronoi(pts, box)
        for centre, poly in zip(tess.points, tess.polygons):
            d = poly - centre
            cross = d[:, 0] * np.roll(d[:, 1], -1) - d[:, 1] * np.roll(d[:, 0], -1)
            self.assertTrue(np.all(cross > 0))

    def test_long_axis_of_stretched_lattice(self):
        pts, box = square_lattice(4)
        stretched = pts * [2.0, 1.0]
        tess = periodic_voronoi(stretched, Box(0, 8, 0, 4))
        np.testing.assert_allclose(tess.long_axis_angle(), 0.0, atol=1e-9)
        np.testing.assert_allclose(tess.elongation(), 2.0, rtol=1e-9)
        tall = periodic_voronoi(pts * [1.0, 3.0], Box(0, 4, 0, 12))
        np.testing.assert_allclose(tall.long_axis_angle(), math.pi / 2, atol=1e-9)

    def test_coincident_centres_name_the_atoms(self):
        box = Box(0.0, 4.0, 0.0, 4.0)
        pts = np.array([[0.5, 0.5], [2.0, 2.0], [3.0, 1.0], [2.0, 2.0]])
        with self.assertRaises(VoronoiError) as ctx:
            periodic_voronoi(pts, box, ids=[10, 20, 30, 40])
        self.assertIn("20 and 40", str(ctx.exception))
        # the same position seen through the periodic boundary
        pts = np.array([[0.0, 1.0], [4.0, 1.0], [2.0, 3.0]])
        with self.assertRaises(VoronoiError) as ctx:
            periodic_voronoi(pts, box, ids=[7, 8, 9])
        self.assertIn("7 and 8", str(ctx.exception))

    def test_non_periodic_box_is_refused(self):
        box = Box(0.0, 4.0, 0.0, 4.0, periodic=(True, False, True))
        with self.assertRaises(VoronoiError):
            periodic_voronoi(np.array([[1.0, 1.0], [2.0, 3.0], [3.0, 1.0]]), box)


if __name__ == "__main__":
    unittest.main()
