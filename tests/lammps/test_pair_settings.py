#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""pair_style vertex/voronoi's settings and parameters: every setting survives
write_restart/read_restart, fix adapt changes kappa, area0, gamma and lambda
(same-type and heterotypic) during a run, the heterotypic tension of the
quadratic form, and the parameter table in the log.  Energies are checked
against the analytic energy of a regular hexagonal lattice."""

import math
import re

import lmptest
from lmptest import LammpsTestCase, nprocs

P = math.sqrt(8.0 * math.sqrt(3.0))     # perimeter of a regular hexagon of area 1
L = P / 6.0                             # its junction length


def two_type_tissue(nx=6, ny=3):
    """A hexagonal lattice (area 1 per cell) whose two basis atoms are types
    1 and 2: each cell has 2 same-type and 4 other-type neighbours, so N
    cells have N/2 1-1, N/2 2-2 and 2N 1-2 junctions."""
    return lmptest.tissue(nx, ny, "hex", 2).replace("create_atoms 1 box",
                                                   "create_atoms 1 box basis 2 2")


def hex_energy_per_cell(K, A0, G, lam11, lam22, lam12, weight=1.0, K2=None, A02=None):
    """Energy per cell of the two-type lattice (areas 1); weight 1 for
    tension edge (each junction once), 2 for tension cell (twice)."""
    K2 = K if K2 is None else K2
    A02 = A0 if A02 is None else A02
    area = 0.25 * K * (1.0 - A0) ** 2 + 0.25 * K2 * (1.0 - A02) ** 2
    return area + 0.5 * G * P * P + weight * L * (0.5 * lam11 + 0.5 * lam22 + 2.0 * lam12)


def thermo(run):
    """(step, pe) rows of the thermo output 'step pe'."""
    rows, on = [], False
    for line in run.stdout.splitlines():
        w = line.split()
        if w[:2] == ["Step", "PotEng"]:
            on = True
            continue
        if on and len(w) == 2 and re.match(r"^-?\d+$", w[0]):
            rows.append((int(w[0]), float(w[1])))
        elif on:
            on = False
    return rows


class Adapt(LammpsTestCase):
    """fix adapt ramps a parameter; the energy of every step is the analytic
    hexagon energy with that step's value."""

    def ramp(self, param, pair, nprocs=1, tension="edge", coeffs=None):
        coeffs = coeffs or "pair_coeff * * 1.0 1.0 0.1 -0.5\n"
        run = self.run_lmp(two_type_tissue() + f"""
pair_style vertex/voronoi 3.0 tension {tension}
{coeffs}
variable v equal 0.8+0.1*step
fix a all adapt 1 pair vertex/voronoi {param} {pair} v_v
thermo_style custom step pe
thermo_modify format float %.15g
thermo 1
run 3
""", nprocs=nprocs)
        rows = thermo(run)
        self.assertEqual([s for s, _ in rows], [0, 1, 2, 3])
        return [(s, 0.8 + 0.1 * s, e) for s, e in rows]

    def check_diag(self, param, nprocs=1):
        for step, v, e in self.ramp(param, "* *", nprocs):
            p = {"kappa": 1.0, "area0": 1.0, "gamma": 0.1, "lambda": -0.5}
            p[param] = v
            lam = p["lambda"]
            expected = hex_energy_per_cell(p["kappa"], p["area0"], p["gamma"], lam, lam, lam)
            self.assertAlmostEqual(e, expected, delta=1e-12, msg="%s at step %d" % (param, step))

    def test_kappa(self):
        # area 1 != A0 so that kappa enters
        for step, v, e in self.ramp("kappa", "* *", coeffs="pair_coeff * * 1.0 1.2 0.1 -0.5"):
            self.assertAlmostEqual(e, hex_energy_per_cell(v, 1.2, 0.1, -0.5, -0.5, -0.5),
                                   delta=1e-12, msg="step %d" % step)

    def test_area0(self):
        self.check_diag("area0")

    def test_gamma(self):
        self.check_diag("gamma")

    def test_lambda(self):
        self.check_diag("lambda")

    @nprocs(2)
    def test_area0_two_ranks(self):
        self.check_diag("area0", nprocs=2)

    @nprocs(2)
    def test_lambda_two_ranks(self):
        self.check_diag("lambda", nprocs=2)

    @nprocs(2)
    def test_kappa_gamma_two_ranks(self):
        for step, v, e in self.ramp("kappa", "* *", nprocs=2,
                                    coeffs="pair_coeff * * 1.0 1.2 0.1 -0.5"):
            self.assertAlmostEqual(e, hex_energy_per_cell(v, 1.2, 0.1, -0.5, -0.5, -0.5),
                                   delta=1e-12)
        self.check_diag("gamma", nprocs=2)

    def test_one_type_area0(self):
        # only type 2's A0 changes
        coeffs = "pair_coeff * * 1.0 1.0 0.1 -0.5"
        for step, v, e in self.ramp("area0", "2 2", coeffs=coeffs):
            self.assertAlmostEqual(e, hex_energy_per_cell(1.0, 1.0, 0.1, -0.5, -0.5, -0.5,
                                                          A02=v), delta=1e-12)

    def test_heterotypic_lambda(self):
        # Lambda_12 was the default mean; fix adapt sets it
        coeffs = "pair_coeff 1 1 1.0 1.0 0.1 -0.5\npair_coeff 2 2 1.0 1.0 0.1 -0.7"
        for tension, weight in (("edge", 1.0), ("cell", 2.0)):
            for step, v, e in self.ramp("lambda", "1 2", tension=tension, coeffs=coeffs):
                self.assertAlmostEqual(e, hex_energy_per_cell(1.0, 1.0, 0.1, -0.5, -0.7, v,
                                                              weight), delta=1e-12)

    def test_same_type_lambda_moves_default_mean(self):
        # Lambda_11 changes; Lambda_12 (not given) follows as the mean
        coeffs = "pair_coeff 1 1 1.0 1.0 0.1 -0.5\npair_coeff 2 2 1.0 1.0 0.1 -0.7"
        for step, v, e in self.ramp("lambda", "1 1", coeffs=coeffs):
            self.assertAlmostEqual(e, hex_energy_per_cell(1.0, 1.0, 0.1, v, -0.7,
                                                          0.5 * (v - 0.7)), delta=1e-12)

    def test_nonpositive_area0_refused(self):
        run = self.run_lmp(two_type_tissue() + """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
variable v equal 1.0-0.6*step
fix a all adapt 1 pair vertex/voronoi area0 * * v_v
run 3
""", ok=False)
        self.assertLammpsError(run, "area0 of type 1 must be > 0")


class QuadraticHeterotypic(LammpsTestCase):
    """pair_coeff I J quadratic sigma: a heterotypic junction's energy per
    length is the default mean plus sigma, in both tension conventions."""

    def test_energy(self):
        # quadratic form: K = 2 KA, Gamma = 2 KP, Lambda = -2 Gamma P0 (edge) or -Gamma P0 (cell)
        KA, KP, P01, P02, sigma = 0.5, 0.05, 3.0, 3.5, 0.3
        G = 2 * KP
        for tension, weight, c in (("edge", 1.0, 2.0), ("cell", 2.0, 1.0)):
            run = self.run_lmp(two_type_tissue() + f"""
pair_style vertex/voronoi 3.0 tension {tension}
pair_coeff 1 1 quadratic {KA} 1.0 {KP} {P01}
pair_coeff 2 2 quadratic {KA} 1.0 {KP} {P02}
pair_coeff 1 2 quadratic {sigma}
thermo_style custom step pe
thermo_modify format float %.15g
run 0
""")
            lam1, lam2 = -c * G * P01, -c * G * P02
            lam12 = 0.5 * (lam1 + lam2) + sigma / weight
            e = thermo(run)[0][1]
            # Half the cells of each type; each adds its quadratic form's
            # constant KP P0^2 (pe is the written energy).
            constant = 0.5 * KP * P01 ** 2 + 0.5 * KP * P02 ** 2
            self.assertAlmostEqual(e, hex_energy_per_cell(2 * KA, 1.0, G, lam1, lam2, lam12,
                                                          weight) + constant, delta=1e-12)
            # the log's matrix shows the effective value
            self.assertRegex(run.stdout, r"\n\s+1\s+%.4g\s+%.4g\n" % (lam1, lam12))

    def test_same_type_refused(self):
        run = self.run_lmp(two_type_tissue() + """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
pair_coeff 1 1 quadratic 0.3
""", ok=False)
        self.assertLammpsError(run, "pair_coeff 1 1", "different types")


class Restart(LammpsTestCase):
    """Every setting and coefficient, non-default, survives a restart file."""

    WRITE = two_type_tissue() + """
pair_style vertex/voronoi 2.5 tension cell incremental check grow no reference 3
pair_coeff 1 1 1.0 1.0 0.1 -0.5
pair_coeff 2 2 quadratic 0.6 1.0 0.05 3.2
pair_coeff 1 2 quadratic 0.3
run 0
write_restart r.restart
"""

    READ = """
read_restart {restart}
compute p all pair vertex/voronoi
thermo_style custom step pe c_p[7]
thermo_modify format float %.15g norm no
thermo 3
run 3
"""

    def check_run(self, nprocs):
        first = self.run_lmp(self.WRITE, nprocs=nprocs)
        run = self.run_lmp(self.READ.format(restart=first.path("r.restart")), nprocs=nprocs)
        settings = [l for r in (first, run) for l in r.stdout.splitlines()
                    if l.startswith("pair_style vertex/voronoi: cutoff")]
        self.assertGreaterEqual(len(settings), 2)
        self.assertEqual(len(set(settings)), 1)
        self.assertIn("cutoff 2.5 tension cell incremental check grow no reference 3", settings[-1])
        table = lambda r: r.stdout[r.stdout.index("  junction energy"):].split("Setting up")[0]
        self.assertEqual(table(first), table(run))
        # the energy after read_restart: tension cell, quadratic type 2, sigma
        rows = thermo(run)
        n = 36
        G2, lam2 = 0.1, -0.1 * 3.2
        lam12 = 0.5 * (-0.5 + lam2) + 0.3 / 2.0
        # type 1 and 2 differ in Gamma here: per cell 0.5 * (G1 + G2) / 2 P^2
        e = (0.25 * (0.1 + G2) * P * P + 2.0 * L * (0.5 * -0.5 + 0.5 * lam2 + 2.0 * lam12)) * n
        # Type 2 was given in the quadratic form (KP 0.05, P0 3.2): its half of
        # the cells adds the constant KP P0^2 each, which the restart keeps.
        e += 0.5 * n * 0.05 * 3.2 ** 2
        pe = [float(l.split()[1]) for l in run.stdout.splitlines()
              if re.match(r"^\s+3\s", l) and len(l.split()) == 3]
        self.assertTrue(pe, run.stdout)
        self.assertAlmostEqual(pe[-1], e, delta=1e-10)
        # reference 3: one reference triangulation per rank each at steps 0 and 3
        ref = float([l for l in run.stdout.splitlines()
                     if re.match(r"^\s+3\s", l) and len(l.split()) == 3][-1].split()[2])
        self.assertEqual(ref, 2.0 * nprocs)

    def test_settings(self):
        self.check_run(1)

    @nprocs(2)
    def test_settings_two_ranks(self):
        self.check_run(2)

    def test_adapted_values_written(self):
        # fix adapt ... reset no leaves A0 = 1.3 and Lambda_12 = 0.2; the
        # restart file carries them
        first = self.run_lmp(two_type_tissue() + """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
variable a equal 1.3
variable l equal 0.2
fix a all adapt 1 pair vertex/voronoi area0 * * v_a pair vertex/voronoi lambda 1 2 v_l reset no
run 1
unfix a
write_restart r.restart
""")
        run = self.run_lmp("""
read_restart %s
thermo_style custom step pe
thermo_modify format float %%.15g
run 0
""" % first.path("r.restart"))
        self.assertAlmostEqual(thermo(run)[0][1],
                               hex_energy_per_cell(1.0, 1.3, 0.1, -0.5, -0.5, 0.2), delta=1e-12)

    def test_grow_no_holds(self):
        # grow no after read_restart: a hole needs a wider shell, the run stops
        script = lmptest.tissue(12, 6) + """
region hole sphere 0.3 0.4 0 2.2 units box
delete_atoms region hole
pair_style vertex/voronoi 1.6 grow no
pair_coeff * * 1 1 0.1 -0.5
write_restart r.restart
"""
        first = self.run_lmp(script)
        run = self.run_lmp("read_restart %s\nrun 0\n" % first.path("r.restart"), ok=False)
        self.assertLammpsError(run, "is too small for this configuration")


class RepeatedPairStyle(LammpsTestCase):
    """A repeated pair_style line starts from the defaults: keywords of the
    earlier line that the new one does not give are gone (LAMMPS calls
    settings() again on the same style object)."""

    def test_keywords_reset(self):
        run = self.run_lmp(two_type_tissue() + """
pair_style vertex/voronoi 3.0 tension cell incremental no grow no reference 2 radius 0.5
pair_coeff * * 1.0 1.0 0.1 -0.5
thermo_style custom step pe
thermo_modify format float %.15g
run 0
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
run 0
""")
        settings = [l for l in run.stdout.splitlines() if l.startswith("pair_style vertex/voronoi: cutoff")]
        self.assertEqual(len(settings), 2, run.stdout)
        self.assertIn("radius 0.5 (finite cells)", settings[0])
        self.assertIn("cutoff 3 tension edge incremental yes grow yes reference 0", settings[1])
        rows = thermo(run)
        # the second run: confluent hexagons of area 1, tension edge
        self.assertAlmostEqual(rows[-1][1], hex_energy_per_cell(1.0, 1.0, 0.1, -0.5, -0.5, -0.5),
                               delta=1e-12)
        # the first: discs of radius 0.5 cut the hexagons (circumradius 0.62), another energy
        self.assertGreater(abs(rows[0][1] - rows[-1][1]), 1e-3)


if __name__ == "__main__":
    lmptest.main()
