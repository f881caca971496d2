#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Species carried by the cells (fix cell/signal), the junction-weighted
neighbour mean (compute cell/neighbor/mean) and parameters that follow
variables (fix cell/adapt): the steady profile of a line source with
degradation on the hexagonal lattice against the discrete decay law derived
in doc/model.md; conservation to round-off without reactions on 1, 2 and 4
ranks, through divisions that split the amounts; the lateral-inhibition
threshold of Collier et al. on both sides of the lattice's linear stability
result, with the growth rate of the unstable mode; the ideal pattern; the
neighbour mean against one computed from compute vertex/local's pieces;
restarts; and the errors that name the cell, the step and the law."""

import math

import numpy as np

import lmptest
from feature_models import local_rows
from lmptest import LammpsTestCase, nprocs

PAIR = """
pair_style vertex/voronoi 3.0
pair_coeff * * quadratic 1.0 1.0 0.1 3.7
thermo_modify norm no
"""

# The hexagonal lattice of cells of area 1: spacing a, rows h apart, edges l.
A = math.sqrt(2 / math.sqrt(3))
H = A * math.sqrt(3) / 2
L = A / math.sqrt(3)


def hex_tissue(nx, ny):
    return lmptest.tissue(nx, ny, "hex") + PAIR


def rows_of(y):
    return np.rint(np.asarray(y) / H).astype(int)


def colour_of(x, y):
    """One of the three colour classes of the triangular lattice of centres
    (no two neighbours share one): (p - q) mod 3 for the centre p a1 + q a2."""
    q = np.rint(np.asarray(y) / H).astype(int)
    p = np.rint(np.asarray(x) / A - q / 2).astype(int)
    return (p - q) % 3


def thermo_rows(run):
    rows, header = [], None
    for line in run.stdout.splitlines():
        w = line.split()
        if w and w[0] == "Step":
            header = w
            continue
        if header and len(w) == len(header):
            try:
                rows.append(dict(zip(header, map(float, w))))
            except ValueError:
                header = None
    return rows


class LineSource(LammpsTestCase):
    """A row of cells produces u at rate p, every cell degrades it at rate k
    and exchanges it with permeability P per unit junction length.  In the
    steady state every row m != 0 of the periodic 12-row lattice obeys
    u_{m+1} + u_{m-1} = (2 + k / (2 P l)) u_m, so u_m = C cosh(lam (m - 6))
    with cosh(lam) = 1 + k / (4 P l): decay length h / lam (doc/model.md)."""

    def profile(self, P, k, dt, steps, extra=""):
        run = self.run_lmp(hex_tissue(4, 6) + f"""
fix sp all property/atom d_u
set group all d_u 0.0
variable src atom 1.0*(y<0.2)
fix s all cell/signal exchange d_u {P!r} degrade d_u {k!r} produce d_u v_src {extra}
timestep {dt}
thermo_style custom step f_s[1] f_s[2]
thermo {steps}
run {steps}
compute pu all property/atom d_u
dump d all custom 1 prof.txt id x y c_pu
dump_modify d format float %.17g
run 0
""")
        f = run.dump("prof.txt")[0]
        m = rows_of(f["y"])
        u = np.array([f["c_pu"][m == r].mean() for r in range(12)])
        spread = max(np.ptp(f["c_pu"][m == r]) for r in range(12))
        return u, spread, thermo_rows(run)

    def check(self, P, k, dt, steps, extra=""):
        u, spread, thermo = self.profile(P, k, dt, steps, extra)
        self.assertLess(spread, 1e-12 * u.max())    # rows are uniform
        lam = math.acosh(1 + k / (4 * P * L))
        # Every row m != 0 against the law, and the decay length from the
        # rows 1..5 (ratios of the cosh), each to 1e-3.
        for r in range(1, 12):
            self.assertAlmostEqual(u[r] / u[6], math.cosh(lam * (r - 6)), delta=1e-3 * math.cosh(lam * (r - 6)))
        measured = np.mean([math.acosh((u[r + 1] + u[r - 1]) / (2 * u[r])) for r in range(1, 11)])
        self.assertAlmostEqual(H / measured, H / lam, delta=1e-3 * H / lam)
        # The amount: production 4 cells x 1 balanced by degradation.
        self.assertAlmostEqual(thermo[-1]["f_s[1]"], 4.0 / k, delta=1e-9)
        return thermo

    def test_decay_length(self):
        thermo = self.check(P=1.0 / L, k=1.0, dt=0.05, steps=1000)
        self.assertEqual(max(r["f_s[2]"] for r in thermo), 1)

    def test_decay_length_stiff_exchange(self):
        """Exchange 12 times faster than the step: automatic substeps."""
        thermo = self.check(P=20.0 / L, k=1.0, dt=0.1, steps=500)
        self.assertGreater(max(r["f_s[2]"] for r in thermo), 20)

    def test_decay_length_implicit(self):
        """Exchange 240 times faster than the step, one implicit step each."""
        thermo = self.check(P=20.0 / L, k=1.0, dt=2.0, steps=40, extra="implicit yes")
        self.assertEqual(max(r["f_s[2]"] for r in thermo), 1)


def random_tissue(test, nx=8, ny=6):
    return test.run_lmp(lmptest.tissue(nx, ny) + """
displace_atoms all random 0.2 0.2 0 4821 units box
write_data cfg.data
""").text("cfg.data")


CONSERVE = """
dimension 2
units lj
atom_style dipole
boundary p p p
read_data cfg.data
""" + PAIR + """
fix sp all property/atom d_u d_w
variable u0 atom 1+((id*37)%11)
variable w0 atom 0.5*((id*13)%7)
set group all d_u v_u0
set group all d_w v_w0
fix move all brownian 1.0 1 gamma_t 1.0 rng none
fix s all cell/signal exchange d_u 3.0 exchange d_w 0.5
timestep 0.02
"""


class Conservation(LammpsTestCase):
    def totals(self, n, data, extra=""):
        run = self.run_lmp(CONSERVE + extra + """
compute nb all vertex/tissue
thermo_style custom step atoms f_s[1] f_s[2] c_nb[2]
thermo_modify format float %.17g
thermo 50
run 400
""", nprocs=n, files={"cfg.data": data})
        return thermo_rows(run)

    def check_ranks(self, extra, grows):
        data = random_tissue(self)
        ref = None
        for n in (1, 2, 4):
            rows = self.totals(n, data, extra)
            u = np.array([r["f_s[1]"] for r in rows])
            w = np.array([r["f_s[2]"] for r in rows])
            np.testing.assert_allclose(u, u[0], rtol=1e-13, atol=0, err_msg=f"{n} ranks")
            np.testing.assert_allclose(w, w[0], rtol=1e-13, atol=0, err_msg=f"{n} ranks")
            atoms = [r["Atoms"] for r in rows]
            if grows:
                self.assertGreater(atoms[-1], atoms[0])
            if ref is None:
                ref = (u, w, atoms)
            else:
                self.assertEqual(atoms, ref[2])
                np.testing.assert_allclose(u, ref[0], rtol=1e-13)
        return rows

    @nprocs(4)
    def test_conserved_on_1_2_4_ranks(self):
        self.check_ranks("", False)

    @nprocs(4)
    def test_conserved_through_divisions(self):
        self.check_ranks("fix div all cell/divide rate 0.5 seed 7 split d_u split d_w max 130\n", True)

    def test_group(self):
        """A fix on a group exchanges among its cells only: their total stays,
        the other cells keep their values."""
        data = random_tissue(self)
        run = self.run_lmp(CONSERVE.replace("fix s all cell/signal", "group half id <= 48\n"
                                            "group rest subtract all half\n"
                                            "fix s half cell/signal") + """
variable uu atom c_pu
compute pu all property/atom d_u
compute rest rest reduce sum v_uu
compute restmax rest reduce max v_uu
thermo_style custom step f_s[1] c_rest c_restmax
thermo_modify format float %.17g norm no
thermo 100
run 400
""", files={"cfg.data": data})
        rows = thermo_rows(run)
        u = np.array([r["f_s[1]"] for r in rows])
        np.testing.assert_allclose(u, u[0], rtol=1e-13, atol=0)
        self.assertEqual(len({r["c_rest"] for r in rows}), 1)
        self.assertEqual(len({r["c_restmax"] for r in rows}), 1)
        self.assertNotEqual(u[0], rows[0]["c_rest"])

    @nprocs(4)
    def test_conserved_implicit(self):
        """The implicit step moves amounts by antisymmetric fluxes: conserved
        on 1, 2 and 4 ranks, with a step 20 times the exchange time."""
        data = random_tissue(self)
        for n in (1, 2, 4):
            run = self.run_lmp(CONSERVE.replace("exchange d_w 0.5", "exchange d_w 0.5 implicit yes")
                               .replace("timestep 0.02", "timestep 2.0")
                               .replace("gamma_t 1.0", "gamma_t 100.0") + """
thermo_style custom step f_s[1] f_s[2]
thermo_modify format float %.17g
thermo 10
run 40
""", nprocs=n, files={"cfg.data": data})
            rows = thermo_rows(run)
            u = np.array([r["f_s[1]"] for r in rows])
            np.testing.assert_allclose(u, u[0], rtol=1e-13, atol=0, err_msg=f"{n} ranks")

    def test_copy_without_split(self):
        """Without 'split' the daughters copy the mother's value: the total grows."""
        data = random_tissue(self)
        rows = self.totals(1, data, "fix div all cell/divide rate 0.5 seed 7 max 130\n")
        self.assertGreater(rows[-1]["Atoms"], rows[0]["Atoms"])
        self.assertGreater(rows[-1]["f_s[1]"], rows[0]["f_s[1]"] * 1.01)


    def test_deaths_take_their_amounts(self):
        """A dying cell takes its amounts with it, nothing more: between two
        consecutive steps the total falls by exactly the amounts the vanished
        cells had at the earlier step (cell/death deletes at the next step's
        start, after the dump of the step that chose them)."""
        data = random_tissue(self)
        run = self.run_lmp(CONSERVE + """
fix die all cell/death rate 0.3 seed 11
compute pu all property/atom d_u
dump du all custom 1 u.txt id c_pu
dump_modify du sort id format float %.17g
run 120
""", files={"cfg.data": data})
        frames = run.dump("u.txt")
        deaths = 0
        for a, b in zip(frames, frames[1:]):
            gone = ~np.isin(a["id"], b["id"])
            self.assertTrue(np.all(np.isin(b["id"], a["id"])))
            deaths += int(gone.sum())
            lost = a["c_pu"][gone].sum()
            np.testing.assert_allclose(b["c_pu"].sum(), a["c_pu"].sum() - lost,
                                       rtol=1e-13, atol=0, err_msg=f"step {b['step']}")
        self.assertGreater(deaths, 3)

    def test_deposits_start_empty(self):
        """Cells made by fix deposit start with 0: the total stays while the
        count grows."""
        data = random_tissue(self)
        rows = self.totals(1, data, "region dep block EDGE EDGE EDGE EDGE -0.1 0.1 units box\n"
                           "fix dep all deposit 4 1 20 4821 region dep near 0.4 attempt 200\n")
        self.assertGreater(rows[-1]["Atoms"], rows[0]["Atoms"])
        u = np.array([r["f_s[1]"] for r in rows])
        np.testing.assert_allclose(u, u[0], rtol=1e-13, atol=0)


def collier_rates(a, b, v, k=2, h=2):
    """Collier et al.'s model, Notch n' = f(<d>) - n, Delta d' = v (g(n) - d),
    f(x) = x^k / (a + x^k), g(x) = 1 / (1 + b x^h): the homogeneous state
    (d*, n*), f'(d*) g'(n*), and the growth rate of the lattice mode whose
    neighbour mean is -1/2 of the cell's value (the 3-colouring), the most
    unstable mode of the hexagonal lattice (doc/model.md)."""
    f = lambda x: x ** k / (a + x ** k)
    g = lambda x: 1 / (1 + b * x ** h)
    lo, hi = 1e-12, 1.0    # d - g(f(d)) increases from < 0 to > 0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if mid - g(f(mid)) < 0 else (lo, mid)
    d = 0.5 * (lo + hi)
    n = f(d)
    fp = k * a * d ** (k - 1) / (a + d ** k) ** 2
    gp = -b * h * n ** (h - 1) / (1 + b * n ** h) ** 2
    lam = -0.5
    disc = (1 - v) ** 2 + 4 * v * lam * fp * gp
    sigma = (-(1 + v) + math.sqrt(disc)) / 2 if disc >= 0 else -(1 + v) / 2
    return d, n, fp * gp, sigma


def collier_script(a, b, v, init_d, dt, steps, every):
    return hex_tissue(6, 3) + f"""
fix sp all property/atom d_d d_n
variable q atom round(y/{H!r})
variable p atom round(x/{A!r}-v_q/2)
variable c atom (((v_p-v_q+30)%3)==0)*3-1
variable d0 atom {init_d}
set group all d_d v_d0
fix s all cell/signal produce d_n hill 1.0 {math.sqrt(a)!r} 2 mean d_d degrade d_n 1.0 &
    produce d_d hillr {v!r} {b ** -0.5!r} 2 d_n degrade d_d {v!r}
compute pd all property/atom d_d
timestep {dt}
thermo_style custom step f_s[1] f_s[2]
thermo {every}
dump dd all custom {every} d.txt id x y c_pd
dump_modify dd sort id format float %.17g
run {steps}
"""


class LateralInhibition(LammpsTestCase):
    """The homogeneous state loses stability where f'(d*) g'(n*) < -2."""

    def growth(self, b):
        a, v = 0.01, 1.0
        d, n, fg, sigma = collier_rates(a, b, v)
        eps = 1e-6
        run = self.run_lmp(collier_script(a, b, v, f"{d!r}*(1+{eps}*v_c)", 0.01, 2000, 500)
                           + "")
        frames = run.dump("d.txt")
        # The mode's amplitude: class 0 against the other two.
        c = colour_of(frames[0]["x"], frames[0]["y"])
        amp = [f["c_pd"][c == 0].mean() - f["c_pd"][c != 0].mean() for f in frames]
        t = [f["step"] * 0.01 for f in frames]
        measured = math.log(abs(amp[-1]) / abs(amp[2])) / (t[-1] - t[2])
        return fg, sigma, measured

    def test_stable_below_threshold(self):
        fg, sigma, measured = self.growth(30.0)
        self.assertGreater(fg, -2.0)
        self.assertLess(sigma, -0.02)
        self.assertAlmostEqual(measured, sigma, delta=2e-3)

    def test_unstable_above_threshold(self):
        fg, sigma, measured = self.growth(100.0)
        self.assertLess(fg, -2.0)
        self.assertGreater(sigma, 0.02)
        self.assertAlmostEqual(measured, sigma, delta=2e-3)

    def pattern(self, init):
        run = self.run_lmp(collier_script(0.01, 100.0, 1.0, init, 0.05, 2000, 2000))
        f = run.dump("d.txt")[-1]
        x, y, dd = f["x"], f["y"], f["c_pd"]
        lx, ly = 6 * A, 6 * H
        dx = (x[:, None] - x[None, :] + lx / 2) % lx - lx / 2
        dy = (y[:, None] - y[None, :] + ly / 2) % ly - ly / 2
        near = (np.hypot(dx, dy) < 1.1 * A) & (np.hypot(dx, dy) > 0)
        high = dd > 0.5 * (dd.max() + dd.min())
        self.assertFalse((near & high[:, None] & high[None, :]).any(), "two high neighbours")
        self.assertGreater(dd.max(), 10 * dd.min())
        return high, colour_of(x, y)

    def test_ideal_pattern(self):
        high, c = self.pattern("0.07*(1+0.3*v_c)")
        self.assertEqual(high.sum(), 12)    # a third of 36
        self.assertTrue((high == (c == 0)).all())

    def test_variable_law_reads_the_neighbour_mean(self):
        """The Notch law written as an atom-style variable of compute
        cell/neighbor/mean gives what the Hill law with 'mean' gives (one
        substep per step: both read the values at the start of the step)."""
        script = collier_script(0.01, 100.0, 1.0, "0.07*(1+0.3*v_c)", 0.05, 400, 400)
        hill = self.run_lmp(script).dump("d.txt")[-1]["c_pd"]
        law = script.replace("produce d_n hill 1.0 0.1 2 mean d_d", "produce d_n v_f").replace(
            "fix s all", "compute md all cell/neighbor/mean d_d\n"
            "variable f atom c_md^2/(0.01+c_md^2)\nfix s all")
        self.assertIn("v_f", law)
        var = self.run_lmp(law).dump("d.txt")[-1]["c_pd"]
        self.assertGreater(np.ptp(hill), 0.5)
        np.testing.assert_allclose(var, hill, rtol=1e-10)

    def test_random_start_isolated(self):
        self.pattern("0.07*(1+0.1*((id*7919)%13-6)/6)")


class NeighborMean(LammpsTestCase):
    def test_against_the_pieces(self):
        """compute cell/neighbor/mean of a per-atom variable against the
        mean over compute vertex/local's rows weighted by the distance
        between each junction's ends."""
        run = self.run_lmp(lmptest.tissue(5, 4) + PAIR + """
displace_atoms all random 0.2 0.2 0 4821 units box
fix sp all property/atom d_u
variable u0 atom 1+((id*37)%11)
set group all d_u v_u0
variable w atom 2*x+y*y
compute m all cell/neighbor/mean d_u v_w
compute loc all vertex/local
compute pu all property/atom d_u
variable wv atom v_w
dump d all custom 1 a.txt id c_pu v_wv c_m[1] c_m[2]
dump_modify d sort id format float %.17g
dump l all local 1 l.txt c_loc[*]
dump_modify l format float %.17g
run 0
""")
        f = run.dump("a.txt")[0]
        rows = None
        lines = run.text("l.txt").split("\n")
        i = lines.index("ITEM: NUMBER OF ENTRIES")
        n = int(lines[i + 1])
        start = [k for k, line in enumerate(lines) if line.startswith("ITEM: ENTRIES")][0]
        rows = np.array([[float(w) for w in lines[start + 1 + k].split()] for k in range(n)])
        index = {int(t): k for k, t in enumerate(f["id"])}
        for col, mean in (("c_pu", "c_m[1]"), ("v_wv", "c_m[2]")):
            num = np.zeros(len(index))
            den = np.zeros(len(index))
            for r in rows:
                i, j = index[int(r[0])], index[int(r[1])]
                s = math.hypot(r[4] - r[2], r[5] - r[3])
                num[i] += s * f[col][j]
                den[i] += s
            np.testing.assert_allclose(f[mean], num / den, rtol=1e-12)


class OneStep(LammpsTestCase):
    """One explicit step of several species at once against the rate law
    evaluated from compute vertex/local's junctions (length = distance
    between each junction's ends):
    u' = u + dt (-k u + P sum_j s_ij (u_j - u_i) + Hill productions), each
    species with its own P and k, a Hill law of another species' neighbour
    mean and one of a field that is only read.  The cells do not move.
    Rows: the fields (a species has (P, k); None: read only) and the Hill
    laws (target, kind, vmax, K, n, mean, input)."""

    CASES = [
        ({"u": (1.0, 0.1)}, []),
        ({"a": (1.0, 0.1), "b": (0.3, 0.0), "c": (2.5, 0.7), "e": (0.0, 0.4)},
         [("a", "hill", 0.5, 0.8, 2.0, True, "c"), ("e", "hillr", 0.3, 1.2, 3.0, False, "b")]),
        ({"a": (0.7, 0.2), "b": (1.9, 0.05), "c": (0.2, 0.3), "e": (1.1, 0.0), "x": None},
         [("b", "hill", 0.4, 1.0, 2.0, True, "x"), ("a", "hillr", 0.6, 1.1, 1.5, True, "e")]),
    ]

    def check(self, fields, laws, dt=0.01):
        names = list(fields)
        args = []
        for n, pk in fields.items():
            if pk is not None:
                args.append(f"exchange d_{n} {pk[0]!r} degrade d_{n} {pk[1]!r}")
        for t, kind, vmax, K, expo, mean, inp in laws:
            args.append(f"produce d_{t} {kind} {vmax!r} {K!r} {expo!r} {'mean ' if mean else ''}d_{inp}")
        sets = "".join(f"variable i{n} atom 1.0+0.5*sin(0.37*id+{s})\nset group all d_{n} v_i{n}\n"
                       f"compute p{n} all property/atom d_{n}\n" for s, n in enumerate(names))
        cols = " ".join(f"c_p{n}" for n in names)
        run = self.run_lmp(lmptest.tissue(5, 4) + PAIR + f"""
displace_atoms all random 0.2 0.2 0 4821 units box
fix sp all property/atom {" ".join("d_" + n for n in names)}
{sets}fix s all cell/signal {" ".join(args)} substeps 1
compute loc all vertex/local
dump d all custom 1 a.txt id {cols}
dump_modify d sort id format float %.17g
dump l all local 1 l.txt c_loc[*]
dump_modify l format float %.17g
timestep {dt!r}
run 1
""")
        before, after = run.dump("a.txt")[0], run.dump("a.txt")[1]
        index = {int(t): k for k, t in enumerate(before["id"])}
        nc = len(index)
        S = np.zeros((nc, nc))
        for r in local_rows(run, "l.txt")[0]:
            S[index[int(r[0])], index[int(r[1])]] += math.hypot(r[4] - r[2], r[5] - r[3])
        W = S.sum(axis=1)
        u = {n: np.asarray(before[f"c_p{n}"]) for n in names}
        for n, pk in fields.items():
            want = u[n].copy()
            if pk is not None:
                P, k = pk
                rate = -k * u[n] + P * (S @ u[n] - W * u[n])
                for t, kind, vmax, K, expo, mean, inp in laws:
                    if t != n:
                        continue
                    x = (S @ u[inp]) / W if mean else u[inp]
                    xn = (x / K) ** expo
                    rate = rate + (vmax * xn / (1 + xn) if kind == "hill" else vmax / (1 + xn))
                want = u[n] + dt * rate
            np.testing.assert_allclose(after[f"c_p{n}"], want, rtol=1e-12, atol=1e-14,
                                       err_msg=f"d_{n}")
            if pk is not None and pk[0] > 0:
                self.assertGreater(np.abs(want - u[n]).max(), 1e-4)

    def test_species_together(self):
        for fields, laws in self.CASES:
            with self.subTest(fields=list(fields)):
                self.check(fields, laws)


def hill_limit(kind, vmax, K, n, x):
    """vmax x^n / (K^n + x^n) (hill) or vmax K^n / (K^n + x^n) (hillr) as
    the logistic function of z = n (ln x - ln K), which overflows for no
    exponent and no ratio: an implementation independent of the fix's."""
    if x == 0.0:
        return 0.0 if kind == "hill" else vmax
    z = n * (math.log(x) - math.log(K))
    if kind == "hillr":
        z = -z
    if z >= 0:
        return vmax / (1.0 + math.exp(-z))
    e = math.exp(z)
    return vmax * e / (1.0 + e)


class HillLaws(LammpsTestCase):
    """One step of u' = u + dt * law(x) from u = 0, a Hill law of every cell's
    own x, the cells each given one case: huge exponents and extreme ratios
    x / K (where (x/K)^n overflows, the law is vmax or 0), against
    hill_limit().  Rows: (kind, vmax, K, n, x)."""

    CASES = [
        ("hill", 1.0, 0.01, 200.0, 1.0), ("hillr", 1.0, 0.01, 200.0, 1.0),
        ("hill", 2.5, 1.0, 200.0, 0.5), ("hillr", 2.5, 1.0, 200.0, 0.5),
        ("hill", 1.0, 1.0, 200.0, 2.0), ("hillr", 1.0, 1.0, 200.0, 2.0),
        ("hill", 1.0, 1.0, 1e6, 1.001), ("hillr", 1.0, 1.0, 1e6, 1.001),
        ("hill", 1.0, 1.0, 1e6, 0.999), ("hillr", 1.0, 1.0, 1e6, 0.999),
        ("hill", 3.0, 1e-300, 2.0, 1e300), ("hillr", 3.0, 1e-300, 2.0, 1e300),
        ("hill", 3.0, 1e300, 2.0, 1e-300), ("hillr", 3.0, 1e300, 2.0, 1e-300),
        ("hill", 1.0, 1.0, 1e300, 1.5), ("hillr", 1.0, 1.0, 1e300, 1.5),
        ("hill", 1.0, 1.0, 3.0, 0.0), ("hillr", 1.0, 1.0, 3.0, 0.0),
        ("hill", 1.0, 0.3, 2.0, 0.3), ("hillr", 1.0, 0.3, 2.0, 0.3),
        ("hill", 0.7, 0.2, 2.5, 0.45), ("hillr", 0.7, 0.2, 2.5, 0.45),
        ("hill", 1.0, 1.0, 0.5, 1e300), ("hillr", 1.0, 1.0, 0.5, 1e300),
    ]

    def test_limits(self):
        n = len(self.CASES)
        fields = " ".join(f"d_u{k} d_x{k}" for k in range(n))
        laws = " ".join(f"produce d_u{k} {kind} {vmax!r} {K!r} {e!r} d_x{k}"
                        for k, (kind, vmax, K, e, x) in enumerate(self.CASES))
        sets = "".join(f"set group all d_x{k} {x!r}\n" for k, (_, _, _, _, x) in enumerate(self.CASES))
        cols = " ".join(f"d_u{k}" for k in range(n))
        run = self.run_lmp(hex_tissue(2, 1) + f"""fix sp all property/atom {fields}
{sets}fix s all cell/signal {laws} substeps 1
timestep 1.0
run 1
write_dump all custom u.txt id {cols} modify format float %.17g
""")
        f = run.dump("u.txt")[0]
        for k, case in enumerate(self.CASES):
            want = hill_limit(*case)
            got = f[f"d_u{k}"]
            with self.subTest(case=case):
                np.testing.assert_allclose(got, want, rtol=1e-9, atol=0)
        # the limits themselves, where (x/K)^n is far beyond double
        self.assertEqual(f["d_u0"][0], 1.0)
        self.assertEqual(f["d_u1"][0], 0.0)
        self.assertEqual(f["d_u10"][0], 3.0)


class ImplicitExact(LammpsTestCase):
    """One backward-Euler step (implicit yes) of exchange and degradation
    against the exact solution of a small tissue: with uniform degradation
    the system (1 + dt k) x + dt P L x = u shares the eigenvectors of the
    junction Laplacian L (built from compute vertex/local's junctions), so
    x = V diag(1 / (1 + dt k + dt P lambda)) V^T u, the zero eigenvalues of
    L (one per unconnected patch) set to 0 exactly.  Steps from 0.1 to 1e17
    exchange times, on one patch (group all) and on two patches (a group of
    three rows of cells), on 1 and 2 ranks: every new value to 1e-12 of the
    largest, the total of pure exchange to round-off.  Rows: (dt P, k,
    group, ranks)."""

    ALL = "group g type 1\n"
    # rows 0 and 2-3 of the 6 rows: two patches that share no junction
    PATCHES = "variable gv atom (y<0.5)||(y>1.5&&y<3.0)\ngroup g variable gv\n"
    CASES = [(0.1, 0.0, ALL, 1), (1e4, 0.0, ALL, 1), (1e8, 0.3, ALL, 1), (1e12, 0.0, ALL, 2),
             (1e17, 0.0, ALL, 1), (1e17, 1.0, ALL, 2), (1e4, 0.0, PATCHES, 1),
             (1e12, 0.5, PATCHES, 1), (1e15, 0.0, PATCHES, 2)]

    def script(self, dtP, k, group):
        return lmptest.tissue(4, 3) + PAIR + f"""displace_atoms all random 0.1 0.1 0 4821 units box
fix sp all property/atom d_u
variable u0 atom 1+((id*37)%11)
set group all d_u v_u0
{group}fix s g cell/signal exchange d_u 1.0 degrade d_u {k!r} implicit yes
timestep {dtP!r}
compute pu all property/atom d_u
compute loc all vertex/local
variable in atom gmask(g)
dump d all custom 1 u.txt id c_pu v_in
dump_modify d sort id format float %.17g
dump l all local 1 l.txt c_loc[*]
dump_modify l format float %.17g
thermo_style custom step f_s[1]
thermo_modify format float %.17g
run 1
"""

    def exact(self, run, dtP, k):
        before, after = run.dump("u.txt")[:2]
        index = {int(t): q for q, t in enumerate(before["id"])}
        taken = before["v_in"] > 0
        n = len(index)
        S = np.zeros((n, n))
        for r in local_rows(run, "l.txt")[0]:
            S[index[int(r[0])], index[int(r[1])]] += math.hypot(r[4] - r[2], r[5] - r[3])
        S = 0.5 * (S + S.T) * np.outer(taken, taken)
        lam, V = np.linalg.eigh(np.diag(S.sum(axis=1)) - S)
        lam[np.abs(lam) < 1e-10] = 0.0
        u = before["c_pu"]
        x = V @ ((V.T @ u) / (1.0 + dtP * k + dtP * lam))
        x[~taken] = u[~taken]
        return u, x, after["c_pu"], taken

    @nprocs(2)
    def test_against_the_exact_step(self):
        for dtP, k, group, ranks in self.CASES:
            with self.subTest(dtP=dtP, k=k, patches=group == self.PATCHES, ranks=ranks):
                run = self.run_lmp(self.script(dtP, k, group), nprocs=ranks)
                u, x, got, taken = self.exact(run, dtP, k)
                self.assertGreater(taken.sum(), 5)
                self.assertNotIn("WARNING: fix cell/signal", run.output)
                np.testing.assert_allclose(got, x, rtol=0, atol=1e-12 * np.abs(x).max())
                if k == 0.0:
                    self.assertAlmostEqual(got.sum(), u.sum(), delta=1e-13 * u.sum())

    def test_limit_is_named(self):
        """Two patches of different means 1e17 exchange times apart: beyond
        double precision, an error that names the step's dt P."""
        run = self.run_lmp(self.script(1e17, 0.0, self.PATCHES), ok=False)
        self.assertLammpsError(run, "the implicit step of d_u at step 1", "dt P = 1e+17",
                               "use a shorter step")


class Restart(LammpsTestCase):
    def test_continues_exactly(self):
        body = hex_tissue(4, 4) + """
displace_atoms all random 0.2 0.2 0 4821 units box
fix sp all property/atom d_u
variable u0 atom 1+((id*37)%11)
set group all d_u v_u0
"""
        law = """fix move all brownian 1.0 1 gamma_t 1.0 rng none
variable src atom 0.1*(id%3)
fix s all cell/signal exchange d_u 2.0 degrade d_u 0.3 produce d_u v_src produce d_u hillr 1 2 2 mean d_u
timestep 0.02
compute pu all property/atom d_u
"""
        out = """dump d all custom 40 u.txt id c_pu
dump_modify d sort id format float %.17g first yes
run {n}
"""
        whole = self.run_lmp(body + law + out.format(n=40))
        second = self.run_lmp(body + law + """run 20
write_restart r.bin
clear
read_restart r.bin
fix sp all property/atom d_u
pair_style vertex/voronoi 3.0
pair_coeff * * quadratic 1.0 1.0 0.1 3.7
""" + law + out.format(n=20).replace("first yes", "first no"))
        a = whole.dump("u.txt")[-1]["c_pu"]
        b = second.dump("u.txt")[-1]["c_pu"]
        np.testing.assert_array_equal(a, b)


class Adapt(LammpsTestCase):
    def test_area0_follows_species(self):
        """d_area0 = 0.5 + d_u every step: the area of one cell holding more
        than the others grows to its preferred area (the pe's A term)."""
        run = self.run_lmp(hex_tissue(4, 4) + """
fix sp all property/atom d_u d_area0
set group all d_u 0.5
set atom 1 d_u 1.0
set group all d_area0 1.0
compute pu all property/atom d_u
variable a0 atom 0.5+c_pu
fix ad all cell/adapt 1 d_area0 v_a0
fix move all brownian 1.0 1 gamma_t 1.0 rng none
compute v all vertex/atom
timestep 0.05
dump d all custom 1000 a.txt id c_v[1] d_area0
dump_modify d sort id format float %.17g
run 1000
""")
        f = run.dump("a.txt")[-1]
        self.assertEqual(f["d_area0"][0], 1.5)
        self.assertEqual(f["d_area0"][1], 1.0)
        self.assertGreater(f["c_v[1]"][0], 1.2)

    def test_division_rate_follows_a_variable(self):
        """fix cell/divide rate d_rate: each cell's own rate.  With rate dt = 1
        a cell divides for certain, with 0 never: fix cell/adapt switches
        the rate of cells 1..5 from 0 to 1/dt at the end of step 4; the
        fix decides then and the five divide at step 5 (and not before),
        the others never; cells of rate 0 keep their base d_area0 with
        growth linear (an infinite cycle)."""
        run = self.run_lmp(hex_tissue(4, 4) + """
fix sp all property/atom d_rate d_area0
set group all d_rate 0.0
set group all d_area0 1.0
variable r atom (id<=5)*(step>=4)*100.0
fix ad all cell/adapt 1 d_rate v_r
fix div all cell/divide rate d_rate seed 5 growth linear
fix move all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.01
thermo_style custom step atoms
thermo 1
dump d all custom 1 a.txt id f_div[2] f_div[5] d_area0
dump_modify d sort id
run 6
""")
        atoms = {int(r["Step"]): int(r["Atoms"]) for r in thermo_rows(run)}
        # step 6: the five again, not their new daughters (IDs 33..37, which
        # the variable gives rate 0)
        self.assertEqual([atoms[k] for k in range(7)], [32] * 5 + [37, 42])
        f = run.dump("a.txt")[5]
        self.assertEqual(sorted(f["f_div[5]"][f["f_div[2]"] == 1].astype(int)), sorted(2 * [1, 2, 3, 4, 5]))
        others = (f["id"] > 5) & (f["id"] <= 32)
        self.assertTrue(np.all(f["f_div[2]"][others] == 0))
        np.testing.assert_array_equal(f["d_area0"][others], 1.0)

    def test_bad_division_rate_is_named(self):
        run = self.run_lmp(hex_tissue(3, 3) + """
fix sp all property/atom d_rate
set group all d_rate 0.1
set atom 4 d_rate -1.0
fix div all cell/divide rate d_rate seed 5
run 1
""", ok=False)
        self.assertLammpsError(run, "rate d_rate of cell 4 is -1", ">= 0")
        run = self.run_lmp(hex_tissue(3, 3) + "fix div all cell/divide rate d_nope seed 5\nrun 1\n",
                           ok=False)
        self.assertLammpsError(run, "rate d_nope: no such per-atom property")


class Errors(LammpsTestCase):
    def fails(self, law, *fragments, setup=""):
        run = self.run_lmp(hex_tissue(4, 4) + """
fix sp all property/atom d_u
set group all d_u 1.0
""" + setup + law + "\nrun 20\n", ok=False)
        self.assertLammpsError(run, *fragments)

    def test_unknown_species(self):
        self.fails("fix s all cell/signal exchange d_x 1.0", "d_x", "unknown species",
                   "property/atom d_x")

    def test_negative_rate(self):
        self.fails("fix s all cell/signal degrade d_u -1", "rate k must be >= 0", "-1")

    def test_nan_law(self):
        self.fails("fix s all cell/signal produce d_u v_bad", "v_bad", "cell 5", "step 1",
                   setup="variable bad atom (id==5)*1e308*10\n")

    def test_negative_law(self):
        self.fails("fix s all cell/signal produce d_u v_neg", "d_u of cell 7", "produce d_u v_neg",
                   setup="variable neg atom -100*(id==7)\n")

    def test_too_few_substeps(self):
        self.fails("fix s all cell/signal exchange d_u 100 substeps 1", "substeps auto",
                   setup="set atom 3 d_u 5.0\n")

    def test_adapt_unknown_property(self):
        self.fails("fix ad all cell/adapt 1 d_perim0 v_p", "d_perim0 is no per-atom property",
                   "property/atom d_perim0", setup="variable p atom 3.8\n")

    def test_mean_unknown_property(self):
        self.fails("compute m all cell/neighbor/mean d_x", "d_x", "property/atom d_x")

    def test_adapt_nonpositive_area(self):
        self.fails("fix ad all cell/adapt 1 d_area0 v_a0", "d_area0", "cell 4", "step 0",
                   setup="fix p2 all property/atom d_area0\nset group all d_area0 1.0\n"
                         "variable a0 atom 1-(id==4)\n")


class Bath(LammpsTestCase):
    def test_finite_cells_steady_state(self):
        """Finite cells exchange across their contact edges and with a bath
        across their free arcs; the steady state against the linear system
        (L + diag(Pb F + k)) u = Pb F cb solved by numpy, with L built from
        compute vertex/local's contact edges and F from its free arcs."""
        self.steady_state("", 0.05, 1200)

    def test_finite_cells_steady_state_implicit(self):
        """The same with implicit steps 40 times the exchange time (the
        steady state of backward Euler is that of the laws)."""
        self.steady_state(" implicit yes", 40.0, 60)

    def steady_state(self, extra, dt, steps):
        from feature_models import local_rows, model_script
        P, Pb, cb, k = 1.0, 2.0, 1.5, 0.5
        run = self.run_lmp(model_script("finite_open") + f"""
fix sp all property/atom d_u
set group all d_u 0.0
fix s all cell/signal exchange d_u {P} bath d_u {Pb} {cb} degrade d_u {k}{extra}
timestep {dt}
run {steps}
compute pu all property/atom d_u
compute l all vertex/local
dump d all custom 1 u.txt id c_pu
dump_modify d sort id format float %.17g
dump e all local 1 l.txt c_l[1] c_l[2] c_l[7]
dump_modify e format float %.17g
run 0
""")
        f = run.dump("u.txt")[-1]
        rows = local_rows(run, "l.txt")[-1]
        index = {int(t): n for n, t in enumerate(f["id"])}
        n = len(index)
        M = np.diag(np.full(n, k))
        b = np.zeros(n)
        for cell, nb, size in rows:
            i = index[int(cell)]
            if int(nb) == 0:    # a free arc
                M[i, i] += Pb * size
                b[i] += Pb * size * cb
            else:
                j = index[int(nb)]
                M[i, i] += P * size
                M[i, j] -= P * size
        self.assertGreater(b.sum(), 0)
        self.assertGreater((b == 0).sum(), 0)    # inner cells reached only by exchange
        np.testing.assert_allclose(f["c_pu"], np.linalg.solve(M, b), rtol=1e-9)


lmptest.main()
