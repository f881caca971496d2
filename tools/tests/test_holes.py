# SPDX-License-Identifier: GPL-2.0-or-later
"""Open area and holes of finite cells with particles in the box, against a raster computed in
numpy: the union of finite cells is the union of the cells' discs, so a grid point is open
when no cell centre (or periodic image) lies within the radius; the open area is the open
fraction of the box, and the hole around a particle is the connected open region (periodic
labelling) that holds it.  The particles never count as cells with --cell-types, and
plot wound refuses the dump without it.  The hole's length is checked against the closed
form of a site removed from a perfect hexagonal lattice: six arcs of angle
2 (pi/3 - arccos(a / 2r))."""

import csv
import math
import os
import tempfile
import unittest

import numpy as np
from scipy import ndimage
from scipy.spatial import cKDTree

from helpers import hex_lattice
from test_particles import run
from tessera_tools.dump import Frame, read_frame, write_dump
from tessera_tools.finite import finite_voronoi
from tessera_tools.holes import free_loops, particle_holes

A, R, H = 1.0, 0.6, 0.008      # lattice spacing, cell radius, raster spacing


def raster(cells, box, r, h=H):
    """(open mask (ny, nx), xs, ys) of the orthogonal periodic box on a grid of spacing ~h."""
    nx, ny = int(round(box.lx / h)), int(round(box.ly / h))
    xs = box.xlo + (np.arange(nx) + 0.5) * box.lx / nx
    ys = box.ylo + (np.arange(ny) + 0.5) * box.ly / ny
    gx, gy = np.meshgrid(xs - box.xlo, ys - box.ylo)
    tree = cKDTree(np.mod(cells - box.lo, [box.lx, box.ly]), boxsize=[box.lx, box.ly])
    d, _ = tree.query(np.column_stack([gx.ravel(), gy.ravel()]))
    return (d >= r).reshape(ny, nx), xs, ys


def periodic_labels(mask):
    """Connected components of mask on a torus."""
    lab, n = ndimage.label(mask)
    parent = list(range(n + 1))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in list(zip(lab[0], lab[-1])) + list(zip(lab[:, 0], lab[:, -1])):
        if a and b:
            parent[find(a)] = find(b)
    roots = np.array([find(v) if v else 0 for v in range(n + 1)])
    return roots[lab]


def tissue(jitter=0.03, seed=4):
    """An 8 x 8 hexagonal tissue of type-1 cells with two sites emptied and particles: type 2 in
    the first hole (off the site), type 3 in the second, type 2 on top of a cell (covered)."""
    pts, box = hex_lattice(8, 8, a=A)
    rng = np.random.default_rng(seed)
    pts = pts + rng.uniform(-jitter, jitter, pts.shape)
    removed = [18, 45]
    cells = np.delete(pts, removed, axis=0)
    particles = np.array([pts[18] + [0.08, -0.05], pts[45] + [-0.1, 0.02], cells[3] + [0.05, 0.05]])
    pos = np.vstack([cells, particles])
    n = len(cells)
    cols = {"id": np.arange(1, n + 4), "type": np.array([1] * n + [2, 3, 2]), "x": pos[:, 0], "y": pos[:, 1]}
    return Frame(0, box, cols, list(cols)), cells, particles, box


class Holes(unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.frame, self.cells, self.particles, self.box = tissue()
        frames = [self.frame]
        f2, *_ = tissue(seed=9)
        f2.timestep = 100
        frames.append(f2)
        self.dump = os.path.join(self.tmp.name, "all.dump")
        write_dump(self.dump, frames)
        self.open, self.xs, self.ys = raster(self.cells, self.box, R)

    def test_open_area_of_the_cells_alone(self):
        expected = self.open.mean() * self.box.area
        code, out, err = run(["plot", "wound", self.dump, "--radius", str(R), "--cell-types", "1",
                              "-o", os.path.join(self.tmp.name, "w.png"), "--dpi", "40"])
        self.assertEqual(code, 0, err)
        first = float(out.split(" from ")[1].split()[0])
        self.assertAlmostEqual(first, expected, delta=0.005 * expected)
        # the particles taken for cells cover some of it: refused without --cell-types
        code, out, err = run(["plot", "wound", self.dump, "--radius", str(R), "-o", os.path.join(self.tmp.name, "x.png")])
        self.assertNotEqual(code, 0)
        self.assertIn("type 1: 62 atoms, type 2: 2 atoms, type 3: 1 atoms", err)
        self.assertIn("--cell-types", err)
        # box minus cells is the loops' hole area in a periodic box
        tess = finite_voronoi(self.cells, self.box, R)
        holes = sum(lp.area for lp in free_loops(tess) if lp.kind == 0)
        self.assertAlmostEqual(holes, self.box.area - tess.area.sum(), delta=1e-9)

    def test_hole_of_each_particle_against_the_raster(self):
        labels = periodic_labels(self.open)
        pixel = self.box.area / self.open.size
        frame = read_frame(self.dump, 0, cell_types={1})
        rows = {r["id"]: r for r in particle_holes(frame, R)}
        for k, p in enumerate(self.particles):
            pid = len(self.cells) + 1 + k
            i = int(np.argmin(abs(self.xs - p[0])))
            j = int(np.argmin(abs(self.ys - p[1])))
            if labels[j, i] == 0:
                self.assertTrue(rows[pid]["covered"], pid)
                self.assertEqual(rows[pid]["area"], 0.0)
                continue
            area = np.sum(labels == labels[j, i]) * pixel
            self.assertFalse(rows[pid]["covered"])
            self.assertAlmostEqual(rows[pid]["area"], area, delta=0.01 * area, msg=f"particle {pid}")
            self.assertEqual(rows[pid]["cells"], 6)
        self.assertTrue(rows[len(self.cells) + 3]["covered"])
        # the command: a table per particle and frame, a picture
        out = os.path.join(self.tmp.name, "holes.csv")
        code, text, err = run(["holes", self.dump, "--cell-types", "1", "--radius", str(R), "--csv", out,
                               "-o", os.path.join(self.tmp.name, "holes.png"), "--dpi", "40"])
        self.assertEqual(code, 0, err)
        with open(out) as f:
            table = list(csv.DictReader(f))
        self.assertEqual(len(table), 6)          # 3 particles x 2 frames
        first = {int(r["id"]): r for r in table if r["timestep"] == "0"}
        for pid, r in rows.items():
            self.assertAlmostEqual(float(first[pid]["area"]), r["area"], places=9)
        code, _, err = run(["holes", self.dump, "--cell-types", "1", "--radius", str(R), "--particle-types", "3",
                            "--csv", out])
        with open(out) as f:
            self.assertEqual({r["type"] for r in csv.DictReader(f)}, {"3"})

    def test_length_of_a_site_removed_from_a_perfect_lattice(self):
        for a, r in ((1.0, 0.6), (1.0, 0.8), (1.3, 0.9)):
            pts, box = hex_lattice(6, 6, a=a)
            cells = np.delete(pts, 14, axis=0)
            loops = [lp for lp in free_loops(finite_voronoi(cells, box, r)) if lp.kind == 0]
            big = max(loops, key=lambda lp: lp.area)
            self.assertAlmostEqual(big.length, 6 * r * 2 * (math.pi / 3 - math.acos(a / (2 * r))), places=12)
            np.testing.assert_allclose(big.centroid, pts[14], atol=1e-9)
            self.assertEqual(len(big.cells), 6)


def write_loops(path, steps_rows):
    """A dump local of compute vertex/loops with the given {timestep: rows}."""
    with open(path, "w") as f:
        for step, rows in steps_rows.items():
            f.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ENTRIES\n{len(rows)}\n"
                    "ITEM: BOX BOUNDS pp pp pp\n0 8\n0 7\n-0.5 0.5\n"
                    "ITEM: ENTRIES c_l[1] c_l[2] c_l[3] c_l[4] c_l[5] c_l[6] c_l[7]\n")
            for r in rows:
                f.write(" ".join(repr(float(v)) for v in r) + "\n")


class LoopColumn(unittest.TestCase):
    """--loop-column: each particle's loop is the dump's index (compute vertex/loops/atom),
    its values the row of that index: a hole's row is taken as it is, a loop that is no hole
    (a colony the cells of which cover the particle) or index 0 is no hole, an index with no
    row is an error, and so are a missing column and --loop-column without --loops."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        frame, self.cells, self.particles, self.box = tissue()
        n = len(frame["id"])
        index = np.zeros(n)
        index[-3:] = [2, 0, 1]        # particle 1 in hole 2; particle 2 nowhere; 3 on colony 1
        frame.columns["c_la[1]"] = index
        frame.names.append("c_la[1]")
        self.dump = os.path.join(self.tmp.name, "all.dump")
        write_dump(self.dump, [frame])
        self.loops = os.path.join(self.tmp.name, "loops.dump")
        write_loops(self.loops, {0: [[1, 40.0, 25.0, 30, 4.0, 3.0, 1], [2, 0.125, 1.5, 6, 1.0, 2.0, 0]]})
        self.n = n

    def holes(self, *extra):
        out = os.path.join(self.tmp.name, "h.csv")
        code, text, err = run(["holes", self.dump, "--cell-types", "1", "--radius", str(R), "--csv", out,
                               *extra])
        if code:
            return code, err, None
        with open(out) as f:
            return code, text, {int(r["id"]): r for r in csv.DictReader(f)}

    def test_rows_by_index(self):
        for column in ("c_la[1]", "la"):
            code, text, rows = self.holes("--loops", self.loops, "--loop-column", column)
            self.assertEqual(code, 0, text)
            p1, p2, p3 = (rows[self.n - 2], rows[self.n - 1], rows[self.n])
            self.assertEqual((p1["loop"], float(p1["area"]), float(p1["length"]), p1["cells"], p1["from_compute"]),
                             ("2", 0.125, 1.5, "6", "1"))
            for p in (p2, p3):
                self.assertEqual((p["loop"], float(p["area"]), p["from_compute"]), ("0", 0.0, "0"))
            self.assertEqual(p3["covered"], "1")          # on a cell: the distance to its centre
            self.assertEqual(p1["covered"], "0")

    def test_errors(self):
        code, err, _ = self.holes("--loop-column", "c_la[1]")
        self.assertNotEqual(code, 0)
        self.assertIn("--loop-column needs --loops", err)
        code, err, _ = self.holes("--loops", self.loops, "--loop-column", "c_other[1]")
        self.assertNotEqual(code, 0)
        self.assertIn("no column 'c_other[1]'", err)
        write_loops(self.loops, {0: [[1, 40.0, 25.0, 30, 4.0, 3.0, 1]]})
        code, err, _ = self.holes("--loops", self.loops, "--loop-column", "la")
        self.assertNotEqual(code, 0)
        self.assertIn("is in loop 2, which has no row", err)


if __name__ == "__main__":
    unittest.main()
