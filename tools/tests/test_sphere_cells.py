# SPDX-License-Identifier: GPL-2.0-or-later
"""Cells on a sphere from vertex/local rows: the icosahedron's 12 regular pentagons,
built here from the dodecahedron (the Voronoi vertices are its vertices), read back with
their spherical area 4 pi R^2 / 12 and perimeter; the rows told apart from 3d face rows."""

import math
import unittest

import numpy as np

from helpers import frame_from  # noqa: F401 (sets the path)
from tessera_tools.dump import Box, Frame
from tessera_tools.sphere_cells import fit_sphere, frame_sphere_cells, is_sphere_local

PHI = (1 + math.sqrt(5)) / 2
COLS = ["c_l[%d]" % k for k in range(1, 10)]


def icosahedron():
    v = []
    for s1 in (-1, 1):
        for s2 in (-1, 1):
            v += [(0, s1, PHI * s2), (s1, PHI * s2, 0), (PHI * s2, 0, s1)]
    v = np.array(v, float)
    return v / np.linalg.norm(v, axis=1)[:, None]


def rows_of_icosahedron(c, R):
    """Each cell's edges, counter-clockwise from outside: its 5 Voronoi vertices are the
    (unit) centres of the 5 faces around it."""
    u = icosahedron()
    faces = [(i, j, k) for i in range(12) for j in range(i + 1, 12) for k in range(j + 1, 12)
             if min(u[i] @ u[j], u[j] @ u[k], u[i] @ u[k]) > 0.4]
    rows = []
    for i in range(12):
        around = [f for f in faces if i in f]
        poles = [sum(u[q] for q in f) for f in around]
        poles = [p / np.linalg.norm(p) for p in poles]
        e1 = np.cross(u[i], [0.3, 0.2, 0.9])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(u[i], e1)
        order = np.argsort([math.atan2(p @ e2, p @ e1) for p in poles])
        poles = [poles[k] for k in order]
        for k in range(5):
            a, b = poles[k], poles[(k + 1) % 5]
            nb = [q for q in set(around[order[k]]) & set(around[order[(k + 1) % 5]]) if q != i][0]
            rows.append([i + 1, nb + 1, *(c + R * a), *(c + R * b), R * math.acos(a @ b)])
    return u, np.array(rows)


class SphereRows(unittest.TestCase):
    def test_icosahedron(self):
        c, R = np.array([1.0, -2.0, 0.5]), 3.0
        u, rows = rows_of_icosahedron(c, R)
        box = Box(-10, 10, -10, 10, zlo=-10, zhi=10, periodic=(False, False, False))
        local = Frame(0, box, {n: rows[:, k] for k, n in enumerate(COLS)})
        x = c + R * u
        atoms = Frame(0, box, {"id": np.arange(1, 13), "x": x[:, 0], "y": x[:, 1], "z": x[:, 2]})
        self.assertTrue(is_sphere_local(local))
        cells = frame_sphere_cells(atoms, local)
        np.testing.assert_allclose(cells.centre, c, atol=1e-12)
        self.assertAlmostEqual(cells.radius, R, delta=1e-12)
        np.testing.assert_allclose(cells.area, 4 * math.pi * R * R / 12, rtol=1e-12)
        theta = math.acos(math.sqrt(5) / 3)
        np.testing.assert_allclose(cells.perimeter, 5 * R * theta, rtol=1e-12)
        np.testing.assert_array_equal(cells.sides, 5)

    def test_face_rows_are_not_sphere_rows(self):
        # a 3d face: three rows with one cell and neighbour
        rows = np.array([[1, 2, 0, 0, 0, 1, 0, 0, 0.5], [1, 2, 1, 0, 0, 0, 1, 0, 0.5],
                         [1, 2, 0, 1, 0, 0, 0, 0, 0.5]])
        box = Box(-1, 2, -1, 2, zlo=-1, zhi=2, periodic=(True, True, True))
        self.assertFalse(is_sphere_local(Frame(0, box, {n: rows[:, k] for k, n in enumerate(COLS)})))

    def test_fit_sphere(self):
        rng = np.random.default_rng(2)
        p = rng.normal(size=(50, 3))
        p = np.array([4.0, 5.0, -1.0]) + 2.5 * p / np.linalg.norm(p, axis=1)[:, None]
        c, r = fit_sphere(p)
        np.testing.assert_allclose(c, [4.0, 5.0, -1.0], atol=1e-12)
        self.assertAlmostEqual(r, 2.5, delta=1e-12)


if __name__ == "__main__":
    unittest.main()
