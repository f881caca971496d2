#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""fix polarity in 'dimension 3' (a unit vector per cell), against results
computed here: the forward-Euler rotation of each alignment term (neighbours
from LAMMPS's compute voronoi/atom, groove, active drift), the statistics of
rotational diffusion on the sphere, and 1 rank == 2 ranks."""

import math

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

FREE = """
units lj
atom_style dipole
boundary p p p
region box block 0 20 0 20 0 20
create_box 1 box
mass 1 1.0
"""

DUMP = ("dump d all custom {every} pol.dump id x y z vx vy vz mux muy muz\n"
        "dump_modify d sort id format float %.17g\n")


def unit(frame):
    n = np.column_stack([frame["mux"], frame["muy"], frame["muz"]])
    return n / np.linalg.norm(n, axis=1)[:, None]


def rotate(n, w):
    """Rodrigues rotation of the unit vectors n (rows) about w by |w|."""
    a = np.linalg.norm(w, axis=1)
    out = n.copy()
    m = a > 0
    k = w[m] / a[m][:, None]
    c, s = np.cos(a[m])[:, None], np.sin(a[m])[:, None]
    nm = n[m]
    out[m] = nm * c + np.cross(k, nm) * s + k * (k * nm).sum(1)[:, None] * (1 - c)
    return out


class GrooveAndDrift(LammpsTestCase):
    """One free cell: n turns towards the groove g = (cos phi, sin phi, 0) by
    n <- rot(n, dt/gamma_R n x J_G (n.g) g), and moves with v = f_a n / gamma_T."""

    def test_recursion(self):
        dt, JG, gR, fa, phi = 0.01, 2.0, 0.7, 0.3, 30.0
        n0 = np.array([0.2, -0.5, 0.8])
        n0 /= np.linalg.norm(n0)
        script = FREE + "create_atoms 1 single 5 5 5 units box\n"
        script += "set atom 1 dipole %r %r %r\n" % tuple(n0)
        script += f"""
timestep {dt}
fix p all polarity {fa} {gR} groove {JG} {phi}
fix b all brownian 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(every=1) + "run 200\n"
        frames = self.run_lmp(script).dump("pol.dump")
        g = np.array([math.cos(math.radians(phi)), math.sin(math.radians(phi)), 0.0])
        n = n0[None, :]
        np.testing.assert_allclose(unit(frames[0]), n, atol=1e-14)
        for k, fr in enumerate(frames[1:], start=1):
            v = np.array([fr["vx"][0], fr["vy"][0], fr["vz"][0]])
            np.testing.assert_allclose(v, fa * n[0], atol=1e-12, err_msg=f"step {k}")
            h = JG * (n @ g)[:, None] * g[None, :]
            n = rotate(n, dt / gR * np.cross(n, h))
            np.testing.assert_allclose(unit(fr), n, atol=1e-12, err_msg=f"step {k}")
        self.assertGreater(abs(n[0] @ g), 0.99)    # aligned with the groove


class Neighbours(LammpsTestCase):
    """J_S in a 3D tissue: one step n_i <- rot(n_i, dt/gamma_R n_i x J_S sum_j n_j)
    over the Voronoi neighbours j, taken from compute voronoi/atom (voro++)."""

    def test_one_step(self):
        dt, JS, gR = 0.01, 1.5, 0.8
        run = self.run_lmp("""
units lj
atom_style dipole
boundary p p p
lattice sc 1.0
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
mass 1 1.0
displace_atoms all random 0.3 0.3 0.3 4821 units box
set group all dipole/random 5531 1.0
pair_style vertex/voronoi 3.0
pair_coeff * * quadratic 1.0 1.0 1.0 5.6
compute vl all voronoi/atom neighbors yes
dump n all local 1000 n.dump c_vl[1] c_vl[2] c_vl[3]
""" + f"""
timestep {dt}
fix p all polarity 0.0 {gR} neighbor {JS}
fix b all brownian 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(every=1) + "run 1\n")
        first, second = run.dump("pol.dump")
        rows = run.text("n.dump").split("ITEM: ENTRIES")[1].strip().split("\n")[1:]
        ids = list(first["id"])
        n0 = unit(first)
        field = np.zeros_like(n0)
        for line in rows:
            a, b, area = (float(w) for w in line.split())
            if area > 1e-9:
                field[ids.index(int(a))] += JS * n0[ids.index(int(b))]
        expect = rotate(n0, dt / gR * np.cross(n0, field))
        self.assertGreater(np.abs(expect - n0).max(), 1e-3)
        np.testing.assert_allclose(unit(second), expect, atol=1e-12)


class Noise(LammpsTestCase):
    """D_r alone: rotational diffusion on the sphere, <|n_{k+1} - n_k|^2> =
    4 D_r dt per step and <n(t).n(0)> = exp(-2 D_r t); initial directions
    uniform on the sphere; the same on 1 and 2 ranks."""

    D, DT, STEPS = 0.5, 0.01, 100

    def noisy(self, nprocs, every):
        data = self.run_lmp(FREE + "create_atoms 1 random 2000 8812 box\nwrite_data cfg.data\n"
                            ).text("cfg.data")
        script = FREE.replace("region box block 0 20 0 20 0 20\ncreate_box 1 box\n",
                              "read_data cfg.data\n") + f"""
timestep {self.DT}
fix p all polarity 0.0 1.0 noise {self.D} 2207
fix b all brownian 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(every=every) + f"run {self.STEPS}\n"
        return self.run_lmp(script, nprocs=nprocs, files={"cfg.data": data}).dump("pol.dump")

    def test_statistics(self):
        frames = self.noisy(1, 1)
        n = [unit(f) for f in frames]
        n0 = n[0]
        N = len(n0)
        # uniform start: each component has mean 0 and variance 1/3
        self.assertLess(np.abs(n0.mean(0)).max(), 5 / math.sqrt(3 * N))
        step = np.concatenate([((b - a) ** 2).sum(1) for a, b in zip(n, n[1:])])
        expect = 4 * self.D * self.DT
        self.assertAlmostEqual(step.mean() / expect, 1.0, delta=0.03)
        t = self.STEPS * self.DT
        corr = (n[-1] * n0).sum(1)
        self.assertAlmostEqual(corr.mean(), math.exp(-2 * self.D * t), delta=5 * corr.std() / math.sqrt(N))

    @nprocs(2)
    def test_rank_independent(self):
        one = self.noisy(1, self.STEPS)[-1]
        two = self.noisy(2, self.STEPS)[-1]
        np.testing.assert_allclose(unit(two), unit(one), atol=1e-12)


class ActiveTissue(LammpsTestCase):
    """An active 3D tissue (vertex forces, active force, neighbour alignment,
    noise): 1 rank == 2 ranks, and run 10 + run 10 == run 20."""

    def data(self):
        return self.run_lmp("""
units lj
atom_style dipole
boundary p p p
lattice sc 1.0
region box block 0 4 0 4 0 4
create_box 1 box
create_atoms 1 box
mass 1 1.0
displace_atoms all random 0.3 0.3 0.3 4821 units box
write_data cfg.data
""").text("cfg.data")

    SETUP = """
units lj
atom_style dipole
boundary p p p
read_data cfg.data
pair_style vertex/voronoi 3.0
pair_coeff * * quadratic 1.0 1.0 1.0 5.6
timestep 0.01
fix p all polarity 0.5 1.0 neighbor 1.0 noise 0.3 991
fix b all brownian 1.0 1 gamma_t 1.0 rng none
"""
    COLS = ("x", "y", "z", "mux", "muy", "muz")

    @nprocs(2)
    def test_ranks_and_split_run(self):
        data = self.data()
        straight = self.run_lmp(self.SETUP + DUMP.format(every=20) + "run 20\n",
                                files={"cfg.data": data}).dump("pol.dump")[-1]
        two = self.run_lmp(self.SETUP + DUMP.format(every=20) + "run 20\n", nprocs=2,
                           files={"cfg.data": data}).dump("pol.dump")[-1]
        split = self.run_lmp(self.SETUP + DUMP.format(every=20) + "run 10\nrun 10\n",
                             files={"cfg.data": data}).dump("pol.dump")[-1]
        self.assertEqual(split["step"], 20)
        moved = np.abs(unit(straight) - unit(self.run_lmp(self.SETUP + DUMP.format(every=1) + "run 0\n",
                                                          files={"cfg.data": data}).dump("pol.dump")[0])).max()
        self.assertGreater(moved, 1e-2)
        for col in self.COLS:
            np.testing.assert_allclose(two[col], straight[col], rtol=0, atol=1e-10, err_msg=col)
            np.testing.assert_allclose(split[col], straight[col], rtol=0, atol=1e-12, err_msg=col)


class Orders(LammpsTestCase):
    """f_ID[1] = |<n>|, f_ID[2] = <P2(n.g)> in 3D, computed here."""

    def test_orders(self):
        run = self.run_lmp(FREE + "create_atoms 1 random 50 1212 box\n" + """
set group all dipole/random 77 1.0
fix p all polarity 0.0 1.0 groove 0.0 25
fix b all brownian 1.0 1 gamma_t 1.0 rng none
thermo_style custom step f_p[1] f_p[2]
thermo_modify format float %.15g
""" + DUMP.format(every=1) + "run 0\n")
        fr = run.dump("pol.dump")[0]
        n = unit(fr)
        g = np.array([math.cos(math.radians(25)), math.sin(math.radians(25)), 0.0])
        row = [float(w) for w in run.stdout.split("Step")[1].splitlines()[1].split()]
        self.assertAlmostEqual(row[1], np.linalg.norm(n.mean(0)), delta=1e-12)
        self.assertAlmostEqual(row[2], (1.5 * (n @ g) ** 2 - 0.5).mean(), delta=1e-12)


lmptest.main()
