#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""pair_style vertex/voronoi ... surface sphere: cells on a sphere, against
values computed here: the icosahedron's 12 regular pentagons (area 4 pi R^2/12,
perimeter 5 R theta with cos theta = sqrt(5)/3, the energy from those), the
pentakis dodecahedron's 12 pentagons and 20 hexagons, forces against central
differences of pe along geodesics, the virial against sum (r - c) F of the
dumped forces, one step of fix polarity's alignment by parallel transport
computed with numpy, 1 == 2 == 4 ranks, restart, and active runs (brownian and
brownian/heun, a growing radius, divisions) that keep the cells on the sphere,
the polarities tangent and sum (6 - z) = 12."""

import math

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

C = np.array([20.0, 20.0, 20.0])
PHI = (1 + math.sqrt(5)) / 2


def icosahedron():
    v = []
    for s1 in (-1, 1):
        for s2 in (-1, 1):
            v += [(0, s1, PHI * s2), (s1, PHI * s2, 0), (PHI * s2, 0, s1)]
    v = np.array(v, float)
    return v / np.linalg.norm(v, axis=1)[:, None]


def dodecahedron():
    v = []
    for a in (-1, 1):
        for b in (-1, 1):
            for c in (-1, 1):
                v.append((a, b, c))
            v += [(0, a * PHI, b / PHI), (a * PHI, b / PHI, 0), (b / PHI, 0, a * PHI)]
    v = np.array(v, float)
    return v / np.linalg.norm(v, axis=1)[:, None]


def random_directions(n, seed):
    rng = np.random.default_rng(seed)
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def data_file(dirs, R, types=None, mu=None, box=40.0, ntypes=2):
    x = C + R * dirs
    lines = ["cells on a sphere", "", f"{len(x)} atoms", f"{ntypes} atom types",
             f"0 {box} xlo xhi", f"0 {box} ylo yhi", f"0 {box} zlo zhi", "", "Atoms # dipole", ""]
    for i, p in enumerate(x):
        t = 1 if types is None else int(types[i])
        m = (0.0, 0.0, 0.0) if mu is None else tuple(mu[i])
        lines.append(f"{i + 1} {t} 0 {p[0]!r} {p[1]!r} {p[2]!r} {m[0]!r} {m[1]!r} {m[2]!r}")
    return "\n".join(lines) + "\n"


def head(R="{R}", cut=8.0, extra=""):
    return f"""units lj
atom_style dipole
boundary f f f
read_data cells.data
mass * 1.0
pair_style vertex/voronoi {cut} surface sphere {C[0]} {C[1]} {C[2]} {R}{extra}
thermo_modify norm no
"""


def printed(run, key):
    return [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
            if line.startswith(key + " ")]


def positions(frame):
    return np.column_stack([frame["x"], frame["y"], frame["z"]])


def polarities(frame):
    return np.column_stack([frame["mux"], frame["muy"], frame["muz"]])


def transport(ua, ub, v):
    """Parallel transport of v (tangent at unit ua) to unit ub along the geodesic."""
    return v - (ub @ v) / (1 + ua @ ub) * (ua + ub)


def rotate(n, k, a):
    """n turned by angle a about the unit axis k (Rodrigues)."""
    return n * math.cos(a) + np.cross(k, n) * math.sin(a) + k * (k @ n) * (1 - math.cos(a))


class Icosahedron(LammpsTestCase):
    """12 cells at an icosahedron's vertices: 12 regular pentagons of area
    4 pi R^2 / 12, perimeter 5 R theta (cos theta = sqrt(5)/3, the angle a
    regular dodecahedron's edge subtends), energy from those, zero force;
    on 1, 2 and 4 ranks."""

    @nprocs(4)
    def test_pentagons(self):
        for n in (1, 2, 4):
            with self.subTest(ranks=n):
                self.pentagons(n)

    def pentagons(self, n):
        R, K, A0, G, L = 3.0, 1.0, 2.0, 0.1, -0.2
        script = head(R) + f"""pair_coeff * * {K} {A0} {G} {L}
compute c all vertex/atom
dump d all custom 1 cells.dump id x y z fx fy fz c_c[1] c_c[2] c_c[3] c_c[4] c_c[5]
dump_modify d format float %.17g
thermo_style custom step pe
thermo_modify norm no
run 0
print "E $(pe:%.17g)"
"""
        run = self.run_lmp(script, nprocs=n,
                           files={"cells.data": data_file(icosahedron(), R, ntypes=1)})
        f = run.dump("cells.dump")[0]
        A = 4 * math.pi * R * R / 12
        theta = math.acos(math.sqrt(5) / 3)
        P = 5 * R * theta
        np.testing.assert_allclose(f["c_c[1]"], A, rtol=1e-13)
        np.testing.assert_allclose(f["c_c[2]"], P, rtol=1e-13)
        np.testing.assert_allclose(f["c_c[3]"], P / math.sqrt(A), rtol=1e-13)
        np.testing.assert_array_equal(f["c_c[4]"], 5)
        e = 12 * (K / 2 * (A - A0) ** 2 + G / 2 * P * P) + L * 30 * R * theta
        self.assertAlmostEqual(printed(run, "E")[0][0], e, delta=1e-12 * abs(e))
        np.testing.assert_allclose(f["c_c[5]"].sum(), e, rtol=1e-12)
        for col in ("fx", "fy", "fz"):
            self.assertLess(np.abs(f[col]).max(), 1e-12)


class PentakisDodecahedron(LammpsTestCase):
    """32 cells (icosahedron + dodecahedron directions): 12 pentagons, 20
    hexagons, areas adding up to 4 pi R^2, sum (6 - z) = 12, and zero force
    with two types (each point on a 5- or 3-fold axis)."""

    def test_pentagons_and_hexagons(self):
        R = 4.0
        dirs = np.vstack([icosahedron(), dodecahedron()])
        types = [1] * 12 + [2] * 20
        script = head(R) + """pair_coeff 1 1 1.0 2.0 0.1 -0.1
pair_coeff 2 2 1.3 1.8 0.2 -0.2
pair_coeff 1 2 0.05
compute c all vertex/atom
dump d all custom 1 cells.dump id type fx fy fz c_c[1] c_c[4]
dump_modify d format float %.17g
run 0
"""
        run = self.run_lmp(script, files={"cells.data": data_file(dirs, R, types)})
        f = run.dump("cells.dump")[0]
        z = f["c_c[4]"]
        np.testing.assert_array_equal(z[f["type"] == 1], 5)
        np.testing.assert_array_equal(z[f["type"] == 2], 6)
        self.assertEqual((6 - z).sum(), 12)
        self.assertAlmostEqual(f["c_c[1]"].sum(), 4 * math.pi * R * R, delta=1e-11 * R * R)
        for t in (1, 2):
            a = f["c_c[1]"][f["type"] == t]
            np.testing.assert_allclose(a, a[0], rtol=1e-12)
        for col in ("fx", "fy", "fz"):
            self.assertLess(np.abs(f[col]).max(), 1e-11)


class Forces(LammpsTestCase):
    """Random cells, two types, junction tension between them: forces equal
    central differences of pe along geodesics, are tangent, have no torque
    about the centre though they do not add up to zero; the virial is
    W_ab = sum (r - c)_a F_b (symmetric, traceless) of the dumped forces."""

    R = 5.0

    def setUp(self):
        super().setUp()
        self.dirs = random_directions(24, 11)
        self.types = [1 + (i % 3 == 0) for i in range(24)]
        self.data = data_file(self.dirs, self.R, self.types)
        self.coeffs = """pair_coeff 1 1 1.0 4.0 0.2 -0.3
pair_coeff 2 2 quadratic 0.7 3.0 0.15 3.9
pair_coeff 1 2 0.1
"""

    @nprocs(4)
    def test_central_differences(self):
        for n in (1, 2, 4):
            with self.subTest(ranks=n):
                self.central_differences(n)

    def central_differences(self, n):
        R, h = self.R, 1e-5
        script = head(R) + self.coeffs + """thermo_style custom step pe
thermo_modify norm no format float %.17g
dump d all custom 1 f.dump id x y z fx fy fz
dump_modify d format float %.17g
run 0
undump d
"""
        cases = []
        for atom in (3, 11, 20):
            u = self.dirs[atom - 1]
            t1 = np.cross(u, [0.3, 0.5, 0.8])
            t1 /= np.linalg.norm(t1)
            t2 = np.cross(u, t1)
            for k, t in enumerate((t1, t2)):
                axis = np.cross(u, t)
                for sign, key in ((1, "EP"), (-1, "EM")):
                    p = C + R * rotate(u, axis, sign * h / R)
                    script += f"set atom {atom} x {p[0]!r} y {p[1]!r} z {p[2]!r}\nrun 0\n"
                    script += f'print "{key} {atom} {k} $(pe:%.17g)"\n'
                p = C + R * u
                script += f"set atom {atom} x {p[0]!r} y {p[1]!r} z {p[2]!r}\n"
                cases.append((atom, k, t))
        run = self.run_lmp(script, nprocs=n, files={"cells.data": self.data})
        f = run.dump("f.dump")[0]
        F = np.column_stack([f["fx"], f["fy"], f["fz"]])
        r = positions(f) - C
        ep = {(int(a), int(k)): e for a, k, e in printed(run, "EP")}
        em = {(int(a), int(k)): e for a, k, e in printed(run, "EM")}
        scale = np.abs(F).max()
        self.assertGreater(scale, 1e-2)
        for atom, k, t in cases:
            fd = -(ep[(atom, k)] - em[(atom, k)]) / (2 * h)
            self.assertAlmostEqual(F[atom - 1] @ t, fd, delta=1e-6 * scale, msg=f"atom {atom} dir {k}")
        # tangent, no torque, but no zero sum
        np.testing.assert_allclose(np.einsum("ij,ij->i", F, r / R), 0.0, atol=1e-12 * scale)
        np.testing.assert_allclose(np.cross(r, F).sum(0), 0.0, atol=1e-11 * scale * R)
        self.assertGreater(np.linalg.norm(F.sum(0)), 1e-4 * scale)

    def test_virial_about_the_centre(self):
        script = head(self.R) + self.coeffs + """compute p all pressure NULL virial
compute s all stress/atom NULL virial
thermo_style custom step pe vol c_p[1] c_p[2] c_p[3] c_p[4] c_p[5] c_p[6]
dump d all custom 1 f.dump id x y z fx fy fz c_s[1] c_s[2] c_s[3] c_s[4] c_s[5] c_s[6]
dump_modify d format float %.17g
run 0
print "P $(vol:%.17g) $(c_p[1]:%.17g) $(c_p[2]:%.17g) $(c_p[3]:%.17g) $(c_p[4]:%.17g) $(c_p[5]:%.17g) $(c_p[6]:%.17g)"
"""
        run = self.run_lmp(script, files={"cells.data": self.data})
        f = run.dump("f.dump")[0]
        F = np.column_stack([f["fx"], f["fy"], f["fz"]])
        r = positions(f) - C
        W = r.T @ F
        vol, *p = printed(run, "P")[0]
        got = np.array(p) * vol
        want = np.array([W[0, 0], W[1, 1], W[2, 2], W[0, 1], W[0, 2], W[1, 2]])
        np.testing.assert_allclose(got, want, atol=1e-10 * np.abs(W).max())
        np.testing.assert_allclose(W, W.T, atol=1e-11 * np.abs(W).max())
        self.assertAlmostEqual(np.trace(W), 0.0, delta=1e-11 * np.abs(W).max())
        self.assertGreater(np.abs(W).max(), 1e-3)
        # per atom: -(r_i - c) (x) F_i (compute stress/atom's sign), symmetrised
        per = -np.column_stack([r[:, 0] * F[:, 0], r[:, 1] * F[:, 1], r[:, 2] * F[:, 2],
                                0.5 * (r[:, 0] * F[:, 1] + r[:, 1] * F[:, 0]),
                                0.5 * (r[:, 0] * F[:, 2] + r[:, 2] * F[:, 0]),
                                0.5 * (r[:, 1] * F[:, 2] + r[:, 2] * F[:, 1])])
        got = np.column_stack([f[f"c_s[{k}]"] for k in range(1, 7)])
        np.testing.assert_allclose(got, per, atol=1e-12 * np.abs(W).max())


class PolarityAlignment(LammpsTestCase):
    """One step of fix polarity on the icosahedron (no forces, no motion):
    n_i <- n_i turned about the normal u_i by dt/gamma_R tau_i,
    tau_i = J_S sum_j u_i . (n_i x T_ji n_j) over the 5 neighbours, T_ji the
    parallel transport, computed here."""

    def test_one_step(self):
        R, dt, JS, gR = 3.0, 0.05, 1.3, 0.7
        u = icosahedron()
        rng = np.random.default_rng(5)
        n = np.cross(u, rng.normal(size=(12, 3)))
        n /= np.linalg.norm(n, axis=1)[:, None]
        script = head(R) + f"""pair_coeff * * 1.0 {4 * math.pi * R * R / 12!r} 0.1 -0.2
fix p all polarity 0.0 {gR} neighbor {JS}
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep {dt}
dump d all custom 1 pol.dump id x y z mux muy muz
dump_modify d format float %.17g
run 2
"""
        run = self.run_lmp(script, files={"cells.data": data_file(u, R, mu=n, ntypes=1)})
        frames = run.dump("pol.dump")
        cos_nb = (u @ u.T)
        nbrs = [np.argsort(-cos_nb[i])[1:6] for i in range(12)]
        for fr in frames[1:]:
            new = np.empty_like(n)
            for i in range(12):
                tau = JS * sum(u[i] @ np.cross(n[i], transport(u[j], u[i], n[j])) for j in nbrs[i])
                new[i] = rotate(n[i], u[i], dt / gR * tau)
            n = new
            got = polarities(fr)
            np.testing.assert_allclose(got, n, atol=1e-12, err_msg=f"step {fr['step']}")
            np.testing.assert_allclose(positions(fr), C + R * u, atol=1e-12)
        self.assertGreater(np.abs(polarities(frames[-1]) - polarities(frames[0])).max(), 1e-3)


def tissue(n=200, R=8.0, seed=3):
    """n random cells on a sphere of radius R (two types), with random
    tangent polarities; A0 a little below the area per cell."""
    dirs = random_directions(n, seed)
    rng = np.random.default_rng(seed + 1)
    mu = np.cross(dirs, rng.normal(size=(n, 3)))
    mu /= np.linalg.norm(mu, axis=1)[:, None]
    types = [1 + (i % 4 == 0) for i in range(n)]
    return data_file(dirs, R, types, mu)


def tissue_coeffs(a0):
    return f"""pair_coeff 1 1 quadratic 1.0 {a0!r} 0.1 {3.8 * math.sqrt(a0)!r}
pair_coeff 2 2 quadratic 1.2 {0.9 * a0!r} 0.12 {3.7 * math.sqrt(a0)!r}
pair_coeff 1 2 quadratic 0.05
"""


class Ranks(LammpsTestCase):
    """An active run (polarity with neighbour alignment, deterministic
    integrator) from one data file ends in the same state on 1, 2 and 4 ranks."""

    @nprocs(4)
    def test_ranks_agree(self):
        R = 8.0
        a0 = 4 * math.pi * R * R / 200
        script = head(R, cut=3 * math.sqrt(a0)) + tissue_coeffs(a0) + """compute c all vertex/atom
compute t all vertex/tissue
fix p all polarity 0.5 1.0 neighbor 0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.02
thermo_style custom step pe c_t[1]
thermo_modify norm no
thermo 10
dump d all custom 30 end.dump id x y z mux muy muz fx fy fz c_c[1]
dump_modify d format float %.17g
run 30
print "E $(pe:%.17g)"
"""
        out = []
        for n in (1, 2, 4):
            run = self.run_lmp(script, nprocs=n, files={"cells.data": tissue(200, R)})
            out.append((printed(run, "E")[0][0], run.dump("end.dump")[-1]))
        for e, f in out[1:]:
            self.assertAlmostEqual(e, out[0][0], delta=1e-10 * abs(out[0][0]))
            for col in ("x", "y", "z", "mux", "muy", "muz", "fx", "fy", "fz", "c_c[1]"):
                np.testing.assert_allclose(f[col], out[0][1][col], rtol=0, atol=1e-10, err_msg=col)


class Restart(LammpsTestCase):
    """write_restart after 10 steps, read_restart, 10 more: the state of 20
    steps in one run."""

    def test_restart_continues(self):
        R = 8.0
        a0 = 4 * math.pi * R * R / 200
        dyn = """fix p all polarity 0.5 1.0 neighbor 0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.02
"""
        end = "write_dump all custom end.dump id x y z mux muy muz modify format float %.17g\n"
        base = head(R, cut=3 * math.sqrt(a0)) + tissue_coeffs(a0) + dyn
        data = {"cells.data": tissue(200, R)}
        whole = self.run_lmp(base + "run 20\n" + end, files=data).dump("end.dump")[0]
        first = self.run_lmp(base + "run 10\nwrite_restart half.restart\n", files=data)
        second = self.run_lmp(f"read_restart {first.path('half.restart')}\n" + dyn + "run 10\n" + end)
        self.assertIn("surface sphere", second.stdout)
        f = second.dump("end.dump")[0]
        for col in ("x", "y", "z", "mux", "muy", "muz"):
            np.testing.assert_allclose(f[col], whole[col], rtol=0, atol=1e-10, err_msg=col)


class RadiusFromComputes(LammpsTestCase):
    """R = v_R reading a compute, here sqrt(sum of d_area0 / 4 pi) with
    d_area0 = 1: the cells sit on the sphere of the current number of cells
    at every dumped step while cells divide between the dumps (the compute
    is evaluated anew at every use, not taken from an earlier step)."""

    def test_radius_follows_the_divisions(self):
        R0 = 4.0
        n0 = 200
        script = (head("v_R", cut=3.0).replace("pair_style", "fix pa all property/atom d_area0\n"
                                               "set group all d_area0 1.0\n"
                                               "compute a all property/atom d_area0\n"
                                               "compute s all reduce sum c_a\n"
                                               "variable R equal sqrt(c_s/(4*PI))\n"
                                               "pair_style", 1) +
                  tissue_coeffs(1.0) + """fix b all brownian 1.0 17 gamma_t 1.0 rng none
fix div all cell/divide rate 2.0 seed 4821 separation 0.1
timestep 0.01
thermo 1000
dump d all custom 5 cells.dump id x y z
dump_modify d format float %.17g
run 30
""")
        run = self.run_lmp(script, files={"cells.data": tissue(n0, R0)})
        frames = run.dump("cells.dump")
        self.assertGreater(len(frames[-1]["id"]), n0 + 20)
        for fr in frames:
            R = math.sqrt(len(fr["id"]) / (4 * math.pi))
            r = np.linalg.norm(positions(fr) - C, axis=1)
            np.testing.assert_allclose(r, R, rtol=1e-12, err_msg=f"step {fr['step']}")


class ActiveRuns(LammpsTestCase):
    """Active runs stay on the sphere: |x - c| = R(t) (R growing by a
    variable), unit tangent polarities, areas adding up to 4 pi R(t)^2 and
    sum (6 - z) = 12 in every frame; with fix brownian (thermal noise,
    rotational noise) and fix brownian/heun, and with divisions."""

    def check_frames(self, frames, radius):
        for fr in frames:
            R = radius(fr["step"])
            x = positions(fr) - C
            r = np.linalg.norm(x, axis=1)
            np.testing.assert_allclose(r, R, rtol=1e-12, err_msg=f"step {fr['step']}")
            mu = polarities(fr)
            np.testing.assert_allclose(np.linalg.norm(mu, axis=1), 1.0, atol=1e-12)
            np.testing.assert_allclose(np.einsum("ij,ij->i", mu, x / r[:, None]), 0.0, atol=1e-12)
            self.assertAlmostEqual(fr["c_c[1]"].sum(), 4 * math.pi * R * R, delta=1e-9 * R * R)
            self.assertEqual((6 - fr["c_c[4]"]).sum(), 12)

    def run_active(self, integrator, extra="", steps=100):
        R0 = 8.0
        a0 = 4 * math.pi * R0 * R0 / 200
        script = f"variable R equal {R0}+0.02*time\n" + head("v_R", cut=3 * math.sqrt(a0)) + \
            tissue_coeffs(a0) + f"""compute c all vertex/atom
fix p all polarity 1.0 1.0 neighbor 0.3 noise 0.5 91
fix b all {integrator}
{extra}
timestep 0.01
dump d all custom 20 cells.dump id x y z mux muy muz c_c[1] c_c[4]
dump_modify d format float %.17g
thermo_style custom step pe atoms
run {steps}
"""
        run = self.run_lmp(script, files={"cells.data": tissue(200, R0)})
        frames = run.dump("cells.dump")
        self.assertEqual(len(frames), steps // 20 + 1)
        self.check_frames(frames, lambda step: R0 + 0.02 * step * 0.01)
        return frames

    def test_brownian(self):
        frames = self.run_active("brownian 0.05 17 gamma_t 1.0")
        moved = np.abs(positions(frames[-1]) - positions(frames[0])).max()
        self.assertGreater(moved, 0.05)

    def test_heun(self):
        self.run_active("brownian/heun 1.0 17 gamma_t 1.0 rng none")

    def test_divisions(self):
        frames = self.run_active("brownian 1.0 17 gamma_t 1.0 rng none",
                                 "fix div all cell/divide rate 1.0 seed 4821 axis long separation 0.2",
                                 steps=60)
        self.assertGreater(len(frames[-1]["id"]), len(frames[0]["id"]))


class Minimise(LammpsTestCase):
    """minimize (fire) lowers pe and the force norm; the next run puts the
    atoms back on the sphere (minimize moves them along tangent forces)."""

    def test_fire(self):
        R = 8.0
        a0 = 4 * math.pi * R * R / 200
        script = head(R, cut=3 * math.sqrt(a0)) + tissue_coeffs(a0) + """thermo_style custom step pe fnorm
thermo_modify norm no format float %.17g
run 0
print "A $(pe:%.17g) $(fnorm:%.17g)"
min_style fire
minimize 0 1e-6 300 3000
run 0
print "B $(pe:%.17g) $(fnorm:%.17g)"
write_dump all custom end.dump id x y z modify format float %.17g
"""
        run = self.run_lmp(script, files={"cells.data": tissue(200, R)})
        (e0, f0), (e1, f1) = printed(run, "A")[0], printed(run, "B")[0]
        self.assertLess(e1, e0)
        self.assertLess(f1, 0.05 * f0)
        r = np.linalg.norm(positions(run.dump("end.dump")[0]) - C, axis=1)
        np.testing.assert_allclose(r, R, rtol=1e-12)


class Errors(LammpsTestCase):
    def test_dimension_2(self):
        # (a 2d box of its own: a current LAMMPS refuses a 2d data file whose
        # z range does not straddle 0 before the pair style is read)
        run = self.run_lmp("""dimension 2
units lj
atom_style dipole
boundary p p p
region box block -6 6 -6 6 -0.5 0.5
create_box 1 box
create_atoms 1 random 12 4821 NULL
mass * 1.0
pair_style vertex/voronoi 8.0 surface sphere 0 0 0 5.0
pair_coeff * * 1 1 0.1 0
run 0
""", ok=False)
        self.assertLammpsError(run, "'surface sphere' needs 'dimension 3'")

    def test_sphere_outside_the_box(self):
        run = self.run_lmp(head(25.0) + "pair_coeff * * 1 1 0.1 0\nrun 0\n",
                           files={"cells.data": data_file(icosahedron(), 5.0, ntypes=1)}, ok=False)
        self.assertLammpsError(run, "reaches past the box")

    def test_groove(self):
        run = self.run_lmp(head(5.0) + "pair_coeff * * 1 1 0.1 0\nfix p all polarity 1 1 groove 1 0\n"
                           "fix b all brownian 1 1 gamma_t 1 rng none\nrun 1\n",
                           files={"cells.data": data_file(icosahedron(), 5.0, ntypes=1)}, ok=False)
        self.assertLammpsError(run, "'groove' alignment has no meaning for cells on a sphere")

    def test_pair_style_again_without_surface(self):
        # the same style again without 'surface': 3d polyhedra, which need a periodic box
        run = self.run_lmp(head(5.0) + "pair_coeff * * 1 1 0.1 0\nrun 0\npair_style vertex/voronoi 8.0\n"
                           "run 0\n", files={"cells.data": data_file(icosahedron(), 5.0, ntypes=1)},
                           ok=False)
        self.assertLammpsError(run, "requires periodic x, y and z boundaries")

    def test_radius(self):
        for r, msg in (("-1", "sphere radius R must be > 0"), ("v_nope", "variable 'nope' does not exist")):
            run = self.run_lmp(head(r) + "pair_coeff * * 1 1 0.1 0\nrun 0\n",
                               files={"cells.data": data_file(icosahedron(), 5.0, ntypes=1)}, ok=False)
            self.assertLammpsError(run, msg)

    @nprocs(2)
    def test_cutoff_too_small_names_the_neighbours(self):
        # grow no and a cutoff below the cell spacing: the message says what
        # the sphere needs (the cells' neighbours), not a circumsphere
        run = self.run_lmp(head(8.0, cut=0.8, extra=" grow no") + tissue_coeffs(1.0) + "run 0\n",
                           files={"cells.data": tissue(200, 8.0)}, nprocs=2, ok=False)
        self.assertLammpsError(run, "a neighbour of a cell of this rank lies past the ghost atoms")


if __name__ == "__main__":
    lmptest.main()
