#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""fix brownian/heun: the order of convergence of positions and polarity
angles of a deterministic active tissue (Richardson ratios of runs at dt,
dt/2, dt/4, ...: about 2 for brownian/heun, about 1 for fix brownian's
forward Euler), exact drift and the diffusion constant of free particles,
1 rank == 2 ranks, restarts and `run N; run M` continuing the run, fix
dt/reset with both integrators, and errors for bad input."""

import math
import os
import re

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

DUMP = "write_dump all custom {name} id xu yu mux muy vx vy modify sort id format float %.17g\n"


def active_tissue(integrator, extra_polarity="", nx=6, ny=4):
    """A jittered solid tissue (p0 = 2.5) of 2 nx ny cells with active force,
    neighbour and groove alignment, no noise, integrated by `integrator`;
    more fix polarity keywords in extra_polarity."""
    return lmptest.tissue(nx, ny) + f"""
displace_atoms all random 0.15 0.15 0 4821 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
fix p all polarity 0.3 1.0 neighbor 1.0 groove 1.0 30 {extra_polarity}
fix b all {integrator} 1.0 1 gamma_t 1.0 rng none
thermo 0
"""


def state(frame):
    return np.column_stack([frame["xu"], frame["yu"]]), np.column_stack([frame["mux"], frame["muy"]])


class Order(LammpsTestCase):
    """Richardson estimate of the order p from the final states y(h) at
    h = T/n for n = 10, 20, 40, 80: |y(h) - y(h/2)| / |y(h/2) - y(h/4)| = 2^p
    as h -> 0, for the positions and the polarity directions separately, with
    every alignment of fix polarity (neighbour, groove, velocity)."""

    TIME = 0.4
    STEPS = (10, 20, 40, 80)

    def final_states(self, integrator):
        out = []
        for n in self.STEPS:
            script = active_tissue(integrator, "velocity 1.0") + f"timestep {self.TIME / n!r}\nrun {n}\n" + \
                DUMP.format(name="final.dump")
            (frame,) = self.run_lmp(script).dump("final.dump")
            out.append(state(frame))
        return out

    def orders(self, integrator):
        states = self.final_states(integrator)
        result = {}
        for k, name in enumerate(("positions", "polarities")):
            diffs = [np.abs(states[j][k] - states[j + 1][k]).max() for j in range(len(states) - 1)]
            self.assertGreater(diffs[0], 1e-5, "%s hardly move: no test" % name)
            result[name] = [math.log2(diffs[j] / diffs[j + 1]) for j in range(len(diffs) - 1)]
        return result

    def test_heun_second_order(self):
        for name, p in self.orders("brownian/heun").items():
            for value in p:
                self.assertGreaterEqual(value, 1.8, "%s: orders %s" % (name, p))
                self.assertLess(value, 2.3, "%s: orders %s" % (name, p))

    def test_euler_first_order(self):
        for name, p in self.orders("brownian").items():
            for value in p:
                self.assertGreater(value, 0.8, "%s: orders %s" % (name, p))
                self.assertLess(value, 1.2, "%s: orders %s" % (name, p))


def free_polarities(n_side, d_rot, dt, steps, adapt=""):
    """Free polarities on a square lattice (no forces: pair zero), rotational
    noise D_r by fix polarity, fix brownian/heun (with 'adapt' settings if
    given): dumps a.dump after the setup and b.dump after the steps."""
    return f"""
dimension 2
units lj
atom_style dipole
boundary p p p
lattice sq 1.0
region box block 0 {n_side} 0 {n_side} -0.5 0.5
create_box 1 box
create_atoms 1 box
mass * 1.0
pair_style zero 0.5
pair_coeff * *
fix p all polarity 0.0 1.0 noise {d_rot} 3301
fix b all brownian/heun 1.0 1 gamma_t 1.0 rng none{adapt}
timestep {dt}
thermo 0
run 0
""" + DUMP.format(name="a.dump") + f"run {steps}\n" + DUMP.format(name="b.dump")


def check_decorrelation(test, a, b, d_rot, elapsed):
    """<cos(theta(t) - theta(0))> = exp(-D_r t) within 5 standard errors (the
    cosine of a Gaussian angle of variance s2 = 2 D_r t has variance
    (1 - e^-s2)^2 / 2)."""
    c = a["mux"] * b["mux"] + a["muy"] * b["muy"]
    expected = math.exp(-d_rot * elapsed)
    s2 = 2 * d_rot * elapsed
    sigma = math.sqrt(0.5 * (1 - math.exp(-s2)) ** 2 / len(c))
    test.assertLess(abs(c.mean() - expected), 5 * sigma, (c.mean(), expected, sigma))


def free_particles(n, length=40.0, seed=4328):
    return f"""
units lj
dimension 2
atom_style atomic
boundary p p p
region box block 0 {length} 0 {length} -0.5 0.5
create_box 1 box
create_atoms 1 random {n} {seed} box
mass * 1.0
pair_style zero 1.0
pair_coeff * *
neighbor 0.3 bin
thermo 0
"""


class FreeParticles(LammpsTestCase):
    """Forces that do not depend on positions: Heun is exact (drift dt F /
    gamma_t per step) and has fix brownian's noise (D = kT/gamma_t)."""

    def test_drift(self):
        script = free_particles(30) + """
variable fx atom 0.01*id-0.2
variable fy atom -0.03*id+0.5
fix f all addforce v_fx v_fy 0.0
fix b all brownian/heun 1.0 5 gamma_t 2.5 rng none
timestep 0.01
write_dump all custom a.dump id xu yu modify sort id format float %.17g
run 40
write_dump all custom b.dump id xu yu vx vy modify sort id format float %.17g
"""
        run = self.run_lmp(script)
        (a,), (b,) = run.dump("a.dump"), run.dump("b.dump")
        ids = a["id"]
        for col, force in (("xu", 0.01 * ids - 0.2), ("yu", -0.03 * ids + 0.5)):
            np.testing.assert_allclose(b[col] - a[col], 0.4 * force / 2.5, rtol=1e-12, atol=1e-12)
            vcol = "v" + col[0]
            np.testing.assert_allclose(b[vcol], force / 2.5, rtol=1e-12, atol=1e-14)

    def test_msd(self):
        n, temp, gamma_t, dt, steps = 8000, 0.5, 2.0, 0.01, 50
        script = free_particles(n, length=100.0) + f"""
fix b all brownian/heun {temp} 31415 gamma_t {gamma_t} rng gaussian
timestep {dt}
write_dump all custom a.dump id xu yu modify sort id format float %.17g
run {steps}
write_dump all custom b.dump id xu yu modify sort id format float %.17g
"""
        run = self.run_lmp(script)
        (a,), (b,) = run.dump("a.dump"), run.dump("b.dump")
        d2 = (b["xu"] - a["xu"]) ** 2 + (b["yu"] - a["yu"]) ** 2
        expected = 4 * temp / gamma_t * dt * steps
        sigma = expected / math.sqrt(n)    # |d|^2 / (2 D t) ~ chi^2 with 2 dof
        self.assertLess(abs(d2.mean() - expected), 5 * sigma, (d2.mean(), expected))


class RotationalDiffusion(LammpsTestCase):
    """Free polarities under fix brownian/heun diffuse with fix polarity's D_r:
    <cos(theta(t) - theta(0))> = exp(-D_r t) (the noise enters once per step,
    not once per stage)."""

    def test_decorrelation(self):
        n_side, d_rot, dt, steps = 64, 0.5, 0.05, 20
        run = self.run_lmp(free_polarities(n_side, d_rot, dt, steps))
        (a,), (b,) = run.dump("a.dump"), run.dump("b.dump")
        check_decorrelation(self, a, b, d_rot, dt * steps)
        np.testing.assert_array_equal(b["xu"], a["xu"])


class Continuation(LammpsTestCase):
    """Without position noise (rotational noise is counter-based), `run N;
    run M`, a restart and 1 vs 2 ranks all give the same trajectory up to the
    rounding of sums."""

    POLARITY = "velocity 0.5 noise 0.3 77"

    def test_run_split_and_restart(self):
        base = active_tissue("brownian/heun", self.POLARITY) + "timestep 0.01\n"
        whole = self.run_lmp(base + "run 40\n" + DUMP.format(name="end.dump")).dump("end.dump")[0]
        split = self.run_lmp(base + "run 25\nrun 15\n" + DUMP.format(name="end.dump")).dump("end.dump")[0]
        first = self.run_lmp(base + "run 25\nwrite_restart half.restart\n")
        restart = f"""
read_restart {first.path('half.restart')}
fix p all polarity 0.3 1.0 neighbor 1.0 groove 1.0 30 {self.POLARITY}
fix b all brownian/heun 1.0 1 gamma_t 1.0 rng none
timestep 0.01
thermo 0
run 15
""" + DUMP.format(name="end.dump")
        restarted = self.run_lmp(restart).dump("end.dump")[0]
        half = self.run_lmp(base + "run 25\n" + DUMP.format(name="half.dump")).dump("half.dump")[0]
        self.assertGreater(np.abs(whole["xu"] - half["xu"]).max(), 1e-3)
        self.assertGreater(np.abs(whole["mux"] - half["mux"]).max(), 1e-3)
        for other in (split, restarted):
            for col in ("xu", "yu", "mux", "muy", "vx", "vy"):
                np.testing.assert_allclose(other[col], whole[col], rtol=0, atol=1e-11, err_msg=col)

    def test_fix_order(self):
        """fix brownian/heun finds fix polarity whichever is defined first."""
        base = active_tissue("brownian/heun", self.POLARITY) + "timestep 0.01\nrun 30\n" + \
            DUMP.format(name="end.dump")
        lines = base.split("\n")
        p = next(i for i, line in enumerate(lines) if line.startswith("fix p "))
        b = next(i for i, line in enumerate(lines) if line.startswith("fix b "))
        lines[p], lines[b] = lines[b], lines[p]
        swapped = "\n".join(lines)
        self.assertLess(swapped.index("fix b "), swapped.index("fix p "))
        one = self.run_lmp(base).dump("end.dump")[0]
        two = self.run_lmp(swapped).dump("end.dump")[0]
        for col in ("xu", "yu", "mux", "muy"):
            np.testing.assert_allclose(two[col], one[col], rtol=0, atol=1e-12, err_msg=col)

    @nprocs(2)
    def test_one_vs_two_ranks(self):
        make = active_tissue("brownian/heun", self.POLARITY, nx=8, ny=6) + \
            "run 0\nwrite_data cells.data\n"
        data = self.run_lmp(make).text("cells.data")
        script = """
dimension 2
units lj
atom_style dipole
boundary p p p
read_data cells.data
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
""" + f"""
fix p all polarity 0.3 1.0 neighbor 1.0 groove 1.0 30 {self.POLARITY}
fix b all brownian/heun 1.0 1 gamma_t 1.0 rng none
timestep 0.02
thermo 0
run 60
""" + DUMP.format(name="end.dump")
        files = {"cells.data": data}
        serial = self.run_lmp(script, files=files).dump("end.dump")[0]
        parallel = self.run_lmp(script, nprocs=2, files=files).dump("end.dump")[0]
        start = self.run_lmp(script.replace("run 60", "run 0"), files=files).dump("end.dump")[0]
        self.assertGreater(np.abs(serial["xu"] - start["xu"]).max(), 0.02)
        self.assertGreater(np.abs(serial["mux"] - start["mux"]).max(), 0.02)
        for col in ("xu", "yu", "mux", "muy", "vx", "vy"):
            np.testing.assert_allclose(parallel[col], serial[col], rtol=0, atol=1e-11, err_msg=col)


class DtReset(LammpsTestCase):
    """fix dt/reset changes the timestep; both integrators must use the new
    one (reset_dt): constant forces move each atom by exactly t F / gamma_t,
    t the elapsed simulated time, and in a tissue no step moves a cell
    much farther than Xmax."""

    INTEGRATORS = ("brownian", "brownian/heun")

    def test_constant_force(self):
        for integrator in self.INTEGRATORS:
            script = free_particles(20) + f"""
variable fx atom 0.1*id
fix f all addforce v_fx 0.5 0.0
fix b all {integrator} 1.0 5 gamma_t 2.0 rng none
fix r all dt/reset 1 NULL NULL 0.01 units box
timestep 1.0e-4
write_dump all custom a.dump id xu yu modify sort id format float %.17g
run 30
variable t equal time
print "elapsed ${{t}}"
variable d equal dt
print "last dt ${{d}}"
write_dump all custom b.dump id xu yu modify sort id format float %.17g
"""
            run = self.run_lmp(script)
            elapsed = float(run.stdout.split("elapsed ")[1].split()[0])
            last_dt = float(run.stdout.split("last dt ")[1].split()[0])
            # The fastest atom (id 20, F = (2, 0.5), v = F / 2) sets dt: fix
            # dt/reset takes dt_v = Xmax / |v| and scales it by Xmax / |dt_v v +
            # dt_v^2 F / (2 m)| (its inertial term; here m = 1).
            speed, fnorm = math.hypot(1.0, 0.25), math.hypot(2.0, 0.5)
            dt_v = 0.01 / speed
            np.testing.assert_allclose(last_dt, dt_v * 0.01 / (0.01 + 0.5 * dt_v**2 * fnorm),
                                       rtol=1e-12)
            (a,), (b,) = run.dump("a.dump"), run.dump("b.dump")
            self.assertGreater(elapsed, 50 * 30 * 1e-4)    # dt grew from 1e-4
            np.testing.assert_allclose(b["xu"] - a["xu"], elapsed * 0.1 * a["id"] / 2.0, rtol=1e-10,
                                       err_msg=integrator)
            np.testing.assert_allclose(b["yu"] - a["yu"], elapsed * 0.25, rtol=1e-10, err_msg=integrator)

    def test_tissue_displacement_capped(self):
        xmax = 0.004
        for integrator in self.INTEGRATORS:
            script = active_tissue(integrator) + f"""
fix r all dt/reset 1 NULL 0.05 {xmax} units box
timestep 0.05
dump d all custom 1 traj.dump id xu yu
dump_modify d sort id format float %.17g
thermo_style custom step dt
thermo 1
run 30
"""
            frames = self.run_lmp(script).dump("traj.dump")
            steps = [np.hypot(b["xu"] - a["xu"], b["yu"] - a["yu"]).max()
                     for a, b in zip(frames[1:], frames[2:])]
            self.assertLess(max(steps), 1.1 * xmax, integrator)
            self.assertGreater(max(steps), 0.9 * xmax, integrator)


class Example(LammpsTestCase):
    """examples/heun (brownian/heun + fix dt/reset) runs to its end time with
    a timestep that fix dt/reset changes, starting from the cells' speeds."""

    INPUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                         "heun", "in.heun")

    def test_example_short(self):
        with open(self.INPUT) as f:
            script = f.read()
        run = self.run_lmp(script, variables={"tend": 0.3})
        self.assertIn("Fix halt condition", run.output)
        # (the thermo header's spacing differs between LAMMPS versions)
        log = re.split(r"(?m)^\s*Step\s+Time\s+Dt\b.*$", run.stdout)[1].split("Loop time")[0].split("\n")[1:]
        rows = np.array([[float(w) for w in line.split()] for line in log
                         if line.strip() and line.split()[0].isdigit()])
        # Step 0: dt from the speed f_a / gamma_t = 10 of the cells (0.1 / 10),
        # not from v = 0 (which would give dtmax = 0.05).
        self.assertLess(rows[0, 2], 0.0101)
        self.assertGreater(rows[0, 2], 0.009)
        self.assertNotEqual(rows[1, 2], rows[0, 2])


def trap(kx, ky, tol, timestep, extra="", tend=2.0, x0=(7.0, 6.0)):
    """One particle in the trap F = -(kx (x - 5), ky (y - 5)), gamma_t = 1, no
    noise, integrated with adapt tol `tol` from `timestep` until time tend;
    thermo every step: step time dt f_b[1..7]."""
    return f"""
units lj
dimension 2
atom_style atomic
atom_modify map array
boundary p p p
region box block 0 10 0 10 -0.5 0.5
create_box 1 box
create_atoms 1 single {x0[0]} {x0[1]} 0.0 units box
mass 1 1.0
pair_style zero 1.0
pair_coeff * *
variable fx atom -{kx}*(x-5)
variable fy atom -{ky}*(y-5)
fix f all addforce v_fx v_fy 0.0
fix b all brownian/heun 1.0 1 gamma_t 1.0 rng none adapt tol {tol} {extra}
timestep {timestep}
variable t equal time
fix stop all halt 1 v_t >= {tend} error continue
thermo_style custom step time dt f_b[1] f_b[2] f_b[3] f_b[4] f_b[5] f_b[6] f_b[7]
thermo_modify format float %.17g
thermo 1
run 1000000
print "END $(time:%.17g) $(x[1]:%.17g) $(y[1]:%.17g) $(f_b[3]) $(f_b[4])"
"""


def thermo_table(run):
    """The rows of the (single) thermo block as an array."""
    rows = []
    # (LAMMPS 2026 pads the header: "   Step ...")
    for block in re.split(r"\n\s*Step\s", run.stdout)[1:]:
        for line in block.split("\n")[1:]:
            words = line.split()
            if not words or not re.match(r"^-?\d", words[0]):
                if line.startswith("Loop time"):
                    break
                continue
            rows.append([float(w) for w in words])
    return np.array(rows)


class Adaptive(LammpsTestCase):
    """fix brownian/heun ... adapt tol T: the error-controlled step."""

    def end_state(self, run):
        t, x, y, acc, rej = [float(w) for w in run.stdout.split("\nEND ")[1].split()[:5]]
        return t, x, y, acc, rej

    def test_global_error_falls_with_tol(self):
        """Overdamped harmonic trap, exact x(t) = 5 + (x0 - 5) e^-t: the error
        at the end falls like the tolerance (local extrapolation: the Heun
        solution is kept, its global error ~ tol), the steps like tol^-1/2;
        'time' is the sum of the steps' dt (f_b[1] = dt of each step)."""
        errors, steps = [], []
        for tol in (1e-3, 1e-4, 1e-5):
            run = self.run_lmp(trap(1.0, 1.0, tol, 0.1))
            t, x, y, acc, rej = self.end_state(run)
            errors.append(math.hypot(x - 5 - 2 * math.exp(-t), y - 5 - math.exp(-t)))
            steps.append(acc)
            rows = thermo_table(run)
            np.testing.assert_allclose(np.diff(rows[:, 1]), rows[1:, 2], rtol=1e-9)
            np.testing.assert_array_equal(rows[:, 3], rows[:, 2])
            np.testing.assert_array_equal(rows[1:, 5], np.arange(1, len(rows)))
            self.assertTrue(np.all(rows[1:, 7] <= tol * (1 + 1e-12)))    # each step's estimate
            self.assertTrue(np.all(rows[1:, 8] <= 1.0 + 1e-12))
        for a, b in zip(errors, errors[1:]):
            self.assertGreater(a / b, 6.0, errors)
            self.assertLess(a / b, 16.0, errors)
        for a, b in zip(steps, steps[1:]):
            self.assertGreater(b / a, 10 ** 0.5 * 0.7, steps)
            self.assertLess(b / a, 10 ** 0.5 * 1.4, steps)

    def test_stiff_mode_rejects_and_settles_at_the_limit(self):
        """A stiff mode (ky = 1000, kx = 1) and dtmax = 0.01, five times past
        Heun's stability limit 2 gamma_t / ky = 0.002: the first attempts are
        rejected, and once the stiff mode has decayed the step settles at
        the limit (an explicit error-controlled step on a stiff problem: the
        controller holds it where the mode neither grows nor decays) while
        the slow mode stays accurate."""
        run = self.run_lmp(trap(1.0, 1000.0, 1e-4, 0.01, "dtmax 0.01"))
        rows = thermo_table(run)
        self.assertGreater(rows[1, 6], 0)    # rejected attempts on the first step
        late = rows[rows[:, 1] > 1.0]
        mean_dt = late[:, 2].mean()
        self.assertGreater(mean_dt, 0.7 * 0.002)
        self.assertLess(mean_dt, 1.1 * 0.002)
        t, x, y, acc, rej = self.end_state(run)
        self.assertAlmostEqual(x, 5 + 2 * math.exp(-t), delta=1e-3)
        self.assertAlmostEqual(y, 5.0, delta=1e-3)

    def test_loose_tolerance_is_the_fixed_step(self):
        """With a tolerance no step exceeds and dtmax = the timestep, the
        adaptive step is the fixed Heun step, bit for bit, positions and
        polarities; no rejections."""
        base = active_tissue("brownian/heun", "velocity 1.0")
        fixed = self.run_lmp(base + "timestep 0.01\nrun 40\n" + DUMP.format(name="end.dump"))
        adaptive = self.run_lmp(base.replace("rng none", "rng none adapt tol 1e9") +
                                "timestep 0.01\nrun 40\n" + DUMP.format(name="end.dump") +
                                'print "R $(f_b[3]) $(f_b[4]) $(dt)"\n')
        a, b = fixed.dump("end.dump")[0], adaptive.dump("end.dump")[0]
        for col in ("xu", "yu", "mux", "muy", "vx", "vy"):
            np.testing.assert_array_equal(b[col], a[col], err_msg=col)
        counts = adaptive.stdout.split("\nR ")[1].split()[:3]
        self.assertEqual(counts[:2], ["40", "0"])
        self.assertEqual(float(counts[2]), 0.01)

    def adaptive_tissue(self, polarity, rng="none", tol="1e-4"):
        return active_tissue("brownian/heun", polarity).replace(
            "rng none", f"rng {rng} adapt tol {tol} dtmax 0.02")

    @nprocs(4)
    def test_ranks(self):
        """1, 2 and 4 ranks: the same trajectory, the same accepted and
        rejected steps (the estimate is the maximum over all ranks), without
        position noise and also with it (the adaptive step's noise is
        counter-based), with fix polarity's rotational noise."""
        make = active_tissue("brownian/heun", nx=8, ny=6) + "run 0\nwrite_data cells.data\n"
        data = self.run_lmp(make).text("cells.data")
        for rng in ("none", "gaussian"):
            script = f"""
dimension 2
units lj
atom_style dipole
boundary p p p
read_data cells.data
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
fix p all polarity 0.3 1.0 neighbor 1.0 groove 1.0 30 noise 0.3 77
fix b all brownian/heun 0.01 5 gamma_t 1.0 rng {rng} adapt tol 3e-4 dtmax 0.02
timestep 0.02
thermo 0
run 60
print "R $(f_b[3]) $(f_b[4]) $(time:%.17g)"
""" + DUMP.format(name="end.dump")
            results = []
            for n in (1, 2, 4):
                run = self.run_lmp(script, nprocs=n, files={"cells.data": data})
                results.append((run.stdout.split("\nR ")[1].split()[:3], run.dump("end.dump")[0]))
            counts = results[0][0]
            self.assertGreater(float(counts[1]), 0, "no rejections: not a test of them")
            for c, frame in results[1:]:
                self.assertEqual(c[:2], counts[:2], rng)
                self.assertAlmostEqual(float(c[2]), float(counts[2]), delta=1e-12)
                for col in ("xu", "yu", "mux", "muy"):
                    np.testing.assert_allclose(frame[col], results[0][1][col], rtol=0, atol=1e-10,
                                               err_msg=f"{rng} {col}")

    def test_restart_and_split_runs(self):
        """`run 25; run 15` and a restart after 25 steps continue the adaptive
        run (dt, counters, the noise queue) like one run of 40, with position
        and rotational noise."""
        polarity = "noise 0.3 77"
        base = self.adaptive_tissue(polarity, "gaussian") + "timestep 0.02\n"
        report = 'print "R $(f_b[1]:%.17g) $(f_b[3]) $(f_b[4]) $(time:%.17g)"\n'
        whole = self.run_lmp(base + "run 40\n" + report + DUMP.format(name="end.dump"))
        split = self.run_lmp(base + "run 25\nrun 15\n" + report + DUMP.format(name="end.dump"))
        first = self.run_lmp(base + "run 25\nwrite_restart half.restart\n")
        fixline = [line for line in base.split("\n") if line.startswith("fix b ")][0]
        restart = f"""
read_restart {first.path('half.restart')}
pair_coeff * * 1.0 1.0 0.1 -0.5
fix p all polarity 0.3 1.0 neighbor 1.0 groove 1.0 30 {polarity}
{fixline}
thermo 0
run 15
""" + report + DUMP.format(name="end.dump")
        restarted = self.run_lmp(restart)
        ref = whole.stdout.split("\nR ")[1].split()[:4]
        self.assertGreater(float(ref[2]), 0, "no rejections: not a test of them")
        for other in (split, restarted):
            got = other.stdout.split("\nR ")[1].split()[:4]
            self.assertEqual(got[1:3], ref[1:3])
            for a, b in ((got[0], ref[0]), (got[3], ref[3])):
                self.assertAlmostEqual(float(a), float(b), delta=1e-12 * float(b))
            f, g = other.dump("end.dump")[0], whole.dump("end.dump")[0]
            for col in ("xu", "yu", "mux", "muy"):
                np.testing.assert_allclose(f[col], g[col], rtol=0, atol=1e-10, err_msg=col)

    def test_noise_is_unbiased(self):
        """An Ornstein-Uhlenbeck particle (trap k = 200, kT = 1, gamma_t = 1):
        the stationary <r^2> / 2 per component is kT / k = 0.005.  The step's
        error estimate (dt k / 2)|r~ - r| is mostly the noise, so the rejected
        attempts are those with large noise (here about 45 %, with safety
        0.99): drawn anew, their noise would make the variance come out low
        (measured with this seed: 0.965 kT / k; over t = 0..200 the
        statistical error is about 0.5 %).  Split by the Brownian bridge it
        comes out 0.988 (the rest is Heun's bias at the larger steps).  The
        average is weighted by each step's dt."""
        script = f"""
units lj
dimension 2
atom_style atomic
boundary p p p
region box block 0 10 0 10 -0.5 0.5
create_box 1 box
create_atoms 1 single 5 5 0 units box
mass * 1.0
pair_style zero 1.0
pair_coeff * *
variable fx atom -200*(x-5)
variable fy atom -200*(y-5)
fix f all addforce v_fx v_fy 0.0
fix b all brownian/heun 1.0 4821 gamma_t 1.0 rng gaussian adapt tol 2e-3 dtmax 0.05 safety 0.99
variable r2 atom 0.5*((x-5)^2+(y-5)^2)
compute r2 all reduce ave v_r2
variable w equal c_r2*dt
variable dtv equal dt
fix av all ave/time 1 1 1 v_w v_dtv ave running
variable t equal time
fix stop all halt 1 v_t >= 200.0 error continue
thermo 0
timestep 0.001
run 100000000
print "R $(f_av[1]/f_av[2]:%.17g) $(f_b[3]) $(f_b[4])"
"""
        run = self.run_lmp(script)
        ratio, accepted, rejected = [float(w) for w in run.stdout.split("\nR ")[1].split()[:3]]
        self.assertGreater(rejected / (accepted + rejected), 0.3)
        self.assertGreater(ratio / 0.005, 0.975)
        self.assertLess(ratio / 0.005, 1.02)

    def test_rotational_noise(self):
        """Free polarities (fix polarity noise D_r) with adapt: the Wiener
        increments of the queue give <cos(theta(t) - theta(0))> = exp(-D_r t)."""
        n_side, d_rot = 64, 0.5
        run = self.run_lmp(free_polarities(n_side, d_rot, 0.05, 20,
                                           adapt=" adapt tol 1e-3 dtmax 0.05") +
                           'print "T $(time:%.17g)"\n')
        (a,), (b,) = run.dump("a.dump"), run.dump("b.dump")
        elapsed = float(run.stdout.split("\nT ")[1].split()[0])
        check_decorrelation(self, a, b, d_rot, elapsed)


class ConstrictionExample(LammpsTestCase):
    """examples/constriction (adaptive step, particles as walls), briefly: the
    run stops at its end time, the particles (in no integrator's group) stay
    where the input put them, no cell centre reaches a particle's core, and
    the net flux through a section counted from the dump's unwrapped
    coordinates, averaged over sections across the box, is the cells' summed
    displacement over Lx."""

    INPUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                         "constriction", "in.constriction")

    def test_short_run(self):
        # without noise (the default) and with it (-var T: fix brownian/heun
        # ... rng gaussian, the noise seeded by -var seed)
        # (same start: the noise is what differs)
        last = {}
        for extra in ({}, {"T": 0.01}):
            with self.subTest(**extra):
                run = self.check_short_run(extra)
                self.assertIn(f"T {extra.get('T', 0.0)} tol", run.output)
                last[bool(extra)] = run.dump("dump.constriction")[-1]
        if len(last) == 2:
            cells = last[False]["type"] == 1
            shift = np.hypot(last[True]["xu"] - last[False]["xu"], last[True]["yu"] - last[False]["yu"])
            # diffusion over t = 3 at D = 0.01: sqrt(4 D t) = 0.35 per cell
            self.assertGreater(np.median(shift[cells]), 0.1)

    def check_short_run(self, extra):
        with open(self.INPUT) as f:
            script = f.read()
        script += 'print "END $(time:%.17g) $(count(cells)) $(lx:%.17g)"\n'
        run = self.run_lmp(script, variables={"tend": 3.0, "every": 25, "tol": 0.05, **extra})
        t_end, n, lx = [float(w) for w in run.stdout.split("\nEND ")[1].split()[:3]]
        self.assertGreaterEqual(t_end, 3.0)
        self.assertLess(t_end, 3.0 + 0.01 + 1e-12)
        frames = run.dump("dump.constriction")
        first, last = frames[0], frames[-1]
        wall = first["type"] == 2
        np.testing.assert_array_equal(last["x"][wall], first["x"][wall])
        np.testing.assert_array_equal(last["y"][wall], first["y"][wall])
        cells = ~wall
        walls = np.column_stack([first["x"][wall], first["y"][wall]])
        ly = first["box"][1, 1] - first["box"][1, 0]
        for f in frames:
            p = np.column_stack([f["x"][cells], f["y"][cells]])
            d = p[:, None, :] - walls[None, :, :]
            d[..., 0] -= lx * np.round(d[..., 0] / lx)
            d[..., 1] -= ly * np.round(d[..., 1] / ly)
            self.assertGreater(np.hypot(d[..., 0], d[..., 1]).min(), 0.4)    # soft core: Rp/2
        # Counted at 1000 sections across the box, the crossings average to
        # the cells' summed displacement over Lx (each cell's count errs by
        # less than one over the number of sections).
        m = 1000
        sections = np.arange(m) * lx / m
        crossed = np.mean([np.sum(np.floor((last["xu"][cells] - x) / lx) -
                                  np.floor((first["xu"][cells] - x) / lx)) for x in sections])
        moved = np.sum(last["xu"][cells] - first["xu"][cells]) / lx
        self.assertGreater(moved, 2.0)
        self.assertLessEqual(abs(crossed - moved), n / m + 1e-9)
        return run


class Errors(LammpsTestCase):

    def test_too_few_arguments(self):
        run = self.run_lmp(free_particles(4) + "fix 7 all brownian/heun 1.0\nrun 1\n", ok=False)
        self.assertLammpsError(run, "Illegal fix brownian/heun command", "fix ID 7")

    def test_gamma_t(self):
        run = self.run_lmp(free_particles(4) + "fix 7 all brownian/heun 1.0 5 gamma_t -1\nrun 1\n",
                           ok=False)
        self.assertLammpsError(run, "Fix brownian/heun (ID 7)", "gamma_t = -1 must be > 0")

    def test_adapt_settings(self):
        cases = (("adapt", "'adapt' needs a tolerance"),
                 ("adapt tol -1", "adapt tol = -1 must be > 0"),
                 ("adapt tol 1e-3 dtmin 0.1 dtmax 0.01", "dtmin = 0.1 is larger than dtmax"),
                 ("adapt tol 1e-3 speed 2", "unknown adapt keyword 'speed'"),
                 ("adapt tol 1e-3 safety 1.5", "adapt safety = 1.5 must be < 1"))
        for words, fragment in cases:
            run = self.run_lmp(free_particles(4) +
                               f"fix 7 all brownian/heun 1.0 5 gamma_t 1.0 rng none {words}\nrun 1\n",
                               ok=False)
            self.assertLammpsError(run, "Fix brownian/heun (ID 7)", fragment)

    def test_adapt_needs_gaussian_noise_and_no_dt_reset(self):
        run = self.run_lmp(free_particles(4) +
                           "fix 7 all brownian/heun 1.0 5 gamma_t 1.0 adapt tol 1e-3\nrun 1\n",
                           ok=False)
        self.assertLammpsError(run, "Fix brownian/heun (ID 7)", "add 'rng gaussian'")
        run = self.run_lmp(free_particles(4) +
                           "fix 7 all brownian/heun 1.0 5 gamma_t 1.0 rng none adapt tol 1e-3\n"
                           "fix r all dt/reset 1 NULL NULL 0.01\nrun 1\n", ok=False)
        self.assertLammpsError(run, "Fix brownian/heun (ID 7)", "fix r (dt/reset)")

    def test_two_drivers(self):
        script = active_tissue("brownian/heun") + \
            "fix b2 all brownian/heun 1.0 1 gamma_t 1.0 rng none\nrun 1\n"
        self.assertLammpsError(self.run_lmp(script, ok=False), "fix polarity p", "keep one")


if __name__ == "__main__":
    lmptest.main()
