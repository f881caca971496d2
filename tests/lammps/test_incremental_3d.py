#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""3d cells from the repaired tetrahedralisation (incremental yes, the
default) against a from-scratch one: 'incremental check' compares every
step's cells with a rebuild (neighbours, volumes, surfaces), and whole runs
with 'incremental yes' and 'no' give the same trajectories to round-off; on
exact lattices, jittered lattices, lattices with slivers (jittered by
1e-12), in tilted boxes and on 1, 2 and 4 ranks."""

import numpy as np

from lmptest import LammpsTestCase, nprocs
import lmptest


def tissue(lattice="bcc", n=3, tilt=None, jitter=0.05, incremental="yes", steps=100, v0=0.5):
    region = (f"region box prism 0 {n} 0 {n} 0 {n} {tilt} {tilt} 0" if tilt is not None
              else f"region box block 0 {n} 0 {n} 0 {n}")
    jit = f"displace_atoms all random {jitter} {jitter} {jitter} 4821 units box" if jitter else ""
    return f"""units lj
atom_style dipole
boundary p p p
lattice {lattice} 1.0
{region}
create_box 1 box
create_atoms 1 box
{jit}
mass 1 1.0
set group all dipole/random 3313 1.0
pair_style vertex/voronoi 3.0 incremental {incremental}
pair_coeff * * quadratic 1.0 1.0 0.05 5.8
fix p all polarity {v0} 1.0 neighbor 0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.01
compute pr all pair vertex/voronoi
thermo_style custom step pe c_pr[3] c_pr[4]
thermo_modify norm no format float %.17g
thermo 50
run {steps}
write_dump all custom end.dump id xu yu zu modify sort id format float %.17g
"""


class Check(LammpsTestCase):
    """incremental check stops the run if any step's cells differ."""

    def run_check(self, ranks=1, **kw):
        run = self.run_lmp(tissue(incremental="check", **kw), nprocs=ranks)
        self.assertNotIn("differs", run.output)

    def test_bcc(self):
        self.run_check(lattice="bcc")

    def test_fcc_exact(self):
        self.run_check(lattice="fcc", jitter=0.0, steps=20)

    def test_sc_jittered(self):
        self.run_check(lattice="sc", n=4, jitter=0.02)

    def test_tilted(self):
        self.run_check(lattice="bcc", tilt=1.0)

    def test_slivers(self):
        # Simple cubic lattices jittered by 1e-12 (in a tilted box and not),
        # passive (v0 = 0: the forces of a near-lattice are ~1e-12, so the
        # cells barely move): co-spherical clusters triangulated with nearly
        # flat tetrahedra at every step, whose circumcentres the repaired
        # mesh computes exactly.
        for tilt in (None, 1.0):
            self.run_check(lattice="sc", n=3, tilt=tilt, jitter=1e-12, steps=10, v0=0.0)

    def test_sliver_cluster(self):
        # Eight cells of a simple cubic lattice in a tilted box as a run left
        # them (core test Reliability3D.SliverCircumcentresAreExact): slivers
        # whose circumcentres the plain formula gets visibly wrong.  Held in
        # place (gamma_t 1e12), every step is checked against a rebuild.
        xyz = [(-0.107762060128898, -3.6701161547548891, -3.6701161548096661),
               (-0.10776206008609845, -3.6701161549499437, -1.8889391074336914),
               (-0.10776206011517164, -2.426073738293268, -0.10776206002668776),
               (-0.1077620600245246, -1.8889391073361359, -1.8889391074999917),
               (-0.94359056737818503, -0.10776206005234013, -3.670116154800469),
               (-1.8889391074143835, -3.6701161549797816, -1.8889391075284323),
               (-1.8889391073227453, -2.426073738285607, -0.10776206007886868),
               (-1.8889391073235646, -1.8889391074479687, -1.8889391073595172)]
        lo, hi = -3.6701161548697527, -0.10776206000552024
        atoms = "\n".join(f"create_atoms 1 single {x!r} {y!r} {z!r} units box" for x, y, z in xyz)
        run = self.run_lmp(f"""units lj
atom_style dipole
boundary p p p
region box prism {lo!r} {hi!r} {lo!r} {hi!r} {lo!r} {hi!r} 0.94534853994367918 0 -0.5371346307860223
create_box 1 box
{atoms}
mass 1 1.0
set group all dipole/random 3313 1.0
pair_style vertex/voronoi 3.0 incremental check
pair_coeff * * quadratic 1.0 1.0 0.05 5.8
fix p all polarity 0.0 1.0
fix b all brownian 1.0 1 gamma_t 1e12 rng none
timestep 0.01
compute pr all pair vertex/voronoi
thermo_style custom step pe c_pr[3] c_pr[4]
run 5
""")
        self.assertNotIn("differs", run.output)

    @nprocs(2)
    def test_two_ranks_slivers(self):
        self.run_check(ranks=2, lattice="sc", n=4, tilt=1.0, jitter=1e-12, steps=10, v0=0.0)

    @nprocs(2)
    def test_two_ranks(self):
        self.run_check(ranks=2, lattice="bcc", n=4)

    @nprocs(4)
    def test_four_ranks(self):
        self.run_check(ranks=4, lattice="bcc", n=4)


class SameTrajectory(LammpsTestCase):
    """200 steps with the repaired mesh and with a rebuild every step."""

    def test_yes_vs_no(self):
        ends = [self.run_lmp(tissue(incremental=inc, steps=200)).dump("end.dump")[0]
                for inc in ("yes", "no")]
        for col in ("xu", "yu", "zu"):
            np.testing.assert_allclose(ends[0][col], ends[1][col], rtol=0, atol=1e-9, err_msg=col)
        moved = self.run_lmp(tissue(incremental="yes", steps=0)).dump("end.dump")[0]
        self.assertGreater(np.abs(ends[0]["xu"] - moved["xu"]).max(), 1e-3)

    def test_fewer_rebuilds(self):
        run = self.run_lmp(tissue(incremental="yes", steps=100))
        rows = [l.split() for l in run.stdout.splitlines() if l.strip().startswith("100 ")]
        rebuilds = float(rows[-1][2])
        self.assertLess(rebuilds, 50)    # a rebuild only after neighbor-list builds


lmptest.main()
