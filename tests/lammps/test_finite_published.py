#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""pair_style vertex/voronoi ... radius r against published numbers: the forces
that the original MATLAB code of the active finite Voronoi model (Huang,
Levine & Bi, Soft Matter 19, 9389, 2023) gives on 100 cells, as published
with PyAFV's test suite (quoted in studies/finite/pyafv_reference.txt, where
the source is named).  PyAFV itself requires 1e-8 against the same values;
so does this test (uniform A0 in an open and a periodic box, on 1 and 2
ranks, and one preferred area per cell, as one atom type per cell and as the
per-atom d_area0)."""

import math
import os

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

REFERENCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "studies",
                         "finite", "pyafv_reference.txt")
# r = 1, A0 = pi, P0 = 4.8, KA = KP = 1, Lambda = 0.2 (quadratic form, PyAFV's convention)
KA, A0, KP, P0, LAM = 1.0, math.pi, 1.0, 4.8, 0.2
TOL = 1e-8


def centres():
    """The MATLAB script's centres: rand(100, 2) of the twister seeded 42 (filled column by
    column; numpy's RandomState(42) gives the same numbers) in the middle of a box of side
    sqrt(100 pi / 0.5)."""
    n = 100
    box = math.sqrt(n * math.pi / 0.5)
    u = np.random.RandomState(42).rand(2 * n).reshape(2, n).T
    return ((u - 0.5) * 0.3 + 0.5) * box, box


def data_file(xy, box, ntypes):
    lines = ["PyAFV reference configuration", "", "%d atoms" % len(xy), "%d atom types" % ntypes, "",
             "0 %r xlo xhi" % box, "0 %r ylo yhi" % box, "-0.5 0.5 zlo zhi", "", "Masses", ""]
    lines += ["%d 1.0" % (t + 1) for t in range(ntypes)] + ["", "Atoms # atomic", ""]
    lines += ["%d %d %r %r 0.0" % (i + 1, i + 1 if ntypes > 1 else 1, x, y)
              for i, (x, y) in enumerate(xy)]
    return "\n".join(lines) + "\n"


class PublishedForces(LammpsTestCase):

    def setUp(self):
        super().setUp()
        ref = np.loadtxt(REFERENCE)
        self.a0_cell, self.f_ref, self.f_ref_a0 = ref[:, 0], ref[:, 1:3], ref[:, 3:5]
        self.xy, self.box = centres()

    def forces(self, boundary, per_cell=False, n=1, d_area0=False):
        pre = post = ""
        if d_area0:
            # atom_style atomic has no d_area0: fix property/atom adds it
            pre = "fix a0 all property/atom d_area0\n"
            post = "".join("set atom %d d_area0 %r\n" % (i + 1, a) for i, a in enumerate(self.a0_cell))
        if per_cell:
            coeffs = "".join("pair_coeff %d %d quadratic %r %r %r %r free %r\n"
                             % (i + 1, i + 1, KA, a, KP, P0, LAM) for i, a in enumerate(self.a0_cell))
        else:
            coeffs = "pair_coeff * * quadratic %r %r %r %r free %r\n" % (KA, A0, KP, P0, LAM)
        run = self.run_lmp(f"""dimension 2
units lj
atom_style atomic
boundary {boundary}
{pre}read_data cells.data
{post}pair_style vertex/voronoi 2.2 radius 1.0
{coeffs}dump d all custom 1 f.dump id fx fy
dump_modify d sort id format float %.17g
run 0
""", nprocs=n, files={"cells.data": data_file(self.xy, self.box, 100 if per_cell else 1)})
        fr = run.dump("f.dump")[0]
        return np.column_stack([fr["fx"], fr["fy"]])

    def check(self, boundary, per_cell=False, n=1, d_area0=False):
        ours = self.forces(boundary, per_cell, n, d_area0)
        theirs = self.f_ref_a0 if per_cell or d_area0 else self.f_ref
        diff = np.max(np.abs(ours - theirs))
        self.assertLess(diff, TOL, "largest force difference to the MATLAB code: %g" % diff)

    def test_centres_are_the_published_ones(self):
        # first and last row of PyAFV's tests/data/init_pts.csv
        self.assertLess(np.max(np.abs(self.xy[0] - (11.5896975168679, 9.00954281768149))), 1e-12)
        self.assertLess(np.max(np.abs(self.xy[-1] - (9.58453006568361, 14.6377732430285))), 1e-12)

    def test_open(self):
        self.check("s s p")

    def test_periodic(self):
        self.check("p p p")

    def test_per_cell_area_as_types(self):
        self.check("s s p", per_cell=True)

    def test_per_cell_area_as_d_area0(self):
        # one type, each cell's A0 from fix property/atom d_area0
        self.check("s s p", d_area0=True)

    @nprocs(2)
    def test_per_cell_area_as_d_area0_2_ranks(self):
        self.check("p p p", n=2, d_area0=True)

    @nprocs(2)
    def test_open_2_ranks(self):
        self.check("s s p", n=2)

    @nprocs(2)
    def test_periodic_2_ranks(self):
        self.check("p p p", n=2)


if __name__ == "__main__":
    lmptest.main()
