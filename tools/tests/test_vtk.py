# SPDX-License-Identifier: GPL-2.0-or-later
"""Cell polygons from a dump local of compute vertex/local, and the VTK files made of them:
analytic hexagonal tilings (cells crossing the periodic boundary, rows in any order), files
read back with meshio, the ParaView time series, and the renderer drawing these polygons."""

import json
import math
import os
import tempfile
import unittest
import xml.etree.ElementTree as ET

import numpy as np

from helpers import frame_from, hex_lattice, is_png  # noqa: F401 (sets the path)
from tessera_tools.dump import Frame, iter_dump, write_dump
from tessera_tools.junctions import junction_tessellation

try:
    import meshio
except ImportError:    # the VTK tests need Debian's python3-meshio
    meshio = None

COLS = ["c_junc[%d]" % k for k in range(1, 8)]


def hex_junctions(points, box, a, shuffle=None, image_of=None):
    """Rows of compute vertex/local for a hexagonal lattice of spacing a, built from the
    analytic hexagon (circumradius a/sqrt 3, vertices at 30 + 60 k degrees) around each
    centre, with each cell given in the periodic image image_of(i) (a box-vector shift)."""
    r = a / math.sqrt(3.0)
    angles = np.radians(30.0 + 60.0 * np.arange(7))
    rows = []
    centres = np.asarray(points)
    for i, c in enumerate(centres):
        shift = image_of(i) if image_of else np.zeros(2)
        v = c + shift + r * np.column_stack([np.cos(angles), np.sin(angles)])
        for k in range(6):
            mid = 0.5 * (v[k] + v[k + 1])
            # the neighbour across edge k: the centre mirrored through the edge midpoint
            other = box.wrap((2 * mid - c - shift)[None, :])[0]
            j = int(np.argmin(np.linalg.norm(box.minimum_image(centres - other), axis=1)))
            rows.append([i + 1, j + 1, v[k][0], v[k][1], v[k + 1][0], v[k + 1][1], r])
    rows = np.array(rows)
    if shuffle is not None:
        rows = rows[shuffle.permutation(len(rows))]
    cols = {name: rows[:, k] for k, name in enumerate(COLS)}
    return cols


def local_frame(box, cols, timestep=0):
    return Frame(timestep, box, cols, COLS)


class Junctions(unittest.TestCase):

    def setUp(self):
        self.a = 1.3
        self.points, self.box = hex_lattice(6, 4, a=self.a, origin=(-0.4, 0.25))
        self.hex_area = math.sqrt(3.0) / 2.0 * self.a ** 2

    def test_hexagons_any_image_any_order(self):
        rng = np.random.default_rng(5)
        shifts = rng.integers(-1, 2, size=(len(self.points), 2)) @ self.box.matrix.T
        cols = hex_junctions(self.points, self.box, self.a, shuffle=rng, image_of=lambda i: shifts[i])
        atoms = frame_from(self.points, self.box)
        tess = junction_tessellation(atoms, local_frame(self.box, cols))
        np.testing.assert_allclose(tess.area, self.hex_area, rtol=1e-12)
        np.testing.assert_allclose(tess.perimeter, 6 * self.a / math.sqrt(3.0), rtol=1e-12)
        np.testing.assert_array_equal(tess.sides, 6)
        for i, poly in enumerate(tess.polygons):
            # brought back around the wrapped centre
            np.testing.assert_allclose(poly.mean(axis=0), tess.points[i], atol=1e-12)
        # neighbours mutual: six each
        for i, nb in enumerate(tess.neighbours):
            self.assertEqual(len(nb), 6)
            for j in nb:
                self.assertIn(i, tess.neighbours[j])

    def test_contact_lengths_of_striped_types(self):
        """Rows of alternating types: each cell has 2 same-type neighbours in its row and 4 of
        the other type, every junction of length a/sqrt 3, so 2/3 of the contacts are heterotypic."""
        from tessera_tools.junctions import contact_lengths

        n = len(self.points)
        row = np.round((self.points[:, 1] - self.points[:, 1].min()) / (self.a * math.sqrt(3) / 2)).astype(int)
        atoms = frame_from(self.points, self.box, type=(row % 2) + 1)
        cols = hex_junctions(self.points, self.box, self.a, shuffle=np.random.default_rng(2))
        side = self.a / math.sqrt(3.0)
        got = contact_lengths(atoms, local_frame(self.box, cols))
        self.assertEqual(sorted(got), [(1, 1), (1, 2), (2, 2)])
        self.assertAlmostEqual(got[(1, 1)], n / 2 * side, places=10)
        self.assertAlmostEqual(got[(2, 2)], n / 2 * side, places=10)
        self.assertAlmostEqual(got[(1, 2)], 2 * n * side, places=10)

    def test_missing_cell_is_an_error(self):
        cols = hex_junctions(self.points, self.box, self.a)
        keep = cols["c_junc[1]"] != 3
        cols = {k: v[keep] for k, v in cols.items()}
        with self.assertRaisesRegex(ValueError, r"cells \[3\]"):
            junction_tessellation(frame_from(self.points, self.box), local_frame(self.box, cols))


@unittest.skipIf(meshio is None, "meshio (python3-meshio) is not installed")
class VTK(unittest.TestCase):

    def write_dumps(self, d, nframes=3):
        a = 1.0
        points, box = hex_lattice(4, 4, a=a)
        hex_area = math.sqrt(3.0) / 2.0
        atoms, local = [], []
        for t in range(nframes):
            atoms.append(frame_from(points, box, timestep=10 * t, vx=np.full(len(points), 1.0),
                                    vy=np.zeros(len(points)), z=np.zeros(len(points)),
                                    type=np.where(np.arange(len(points)) % 2, 2, 1)))
            local.append(local_frame(box, hex_junctions(points, box, a), timestep=10 * t))
        write_dump(os.path.join(d, "cells.dump"), atoms)
        with open(os.path.join(d, "junctions.dump"), "w") as f:
            for fr in local:
                f.write(f"ITEM: TIMESTEP\n{fr.timestep}\nITEM: NUMBER OF ENTRIES\n{fr.natoms}\n"
                        f"ITEM: BOX BOUNDS pp pp pp\n{box.xlo} {box.xhi}\n{box.ylo} {box.yhi}\n-0.5 0.5\n"
                        "ITEM: ENTRIES " + " ".join(COLS) + "\n")
                for row in zip(*(fr[c] for c in COLS)):
                    f.write(" ".join("%.17g" % v for v in row) + "\n")
        return points, hex_area

    def test_files_parse_back(self):
        from tessera_tools.vtk import write_vtk

        with tempfile.TemporaryDirectory() as d:
            points, hex_area = self.write_dumps(d)
            # the local dump reads back as 96 rows per frame, in file order
            frames = list(iter_dump(os.path.join(d, "junctions.dump")))
            self.assertEqual([len(f) for f in frames], [96, 96, 96])
            written = write_vtk(os.path.join(d, "cells.dump"), os.path.join(d, "out", "cells"),
                                local_path=os.path.join(d, "junctions.dump"), dt=0.5)
            self.assertEqual(len(written), 3)
            for path in written:
                mesh = meshio.read(path)
                ids, areas, types = [], [], []
                for block, cid, ctype, carea in zip(mesh.cells, mesh.cell_data["id"], mesh.cell_data["type"],
                                                    mesh.cell_data["area"]):
                    self.assertEqual(block.type, "polygon")
                    for conn, i, t, stored in zip(block.data, cid, ctype, carea):
                        p = mesh.points[conn]
                        self.assertTrue(np.all(p[:, 2] == 0.0))
                        area = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
                        areas.append(area)
                        self.assertAlmostEqual(stored, area, places=12)
                        ids.append(i)
                        types.append(t)
                np.testing.assert_allclose(areas, hex_area, rtol=1e-12)    # counter-clockwise: positive
                self.assertEqual(sorted(ids), list(range(1, 17)))
                self.assertEqual(sorted(types), [1] * 8 + [2] * 8)
                vel = np.concatenate(mesh.cell_data["velocity"])
                np.testing.assert_array_equal(vel, np.tile([1.0, 0.0, 0.0], (16, 1)))
                self.assertTrue(np.all(np.concatenate(mesh.cell_data["sides"]) == 6))
            # the ParaView time series: files and times
            with open(os.path.join(d, "out", "cells.vtu.series")) as f:
                series = json.load(f)
            self.assertEqual([e["time"] for e in series["files"]], [0.0, 5.0, 10.0])
            self.assertEqual([e["name"] for e in series["files"]], [os.path.basename(p) for p in written])
            pvd = ET.parse(os.path.join(d, "out", "cells.pvd")).getroot()
            sets = pvd.find("Collection").findall("DataSet")
            self.assertEqual([float(s.get("timestep")) for s in sets], [0.0, 5.0, 10.0])
            for s in sets:
                self.assertTrue(os.path.exists(os.path.join(d, "out", s.get("file"))))

    def test_command_line_and_render(self):
        from tessera_tools.cli import main

        with tempfile.TemporaryDirectory() as d:
            self.write_dumps(d, nframes=2)
            cells, junc = os.path.join(d, "cells.dump"), os.path.join(d, "junctions.dump")
            self.assertEqual(main(["vtk", cells, "--local", junc, "-o", os.path.join(d, "v"), "-q"]), 0)
            self.assertTrue(os.path.exists(os.path.join(d, "v_10.vtu")))
            # without the local dump: the Voronoi tessellation of the centres, same hexagons; the
            # dump has two types, so they are named as cells (the local dump's rows said so above)
            self.assertEqual(main(["vtk", cells, "-o", os.path.join(d, "w"), "-q", "--frames", "0",
                                   "--cell-types", "1,2"]), 0)
            mesh = meshio.read(os.path.join(d, "w_0.vtu"))
            np.testing.assert_allclose(np.concatenate(mesh.cell_data["area"]), math.sqrt(3) / 2, rtol=1e-9)
            png = os.path.join(d, "types.png")
            self.assertEqual(main(["render", cells, "--local", junc, "-o", png, "-f", "type",
                                   "--vector", "pdf", "--dpi", "60"]), 0)
            self.assertTrue(is_png(png))
            with open(os.path.join(d, "types.pdf"), "rb") as f:
                self.assertEqual(f.read(5), b"%PDF-")


if __name__ == "__main__":
    unittest.main()
