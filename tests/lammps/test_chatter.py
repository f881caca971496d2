#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""fix brownian and fix brownian/heun warn once when their steps oscillate
with period two (chatter), on linear force fields whose behaviour is
analytic: F = -A (r - c) with A = a I + b J (J the rotation by 90 degrees),
so that each step multiplies r - c by a known matrix.  Forward Euler:
I - dt A, for b = 0 the number m = 1 - a dt (anti-parallel steps for
a dt > 1, growing for a dt > 2).  Heun: I - dt A + (dt A)^2 / 2, which for
a dt = 1 is m = (1 - (b dt)^2) / 2 (real: period two for b dt > 1, growing
for b dt > sqrt(3)).  A case must warn exactly when |m| > 1 and m < 0; the
distance from c after N steps, |m|^N times the start, shows that the run is
the analytic case.  The warning names the atoms that alternate most and the
force that alternates on them (each sub-style of pair_style hybrid/overlay
alone, and the fixes), and advises the adaptive step."""

import math

import lmptest
from lmptest import LammpsTestCase

WARNING = "reversed direction from step to step"

# integrator, a, b, dt, m (the analytic multiplier per step), warns
CASES = {
    "euler_past_limit": ("brownian", 20.2, 0.0, 0.1, -1.02, True),
    "euler_decaying_oscillation": ("brownian", 15.0, 0.0, 0.1, -0.5, False),
    "euler_monotonic": ("brownian", 5.0, 0.0, 0.1, 0.5, False),
    "heun_past_limit": ("brownian/heun", 10.0, 3.04 ** 0.5 * 10.0, 0.1, -1.02, True),
    "heun_decaying_oscillation": ("brownian/heun", 10.0, 15.0, 0.1, -0.625, False),
}
STEPS = 80
START = ((5.2, 5.0), (4.9, 5.1), (5.0, 4.85))


def script(integrator, a, b, dt):
    atoms = "".join(f"create_atoms 1 single {x} {y} 0.0 units box\n" for x, y in START)
    return f"""units lj
dimension 2
atom_style atomic
atom_modify map array
boundary p p p
region box block 0 10 0 10 -0.5 0.5
create_box 1 box
{atoms}mass 1 1.0
pair_style zero 1.0
pair_coeff * *
variable fx atom -{a!r}*(x-5)+{b!r}*(y-5)
variable fy atom -{a!r}*(y-5)-{b!r}*(x-5)
fix f all addforce v_fx v_fy 0.0
fix b all {integrator} 1.0 1 gamma_t 1.0 rng none
timestep {dt!r}
thermo 20
run {STEPS}
print "D $(sqrt((x[1]-5)^2+(y[1]-5)^2):%.17g)"
"""


class Chatter(LammpsTestCase):
    def check(self, name):
        integrator, a, b, dt, m, warns = CASES[name]
        if warns and integrator == "brownian" and self.plugin_host:
            self.skipTest("on this host fix brownian is upstream BROWNIAN's, which does not watch")
        run = self.run_lmp(script(integrator, a, b, dt))
        d = [float(line.split()[1]) for line in run.stdout.splitlines() if line.startswith("D ")]
        r0 = math.hypot(START[0][0] - 5, START[0][1] - 5)
        self.assertAlmostEqual(d[0], r0 * abs(m) ** STEPS, delta=1e-9 * max(d[0], 1e-6) + 1e-12)
        warnings = [line for line in run.output.splitlines() if WARNING in line]
        if warns:
            self.assertEqual(len(warnings), 1, run.output[-3000:])
            for cure in ("smaller fixed timestep", "tessera-tools converge", "adapt tol T"):
                self.assertIn(cure, warnings[0])
            # Every atom oscillates (|m| > 1 for all three): each is named, and
            # the only force is fix addforce's.
            for atom in (1, 2, 3):
                self.assertRegex(warnings[0], r"[:;] %d at \(" % atom)
            self.assertIn("alternates on them is from fixes and bonds", warnings[0])
            self.assertIn("fixes and bonds 100 %", warnings[0])
        else:
            self.assertEqual(warnings, [], run.output[-3000:])


# A stiff soft contact under pair_style hybrid/overlay: two mobile atoms
# pushed (fix addforce, F = 5 towards the particle) against a fixed particle
# (pair soft, A = 10, rc = 1) rest where A pi/rc sin(pi r/rc) = F, with
# stiffness -A (pi/rc)^2 cos(pi r/rc) = 97.4; forward Euler at dt = 0.0226
# (dt k = 2.2, past 2) settles into a period-two oscillation there.  The
# sub-style zero adds nothing, fix addforce's force only turns slightly with
# the direction: the warning must name soft.
HYBRID = """units lj
dimension 2
atom_style atomic
atom_modify map array
boundary p p p
region box block 0 10 0 10 -0.5 0.5
create_box 2 box
create_atoms 2 single 5.0 5.0 0.0 units box
create_atoms 1 single 5.9 5.1 0.0 units box
create_atoms 1 single 3.0 3.0 0.0 units box
mass * 1.0
group mobile type 1
pair_style hybrid/overlay zero 1.0 soft 1.0
pair_coeff * * zero
pair_coeff 1 2 soft 10.0 1.0
pair_coeff 1 1 soft 0.0 1.0
pair_coeff 2 2 soft 0.0 1.0
variable fx atom -5*(x-5)/sqrt((x-5)^2+(y-5)^2)
variable fy atom -5*(y-5)/sqrt((x-5)^2+(y-5)^2)
fix f mobile addforce v_fx v_fy 0.0
fix b mobile {integrator}
timestep 0.0226
thermo 20
run 80
"""


class HybridTerms(LammpsTestCase):
    def test_names_the_stiff_substyle(self):
        """The warning names both oscillating atoms (IDs 2 and 3, at distance
        r* = 0.95 from the particle) and pair soft's force as the one that
        alternates (zero's share exactly 0)."""
        if self.plugin_host:
            self.skipTest("on this host fix brownian is upstream BROWNIAN's, which does not watch")
        run = self.run_lmp(HYBRID.format(integrator="brownian 1.0 1 gamma_t 1.0 rng none"))
        warnings = [line for line in run.output.splitlines() if WARNING in line]
        self.assertEqual(len(warnings), 1, run.output[-3000:])
        text = warnings[0]
        self.assertIn("alternates on them is from pair soft", text)
        self.assertIn("pair zero 0 %", text)
        for atom in (2, 3):
            self.assertRegex(text, r"[:;] %d at \(" % atom)

    def test_adaptive_step_stays_stable(self):
        """fix brownian/heun with adapt (dtmax the same 0.0226): the controller
        rejects the unstable steps and keeps dt below Heun's limit 2/97.4, so
        nothing oscillates and nothing is reported."""
        run = self.run_lmp(HYBRID.format(
            integrator="brownian/heun 1.0 1 gamma_t 1.0 rng none adapt tol 1e-4") +
            'print "R $(f_b[4]) $(f_b[1]:%.17g)"\n')
        self.assertEqual([line for line in run.output.splitlines() if WARNING in line], [],
                         run.output[-3000:])
        rejected, dt = [float(w) for w in run.stdout.split("\nR ")[1].split()[:2]]
        self.assertGreater(rejected, 0)
        self.assertLess(dt, 2 / 97.4)


def _make(name):
    def test(self):
        self.check(name)
    integrator, a, b, dt, m, warns = CASES[name]
    test.__doc__ = f"{integrator}, multiplier {m} per step: {'warns' if warns else 'silent'}"
    return test


for _name in CASES:
    setattr(Chatter, "test_" + _name, _make(_name))


if __name__ == "__main__":
    lmptest.main()
