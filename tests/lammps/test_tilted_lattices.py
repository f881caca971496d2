#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Perfect SC, BCC and FCC lattices in a tilted (triclinic) box, whose tilt
is a lattice period: every cell is the same analytic polyhedron, so the
forces are exactly zero and the volumes tile the box, on 1, 2 and 4 ranks.
(FCC's co-spherical octahedral holes, given with round-off, used to be split
into flat tetrahedra whose circumcentres were round-off: forces of order 1
that depended on the rank count.  SC's squares are four-fold Voronoi edges
where the energy has a kink; before the four-fold rule took the mean of the
two branches there, the forces were 0.94 and depended on how round-off
broke the ties.)"""

from lmptest import LammpsTestCase, nprocs

SCRIPT = """units lj
atom_style atomic
boundary p p p
lattice {lattice} 1.0
region box prism 0 3 0 3 0 3 {tilt} 0 0
create_box 1 box
create_atoms 1 box
mass 1 1
pair_style vertex/voronoi 3.0 incremental {inc}
pair_coeff * * quadratic 1.0 1.0 1.0 5.6
compute fm all reduce max fx fy fz
compute c all vertex/atom
compute v all reduce sum c_c[1]
thermo_style custom step pe c_fm[1] c_fm[2] c_fm[3] c_v vol
thermo_modify norm no
run 0
print "R $(c_fm[1]:%.17g) $(c_fm[2]:%.17g) $(c_fm[3]:%.17g) $(c_v:%.17g) $(vol:%.17g)"
"""


class TiltedLattices(LammpsTestCase):
    def check(self, lattice, n, inc="yes", tilt=1):
        run = self.run_lmp(SCRIPT.format(lattice=lattice, tilt=tilt, inc=inc), nprocs=n)
        row = [[float(w) for w in l.split()[1:]] for l in run.stdout.splitlines() if l.startswith("R ")][0]
        fx, fy, fz, vsum, vol = row
        self.assertLess(max(abs(fx), abs(fy), abs(fz)), 1e-10)
        self.assertAlmostEqual(vsum, vol, delta=1e-10 * vol)

    def test_fcc(self):
        self.check("fcc", 1)
        self.check("fcc", 1, inc="no")

    def test_bcc(self):
        self.check("bcc", 1)

    def test_sc(self):
        for tilt in (1, -1):
            self.check("sc", 1, tilt=tilt)
            self.check("sc", 1, inc="no", tilt=tilt)

    @nprocs(2)
    def test_sc_two_ranks(self):
        for tilt in (1, -1):
            self.check("sc", 2, tilt=tilt)
            self.check("sc", 2, inc="no", tilt=tilt)

    @nprocs(4)
    def test_sc_four_ranks(self):
        for tilt in (1, -1):
            self.check("sc", 4, tilt=tilt)
            self.check("sc", 4, inc="no", tilt=tilt)

    @nprocs(2)
    def test_fcc_two_ranks(self):
        self.check("fcc", 2)

    @nprocs(4)
    def test_fcc_four_ranks(self):
        self.check("fcc", 4)
        self.check("bcc", 4)


import lmptest
lmptest.main()
