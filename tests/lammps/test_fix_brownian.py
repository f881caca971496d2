#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""fix brownian run through tessera-lmp, against analytic results:
drift F/gamma_t dt per step without noise, mean-square displacement 2 d D t
with D = kT/gamma_t, the single-step noise distribution of each rng, v = dr/dt,
1 rank == 2 ranks without noise, and the errors for bad input."""

import math

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs


def free_particles(n, dim=2, length=40.0, seed=4328, units="lj"):
    """n non-interacting particles at random positions in a periodic box."""
    zlo, zhi = (-0.5, 0.5) if dim == 2 else (0.0, length)
    return f"""
units {units}
dimension {dim}
atom_style atomic
boundary p p p
region box block 0 {length} 0 {length} {zlo} {zhi}
create_box 2 box
create_atoms 1 random {n} {seed} box
mass * 1.0
pair_style zero 1.0
pair_coeff * *
neighbor 0.3 bin
thermo 0
"""


DUMP_ALL = "id xu yu zu vx vy vz"


def dump_every(n, name="traj.dump"):
    return (f"dump d all custom {n} {name} {DUMP_ALL}\n"
            f"dump_modify d sort id format float %.17g\n")


def displacement(first, last, dims=("xu", "yu", "zu")):
    return np.column_stack([last[c] - first[c] for c in dims])


class Drift(LammpsTestCase):
    """rng none: every step moves each atom by exactly dt F / gamma_t."""

    def drift_script(self, dim=2, fz=0.0):
        return free_particles(50, dim) + f"""
variable fx atom 0.01*id-0.2
variable fy atom -0.03*id+0.5
fix f all addforce v_fx v_fy {fz}
fix 2 all brownian 1.0 12908410 gamma_t ${{g}} rng none
timestep 0.01
""" + dump_every(40) + "run 40\n"

    def check_drift(self, run, dim, gamma_t=2.5, fz=0.0, steps=40, dt=0.01):
        first, last = run.dump("traj.dump")
        ids = first["id"]
        force = np.column_stack([0.01 * ids - 0.2, -0.03 * ids + 0.5, np.full(len(ids), fz)])
        moved = displacement(first, last)
        expected = steps * dt * force / gamma_t
        if dim == 2:
            expected[:, 2] = 0.0
        # Rounding: one ulp of a coordinate (|x| < 40) per step.
        np.testing.assert_allclose(moved, expected, rtol=1e-12, atol=steps * 40 * 2.3e-16)
        velocity = np.column_stack([last["vx"], last["vy"], last["vz"]])
        np.testing.assert_allclose(velocity, expected / (steps * dt), rtol=1e-12, atol=1e-14)

    def test_drift_2d(self):
        run = self.run_lmp(self.drift_script(2, fz=0.7), variables={"g": 2.5})
        self.check_drift(run, 2, fz=0.7)    # the z force moves nothing in 2D

    def test_drift_3d(self):
        run = self.run_lmp(self.drift_script(3, fz=0.7), variables={"g": 2.5})
        self.check_drift(run, 3, fz=0.7)

    @nprocs(2)
    def test_drift_2d_two_ranks(self):
        run = self.run_lmp(self.drift_script(2), nprocs=2, variables={"g": 2.5})
        self.assertIn("on 2 procs", run.stdout)
        self.check_drift(run, 2)

    def test_thesis_line(self):
        """The thesis's own line (with the space between T and the seed that
        its text lost), with gamma_T from -var."""
        script = free_particles(10) + """
fix f all addforce 1.0 0.0 0.0
fix 2 all brownian 1.0 12908410 gamma_t ${gamma_T} rng none
timestep 0.1
""" + dump_every(10) + "run 10\n"
        run = self.run_lmp(script, variables={"gamma_T": 4.0})
        first, last = run.dump("traj.dump")
        np.testing.assert_allclose(last["xu"] - first["xu"], 10 * 0.1 * 1.0 / 4.0, rtol=1e-12)
        np.testing.assert_allclose(last["yu"] - first["yu"], 0.0, atol=1e-15)

    def test_timestep_change_between_runs(self):
        script = free_particles(20) + """
fix f all addforce 0.5 -1.0 0.0
fix 2 all brownian 1.0 5 gamma_t 2.0 rng none
timestep 0.01
run 10
write_dump all custom a.dump id xu yu zu modify sort id format float %.17g
timestep 0.04
run 10
write_dump all custom b.dump id xu yu zu modify sort id format float %.17g
"""
        run = self.run_lmp(script)
        (a,), (b,) = run.dump("a.dump"), run.dump("b.dump")
        np.testing.assert_allclose(b["xu"] - a["xu"], 10 * 0.04 * 0.5 / 2.0, rtol=1e-12)
        np.testing.assert_allclose(b["yu"] - a["yu"], 10 * 0.04 * -1.0 / 2.0, rtol=1e-12)

    def test_group_only(self):
        """Atoms outside the fix group do not move and keep their velocity."""
        script = free_particles(40) + """
group odd id 1:40:2
velocity all set 0.3 0.2 0.0
fix f all addforce 1.0 1.0 0.0
fix 2 odd brownian 1.0 5 gamma_t 1.0
timestep 0.01
""" + dump_every(20) + "run 20\n"
        first, last = self.run_lmp(script).dump("traj.dump")
        even = first["id"] % 2 == 0
        moved = displacement(first, last)
        np.testing.assert_array_equal(moved[even], 0.0)
        np.testing.assert_array_equal(last["vx"][even], 0.3)
        self.assertTrue(np.all(np.abs(moved[~even, :2]) > 0))


class RankIndependence(LammpsTestCase):
    """Without noise, interacting particles follow the same trajectory on 1
    and 2 ranks (forces summed in another order: rounding only)."""

    # Atoms from a data file: create_atoms random numbers atoms by rank.
    SCRIPT = """
units lj
dimension 2
atom_style atomic
boundary p p p
read_data atoms.data
mass * 1.0
thermo 0
pair_style soft 1.0
pair_coeff * * 20.0
fix 2 all brownian 1.0 77 gamma_t 1.0 rng none
timestep 0.002
""" + dump_every(200) + "run 200\n"

    @staticmethod
    def data_file(n=300, length=15.0, seed=99):
        rng = np.random.default_rng(seed)
        xy = rng.uniform(0.0, length, size=(n, 2))
        lines = ["random atoms", "", f"{n} atoms", "1 atom types", "",
                 f"0 {length} xlo xhi", f"0 {length} ylo yhi", "-0.5 0.5 zlo zhi", "", "Atoms", ""]
        lines += [f"{i + 1} 1 {x:.17g} {y:.17g} 0.0" for i, (x, y) in enumerate(xy)]
        return "\n".join(lines) + "\n"

    @nprocs(2)
    def test_one_vs_two_ranks(self):
        files = {"atoms.data": self.data_file()}
        serial = self.run_lmp(self.SCRIPT, files=files).dump("traj.dump")
        parallel = self.run_lmp(self.SCRIPT, nprocs=2, files=files).dump("traj.dump")
        moved = displacement(serial[0], serial[1])
        self.assertGreater(np.abs(moved).max(), 0.05)    # the soft repulsion did move them
        for s, p in zip(serial, parallel):
            for col in ("xu", "yu", "vx", "vy"):
                np.testing.assert_allclose(p[col], s[col], rtol=0, atol=1e-10, err_msg=col)


class Noise(LammpsTestCase):
    """Diffusion: D = kB T / gamma_t."""

    def msd_run(self, n, dim, rng, temp, gamma_t, dt, steps, force=(0.0, 0.0, 0.0), seed=31415):
        script = free_particles(n, dim, length=100.0) + f"""
fix f all addforce {force[0]} {force[1]} {force[2]}
fix 2 all brownian {temp} {seed} gamma_t {gamma_t} rng {rng}
timestep {dt}
""" + dump_every(steps) + f"run {steps}\n"
        first, last = self.run_lmp(script).dump("traj.dump")
        return displacement(first, last)

    def check_msd(self, dim, rng, n=10000, temp=0.5, gamma_t=2.0, dt=0.01, steps=100,
                  force=(0.0, 0.0, 0.0)):
        moved = self.msd_run(n, dim, rng, temp, gamma_t, dt, steps, force)
        t = steps * dt
        diffusion = temp / gamma_t
        drift = np.array(force[:dim]) / gamma_t * t
        d = moved[:, :dim] - drift
        if dim == 2:
            np.testing.assert_array_equal(moved[:, 2], 0.0)
        # After many steps each component is ~Gaussian with variance 2 D t,
        # so |d|^2 / (2 D t) ~ chi^2 with dim degrees of freedom (variance 2 dim).
        msd = np.mean(np.sum(d**2, axis=1))
        expected = 2 * dim * diffusion * t
        sigma = expected * math.sqrt(2.0 / dim) / math.sqrt(n)
        self.assertLess(abs(msd - expected), 5 * sigma,
                        "MSD %.5g, expected 2 d D t = %.5g +- %.2g" % (msd, expected, sigma))
        # The mean displacement is the drift.
        mean_sigma = math.sqrt(2 * diffusion * t / n)
        for k in range(dim):
            self.assertLess(abs(np.mean(d[:, k])), 5 * mean_sigma)

    def test_msd_2d_uniform(self):
        self.check_msd(2, "uniform")

    def test_msd_2d_gaussian(self):
        self.check_msd(2, "gaussian")

    def test_msd_3d_uniform(self):
        self.check_msd(3, "uniform", n=6000)

    def test_msd_with_drift(self):
        self.check_msd(2, "gaussian", force=(1.0, -0.5, 0.0))

    def single_step(self, rng, n=20000, temp=0.8, gamma_t=4.0, dt=0.05):
        d = self.msd_run(n, 2, rng, temp, gamma_t, dt, 1)[:, :2].ravel()
        sigma2 = 2 * temp / gamma_t * dt    # variance of one component of one step
        return d, sigma2

    def test_uniform_step_distribution(self):
        """rng uniform: each component is uniform on [-sqrt(3) s, sqrt(3) s]
        with s^2 = 2 D dt (variance matched), kurtosis 9/5."""
        d, s2 = self.single_step("uniform")
        m = len(d)
        self.assertLessEqual(np.abs(d).max(), math.sqrt(3 * s2) * (1 + 1e-12))
        self.assertGreater(np.abs(d).max(), 0.99 * math.sqrt(3 * s2))
        var = np.mean(d**2)
        self.assertLess(abs(var / s2 - 1), 5 * math.sqrt(0.8 / m))
        kurtosis = np.mean(d**4) / var**2
        self.assertLess(abs(kurtosis - 1.8), 0.05)

    def test_gaussian_step_distribution(self):
        """rng gaussian: each component is N(0, 2 D dt), kurtosis 3."""
        d, s2 = self.single_step("gaussian")
        m = len(d)
        var = np.mean(d**2)
        self.assertLess(abs(var / s2 - 1), 5 * math.sqrt(2.0 / m))
        kurtosis = np.mean(d**4) / var**2
        self.assertLess(abs(kurtosis - 3.0), 6 * math.sqrt(24.0 / m))
        self.assertGreater(np.abs(d).max(), 3.5 * math.sqrt(s2))    # tails beyond uniform's

    def test_velocity_is_displacement_over_dt(self):
        script = free_particles(200) + """
fix f all addforce 0.2 0.1 0.0
fix 2 all brownian 2.0 42 gamma_t 1.5 rng gaussian
timestep 0.02
run 5
write_dump all custom a.dump id xu yu zu modify sort id format float %.17g
run 1
write_dump all custom b.dump id xu yu zu vx vy vz modify sort id format float %.17g
"""
        run = self.run_lmp(script)
        (a,), (b,) = run.dump("a.dump"), run.dump("b.dump")
        np.testing.assert_allclose(b["vx"], (b["xu"] - a["xu"]) / 0.02, rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(b["vy"], (b["yu"] - a["yu"]) / 0.02, rtol=1e-9, atol=1e-12)
        np.testing.assert_array_equal(b["vz"], 0.0)

    def test_metal_units(self):
        """Unit conversions: in metal units F/gamma_t needs ftm2v and
        kB T / gamma_t needs mvv2e (LAMMPS's constants for metal units)."""
        mvv2e, boltz = 1.0364269e-4, 8.617343e-5
        temp, gamma_t, dt, steps, n, fx = 300.0, 50.0, 0.001, 100, 10000, 0.02
        script = free_particles(n, 2, length=100.0, units="metal") + f"""
fix f all addforce {fx} 0.0 0.0
fix 2 all brownian {temp} 2718 gamma_t {gamma_t} rng gaussian
timestep {dt}
""" + dump_every(steps) + f"run {steps}\n"
        first, last = self.run_lmp(script).dump("traj.dump")
        d = displacement(first, last)[:, :2]
        t = steps * dt
        drift = fx / mvv2e / gamma_t * t
        diffusion = boltz * temp / (mvv2e * gamma_t)
        sigma_mean = math.sqrt(2 * diffusion * t / n)
        self.assertLess(abs(np.mean(d[:, 0]) - drift), 5 * sigma_mean)
        d[:, 0] -= drift
        msd, expected = np.mean(np.sum(d**2, axis=1)), 4 * diffusion * t
        self.assertLess(abs(msd / expected - 1), 5 / math.sqrt(n))


class Errors(LammpsTestCase):
    """Bad input stops LAMMPS with an ERROR naming the fix, argument and value.
    On the plugin host `fix brownian` is upstream BROWNIAN's (ours is only
    registered where the host has none): its ERROR lines, in `upstream`."""

    def fail_with(self, fix_args, *fragments, extra="", upstream=()):
        script = free_particles(4) + extra + f"fix 7 all brownian {fix_args}\nrun 1\n"
        if self.plugin_host:
            self.assertTrue(upstream, "no expectation for upstream's fix brownian")
            fragments = upstream
        self.assertLammpsError(self.run_lmp(script, ok=False), *fragments)

    def test_too_few_arguments(self):
        self.fail_with("1.0", "Illegal fix brownian command", "fix ID 7",
                       upstream=("Illegal fix brownian command: missing argument(s)",))

    def test_gamma_t_missing(self):
        self.fail_with("1.0 5 rng none", "(ID 7)", "gamma_t is required",
                       upstream=("Keyword gamma_t is required for fix brownian",))

    def test_gamma_t_zero(self):
        self.fail_with("1.0 5 gamma_t 0", "(ID 7)", "gamma_t = 0 must be > 0",
                       upstream=("Fix brownian gamma_t value must be > 0",))

    def test_gamma_t_negative(self):
        self.fail_with("1.0 5 gamma_t -1.5", "gamma_t = -1.5 must be > 0",
                       upstream=("Fix brownian gamma_t value must be > 0",))

    def test_gamma_t_not_a_number(self):
        self.fail_with("1.0 5 gamma_t abc", "gamma_t must be a number, got 'abc'",
                       upstream=("Expected floating point parameter instead of 'abc'",))

    def test_gamma_t_without_value(self):
        self.fail_with("1.0 5 gamma_t", "keyword gamma_t needs a value",
                       upstream=("Illegal fix brownian gamma_t command: missing argument(s)",))

    def test_bad_rng(self):
        self.fail_with("1.0 5 gamma_t 1 rng poisson",
                       "rng must be uniform, gaussian or none, got 'poisson'",
                       upstream=("Unknown fix brownian rng keyword poisson",))

    def test_rng_without_value(self):
        self.fail_with("1.0 5 gamma_t 1 rng", "keyword rng needs a value",
                       upstream=("Illegal fix brownian rng command: missing argument(s)",))

    def test_temperature_not_positive(self):
        self.fail_with("0.0 5 gamma_t 1 rng none", "temperature T = 0.0 must be > 0",
                       upstream=("Fix brownian temp must be > 0.0",))

    def test_seed_not_positive(self):
        self.fail_with("1.0 0 gamma_t 1", "seed = 0 must be in [1, 900000000]",
                       upstream=("Fix brownian seed must be > 0",))

    def test_thesis_typo(self):
        """The thesis prints 'brownian 1.012908410 gamma_t ...' (space lost)."""
        self.fail_with("1.012908410 gamma_t 1.0 rng none", "seed must be an integer, got 'gamma_t'",
                       upstream=("Expected integer parameter instead of 'gamma_t'",))

    def test_sphere_keyword(self):
        self.fail_with("1.0 5 gamma_t 1 gamma_r 1", "keyword gamma_r belongs to upstream's fix brownian/sphere",
                       upstream=("Using keyword(s) not compatible with fix brownian",))

    def test_unknown_keyword(self):
        self.fail_with("1.0 5 gamma_t 1 colour red", "unknown keyword 'colour'",
                       upstream=("Unknown fix brownian keyword colour",))

    def test_respa(self):
        if not self.plugin_host:
            self.fail_with("1.0 5 gamma_t 1", "does not support run_style respa",
                           extra="run_style respa 2 2\n")
            return
        # Upstream's fix brownian has no respa hook: it runs, and nothing moves
        # (why ours refuses respa instead).
        script = free_particles(1) + """
run_style respa 2 2
fix f all addforce 3.0 0.0 0.0
fix 7 all brownian 1.0 5 gamma_t 2.0 rng none
print "X0 $(xcm(all,x):%.12f)"
run 10
print "X1 $(xcm(all,x):%.12f)"
"""
        run = self.run_lmp(script)
        x = {w[0]: float(w[1]) for w in (l.split() for l in run.stdout.splitlines())
             if len(w) == 2 and w[0] in ("X0", "X1")}
        self.assertEqual(x["X0"], x["X1"], run.output[-2000:])

    @nprocs(2)
    def test_error_on_two_ranks(self):
        script = free_particles(4) + "fix 7 all brownian 1.0 5 gamma_t -2\nrun 1\n"
        self.assertLammpsError(self.run_lmp(script, nprocs=2, ok=False),
                               "Fix brownian gamma_t value must be > 0" if self.plugin_host
                               else "gamma_t = -2 must be > 0")


if __name__ == "__main__":
    lmptest.main()
