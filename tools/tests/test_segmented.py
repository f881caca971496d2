# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools segmented: a vertex tissue from a label image, against tilings
whose polygons are known: a brick wall (three-fold junctions, every brick a
hexagon of the brick's exact area), a square grid (four-fold corners split in
two), the example's image (every vertex in three cells, the edges' twins, the
polygons tiling the box, its data file's rings), and the
errors of labels that make no cell."""

import os
import subprocess
import tempfile
import unittest

import numpy as np

import helpers  # noqa: F401  (import path)
from tessera_tools import segmented
from tessera_tools.voronoi import polygon_area
from tessera_tools.vertex_data import VertexData

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "..", "examples", "vertex_segmented")
TOOL = os.path.join(HERE, "..", "tessera-tools")


def bricks(rows=4, per_row=3, w=8, h=5):
    """Bricks of w x h pixels, each row shifted by half a brick."""
    lab = np.zeros((rows * h, per_row * w), dtype=int)
    for r in range(rows):
        for c in range(per_row):
            for j in range(w):
                col = (c * w + j + (r % 2) * (w // 2)) % (per_row * w)
                lab[r * h:(r + 1) * h, col] = 1 + r * per_row + c
    return lab


def check_tissue(tc, t):
    """Every vertex in three rings, every directed edge's twin in another
    ring, positive areas adding up to the box's."""
    count = np.zeros(len(t.vertices), dtype=int)
    edges = {}
    for c, ring in t.rings.items():
        for k, v in enumerate(ring):
            count[v] += 1
            e = (v, ring[(k + 1) % len(ring)])
            tc.assertNotIn(e, edges, f"edge {e} twice")
            edges[e] = c
    np.testing.assert_array_equal(count, 3)
    for a, b in edges:
        tc.assertIn((b, a), edges)
        tc.assertNotEqual(edges[(a, b)], edges[(b, a)])
    areas = {c: polygon_area(t.polygon(c)) for c in t.rings}
    tc.assertTrue(all(a > 0 for a in areas.values()))
    tc.assertAlmostEqual(sum(areas.values()), t.box[0] * t.box[1], delta=1e-9)
    return areas


class Tilings(unittest.TestCase):

    def test_bricks(self):
        lab = bricks()
        t = segmented.tissue_from_labels(lab, pixel=0.5)
        self.assertEqual(sorted(t.rings), list(range(1, 13)))
        self.assertEqual(len(t.vertices), 24)    # two three-fold junctions per cell
        areas = check_tissue(self, t)
        for c, ring in t.rings.items():
            self.assertEqual(len(ring), 6)
            self.assertAlmostEqual(areas[c], 8 * 5 * 0.25, delta=1e-12)

    def test_square_grid_splits_four_fold_corners(self):
        lab = np.kron(np.arange(1, 10).reshape(3, 3), np.ones((6, 6), dtype=int))
        t = segmented.tissue_from_labels(lab)
        self.assertEqual(len(t.vertices), 18)    # 9 corners, two vertices each
        areas = check_tissue(self, t)
        # Each corner's short edge (0.5 * sqrt 2 pixels) lies between two
        # opposite cells: a cell gains or loses two triangles of 1/16 each.
        for a in areas.values():
            self.assertIn(round(a * 16), (36 * 16 - 2, 36 * 16, 36 * 16 + 2))
        d = t.vertices[0::2] - t.vertices[1::2]
        d -= np.array(t.box) * np.round(d / np.array(t.box))
        lengths = np.linalg.norm(d, axis=1)
        np.testing.assert_allclose(lengths, 0.5 * np.sqrt(2.0))

    def test_example_image(self):
        lab = np.loadtxt(os.path.join(EXAMPLE, "labels.txt"), dtype=int)
        lab = segmented.fill_boundaries(np.flipud(lab), 0)
        self.assertFalse(np.any(lab == 0))
        lab, joined = segmented.join_pinches(lab)
        self.assertEqual(segmented._pinches(lab), [])
        t = segmented.tissue_from_labels(lab, pixel=0.0645497)
        self.assertEqual(len(t.rings), 80)
        self.assertEqual(len(t.vertices), 160)
        check_tissue(self, t)

    def test_pinches_are_joined(self):
        # Two pixels swapped across the border of bricks 6 (above) and 1
        # (below): each label then holds two diagonal pixels of a corner.
        lab = bricks()
        lab[5, 2], lab[4, 2] = 1, 6
        self.assertTrue(segmented._pinches(lab))
        with self.assertRaisesRegex(ValueError, "touches itself"):
            segmented.tissue_from_labels(lab)
        fixed, joined = segmented.join_pinches(lab)
        self.assertGreater(joined, 0)
        self.assertEqual(segmented._pinches(fixed), [])
        self.assertEqual(int(np.sum(fixed != lab)), joined)
        check_tissue(self, segmented.tissue_from_labels(fixed))


class Errors(unittest.TestCase):

    def test_labels_that_make_no_cell(self):
        hole = bricks()
        hole[6:8, 6:8] = 99                      # a cell inside brick 4
        two = bricks()
        two[0:2, 0:2] = 5                        # brick 5 in two pieces
        band = np.kron(np.array([[1], [2], [3]]), np.ones((4, 12), dtype=int))
        for lab, fragment in ((hole, "more than one boundary"), (two, "more than one boundary"),
                              (band, "more than one boundary")):
            with self.subTest(fragment):
                with self.assertRaisesRegex(ValueError, fragment):
                    segmented.tissue_from_labels(lab)
        with self.assertRaisesRegex(ValueError, "junction"):
            # a cell between only two others: a lens across a border
            lens = bricks()
            lens[1:3, 6:10] = 77                 # across the border of bricks 1 and 2
            segmented.tissue_from_labels(lens)


class Command(unittest.TestCase):

    def test_example_data_file(self):
        """The example's command: its summary, and a data file whose rings are
        the tissue's (read back: every vertex in three rings)."""
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "tissue.data")
            run = subprocess.run([TOOL, "segmented", os.path.join(EXAMPLE, "labels.txt"),
                                  "--boundary-label", "0", "--pixel", "0.0645497", "-o", out],
                                 capture_output=True, text=True)
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertIn("80 cells, 160 vertices", run.stdout)
            with open(out) as f:
                text = f.read()
        rows = text.split("vring\n\n")[1].strip().split("\n")
        self.assertEqual(len(rows), 240)
        ids = [int(v) for r in rows[:80] for v in r.split()[1:] if v != "0"]
        self.assertEqual(sorted(set(ids)), list(range(81, 241)))
        self.assertTrue(all(ids.count(v) == 3 for v in set(ids)))
        self.assertTrue(all(set(r.split()[1:]) == {"0"} for r in rows[80:]))

    def test_data_file_reads_back(self):
        """write_data's file read by VertexData (the example pictures'
        reader): the same rings and polygons, in both atom styles."""
        t = segmented.tissue_from_labels(bricks(), pixel=0.5)
        with tempfile.TemporaryDirectory() as tmp:
            for style in ("atomic", "dipole"):
                path = os.path.join(tmp, style + ".data")
                ids = segmented.write_data(t, path, atom_style=style)
                d = VertexData(path)
                self.assertEqual((d.lx, d.ly), t.box)
                nc = len(t.rings)
                for label, ring in t.rings.items():
                    self.assertEqual(d.rings[ids[label]], [nc + 1 + v for v in ring])
                    p, q = d.polygon(ids[label]), t.polygon(label)
                    np.testing.assert_allclose(p - p[0], q - q[0], atol=1e-12)

    def test_example_labels_are_make_labels_output(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "labels.txt")
            subprocess.run(["/usr/bin/python3", os.path.join(EXAMPLE, "make_labels.py"), "-o", out],
                           check=True)
            with open(out) as f, open(os.path.join(EXAMPLE, "labels.txt")) as g:
                self.assertEqual(f.read(), g.read())

    def test_bad_input(self):
        with tempfile.TemporaryDirectory() as tmp:
            bad = os.path.join(tmp, "bad.txt")
            with open(bad, "w") as f:
                f.write("1 2 3\n1.5 2 3\n")
            run = subprocess.run([TOOL, "segmented", bad, "-o", os.path.join(tmp, "x.data")],
                                 capture_output=True, text=True)
            self.assertNotEqual(run.returncode, 0)
            self.assertIn("labels must be integers", run.stderr)
            np.save(os.path.join(tmp, "b.npy"), bricks())
            run = subprocess.run([TOOL, "segmented", os.path.join(tmp, "b.npy"), "--maxsides", "4",
                                  "-o", os.path.join(tmp, "x.data")], capture_output=True, text=True)
            self.assertIn("--maxsides 6", run.stderr)


if __name__ == "__main__":
    unittest.main()
