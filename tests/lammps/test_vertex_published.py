#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The vertex model (pair_style vertex/polygon) against published set-ups.

* Sussman & Merkel (Soft Matter 14, 3397, 2018) compare the Voronoi and the
  vertex model from the same polygons: a Voronoi tessellation of random
  centres has the same energy in pair_style vertex/voronoi and, converted by
  create_vertices, in pair_style vertex/polygon (to round-off; a table of
  cases: forms of pair_coeff, two types with a junction tension, a tilted box).
* Farhadifar et al. (Curr. Biol. 17, 2095, 2007): the energy
  sum K/2 (A - A0)^2 + sum_edges Lambda l + sum Gamma/2 P^2 in their normalised
  parameters Lambda-bar = Lambda / (K A0^(3/2)), Gamma-bar = Gamma / (K A0).
  Each edge is shared by two cells, so per cell Gamma/2 P^2 + Lambda/2 P =
  (Gamma/2) (P + Lambda/(2 Gamma))^2 + const: KP = Gamma/2, P0 = -Lambda/(2 Gamma).
  The hexagonal network of "case I" (Lambda-bar = 0.12, Gamma-bar = 0.04),
  minimised with the box free (fix box/relax), has the area and perimeter of
  the closed form's minimum over the hexagon's area a = A/A0,
  e(a) = (a - 1)^2/2 + Gamma-bar c^2 a/2 + Lambda-bar c sqrt(a)/2,
  c = sqrt(8 sqrt 3); a jittered network returns to it; the quadratic form
  with the mapped KP and P0 gives the same forces; and its shear modulus is
  the closed form's G = Gamma P_h (P_h - P0) / (4 A) on the stable side of
  the boundary P0 = P_h (Lambda-bar = -2 c Gamma-bar sqrt(a)) and 0 beyond it.
"""

import math

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

C_HEX = math.sqrt(8 * math.sqrt(3))   # perimeter of the regular hexagon of unit area


def printed(run, tag):
    return [[float(v) for v in line.split()[1:]] for line in run.stdout.splitlines()
            if line.startswith(tag + " ")]


# name -> (box region, pair_coeff lines of the cell types 1 and 2 for both styles)
SAME_ENERGY = {
    "quadratic": ("block 0 10 0 10 -0.5 0.5",
                  "pair_coeff 1 1 quadratic 1.0 1.0 1.0 3.8\n"
                  "pair_coeff 2 2 quadratic 1.0 1.0 1.0 3.8\n"),
    "two_types_sigma": ("block 0 10 0 10 -0.5 0.5",
                        "pair_coeff 1 1 quadratic 1.0 1.0 0.8 3.7\n"
                        "pair_coeff 2 2 quadratic 0.7 1.2 0.5 3.9\n"
                        "pair_coeff 1 2 quadratic 0.3\n"),
    "thesis_form": ("block 0 10 0 10 -0.5 0.5",
                    "pair_coeff 1 1 1.0 1.0 0.08 0.12\n"
                    "pair_coeff 2 2 2.0 0.9 0.04 -0.3\n"
                    "pair_coeff 1 2 0.2\n"),
    "tilted": ("prism 0 10 0 10 -0.5 0.5 3.0 0 0",
               "pair_coeff 1 1 quadratic 1.0 1.0 0.8 3.7\n"
               "pair_coeff 2 2 quadratic 0.7 1.2 0.5 3.9\n"
               "pair_coeff 1 2 quadratic 0.3\n"),
}


def same_start_script(region, coeffs, seed=2018):
    """Random centres: their Voronoi tissue's pe, then the vertex tissue's of
    the same polygons (create_vertices), printed as 'E voronoi vertex'."""
    return f"""
dimension 2
units lj
atom_style atomic
atom_modify map yes
boundary p p p
region box {region}
create_box 3 box
create_atoms 1 random 100 {seed} box
set type 1 type/fraction 2 0.4 {seed + 1}
mass * 1.0
pair_style vertex/voronoi 4.0
{coeffs}pair_coeff 3 3 quadratic 1.0 1.0 1.0 3.8
thermo_modify norm no
run 0
variable evor equal $(pe:%.17g)
create_vertices all 3
pair_style vertex/polygon 4.0
{coeffs}pair_coeff 3 3 vertex
run 0
print "E ${{evor}} $(pe:%.17g)"
"""


class SussmanMerkel(LammpsTestCase):
    """The same polygons have the same energy in both models."""

    def check(self, name, nprocs=1):
        region, coeffs = SAME_ENERGY[name]
        run = self.run_lmp(same_start_script(region, coeffs), nprocs=nprocs)
        (evor, evert), = printed(run, "E")
        self.assertGreater(abs(evor), 1.0, name)        # not a trivial zero
        self.assertAlmostEqual(evert, evor, delta=1e-11 * abs(evor), msg=name)

    def test_cases(self):
        for name in SAME_ENERGY:
            with self.subTest(name):
                self.check(name)

    @nprocs(2)
    def test_two_ranks(self):
        self.check("two_types_sigma", nprocs=2)


def hex_tissue(nx, ny, scale, gamma_bar, lambda_bar, jitter=0.0, form="thesis"):
    """A regular hexagonal vertex tissue of nx x ny cells of area scale^2 (K = A0 = 1),
    Farhadifar's energy in Tessera's thesis form or the mapped quadratic form."""
    if form == "thesis":
        coeff = f"pair_coeff 1 1 1.0 1.0 {gamma_bar} {lambda_bar}"
    else:   # KA = K/2, KP = Gamma/2, P0 = -Lambda/(2 Gamma)
        coeff = (f"pair_coeff 1 1 quadratic 0.5 1.0 {gamma_bar / 2} "
                 f"{-lambda_bar / (2 * gamma_bar)}")
    jit = (f"group vertices type 2\ndisplace_atoms vertices random {jitter} {jitter} 0 77 "
           "units box\n" if jitter else "group vertices type 2\n")
    return f"""
dimension 2
units lj
atom_style atomic
atom_modify map yes
boundary p p p
lattice hex {1.0 / scale ** 2}
region box block 0 {nx} 0 {ny} -0.5 0.5
create_box 2 box
create_atoms 1 box
mass * 1.0
create_vertices all 2
{jit}pair_style vertex/polygon 4.0
{coeff}
pair_coeff 2 2 vertex
thermo_modify norm no
compute cell all vertex/atom
compute area all reduce sum c_cell[1]
compute perim all reduce sum c_cell[2]
thermo_style custom step pe pxy vol c_area c_perim
thermo_modify norm no
"""


def closed_form_minimum(gamma_bar, lambda_bar):
    """The hexagon's area a (units A0) minimising e(a), and e, P there."""
    from scipy.optimize import minimize_scalar

    def e(a):
        return ((a - 1) ** 2 / 2 + gamma_bar * C_HEX ** 2 * a / 2
                + lambda_bar * C_HEX * math.sqrt(a) / 2)
    res = minimize_scalar(e, bounds=(1e-6, 4.0), method="bounded",
                          options=dict(xatol=1e-13))
    a = res.x
    return a, e(a), C_HEX * math.sqrt(a)


CASE_I = (0.04, 0.12)    # (Gamma-bar, Lambda-bar), Farhadifar et al. 2007


class Farhadifar(LammpsTestCase):

    def test_case_I_ground_state(self):
        gamma_bar, lambda_bar = CASE_I
        a, e, p = closed_form_minimum(gamma_bar, lambda_bar)
        self.assertTrue(0.5 < a < 1.0)     # the tensions shrink the cells below A0
        n = 2 * 4 * 2      # two cells per unit cell of the hex lattice
        for jitter in (0.0, 0.03):
            script = hex_tissue(4, 2, 1.0, gamma_bar, lambda_bar, jitter=jitter) + """
fix relax all box/relax x 0.0 y 0.0 couple xy vmax 0.001
min_modify line quadratic
minimize 0 1e-13 20000 40000
unfix relax
minimize 0 1e-13 20000 40000
run 0
print "M $(pe:%.17g) $(c_area:%.17g) $(c_perim:%.17g) $(vol:%.17g)"
"""
            (pe, area, perim, vol), = printed(self.run_lmp(script), "M")
            with self.subTest(jitter=jitter):
                self.assertAlmostEqual(area / n, a, delta=1e-7)
                self.assertAlmostEqual(vol / n, a, delta=1e-7)
                self.assertAlmostEqual(perim / n, p, delta=1e-7)
                self.assertAlmostEqual(pe / n, e, delta=1e-9)

    def test_mapping_to_the_quadratic_form(self):
        # the same forces in both forms (the energies differ by a constant)
        gamma_bar, lambda_bar = CASE_I
        dumps = []
        for form in ("thesis", "quadratic"):
            script = hex_tissue(4, 2, 0.9, gamma_bar, lambda_bar, jitter=0.1, form=form) + """
dump d all custom 1 forces.dump id fx fy
dump_modify d sort id format float %.17g
run 0
"""
            dumps.append(self.run_lmp(script).dump("forces.dump")[-1])
        f0 = np.column_stack([dumps[0]["fx"], dumps[0]["fy"]])
        f1 = np.column_stack([dumps[1]["fx"], dumps[1]["fy"]])
        self.assertGreater(np.abs(f0).max(), 1e-3)
        np.testing.assert_allclose(f1, f0, atol=1e-12 * np.abs(f0).max())

    def test_shear_modulus_across_the_boundary(self):
        # At fixed area A = A0: G = Gamma P_h (P_h - P0) / (4 A) (KP = Gamma/2 in
        # G = KP P_h (P_h - P0) / (2 A)) while P0 = -Lambda/(2 Gamma) < P_h, i.e.
        # Lambda-bar > -2 c Gamma-bar: the hexagonal network; 0 beyond (soft network).
        gamma_bar = CASE_I[0]
        boundary = -2 * C_HEX * gamma_bar
        eps = 1e-3
        for lambda_bar in (CASE_I[1], boundary + 0.05, boundary - 0.05):
            p0 = -lambda_bar / (2 * gamma_bar)
            expect = max(0.0, gamma_bar * C_HEX * (C_HEX - p0) / 4)
            script = hex_tissue(4, 2, 1.0, gamma_bar, lambda_bar, jitter=0.0) + f"""
change_box all triclinic
min_modify line quadratic
minimize 0 1e-13 1000 4000
variable s equal -pxy
change_box all xy delta {eps} remap units box
minimize 0 1e-13 10000 40000
run 0
print "S $(v_s:%.17g) $(ly:%.17g)"
change_box all xy delta {-2 * eps} remap units box
minimize 0 1e-13 10000 40000
run 0
print "S $(v_s:%.17g) $(ly:%.17g)"
"""
            (sp, ly), (sm, _) = printed(self.run_lmp(script), "S")
            g = (sp - sm) / (2 * eps / ly)
            with self.subTest(lambda_bar=lambda_bar):
                self.assertAlmostEqual(g, expect, delta=1e-5 + 1e-4 * expect)


if __name__ == "__main__":
    lmptest.main()
