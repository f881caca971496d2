#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Tissues of very few cells: when the ghost atoms give fewer than 3
non-collinear points (4 non-coplanar in 3d), the pair style widens the ghost
shell until the cells' periodic images bound them, instead of stopping.  One
cell in a periodic box is a square (a cube) of the box's size: its energy is
analytic.  On 1, 2 and 4 ranks."""

import lmptest
from lmptest import LammpsTestCase, nprocs

K, A0, G, LAM = 1.0, 1.0, 0.1, -0.5


def one_cell(dim, L=10.0):
    zlo, zhi, z = (-0.5, 0.5, 0.0) if dim == 2 else (0.0, L, 1.0)
    return f"""{"dimension 2" if dim == 2 else ""}
units lj
atom_style atomic
boundary p p p
region box block 0 {L} 0 {L} {zlo} {zhi}
create_box 1 box
create_atoms 1 single 1 1 {z}
mass 1 1
pair_style vertex/voronoi 3.0
pair_coeff * * {K} {A0} {G} {LAM}
thermo_modify norm no
run 0
print "E $(pe:%.17g)"
"""


def energy(run):
    return [float(l.split()[1]) for l in run.stdout.splitlines() if l.startswith("E ")][0]


class OneCell(LammpsTestCase):
    def check(self, dim, n):
        L = 10.0
        run = self.run_lmp(one_cell(dim, L), nprocs=n)
        self.assertIn("cutoff grown", run.stdout)
        # A square (cube) of side L: its edges (faces) are shared with its own
        # images, each junction counted once, i.e. half of the cell's boundary.
        m, b = (L * L, 4 * L) if dim == 2 else (L ** 3, 6 * L * L)
        expect = 0.5 * K * (m - A0) ** 2 + 0.5 * G * b * b + 0.5 * LAM * b
        self.assertAlmostEqual(energy(run), expect, delta=1e-12 * abs(expect))

    def test_2d(self):
        self.check(2, 1)

    @nprocs(2)
    def test_2d_two_ranks(self):
        self.check(2, 2)

    @nprocs(4)
    def test_2d_four_ranks(self):
        self.check(2, 4)

    def test_3d(self):
        self.check(3, 1)

    @nprocs(2)
    def test_3d_two_ranks(self):
        self.check(3, 2)


class DeathToOne(LammpsTestCase):
    def test_last_cell(self):
        """Cells die until one is left; the run goes on with that one."""
        run = self.run_lmp(lmptest.tissue(4, 2) + """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix d all cell/death rate 100 seed 3 min 1
timestep 0.01
thermo_style custom step atoms pe
run 20
print "N $(atoms)"
""")
        n = [float(l.split()[1]) for l in run.stdout.splitlines() if l.startswith("N ")][0]
        self.assertEqual(n, 1)


lmptest.main()
