# SPDX-License-Identifier: GPL-2.0-or-later
"""Per-cell species and other per-atom columns (d_NAME of fix property/atom, c_ID[k], f_ID) as
VTK cell data in every model: the atom dump is written with its rows in a shuffled order (as
LAMMPS writes them without dump_modify sort) and each column's value, a known function of the
cell's ID, must be read back by meshio on the polygon or polyhedron of that ID."""

import math
import os
import tempfile
import unittest

import numpy as np

from helpers import frame_from, hex_lattice  # noqa: F401 (sets the path)
from tessera_tools.cli import main
from tessera_tools.dump import Box, Frame, write_dump

try:
    import meshio
except ImportError:    # the VTK tests need Debian's python3-meshio
    meshio = None

#: the per-atom columns and their values for cell ID i
COLUMNS = {"d_delta": lambda i: np.cos(1.7 * i) + 2.0,
           "d_notch": lambda i: 0.01 * i * i,
           "c_sig[2]": lambda i: -3.0 * i,
           "f_ode": lambda i: np.sqrt(i)}


def atoms_frame(centres, box, rng):
    """The cells with the species columns, rows in a random order."""
    n = len(centres)
    ids = np.arange(1, n + 1)
    order = rng.permutation(n)
    cols = {"id": ids[order], "type": np.ones(n, dtype=np.int64)}
    for k, name in enumerate("xyz"[:centres.shape[1]]):
        cols[name] = centres[order, k]
    for name, f in COLUMNS.items():
        cols[name] = f(ids[order].astype(float))
    return Frame(0, box, cols, list(cols))


def confluent_case():
    from test_vtk import COLS, hex_junctions

    a = 1.0
    points, box = hex_lattice(4, 4, a=a)
    cols = hex_junctions(points, box, a, shuffle=np.random.default_rng(8))
    return points, box, np.column_stack([cols[c] for c in COLS]), COLS


def finite_case():
    from test_vtk_models import COLS2, finite_case as case

    box, centres, rows, _, _ = case()
    return centres, box, rows, COLS2


def cube_case():
    from test_vtk_models import COLS3, cube_case as case

    box, centres, rows = case(a=1.3, rng=np.random.default_rng(4))
    return centres, box, rows, COLS3


def sphere_case():
    from test_sphere_cells import COLS, rows_of_icosahedron

    c, R = np.array([1.0, -2.0, 0.5]), 3.0
    u, rows = rows_of_icosahedron(c, R)
    box = Box(-10, 10, -10, 10, zlo=-10, zhi=10, periodic=(False, False, False))
    return c + R * u, box, rows, COLS


#: model, the cells (centres, box, local rows, local names), extra vtk arguments
CASES = [("confluent, Voronoi of the centres", confluent_case, False, []),
         ("confluent, polygons of compute vertex/local", confluent_case, True, []),
         ("finite, polygons of compute vertex/local", finite_case, True, []),
         ("finite, from the centres and the radius", finite_case, False, ["--radius", "0.8"]),
         ("3d polyhedra", cube_case, True, []),
         ("sphere", sphere_case, True, [])]


@unittest.skipIf(meshio is None, "meshio (python3-meshio) is not installed")
class SpeciesAsCellData(unittest.TestCase):

    def test_every_column_on_its_cell_in_every_model(self):
        from test_vtk_models import write_local

        for label, case, with_local, extra in CASES:
            with self.subTest(label), tempfile.TemporaryDirectory() as d:
                centres, box, rows, names = case()
                cells = os.path.join(d, "cells.dump")
                write_dump(cells, [atoms_frame(centres, box, np.random.default_rng(3))], include_z=False)
                args = ["vtk", cells, "-o", os.path.join(d, "v"), "-q"] + extra
                if with_local:
                    local = os.path.join(d, "cells.local")
                    write_local(local, box, rows, names)
                    args += ["--local", local]
                self.assertEqual(main(args), 0)
                mesh = meshio.read(os.path.join(d, "v_0.vtu"))
                seen = []
                for k, block in enumerate(mesh.cells):
                    ids = np.asarray(mesh.cell_data["id"][k]).astype(int)
                    self.assertEqual(len(ids), len(block.data))
                    seen += ids.tolist()
                    for name, f in COLUMNS.items():
                        self.assertIn(name, mesh.cell_data)
                        np.testing.assert_allclose(mesh.cell_data[name][k], f(ids.astype(float)),
                                                   rtol=1e-12, err_msg=f"{label}: {name}")
                    # the cell of each ID is the one around that ID's centre
                    for conn, i in zip(block.data, ids):
                        corners = np.vstack([mesh.points[f] for f in conn]) if block.type.startswith(
                            "polyhedron") else mesh.points[conn]
                        mid = corners.mean(axis=0)[:centres.shape[1]]
                        gap = centres - mid
                        if box.periodic[0] and box.periodic[1] and centres.shape[1] == 2:
                            gap = box.minimum_image(gap)
                        self.assertEqual(np.argmin(np.linalg.norm(gap, axis=1)) + 1, i, f"{label}: cell {i}")
                self.assertEqual(sorted(seen), list(range(1, len(centres) + 1)))


if __name__ == "__main__":
    unittest.main()
