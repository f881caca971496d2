#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The step guard names the cause that fits, with the numbers of the step's
start, each checked against an independent reading of that state (a dump of
step 0: a brute-force search for the closest neighbours, compute
vertex/atom's areas, the forces):

* a close pair: the moved atom's closest Voronoi neighbour nearly on it;
* a cell far above its preferred area: a confluent cell next to an empty
  region fills it;
* not the cells: a stiff force of another sub-style of pair_style
  hybrid/overlay;
* with fix brownian/heun, whose second force computation is at predicted
  positions, the neighbour named is still that of the step's start (it used
  to be searched with the predicted cells: an unrelated atom), on the plane
  and on the sphere, and a near collision elsewhere is named as such."""

import re

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

DUMP = """dump d all custom 1 d.txt id x y z fx fy fz{extra}
dump_modify d sort id format float %.17g
"""

NAMED = re.compile(r"atom (\d+) moved by (\S+)")
NEAREST = re.compile(r"its closest Voronoi neighbour then, atom (\d+), was (\S+) away")


def guard_line(run):
    lines = [l for l in run.output.splitlines()
             if ("WARNING" in l or "ERROR" in l) and "moved by" in l]
    return lines[0] if lines else None


def closest(frame, i, periodic, exclude=()):
    """Brute force: the atom closest to atom i (ID) and the distance, with
    minimum images along the periodic directions (2 in the plane)."""
    x = np.column_stack([frame["x"], frame["y"], frame["z"]])
    ids = frame["id"]
    k = int(np.nonzero(ids == i)[0][0])
    d = x - x[k]
    if periodic:
        L = frame["box"][:, 1] - frame["box"][:, 0]
        for a in range(2):
            d[:, a] -= L[a] * np.round(d[:, a] / L[a])
        d[:, 2] = 0.0
    r = np.linalg.norm(d, axis=1)
    r[k] = np.inf
    for e in exclude:
        r[ids == e] = np.inf
    m = int(np.argmin(r))
    return int(ids[m]), float(r[m])


def closest_pair(frame, periodic):
    best = (None, None, np.inf)
    for i in frame["id"]:
        j, d = closest(frame, int(i), periodic)
        if d < best[2]:
            best = (int(i), j, d)
    return best


def tissue_with_gap(ranks=1):
    """A hexagonal tissue of 72 cells of area 1 with its upper 30 removed:
    the cells along the gap fill it (area 3.5); dt = 1 moves them by 1.8."""
    return lmptest.tissue(6, 6) + """region gap block INF INF 3.2 INF INF INF
delete_atoms region gap
pair_style vertex/voronoi 3.0
pair_coeff * * 1 1 0.1 -0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
compute c all vertex/atom
""" + DUMP.format(extra=" c_c[1]") + "timestep 1.0\nrun 1\n"


class Causes(LammpsTestCase):

    def check_nearest(self, line, frame, periodic=True):
        moved = int(NAMED.search(line).group(1))
        j, d = NEAREST.search(line).groups()
        bj, bd = closest(frame, moved, periodic)
        self.assertEqual(int(j), bj, line)
        self.assertEqual(d, "%.3g" % bd)    # printed to 3 digits
        return moved, int(j), float(d)

    def test_close_pair(self):
        # a cell 1e-3 from atom 1 along the diagonal, dt 0.1: the pair
        # separates by about 1.4 in one step
        run = self.run_lmp(lmptest.tissue(6, 3) + """
create_atoms 1 single 0.001 0.001 0 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(extra="") + "timestep 0.1\nrun 1\n")
        line = guard_line(run)
        self.assertIsNotNone(line, run.output[-3000:])
        self.assertIn("Cause: a close pair: its closest Voronoi neighbour then", line)
        self.assertIn("Voronoi forces grow as 1/distance", line)
        moved, j, d = self.check_nearest(line, run.dump("d.txt")[0])
        self.assertEqual({moved, j}, {1, 37})
        self.assertNotIn("far above", line)

    def check_gap(self, run):
        line = guard_line(run)
        self.assertIsNotNone(line, run.output[-3000:])
        self.assertIn("Cause: a cell far above its preferred area or perimeter", line)
        m = re.search(r"(the cell itself|its Voronoi neighbour, atom (\d+),) had area (\S+), "
                      r"(\S+) times A0 = 1 \(the tissue's mean (\S+) times\)", line)
        self.assertIsNotNone(m, line)
        first = run.dump("d.txt")[0]
        moved = int(NAMED.search(line).group(1))
        big = moved if m.group(2) is None else int(m.group(2))
        area = first["c_c[1]"][first["id"] == big][0]
        self.assertEqual(m.group(3), "%.3g" % area)
        self.assertGreater(area, 3.0)
        # the tissue's mean: the cells tile the box of 72 cells' area
        self.assertEqual(m.group(5), "%.2g" % (72 / 42))
        self.check_nearest(line, first)
        self.assertNotIn("close pair", line)

    def test_cell_far_above_its_area(self):
        self.check_gap(self.run_lmp(tissue_with_gap()))

    @nprocs(2)
    def test_cell_far_above_its_area_two_ranks(self):
        # the neighbours of the moved cell lie on both ranks
        self.check_gap(self.run_lmp(tissue_with_gap(), nprocs=2))

    def test_another_substyle(self):
        # lj/cut between the cells (sigma 1.25 at spacing 1.07): the cells
        # are ordinary, the force is lj's
        run = self.run_lmp(lmptest.tissue(6, 3) + """
displace_atoms all random 0.05 0.05 0 4821 units box
pair_style hybrid/overlay vertex/voronoi 3.0 lj/cut 1.5
pair_coeff * * vertex/voronoi 1 1 0.1 -0.5
pair_coeff * * lj/cut 1.0 1.25
fix b all brownian 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(extra="") + "timestep 0.02\nrun 1\n", ok=False)
        line = guard_line(run)
        self.assertIsNotNone(line, run.output[-3000:])
        self.assertIn("Cause: not the cells around it (neither a close pair nor a cell far above "
                      "its preferred area or perimeter", line)
        self.assertIn("likely a stiff force from another sub-style of pair_style hybrid/overlay",
                      line)
        first = run.dump("d.txt")[0]
        moved, _, _ = self.check_nearest(line, first)
        k = first["id"] == moved
        f = np.sqrt(first["fx"][k] ** 2 + first["fy"][k] ** 2 + first["fz"][k] ** 2)[0]
        said = float(re.search(r"the force on it then, (\S+),", line).group(1))
        self.assertEqual(said, float("%.3g" % f))

    def test_the_cells_own_force(self):
        # K = 1e4 on a jittered tissue, no other force: the cells' own
        # stiffness
        run = self.run_lmp(lmptest.tissue(6, 3) + """
displace_atoms all random 0.1 0.1 0 4821 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1e4 1.0 0.1 -0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.01
run 1
""", ok=None)
        line = guard_line(run)
        self.assertIsNotNone(line, run.output[-3000:])
        self.assertIn("likely the cells' own force, too stiff for this timestep", line)


    def test_later_step(self):
        # An ordinary tissue, kicked by fix addforce from the force computation
        # of step 2 on: the guard fires at step 3, and names the neighbourhood of
        # step 2 (the step's start), found only then from the cells of that
        # computation while the atoms already stand at their new places.  With
        # every atom a cell the cells' points are the atoms' positions; with a
        # particle of another type they are a copy: both are checked.
        cases = {"cells only": ("1", "vertex/voronoi 3.0", "* * 1 1 0.1 -0.5", ""),
                 "with a particle": ("2", "hybrid/overlay vertex/voronoi 3.0 soft 0.5",
                                     "1 1 vertex/voronoi 1 1 0.1 -0.5",
                                     "pair_coeff * * soft 1.0 0.5\n"
                                     "create_atoms 2 single 2.9 1.3 0 units box\n")}
        for name, (ntypes, style, coeff, extra) in cases.items():
            with self.subTest(name):
                run = self.run_lmp(lmptest.tissue(6, 3, ntypes=int(ntypes)) + f"""
displace_atoms all random 0.1 0.1 0 4821 units box
pair_style {style}
pair_coeff {coeff}
{extra}mass * 1.0
group kicked id 5
variable k equal (step>=2)*2000.0
fix kick kicked addforce v_k 0.0 0.0
fix b all brownian 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(extra="") + "timestep 0.01\nrun 4\n", ok=None)
                line = guard_line(run)
                self.assertIsNotNone(line, run.output[-3000:])
                self.assertIn("in the step from 2 to 3", line)
                frames = run.dump("d.txt")
                self.assertEqual(int(frames[2]["step"]), 2)
                cells = frames[2]
                if ntypes == "2":
                    keep = cells["id"] != max(cells["id"])
                    cells = {k: (v[keep] if k in ("id", "x", "y", "z") else v)
                             for k, v in cells.items()}
                moved, _, _ = self.check_nearest(line, cells)
                self.assertEqual(moved, 5)


class Heun(LammpsTestCase):
    """fix brownian/heun computes the forces a second time at predicted
    positions: the neighbour and the distance named are those of the step's
    start all the same."""

    def test_plane(self):
        # a cell 5e-4 from lattice site 5 (2.149, 0): the predictor throws
        # the pair apart, and the corrector moves atom 1 by the forces of
        # that state
        run = self.run_lmp(lmptest.tissue(6, 3) + """
create_atoms 1 single 2.149 0.0005 0 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
fix h all brownian/heun 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(extra="") + "timestep 0.1\nrun 1\n", ok=None)
        line = guard_line(run)
        self.assertIsNotNone(line, run.output[-3000:])
        first = run.dump("d.txt")[0]
        Causes.check_nearest(self, line, first)
        a, b, d = closest_pair(first, True)
        m = re.search(r"a close pair elsewhere: atoms (\d+) and (\d+) were (\S+) apart at step 0",
                      line)
        if m is None:    # the named atom is one of the pair itself
            self.assertIn("Cause: a close pair: its closest Voronoi neighbour", line)
        else:
            self.assertEqual({int(m.group(1)), int(m.group(2))}, {a, b})
            self.assertEqual(m.group(3), "%.3g" % d)
            self.assertIn("computes the forces again at its predicted positions", line)

    def test_sphere(self):
        # atom 20 put 1e-3 from atom 4 (1.7e-4 apart once on the sphere)
        run = self.run_lmp("""units lj
atom_style dipole
atom_modify map array
boundary f f f
region box block 0 20 0 20 0 20
create_box 1 box
create_atoms 1 random 40 123 box
mass 1 1.0
set group all dipole/random 5 1.0
set atom 20 x $(x[4]+1e-3) y $(y[4]) z $(z[4])
pair_style vertex/voronoi 8 surface sphere 10 10 10 3
pair_coeff * * 1 2.8 0.1 -0.2
fix h all brownian/heun 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(extra="") + "timestep 0.1\nrun 1\n")
        line = guard_line(run)
        self.assertIsNotNone(line, run.output[-3000:])
        moved, j, d = Causes.check_nearest(self, line, run.dump("d.txt")[0], periodic=False)
        self.assertEqual({moved, j}, {4, 20})
        self.assertLess(d, 1e-3)


lmptest.main()
