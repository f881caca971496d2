#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""pair_style vertex/voronoi ... radius r (finite Voronoi cells) through
tessera-lmp: closed-form energies of an isolated cell and of two touching
cells, forces against central differences of pe (open and periodic boxes
with holes, 1 and 2 ranks), the virial against box strain, the same forces
on 1, 2 and 4 ranks in open boxes (from one data file), restart, errors."""

import math
import os

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

R = 0.7
# quadratic KA A0 KP P0 free Lambda, per type; Lambda between the types.
QUAD = {1: (1.0, 1.2, 0.15, 3.5, 0.3), 2: (1.5, 1.0, 0.25, 3.0, -0.1)}
LAMBDA_12 = -0.2


def rng_cluster(seed, n, w, h, min_dist, hole=None):
    """n random points in [0, w) x [0, h) at least min_dist apart, none in the
    disc hole = (x, y, radius)."""
    rng = np.random.default_rng(seed)
    pts = []
    while len(pts) < n:
        p = rng.uniform((0, 0), (w, h))
        if hole and math.hypot(p[0] - hole[0], p[1] - hole[1]) < hole[2]:
            continue
        if all(math.hypot(*(p - q)) >= min_dist for q in pts):
            pts.append(p)
    return np.array(pts)


def data_file(xy, types, box, tilt=None):
    """A LAMMPS data file (atom_style atomic) with these atoms; box =
    (xlo, xhi, ylo, yhi), triclinic with xy = tilt if given."""
    lines = ["finite-cell test configuration", "", "%d atoms" % len(xy), "2 atom types", "",
             "%r %r xlo xhi" % box[:2], "%r %r ylo yhi" % box[2:], "-0.5 0.5 zlo zhi"]
    if tilt is not None:
        lines.append("%r 0.0 0.0 xy xz yz" % tilt)
    lines += ["",
             "Masses", "", "1 1.0", "2 1.0", "", "Atoms # atomic", ""]
    for i, ((x, y), t) in enumerate(zip(xy, types)):
        lines.append("%d %d %r %r 0.0" % (i + 1, t, x, y))
    return "\n".join(lines) + "\n"


def script(boundary, two_types=True, cutoff=None, extra="", coeffs=None, style=""):
    cutoff = cutoff or 2 * R + 0.1
    if coeffs:
        two_types = False
    else:
        coeffs = "pair_coeff * * quadratic %g %g %g %g free %g\n" % QUAD[1]
    if two_types:
        coeffs += "pair_coeff 2 2 quadratic %g %g %g %g free %g\npair_coeff 1 2 %g\n" % (
            QUAD[2] + (LAMBDA_12,))
    return f"""
dimension 2
units lj
atom_style atomic
boundary {boundary}
read_data cells.data
pair_style vertex/voronoi {cutoff} radius {R} {style}
{coeffs}
thermo_style custom step pe pxx pyy
thermo_modify norm no format float %.17g
{extra}
"""


def energies(run):
    return [float(line.split()[1]) for line in run.stdout.splitlines() if line.startswith("E ")]


def fd_script(atoms, h):
    """Prints pe with each of `atoms` moved by +-h along x and y."""
    s = """
dump d all custom 1 cfg.dump id type x y fx fy
dump_modify d sort id format float %.17g
run 0
undump d
"""
    for a in atoms:
        for dim, move, back in (("x", f"{h} 0 0", f"{-2 * h} 0 0"), ("y", f"0 {h} 0", f"0 {-2 * h} 0")):
            s += f"""
group g{a}{dim} id {a}
displace_atoms g{a}{dim} move {move} units box
run 0
print "E $(pe:%.17g)"
displace_atoms g{a}{dim} move {back} units box
run 0
print "E $(pe:%.17g)"
displace_atoms g{a}{dim} move {move} units box
"""
    return s


def quad_cell(t, A, P, L):
    KA, A0, KP, P0, lam = QUAD[t]
    # The written energy, the constant KP P0^2 included (pe is this sum).
    return KA * (A - A0) ** 2 + KP * (P - P0) ** 2 + lam * L


class Analytic(LammpsTestCase):
    """An isolated cell is a disc; two cells at distance d < 2r lose a cap
    each: pe and compute vertex/atom's area, perimeter and free length equal
    the closed forms."""

    def check(self, nprocs):
        d = 1.1
        xy = [(0.0, 0.0), (5.0, 0.3), (5.0 + d * 0.6, 0.3 + d * 0.8)]
        run = self.run_lmp(script("s s p", two_types=False, extra="""
compute c all vertex/atom
compute t all vertex/tissue
dump d all custom 1 cells.dump id c_c[1] c_c[2] c_c[8] c_c[9]
dump_modify d sort id format float %.17g
thermo_style custom step pe c_t[4] c_t[5]
thermo_modify norm no format float %.17g
run 0
print "E $(pe:%.17g)"
"""), nprocs=nprocs, files={"cells.data": data_file(xy, [1, 1, 1], (-1, 8, -1, 3))})
        ca = d / (2 * R)
        alpha = math.acos(ca)
        sa = math.sqrt(1 - ca * ca)
        A2 = R * R * (math.pi - alpha + sa * ca)
        L2 = 2 * R * (math.pi - alpha)
        P2 = L2 + 2 * R * sa
        A1, P1 = math.pi * R * R, 2 * math.pi * R
        expected = quad_cell(1, A1, P1, P1) + 2 * quad_cell(1, A2, P2, L2)
        self.assertAlmostEqual(energies(run)[0], expected, delta=1e-12 * abs(expected))
        f = run.dump("cells.dump")[0]
        for col, values in (("c_c[1]", (A1, A2, A2)), ("c_c[2]", (P1, P2, P2)),
                            ("c_c[8]", (P1, L2, L2)), ("c_c[9]", (1, 1, 1))):
            for got, want in zip(f[col], values):
                self.assertAlmostEqual(got, want, delta=1e-12)
        g = run.stdout.split("Step")[1].splitlines()[1].split()[2:]
        self.assertEqual(float(g[0]), 3)
        self.assertAlmostEqual(float(g[1]), P1 + 2 * L2, delta=1e-12)

    def test_disc_and_pair(self):
        self.check(1)

    @nprocs(2)
    def test_disc_and_pair_2_ranks(self):
        self.check(2)


class FiniteDifferences(LammpsTestCase):
    """Forces equal -dpe/dx by central differences in an open box and in a
    periodic box with a hole, on 1 and 2 ranks."""

    def check(self, boundary, nprocs, tilt=None, **kw):
        if boundary == "p p p":
            xy = rng_cluster(3, 26, 6.0, 5.0, 0.55, hole=(3.0, 2.5, 1.4))
            box = (0.0, 6.0, 0.0, 5.0)
            if tilt is not None:    # the same cells, sheared into the tilted box
                xy = xy + np.outer(xy[:, 1] / 5.0, (tilt, 0.0))
        else:
            xy = rng_cluster(4, 24, 5.0, 4.0, 0.5)
            box = (-1.0, 6.0, -1.0, 5.0)
        types = [1 + (i % 3 == 0) for i in range(len(xy))]
        atoms = [1, 4, 9, 14, 20]
        h = 1e-6
        run = self.run_lmp(script(boundary, **kw) + fd_script(atoms, h), nprocs=nprocs,
                           files={"cells.data": data_file(xy, types, box, tilt)})
        frame = run.dump("cfg.dump")[0]
        e = energies(run)
        k = 0
        for a in atoms:
            row = np.where(frame["id"] == a)[0][0]
            for col in ("fx", "fy"):
                fd = -(e[k] - e[k + 1]) / (2 * h)
                k += 2
                self.assertAlmostEqual(frame[col][row], fd, delta=1e-6 * max(1.0, abs(fd)),
                                       msg=f"{boundary} atom {a} {col}")
        self.assertGreater(np.abs(frame["fx"]).max(), 1e-3)

    def test_open(self):
        self.check("s s p", 1)

    def test_edge_form_tension_cell(self):
        # K A0 Gamma Lambda free F per type, Lambda_12 between types, tension cell
        self.check("s s p", 1, style="tension cell",
                   coeffs="pair_coeff 1 1 1.0 1.1 0.2 -0.3 free 0.4\n"
                          "pair_coeff 2 2 1.3 0.9 0.3 -0.5 free -0.2\npair_coeff 1 2 0.15\n")

    @nprocs(2)
    def test_open_2_ranks(self):
        self.check("f f p", 2)

    def test_periodic_hole(self):
        self.check("p p p", 1)

    @nprocs(2)
    def test_periodic_hole_2_ranks(self):
        self.check("p p p", 2)

    @nprocs(2)
    def test_triclinic_hole_2_ranks(self):
        self.check("p p p", 2, tilt=1.7)


class Virial(LammpsTestCase):
    """pxx A and pyy A equal -dE/d(strain) in a periodic box with a hole."""

    def test_normal_components(self):
        eps = 1e-6
        xy = rng_cluster(8, 26, 6.0, 5.0, 0.55, hole=(3.0, 2.5, 1.4))
        s = script("p p p") + "run 0\n" + 'print "P $(pxx:%.17g) $(pyy:%.17g) $(lx*ly:%.17g)"\n'
        for dim in ("x", "y"):
            s += f"""
change_box all {dim} scale {1 + eps} remap
run 0
print "E $(pe:%.17g)"
change_box all {dim} scale {(1 - eps) / (1 + eps)!r} remap
run 0
print "E $(pe:%.17g)"
change_box all {dim} scale {1 / (1 - eps)!r} remap
"""
        run = self.run_lmp(s, files={"cells.data": data_file(xy, [1] * len(xy), (0, 6, 0, 5))})
        p = [line.split()[1:] for line in run.stdout.splitlines() if line.startswith("P ")][0]
        pxx, pyy, area = (float(w) for w in p)
        e = energies(run)
        for k, pkk in enumerate((pxx, pyy)):
            dE = (e[2 * k] - e[2 * k + 1]) / (2 * eps)
            self.assertAlmostEqual(-pkk * area, dE, delta=1e-5 * max(1.0, abs(dE)))
            self.assertGreater(abs(dE), 1e-3)


class PerAtom(LammpsTestCase):
    """compute stress/atom and pe/atom add up to the global virial and pe in a
    periodic box with a hole and in an open box, on 1 and 2 ranks."""

    def check(self, boundary, nprocs):
        xy = rng_cluster(8, 26, 6.0, 5.0, 0.55, hole=(3.0, 2.5, 1.4))
        run = self.run_lmp(script(boundary) + """
compute s all stress/atom NULL virial
compute st all reduce sum c_s[1] c_s[2] c_s[4]
compute e all pe/atom
compute es all reduce sum c_e
thermo_style custom step pe c_es pxx pyy pxy c_st[1] c_st[2] c_st[3] vol
thermo_modify norm no format float %.15g
run 0
""", nprocs=nprocs, files={"cells.data": data_file(xy, [1 + (i % 2) for i in range(len(xy))],
                                                   (0, 6, 0, 5))})
        row = [float(w) for w in run.stdout.split("Step")[1].splitlines()[1].split()]
        _, pe, es, pxx, pyy, pxy, sxx, syy, sxy, vol = row
        self.assertAlmostEqual(es, pe, delta=1e-10 * (1 + abs(pe)))
        for p, s in ((pxx, sxx), (pyy, syy), (pxy, sxy)):
            self.assertAlmostEqual(s, -p * vol, delta=1e-9 * (1 + abs(p * vol)))
        self.assertGreater(abs(sxx), 1e-3)

    def test_periodic_hole(self):
        self.check("p p p", 1)

    @nprocs(2)
    def test_periodic_hole_2_ranks(self):
        self.check("p p p", 2)

    @nprocs(2)
    def test_open_2_ranks(self):
        self.check("s s p", 2)


class Ranks(LammpsTestCase):
    """An open box (s s p) of a cluster: pe and forces on 1, 2 and 4 ranks
    agree, and a short overdamped run keeps every atom."""

    def run_on(self, n, boundary="s s p"):
        xy = rng_cluster(6, 40, 7.0, 6.0, 0.5)
        types = [1 + (i % 4 == 0) for i in range(len(xy))]
        run = self.run_lmp(script(boundary, extra="""
dump d all custom 1 cfg.dump id x y fx fy
dump_modify d sort id format float %.17g
run 0
undump d
fix move all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.01
run 50
print "E $(pe:%.17g) $(count(all))"
"""), nprocs=n, files={"cells.data": data_file(xy, types, (-1, 8, -1, 7))})
        return run.dump("cfg.dump")[0], energies(run)[0], run

    def test_1_2_4_ranks(self):
        f1, e1, r1 = self.run_on(1)
        self.assertGreater(np.abs(f1["fx"]).max(), 1e-3)
        for n in (2, 4):
            fn, en, rn = self.run_on(n)
            for col in ("fx", "fy"):
                np.testing.assert_allclose(fn[col], f1[col], atol=1e-10)
            self.assertAlmostEqual(en, e1, delta=1e-9 * max(1, abs(e1)))
            count = [line for line in rn.stdout.splitlines() if line.startswith("E ")][0]
            self.assertEqual(int(float(count.split()[2])), 40)

    test_1_2_4_ranks.nprocs = 4


class Restart(LammpsTestCase):
    """write_restart / read_restart keeps the radius and the free tensions."""

    def test_restart(self):
        xy = rng_cluster(9, 15, 4.0, 4.0, 0.5)
        types = [1 + (i % 2) for i in range(len(xy))]
        first = self.run_lmp(script("s s p") + """
run 0
print "E $(pe:%.17g)"
write_restart cells.restart
""", files={"cells.data": data_file(xy, types, (-1, 5, -1, 5))})
        second = self.run_lmp(f"""
read_restart {first.path("cells.restart")}
thermo_modify norm no
run 0
print "E $(pe:%.17g)"
""")
        self.assertAlmostEqual(energies(second)[0], energies(first)[0], delta=1e-12)


EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")


def example(name):
    with open(os.path.join(EXAMPLES, name, "in." + name)) as f:
        return f.read().replace("dump_modify", "#").replace("dump ", "# dump ")


class Examples(LammpsTestCase):
    """examples/wound: the hole closes (wound area below 2% of the start by
    t = 16); examples/colony on 4 ranks prints the 1-rank values."""

    def test_wound_closes(self):
        run = self.run_lmp(example("wound"), args=["-var", "tend", "16"])
        data = np.loadtxt(run.path("wound.dat"))
        self.assertGreater(data[0, 1], 14.0)
        self.assertLess(data[data[:, 0] >= 10.0, 1].min(), 0.02 * data[0, 1])

    def thermo(self, run):
        rows = run.stdout.split("Step")[1].split("Loop")[0].strip().splitlines()[1:]
        return np.array([[float(w) for w in r.split()] for r in rows])

    @nprocs(4)
    def test_colony_4_ranks(self):
        one = self.thermo(self.run_lmp(example("colony"), args=["-var", "tend", "10"]))
        four = self.thermo(self.run_lmp(example("colony"), nprocs=4, args=["-var", "tend", "10"]))
        np.testing.assert_allclose(four, one, rtol=1e-5)
        self.assertGreater(one[-1, 3], one[0, 3] + 10)    # the colony spread

    def test_micropattern_rotates_coherently(self):
        # examples/micropattern: 8 cells on an island, polarity aligned with
        # velocity, rotate together (mean |phi| well above that of the same
        # colony without the alignment), and fix wall/region keeps every
        # centre on the island.
        def rotation(jv):
            script = example("micropattern") + ('compute rad all reduce max v_rr\n'
                                                'thermo_style custom step c_rad\n'
                                                'run 0\nprint "R $(sqrt(c_rad):%.10g) ${R}"\n')
            run = self.run_lmp(script, args=["-var", "N", "8", "-var", "tend", "100", "-var", "JV", jv])
            data = np.loadtxt(run.path("rot.dat"))
            rmax, island = [float(w) for w in run.stdout.split("\nR ")[1].split()[:2]]
            self.assertLess(rmax, island)
            return np.abs(data[data[:, 0] > 20.0, 2]).mean()
        aligned, plain = rotation("1.0"), rotation("0.0")
        self.assertGreater(aligned, 0.7)
        self.assertLess(plain, 0.5)

class Errors(LammpsTestCase):
    def files(self):
        return {"cells.data": data_file([(0, 0), (1, 0)], [1, 1], (-1, 2, -1, 1))}

    def test_cutoff_below_2r(self):
        run = self.run_lmp(script("s s p", cutoff=1.0) + "run 0\n", ok=False, files=self.files())
        self.assertLammpsError(run, "smaller than twice the radius", "radius 0.7")

    def test_open_box_needs_radius(self):
        run = self.run_lmp(script("s s p").replace(f"radius {R}", "") + "run 0\n", ok=False,
                           files=self.files())
        self.assertLammpsError(run, "radius r")

    def test_bad_radius(self):
        run = self.run_lmp(script("s s p").replace(f"radius {R}", "radius -1") + "run 0\n",
                           ok=False, files=self.files())
        self.assertLammpsError(run, "radius must be > 0", "-1")

    def test_free_between_types(self):
        run = self.run_lmp(script("s s p") + "pair_coeff 1 2 0.1 free 0.2\nrun 0\n", ok=False,
                           files=self.files())
        self.assertLammpsError(run, "'free' is a per-type tension")


lmptest.main()
