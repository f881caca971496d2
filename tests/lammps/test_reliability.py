#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Runs that used to end in NaN, LAMMPS's bare "Lost atoms" or a misleading
tessellation error: a near collision of two centres (an error naming both
atoms, their distance and the step before any atom is lost; a warning when
the run can go on), ranks that own no cell, and atoms lost for another
reason."""

import os
import re

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs


def near_collision(distance, dt, steps=2, site=0):
    """A hexagonal tissue (cells of area 1) and one more cell `distance`
    along the diagonal from the lattice site (site, 0) (site 0: atom 1);
    overdamped dynamics with gamma_T = 1.  The Voronoi forces on the pair
    are about 0.014 / distance here."""
    x0 = site * 1.0745699318235422    # the hex lattice constant for area 1
    return lmptest.tissue(6, 3) + f"""
create_atoms 1 single {x0 + distance} {distance} 0 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
timestep {dt}
fix b all brownian 1.0 1 gamma_t 1.0 rng none
thermo 1
run {steps}
"""


class Collision(LammpsTestCase):

    def test_error_names_pair(self):
        # forces ~1e7 at distance 1e-9: the next step would throw atom 1 or 37
        # ~1e5 away
        run = self.run_lmp(near_collision(1e-9, 0.01), ok=False)
        self.assertLammpsError(run, "the step from 0 to 1", "it would be lost",
                               "smaller timestep", "fix dt/reset", "fix brownian/heun")
        line = [l for l in run.output.splitlines() if "ERROR" in l][0]
        moved, = re.findall(r"atom (\d+) moved by", line)
        other, d = re.findall(r"atom (\d+), was ([0-9.e+-]+) away", line)[0]
        self.assertEqual({int(moved), int(other)}, {1, 37})
        self.assertAlmostEqual(float(d), 1e-9 * 2 ** 0.5, delta=1e-11)    # 3 digits
        self.assertNotIn("Lost atoms", run.output)

    @nprocs(2)
    def test_error_two_ranks(self):
        run = self.run_lmp(near_collision(1e-9, 0.01), nprocs=2, ok=False)
        self.assertLammpsError(run, "it would be lost", "the step from 0 to 1")
        self.assertNotIn("Lost atoms", run.output)

    @nprocs(2)
    def test_coincident_centres_refused(self):
        # 1.4e-12 apart is below what double precision resolves in a box of
        # ~10 (the core's limit, 1e-10 of the coordinates): refused before
        # any force, naming both atoms, their distance and the step
        for n in (1, 2):
            run = self.run_lmp(near_collision(1e-12, 0.01), nprocs=n, ok=False)
            self.assertLammpsError(run, "at step 0", "nearly coincide", "id 1 ", "id 37 ",
                                   "e-12 apart", "fix dt/reset")
            self.assertNotIn("Lost atoms", run.output)

    def test_warning_when_the_run_can_go_on(self):
        # distance 1e-3, dt 0.1: the pair separates by about 1.4 in one step,
        # more than a cell diameter but far from being lost
        run = self.run_lmp(near_collision(1e-3, 0.1, steps=3))
        warnings = [l for l in run.output.splitlines()
                    if "WARNING" in l and "more than a cell diameter" in l]
        self.assertEqual(len(warnings), 1, run.output[-3000:])
        self.assertIn("the step from 0 to 1", warnings[0])
        self.assertIn("reported once per run", warnings[0])

    @nprocs(2)
    def test_warning_two_ranks(self):
        # printed once, by rank 0, whichever rank holds the atom (site 4 is
        # in the right half of the box: rank 1's)
        for site in (0, 4):
            run = self.run_lmp(near_collision(1e-3, 0.1, steps=3, site=site), nprocs=2)
            warnings = [l for l in run.output.splitlines()
                        if "WARNING" in l and "more than a cell diameter" in l]
            self.assertEqual(len(warnings), 1, run.output[-3000:])
            self.assertRegex(warnings[0], r"atom \d+ moved by")

    def test_resolved_step_is_silent(self):
        # the same pair with a timestep that resolves it: no warning
        run = self.run_lmp(near_collision(1e-3, 1e-3, steps=3))
        self.assertNotIn("more than a cell diameter", run.output)

    def test_grooves_reproducers(self):
        # examples/grooves at the thesis's dt with J_S = 1, J_G = 0: some seeds
        # end with two centres colliding (seeds 81 and 2023 used to end in
        # "Lost atoms").  Which seeds collide is chaotic (round-off, e.g. the
        # order in which a repaired mesh sums forces, moves it), so a handful
        # of seeds that collided in some build is run: every collision must
        # be the step guard's message, never "Lost atoms", and at least two
        # must collide.
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                            "grooves", "in.grooves")
        with open(path) as f:
            script = "\n".join(l for l in f.read().splitlines() if not l.startswith("dump"))
        collided = 0
        for seed in (31, 81, 92, 102, 141, 2023):
            run = self.run_lmp(script, variables={"JS": 1, "JG": 0, "seed": seed}, ok=None)
            self.assertNotIn("Lost atoms", run.output)
            errors = [l for l in run.output.splitlines() if "ERROR" in l]
            if not errors:
                self.assertEqual(run.returncode, 0, run.output[-3000:])
                continue
            collided += 1
            self.assertLammpsError(run, "it would be lost", "closest Voronoi neighbour")
            self.assertRegex(errors[0], r"atom \d+ moved by \S+ in the step from \d+ to \d+")
            self.assertRegex(errors[0], r"atom \d+, was \S+ away")
        self.assertGreaterEqual(collided, 2)

    def test_stiff_parameters(self):
        # K = 1e200: every atom would leave; the error says why, not "need at
        # least 3 non-collinear points"
        run = self.run_lmp(lmptest.tissue(6, 3) + """
displace_atoms all random 0.1 0.1 0 4821 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1e200 1.0 0.1 -0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.01
run 3
""", ok=False)
        self.assertLammpsError(run, "moved by", "the timestep does not resolve the forces")
        self.assertNotIn("non-collinear", run.output)


def near_pair_3d(distance, incremental, approach=False, divide=None):
    """A jittered simple cubic tissue of 64 cells (volume 1) and two more
    cells, atoms 65 and 66, `distance` apart along x.  approach: 66 starts
    1e-3 away and moves onto the distance in the first step (fix move, 65
    held still, no neighbour-list rebuild: the flipped mesh's path).  divide: no pair;
    every cell divides with this separation instead."""
    start = 1e-3 if approach else distance
    pair = "" if divide else f"""create_atoms 1 single 1.3 1.2 1.1 units box
create_atoms 1 single {1.3 + start!r} 1.2 1.1 units box
group mover id 66
"""
    moving = (f"group still id 65\ngroup rest subtract all mover still\n"
              f"fix m mover move linear {-(start - distance) / 0.01!r} 0 0\n"
              "fix s still move linear 0 0 0\n"
              "fix b rest brownian 1.0 1 gamma_t 1.0 rng none\n" if approach else
              f"fix div all cell/divide rate 1e6 seed 3 separation {divide!r} max 65\n"
              "fix b all brownian 1.0 1 gamma_t 1.0 rng none\n" if divide else
              "fix b all brownian 1.0 1 gamma_t 1.0 rng none\n")
    return f"""units lj
atom_style atomic
boundary p p p
lattice sc 1.0
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
mass * 1.0
displace_atoms all random 0.2 0.2 0.2 4821 units box
{pair}pair_style vertex/voronoi 3.0 incremental {incremental}
pair_coeff * * 1.0 1.0 0.2 -1.6
{"group mover empty" if not pair else ""}
timestep 0.01
{moving}thermo 1
run 2
"""


class NearPair3d(LammpsTestCase):
    """3D centres closer than the cells resolve (1e-8 .. 1e-15 apart, from
    the start, approaching during a run, or a division's separation) stop
    with one message naming the pair, their distance and the fix, whatever
    the incremental mode and the number of ranks (they used to give NaN
    forces blamed on the units, on an unrelated point)."""

    def message(self, run):
        self.assertLammpsError(run, "nearly coincide", "fix dt/reset")
        line = [l for l in run.output.splitlines() if "ERROR" in l and "coincide" in l][0]
        self.assertNotIn("not finite", run.output)
        # The message without the source location of the rank that raised it.
        return re.sub(r" \(\.\./.*$", "", line.split("ERROR", 1)[1].split(":", 1)[1])

    def test_table(self):
        cases = [(d, inc, approach, n) for d in (1e-8, 1e-13, 1e-15)
                 for inc in ("yes", "no", "check") for approach in (False, True) for n in (1,)]
        cases += [(1e-13, inc, approach, 4) for inc in ("yes", "no") for approach in (False, True)]
        seen = {}
        for d, inc, approach, n in cases:
            with self.subTest(distance=d, incremental=inc, approach=approach, nprocs=n):
                run = self.run_lmp(near_pair_3d(d, inc, approach), nprocs=n, ok=False)
                msg = self.message(run)
                self.assertIn("id 65 at (1.3, 1.2, 1.1", msg)
                self.assertIn("id 66 at (1.3", msg)
                self.assertIn("at step 1" if approach else "at step 0", msg)
                got = float(re.search(r"are ([0-9.e+-]+) apart", msg).group(1))
                # (1.3 + d rounds to a multiple of 2.2e-16)
                self.assertAlmostEqual(got, d, delta=0.3 * d + 3e-16)
                seen.setdefault((d, approach), set()).add(msg)
        for key, msgs in seen.items():
            self.assertEqual(len(msgs), 1, f"{key}: the message depends on the mode or ranks: {msgs}")

    def test_resolved_pair_runs(self):
        # 1e-5 apart is resolved: finite forces, the run goes on (the step
        # guard names the pair if the timestep does not resolve it)
        run = self.run_lmp(near_pair_3d(1e-5, "yes").replace("run 2", "run 0"))
        self.assertNotIn("ERROR", run.output)

    def test_division_separation(self):
        run = self.run_lmp(near_pair_3d(None, "yes", divide=1e-9), ok=False)
        msg = self.message(run)
        self.assertRegex(msg, r"are [0-9.]+e-(09|10) apart")


class LostAtoms(LammpsTestCase):
    """Atoms lost by other means (here an atom put far outside the box):
    the pair style names the count before tessellating what is left."""

    @nprocs(2)
    def test_named(self):
        run = self.run_lmp(lmptest.tissue(6, 3) + """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
set atom 5 x 1e6
run 0
""", nprocs=2, ok=False)
        self.assertLammpsError(run, "35 of 36 atoms are left at step 0", "were lost")


class IdleRank(LammpsTestCase):
    """44 cells (a square lattice) in the left quarter of a 40 x 4 box: with
    'processors 4 1 1' two ranks own no cell.  The run is the same as on one rank."""

    SCRIPT = """
dimension 2
units lj
atom_style dipole
boundary p p p
{processors}
region box block 0 40 0 4 -0.5 0.5 units box
create_box 1 box
region left block 0 10 0 4 -0.5 0.5 units box
lattice sq 1.0
create_atoms 1 region left
mass * 1.0
displace_atoms all random 0.1 0.1 0 4821 units box
reset_atom_ids sort yes
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 4.0 0.1 -1.0
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 1e-4
thermo_style custom step pe
thermo_modify format float %.15g
run 5
write_dump all custom end.dump id x y fx fy modify sort id format float %.17g
"""

    @nprocs(4)
    def test_four_ranks(self):
        one = self.run_lmp(self.SCRIPT.format(processors=""))
        four = self.run_lmp(self.SCRIPT.format(processors="processors 4 1 1"), nprocs=4)
        a, b = one.dump("end.dump")[0], four.dump("end.dump")[0]
        np.testing.assert_array_equal(a["id"], b["id"])
        for col in ("x", "y"):
            np.testing.assert_allclose(a[col], b[col], rtol=0, atol=1e-12)
        for col in ("fx", "fy"):    # up to ~2e3 at the void's edge: round-off relative to that
            np.testing.assert_allclose(a[col], b[col], rtol=1e-10, atol=1e-9)


class FewCells(LammpsTestCase):
    """Fewer than three cells, or cells on one line, are ordinary input in a
    periodic box: the periodic images make the points non-collinear."""

    def energy_area(self, atoms):
        run = self.run_lmp("""
dimension 2
units lj
atom_style dipole
boundary p p p
region box block 0 10 0 10 -0.5 0.5 units box
create_box 1 box
mass * 1.0
""" + "".join("create_atoms 1 single %g %g 0 units box\n" % xy for xy in atoms) + """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 100.0 0.1 -0.5
compute v all vertex/atom
compute a all reduce sum c_v[1]
thermo_style custom step pe c_a
thermo_modify norm no format float %.15g
run 0
""")
        rows = run.stdout.split("Step")[1].split("Loop time")[0].strip().splitlines()
        return [float(w) for w in rows[-1].split()[1:3]]

    def test_one_cell(self):
        # the cell is the 10 x 10 box: A = 100 = A0, P = 40, each edge a
        # junction with an image of itself
        e, a = self.energy_area([(1, 1)])
        self.assertAlmostEqual(a, 100.0, delta=1e-9)
        self.assertAlmostEqual(e, 0.5 * 0.1 * 40 ** 2 + 0.5 * -0.5 * 40, delta=1e-9)

    def test_two_cells(self):
        # a centred rectangular lattice: the areas add up to the box
        e, a = self.energy_area([(1, 1), (6, 6)])
        self.assertAlmostEqual(a, 100.0, delta=1e-9)

    def test_collinear_cells(self):
        # three cells on y = 1 along x: 10-high strips between the bisectors
        # x = 2, 4 and 8 (with the image of the first cell at x = 11)
        e, a = self.energy_area([(1, 1), (3, 1), (5, 1)])
        self.assertAlmostEqual(a, 100.0, delta=1e-9)
        widths = [4.0, 2.0, 4.0]
        areas = [10 * w for w in widths]
        perims = [2 * (10 + w) for w in widths]
        # tension edge: each cell's junctions (with neighbours and with its own
        # images above and below) weighted 1/2
        expected = sum(0.5 * (A - 100) ** 2 + 0.05 * P ** 2 + 0.5 * -0.5 * P
                       for A, P in zip(areas, perims))
        self.assertAlmostEqual(e, expected, delta=1e-9)

if __name__ == "__main__":
    lmptest.main()
