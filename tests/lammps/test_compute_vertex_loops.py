#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""compute vertex/loops through tessera-lmp: the free-boundary loops of finite
cells against geometry computed here from the centres and the radius alone
(the union of finite cells is the union of their discs): holes made by
removing one, two or three cells from a hexagonal tissue, whose area is the
polygon of the discs' uncovered intersection points less the circular
segments between them, on 1, 2 and 4 ranks (the hole split between them);
an isolated disc; the outer loop, which encloses the cells and the holes;
a strip spanning a periodic box (two edges that wrap around the box); a
periodic tissue with a hole; identities that hold for any configuration,
checked along Brownian runs of jittered tissues on 1 and 2 ranks (a
colony's outer loop encloses its cells and its holes; the cells and holes of
a tissue filling a periodic box, orthogonal or triclinic, tile the box,
also with a wound across the box's edges); the largest hole and the
'min_area' keyword against the analytic area of the gap at a three-cell
corner and the geometry of a removed cell's hole; the hole around a
particle (a site of a hexagonal tissue that is no cell) against its closed
form, itself checked on a fine grid; and the errors."""

import math

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

R = 0.7
A = math.sqrt(2.0 / math.sqrt(3.0))    # hexagonal spacing of unit area per site
H = A * math.sqrt(3.0) / 2.0           # row spacing


def hex_sites(nx, ny, a=A):
    """Sites (i + j/2 mod 1) a, j a sqrt(3)/2 of an nx x ny hexagonal patch of
    spacing a (default A: unit area per site, rows H apart)."""
    h = H if a == A else a * math.sqrt(3.0) / 2.0
    return np.array([((i + 0.5 * (j % 2)) * a, j * h) for j in range(ny) for i in range(nx)])


def data_file(xy, box, types=None, tilt=None):
    lines = ["loops test", "", "%d atoms" % len(xy), "2 atom types", "",
             "%r %r xlo xhi" % box[:2], "%r %r ylo yhi" % box[2:], "-0.5 0.5 zlo zhi"]
    if tilt is not None:
        lines.append("%r 0.0 0.0 xy xz yz" % tilt)
    lines += ["",
             "Masses", "", "1 1.0", "2 1.0", "", "Atoms # atomic", ""]
    for k, (x, y) in enumerate(xy):
        lines.append("%d %d %r %r 0.0" % (k + 1, 1 if types is None else types[k], x, y))
    return "\n".join(lines) + "\n"


def script(boundary, extra=""):
    return f"""
dimension 2
units lj
atom_style atomic
boundary {boundary}
{extra}
read_data cells.data
pair_style vertex/voronoi {2 * R + 0.1} radius {R}
pair_coeff * * quadratic 1.0 1.2 0.1 3.9 free 0.2
compute loops all vertex/loops
compute va all vertex/atom
compute asum all reduce sum c_va[1]
dump l all local 1 loops.dump c_loops[1] c_loops[2] c_loops[3] c_loops[4] c_loops[5] c_loops[6] c_loops[7]
dump_modify l format float %.17g
thermo_style custom step pe c_loops[1] c_loops[2] c_loops[3] c_loops[4] c_asum
run 0
print "G $(c_loops[1]:%.17g) $(c_loops[2]:%.17g) $(c_loops[3]:%.17g) $(c_loops[4]:%.17g) $(c_asum:%.17g)"
"""


def local_rows(text):
    lines = text.split("\n")
    for k, line in enumerate(lines):
        if line.startswith("ITEM: NUMBER OF ENTRIES"):
            n = int(lines[k + 1])
        if line.startswith("ITEM: ENTRIES"):
            return np.array([[float(w) for w in lines[k + 1 + q].split()] for q in range(n)]).reshape(n, 7)
    raise AssertionError("no entries in the local dump")


def hole_geometry(centres, r, near, within):
    """Area and length of the hole around the point `near`, from the discs
    alone: the intersection points of pairs of circles that no other disc
    covers and that lie within `within` of `near` are the hole's corners;
    sorted by angle around `near` (the holes here are star-shaped from it),
    consecutive corners share one circle, whose arc between them bulges into
    the hole.  Area = polygon of the corners less the circular segments."""
    c = np.asarray(centres)
    close = c[np.linalg.norm(c - near, axis=1) < within + 2 * r]
    corners = []
    for i in range(len(close)):
        for j in range(i + 1, len(close)):
            d = np.linalg.norm(close[j] - close[i])
            if d >= 2 * r:
                continue
            mid = 0.5 * (close[i] + close[j])
            u = (close[j] - close[i]) / d
            perp = np.array([-u[1], u[0]])
            half = math.sqrt(r * r - d * d / 4)
            for s in (1, -1):
                p = mid + s * half * perp
                if np.linalg.norm(p - near) > within:
                    continue
                dist = np.linalg.norm(close - p, axis=1)
                dist[[i, j]] = np.inf
                if np.all(dist > r + 1e-12):
                    corners.append((p, {i, j}))
    ang = [math.atan2(p[1] - near[1], p[0] - near[0]) for p, _ in corners]
    corners = [corners[k] for k in np.argsort(ang)]
    pts = np.array([p for p, _ in corners])
    x, y = pts[:, 0], pts[:, 1]
    area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
    length = 0.0
    for k in range(len(corners)):
        (p, a), (q, b) = corners[k], corners[(k + 1) % len(corners)]
        assert len(a & b) == 1, "consecutive corners must share one circle"
        theta = 2 * math.asin(min(1.0, np.linalg.norm(q - p) / (2 * r)))
        area -= 0.5 * r * r * (theta - math.sin(theta))
        length += r * theta
    return area, length, len(corners)


def holes_case(removed):
    """A 12 x 10 hexagonal tissue in an open box with the given sites
    (indices into the patch) removed; returns (data, removed positions)."""
    sites = hex_sites(12, 10)
    keep = np.ones(len(sites), bool)
    keep[removed] = False
    box = (-3.0, 12 * A + 3.0, -3.0, 10 * H + 3.0)
    return data_file(sites[keep], box), sites[keep], sites[removed]


def site(i, j):
    return j * 12 + i


class VertexLoops(LammpsTestCase):

    def run_case(self, data, boundary="f f p", nprocs=1, extra=""):
        run = self.run_lmp(script(boundary, extra), nprocs=nprocs, files={"cells.data": data})
        g = [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
             if line.startswith("G ")][0]
        return g, local_rows(run.text("loops.dump"))

    def check_holes(self, removed, nprocs):
        grid = {2: "processors 2 1 1", 4: "processors 2 2 1"}
        data, kept, gone = holes_case(removed)
        near = gone.mean(axis=0)
        area, length, corners = hole_geometry(kept, R, near, within=2 * A)
        self.assertGreaterEqual(corners, 6)
        g, rows = self.run_case(data, nprocs=nprocs, extra=grid.get(nprocs, ""))
        holes, hole_area, nloops, wrapping, cell_area = g
        self.assertEqual((holes, nloops, wrapping), (1, 2, 0))
        self.assertEqual(len(rows), 2)
        np.testing.assert_array_equal(rows[:, 0], [1, 2])
        # numbered by their lowest atom ID: atom 1 (a corner cell) is on the outer loop
        np.testing.assert_array_equal(rows[:, 6], [1, 0])
        hole = rows[rows[:, 6] == 0][0]
        outer = rows[rows[:, 6] == 1][0]
        self.assertAlmostEqual(hole[1], area, delta=1e-10)
        self.assertAlmostEqual(hole_area, area, delta=1e-10)
        self.assertAlmostEqual(hole[2], length, delta=1e-10)
        self.assertEqual(hole[3], corners)    # one arc per cell around these holes
        # symmetric holes: the centroid is the mean of the removed sites
        self.assertAlmostEqual(hole[4], near[0], delta=1e-9)
        self.assertAlmostEqual(hole[5], near[1], delta=1e-9)
        # the outer loop encloses the cells and the hole
        self.assertAlmostEqual(outer[1], cell_area + area, delta=1e-9 * outer[1])
        self.assertEqual(outer[3], 2 * 12 + 2 * 10 - 4)
        return hole

    def test_one_two_three_removed_cells(self):
        for removed in ([site(6, 4)], [site(6, 4), site(7, 4)], [site(6, 4), site(7, 4), site(6, 5)]):
            with self.subTest(removed=removed):
                self.check_holes(removed, 1)

    @nprocs(2)
    def test_holes_split_between_two_ranks(self):
        # The box's middle (x = 6 A) runs through each hole.
        for removed in ([site(6, 4)], [site(5, 4), site(6, 4)], [site(5, 4), site(6, 4), site(5, 5)]):
            with self.subTest(removed=removed):
                one = self.check_holes(removed, 1)
                two = self.check_holes(removed, 2)
                np.testing.assert_allclose(two[1:6], one[1:6], rtol=0, atol=1e-12)

    @nprocs(4)
    def test_holes_split_between_four_ranks(self):
        # The box's middle lines (x = 6 A, y = 5 H) cross at the hole's centre.
        removed = [site(5, 5), site(6, 5)]
        _, _, gone = holes_case(removed)
        np.testing.assert_allclose(gone.mean(axis=0), [6 * A, 5 * H], atol=1e-12)
        one = self.check_holes(removed, 1)
        four = self.check_holes(removed, 4)
        np.testing.assert_allclose(four[1:6], one[1:6], rtol=0, atol=1e-12)

    def test_isolated_disc(self):
        data = data_file([(0.3, -0.2)], (-2.0, 2.0, -2.0, 2.0))
        g, rows = self.run_case(data)
        self.assertEqual(g[:4], [0, 0, 1, 0])
        self.assertEqual(len(rows), 1)
        self.assertAlmostEqual(rows[0, 1], math.pi * R * R, delta=1e-12)
        self.assertAlmostEqual(rows[0, 2], 2 * math.pi * R, delta=1e-12)
        self.assertEqual(rows[0, 3], 1)
        self.assertAlmostEqual(rows[0, 4], 0.3, delta=1e-12)
        self.assertAlmostEqual(rows[0, 5], -0.2, delta=1e-12)
        self.assertEqual(rows[0, 6], 1)

    def test_strip_edges_wrap_around_the_box(self):
        # 12 x 6 sites filling x of a box periodic in x: the top and bottom
        # rows' arcs make two loops that close only across the box.
        nx, ny = 12, 6
        sites = hex_sites(nx, ny) + np.array([0.25 * A, 2.0])
        data = data_file(sites, (0.0, nx * A, 0.0, ny * H + 4.0))
        theta = math.pi - 2 * math.acos(A / (2 * R))    # a row cell's arc between its row neighbours
        for n in (1, 2):
            with self.subTest(nprocs=n):
                g, rows = self.run_case(data, boundary="p f p", nprocs=n,
                                        extra="processors 2 1 1" if n == 2 else "")
                self.assertEqual(g[:4], [0, 0, 2, 2])
                np.testing.assert_array_equal(rows[:, 6], [-1, -1])
                np.testing.assert_array_equal(rows[:, 1], [0, 0])
                np.testing.assert_array_equal(rows[:, 3], [nx, nx])
                np.testing.assert_allclose(rows[:, 2], nx * R * theta, rtol=1e-12)

    def test_periodic_tissue_with_a_hole(self):
        # A tissue filling a periodic box has no outer boundary: one loop.
        nx, ny = 8, 8
        sites = hex_sites(nx, ny) + np.array([0.1, 0.2])
        removed = 3 * nx + 4
        kept = np.delete(sites, removed, axis=0)
        data = data_file(kept, (0.0, nx * A, 0.0, ny * H))
        # images of the sites around the hole are not needed: it is inside the box
        area, length, corners = hole_geometry(kept, R, sites[removed], within=2 * A)
        g, rows = self.run_case(data, boundary="p p p")
        self.assertEqual(g[:4], [1, g[1], 1, 0])
        self.assertAlmostEqual(g[1], area, delta=1e-10)
        self.assertAlmostEqual(rows[0, 2], length, delta=1e-10)
        self.assertEqual(rows[0, 6], 0)

    @nprocs(2)
    def test_hole_around_a_particle(self):
        # The removed site holds a particle (type 2, no cell parameters:
        # pair soft under hybrid/overlay): the cells leave the same hole
        # around it as around nothing, with the geometry of the discs alone.
        nx, ny = 8, 8
        sites = hex_sites(nx, ny) + np.array([0.1, 0.2])
        removed = 3 * nx + 4
        types = [2 if k == removed else 1 for k in range(len(sites))]
        data = data_file(sites, (0.0, nx * A, 0.0, ny * H), types=types)
        kept = np.delete(sites, removed, axis=0)
        area, length, corners = hole_geometry(kept, R, sites[removed], within=2 * A)
        for n in (1, 2):
            with self.subTest(nprocs=n):
                text = script("p p p", "processors 2 1 1" if n == 2 else "").replace(
                    "pair_style vertex/voronoi", "pair_style hybrid/overlay vertex/voronoi").replace(
                    f"radius {R}\n", f"radius {R} soft 0.9\n").replace(
                    "pair_coeff * * quadratic", "pair_coeff 1 1 vertex/voronoi quadratic").replace(
                    "compute loops", "pair_coeff * 2 soft 1.0 0.9\ncompute loops")
                run = self.run_lmp(text, nprocs=n, files={"cells.data": data})
                g = [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
                     if line.startswith("G ")][0]
                rows = local_rows(run.text("loops.dump"))
                self.assertEqual(g[0], 1)
                self.assertAlmostEqual(g[1], area, delta=1e-10)
                self.assertAlmostEqual(rows[0, 2], length, delta=1e-10)
                self.assertEqual(rows[0, 3], corners)
                # The cells and the hole tile the box; the particle has no area.
                self.assertAlmostEqual(g[4] + g[1], nx * A * ny * H, delta=1e-9)

    def moving(self, data, boundary, nprocs, steps=20):
        """A Brownian run of the tissue in `data`, loops and cell areas every 5 steps."""
        extra = "processors 2 1 1" if nprocs == 2 else ""
        body = script(boundary, extra).split("run 0\n")[0]
        body = body.replace("dump l all local 1", "dump l all local 5")
        body += f"""fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.01
thermo 5
thermo_modify norm no format float %.17g
run {steps}
"""
        run = self.run_lmp(body, nprocs=nprocs, files={"cells.data": data})
        frames = []
        lines = run.text("loops.dump").split("\n")
        for k, line in enumerate(lines):
            if line.startswith("ITEM: TIMESTEP"):
                step = int(lines[k + 1])
            if line.startswith("ITEM: NUMBER OF ENTRIES"):
                n = int(lines[k + 1])
            if line.startswith("ITEM: ENTRIES"):
                rows = np.array([[float(w) for w in lines[k + 1 + q].split()] for q in range(n)]).reshape(n, 7)
                frames.append((step, rows))
        thermo = {}
        header = None
        for line in run.stdout.splitlines():
            w = line.split()
            if w and w[0] == "Step":
                header = w
                continue
            if header and len(w) == len(header):
                try:
                    thermo[int(w[0])] = dict(zip(header, map(float, w)))
                except ValueError:
                    header = None
        self.assertEqual(len(frames), steps // 5 + 1)
        return frames, thermo

    def test_colony_encloses_its_cells_and_holes_while_moving(self):
        rng = np.random.default_rng(11)
        sites = hex_sites(12, 10) + rng.uniform(-0.08, 0.08, (120, 2))
        removed = [site(3, 3), site(8, 6), site(9, 6)]
        kept = np.delete(sites, removed, axis=0)
        data = data_file(kept, (-3.0, 12 * A + 3.0, -3.0, 10 * H + 3.0))
        results = []
        for n in (1, 2):
            frames, thermo = self.moving(data, "f f p", n)
            for step, rows in frames:
                # one colony; the removed cells' holes and any small gap that opens
                # where three jittered cells' discs no longer meet
                self.assertEqual((rows[:, 6] == 1).sum(), 1, f"step {step}")
                self.assertEqual((rows[:, 6] == -1).sum(), 0, f"step {step}")
                outer = rows[rows[:, 6] == 1][0]
                holes = rows[rows[:, 6] == 0]
                self.assertGreaterEqual(len(holes), 2)
                t = thermo[step]
                self.assertEqual((t["c_loops[1]"], t["c_loops[3]"], t["c_loops[4]"]), (len(holes), len(rows), 0))
                self.assertAlmostEqual(t["c_loops[2]"], holes[:, 1].sum(), delta=1e-6)
                self.assertAlmostEqual(outer[1] - holes[:, 1].sum(), t["c_asum"],
                                       delta=1e-5 * outer[1], msg=f"step {step}")
            results.append(frames[-1][1])
        # the same loops in the same order (by their lowest atom ID) on both rank counts
        np.testing.assert_allclose(results[1], results[0], rtol=1e-8, atol=1e-8)

    def test_periodic_cells_and_holes_tile_the_box(self):
        # a wound across the box's corner: its loop crosses both periodic edges
        rng = np.random.default_rng(12)
        nx, ny = 8, 8
        sites = hex_sites(nx, ny) + rng.uniform(-0.08, 0.08, (nx * ny, 2))
        kept = np.delete(sites, [0, 1, nx], axis=0)
        area_box = nx * A * ny * H
        data = data_file(kept, (-0.3, nx * A - 0.3, -0.3, ny * H - 0.3))
        for n in (1, 2):
            frames, thermo = self.moving(data, "p p p", n)
            for step, rows in frames:
                self.assertEqual(rows[:, 6].tolist(), [0], f"step {step}")
                t = thermo[step]
                self.assertAlmostEqual(t["c_asum"] + rows[0, 1], area_box, delta=1e-6 * area_box)
                self.assertTrue(-0.3 <= rows[0, 4] < nx * A - 0.3 and -0.3 <= rows[0, 5] < ny * H - 0.3)

    def test_triclinic_cells_and_holes_tile_the_box(self):
        # a hexagonal lattice is periodic in a box tilted by whole spacings
        rng = np.random.default_rng(13)
        nx, ny, tilt = 8, 8, 2 * A
        sites = hex_sites(nx, ny) + rng.uniform(-0.05, 0.05, (nx * ny, 2))
        # into the tilted box [0, nx A) + s (tilt, ny H)
        s = np.floor(sites[:, 1] / (ny * H))
        sites = sites - np.outer(s, [tilt, ny * H])
        sites[:, 0] -= nx * A * np.floor((sites[:, 0] - sites[:, 1] / (ny * H) * tilt) / (nx * A))
        kept = np.delete(sites, [0, nx - 1, nx * (ny - 1)], axis=0)    # a wound at the box's edges
        data = data_file(kept, (0.0, nx * A, 0.0, ny * H), tilt=tilt)
        area_box = nx * A * ny * H
        for n in (1, 2):
            frames, thermo = self.moving(data, "p p p", n, steps=10)
            for step, rows in frames:
                self.assertEqual((rows[:, 6] == 1).sum() + (rows[:, 6] == -1).sum(), 0)
                self.assertGreaterEqual(len(rows), 1)
                t = thermo[step]
                self.assertAlmostEqual(t["c_asum"] + rows[:, 1].sum(), area_box, delta=1e-6 * area_box)

    def test_errors(self):
        data = data_file([(0.3, -0.2)], (-2.0, 2.0, -2.0, 2.0))
        confluent = """
dimension 2
units lj
atom_style atomic
boundary p p p
read_data cells.data
pair_style vertex/voronoi 2.0
pair_coeff * * 1.0 1.0 0.1 -0.5
compute loops all vertex/loops
thermo_style custom step c_loops[1]
run 0
"""
        run = self.run_lmp(confluent, files={"cells.data": data}, ok=False)
        self.assertLammpsError(run, "vertex/loops", "needs finite cells")
        for extra, fragment in (("compute bad all vertex/loops 3", "unexpected argument"),
                                ("group one id 1\ncompute bad one vertex/loops", "use group 'all'")):
            run = self.run_lmp(script("f f p").replace("compute va", extra + "\ncompute va"),
                               files={"cells.data": data}, ok=False)
            self.assertLammpsError(run, fragment)
        three = """
units lj
atom_style atomic
boundary p p p
region b block 0 2 0 2 0 2
create_box 1 b
compute loops all vertex/loops
"""
        run = self.run_lmp(three, ok=False)
        self.assertLammpsError(run, "is for 2d")


def corner_gap_area(a, r):
    """The gap between three discs of radius r centred on an equilateral
    triangle of side a (a/2 < r < a/sqrt(3): the discs overlap in pairs but
    leave the centre uncovered): the triangle less the three 60-degree
    sectors, plus the three half-lenses the sectors overlap in."""
    lens = 2 * r * r * math.acos(a / (2 * r)) - 0.5 * a * math.sqrt(4 * r * r - a * a)
    return math.sqrt(3) / 4 * a * a - math.pi * r * r / 2 + 1.5 * lens


class LargestHole(LammpsTestCase):
    """Global values 5-9 (the largest hole) and 'min_area': a periodic
    hexagonal tissue of finite cells of radius r between half the spacing
    and the hexagons' circumradius has a gap at every three-cell corner
    (two per cell), of the area corner_gap_area; with a cell removed, its
    hole is the largest, of the area hole_geometry gives."""

    r = 0.6
    nx, ny = 8, 8

    def run_tissue(self, removed, min_area=None, nprocs=1):
        sites = hex_sites(self.nx, self.ny) + np.array([0.1, 0.2])
        kept = np.delete(sites, removed, axis=0)
        data = data_file(kept, (0.0, self.nx * A, 0.0, self.ny * H))
        keyword = "" if min_area is None else f" min_area {min_area!r}"
        values = " ".join("$(c_loops[%d]:%%.17g)" % k for k in range(1, 10))
        script = f"""
dimension 2
units lj
atom_style atomic
boundary p p p
{"processors 2 1 1" if nprocs == 2 else ""}
read_data cells.data
pair_style vertex/voronoi {2 * self.r + 0.1} radius {self.r}
pair_coeff * * quadratic 1.0 1.2 0.1 3.9 free 0.2
compute loops all vertex/loops{keyword}
thermo_style custom step pe c_loops[1] c_loops[5]
run 0
print "G {values}"
"""
        run = self.run_lmp(script, nprocs=nprocs, files={"cells.data": data})
        g = [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
             if line.startswith("G ")][0]
        return g, kept, sites

    def test_corner_gaps_of_a_perfect_tissue(self):
        gap = corner_gap_area(A, self.r)
        self.assertTrue(A / 2 < self.r < A / math.sqrt(3) and 0 < gap < 0.01)
        n = self.nx * self.ny
        g, _, _ = self.run_tissue([])
        self.assertEqual(g[0], 2 * n)
        self.assertAlmostEqual(g[1], 2 * n * gap, delta=1e-9)
        self.assertAlmostEqual(g[4], gap, delta=1e-12)    # the largest is one of them
        self.assertEqual(g[8], 3)                          # between three cells
        # above the gaps' area: no hole, and the largest hole's values are 0
        g, _, _ = self.run_tissue([], min_area=2 * gap)
        self.assertEqual(g[:2] + g[4:], [0, 0, 0, 0, 0, 0, 0])
        self.assertEqual(g[2], 2 * n)                       # the loops are all still there

    def check_wound(self, nprocs):
        removed = 3 * self.nx + 4
        gap = corner_gap_area(A, self.r)
        n = self.nx * self.ny
        for min_area in (None, 10 * gap):
            with self.subTest(min_area=min_area):
                g, kept, sites = self.run_tissue([removed], min_area, nprocs)
                # corners within 0.9 of the removed site: the hole's only (the
                # gaps beyond its ring of cells are 1.2 away)
                area, length, corners = hole_geometry(kept, self.r, sites[removed], within=0.9)
                self.assertEqual(corners, 6)
                gaps = 2 * n - 6 if min_area is None else 0    # the hole took 6 corners
                self.assertEqual(g[0], 1 + gaps)
                self.assertAlmostEqual(g[1], area + gaps * gap, delta=1e-9)
                self.assertAlmostEqual(g[4], area, delta=1e-10)
                np.testing.assert_allclose(g[5:7], sites[removed], atol=1e-9)
                self.assertAlmostEqual(g[7], length, delta=1e-10)
                self.assertEqual(g[8], 6)

    def test_wound(self):
        self.check_wound(1)

    @nprocs(2)
    def test_wound_two_ranks(self):
        self.check_wound(2)

    def test_bad_min_area(self):
        data = data_file([(0.3, -0.2)], (-2.0, 2.0, -2.0, 2.0))
        for value, fragment in (("-1", "min_area must be a finite area >= 0"),
                                ("", "'min_area' needs an area A")):
            run = self.run_lmp(script("f f p").replace("compute loops all vertex/loops",
                                                       "compute loops all vertex/loops min_area " + value),
                               files={"cells.data": data}, ok=False)
            self.assertLammpsError(run, "compute vertex/loops loops", fragment)


def hole_around_a_site(a, r):
    """The hole left by removing one site of a hexagonal lattice of spacing a
    whose other sites carry discs of radius r, a/2 < r < a (closed form,
    derived in doc/model.md): the circles of neighbours k and k+1 cross at
    rho = (sqrt(3)/2) a - sqrt(r^2 - a^2/4) from the site, six corners of a
    regular hexagon of side rho; each neighbour's arc between two corners
    subtends theta = 2 asin(rho / (2 r)) at its centre.  Returns (area,
    length, rho) with area = (3 sqrt(3)/2) rho^2 - 3 r^2 (theta - sin theta)
    (the hexagon less six circular segments) and length = 6 r theta."""
    rho = math.sqrt(3.0) / 2.0 * a - math.sqrt(r * r - a * a / 4.0)
    theta = 2.0 * math.asin(rho / (2.0 * r))
    return 1.5 * math.sqrt(3.0) * rho ** 2 - 3.0 * r * r * (theta - math.sin(theta)), 6.0 * r * theta, rho


def uncovered_area_on_grid(a, r, n=1200):
    """Independent of hole_around_a_site: the area of the region around the
    removed site (the origin) that no disc of the lattice's three rings
    covers, counted on an n x n grid of cell midpoints; the region is the
    grid's connected uncovered component at the origin.  Returns the area and
    whether that component reaches the grid's edge (then the window, 1.1 rho
    wide on each side, did not hold the hole)."""
    from scipy import ndimage

    w = 1.1 * hole_around_a_site(a, r)[2]
    x = (np.arange(n) + 0.5) / n * 2 * w - w
    X, Y = np.meshgrid(x, x)
    free = np.ones(X.shape, bool)
    for i in range(-5, 6):
        for j in range(-5, 6):
            c = (a * (i + 0.5 * j), a * math.sqrt(3.0) / 2.0 * j)
            if (i, j) != (0, 0) and math.hypot(*c) < 3.5 * a:
                free &= (X - c[0]) ** 2 + (Y - c[1]) ** 2 > r * r
    labels, _ = ndimage.label(free)
    hole = labels == labels[n // 2, n // 2]
    edge = hole[0].any() or hole[-1].any() or hole[:, 0].any() or hole[:, -1].any()
    return hole.sum() * (2 * w / n) ** 2, bool(edge)


class HoleAroundAParticle(LammpsTestCase):
    """A periodic hexagonal tissue of finite cells (spacing a, radius r) with
    one site holding a particle instead of a cell (type 2, pair soft under
    hybrid/overlay, no cell parameters): the cells leave around it the hole
    of hole_around_a_site, whose area and length compute vertex/loops gives
    to round-off (the largest hole, its centroid on the site and its six
    cells; the total of all holes; the cells and holes tiling the box), with
    the particle on the site or off it (the particle never enters the
    tessellation), on 1 and 2 ranks (the hole split between them).  For
    r < a/sqrt(3) the lattice's three-cell corners leave gaps too (2 per
    site, less the 6 around the removed one).  Made a cell, the particle
    fills the hole."""

    # (a, r): r/a from just above 1/2 (gaps at the corners) to near 1 (a small hole)
    CASES = [(1.0, 0.52), (1.2, 0.66), (1.0, 0.6), (1.0, 0.75), (1.3, 0.9), (0.8, 0.76)]
    NX, NY, SITE = 6, 6, (3, 2)

    def test_closed_form_against_the_discs(self):
        for a, r in self.CASES + [(1.0, 0.95), (2.0, 1.5)]:
            with self.subTest(a=a, r=r):
                area, length, rho = hole_around_a_site(a, r)
                grid, reaches_edge = uncovered_area_on_grid(a, r)
                self.assertFalse(reaches_edge)
                self.assertAlmostEqual(area, grid, delta=5e-4 * area)
                # the length is minus the derivative of the area in r (growing every
                # disc by dr moves the whole boundary inwards by dr)
                dr = 1e-6 * r
                d_area = (hole_around_a_site(a, r + dr)[0] - hole_around_a_site(a, r - dr)[0]) / (2 * dr)
                self.assertAlmostEqual(-d_area, length, delta=1e-7 * length)
                # and the corners-and-segments construction of hole_geometry
                sites = [(a * (i + 0.5 * j), a * math.sqrt(3.0) / 2.0 * j)
                         for i in range(-3, 4) for j in range(-3, 4) if (i, j) != (0, 0)]
                geo_area, geo_length, corners = hole_geometry(sites, r, np.zeros(2), within=a)
                self.assertEqual(corners, 6)
                self.assertAlmostEqual(geo_area, area, delta=1e-12)
                self.assertAlmostEqual(geo_length, length, delta=1e-12)

    def measure(self, a, r, offset=(0.0, 0.0), nprocs=1, particle_is_cell=False):
        """The global values of compute vertex/loops and the sum of the cell
        areas, and the site's position."""
        h = a * math.sqrt(3.0) / 2.0
        sites = hex_sites(self.NX, self.NY, a)
        sites += np.array([0.05, 0.1]) * a
        k = self.SITE[1] * self.NX + self.SITE[0]
        xy = sites.copy()
        xy[k] += np.asarray(offset) * a
        types = [2 if q == k else 1 for q in range(len(xy))]
        data = data_file(xy, (0.0, self.NX * a, 0.0, self.NY * h), types=types)
        cells = "* *" if particle_is_cell else "1 1"
        values = " ".join("$(c_loops[%d]:%%.17g)" % q for q in range(1, 10))
        text = f"""
dimension 2
units lj
atom_style atomic
boundary p p p
{"processors 2 1 1" if nprocs == 2 else ""}
read_data cells.data
pair_style hybrid/overlay vertex/voronoi {2 * r + 0.1} radius {r} soft {0.4 * a}
pair_coeff {cells} vertex/voronoi quadratic 1.0 1.2 0.1 3.9 free 0.2
pair_coeff * 2 soft 1.0 {0.4 * a}
compute loops all vertex/loops
compute va all vertex/atom
compute asum all reduce sum c_va[1]
thermo_style custom step pe c_loops[1] c_asum
run 0
print "G {values} $(c_asum:%.17g)"
"""
        run = self.run_lmp(text, nprocs=nprocs, files={"cells.data": data})
        g = [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
             if line.startswith("G ")][0]
        return g, sites[k]

    def check(self, a, r, g, site):
        area, length, _ = hole_around_a_site(a, r)
        n = self.NX * self.NY
        gaps = 2 * n - 6 if r < a / math.sqrt(3.0) else 0
        gap = corner_gap_area(a, r) if gaps else 0.0
        self.assertLess(gap, area)
        self.assertEqual(g[0], 1 + gaps)                                  # holes
        self.assertAlmostEqual(g[1], area + gaps * gap, delta=1e-9)       # their total area
        self.assertEqual(g[2:4], [1 + gaps, 0])                           # loops, wrapping
        self.assertAlmostEqual(g[4], area, delta=1e-10)                   # the largest hole
        np.testing.assert_allclose(g[5:7], site, rtol=0, atol=1e-9)       # centred on the site
        self.assertAlmostEqual(g[7], length, delta=1e-10)                 # bounded by six arcs
        self.assertEqual(g[8], 6)
        box = self.NX * a * self.NY * a * math.sqrt(3.0) / 2.0
        self.assertAlmostEqual(g[9] + g[1], box, delta=1e-9 * box)        # cells + holes = box

    def test_hole_on_and_off_the_site(self):
        for a, r in self.CASES:
            for offset in ((0.0, 0.0), (0.21, -0.13)):
                with self.subTest(a=a, r=r, offset=offset):
                    self.check(a, r, *self.measure(a, r, offset))

    @nprocs(2)
    def test_hole_split_between_two_ranks(self):
        # The sub-domains meet at x = 3 a, 0.05 a from the site.
        for a, r in self.CASES:
            with self.subTest(a=a, r=r):
                g2, site = self.measure(a, r, (0.21, -0.13), nprocs=2)
                self.check(a, r, g2, site)
                g1, _ = self.measure(a, r, (0.21, -0.13))
                np.testing.assert_allclose(g2, g1, rtol=1e-12, atol=1e-12)

    def test_a_tessellated_particle_fills_the_hole(self):
        # Given cell parameters, the particle is a cell: no hole but the gaps.
        for a, r in ((1.0, 0.52), (1.0, 0.75)):
            with self.subTest(a=a, r=r):
                g, _ = self.measure(a, r, particle_is_cell=True)
                n = self.NX * self.NY
                gaps = 2 * n if r < a / math.sqrt(3.0) else 0
                self.assertEqual(g[0], gaps)
                self.assertAlmostEqual(g[4], corner_gap_area(a, r) if gaps else 0.0, delta=1e-10)


def min_image(d, box, periodic, tilt=0.0):
    """d (N x 2) less whole box vectors in the periodic directions (box: lx, ly)."""
    d = np.array(d, float)
    if periodic[1]:
        m = np.round(d[:, 1] / box[1])
        d[:, 1] -= m * box[1]
        d[:, 0] -= m * tilt
    if periodic[0]:
        d[:, 0] -= np.round(d[:, 0] / box[0]) * box[0]
    return d


class LoopOfEachAtom(LammpsTestCase):
    """compute vertex/loops/atom against the geometry of a hexagonal tissue
    of finite cells (spacing a, radius r, a/sqrt(3) < r < a: no gaps at the
    three-cell corners) with particles (type 2, no cell parameters) on some
    sites: each particle's first column is the compute vertex/loops row
    (dumped by a second compute) whose centroid is the particle's site and
    whose area is hole_around_a_site's; a particle beyond the tissue (open
    box, or the open band beside a strip that wraps around a periodic box)
    gets 0, and so does one the cells cover (r > a).  A cell's first column
    is its colony's outer loop (0 where the tissue has none: a periodic box
    or a strip); its second is the hole it borders when it is a particle's
    neighbour, the outer loop when it is at the patch's edge (fewer than six
    neighbours), else 0, and the third counts those loops.  One table of
    cases (open, strip, periodic, tilted, a hole across the box's corner),
    each on 1 and 2 ranks with identical output; the atom-style variable
    c_ID[1] equals the dumped column."""

    # name, boundary, (nx, ny), a, r, particle sites (i, j), tilt in spacings, extra particles
    CASES = [
        ("open", "f f p", (10, 8), 1.0, 0.7, [(3, 3), (6, 4)], 0, [(-2.0, 1.5)]),
        ("strip", "p f p", (10, 6), 1.0, 0.8, [(4, 2)], 0, [(2.3, 6.5)]),
        ("periodic", "p p p", (8, 8), 1.2, 0.9, [(2, 2), (5, 6)], 0, []),
        ("tilted", "p p p", (8, 8), 1.0, 0.66, [(3, 4)], 1, []),
        ("corner", "p p p", (8, 8), 1.0, 0.75, [(0, 0)], 0, []),
        ("covered", "p p p", (6, 6), 1.0, 1.05, [(2, 3)], 0, []),
    ]

    def build(self, case):
        name, boundary, (nx, ny), a, r, psites, tilt, extra = case
        h = a * math.sqrt(3.0) / 2.0
        periodic = [w == "p" for w in boundary.split()[:2]]
        sites = hex_sites(nx, ny, a) + np.array([0.05, 0.1]) * a
        t = tilt * a
        if name == "corner":
            sites -= np.array([0.05, 0.1]) * a + np.array([0.02, 0.03]) * a    # the site near (0, 0)
        if tilt:
            s = np.floor(sites[:, 1] / (ny * h))
            sites = sites - np.outer(s, [t, ny * h])
            sites[:, 0] -= nx * a * np.floor((sites[:, 0] - sites[:, 1] / (ny * h) * t) / (nx * a))
        lx, ly = nx * a, ny * h
        lo = [0.0 if periodic[0] else -3.0, 0.0 if periodic[1] else -3.0]
        hi = [lx if periodic[0] else lx + 3.0, ly if periodic[1] else ly + 3.0]
        if name == "corner":
            # wrapped into [0, L): the site at the corner goes to the far side
            sites = np.mod(sites, [lx, ly])
        k_part = [j * nx + i for i, j in psites]
        types = [2 if k in k_part else 1 for k in range(len(sites))]
        xy = [tuple(p) for p in sites] + [tuple(np.array(e) * a) for e in extra]
        types += [2] * len(extra)
        data = data_file(xy, (lo[0], hi[0], lo[1], hi[1]), types=types, tilt=t if tilt else None)
        return data, sites, k_part, (hi[0] - lo[0], hi[1] - lo[1]), periodic, t

    def run_case(self, case, nprocs):
        name, boundary, _, a, r, _, _, _ = case
        data, *_ = self.build(case)
        text = f"""
dimension 2
units lj
atom_style atomic
boundary {boundary}
{"processors 2 1 1" if nprocs == 2 else ""}
read_data cells.data
pair_style hybrid/overlay vertex/voronoi {2 * r + 0.1} radius {r} soft {0.4 * a}
pair_coeff 1 1 vertex/voronoi quadratic 1.0 1.2 0.1 3.9 free 0.2
pair_coeff * 2 soft 1.0 {0.4 * a}
compute loops all vertex/loops
compute la all vertex/loops/atom
variable hole atom c_la[1]
variable edge atom c_la[3]
dump a all custom 1 atoms.dump id type x y c_la[1] c_la[2] c_la[3] v_hole v_edge
dump_modify a format float %.17g
dump l all local 1 loops.dump c_loops[*]
dump_modify l format float %.17g
run 0
"""
        run = self.run_lmp(text, nprocs=nprocs, files={"cells.data": data})
        return run.dump("atoms.dump")[0], local_rows(run.text("loops.dump"))

    def check(self, case, frame, rows):
        name, boundary, (nx, ny), a, r, psites, tilt, extra = case
        _, sites, k_part, box, periodic, t = self.build(case)
        ids = frame["id"]
        col1, col2, col3 = frame["c_la[1]"], frame["c_la[2]"], frame["c_la[3]"]
        np.testing.assert_array_equal(frame["v_hole"], col1)
        np.testing.assert_array_equal(frame["v_edge"], col3)
        np.testing.assert_array_equal(rows[:, 0], np.arange(1, len(rows) + 1))
        holes = {}
        covered = r >= a
        for k in k_part:
            i = int(np.nonzero(ids == k + 1)[0][0])
            if covered:
                self.assertEqual(col1[i], 0, f"{name}: particle {k + 1} covered by cells")
                continue
            # the hole around the site: the row whose centroid is the site
            d = min_image(rows[:, 4:6] - sites[k], box, periodic, t)
            near = int(np.argmin(np.hypot(d[:, 0], d[:, 1])))
            self.assertLess(np.hypot(*d[near]), 1e-9)
            area, length, _ = hole_around_a_site(a, r)
            self.assertAlmostEqual(rows[near, 1], area, delta=1e-10)
            self.assertEqual(rows[near, 6], 0)
            self.assertEqual(col1[i], near + 1, f"{name}: particle {k + 1}")
            self.assertEqual((col2[i], col3[i]), (0, 0))    # a particle has no arcs
            holes[k] = near + 1
        for q in range(len(extra)):
            i = int(np.nonzero(ids == len(sites) + q + 1)[0][0])
            self.assertEqual((col1[i], col2[i], col3[i]), (0, 0, 0), f"{name}: particle beyond the tissue")
        # the cells
        outer = [int(row[0]) for row in rows if row[6] == 1]
        self.assertEqual(len(outer), 1 if boundary == "f f p" else 0)
        wrapping = [int(row[0]) for row in rows if row[6] == -1]
        self.assertEqual(len(wrapping), 2 if boundary == "p f p" else 0)
        cells = [k for k in range(len(sites)) if k not in k_part]
        for k in cells:
            i = int(np.nonzero(ids == k + 1)[0][0])
            self.assertEqual(col1[i], outer[0] if outer else 0, f"{name}: cell {k + 1}")
            d = min_image(sites - sites[k], box, periodic, t)
            dist = np.hypot(d[:, 0], d[:, 1])
            neighbours = np.nonzero(np.abs(dist - a) < 1e-6 * a)[0]
            on = sorted({holes[j] for j in neighbours if j in holes})
            if len(neighbours) < 6:
                on = sorted(on + (outer if outer else []) + ([int(col2[i])] if wrapping else []))
                if wrapping:
                    self.assertIn(int(col2[i]), wrapping)
            self.assertEqual(col3[i], len(on), f"{name}: cell {k + 1}")
            self.assertEqual(col2[i], on[0] if on else 0, f"{name}: cell {k + 1}")

    @nprocs(2)
    def test_cases_on_one_and_two_ranks(self):
        for case in self.CASES:
            with self.subTest(case=case[0]):
                one = self.run_case(case, 1)
                self.check(case, *one)
                two = self.run_case(case, 2)
                for col in ("c_la[1]", "c_la[2]", "c_la[3]"):
                    np.testing.assert_array_equal(two[0][col], one[0][col], err_msg=col)
                np.testing.assert_allclose(two[1], one[1], rtol=0, atol=1e-12)    # (round-off)

    def test_errors(self):
        data = data_file([(0.3, -0.2)], (-2.0, 2.0, -2.0, 2.0))
        run = self.run_lmp(script("f f p").replace("compute va", "compute bad all vertex/loops/atom 3\ncompute va"),
                           files={"cells.data": data}, ok=False)
        self.assertLammpsError(run, "vertex/loops/atom", "unexpected argument '3'")


if __name__ == "__main__":
    lmptest.main()
