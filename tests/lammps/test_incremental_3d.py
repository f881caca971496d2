#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""3d cells from the repaired tetrahedralisation (incremental yes, the
default) against a from-scratch one: 'incremental check' compares every
step's cells with a rebuild (neighbours, volumes, surfaces), and whole runs
with 'incremental yes' and 'no' give the same trajectories to round-off; on
exact lattices, jittered lattices, in tilted boxes and on 1, 2 and 4 ranks."""

import numpy as np

from lmptest import LammpsTestCase, nprocs
import lmptest


def tissue(lattice="bcc", n=3, tilt=None, jitter=0.05, incremental="yes", steps=100):
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
fix p all polarity 0.5 1.0 neighbor 0.5
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
