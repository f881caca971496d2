#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""fix polarity through tessera-lmp, against independent results: the exact
forward-Euler recursion of each torque term computed here, the analytic
groove relaxation, the active drift f_a n / gamma_T, the statistics of the
rotational noise, 1 rank == 2 ranks, restart == uninterrupted, and errors."""

import math

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

FREE = """
dimension 2
units lj
atom_style dipole
boundary p p p
region box block 0 20 0 20 -0.5 0.5
create_box 1 box
mass 1 1.0
"""

def hex_vertex_model(nx, ny):
    """A hexagonal tissue of nx x ny lattice cells with the vertex model."""
    return lmptest.tissue(nx, ny) + """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
"""

DUMP = ("dump d all custom {every} pol.dump id x y xu yu vx vy mux muy\n"
        "dump_modify d sort id format float %.17g\n")


def angles(frame):
    return np.arctan2(frame["muy"], frame["mux"])


def wrap(a):
    return (a + np.pi) % (2 * np.pi) - np.pi


class Groove(LammpsTestCase):
    """J_G alone: theta_{n+1} = theta_n - dt J_G/gamma_R sin(th-phi) cos(th-phi),
    exactly; and the forward-Euler solution approaches the analytic one
    tan(th - phi) = tan(th0 - phi) exp(-J_G t / gamma_R) as O(dt)."""

    def run_groove(self, dt, steps, JG=2.0, gR=0.5, phi_deg=30.0):
        th0 = np.linspace(-3.0, 3.0, 13)
        script = FREE
        for k, th in enumerate(th0):
            script += "create_atoms 1 single %g 5 0 units box\n" % (1 + 1.4 * k)
        for k, th in enumerate(th0):
            script += "set atom %d dipole %r %r 0\n" % (k + 1, math.cos(th), math.sin(th))
        script += f"""
timestep {dt}
fix p all polarity 0.0 {gR} groove {JG} {phi_deg}
fix b all brownian 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(every=steps) + f"run {steps}\n"
        run = self.run_lmp(script)
        return th0, angles(run.dump("pol.dump")[-1])

    def test_euler_recursion(self):
        dt, steps, JG, gR, phi = 0.01, 50, 2.0, 0.5, math.radians(30.0)
        th0, th = self.run_groove(dt, steps, JG, gR, 30.0)
        ref = th0.copy()
        for _ in range(steps):
            ref = ref - dt * JG / gR * np.sin(ref - phi) * np.cos(ref - phi)
        np.testing.assert_allclose(wrap(th - ref), 0.0, atol=1e-12)

    def test_analytic_relaxation(self):
        JG, gR, phi, t = 2.0, 0.5, math.radians(30.0), 0.5
        errors = []
        for dt in (0.01, 0.005):
            th0, th = self.run_groove(dt, int(round(t / dt)), JG, gR, 30.0)
            exact = phi + np.arctan(np.tan(th0 - phi) * math.exp(-JG * t / gR))
            # tan is pi-periodic: compare nematic angles
            errors.append(np.abs(wrap(2 * (th - exact)) / 2).max())
        self.assertLess(errors[0], 0.05)
        self.assertAlmostEqual(errors[0] / errors[1], 2.0, delta=0.3)   # first order


class ActiveDrift(LammpsTestCase):
    """Without torques the polarity is fixed and every cell moves with
    v0 = f_a / gamma_T along it (thesis erratum: not f_a / gamma_R)."""

    def test_drift(self):
        fa, gT, gR, dt, steps = 0.7, 2.0, 5.0, 0.01, 40
        script = FREE + "create_atoms 1 random 30 4412 box\n"
        script += "set group all dipole/random 881 1.0\n"
        script += f"""
timestep {dt}
fix p all polarity {fa} {gR}
fix b all brownian 1.0 1 gamma_t {gT} rng none
""" + DUMP.format(every=steps) + f"run {steps}\n"
        first, last = self.run_lmp(script).dump("pol.dump")
        n = np.column_stack([first["mux"], first["muy"]])
        n /= np.linalg.norm(n, axis=1)[:, None]
        disp = np.column_stack([last["xu"] - first["xu"], last["yu"] - first["yu"]])
        np.testing.assert_allclose(disp, fa / gT * dt * steps * n, atol=1e-12)
        v = np.column_stack([last["vx"], last["vy"]])
        np.testing.assert_allclose(v, fa / gT * n, atol=1e-12)


class Neighbours(LammpsTestCase):
    """J_S on a hexagonal lattice (zero vertex forces): one step of
    theta_i += dt/gamma_R J_S sum_j sin(theta_j - theta_i) over the six
    Voronoi neighbours, which are found here from the lattice geometry."""

    def test_one_step(self):
        dt, JS, gR = 0.01, 1.5, 0.8
        run = self.run_lmp(hex_vertex_model(6, 3) + f"""
set group all dipole/random 5531 1.0
timestep {dt}
fix p all polarity 0.0 {gR} neighbor {JS}
fix b all brownian 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(every=1) + "run 1\n")
        first, second = run.dump("pol.dump")
        box = first["box"]
        L = box[:2, 1] - box[:2, 0]
        xy = np.column_stack([first["x"], first["y"]])
        th0 = angles(first)
        ref = th0.copy()
        a = 1.0745699318741  # lattice hex 1.0: nearest-neighbour distance
        for i in range(len(xy)):
            d = xy - xy[i]
            d -= L * np.round(d / L)
            r = np.hypot(d[:, 0], d[:, 1])
            nb = np.where((r > 0.5 * a) & (r < 1.2 * a))[0]
            self.assertEqual(len(nb), 6)
            ref[i] += dt / gR * JS * np.sin(th0[nb] - th0[i]).sum()
        np.testing.assert_allclose(wrap(angles(second) - ref), 0.0, atol=1e-12)


class VelocityAlignment(LammpsTestCase):
    """J_V turns the polarity towards the velocity: with a constant push
    along +x, theta follows theta_{n+1} = theta_n - dt J_V/gamma_R sin(theta_n - psi_n)
    with psi_n the direction of v_n = (F + f_a n_n)/gamma_T."""

    def test_turns_to_velocity(self):
        dt, JV, gR, fa, F = 0.01, 3.0, 1.0, 0.2, 1.0
        th_init = 2.5
        script = FREE + "create_atoms 1 single 5 5 0 units box\n"
        script += "set atom 1 dipole %r %r 0\n" % (math.cos(th_init), math.sin(th_init))
        script += f"""
timestep {dt}
fix f all addforce {F} 0 0
fix p all polarity {fa} {gR} velocity {JV}
fix b all brownian 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(every=1) + "run 100\n"
        frames = self.run_lmp(script).dump("pol.dump")
        # Step k's torque uses the velocity of frame k-1 and the angle of
        # frame k-1; frame k's velocity is (F + f_a n(theta of frame k-1)) / gamma_T.
        th = th_init
        self.assertAlmostEqual(float(wrap(angles(frames[0])[0] - th)), 0.0, delta=1e-12)
        v_prev = (frames[0]["vx"][0], frames[0]["vy"][0])
        for k, fr in enumerate(frames[1:], start=1):
            vx, vy = fr["vx"][0], fr["vy"][0]
            self.assertAlmostEqual(vx, F + fa * math.cos(th), delta=1e-12)
            self.assertAlmostEqual(vy, fa * math.sin(th), delta=1e-12)
            if v_prev != (0.0, 0.0):
                th = th - dt * JV / gR * math.sin(th - math.atan2(v_prev[1], v_prev[0]))
            self.assertAlmostEqual(float(wrap(angles(fr)[0] - th)), 0.0, delta=1e-12,
                                   msg="step %d" % k)
            v_prev = (vx, vy)
        self.assertLess(abs(th), 0.5 * th_init)    # turned towards +x


class Noise(LammpsTestCase):
    """D_r alone: increments of theta are Gaussian with variance 2 D_r dt;
    the same on 1 and 2 ranks (the random numbers depend on atom ID and step)."""

    def noisy(self, nprocs):
        # write_data from one rank: the same atom IDs for both rank counts
        data = self.run_lmp(FREE + "create_atoms 1 random 400 8812 box\nwrite_data cfg.data\n"
                            ).text("cfg.data")
        script = FREE.replace("region box block 0 20 0 20 -0.5 0.5\ncreate_box 1 box\n",
                              "read_data cfg.data\n") + """
timestep 0.01
fix p all polarity 0.0 1.0 noise 0.5 2207
fix b all brownian 1.0 1 gamma_t 1.0 rng none
""" + DUMP.format(every=1) + "run 20\n"
        return self.run_lmp(script, nprocs=nprocs, files={"cfg.data": data}).dump("pol.dump")

    def test_statistics(self):
        frames = self.noisy(1)
        inc = np.concatenate([wrap(angles(b) - angles(a)) for a, b in zip(frames, frames[1:])])
        var = 2 * 0.5 * 0.01
        n = len(inc)
        self.assertAlmostEqual(inc.mean(), 0.0, delta=5 * math.sqrt(var / n))
        self.assertAlmostEqual(inc.var() / var, 1.0, delta=5 * math.sqrt(2.0 / n))
        kurt = ((inc - inc.mean()) ** 4).mean() / inc.var() ** 2
        self.assertAlmostEqual(kurt, 3.0, delta=0.3)

    def test_initial_angles_uniform(self):
        frames = self.noisy(1)
        th = angles(frames[0])
        n = len(th)
        self.assertLess(abs(np.cos(th).mean()), 5 / math.sqrt(2 * n))
        self.assertLess(abs(np.sin(th).mean()), 5 / math.sqrt(2 * n))
        self.assertLess(abs(np.cos(2 * th).mean()), 5 / math.sqrt(2 * n))

    @nprocs(2)
    def test_rank_independent(self):
        one, two = self.noisy(1), self.noisy(2)
        for a, b in zip(one, two):
            np.testing.assert_allclose(a["x"], b["x"], atol=1e-12)
            np.testing.assert_allclose(wrap(angles(a) - angles(b)), 0.0, atol=1e-12)


class ActiveTissue(LammpsTestCase):
    """A 200-step active run with all alignment terms and noise on a vertex
    model tissue: identical on 1 and 2 ranks, and restart == uninterrupted."""

    SETUP = """
dimension 2
units lj
atom_style dipole
boundary p p p
read_data cfg.data
pair_style vertex/voronoi 3.5
pair_coeff * * 1.0 1.0 0.1 -0.56
timestep 0.01
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix p all polarity 0.05 1.0 neighbor 1.0 groove 0.5 20 velocity 0.3 noise 0.2 991
thermo_style custom step pe f_p[1] f_p[2]
thermo 50
"""

    def data(self):
        make = self.run_lmp(hex_vertex_model(10, 5) +
                            "displace_atoms all random 0.1 0.1 0 4821 units box\n"
                            "write_data cfg.data\n")
        return make.text("cfg.data")

    @nprocs(2)
    def test_ranks(self):
        data = self.data()
        script = self.SETUP + DUMP.format(every=200) + "run 200\n"
        one = self.run_lmp(script, files={"cfg.data": data}).dump("pol.dump")[-1]
        two = self.run_lmp(script, nprocs=2, files={"cfg.data": data}).dump("pol.dump")[-1]
        for col in ("xu", "yu", "mux", "muy"):
            np.testing.assert_allclose(one[col], two[col], rtol=0, atol=1e-12)

    def test_split_run(self):
        """run 100 + run 100 == run 200 (the second setup recomputes forces)."""
        data = self.data()
        one = self.run_lmp(self.SETUP + DUMP.format(every=200) + "run 200\n",
                           files={"cfg.data": data}).dump("pol.dump")[-1]
        two = self.run_lmp(self.SETUP + DUMP.format(every=200) + "run 100\nrun 100\n",
                           files={"cfg.data": data}).dump("pol.dump")[-1]
        for col in ("xu", "yu", "mux", "muy"):
            np.testing.assert_allclose(one[col], two[col], rtol=0, atol=1e-12)

    def test_restart(self):
        data = self.data()
        straight = self.run_lmp(self.SETUP + DUMP.format(every=200) + "run 200\n",
                                files={"cfg.data": data}).dump("pol.dump")[-1]
        first = self.run_lmp(self.SETUP + "run 100\nwrite_restart state.rst\n",
                             files={"cfg.data": data})
        with open(first.path("state.rst"), "rb") as f:
            restart = f.read()
        script = self.SETUP.replace("read_data cfg.data", "read_restart state.rst")
        script = script.replace("pair_style vertex/voronoi 3.5\npair_coeff * * 1.0 1.0 0.1 -0.56\n", "")
        d = self.new_dir()
        import os
        import shutil
        import subprocess
        with open(os.path.join(d, "state.rst"), "wb") as f:
            f.write(restart)
        with open(os.path.join(d, "in.test"), "w") as f:
            f.write(script + DUMP.format(every=100) + "run 100\n")
        proc = subprocess.run([lmptest.Config.lmp, "-in", "in.test"], cwd=d,
                              capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, proc.stdout[-3000:] + proc.stderr)
        resumed = lmptest.Run(d, proc).dump("pol.dump")[-1]
        self.assertEqual(resumed["step"], straight["step"])
        for col in ("xu", "yu", "mux", "muy"):
            np.testing.assert_allclose(resumed[col], straight[col], rtol=0, atol=1e-12)
        del shutil


class Output(LammpsTestCase):
    """f_ID[1] = |<n>| and f_ID[2] = <cos 2(theta - phi)>, computed here."""

    def test_orders(self):
        run = self.run_lmp(FREE + "create_atoms 1 random 50 1212 box\n" + """
set group all dipole/random 77 1.0
fix p all polarity 0.0 1.0 groove 0.0 25
fix b all brownian 1.0 1 gamma_t 1.0 rng none
thermo_style custom step f_p[1] f_p[2]
thermo_modify format float %.15g
""" + DUMP.format(every=1) + "run 0\n")
        frame = run.dump("pol.dump")[0]
        th = angles(frame)
        polar = math.hypot(np.cos(th).mean(), np.sin(th).mean())
        nematic = np.cos(2 * (th - math.radians(25))).mean()
        row = run.stdout.split("Step")[1].splitlines()[1].split()
        self.assertAlmostEqual(float(row[1]), polar, delta=1e-12)
        self.assertAlmostEqual(float(row[2]), nematic, delta=1e-12)


class PerCellActiveForce(LammpsTestCase):
    """f_a given as d_name: each cell's own active force, which fix
    cell/adapt may change during a run.  Free particles (2d, 3d): each
    moves with d_fa / gamma_T along its polarity, one with d_fa = 0 stays
    put.  Tissues (confluent and finite 2d, 3d, sphere): the force the fix adds at step
    k (total force minus the force stored by fix store/force before it) is
    d_fa n, with d_fa as set by cell/adapt at the end of step k-1, which
    varies per cell and in time and is 0 for every fourth cell."""

    def free_drift(self, dim):
        fa_of = lambda ids: 0.25 * (ids % 4)          # id 4, 8, ...: 0
        gT, dt, steps = 2.0, 0.01, 30
        script = FREE + "create_atoms 1 random 20 4412 box\n"
        if dim == 3:
            script = script.replace("dimension 2\n", "").replace("-0.5 0.5", "0 20")
        script += "set group all dipole/random 881 1.0\n"
        script += f"""fix fa all property/atom d_fa
variable f atom 0.25*(id%4)
set group all d_fa v_f
timestep {dt}
fix p all polarity d_fa 5.0
fix b all brownian 1.0 1 gamma_t {gT} rng none
dump d all custom {steps} pol.dump id xu yu zu mux muy muz
dump_modify d sort id format float %.17g
run {steps}
"""
        first, last = self.run_lmp(script).dump("pol.dump")
        n = np.column_stack([first["mux"], first["muy"], first["muz"]])
        n /= np.linalg.norm(n, axis=1)[:, None]
        disp = np.column_stack([last[c] - first[c] for c in ("xu", "yu", "zu")])
        speed = fa_of(first["id"]) / gT
        np.testing.assert_allclose(disp, (speed * dt * steps)[:, None] * n, atol=1e-12)
        self.assertTrue((speed == 0).any() and (speed > 0).any())

    def test_free_drift_2d(self):
        self.free_drift(2)

    def test_free_drift_3d(self):
        self.free_drift(3)

    def added_force(self, model):
        from feature_models import model_script
        steps = 6
        script = model_script(model) + f"""fix fa all property/atom d_fa
set group all d_fa 0.5
variable f atom 0.3*(id%4)*(1+0.5*sin(0.7*step))
fix sf all store/force
fix p all polarity d_fa 1.0 neighbor 0.2
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix ad all cell/adapt 1 d_fa v_f
timestep 0.01
dump d all custom 1 pol.dump id fx fy fz f_sf[1] f_sf[2] f_sf[3] mux muy muz d_fa
dump_modify d sort id format float %.17g
run {steps}
"""
        frames = self.run_lmp(script).dump("pol.dump")
        self.assertEqual(len(frames), steps + 1)
        for prev, fr in zip(frames[:-1], frames[1:]):
            n = np.column_stack([fr["mux"], fr["muy"], fr["muz"]])
            n /= np.linalg.norm(n, axis=1)[:, None]
            added = np.column_stack([fr[c] - fr["f_sf[%d]" % (k + 1)]
                                     for k, c in enumerate(("fx", "fy", "fz"))])
            np.testing.assert_allclose(added, prev["d_fa"][:, None] * n, atol=1e-10,
                                       err_msg=f"{model} step {fr['step']}")
            expect = 0.3 * (fr["id"] % 4) * (1 + 0.5 * np.sin(0.7 * fr["step"]))
            np.testing.assert_allclose(fr["d_fa"], expect, atol=1e-12)
        # the values the forces used changed during the run, and some are 0
        self.assertGreater(np.abs(frames[-2]["d_fa"] - frames[1]["d_fa"]).max(), 0.05)
        self.assertTrue((frames[1]["d_fa"] == 0).any())

    def test_added_force_confluent(self):
        self.added_force("confluent")

    def test_added_force_3d(self):
        self.added_force("3d")

    def test_added_force_sphere(self):
        self.added_force("sphere")

    def test_added_force_finite(self):
        self.added_force("finite_open")

    def test_errors(self):
        run = self.run_lmp(FREE + "create_atoms 1 random 3 1 box\n"
                           "fix p all polarity d_fa 1.0\nrun 0\n", ok=False)
        self.assertLammpsError(run, "d_fa is no per-atom double property", "property/atom d_fa")
        run = self.run_lmp(FREE + "create_atoms 1 random 3 1 box\nfix fa all property/atom d_fa\n"
                           "variable f atom 1+(id==2)*1e308*10\nset group all d_fa v_f\n"
                           "set group all dipole/random 1 1.0\n"
                           "fix p all polarity d_fa 1.0\nrun 0\n", ok=False)
        self.assertLammpsError(run, "active force d_fa of cell 2", "must be finite")


class Errors(LammpsTestCase):

    def test_without_dipole(self):
        run = self.run_lmp(FREE.replace("atom_style dipole", "atom_style atomic") +
                           "fix p all polarity 1.0 1.0\n", ok=False)
        self.assertLammpsError(run, "dipole moment mu", "atom_style dipole")

    def test_neighbor_needs_pair(self):
        run = self.run_lmp(FREE + "create_atoms 1 random 10 1 box\n"
                           "fix p all polarity 1.0 1.0 neighbor 1.0\nrun 0\n", ok=False)
        self.assertLammpsError(run, "pair_style vertex/voronoi")

    def test_bad_gamma(self):
        run = self.run_lmp(FREE + "fix p all polarity 1.0 0\n", ok=False)
        self.assertLammpsError(run, "gamma_R must be > 0", "0")

    def test_unknown_keyword(self):
        run = self.run_lmp(FREE + "fix p all polarity 1.0 1.0 grooves 1 0\n", ok=False)
        self.assertLammpsError(run, "unknown keyword 'grooves'")

    def test_missing_value(self):
        run = self.run_lmp(FREE + "fix p all polarity 1.0 1.0 groove 1\n", ok=False)
        self.assertLammpsError(run, "groove J_G phi")

    def test_negative_noise(self):
        run = self.run_lmp(FREE + "fix p all polarity 1.0 1.0 noise -1 5\n", ok=False)
        self.assertLammpsError(run, "D_r must be >= 0")


if __name__ == "__main__":
    lmptest.main()
