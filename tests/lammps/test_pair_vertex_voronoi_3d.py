#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""pair_style vertex/voronoi and compute vertex/atom in 'dimension 3', against
independent results: LAMMPS's own compute voronoi/atom (voro++) for volumes,
surfaces and face counts, central differences of pe for forces and of pe under
box strain for the pressure, the BCC and FCC lattices' analytic cells, and 1,
2, 4 ranks from one data file."""

import math

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

# Two cell types (K, V0, Gamma, Lambda), a face tension between them.
TYPES = {1: (1.0, 1.0, 0.2, -1.6), 2: (1.4, 0.9, 0.3, -2.0)}
LAMBDA_12 = 0.3

S_BCC = (6 + 12 * math.sqrt(3)) / (8 * math.sqrt(2)) ** (2 / 3)    # truncated octahedron
S_FCC = 8 * math.sqrt(2) / (16 * math.sqrt(3) / 9) ** (2 / 3)     # rhombic dodecahedron


def tissue3d(n=5, disp=0.3, seed=4821, two_types=True, cutoff=3.0, lattice="sc", extra=""):
    """n^3 lattice cells (sc; bcc/fcc hold 2/4 cells each) of volume 1 per cell in a
    periodic box, displaced at random by up to disp, with two cell types."""
    coeffs = "pair_coeff * * %r %r %r %r\n" % TYPES[1]
    if two_types:
        coeffs += "pair_coeff 2 2 %r %r %r %r\npair_coeff 1 2 %r\n" % (TYPES[2] + (LAMBDA_12,))
    return f"""
units lj
atom_style atomic
boundary p p p
lattice {lattice} 1.0
region box block 0 {n} 0 {n} 0 {n}
create_box 2 box
create_atoms 1 box
mass * 1.0
{"set type 1 type/fraction 2 0.4 7731" if two_types else ""}
{f"displace_atoms all random {disp} {disp} {disp} {seed} units box" if disp else ""}
pair_style vertex/voronoi {cutoff}
{coeffs}
thermo_style custom step pe press pxx pyy pzz vol
thermo_modify norm no format float %.17g
{extra}
"""


def printed(run, key):
    return [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
            if line.startswith(key + " ")]


def from_data(data_script):
    """The same tissue read back from cfg.data (the same atom IDs on any
    number of ranks)."""
    return """
units lj
atom_style atomic
boundary p p p
read_data cfg.data
pair_style vertex/voronoi 3.0
pair_coeff * * %r %r %r %r
pair_coeff 2 2 %r %r %r %r
pair_coeff 1 2 %r
""" % (TYPES[1] + TYPES[2] + (LAMBDA_12,)) + data_script


class AgainstVoroPlusPlus(LammpsTestCase):
    """Volumes, surfaces and face counts equal LAMMPS's compute voronoi/atom
    (voro++, an independent Voronoi code); the energy per cell is the model's
    function of those; a jittered tissue on 1 and 2 ranks."""

    def check(self, n):
        make = self.run_lmp(tissue3d() + "write_data cfg.data\n")
        script = from_data("""
compute voro all voronoi/atom surface all
compute cells all vertex/atom
compute pe all pe/atom
dump d all custom 1 c.dump id type c_voro[1] c_voro[2] c_voro[3] c_cells[1] c_cells[2] c_cells[3] c_cells[4] c_cells[5] c_pe
dump_modify d sort id format float %.17g
run 0
""")
        run = self.run_lmp(script, nprocs=n, files={"cfg.data": make.text("cfg.data")})
        fr = run.dump("c.dump")[0]
        V, S = fr["c_voro[1]"], fr["c_voro[3]"]
        np.testing.assert_allclose(fr["c_cells[1]"], V, rtol=0, atol=1e-12)
        np.testing.assert_allclose(fr["c_cells[2]"], S, rtol=0, atol=1e-11)
        np.testing.assert_allclose(fr["c_cells[3]"], S / V ** (2 / 3), rtol=0, atol=1e-11)
        np.testing.assert_array_equal(fr["c_cells[4]"], fr["c_voro[2]"])
        self.assertAlmostEqual(V.sum(), 125.0, delta=1e-9)
        np.testing.assert_allclose(fr["c_cells[5]"], fr["c_pe"], rtol=0, atol=1e-12)
        if n == 1:
            # One cell type: E_i = K/2 (V-V0)^2 + Gamma/2 S^2 + Lambda S/2 from voro++'s V, S.
            one = self.run_lmp(tissue3d(two_types=False) + script.split("pair_coeff 1 2 %r\n" % LAMBDA_12)[1])
            f1 = one.dump("c.dump")[0]
            K, V0, G, L = TYPES[1]
            V, S = f1["c_voro[1]"], f1["c_voro[3]"]
            np.testing.assert_allclose(f1["c_pe"], K / 2 * (V - V0) ** 2 + G / 2 * S ** 2 + L * S / 2,
                                       rtol=0, atol=1e-11)

    def test_serial(self):
        self.check(1)

    @nprocs(2)
    def test_two_ranks(self):
        self.check(2)


class FiniteDifferences(LammpsTestCase):
    """Forces equal -dE/dx from central differences of pe (displace_atoms),
    with two cell types and face tensions, through periodic images."""

    def test_forces(self):
        h = 1e-6
        atoms = [1, 9, 33, 64, 125]
        script = tissue3d() + """
dump d all custom 1 cfg.dump id x y z fx fy fz
dump_modify d sort id format float %.17g
run 0
undump d
"""
        for a in atoms:
            script += f"group g{a} id {a}\n"
            for move in ((h, 0, 0), (0, h, 0), (0, 0, h)):
                plus = " ".join(repr(w) for w in move)
                minus = " ".join(repr(-2 * w) for w in move)
                script += f"""
displace_atoms g{a} move {plus} units box
run 0
print "E $(pe:%.17g)"
displace_atoms g{a} move {minus} units box
run 0
print "E $(pe:%.17g)"
displace_atoms g{a} move {plus} units box
"""
        run = self.run_lmp(script)
        frame = run.dump("cfg.dump")[0]
        e = [v[0] for v in printed(run, "E")]
        k = 0
        for a in atoms:
            row = np.where(frame["id"] == a)[0][0]
            for col in ("fx", "fy", "fz"):
                fd = -(e[k] - e[k + 1]) / (2 * h)
                k += 2
                self.assertAlmostEqual(frame[col][row], fd, delta=1e-6 * max(1.0, abs(fd)),
                                       msg=f"atom {a} {col}")


class Virial(LammpsTestCase):
    """pxx V, pyy V, pzz V equal -dE/d(strain) (central differences under
    change_box ... scale ... remap; no velocities, so no kinetic part)."""

    def test_normal_components(self):
        eps = 1e-6
        script = tissue3d() + 'run 0\nprint "P $(pxx:%.17g) $(pyy:%.17g) $(pzz:%.17g) $(vol:%.17g)"\n'
        for dim in ("x", "y", "z"):
            script += f"""
change_box all {dim} scale {1 + eps!r} remap
run 0
print "E $(pe:%.17g)"
change_box all {dim} scale {(1 - eps) / (1 + eps)!r} remap
run 0
print "E $(pe:%.17g)"
change_box all {dim} scale {1 / (1 - eps)!r} remap
"""
        run = self.run_lmp(script)
        p = printed(run, "P")[0]
        e = [v[0] for v in printed(run, "E")]
        for k in range(3):
            dE = (e[2 * k] - e[2 * k + 1]) / (2 * eps)
            self.assertAlmostEqual(-p[k] * p[3], dE, delta=1e-5 * max(1.0, abs(dE)))


class PerAtomVirial(LammpsTestCase):
    """compute stress/atom in 3D: the cells' virials add up to the global one
    (sum of stress/atom = -p V with zero velocities), on 1 and 2 ranks."""

    def check(self, nprocs):
        run = self.run_lmp(tissue3d() + """
compute s all stress/atom NULL virial
compute st all reduce sum c_s[1] c_s[2] c_s[3] c_s[4] c_s[5] c_s[6]
thermo_style custom step pxx pyy pzz pxy pxz pyz c_st[1] c_st[2] c_st[3] c_st[4] c_st[5] c_st[6] vol
thermo_modify norm no format float %.15g
run 0
""", nprocs=nprocs)
        row = [float(w) for w in run.stdout.split("Step")[1].splitlines()[1].split()]
        p, s, vol = row[1:7], row[7:13], row[13]
        for pk, sk in zip(p, s):
            self.assertAlmostEqual(sk, -pk * vol, delta=1e-9 * (1 + abs(pk * vol)))
        self.assertGreater(abs(s[0]), 1e-3)
        self.assertGreater(abs(s[3]), 1e-4)

    def test_serial(self):
        self.check(1)

    @nprocs(2)
    def test_two_ranks(self):
        self.check(2)


class Lattices(LammpsTestCase):
    """BCC: truncated octahedra (s = 5.3147, 14 faces); FCC: rhombic
    dodecahedra (s = 5.3454, 12 faces, one zero-area face per octahedral
    hole, i.e. per cell).  Analytic energy of the quadratic form, zero force."""

    def check(self, lattice, per_cell, s, faces, zero_faces_per_cell):
        KV, V0, KS, S0 = 1.3, 1.2, 0.7, 5.5
        n = 3
        script = tissue3d(n=n, disp=0, two_types=False, lattice=lattice).replace(
            "pair_coeff * * %r %r %r %r\n" % TYPES[1],
            f"pair_coeff * * quadratic {KV} {V0} {KS} {S0}\n") + """
compute cells all vertex/atom
compute tissue all vertex/tissue
thermo_style custom step pe c_tissue[1] c_tissue[2]
thermo_modify norm no
dump d all custom 1 c.dump id fx fy fz c_cells[1] c_cells[2] c_cells[3] c_cells[4]
dump_modify d sort id format float %.17g
run 0
print "R $(pe:%.17g) $(c_tissue[1]:%.17g) $(c_tissue[2]:%.17g)"
"""
        run = self.run_lmp(script)
        fr = run.dump("c.dump")[0]
        N = per_cell * n ** 3
        self.assertEqual(len(fr["id"]), N)
        V = 1.0    # 'lattice ... 1.0' in lj units: one cell per unit volume
        S = s * V ** (2 / 3)
        np.testing.assert_allclose(fr["c_cells[1]"], V, rtol=1e-12)
        np.testing.assert_allclose(fr["c_cells[3]"], s, rtol=1e-12)
        np.testing.assert_array_equal(fr["c_cells[4]"], faces)
        self.assertLess(np.abs(np.column_stack([fr["fx"], fr["fy"], fr["fz"]])).max(), 1e-10)
        pe, mean_s, zero = printed(run, "R")[0]
        # pe is the written energy, the constant KS S0^2 of the quadratic form included.
        expect = N * (KV * (V - V0) ** 2 + KS * (S - S0) ** 2)
        self.assertAlmostEqual(pe, expect, delta=1e-12 * abs(expect))
        self.assertAlmostEqual(mean_s, s, delta=1e-12)
        self.assertEqual(zero, zero_faces_per_cell * N)

    def test_bcc(self):
        self.assertAlmostEqual(S_BCC, 5.3147, delta=5e-5)
        self.check("bcc", 2, S_BCC, 14, 0)

    def test_fcc(self):
        self.assertAlmostEqual(S_FCC, 5.3454, delta=5e-5)
        self.check("fcc", 4, S_FCC, 12, 1)


class Velocities(LammpsTestCase):
    """Coordination over faces of non-zero area and orientation in 3D: all
    cells move along one direction except atom 1, which moves against it."""

    def test_one_reversed(self):
        run = self.run_lmp(tissue3d() + """
compute cells all vertex/atom
compute voro all voronoi/atom surface all
group one id 1
velocity all set 0.3 0.4 1.2
velocity one set -0.3 -0.4 -1.2
dump d all custom 1 c.dump id c_cells[4] c_cells[6] c_cells[7] c_voro[2]
dump_modify d sort id format float %.17g
compute vl all voronoi/atom neighbors yes
dump n all local 1 n.dump c_vl[1] c_vl[2] c_vl[3]
run 0
""")
        fr = run.dump("c.dump")[0]
        # voro++'s neighbours of atom 1 (local rows: atom, neighbour, area).
        rows = [line.split() for line in run.text("n.dump").split("ITEM: ENTRIES")[1].split("\n")[1:]
                if line.strip()]
        nb = {int(float(b)) for a, b, area in rows if int(float(a)) == 1 and float(area) > 0}
        self.assertGreater(len(nb), 6)
        for k, i in enumerate(fr["id"]):
            nf = fr["c_voro[2]"][k]
            self.assertEqual(fr["c_cells[4]"][k], nf)
            if i == 1:
                expect_c, expect_o = -1.0, math.acos(-0.3 / 1.3)
            else:
                expect_c = (nf - 2) / nf if i in nb else 1.0
                expect_o = math.acos(0.3 / 1.3)
            self.assertAlmostEqual(fr["c_cells[6]"][k], expect_c, delta=1e-12, msg=f"atom {i}")
            self.assertAlmostEqual(fr["c_cells[7]"][k], expect_o, delta=1e-12, msg=f"atom {i}")


class NeighbourExchanges(LammpsTestCase):
    """Global element 3 in 3D: pairs of cells sharing a face of non-zero area
    now but not at the previous computation, against voro++'s face lists of
    the two configurations (by atom IDs)."""

    def test_against_voro(self):
        run = self.run_lmp(tissue3d(disp=0.05, two_types=False) + """
compute cells all vertex/atom
compute tissue all vertex/tissue
compute vl all voronoi/atom neighbors yes
thermo_style custom step pe c_tissue[3]
dump n all local 1 n.dump c_vl[1] c_vl[2] c_vl[3]
run 0
displace_atoms all random 0.25 0.25 0.25 991 units box
undump n
dump n2 all local 1 n2.dump c_vl[1] c_vl[2] c_vl[3]
run 0
print "X $(c_tissue[3])"
""")
        text = run.text("n.dump") + run.text("n2.dump")
        pairs = []
        for block in text.split("ITEM: TIMESTEP")[1:]:
            rows = block.split("ITEM: ENTRIES")[1].strip().split("\n")[1:]
            now = set()
            for line in rows:
                a, b, area = line.split()
                if float(area) > 1e-9:
                    now.add(tuple(sorted((int(float(a)), int(float(b))))))
            pairs.append(now)
        self.assertEqual(len(pairs), 2)
        new = len(pairs[1] - pairs[0])
        self.assertGreater(new, 5)
        self.assertEqual(printed(run, "X")[0][0], new)


class Ranks(LammpsTestCase):
    """Forces and energy do not depend on the number of ranks (same data file)."""

    @nprocs(2)
    def test_forces_1_vs_2_vs_4(self):
        make = self.run_lmp(tissue3d() + "write_data cfg.data\n")
        script = from_data("""
dump d all custom 1 f.dump id fx fy fz
dump_modify d sort id format float %.17g
run 0
print "E $(pe:%.17g)"
""")
        forces, energies = [], []
        for n in (1, 2, 4):
            run = self.run_lmp(script, nprocs=n, files={"cfg.data": make.text("cfg.data")})
            fr = run.dump("f.dump")[0]
            forces.append(np.column_stack([fr["fx"], fr["fy"], fr["fz"]]))
            energies.append(printed(run, "E")[0][0])
        for f, e in zip(forces[1:], energies[1:]):
            np.testing.assert_allclose(f, forces[0], rtol=0, atol=1e-11)
            self.assertAlmostEqual(e, energies[0], delta=1e-10 * abs(energies[0]))


class EmptyRank(LammpsTestCase):
    """A rank that owns no atom: the cells fill the empty slab, and 4 ranks
    (one of them empty) give the energy and forces of 1 rank."""

    @nprocs(2)
    def test_empty_rank(self):
        make = self.run_lmp(tissue3d(n=4).replace("region box block 0 4 0 4 0 4",
                                                  "region box block 0 4 0 4 0 4\nregion fill block 0.5 2.5 0 4 0 4")
                            .replace("create_atoms 1 box", "create_atoms 1 region fill")
                            + "write_data cfg.data\n")
        script = from_data("""
dump d all custom 1 f.dump id fx fy fz
dump_modify d sort id format float %.17g
run 0
print "E $(pe:%.17g) $(count(all))"
""")
        one = self.run_lmp(script, files={"cfg.data": make.text("cfg.data")})
        four = self.run_lmp(script.replace("read_data cfg.data", "processors 4 1 1\nread_data cfg.data"),
                            nprocs=4, files={"cfg.data": make.text("cfg.data")})
        self.assertEqual(printed(one, "E")[0][1], 32)
        self.assertRegex(four.output, r"Nlocal:.* 0 min")    # a rank with no atoms
        self.assertAlmostEqual(printed(four, "E")[0][0], printed(one, "E")[0][0],
                               delta=1e-10 * abs(printed(one, "E")[0][0]))
        f1, f4 = one.dump("f.dump")[0], four.dump("f.dump")[0]
        for c in ("fx", "fy", "fz"):
            np.testing.assert_allclose(f4[c], f1[c], rtol=0, atol=1e-11)


class Dynamics(LammpsTestCase):
    """Minimisation lowers the energy to a force-free state; the ghost shell
    grows from a cutoff that is too small."""

    def test_minimize(self):
        run = self.run_lmp(tissue3d(n=4) + """
run 0
print "E0 $(pe:%.17g)"
min_style fire
minimize 0 1e-8 2000 20000
print "E1 $(pe:%.17g) $(fnorm:%.17g)"
""")
        e0 = printed(run, "E0")[0][0]
        e1, fnorm = printed(run, "E1")[0]
        self.assertLess(e1, e0 - 1.0)
        self.assertLess(fnorm, 1e-6)

    def test_grow(self):
        run = self.run_lmp(tissue3d(cutoff=0.8) + "run 0\n")
        self.assertIn("cutoff grown from 0.8", run.output)

    def test_grow_no(self):
        run = self.run_lmp(tissue3d(cutoff=0.8).replace("vertex/voronoi 0.8", "vertex/voronoi 0.8 grow no")
                           + "run 0\n", ok=False)
        self.assertLammpsError(run, "too small")


def triclinic(script, tilt="1 -0.5 0.7"):
    """The tissue of tissue3d() (n = 5) in a box tilted by xy xz yz."""
    return script.replace("region box block 0 5 0 5 0 5", "region box prism 0 5 0 5 0 5 " + tilt)


class Triclinic(LammpsTestCase):
    """A tilted (triclinic) 3D box: volumes, surfaces and face counts equal
    voro++'s; forces equal central differences; the shear pressures equal
    -dE/d(shear)/V; 1 rank == 2 ranks."""

    def against_voro(self, n):
        run = self.run_lmp(triclinic(tissue3d()) + """
compute voro all voronoi/atom surface all
compute cells all vertex/atom
dump d all custom 1 c.dump id c_voro[1] c_voro[2] c_voro[3] c_cells[1] c_cells[2] c_cells[4]
dump_modify d sort id format float %.17g
run 0
""", nprocs=n)
        fr = run.dump("c.dump")[0]
        np.testing.assert_allclose(fr["c_cells[1]"], fr["c_voro[1]"], rtol=0, atol=1e-11)
        np.testing.assert_allclose(fr["c_cells[2]"], fr["c_voro[3]"], rtol=0, atol=1e-10)
        np.testing.assert_array_equal(fr["c_cells[4]"], fr["c_voro[2]"])
        self.assertAlmostEqual(fr["c_cells[1]"].sum(), 125.0, delta=1e-9)

    def test_against_voro(self):
        self.against_voro(1)

    @nprocs(2)
    def test_against_voro_two_ranks(self):
        self.against_voro(2)

    def test_forces(self):
        h = 1e-6
        atoms = [2, 40, 77, 125]
        script = triclinic(tissue3d()) + """
dump d all custom 1 cfg.dump id fx fy fz
dump_modify d sort id format float %.17g
run 0
undump d
"""
        for a in atoms:
            script += f"group g{a} id {a}\n"
            for move in ((h, 0, 0), (0, h, 0), (0, 0, h)):
                plus = " ".join(repr(w) for w in move)
                minus = " ".join(repr(-2 * w) for w in move)
                script += f"""
displace_atoms g{a} move {plus} units box
run 0
print "E $(pe:%.17g)"
displace_atoms g{a} move {minus} units box
run 0
print "E $(pe:%.17g)"
displace_atoms g{a} move {plus} units box
"""
        run = self.run_lmp(script)
        frame = run.dump("cfg.dump")[0]
        e = [v[0] for v in printed(run, "E")]
        k = 0
        for a in atoms:
            row = np.where(frame["id"] == a)[0][0]
            for col in ("fx", "fy", "fz"):
                fd = -(e[k] - e[k + 1]) / (2 * h)
                k += 2
                self.assertAlmostEqual(frame[col][row], fd, delta=1e-6 * max(1.0, abs(fd)),
                                       msg=f"atom {a} {col}")

    def test_shear_pressure(self):
        # change_box ... xz delta d remap: x += d lamda_z = d (z - zlo)/lz, so
        # dE/dd = -pxz V / lz, likewise yz; xy: x += d lamda_y with
        # lamda_y = (y - ylo - yz lamda_z)/ly, so dE/dd = -(pxy - yz/lz pxz) V / ly.
        d = 1e-6
        script = triclinic(tissue3d()) + """
run 0
print "P $(pxy:%.17g) $(pxz:%.17g) $(pyz:%.17g) $(vol:%.17g) $(ly:%.17g) $(lz:%.17g) $(yz:%.17g)"
"""
        for tilt in ("xy", "xz", "yz"):
            script += f"""
change_box all {tilt} delta {d!r} remap units box
run 0
print "E $(pe:%.17g)"
change_box all {tilt} delta {-2 * d!r} remap units box
run 0
print "E $(pe:%.17g)"
change_box all {tilt} delta {d!r} remap units box
"""
        run = self.run_lmp(script)
        pxy, pxz, pyz, vol, ly, lz, yz = printed(run, "P")[0]
        self.assertNotEqual(yz, 0.0)
        e = [v[0] for v in printed(run, "E")]
        for k, (p, l) in enumerate(((pxy - yz / lz * pxz, ly), (pxz, lz), (pyz, lz))):
            dE = (e[2 * k] - e[2 * k + 1]) / (2 * d)
            self.assertAlmostEqual(-p * vol / l, dE, delta=1e-5 * max(1.0, abs(dE)), msg=f"component {k}")
        self.assertGreater(abs(pxy), 1e-4)

    @nprocs(2)
    def test_ranks(self):
        make = self.run_lmp(triclinic(tissue3d()) + "write_data cfg.data\n")
        script = from_data("""
dump d all custom 1 f.dump id fx fy fz
dump_modify d sort id format float %.17g
run 0
""")
        res = []
        for n in (1, 2):
            fr = self.run_lmp(script, nprocs=n, files={"cfg.data": make.text("cfg.data")}).dump("f.dump")[0]
            res.append(np.column_stack([fr["fx"], fr["fy"], fr["fz"]]))
        np.testing.assert_allclose(res[1], res[0], rtol=0, atol=1e-11)


class Restart(LammpsTestCase):
    """A restart file carries the 3D settings: the same energy and forces
    after read_restart, without pair_coeff."""

    def test_restart(self):
        dump = """
dump d all custom 1 f.dump id fx fy fz
dump_modify d sort id format float %.17g
run 0
print "E $(pe:%.17g)"
"""
        first = self.run_lmp(tissue3d() + "write_restart cfg.restart\n" + dump)
        again = self.run_lmp("read_restart %s\nthermo_modify norm no\n" % first.path("cfg.restart")
                             + dump)
        e0, e1 = printed(first, "E")[0][0], printed(again, "E")[0][0]
        self.assertAlmostEqual(e0, e1, delta=1e-12 * abs(e0))
        f0, f1 = first.dump("f.dump")[0], again.dump("f.dump")[0]
        for c in ("fx", "fy", "fz"):
            np.testing.assert_allclose(f1[c], f0[c], rtol=0, atol=1e-12)


class Adapt(LammpsTestCase):
    """fix adapt ... area0 changes the preferred volume V0 in 3D: unit cubes,
    E = N (K/2 (1 - V0)^2 + Gamma/2 36 + Lambda/2 6) at every step."""

    def test_adapt_v0(self):
        run = self.run_lmp(tissue3d(n=3, disp=0, two_types=False) + """
variable v0 equal 1.0+0.5*step
fix a all adapt 1 pair vertex/voronoi area0 * * v_v0
thermo 1
run 3
""")
        K, _, G, L = TYPES[1]
        rows = [line.split() for line in run.stdout.split("Step")[1].splitlines()[1:5]]
        for row in rows:
            step, pe = int(row[0]), float(row[1])
            v0 = 1.0 + 0.5 * step
            self.assertAlmostEqual(pe, 27 * (K / 2 * (1 - v0) ** 2 + G / 2 * 36 + L / 2 * 6),
                                   delta=1e-9, msg=f"step {step}")


class Errors(LammpsTestCase):
    def test_finite_cells_are_2d(self):
        # (per-cell V0, fix brownian/heun's 3d polarities and compute
        # vertex/local in 3d work: tests/lammps/test_feature_matrix.py)
        run = self.run_lmp(tissue3d().replace("vertex/voronoi 3.0", "vertex/voronoi 3.0 radius 0.8")
                           + "run 0\n", ok=False)
        self.assertLammpsError(run, "finite cells ('radius') are for 2d")

    def test_reference_times_in_3d(self):
        # 'reference N' times, every N steps, a rebuild (value 6) and a plain
        # CGAL Delaunay_triangulation_3 (value 8); value 7 counts them.
        run = self.run_lmp(tissue3d().replace("vertex/voronoi 3.0", "vertex/voronoi 3.0 reference 5")
                           + "compute pr all pair vertex/voronoi\n"
                           + "thermo_style custom step c_pr[6] c_pr[7] c_pr[8]\n"
                           + "thermo_modify norm no\nthermo 10\nrun 10\n")
        row = [l.split() for l in run.stdout.splitlines() if l.strip().startswith("10 ")][-1]
        self.assertEqual(float(row[2]), 3.0)    # steps 0, 5 and 10
        self.assertGreater(float(row[1]), 0.0)
        self.assertGreater(float(row[3]), 0.0)

    def test_non_periodic_z(self):
        run = self.run_lmp(tissue3d().replace("boundary p p p", "boundary p p f") + "run 0\n",
                           ok=False)
        self.assertLammpsError(run, "periodic x, y and z")


    def test_coincident_atoms_named(self):
        run = self.run_lmp(tissue3d(disp=0, two_types=False) +
                           "create_atoms 1 single 0 0 0 units box\nrun 0\n", ok=False)
        self.assertLammpsError(run, "same position", "id 1", "id 126")


lmptest.main()
