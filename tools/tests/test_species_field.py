# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools plot field: each cell drawn in the colour of its value of a species column.
On a hexagonal lattice with random d_delta values, the polygon that contains a cell's centre
is filled with the colour map's colour of that cell's value on the scale from the smallest to
the largest value; the command writes the picture from the Voronoi cells of the centres, from
LAMMPS's polygons (--local) and for finite cells (--radius)."""

import contextlib
import io
import os
import tempfile
import unittest

import matplotlib
import numpy as np
from matplotlib.path import Path

from helpers import frame_from, hex_lattice, is_png  # noqa: F401 (sets the path)
from tessera_tools.cli import main
from tessera_tools.dump import write_dump
from tessera_tools.plots import plot_field
from tessera_tools.voronoi import tessellate_frame


class SpeciesField(unittest.TestCase):

    def setUp(self):
        self.points, self.box = hex_lattice(6, 4, a=1.0)
        rng = np.random.default_rng(11)
        self.values = rng.uniform(-2.0, 5.0, len(self.points))
        self.frame = frame_from(self.points, self.box, d_delta=self.values)

    def test_each_cell_in_the_colour_of_its_value(self):
        with tempfile.TemporaryDirectory() as d:
            tess = tessellate_frame(self.frame)
            _, coll, _ = plot_field(self.frame, tess, "d_delta", os.path.join(d, "f.png"), dpi=50)
            colours = coll.get_facecolors()
            paths = coll.get_paths()
            cmap = matplotlib.colormaps["viridis"]
            lo, hi = self.values.min(), self.values.max()
            for i, (centre, v) in enumerate(zip(self.points, self.values)):
                inside = [k for k, p in enumerate(paths) if Path(p.vertices).contains_point(centre)]
                self.assertEqual(len(inside), 1, f"cell {i + 1}")
                np.testing.assert_allclose(colours[inside[0]], cmap((v - lo) / (hi - lo)), atol=1e-12,
                                           err_msg=f"cell {i + 1}")
            self.assertTrue(is_png(os.path.join(d, "f.png")))

    def test_command(self):
        from test_vtk import COLS, hex_junctions

        with tempfile.TemporaryDirectory() as d:
            cells, local = os.path.join(d, "cells.dump"), os.path.join(d, "cells.local")
            write_dump(cells, [self.frame])
            cols = hex_junctions(self.points, self.box, 1.0)
            with open(local, "w") as f:
                f.write(f"ITEM: TIMESTEP\n0\nITEM: NUMBER OF ENTRIES\n{len(cols[COLS[0]])}\n"
                        f"ITEM: BOX BOUNDS pp pp pp\n{self.box.xlo} {self.box.xhi}\n{self.box.ylo} "
                        f"{self.box.yhi}\n-0.5 0.5\nITEM: ENTRIES " + " ".join(COLS) + "\n")
                for row in zip(*(cols[c] for c in COLS)):
                    f.write(" ".join("%.17g" % v for v in row) + "\n")
            for extra in ([], ["--local", local], ["--radius", "0.7"]):
                with self.subTest(extra=extra):
                    out = os.path.join(d, "field.png")
                    text = io.StringIO()
                    with contextlib.redirect_stdout(text):
                        self.assertEqual(main(["plot", "field", cells, "-c", "d_delta", "-o", out, "--dpi", "50"]
                                              + extra), 0)
                    self.assertTrue(is_png(out))
                    self.assertIn(f"d_delta from {self.values.min():.6g} to {self.values.max():.6g}", text.getvalue())
            self.assertEqual(main(["plot", "field", cells, "-c", "d_notch", "-o", out]), 1)


if __name__ == "__main__":
    unittest.main()
