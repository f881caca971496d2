#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Cells on a sphere among atoms that are no cells (pair_style hybrid/overlay):

* fix polarity treats those as active Brownian particles in space, as it does
  off the sphere: their polarity is not made tangent to the sphere (one at
  its centre, which has no tangent plane, used to stop the run), it diffuses
  in three dimensions, while the cells' polarities stay tangent;
* the minimisers see the gradient of the energy on the sphere: another
  sub-style's forces between cells act along chords, whose radial part the
  constraint holds; cg and sd used to stop on "linesearch alpha is zero"
  with fnorm 5.7.  Now they reach the force tolerance, and the minimum is
  stationary: central differences of pe along the sphere vanish."""

import numpy as np

import lmptest
from lmptest import LammpsTestCase

CELLS = """units lj
atom_style dipole
atom_modify map array
boundary f f f
region box block 0 20 0 20 0 20
create_box 2 box
create_atoms 1 random 40 123 box
create_atoms 2 single 10 10 10 units box
mass * 1.0
"""


class Polarity(LammpsTestCase):

    def test_particles_diffuse_in_space(self):
        run = self.run_lmp(CELLS + """create_atoms 2 single 10 10 15 units box
set group all dipole/random 5 1.0
set atom 42 dipole 1 0 0
pair_style hybrid/overlay vertex/voronoi 8 surface sphere 10 10 10 3 zero 1.0
pair_coeff 1 1 vertex/voronoi 1 2.8 0.1 -0.2
pair_coeff * * zero
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix p all polarity 0.1 1.0 noise 0.5 77 velocity 0.2
timestep 0.01
dump d all custom 20 d.txt id type x y z mux muy muz
dump_modify d sort id format float %.17g
run 20
""")
        last = run.dump("d.txt")[-1]
        x = np.column_stack([last["x"], last["y"], last["z"]]) - 10.0
        mu = np.column_stack([last["mux"], last["muy"], last["muz"]])
        cells = last["type"] == 1
        # the cells' polarities are tangent to the sphere
        radial = np.abs(np.sum(x[cells] * mu[cells], axis=1)) / np.linalg.norm(x[cells], axis=1)
        self.assertLess(radial.max(), 1e-12)
        # atom 42 sits over the pole (0, 0, 5) with mu along x: in-plane noise
        # about the radial axis would keep mu_z = 0; 3d diffusion does not
        k = int(np.nonzero(last["id"] == 42)[0][0])
        self.assertGreater(abs(mu[k, 2]), 1e-3)
        self.assertAlmostEqual(np.linalg.norm(mu[k]), 1.0, delta=1e-12)
        # and the one at the centre kept a unit polarity (no error)
        c = int(np.nonzero(last["id"] == 41)[0][0])
        self.assertAlmostEqual(np.linalg.norm(mu[c]), 1.0, delta=1e-12)


class Minimize(LammpsTestCase):

    SETUP = CELLS + """pair_style hybrid/overlay vertex/voronoi 8 surface sphere 10 10 10 3 soft 2.5
pair_coeff 1 1 vertex/voronoi 1 2.8 0.1 -0.2
pair_coeff * * soft 0.5
thermo_modify norm no
"""

    def test_minimizers_reach_the_tolerance(self):
        for style in ("cg", "sd"):
            with self.subTest(style):
                run = self.run_lmp(self.SETUP + f"min_style {style}\n"
                                   "minimize 0 1e-6 20000 100000\n"
                                   "print \"FNORM $(fnorm:%.6g)\"\n")
                self.assertIn("Stopping criterion = force tolerance", run.stdout)
                fnorm = float([l for l in run.stdout.splitlines()
                               if l.startswith("FNORM")][0].split()[1])
                self.assertLess(fnorm, 1e-6)

    def test_minimum_is_stationary_on_the_sphere(self):
        # after cg: move cell 7 by +-h along two tangent directions (the pair
        # style puts it back on the sphere at 'run 0', a second-order change
        # that the central difference cancels): pe does not change to first
        # order
        h = 1e-4
        script = self.SETUP + "min_style cg\nminimize 0 1e-8 20000 100000\n" \
            "variable ux equal (x[7]-10)/3\nvariable uy equal (y[7]-10)/3\n" \
            "variable uz equal (z[7]-10)/3\n"
        # tangent directions: u x e_z and u x (u x e_z), normalised in the input
        script += """variable t1x equal v_uy
variable t1y equal -v_ux
variable t1z equal 0
variable n1 equal sqrt(v_t1x^2+v_t1y^2)
variable a1x equal $(v_t1x/v_n1)
variable a1y equal $(v_t1y/v_n1)
variable a1z equal 0
variable a2x equal $(v_uy*v_a1z-v_uz*v_a1y)
variable a2y equal $(v_uz*v_a1x-v_ux*v_a1z)
variable a2z equal $(v_ux*v_a1y-v_uy*v_a1x)
variable x0 equal $(x[7])
variable y0 equal $(y[7])
variable z0 equal $(z[7])
"""
        for k in (1, 2):
            for sign, tag in ((1, "P"), (-1, "M")):
                script += (f"set atom 7 x $(v_x0+{sign}*{h}*v_a{k}x) y $(v_y0+{sign}*{h}*v_a{k}y) "
                           f"z $(v_z0+{sign}*{h}*v_a{k}z)\nrun 0\n"
                           f"print \"E{k}{tag} $(pe:%.17g)\"\n")
        run = self.run_lmp(script)
        e = {l.split()[0]: float(l.split()[1]) for l in run.stdout.splitlines()
             if l.startswith("E") and len(l.split()) == 2}
        for k in (1, 2):
            slope = (e[f"E{k}P"] - e[f"E{k}M"]) / (2 * h)
            self.assertLess(abs(slope), 1e-5, e)


lmptest.main()
