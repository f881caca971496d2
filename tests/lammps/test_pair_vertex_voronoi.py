#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""pair_style vertex/voronoi through tessera-lmp, against independent results:
the core library's forces (tests/core_forces), central finite differences of
pe under displace_atoms and of pe under box strain (virial), the analytic
hexagonal-lattice energy, 1 rank == 2 ranks, minimizers, and the errors."""

import math
import os
import subprocess

import numpy as np

import lmptest
from lmptest import Config, LammpsTestCase, nprocs

HEX_PERIMETER = math.sqrt(8.0 * math.sqrt(3.0))     # regular hexagon of area 1

# Two cell types with different parameters, Lambda of both signs.
TYPES = {1: (1.0, 1.0, 0.12, -0.45), 2: (1.4, 0.9, 0.2, -0.6)}
LAMBDA_12 = 0.1


def hex_tissue(nx, ny, ntypes=1, tilt=None):
    return lmptest.tissue(nx, ny, "hex", ntypes, tilt)


def config_script(nx=8, ny=4, disp=0.25, seed=4821, two_types=True, tension="edge",
                  cutoff=3.5, extra="", tilt=None):
    """A displaced hexagonal lattice (area 1 per cell) in a periodic box;
    tilt (in lattice units: a whole number keeps the lattice periodic) makes
    it a triclinic box."""
    coeffs = "pair_coeff * * %g %g %g %g\n" % TYPES[1]
    if two_types:
        coeffs += "pair_coeff 2 2 %g %g %g %g\npair_coeff 1 2 %g\n" % (TYPES[2] + (LAMBDA_12,))
    return hex_tissue(nx, ny, 2, tilt) + f"""
{"set type 1 type/fraction 2 0.4 7731" if two_types else ""}
displace_atoms all random {disp} {disp} 0 {seed} units box
pair_style vertex/voronoi {cutoff} tension {tension}
{coeffs}
thermo_style custom step pe pxx pyy pxy
thermo_modify norm no format float %.17g
{extra}
"""


def core_forces(frame, tension="edge", box=None):
    """Energy, virial and forces from the core library for a dump frame;
    box = (xlo, xhi, ylo, yhi, xy), by default the frame's orthogonal box."""
    exe = os.path.join(Config.build, "tests", "core_forces")
    if box is None:
        b = frame["box"]
        box = (b[0, 0], b[0, 1], b[1, 0], b[1, 1], 0.0)
    lines = ["%r %r %r %r %r %d 2 %s" % (tuple(box) + (len(frame["id"]), tension))]
    for t in (1, 2):
        lines.append("%r %r %r" % TYPES[t][:3])
    lines.append("%r %r" % (TYPES[1][3], LAMBDA_12))
    lines.append("%r %r" % (LAMBDA_12, TYPES[2][3]))
    for x, y, t in zip(frame["x"], frame["y"], frame["type"]):
        lines.append("%r %r %d" % (x, y, int(t)))
    out = subprocess.run([exe], input="\n".join(lines) + "\n", capture_output=True, text=True,
                         check=True).stdout.split("\n")
    energy = float(out[0].split()[1])
    virial = [float(w) for w in out[1].split()[1:]]
    forces = np.array([[float(w) for w in line.split()] for line in out[2:] if line.strip()])
    return energy, virial, forces


def thermo_values(run, key="E"):
    """Values printed by 'print "<key> ..."' lines, in order."""
    return [float(line.split()[1]) for line in run.stdout.splitlines()
            if line.startswith(key + " ")]


class AgainstCore(LammpsTestCase):
    """LAMMPS forces and energy equal the core library's periodic result."""

    def check(self, tension, nprocs=1):
        run = self.run_lmp(config_script(tension=tension) + """
dump d all custom 1 cfg.dump id type x y fx fy
dump_modify d sort id format float %.17g
variable e equal pe
run 0
print "E $(pe:%.17g)"
""", nprocs=nprocs)
        frame = run.dump("cfg.dump")[0]
        energy, _, forces = core_forces(frame, tension)
        fl = np.column_stack([frame["fx"], frame["fy"]])
        scale = np.abs(forces).max()
        self.assertGreater(scale, 0.1)      # a configuration with real forces
        np.testing.assert_allclose(fl, forces, rtol=0, atol=1e-10 * scale)
        self.assertAlmostEqual(thermo_values(run)[0], energy, delta=1e-10 * abs(energy))

    def test_edge(self):
        self.check("edge")

    def test_cell(self):
        self.check("cell")

    @nprocs(2)
    def test_edge_2_ranks(self):
        self.check("edge", nprocs=2)


class FiniteDifferences(LammpsTestCase):
    """Forces equal -dE/dx from central differences of pe (displace_atoms)."""

    def test_forces(self):
        h = 1e-6
        atoms = [1, 7, 13, 22, 31]
        script = config_script() + """
dump d all custom 1 cfg.dump id type x y fx fy
dump_modify d sort id format float %.17g
run 0
undump d
"""
        for a in atoms:
            for dim, move in (("x", f"{h} 0 0"), ("y", f"0 {h} 0")):
                minus = " ".join("-%g" % (2 * float(w)) if float(w) else "0" for w in move.split())
                script += f"""
group g{a}{dim} id {a}
displace_atoms g{a}{dim} move {move} units box
run 0
print "E $(pe:%.17g)"
displace_atoms g{a}{dim} move {minus} units box
run 0
print "E $(pe:%.17g)"
displace_atoms g{a}{dim} move {move} units box
"""
        run = self.run_lmp(script)
        frame = run.dump("cfg.dump")[0]
        e = thermo_values(run)
        k = 0
        for a in atoms:
            row = np.where(frame["id"] == a)[0][0]
            for col in ("fx", "fy"):
                fd = -(e[k] - e[k + 1]) / (2 * h)
                k += 2
                self.assertAlmostEqual(frame[col][row], fd,
                                       delta=1e-6 * max(1.0, abs(fd)),
                                       msg=f"atom {a} {col}")


class Virial(LammpsTestCase):
    """pxx*A and pyy*A equal -dE/d(strain) from central differences under
    change_box ... scale ... remap (velocities are zero: no kinetic part)."""

    def test_normal_components(self):
        eps = 1e-6
        script = config_script() + "run 0\n"
        script += 'print "P $(pxx:%.17g) $(pyy:%.17g) $(lx*ly:%.17g)"\n'
        for dim in ("x", "y"):
            script += f"""
change_box all {dim} scale {1 + eps} remap
run 0
print "E $(pe:%.17g)"
change_box all {dim} scale {(1 - eps) / (1 + eps)!r} remap
run 0
print "E $(pe:%.17g)"
change_box all {dim} scale {1 / (1 - eps)!r} remap
"""
        run = self.run_lmp(script)
        p = [line.split()[1:] for line in run.stdout.splitlines() if line.startswith("P ")][0]
        pxx, pyy, area = (float(w) for w in p)
        e = thermo_values(run)
        for k, pkk in enumerate((pxx, pyy)):
            dE = (e[2 * k] - e[2 * k + 1]) / (2 * eps)
            self.assertAlmostEqual(-pkk * area, dE, delta=1e-5 * max(1.0, abs(dE)))


class PerAtomVirial(LammpsTestCase):
    """compute stress/atom: the cells' virials add up to the global one
    (sum of stress/atom = -p V with zero velocities), on 1 and 2 ranks."""

    def check(self, nprocs):
        run = self.run_lmp(config_script() + """
compute s all stress/atom NULL virial
compute st all reduce sum c_s[1] c_s[2] c_s[4]
thermo_style custom step pxx pyy pxy c_st[1] c_st[2] c_st[3] vol
thermo_modify norm no format float %.15g
run 0
""", nprocs=nprocs)
        row = [float(w) for w in run.stdout.split("Step")[1].splitlines()[1].split()]
        _, pxx, pyy, pxy, sxx, syy, sxy, vol = row
        area = vol    # LAMMPS's 2d volume is the area
        for p, s in ((pxx, sxx), (pyy, syy), (pxy, sxy)):
            self.assertAlmostEqual(s, -p * area, delta=1e-9 * (1 + abs(p * area)))
        self.assertGreater(abs(sxx), 1e-3)

    def test_serial(self):
        self.check(1)

    @nprocs(2)
    def test_two_ranks(self):
        self.check(2)


class Triclinic(LammpsTestCase):
    """A tilted (triclinic) box: forces and energy equal the core's for the
    same tilted box, on 1 and 2 ranks; the shear pressure is the derivative
    of the energy under change_box xy; fix deform xy shears a tissue."""

    BOXPRINT = 'print "BOX $(xlo:%.17g) $(xhi:%.17g) $(ylo:%.17g) $(yhi:%.17g) $(xy:%.17g)"\n'

    def check_core(self, nprocs):
        run = self.run_lmp(config_script(tilt=1) + """
dump d all custom 1 cfg.dump id type x y fx fy
dump_modify d sort id format float %.17g
run 0
print "E $(pe:%.17g)"
""" + self.BOXPRINT, nprocs=nprocs)
        box = [float(w) for w in [l for l in run.stdout.splitlines()
                                  if l.startswith("BOX ")][0].split()[1:]]
        self.assertGreater(box[4], 1.0)
        frame = run.dump("cfg.dump")[0]
        energy, _, forces = core_forces(frame, "edge", box)
        fl = np.column_stack([frame["fx"], frame["fy"]])
        np.testing.assert_allclose(fl, forces, rtol=0, atol=1e-10 * np.abs(forces).max())
        self.assertAlmostEqual(thermo_values(run)[0], energy, delta=1e-10 * abs(energy))

    def test_against_core(self):
        self.check_core(1)

    @nprocs(2)
    def test_against_core_two_ranks(self):
        self.check_core(2)

    def test_shear_pressure(self):
        # change_box xy delta h remap shears x -> x + (h / ly) (y - ylo):
        # dE/dh = -W_yx / ly = -pxy V / ly (zero velocities)
        h = 1e-6
        run = self.run_lmp(config_script(tilt=1) + "run 0\n" +
                           'print "P $(pxy:%.17g) $(vol:%.17g) $(ly:%.17g)"\n' + f"""
change_box all xy delta {h} remap units box
run 0
print "E $(pe:%.17g)"
change_box all xy delta {-2 * h} remap units box
run 0
print "E $(pe:%.17g)"
""")
        pxy, vol, ly = (float(w) for w in [l for l in run.stdout.splitlines()
                                           if l.startswith("P ")][0].split()[1:])
        e = thermo_values(run)
        dE = (e[0] - e[1]) / (2 * h)
        self.assertAlmostEqual(dE, -pxy * vol / ly, delta=1e-5 * max(1.0, abs(dE)))

    def test_deform_shear(self):
        run = self.run_lmp(config_script(tilt=0, two_types=False, disp=0.05) + """
timestep 0.01
fix m all brownian 1.0 1 gamma_t 1.0 rng none
fix d all deform 1 xy erate 0.05 remap x
run 300
print "S $(pxy:%.17g) $(xy:%.17g)"
""")
        pxy, xy = (float(w) for w in [l for l in run.stdout.splitlines()
                                      if l.startswith("S ")][0].split()[1:])
        self.assertGreater(xy, 0.1)
        self.assertNotEqual(pxy, 0.0)


class Hexagonal(LammpsTestCase):
    """Perfect hexagonal lattice with A0 = area per cell: zero force and the
    analytic energy, for both junction conventions."""

    def check(self, tension, weight):
        K, A0, G, L = 1.0, 1.0, 0.1, -0.5
        run = self.run_lmp(hex_tissue(10, 5) + f"""
pair_style vertex/voronoi 3.0 tension {tension}
pair_coeff * * {K} {A0} {G} {L}
compute fm all reduce max fx fy
compute fn all reduce min fx fy
thermo_style custom step pe c_fm[1] c_fm[2] c_fn[1] c_fn[2]
run 0
print "E $(pe:%.17g) $(c_fm[1]:%.17g) $(c_fm[2]:%.17g) $(c_fn[1]:%.17g) $(c_fn[2]:%.17g)"
""")
        line = [l for l in run.stdout.splitlines() if l.startswith("E ")][0].split()[1:]
        pe, fmax = float(line[0]), max(abs(float(w)) for w in line[1:])
        P = HEX_PERIMETER
        expected = 0.5 * G * P * P + weight * L * P     # per cell; pe is normalized
        self.assertAlmostEqual(pe, expected, delta=1e-12)
        self.assertLess(fmax, 1e-12)

    def test_edge(self):
        self.check("edge", 0.5)

    def test_cell(self):
        self.check("cell", 1.0)


class Ranks(LammpsTestCase):
    """Forces do not depend on the number of ranks (same data file)."""

    @nprocs(2)
    def test_forces_1_vs_2_vs_4(self):
        make = self.run_lmp(config_script(nx=12, ny=6) + "write_data cfg.data\n")
        data = make.text("cfg.data")
        script = """
dimension 2
units lj
atom_style dipole
boundary p p p
read_data cfg.data
pair_style vertex/voronoi 3.5
pair_coeff * * %g %g %g %g
pair_coeff 2 2 %g %g %g %g
pair_coeff 1 2 %g
dump d all custom 1 f.dump id fx fy
dump_modify d sort id format float %%.17g
run 0
""" % (TYPES[1] + TYPES[2] + (LAMBDA_12,))
        results = []
        for n in (1, 2, 4):
            run = self.run_lmp(script, nprocs=n, files={"cfg.data": data})
            fr = run.dump("f.dump")[0]
            results.append(np.column_stack([fr["fx"], fr["fy"]]))
        for r in results[1:]:
            np.testing.assert_allclose(r, results[0], rtol=0, atol=1e-12)


class Minimize(LammpsTestCase):
    """Energy minimization (CG and FIRE) relaxes a displaced solid to the
    hexagonal ground state: analytic energy, vanishing forces."""

    def check(self, style):
        K, A0, G, L = 1.0, 1.0, 0.18, -0.1       # thesis 5.1.1: p0 = 0.28, solid
        run = self.run_lmp(hex_tissue(6, 3) + f"""
displace_atoms all random 0.05 0.05 0 9117 units box
pair_style vertex/voronoi 3.0
pair_coeff * * {K} {A0} {G} {L}
timestep 0.01
min_style {style}
minimize 0 1e-10 20000 40000
print "E $(pe:%.17g) $(fnorm:%.17g)"
""")
        line = [l for l in run.stdout.splitlines() if l.startswith("E ")][0].split()[1:]
        P = HEX_PERIMETER
        self.assertAlmostEqual(float(line[0]), 0.5 * G * P * P + 0.5 * L * P, delta=1e-8)
        self.assertLess(float(line[1]), 1e-6)

    def test_cg(self):
        self.check("cg")

    def test_fire(self):
        self.check("fire")


class Deform(LammpsTestCase):
    """fix deform runs; stretching a relaxed solid raises its energy and
    its x pressure responds in the right direction."""

    def test_stretch(self):
        run = self.run_lmp(config_script(two_types=False, disp=0.02) + """
timestep 0.01
fix m all brownian 1.0 1 gamma_t 1.0 rng none
run 200
print "E0 $(pe:%.17g) $(pxx:%.17g)"
fix d all deform 1 x scale 1.1 remap x
run 200
print "E1 $(pe:%.17g) $(pxx:%.17g)"
""")
        e0, p0 = (float(w) for w in [l for l in run.stdout.splitlines()
                                     if l.startswith("E0 ")][0].split()[1:])
        e1, p1 = (float(w) for w in [l for l in run.stdout.splitlines()
                                     if l.startswith("E1 ")][0].split()[1:])
        self.assertGreater(e1, e0)
        self.assertLess(p1, p0)     # stretched cells pull back: tension, lower pressure


class Errors(LammpsTestCase):
    """Bad input stops with a message that names the problem."""

    BASE = hex_tissue(6, 3)

    def test_missing_pair_coeff(self):
        run = self.run_lmp(self.BASE + "pair_style vertex/voronoi 3.0\nrun 0\n", ok=False)
        self.assertLammpsError(run, "pair_coeff 1 1")

    def test_nonpositive_K(self):
        run = self.run_lmp(self.BASE + "pair_style vertex/voronoi 3.0\n"
                           "pair_coeff * * 0.0 1.0 0.1 -0.5\n", ok=False)
        self.assertLammpsError(run, "K must be > 0", "0.0")

    def test_nonpositive_A0(self):
        run = self.run_lmp(self.BASE + "pair_style vertex/voronoi 3.0\n"
                           "pair_coeff * * 1.0 -1 0.1 -0.5\n", ok=False)
        self.assertLammpsError(run, "A0 must be > 0")

    def test_bad_cutoff(self):
        run = self.run_lmp(self.BASE + "pair_style vertex/voronoi -2\n", ok=False)
        self.assertLammpsError(run, "cutoff must be > 0")

    def test_cutoff_too_small(self):
        run = self.run_lmp(self.BASE + "pair_style vertex/voronoi 0.6 grow no\n"
                           "pair_coeff * * 1 1 0.1 -0.5\nrun 0\n", ok=False)
        self.assertLammpsError(run, "vertex/voronoi", "cutoff")

    HOLE = """
region hole sphere 0.3 0.4 0 2.2 units box
delete_atoms region hole
"""

    def test_cutoff_too_small_names_needed_value(self):
        # A hole: the circumcircles around it need more than the cutoff.
        run = self.run_lmp(hex_tissue(12, 6) + self.HOLE + """
pair_style vertex/voronoi 1.6 grow no
pair_coeff * * 1 1 0.1 -0.5
run 0
""", ok=False)
        self.assertLammpsError(run, "too small", "use 'pair_style vertex/voronoi")

    def test_3d(self):
        # dimension 3 is the 3D model (test_pair_vertex_voronoi_3d.py): a
        # simple cubic lattice of unit cubes, E = N (Gamma/2 S^2 + Lambda S/2).
        run = self.run_lmp("""
units lj
atom_style dipole
boundary p p p
lattice sc 1.0
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
mass 1 1.0
pair_style vertex/voronoi 3.0
pair_coeff * * 1 1 0.1 -0.5
thermo_modify norm no format float %.17g
run 0
print "E $(pe:%.17g)"
""")
        self.assertAlmostEqual(thermo_values(run)[0], 64 * (0.05 * 36 - 0.25 * 6), delta=1e-10)

    def test_non_periodic(self):
        run = self.run_lmp(self.BASE.replace("boundary p p p", "boundary p f p") +
                           "pair_style vertex/voronoi 3.0\npair_coeff * * 1 1 0.1 -0.5\nrun 0\n",
                           ok=False)
        self.assertLammpsError(run, "periodic")

    def test_unknown_keyword(self):
        run = self.run_lmp(self.BASE + "pair_style vertex/voronoi 3.0 tensoin edge\n", ok=False)
        self.assertLammpsError(run, "unknown keyword 'tensoin'")

    def test_duplicate_atoms_named(self):
        run = self.run_lmp(self.BASE + """
create_atoms 1 single 0.0 0.0 0.0 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1 1 0.1 -0.5
run 0
""", ok=False)
        self.assertLammpsError(run, "same position", "id ")


class Grow(LammpsTestCase):
    """grow yes (the default): a ghost shell too thin for a cell is widened
    during the step, and the forces and energy are those of a run with a
    wide enough cutoff from the start."""

    SCRIPT = hex_tissue(12, 6) + Errors.HOLE + """
pair_style vertex/voronoi {cut}
pair_coeff * * 1 1 0.1 -0.5
thermo_modify norm no
dump d all custom 1 f.dump id fx fy
dump_modify d sort id format float %.17g
run 0
print "E $(pe:%.17g)"
"""

    def check(self, nprocs):
        wide = self.run_lmp(self.SCRIPT.format(cut=6.0), nprocs=nprocs)
        self.assertNotIn("cutoff grown", wide.stdout)
        grown = self.run_lmp(self.SCRIPT.format(cut=1.6), nprocs=nprocs)
        self.assertIn("cutoff grown from 1.6", grown.stdout)
        fw, fg = wide.dump("f.dump")[0], grown.dump("f.dump")[0]
        for col in ("fx", "fy"):
            np.testing.assert_allclose(fg[col], fw[col], rtol=0, atol=1e-10)
        self.assertAlmostEqual(thermo_values(grown)[0], thermo_values(wide)[0], delta=1e-9)

    def test_serial(self):
        self.check(1)

    @nprocs(2)
    def test_two_ranks(self):
        self.check(2)

    def test_far_too_small(self):
        # cells without a complete ring of neighbours: the shell doubles
        run = self.run_lmp(Errors.BASE + "pair_style vertex/voronoi 0.6\n"
                           "pair_coeff * * 1 1 0.1 -0.5\nrun 0\n")
        self.assertIn("cutoff grown from 0.6", run.stdout)

    def test_during_a_run(self):
        # the active example with a small cutoff: voids open during the run,
        # the shell grows, and the run still forms one stream
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                            "grooves", "in.grooves")
        with open(path) as f:
            script = f.read().replace("pair_style      vertex/voronoi 8.0",
                                      "pair_style      vertex/voronoi 3.0")
        script = "\n".join(l for l in script.splitlines() if not l.startswith("dump"))
        run = self.run_lmp(script + "\nprint \"P $(f_act[1]:%.6f)\"\n")
        self.assertIn("cutoff grown from 3", run.stdout)
        polar = [float(l.split()[1]) for l in run.stdout.splitlines() if l.startswith("P ")][0]
        self.assertGreater(polar, 0.99)


if __name__ == "__main__":
    lmptest.main()
