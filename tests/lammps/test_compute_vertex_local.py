#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""compute vertex/local through tessera-lmp: the junction rows of each cell
close into its counter-clockwise polygon around the cell's own position,
with the area and perimeter that compute vertex/atom reports; neighbour IDs
and lengths are mutual; the neighbour pairs are those of an independent
periodic Voronoi tessellation (scipy's Qhull); analytic lattices (hexagonal,
and square with its four-fold vertices); 2 ranks give the same rows as 1
rank from one data file; compute reduce over the rows; errors."""

import math
import os
import subprocess
import sys

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs
from test_compute_vertex_atom import PeriodicVoronoi

HEX_SIDE = math.sqrt(2.0 / (3.0 * math.sqrt(3.0)))    # regular hexagon of area 1

SETUP = """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
compute va all vertex/atom
compute vl {group} vertex/local
compute njunc all reduce sum c_vl[7]{inputs}
thermo_style custom step pe c_njunc
thermo_modify norm no format float %.15g
dump a all custom 1 cells.dump id type x y z c_va[1] c_va[2] c_va[4]
dump_modify a sort id format float %.17g
dump l all local 1 junctions.dump c_vl[1] c_vl[2] c_vl[3] c_vl[4] c_vl[5] c_vl[6] c_vl[7]
dump_modify l format float %.17g
"""


def script(start, group="all", extra="", before=""):
    """start, then `before`, the computes and dumps, `extra` and run 0."""
    # LAMMPS after 2021 reduces local values only when told ('inputs local',
    # which 2021 does not know)
    inputs = " inputs local" if lmptest.Config.host == "plugin" else ""
    return start + before + SETUP.format(group=group, inputs=inputs) + extra + "run 0\n"


def junction_rows(frame):
    """The rows of a local dump frame as an (n, 7) array, in file order."""
    return np.column_stack([frame["c_vl[%d]" % (k + 1)] for k in range(7)])


def cells_of(rows):
    """Rows grouped by cell ID, each cell's rows in output order."""
    out = {}
    for row in rows:
        out.setdefault(int(row[0]), []).append(row)
    return {c: np.array(r) for c, r in out.items()}


class Junctions(LammpsTestCase):

    def check_polygons(self, atoms, rows, tol=1e-10):
        """Each cell's rows form a closed counter-clockwise chain around the
        cell's position, with compute vertex/atom's area and perimeter; returns
        {(cell, neighbour): length}."""
        cells = cells_of(rows)
        ids = atoms["id"]
        self.assertEqual(sorted(cells), sorted(ids.tolist()))
        for c, r in cells.items():
            i = int(np.searchsorted(ids, c))
            start, end = r[:, 2:4], r[:, 4:6]
            # the chain closes exactly: each junction ends where the next starts
            np.testing.assert_array_equal(end, np.roll(start, -1, axis=0), err_msg="cell %d" % c)
            # the lengths are those of the segments
            np.testing.assert_allclose(np.hypot(*(end - start).T), r[:, 6], rtol=1e-9, atol=1e-12)
            # shoelace around the centre: vertex/atom's area, counter-clockwise
            d0 = start - [atoms["x"][i], atoms["y"][i]]
            d1 = end - [atoms["x"][i], atoms["y"][i]]
            cross = d0[:, 0] * d1[:, 1] - d0[:, 1] * d1[:, 0]
            self.assertAlmostEqual(0.5 * cross.sum(), atoms["c_va[1]"][i], delta=tol)
            self.assertAlmostEqual(r[:, 6].sum(), atoms["c_va[2]"][i], delta=tol)
            # convex and around the cell's own position (not another image)
            self.assertTrue(np.all(cross > 0), "cell %d is not counter-clockwise around x" % c)
            # one row per neighbour relation
            self.assertEqual(len(r), atoms["c_va[4]"][i])
        lengths = {}
        for row in rows:
            key = (int(row[0]), int(row[1]))
            self.assertNotIn(key, lengths, "two junctions between the same cells")
            lengths[key] = row[6]
        for (a, b), l in lengths.items():
            self.assertIn((b, a), lengths, "junction %d-%d is not mutual" % (a, b))
            self.assertAlmostEqual(lengths[(b, a)], l, delta=1e-10)
        return lengths

    def test_hexagonal_lattice(self):
        run = self.run_lmp(script(lmptest.tissue(10, 5)))
        (atoms,), (local,) = run.dump("cells.dump"), run.dump("junctions.dump")
        rows = junction_rows(local)
        self.assertEqual(len(rows), 600)
        np.testing.assert_allclose(rows[:, 6], HEX_SIDE, rtol=1e-12)
        self.check_polygons(atoms, rows)

    def check_square(self, n):
        """Square lattice: every vertex is four-fold; its zero-length edges
        are not junctions, so each cell has 4 rows of length 1."""
        run = self.run_lmp(script(lmptest.tissue(10, 10, "sq")), nprocs=n)
        (atoms,), (local,) = run.dump("cells.dump"), run.dump("junctions.dump")
        rows = junction_rows(local)
        self.assertEqual(len(rows), 400)
        np.testing.assert_allclose(rows[:, 6], 1.0, rtol=1e-12)
        lengths = self.check_polygons(atoms, rows)
        # the neighbours are the 4 nearest cells, through periodic images
        pos = {int(i): (x, y) for i, x, y in zip(atoms["id"], atoms["x"], atoms["y"])}
        for a, b in lengths:
            d = np.subtract(pos[a], pos[b])
            d -= 10.0 * np.round(d / 10.0)
            self.assertAlmostEqual(np.hypot(*d), 1.0, places=9)

    def test_square_lattice(self):
        self.check_square(1)

    @nprocs(2)
    def test_square_lattice_two_ranks(self):
        self.check_square(2)

    def disordered_data(self):
        run = self.run_lmp(lmptest.tissue(10, 5, ntypes=2) + """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
displace_atoms all random 0.3 0.3 0 6553
set type 1 type/fraction 2 0.5 4417
write_data tissue.data
""")
        return run.text("tissue.data")

    def run_disordered(self, data, n, group="all", before=""):
        start = """
dimension 2
units lj
atom_style dipole
boundary p p p
read_data tissue.data
mass * 1.0
"""
        run = self.run_lmp(script(start, group, before=before), nprocs=n, files={"tissue.data": data})
        (atoms,), (local,) = run.dump("cells.dump"), run.dump("junctions.dump")
        return run, atoms, junction_rows(local)

    def check_disordered(self, n):
        data = self.disordered_data()
        run, atoms, rows = self.run_disordered(data, n)
        lengths = self.check_polygons(atoms, rows)
        # the neighbour pairs of an independent tessellation
        ref = PeriodicVoronoi(atoms["x"], atoms["y"], atoms_box(run))
        pairs = {(min(a, b), max(a, b)) for a, b in lengths}
        expected = {(int(atoms["id"][a]), int(atoms["id"][b])) for a, b in ref.pairs()}
        self.assertEqual(pairs, expected)
        # compute reduce over the rows: every junction twice, i.e. the sum of perimeters
        (row,) = [line.split() for line in run.stdout.splitlines() if line.split()[:1] == ["0"]]
        self.assertAlmostEqual(float(row[2]), atoms["c_va[2]"].sum(), delta=1e-9)
        return lengths

    def test_disordered(self):
        self.check_disordered(1)

    @nprocs(2)
    def test_two_ranks_equal_one(self):
        one = self.check_disordered(1)
        two = self.check_disordered(2)
        self.assertEqual(sorted(one), sorted(two))
        for key, l in one.items():
            self.assertAlmostEqual(two[key], l, delta=1e-12)

    @nprocs(2)
    def test_group(self):
        """Rows only for the group's cells; their polygons are complete,
        neighbours outside the group included."""
        data = self.disordered_data()
        _, atoms, rows = self.run_disordered(data, 2, group="two",
                                             before="group two type 2\n")
        mine = atoms["type"] == 2
        self.assertEqual(sorted(set(rows[:, 0].astype(int))), sorted(atoms["id"][mine].tolist()))
        _, _, all_rows = self.run_disordered(data, 1)
        expected = sorted(tuple(r[:2].astype(int)) for r in all_rows
                          if int(r[0]) in set(atoms["id"][mine].tolist()))
        self.assertEqual(sorted(tuple(r[:2].astype(int)) for r in rows), expected)

    @nprocs(2)
    def test_one_cell_group(self):
        """A group of one cell: the other rank has no rows at all."""
        data = self.disordered_data()
        _, atoms, rows = self.run_disordered(data, 2, group="one", before="group one id 37\n")
        self.assertEqual(set(rows[:, 0].astype(int)), {37})
        i = int(np.searchsorted(atoms["id"], 37))
        self.assertEqual(len(rows), atoms["c_va[4]"][i])

    def test_after_motion(self):
        """After steps with reneighbouring, cells that moved out of the box
        still get their polygon around their own position."""
        start = lmptest.tissue(10, 5) + "velocity all create 1.0 4321 loop geom\n"
        extra = ("fix move all brownian 1.0 77 gamma_t 1.0 rng gaussian\n"
                 "timestep 0.01\nneigh_modify every 1 delay 0 check yes\n"
                 "dump_modify a every 40\ndump_modify l every 40\n")
        run = self.run_lmp(script(start, extra=extra).replace("run 0", "run 40"), nprocs=2)
        atoms, local = run.dump("cells.dump")[-1], run.dump("junctions.dump")[-1]
        self.assertEqual(local["step"], 40)
        self.check_polygons(atoms, junction_rows(local))


class ToVTK(LammpsTestCase):
    """tessera-tools vtk on LAMMPS's dumps: the polygons read back from the .vtu files
    (meshio) have the areas compute vertex/atom reports."""

    @nprocs(2)
    def test_vtk_areas(self):
        try:
            import meshio
        except ImportError:
            self.skipTest("meshio (Debian python3-meshio) is not installed")
        start = lmptest.tissue(10, 5, ntypes=2) + ("displace_atoms all random 0.3 0.3 0 6553\n"
                                                   "set type 1 type/fraction 2 0.5 4417\n")
        run = self.run_lmp(script(start), nprocs=2)
        (atoms,) = run.dump("cells.dump")
        tools = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "tessera-tools")
        proc = subprocess.run([sys.executable, tools, "vtk", "cells.dump", "--local", "junctions.dump",
                               "-o", "vtk/cells", "-q"], cwd=run.dir, capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
        mesh = meshio.read(run.path("vtk/cells_0.vtu"))
        area = {}
        for block, ids, types in zip(mesh.cells, mesh.cell_data["id"], mesh.cell_data["type"]):
            for conn, i, t in zip(block.data, ids, types):
                p = mesh.points[conn]
                area[int(i)] = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
                self.assertEqual(t, atoms["type"][int(i) - 1])
        self.assertEqual(sorted(area), atoms["id"].tolist())
        np.testing.assert_allclose([area[i] for i in atoms["id"]], atoms["c_va[1]"], rtol=1e-10)


def atoms_box(run):
    return run.dump("cells.dump")[0]["box"]


class Errors(LammpsTestCase):

    def test_extra_argument(self):
        run = self.run_lmp(lmptest.tissue(4, 2) + "compute vl all vertex/local 3\n", ok=False)
        self.assertLammpsError(run, "compute vertex/local", "'3'")

    def test_needs_pair_vertex_voronoi(self):
        run = self.run_lmp(lmptest.tissue(4, 2) + """
pair_style zero 1.0
pair_coeff * *
compute vl all vertex/local
dump l all local 1 j.dump c_vl[1]
run 0
""", ok=False)
        self.assertLammpsError(run, "vertex/local", "pair_style vertex/voronoi")


lmptest.main()
