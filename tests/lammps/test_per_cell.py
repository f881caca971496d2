#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Per-cell parameters of pair_style vertex/voronoi: fix property/atom d_ka
d_kp d_perim0 (with d_area0), in the quadratic form's units.

* forces = central differences of pe with random per-cell values of two
  types, confluent, finite and 3d cells and cells on a sphere (along
  geodesics), on 1 and 2 ranks;
* pe of a one-type tissue equals sum_c d_ka (A - d_area0)^2 + d_kp (P -
  d_perim0)^2 written from compute vertex/atom's areas and perimeters (2d,
  3d, sphere), and the thesis form gets the same forces without the constant;
* per-atom values equal to the types' give the types' forces (1e-13; also
  on a sphere);
* restart files keep the values (fix property/atom defined again), and
  fix cell/divide's daughters keep their mother's;
* bad values stop with an error naming the atom;
* examples/heterogeneous runs (short) and cells of the larger p0 end up
  with the larger shape index."""

import math
import os
import re

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs
import test_sphere as sphere
from test_feature_matrix import COEFFS_2D, COEFFS_3D, COEFFS_FINITE, model_script

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "..", "examples", "heterogeneous")

# Per-cell values around the types' (2d: KA 1.0/1.2, KP 0.1/0.12, P0 3.7/3.8;
# 3d: KV 1.0/1.2, KS 0.05/0.06, S0 5.6/5.5), as atom-style variables.
PER_CELL_2D = """fix pc all property/atom d_ka d_kp d_perim0 d_area0
variable ka atom 0.8+0.1*(id%5)
variable kp atom 0.06+0.02*(id%4)
variable p0 atom 3.4+0.15*(id%6)
variable a0 atom 0.85+0.05*(id%7)
set atom * d_ka v_ka
set atom * d_kp v_kp
set atom * d_perim0 v_p0
set atom * d_area0 v_a0
"""
PER_CELL_3D = (PER_CELL_2D.replace("0.06+0.02*(id%4)", "0.03+0.01*(id%4)")
               .replace("3.4+0.15*(id%6)", "5.3+0.1*(id%6)"))


def per_cell(model):
    return PER_CELL_3D if model.startswith("3d") else PER_CELL_2D


def printed(run, key):
    return [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
            if line.startswith(key + " ")]


class PerCellForces(LammpsTestCase):

    def fd_script(self, model, atoms=(5, 17), h=1e-5):
        d = 3 if model.startswith("3d") else 2
        s = "thermo_style custom step pe\nthermo_modify norm no format float %.17g\nrun 0\n"
        for atom in atoms:
            s += f"group a{atom} id {atom}\nrun 0\n"
            s += f'print "F {atom} $(fx[{atom}]:%.17g) $(fy[{atom}]:%.17g) $(fz[{atom}]:%.17g)"\n'
            for k in range(d):
                v = ["0", "0", "0"]
                v[k] = repr(h)
                s += f"displace_atoms a{atom} move {' '.join(v)} units box\nrun 0\n"
                s += f'print "EP {atom} {k} $(pe:%.17g)"\n'
                v[k] = repr(-2 * h)
                s += f"displace_atoms a{atom} move {' '.join(v)} units box\nrun 0\n"
                s += f'print "EM {atom} {k} $(pe:%.17g)"\n'
                v[k] = repr(h)
                s += f"displace_atoms a{atom} move {' '.join(v)} units box\n"
        return s

    def check_fd(self, model, n):
        h = 1e-5
        run = self.run_lmp(model_script(model) + per_cell(model) + self.fd_script(model, h=h),
                           nprocs=n)
        self.assertIn("per-cell values (fix property/atom) replace the types': d_area0 d_ka "
                      "d_kp d_perim0", run.stdout)
        forces = {int(r[0]): r[1:] for r in printed(run, "F")}
        em = {(int(r[0]), int(r[1])): r[2] for r in printed(run, "EM")}
        scale = max(abs(x) for f in forces.values() for x in f)
        self.assertGreater(scale, 1e-2)
        checked = 0
        for r in printed(run, "EP"):
            atom, k = int(r[0]), int(r[1])
            fd = -(r[2] - em[(atom, k)]) / (2 * h)
            self.assertAlmostEqual(forces[atom][k], fd, delta=1e-6 * scale,
                                   msg=f"{model}, {n} ranks: atom {atom} component {k}")
            checked += 1
        self.assertEqual(checked, 2 * (3 if model.startswith("3d") else 2))

    def test_confluent_fd(self):
        self.check_fd("confluent", 1)

    @nprocs(2)
    def test_confluent_fd_2_ranks(self):
        self.check_fd("confluent", 2)

    def test_finite_fd(self):
        self.check_fd("finite_open", 1)

    @nprocs(2)
    def test_finite_fd_2_ranks(self):
        self.check_fd("finite_per", 2)

    def test_3d_fd(self):
        self.check_fd("3d", 1)

    @nprocs(2)
    def test_3d_fd_2_ranks(self):
        self.check_fd("3d", 2)


class PerCellEnergy(LammpsTestCase):
    """pe against the quadratic form written from the cells' measures."""

    def check_quadratic_pe(self, model, tension="edge"):
        three = model.startswith("3d")
        script = model_script(model)
        coeffs = COEFFS_3D if three else COEFFS_2D
        # one type, no heterotypic tension: pe = sum_c KA_c (A - A0_c)^2 + KP_c (P - P0_c)^2
        script = script.replace(coeffs, "pair_coeff * * quadratic 1.0 1.0 0.1 3.7\n")
        if tension == "cell":
            script = script.replace("pair_style vertex/voronoi 3.0",
                                    "pair_style vertex/voronoi 3.0 tension cell")
        script += per_cell(model) + """compute c all vertex/atom
thermo_style custom step pe
thermo_modify norm no format float %.17g
dump d all custom 1 cells.dump id c_c[1] c_c[2] c_c[5] d_ka d_kp d_perim0 d_area0
dump_modify d format float %.17g
run 0
print "E $(pe:%.17g)"
"""
        run = self.run_lmp(script)
        f = run.dump("cells.dump")[0]
        A, P = f["c_c[1]"], f["c_c[2]"]
        e = f["d_ka"] * (A - f["d_area0"]) ** 2 + f["d_kp"] * (P - f["d_perim0"]) ** 2
        pe = printed(run, "E")[0][0]
        self.assertAlmostEqual(pe, e.sum(), delta=1e-11 * abs(pe))
        # the cells' energies (compute vertex/atom, pe/atom) are the same per cell
        np.testing.assert_allclose(f["c_c[5]"], e, rtol=1e-10, atol=1e-12)

    def test_confluent_quadratic_pe(self):
        self.check_quadratic_pe("confluent")

    def test_confluent_quadratic_pe_tension_cell(self):
        self.check_quadratic_pe("confluent", "cell")

    def test_3d_quadratic_pe(self):
        self.check_quadratic_pe("3d")

    def test_thesis_form_same_forces_no_constant(self):
        """The thesis form of the same types with the same per-cell values:
        the same forces; pe lower by sum_c d_kp d_perim0^2 (quadratic types only)."""
        base = model_script("confluent")
        thesis = base.replace(COEFFS_2D, "pair_coeff 1 1 2.0 1.0 0.2 -1.48\n"
                              "pair_coeff 2 2 2.4 0.9 0.24 -1.824\npair_coeff 1 2 -1.602\n")
        out = """thermo_style custom step pe
thermo_modify norm no format float %.17g
run 0
print "E $(pe:%.17g)"
write_dump all custom f.dump id fx fy d_kp d_perim0 modify format float %.17g sort id
"""
        a = self.run_lmp(base + PER_CELL_2D + out)
        b = self.run_lmp(thesis + PER_CELL_2D + out)
        fa, fb = a.dump("f.dump")[0], b.dump("f.dump")[0]
        scale = np.abs(fa["fx"]).max()
        np.testing.assert_allclose(fb["fx"], fa["fx"], rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(fb["fy"], fa["fy"], rtol=0, atol=1e-12 * scale)
        const = (fa["d_kp"] * fa["d_perim0"] ** 2).sum()
        ea, eb = printed(a, "E")[0][0], printed(b, "E")[0][0]
        self.assertAlmostEqual(ea - eb, const, delta=1e-10 * abs(ea))


class PerCellEqualsTypes(LammpsTestCase):
    """Per-atom values equal to the types' give the types' forces and pe."""

    def check_equal(self, model):
        three = model.startswith("3d")
        finite = model.startswith("finite")
        coeffs = COEFFS_3D if three else COEFFS_FINITE if finite else COEFFS_2D
        vals = {}
        for line in coeffs.splitlines():
            w = line.split()
            if w[1] == w[2]:
                vals[int(w[1])] = [float(x) for x in w[4:8]]
        setv = "fix pc all property/atom d_ka d_kp d_perim0 d_area0\n"
        for t, (ka, a0, kp, p0) in vals.items():
            setv += (f"set type {t} d_ka {ka!r}\nset type {t} d_kp {kp!r}\n"
                     f"set type {t} d_perim0 {p0!r}\nset type {t} d_area0 {a0!r}\n")
        out = """thermo_style custom step pe
thermo_modify norm no format float %.17g
run 0
print "E $(pe:%.17g)"
write_dump all custom f.dump id fx fy fz modify format float %.17g sort id
"""
        a = self.run_lmp(model_script(model) + out)
        b = self.run_lmp(model_script(model) + setv + out)
        fa, fb = a.dump("f.dump")[0], b.dump("f.dump")[0]
        scale = max(np.abs(fa[c]).max() for c in ("fx", "fy", "fz"))
        for c in ("fx", "fy", "fz"):
            np.testing.assert_allclose(fb[c], fa[c], rtol=0, atol=1e-13 * scale, err_msg=c)
        ea, eb = printed(a, "E")[0][0], printed(b, "E")[0][0]
        self.assertAlmostEqual(ea, eb, delta=1e-13 * abs(ea))

    def test_confluent(self):
        self.check_equal("confluent")

    def test_finite(self):
        self.check_equal("finite_open")

    def test_3d(self):
        self.check_equal("3d")

    def test_stiffnesses_alone_same_bits(self):
        """d_ka = KA and d_kp = KP (no d_perim0) give K = 2 KA and Gamma = 2 KP
        exactly: the same forces and pe bit for bit."""
        setv = """fix pc all property/atom d_ka d_kp
set type 1 d_ka 1.0
set type 2 d_ka 1.2
set type 1 d_kp 0.1
set type 2 d_kp 0.12
"""
        out = """thermo_style custom step pe
thermo_modify norm no format float %.17g
run 0
print "E $(pe:%.17g)"
write_dump all custom f.dump id fx fy modify format float %.17g sort id
"""
        a = self.run_lmp(model_script("confluent") + out)
        b = self.run_lmp(model_script("confluent") + setv + out)
        np.testing.assert_array_equal(a.dump("f.dump")[0]["fx"], b.dump("f.dump")[0]["fx"])
        np.testing.assert_array_equal(a.dump("f.dump")[0]["fy"], b.dump("f.dump")[0]["fy"])
        self.assertEqual(printed(a, "E")[0][0], printed(b, "E")[0][0])


class PerCellRestart(LammpsTestCase):

    def test_restart_keeps_the_values(self):
        """write_restart / read_restart with fix property/atom defined again
        (same ID): the per-cell values, pe and forces come back, and a run
        continued from the restart matches the uninterrupted one."""
        dyn = """fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.005
thermo_style custom step pe
thermo_modify norm no format float %.17g
"""
        end = ("run 0\nprint \"E $(pe:%.17g)\"\n"
               "write_dump all custom end.dump id x y d_perim0 d_kp d_ka modify format float %.17g sort id\n")
        whole = self.run_lmp(model_script("confluent") + PER_CELL_2D + dyn + "run 20\n" + end)
        first = self.run_lmp(model_script("confluent") + PER_CELL_2D + dyn
                             + "run 10\nwrite_restart half.restart\n")
        second = self.run_lmp("dimension 2\n"
                              f"read_restart {first.path('half.restart')}\n"
                              "fix pc all property/atom d_ka d_kp d_perim0 d_area0\n"
                              + dyn + "run 10\n" + end)
        self.assertIn("per-cell values (fix property/atom) replace the types'", second.stdout)
        a, b = whole.dump("end.dump")[0], second.dump("end.dump")[0]
        for c in ("d_perim0", "d_kp", "d_ka"):
            np.testing.assert_array_equal(a[c], b[c], err_msg=c)
        for c in ("x", "y"):
            np.testing.assert_allclose(b[c], a[c], rtol=0, atol=1e-10, err_msg=c)
        ea, eb = printed(whole, "E")[0][0], printed(second, "E")[0][0]
        self.assertAlmostEqual(ea, eb, delta=1e-9 * abs(ea))
        # and they matter: without them the energy is another
        plain = self.run_lmp(model_script("confluent") + dyn + "run 20\n"
                             + end.replace(" d_perim0 d_kp d_ka", ""))
        self.assertGreater(abs(printed(plain, "E")[0][0] - ea), 1e-3)


class PerCellDivision(LammpsTestCase):

    def test_daughters_keep_the_mothers_values(self):
        """fix cell/divide: every cell has its own d_perim0 (all different);
        after divisions each value is held by its cell or by its descendants."""
        script = model_script("confluent") + PER_CELL_2D.replace("3.4+0.15*(id%6)", "3.4+0.001*id") + """
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix div all cell/divide rate 20.0 seed 4821 axis random separation 0.1 max 110
timestep 0.005
thermo_style custom step atoms pe
write_dump all custom start.dump id d_perim0 d_kp modify format float %.17g
run 4
write_dump all custom end.dump id d_perim0 d_kp modify format float %.17g
"""
        run = self.run_lmp(script)
        a, b = run.dump("start.dump")[0], run.dump("end.dump")[0]
        n0, n1 = len(a["id"]), len(b["id"])
        self.assertGreater(n1, n0)
        start = dict(zip(np.round(a["d_perim0"], 9), a["d_kp"]))
        self.assertEqual(len(start), n0)
        values, counts = np.unique(np.round(b["d_perim0"], 9), return_counts=True)
        self.assertEqual(len(values), n0)
        self.assertTrue(set(values) <= set(start))
        self.assertEqual(int((counts - 1).sum()), n1 - n0)    # (a daughter may divide again)
        for p0, kp in zip(np.round(b["d_perim0"], 9), b["d_kp"]):
            self.assertEqual(kp, start[p0])


class PerCellNewCells(LammpsTestCase):
    """Cells that fix deposit makes during a run are cells of their type:
    d_area0, d_ka, d_kp and d_perim0 hold the type's pair_coeff values
    (LAMMPS itself would leave in them whatever the memory held, often a
    ghost atom's values); the other cells keep theirs."""

    TYPES = {"2d": {1: (1.0, 1.0, 0.1, 3.7), 2: (0.9, 1.2, 0.12, 3.8)},
             "3d": {1: (1.0, 1.0, 0.05, 5.6), 2: (0.9, 1.2, 0.06, 5.5)}}

    def check(self, model):
        three = model.startswith("3d")
        zlo, zhi = ("EDGE", "EDGE") if three else ("-0.1", "0.1")
        script = model_script(model) + per_cell(model) + f"""
write_dump all custom start.dump id d_area0 d_ka d_kp d_perim0 modify format float %.17g
region dep block EDGE EDGE EDGE EDGE {zlo} {zhi} units box
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix dep1 all deposit 2 1 3 4821 region dep near 0.3 attempt 500
fix dep2 all deposit 2 2 4 1234 region dep near 0.3 attempt 500
timestep 0.001
run 9
write_dump all custom end.dump id type d_area0 d_ka d_kp d_perim0 modify format float %.17g
"""
        run = self.run_lmp(script)
        a, b = run.dump("start.dump")[0], run.dump("end.dump")[0]
        n0 = len(a["id"])
        self.assertEqual(len(b["id"]), n0 + 4)
        cols = ("d_area0", "d_ka", "d_kp", "d_perim0")
        old = np.isin(b["id"], a["id"])
        for c in cols:
            np.testing.assert_array_equal(b[c][old], a[c])
        types = self.TYPES["3d" if three else "2d"]
        new = np.flatnonzero(~old)
        self.assertEqual(sorted(b["type"][new].astype(int)), [1, 1, 2, 2])
        for i in new:
            want = types[int(b["type"][i])]
            got = [b[c][i] for c in cols]
            np.testing.assert_allclose(got, want, rtol=1e-13, atol=0,
                                       err_msg=f"new atom {b['id'][i]} of type {int(b['type'][i])}")

    def test_confluent(self):
        self.check("confluent")

    def test_3d(self):
        self.check("3d")


class PerCellAdapt(LammpsTestCase):

    def test_adapt_of_kappa_does_not_override_d_ka(self):
        """With d_ka on every cell, fix adapt of kappa changes no energy and
        says once why."""
        base = model_script("confluent") + "fix pc all property/atom d_ka\nset atom * d_ka 0.9\n"
        out = "thermo_style custom step pe\nthermo_modify norm no format float %.17g\nrun 0\nprint \"E $(pe:%.17g)\"\n"
        plain = self.run_lmp(base + out)
        adapted = self.run_lmp(base + "variable v equal 3.0\n"
                               "fix ad all adapt 1 pair vertex/voronoi kappa 1 1 v_v reset no\n" + out)
        self.assertEqual(printed(plain, "E")[0][0], printed(adapted, "E")[0][0])
        warnings = [l for l in adapted.output.splitlines() if "WARNING" in l and "per-atom d_ka" in l]
        self.assertEqual(len(warnings), 1, adapted.output[-2000:])


class PerCellErrors(LammpsTestCase):

    def test_unset_value_is_named(self):
        run = self.run_lmp(model_script("confluent") + """fix pc all property/atom d_perim0
set type 1 d_perim0 3.6
run 0
""", ok=False)
        self.assertLammpsError(run, "preferred perimeter P0 d_perim0 of atom", "must be > 0")

    def test_unset_3d_value_is_named(self):
        run = self.run_lmp(model_script("3d") + """fix pc all property/atom d_kp
set type 1 d_kp 0.05
run 0
""", ok=False)
        self.assertLammpsError(run, "surface modulus KS d_kp of atom", "must be > 0")

    def test_integer_property_is_an_error(self):
        run = self.run_lmp(model_script("confluent") + """fix pc all property/atom i_ka
run 0
""", ok=False)
        self.assertLammpsError(run, "'ka' must be a double vector")

    def test_kp_without_p0_needs_a_type_perimeter_modulus(self):
        script = model_script("confluent").replace(COEFFS_2D, "pair_coeff * * 2.0 1.0 0.0 -0.5\n")
        run = self.run_lmp(script + """fix pc all property/atom d_kp
set atom * d_kp 0.1
run 0
""", ok=False)
        self.assertLammpsError(run, "has perimeter modulus 0 (Gamma = 2 KP)", "also define d_perim0")


# Cells on a sphere (surface sphere): the per-cell values around the types'
# of SPHERE_COEFFS, scaled with the area per cell a of SPHERE_N cells on a
# sphere of radius SPHERE_R.
SPHERE_N, SPHERE_R = 24, 5.0
SPHERE_A = 4 * math.pi * SPHERE_R ** 2 / SPHERE_N
SPHERE_COEFFS = f"""pair_coeff 1 1 1.0 {SPHERE_A!r} 0.02 -0.3
pair_coeff 2 2 quadratic 0.01 {0.9 * SPHERE_A!r} 0.015 {3.9 * math.sqrt(SPHERE_A)!r}
pair_coeff 1 2 0.1
"""
PER_CELL_SPHERE = f"""fix pc all property/atom d_ka d_kp d_perim0 d_area0
variable ka atom 0.006+0.002*(id%5)
variable kp atom 0.01+0.004*(id%4)
variable p0 atom {math.sqrt(SPHERE_A)!r}*(3.5+0.15*(id%6))
variable a0 atom {SPHERE_A!r}*(0.85+0.05*(id%7))
set atom * d_ka v_ka
set atom * d_kp v_kp
set atom * d_perim0 v_p0
set atom * d_area0 v_a0
"""


def sphere_data(types=None):
    dirs = sphere.random_directions(SPHERE_N, 11)
    if types is None:
        types = [1 + (i % 3 == 0) for i in range(SPHERE_N)]
    return dirs, sphere.data_file(dirs, SPHERE_R, types)


class PerCellSphere(LammpsTestCase):
    """Cells on a sphere with per-cell d_ka, d_kp, d_perim0, d_area0: forces
    equal central differences of pe along geodesics (1 and 2 ranks, which
    agree), pe of a
    one-type tissue is sum_c d_ka (A - d_area0)^2 + d_kp (P - d_perim0)^2 of
    compute vertex/atom's spherical areas and geodesic perimeters, and values
    equal to the types' give the types' forces and pe."""

    def check_fd(self, n):
        R, h = SPHERE_R, 1e-5
        dirs, data = sphere_data()
        script = sphere.head(R) + SPHERE_COEFFS + PER_CELL_SPHERE + """thermo_style custom step pe
thermo_modify norm no format float %.17g
dump d all custom 1 f.dump id x y z fx fy fz
dump_modify d format float %.17g sort id
run 0
undump d
"""
        cases = []
        for atom in (3, 11, 20):
            u = dirs[atom - 1]
            t1 = np.cross(u, [0.3, 0.5, 0.8])
            t1 /= np.linalg.norm(t1)
            t2 = np.cross(u, t1)
            for k, t in enumerate((t1, t2)):
                axis = np.cross(u, t)
                for sign, key in ((1, "EP"), (-1, "EM")):
                    p = sphere.C + R * sphere.rotate(u, axis, sign * h / R)
                    script += f"set atom {atom} x {p[0]!r} y {p[1]!r} z {p[2]!r}\nrun 0\n"
                    script += f'print "{key} {atom} {k} $(pe:%.17g)"\n'
                p = sphere.C + R * u
                script += f"set atom {atom} x {p[0]!r} y {p[1]!r} z {p[2]!r}\n"
                cases.append((atom, k, t))
        run = self.run_lmp(script, nprocs=n, files={"cells.data": data})
        self.assertIn("per-cell values (fix property/atom) replace the types': d_area0 d_ka "
                      "d_kp d_perim0", run.stdout)
        f = run.dump("f.dump")[0]
        F = np.column_stack([f["fx"], f["fy"], f["fz"]])
        ep = {(int(a), int(k)): e for a, k, e in printed(run, "EP")}
        em = {(int(a), int(k)): e for a, k, e in printed(run, "EM")}
        scale = np.abs(F).max()
        self.assertGreater(scale, 1e-2)
        for atom, k, t in cases:
            fd = -(ep[(atom, k)] - em[(atom, k)]) / (2 * h)
            self.assertAlmostEqual(F[atom - 1] @ t, fd, delta=1e-6 * scale,
                                   msg=f"{n} ranks: atom {atom} dir {k}")
        self.assertEqual(len(ep), 6)
        # tangent forces
        r = np.column_stack([f["x"], f["y"], f["z"]]) - sphere.C
        np.testing.assert_allclose(np.einsum("ij,ij->i", F, r / R), 0.0, atol=1e-12 * scale)
        return F

    def test_fd(self):
        self.check_fd(1)

    @nprocs(2)
    def test_fd_2_ranks(self):
        self.check_fd(2)

    @nprocs(2)
    def test_ranks_agree(self):
        """Every rank uses every cell's values: 1 and 2 ranks give the same
        forces and pe (1e-13)."""
        _, data = sphere_data()
        script = sphere.head(SPHERE_R) + SPHERE_COEFFS + PER_CELL_SPHERE + """thermo_style custom step pe
thermo_modify norm no format float %.17g
run 0
print "E $(pe:%.17g)"
write_dump all custom f.dump id fx fy fz modify format float %.17g sort id
"""
        runs = [self.run_lmp(script, nprocs=n, files={"cells.data": data}) for n in (1, 2)]
        fa, fb = runs[0].dump("f.dump")[0], runs[1].dump("f.dump")[0]
        scale = max(np.abs(fa[c]).max() for c in ("fx", "fy", "fz"))
        self.assertGreater(scale, 1e-2)
        for c in ("fx", "fy", "fz"):
            np.testing.assert_allclose(fb[c], fa[c], rtol=0, atol=1e-13 * scale, err_msg=c)
        ea, eb = printed(runs[0], "E")[0][0], printed(runs[1], "E")[0][0]
        self.assertAlmostEqual(ea, eb, delta=1e-13 * abs(ea))

    def test_quadratic_pe(self):
        """One quadratic type: pe = sum_c d_ka (A - d_area0)^2 + d_kp (P -
        d_perim0)^2 (the constant KP_c P0_c^2 included), per cell too."""
        _, data = sphere_data([1] * SPHERE_N)
        script = sphere.head(SPHERE_R) + (
            f"pair_coeff * * quadratic 0.01 {SPHERE_A!r} 0.015 {3.8 * math.sqrt(SPHERE_A)!r}\n"
            + PER_CELL_SPHERE + """compute c all vertex/atom
thermo_style custom step pe
thermo_modify norm no format float %.17g
dump d all custom 1 cells.dump id c_c[1] c_c[2] c_c[5] d_ka d_kp d_perim0 d_area0
dump_modify d format float %.17g
run 0
print "E $(pe:%.17g)"
""")
        run = self.run_lmp(script, files={"cells.data": data})
        f = run.dump("cells.dump")[0]
        A, P = f["c_c[1]"], f["c_c[2]"]
        self.assertAlmostEqual(A.sum(), 4 * math.pi * SPHERE_R ** 2, delta=1e-10 * A.sum())
        e = f["d_ka"] * (A - f["d_area0"]) ** 2 + f["d_kp"] * (P - f["d_perim0"]) ** 2
        pe = printed(run, "E")[0][0]
        self.assertAlmostEqual(pe, e.sum(), delta=1e-11 * abs(pe))
        np.testing.assert_allclose(f["c_c[5]"], e, rtol=1e-10, atol=1e-12)

    def test_values_equal_to_the_types(self):
        """d_ka, d_kp, d_perim0, d_area0 set to the types' quadratic values
        give the types' forces and pe (1e-13)."""
        _, data = sphere_data()
        vals = {1: (0.02, SPHERE_A, 0.01, 3.7 * math.sqrt(SPHERE_A)),
                2: (0.01, 0.9 * SPHERE_A, 0.015, 3.9 * math.sqrt(SPHERE_A))}
        coeffs = "".join(f"pair_coeff {t} {t} quadratic {ka!r} {a0!r} {kp!r} {p0!r}\n"
                         for t, (ka, a0, kp, p0) in vals.items()) + "pair_coeff 1 2 quadratic 0.1\n"
        setv = "fix pc all property/atom d_ka d_kp d_perim0 d_area0\n"
        for t, (ka, a0, kp, p0) in vals.items():
            setv += (f"set type {t} d_ka {ka!r}\nset type {t} d_kp {kp!r}\n"
                     f"set type {t} d_perim0 {p0!r}\nset type {t} d_area0 {a0!r}\n")
        out = """thermo_style custom step pe
thermo_modify norm no format float %.17g
run 0
print "E $(pe:%.17g)"
write_dump all custom f.dump id fx fy fz modify format float %.17g sort id
"""
        a = self.run_lmp(sphere.head(SPHERE_R) + coeffs + out, files={"cells.data": data})
        b = self.run_lmp(sphere.head(SPHERE_R) + coeffs + setv + out, files={"cells.data": data})
        self.assertIn("replace the types'", b.stdout)
        fa, fb = a.dump("f.dump")[0], b.dump("f.dump")[0]
        scale = max(np.abs(fa[c]).max() for c in ("fx", "fy", "fz"))
        self.assertGreater(scale, 1e-2)
        for c in ("fx", "fy", "fz"):
            np.testing.assert_allclose(fb[c], fa[c], rtol=0, atol=1e-13 * scale, err_msg=c)
        ea, eb = printed(a, "E")[0][0], printed(b, "E")[0][0]
        self.assertAlmostEqual(ea, eb, delta=1e-13 * abs(ea))
        # and other values give another energy
        c = self.run_lmp(sphere.head(SPHERE_R) + coeffs + PER_CELL_SPHERE + out,
                         files={"cells.data": data})
        self.assertGreater(abs(printed(c, "E")[0][0] - ea), 1e-4 * abs(ea))


class HeterogeneousExample(LammpsTestCase):

    def test_example_runs_and_shapes_follow_p0(self):
        """examples/heterogeneous, shortened: it runs, every cell keeps its
        drawn p0, and cells of the larger p0 have the larger mean shape index."""
        with open(os.path.join(EXAMPLE, "in.heterogeneous")) as f:
            script = f.read()
        run = self.run_lmp(script, variables={"tend": 20})
        f = run.dump("cells.dump")[-1]
        p0, shape = f["d_perim0"], f["c_cell[3]"]
        values = sorted(set(np.round(p0, 12)))
        self.assertEqual(len(values), 2, values)
        lo = shape[np.isclose(p0, values[0])].mean()
        hi = shape[np.isclose(p0, values[1])].mean()
        self.assertGreater(hi, lo + 0.03, f"shape index {lo} (p0 {values[0]}) vs {hi} (p0 {values[1]})")


if __name__ == "__main__":
    lmptest.main()
