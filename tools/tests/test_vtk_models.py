# SPDX-License-Identifier: GPL-2.0-or-later
"""VTK files of every model from the dumps LAMMPS writes, on analytic cells: finite cells in an
open box (two overlapping discs and an isolated disc: the cells' areas are the discs' less
the lens, exactly, and the polygons' within the arc-sampling bound; also from the centres and
the radius alone), 3d cubes of a simple cubic lattice in a periodic box
(rows shuffled, cells in other images: polyhedra that meshio reads back with volume a^3), the
type contacts of finite and 3d rows, and the error for an open box without a local dump."""

import math
import os
import tempfile
import unittest

import numpy as np

from helpers import frame_from  # noqa: F401 (sets the path)
from tessera_tools.dump import Box, Frame, write_dump
from tessera_tools.junctions import ARC_STEP, contact_lengths, junction_tessellation
from tessera_tools.vtk import frame_cells3d, polyhedron_volume

try:
    import meshio
except ImportError:    # the VTK tests need Debian's python3-meshio
    meshio = None


def write_local(path, box, rows, names, timestep=0):
    flags = " ".join("pp" if p else "ff" for p in box.periodic)
    with open(path, "w") as f:
        f.write(f"ITEM: TIMESTEP\n{timestep}\nITEM: NUMBER OF ENTRIES\n{len(rows)}\n"
                f"ITEM: BOX BOUNDS {flags}\n{box.xlo} {box.xhi}\n{box.ylo} {box.yhi}\n{box.zlo} {box.zhi}\n"
                "ITEM: ENTRIES " + " ".join(names) + "\n")
        for row in rows:
            f.write(" ".join("%.17g" % v for v in row) + "\n")


COLS2 = ["c_l[%d]" % k for k in range(1, 8)]
COLS3 = ["c_l[%d]" % k for k in range(1, 10)]


def finite_case(r=0.8, d=1.1):
    """Cells 1 and 2 (discs of radius r, centres d apart, touching along a chord) and an
    isolated cell 3, in an open box: their rows (counter-clockwise) and exact areas."""
    h = math.sqrt(r * r - d * d / 4)
    c1, c2, c3 = np.array([0.5, 0.3]), np.array([0.5 + d, 0.3]), np.array([4.0, 2.0])
    lo, hi = c1 + [d / 2, -h], c1 + [d / 2, h]
    alpha = math.acos(d / (2 * r))
    arc = r * (2 * math.pi - 2 * alpha)
    rows = [[1, 2, *lo, *hi, 2 * h], [1, 0, *hi, *lo, arc],
            [2, 1, *hi, *lo, 2 * h], [2, 0, *lo, *hi, arc],
            [3, 0, *(c3 + [0.0, r]), *(c3 + [0.0, r]), 2 * math.pi * r]]
    lens = 2 * r * r * alpha - 0.5 * d * 2 * h
    area = [math.pi * r * r - lens / 2] * 2 + [math.pi * r * r]
    theta = [2 * math.pi - 2 * alpha] * 2 + [2 * math.pi]
    box = Box(-2.0, 6.0, -2.0, 4.0, periodic=(False, False, True))
    return box, np.array([c1, c2, c3]), np.array(rows), np.array(area), np.array(theta)


def cube_case(n=2, a=1.3, rng=None):
    """A simple cubic lattice of n^3 cubic cells of side a in a periodic box: rows of compute
    vertex/local in 3d (each face's four edges counter-clockwise seen from the neighbour),
    each cell in a random periodic image, rows shuffled."""
    box = Box(0.0, n * a, 0.0, n * a, zlo=0.0, zhi=n * a, periodic=(True, True, True))
    centres = np.array([((i + 0.5) * a, (j + 0.5) * a, (k + 0.5) * a)
                        for k in range(n) for j in range(n) for i in range(n)])
    index = {(i, j, k): 1 + i + n * j + n * n * k for k in range(n) for j in range(n) for i in range(n)}
    rows = []
    for (i, j, k), cid in index.items():
        shift = (rng.integers(-1, 2, 3) * n * a) if rng is not None else np.zeros(3)
        c = centres[cid - 1] + shift
        for axis in range(3):
            for sign in (1, -1):
                nvec = np.zeros(3)
                nvec[axis] = sign
                u = np.zeros(3)
                u[(axis + 1) % 3] = 1.0
                v = np.cross(nvec, u)
                corners = [c + a / 2 * (nvec + s * u + t * v) for s, t in ((1, 1), (-1, 1), (-1, -1), (1, -1))]
                nb = [i, j, k]
                nb[axis] = (nb[axis] + sign) % n
                for q in range(4):
                    rows.append([cid, index[tuple(nb)], *corners[q], *corners[(q + 1) % 4], a * a])
    rows = np.array(rows)
    if rng is not None:
        rows = rows[rng.permutation(len(rows))]
    return box, centres, rows


@unittest.skipIf(meshio is None, "needs meshio (Debian: python3-meshio)")
class FiniteCells(unittest.TestCase):

    def test_polygons_sample_the_arcs(self):
        box, centres, rows, area, theta = finite_case()
        atoms = frame_from(centres, box)
        local = Frame(0, box, {n: rows[:, k] for k, n in enumerate(COLS2)}, COLS2)
        tess = junction_tessellation(atoms, local)
        r = 0.8
        # the cells' own measures are exact; the polygons sample the arcs
        np.testing.assert_allclose(tess.area, area, rtol=1e-12)
        p12 = rows[0, 6] + rows[1, 6]
        np.testing.assert_allclose(tess.perimeter, [p12, p12, 2 * math.pi * r], rtol=1e-12)
        polygon = np.array([0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
                            for p in tess.polygons])
        bound = r * r * theta * ARC_STEP ** 2 / 12
        self.assertTrue(np.all(polygon <= area + 1e-12))
        self.assertTrue(np.all(polygon >= area - bound))
        self.assertTrue(np.all(area - polygon > 0.0))
        # the arcs are no junctions: 1 and 2 are neighbours, 3 has none
        np.testing.assert_array_equal(tess.sides, [1, 1, 0])
        self.assertEqual([list(nb) for nb in tess.neighbours], [[1], [0], []])

    def test_vtk_of_an_open_box_and_its_errors(self):
        from tessera_tools.cli import main

        box, centres, rows, area, theta = finite_case()
        with tempfile.TemporaryDirectory() as d:
            cells, local = os.path.join(d, "cells.dump"), os.path.join(d, "cells.local")
            write_dump(cells, [frame_from(centres, box)])
            write_local(local, box, rows, COLS2)
            self.assertEqual(main(["vtk", cells, "--local", local, "-o", os.path.join(d, "v"), "-q"]), 0)
            mesh = meshio.read(os.path.join(d, "v_0.vtu"))
            got, stored = {}, {}
            for block, ids, cell_area in zip(mesh.cells, mesh.cell_data["id"], mesh.cell_data["area"]):
                for conn, i, a in zip(block.data, ids, cell_area):
                    p = mesh.points[conn]
                    got[int(i)] = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
                    stored[int(i)] = a
            bound = 0.8 ** 2 * theta * ARC_STEP ** 2 / 12
            for k in range(3):
                self.assertLessEqual(got[k + 1], area[k] + 1e-12)
                self.assertGreaterEqual(got[k + 1], area[k] - bound[k])
                self.assertAlmostEqual(stored[k + 1], area[k], places=12)    # the exact area as cell data
            # without the local dump, the finite cells of the centres (--radius): the same areas
            self.assertEqual(main(["vtk", cells, "--radius", "0.8", "-o", os.path.join(d, "f"), "-q"]), 0)
            mesh = meshio.read(os.path.join(d, "f_0.vtu"))
            for block, ids, cell_area in zip(mesh.cells, mesh.cell_data["id"], mesh.cell_data["area"]):
                for i, a in zip(ids, cell_area):
                    self.assertAlmostEqual(a, area[int(i) - 1], places=12)
            # without the local dump an open box cannot be re-tessellated: say what to do
            with self.assertRaises(SystemExit) as caught:
                main(["vtk", cells, "-o", os.path.join(d, "w"), "-q"])
            self.assertIn("--local", str(caught.exception))
            self.assertIn("not periodic", str(caught.exception))
            with self.assertRaises(SystemExit) as caught:
                main(["info", cells, "--stats"])
            self.assertIn("--local", str(caught.exception))
            self.assertEqual(main(["info", cells, "--stats", "--local", local]), 0)

    def test_contacts_leave_out_the_arcs(self):
        box, centres, rows, _, _ = finite_case()
        atoms = frame_from(centres, box, type=np.array([1, 2, 1]))
        local = Frame(0, box, {n: rows[:, k] for k, n in enumerate(COLS2)}, COLS2)
        h = math.sqrt(0.8 ** 2 - 1.1 ** 2 / 4)
        self.assertEqual(set(contact_lengths(atoms, local)), {(1, 2)})
        self.assertAlmostEqual(contact_lengths(atoms, local)[(1, 2)], 2 * h, places=12)


@unittest.skipIf(meshio is None, "needs meshio (Debian: python3-meshio)")
class Polyhedra(unittest.TestCase):

    def test_cubes_any_image_any_order(self):
        a = 1.3
        box, centres, rows = cube_case(a=a, rng=np.random.default_rng(3))
        atoms = Frame(0, box, {"id": np.arange(1, 9), "type": np.array([1, 2] * 4),
                               "x": centres[:, 0], "y": centres[:, 1], "z": centres[:, 2]})
        local = Frame(0, box, {n: rows[:, k] for k, n in enumerate(COLS3)}, COLS3)
        cells = frame_cells3d(atoms, local)
        np.testing.assert_allclose(cells.volume, a ** 3, rtol=1e-12)
        np.testing.assert_allclose(cells.surface, 6 * a * a, rtol=1e-12)
        np.testing.assert_array_equal(cells.nfaces, 6)
        for i, v in enumerate(cells.vertices):
            self.assertEqual(len(v), 8)
            np.testing.assert_allclose(v.mean(axis=0), centres[i], atol=1e-12)    # next to the centre
        # in a 2 x 2 x 2 box each cell meets each of its 3 neighbours through two faces (images);
        # types alternate along x: the x faces (a third) are heterotypic
        c = contact_lengths(atoms, local)
        self.assertAlmostEqual(sum(c.values()), 8 * 6 * a * a / 2, places=10)
        self.assertAlmostEqual(c[(1, 2)], 8 * 6 * a * a / 2 / 3, places=10)

    def test_vtk_polyhedra_read_back(self):
        from tessera_tools.cli import main

        a = 1.3
        box, centres, rows = cube_case(a=a, rng=np.random.default_rng(4))
        atoms = Frame(0, box, {"id": np.arange(1, 9), "type": np.ones(8, dtype=np.int64),
                               "x": centres[:, 0], "y": centres[:, 1], "z": centres[:, 2]},
                      ["id", "type", "x", "y", "z"])
        with tempfile.TemporaryDirectory() as d:
            cells, local = os.path.join(d, "cells.dump"), os.path.join(d, "cells.local")
            write_dump(cells, [atoms])
            write_local(local, box, rows, COLS3)
            self.assertEqual(main(["vtk", cells, "--local", local, "-o", os.path.join(d, "v"), "-q"]), 0)
            mesh = meshio.read(os.path.join(d, "v_0.vtu"))
            ids = []
            for block, cid, vol in zip(mesh.cells, mesh.cell_data["id"], mesh.cell_data["volume"]):
                self.assertTrue(block.type.startswith("polyhedron"))
                for faces, i, stored in zip(block.data, cid, vol):
                    self.assertEqual(len(faces), 6)
                    v = polyhedron_volume(mesh.points, faces)
                    self.assertAlmostEqual(v, a ** 3, places=12)    # outward faces: positive
                    self.assertAlmostEqual(stored, v, places=12)
                    ids.append(int(i))
            self.assertEqual(sorted(ids), list(range(1, 9)))
            self.assertEqual(main(["info", cells, "--stats", "--local", local]), 0)
            # a 3d dump without the local dump: not re-tessellated in the plane
            with self.assertRaises(SystemExit) as caught:
                main(["vtk", cells, "-o", os.path.join(d, "w"), "-q"])
            self.assertIn("3d", str(caught.exception))
            self.assertIn("--local", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
