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


# Two cell types on a simple cubic lattice (rounded coordinates) in a tilted
# box: the forces are not zero, but the mean of the branches at every
# square; they must be the same on any number of ranks and with or without
# the incremental mesh.  (A guard: the branch CGAL picked was consistent
# across ranks here before the rule too; the core tests show the forces are
# the mean of the one-sided derivatives.)
TWO_TYPES = """units lj
atom_style atomic
boundary p p p
lattice sc 1.0 origin 0.3 0.3 0.3
region box prism 0 4 0 4 0 4 1 0 0
create_box 2 box
create_atoms 1 box
set group all type/fraction 2 0.5 4821
mass * 1
pair_style vertex/voronoi 3.0 incremental {inc}
pair_coeff * * 1.0 1.0 0.2 -1.6
pair_coeff 2 2 1.4 0.9 0.3 -2.0
pair_coeff 1 2 0.3
variable f2 atom fx*fx+fy*fy+fz*fz
variable xf atom x*fx+y*fy+z*fz
compute fm all reduce max fx fy fz
compute fs all reduce sum fx fy fz v_f2 v_xf
thermo_style custom step pe c_fm[1] c_fm[2] c_fm[3] c_fs[1] c_fs[2] c_fs[3] c_fs[4] c_fs[5]
run 0
print "R $(pe:%.17g) $(c_fm[1]:%.17g) $(c_fm[2]:%.17g) $(c_fm[3]:%.17g) $(c_fs[1]:%.17g) $(c_fs[2]:%.17g) $(c_fs[3]:%.17g) $(c_fs[4]:%.17g) $(c_fs[5]:%.17g)"
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

    def check_sc(self, n):
        # Simple cubic tilted both ways, with the kept mesh and without.
        for tilt in (1, -1):
            self.check("sc", n, tilt=tilt)
            self.check("sc", n, inc="no", tilt=tilt)

    def test_sc(self):
        self.check_sc(1)

    @nprocs(2)
    def test_sc_two_ranks(self):
        self.check_sc(2)

    def two_types(self, n, inc):
        run = self.run_lmp(TWO_TYPES.format(inc=inc), nprocs=n)
        return [[float(w) for w in l.split()[1:]] for l in run.stdout.splitlines() if l.startswith("R ")][0]

    @nprocs(4)
    def test_sc_two_types_same_on_any_ranks(self):
        ref = self.two_types(1, "no")
        pe, fx, fy, fz, sx, sy, sz, f2, xf = ref
        self.assertGreater(max(fx, fy, fz), 1e-2)  # not trivially zero
        for s in (sx, sy, sz):  # the forces sum to zero
            self.assertLess(abs(s), 1e-10 * f2 ** 0.5)
        for n, inc in ((1, "yes"), (2, "yes"), (2, "no"), (4, "yes"), (4, "no")):
            row = self.two_types(n, inc)
            for a, b in zip(row[:4] + row[7:], ref[:4] + ref[7:]):
                self.assertAlmostEqual(a, b, delta=1e-10 * max(1.0, abs(b)), msg=f"{n} ranks, incremental {inc}")

    @nprocs(4)
    def test_sc_four_ranks(self):
        self.check_sc(4)

    @nprocs(2)
    def test_fcc_two_ranks(self):
        self.check("fcc", 2)

    @nprocs(4)
    def test_fcc_four_ranks(self):
        self.check("fcc", 4)
        self.check("bcc", 4)


import lmptest
lmptest.main()
