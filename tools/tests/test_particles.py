# SPDX-License-Identifier: GPL-2.0-or-later
"""Atoms that are no cells (particles of other types) in the dumps given to tessera-tools:
with --cell-types they are never tessellated, the cells are those of the dump without the
particles (analytic hexagon areas), vtk writes them as points with their columns, render
draws them, traj leaves them out."""

import io
import math
import os
import tempfile
import unittest
from contextlib import redirect_stderr, redirect_stdout

import numpy as np

from helpers import hex_lattice  # noqa: F401 (sets the path)
from test_vtk import hex_junctions, local_frame
from tessera_tools.cli import main
from tessera_tools.dump import Frame, cell_mask, iter_dump, parse_types, write_dump
from tessera_tools.trajectories import load_trajectory

try:
    import meshio
except ImportError:
    meshio = None


def tissue_with_particles(a=1.2, timestep=0, shift=0.0):
    """A 6x4 hexagonal tissue of type 1 and five particles of types 2 and 3: at triangle centres
    of the lattice, at a cell centre and near a box edge."""
    cells, box = hex_lattice(6, 4, a=a)
    h = a * math.sqrt(3.0) / 2.0
    particles = np.array([[0.5 * a, h / 3.0], [2.5 * a, h / 3.0], cells[9], [3.0 * a, 2.5 * h],
                          [box.xhi - 0.05, 0.3]])
    pos = np.vstack([cells, particles]) + shift
    n, m = len(cells), len(particles)
    # particles first in the file, with IDs among the cells' so that the order is mixed
    ids = np.concatenate([np.arange(1, n + 1) * 2, [1, 3, 5, 7, 9]])
    types = np.concatenate([np.ones(n, int), [2, 2, 3, 2, 3]])
    cols = {"id": ids, "type": types, "x": pos[:, 0], "y": pos[:, 1],
            "vx": np.full(n + m, 0.1), "vy": np.zeros(n + m), "c_f[1]": np.arange(n + m) * 0.5}
    return Frame(timestep, box, cols, list(cols)), n, m, a


def run(argv):
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as stop:
            code = stop.code
    if isinstance(code, str):       # SystemExit("message"): Python prints it and exits with 1
        err.write(code + "\n")
        code = 1
    return code, out.getvalue(), err.getvalue()


class CellTypes(unittest.TestCase):

    def test_parse_types(self):
        self.assertEqual(parse_types("1,3"), {1, 3})
        self.assertEqual(parse_types("1*3"), {1, 2, 3})
        self.assertEqual(cell_mask([1, 2, 3, 7], parse_types("2*")).tolist(), [False, True, True, True])
        self.assertEqual(cell_mask([1, 2, 3], parse_types("*2")).tolist(), [True, True, False])
        for bad in ("a", ",", "1*b"):
            with self.assertRaises(ValueError):
                parse_types(bad)

    def test_types_given_as_text_or_numbers(self):
        """A string, an int or a list selects the same rows as parse_types's set
        (a plain '1' once selected none: its characters are no types)."""
        for given in ("1,3", [1, 3], (3, 1)):
            self.assertEqual(cell_mask([1, 2, 3, 1], given).tolist(), [True, False, True, True])
        self.assertEqual(cell_mask([1, 2, 3], 2).tolist(), [False, True, False])
        self.assertEqual(cell_mask([1, 2, 3], "2*").tolist(), [False, True, True])


class Particles(unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.frames = [tissue_with_particles(timestep=t, shift=0.01 * t)[0] for t in (0, 10, 20)]
        _, self.n, self.m, a = tissue_with_particles()
        self.hex_area = math.sqrt(3.0) / 2.0 * a ** 2
        self.dump = os.path.join(self.dir, "all.dump")
        write_dump(self.dump, self.frames)

    def tearDown(self):
        self.tmp.cleanup()

    def test_split_keeps_rows_together(self):
        frame = next(iter_dump(self.dump, parse_types("1")))
        self.assertEqual(frame.natoms, self.n)
        self.assertEqual(frame.particles.natoms, self.m)
        self.assertTrue(np.all(frame["type"] == 1))
        self.assertEqual(sorted(frame.particles["id"].tolist()), [1, 3, 5, 7, 9])
        # each particle keeps its own row: c_f[1] = 0.5 * (its row in the file)
        for k, i in enumerate(frame.particles["id"]):
            self.assertAlmostEqual(frame.particles["c_f[1]"][k], 0.5 * (self.n + [1, 3, 5, 7, 9].index(i)))

    def test_info_stats_are_those_of_the_cells(self):
        code, out, _ = run(["info", self.dump, "--stats", "--cell-types", "1"])
        self.assertEqual(code, 0, out)
        self.assertIn(f"atoms: {self.n} cells, {self.m} particles (types 2,3)", out)
        mean = float(out.split("mean area ")[1].split()[0])
        self.assertAlmostEqual(mean, self.hex_area, places=5)
        # without --cell-types a dump of several types is refused, naming the types and the option
        code, out, err = run(["info", self.dump, "--stats"])
        self.assertNotEqual(code, 0)
        self.assertIn("type 1: 24 atoms, type 2: 3 atoms, type 3: 2 atoms", err)
        self.assertIn("--cell-types 1 ", err)
        # info alone says what the dump holds, by type
        code, out, err = run(["info", self.dump])
        self.assertEqual(code, 0, err)
        self.assertIn("(type 1: 24, type 2: 3, type 3: 2)", out)
        # all taken for cells, the particles are tessellated: the one at a cell centre is refused
        code, out, err = run(["info", self.dump, "--stats", "--cell-types", "1*3"])
        self.assertNotEqual(code, 0)
        self.assertIn("coincident cell centres", err)
        # and without that one the areas are not the hexagons'
        dump = os.path.join(self.dir, "other.dump")
        frame = self.frames[0]
        write_dump(dump, [frame.subset(frame["id"] != 5)])
        code, out, _ = run(["info", dump, "--stats", "--cell-types", "1,2,3"])
        self.assertGreater(abs(float(out.split("mean area ")[1].split()[0]) - self.hex_area), 0.1)

    def test_cell_types_need_a_type_column(self):
        dump = os.path.join(self.dir, "notype.dump")
        write_dump(dump, self.frames, columns=["id", "x", "y"])
        code, _, err = run(["info", dump, "--cell-types", "1"])
        self.assertNotEqual(code, 0)
        self.assertIn("'type' column", err)

    @unittest.skipIf(meshio is None, "needs python3-meshio")
    def test_vtk_particles_are_points(self):
        prefix = os.path.join(self.dir, "vtk", "t")
        code, out, err = run(["vtk", self.dump, "-o", prefix, "--cell-types", "1", "-q"])
        self.assertEqual(code, 0, err)
        for t, frame in zip((0, 10, 20), iter_dump(self.dump, parse_types("1"))):
            cells = meshio.read(f"{prefix}_{t:02d}.vtu")
            area = np.concatenate(cells.cell_data["area"])
            self.assertEqual(len(area), self.n)
            np.testing.assert_allclose(area, self.hex_area, rtol=1e-9)
            self.assertTrue(np.all(np.concatenate(cells.cell_data["type"]) == 1))
            parts = meshio.read(f"{prefix}_particles_{t:02d}.vtu")
            self.assertEqual(len(parts.points), self.m)
            np.testing.assert_allclose(parts.points[:, :2], frame.particles.positions(), atol=1e-12)
            np.testing.assert_array_equal(parts.point_data["id"], frame.particles["id"])
            np.testing.assert_allclose(parts.point_data["c_f[1]"], frame.particles["c_f[1]"])
            self.assertEqual(parts.point_data["velocity"].shape, (self.m, 3))
        self.assertTrue(os.path.exists(prefix + "_particles.pvd"))

    @unittest.skipIf(meshio is None, "needs python3-meshio")
    def test_vtk_local_with_particles(self):
        # compute vertex/local writes no rows for particles: the atom frames are split to match
        frame, n, m, a = tissue_with_particles()
        cells = frame.subset(frame["type"] == 1)
        local = os.path.join(self.dir, "cells.local")
        cols = hex_junctions(cells.positions(), cells.box, a)
        cols["c_junc[1]"] = cells["id"][cols["c_junc[1]"].astype(int) - 1]
        cols["c_junc[2]"] = cells["id"][cols["c_junc[2]"].astype(int) - 1]
        write_dump(local, [local_frame(cells.box, cols)])
        # write_dump writes ATOMS; a dump local says ENTRIES
        text = open(local).read().replace("NUMBER OF ATOMS", "NUMBER OF ENTRIES").replace("ITEM: ATOMS", "ITEM: ENTRIES")
        open(local, "w").write(text)
        prefix = os.path.join(self.dir, "loc")
        code, out, err = run(["vtk", self.dump, "--local", local, "-o", prefix, "--cell-types", "1", "-q",
                              "--frames", "0"])
        self.assertEqual(code, 0, err)
        mesh = meshio.read(f"{prefix}_0.vtu")
        np.testing.assert_allclose(np.concatenate(mesh.cell_data["area"]), self.hex_area, rtol=1e-9)
        self.assertEqual(len(meshio.read(f"{prefix}_particles_0.vtu").points), m)

    def test_render_draws_particles_apart(self):
        from tessera_tools.render import draw_tessellation
        from tessera_tools.voronoi import tessellate_frame
        import matplotlib.pyplot as plt

        frame = next(iter_dump(self.dump, parse_types("1")))
        fig, ax = plt.subplots()
        tess = tessellate_frame(frame)
        draw_tessellation(ax, frame, tess, field="area")
        self.assertEqual(len(tess), self.n)
        drawn = [np.column_stack(line.get_data()) for line in ax.lines]
        self.assertTrue(any(len(d) == self.m and np.allclose(d, frame.particles.positions()) for d in drawn))
        plt.close(fig)
        png = os.path.join(self.dir, "r.png")
        code, out, err = run(["render", self.dump, "-o", png, "--cell-types", "1", "--dpi", "40"])
        self.assertEqual(code, 0, err)
        self.assertIn(f"{self.n} cells", out)

    def test_traj_follows_cells_only(self):
        traj = load_trajectory(self.dump, cell_types=parse_types("1"))
        self.assertEqual(len(traj.ids), self.n)
        self.assertTrue(np.all(traj.ids % 2 == 0))
        png = os.path.join(self.dir, "traj.png")
        code, out, err = run(["traj", self.dump, "-o", png, "--cell-types", "1", "--dpi", "40"])
        self.assertEqual(code, 0, err)
        self.assertIn(f"{self.n} cells", out)


if __name__ == "__main__":
    unittest.main()
