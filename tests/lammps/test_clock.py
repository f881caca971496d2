#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""fix clock: a time that continues across restart files on both hosts.
LAMMPS 29 Sep 2021 keeps no time in restart files (its `time` starts again
at 0 at the first run after read_restart); LAMMPS 4 Jul 2026 keeps it.  The
clock is the sum of the timesteps of the runs (analytic here: runs of known
length and timestep), the same number as LAMMPS's `time` where that does
not break, and it does not advance during minimize.  A sphere radius that
reads `time` where it restarted at 0 gets a warning.  Every run restarts
within one LAMMPS process ('clear', then read_restart), which on LAMMPS 29
Sep 2021 starts `time` at 0 as a new process does."""

import os
import re

import lmptest
from lmptest import LammpsTestCase

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")

CELLS = """units lj
atom_style dipole
boundary f f f
region box block 0 20 0 20 0 20
create_box 1 box
create_atoms 1 random 40 123 box
mass 1 1.0
set group all dipole/random 5 1.0
"""

# the styles a restart file does not keep; radius: what v_R reads
SETUP = """variable R equal 3*exp(0.5*0.1*{clock})
pair_style vertex/voronoi 8 surface sphere 10 10 10 v_R
pair_coeff * * 1 2.8 0.1 -0.2
fix b all brownian 1.0 1 gamma_t 1.0 rng none
{fix}
thermo_style custom step time {clock} v_R
thermo_modify format float %.17g
thermo 10
"""


def rows(output):
    """(step, time, clock, R) of every thermo row."""
    out = []
    for line in output.splitlines():
        w = line.split()
        if len(w) == 4 and re.match(r"^\d+$", w[0]):
            try:
                out.append((int(w[0]), float(w[1]), float(w[2]), float(w[3])))
            except ValueError:
                pass
    return out


def restarted(clock, fix="fix clk all clock"):
    """20 steps of 0.05, write_restart, clear, read_restart, 10 steps of 0.02."""
    setup = SETUP.format(clock=clock, fix=fix)
    return (CELLS + setup + "timestep 0.05\nrun 20\nwrite_restart r.bin\nclear\n"
            "read_restart r.bin\n" + setup + "timestep 0.02\nrun 10\n")


class Restart(LammpsTestCase):

    def test_clock_continues(self):
        run = self.run_lmp(restarted("f_clk"))
        r = rows(run.stdout)
        by_step = {}
        for step, t, clock, R in r:
            by_step.setdefault(step, []).append((t, clock, R))
        # before: the clock is LAMMPS's time, step x 0.05
        self.assertEqual(by_step[20][0][1], by_step[20][0][0])
        self.assertAlmostEqual(by_step[20][0][1], 1.0, delta=1e-12)
        # after: it goes on from 1.0 with the new timestep, on both hosts
        self.assertEqual(len(by_step[20]), 2, run.stdout[-3000:])
        self.assertAlmostEqual(by_step[20][1][1], 1.0, delta=1e-12)
        self.assertAlmostEqual(by_step[30][0][1], 1.0 + 10 * 0.02, delta=1e-12)
        # and the radius with it, without a jump
        self.assertEqual(by_step[20][1][2], by_step[20][0][2])
        self.assertAlmostEqual(by_step[30][0][2], 3 * 2.718281828459045 ** (0.05 * 1.2),
                               delta=1e-12)
        # LAMMPS's own time: 29 Sep 2021 starts again at 0, 4 Jul 2026 goes on
        self.assertEqual(by_step[20][1][0], 1.0 if self.plugin_host else 0.0)
        self.assertNotIn("reads LAMMPS's time", run.output)
        if self.plugin_host:
            self.assertNotIn("fix clock clk: the clock goes on", run.stdout)
        else:
            self.assertIn("fix clock clk: the clock goes on at 1 at step 20, where LAMMPS's own "
                          "time is 0", run.stdout)

    def test_radius_reading_time_warns_where_time_restarted(self):
        run = self.run_lmp(restarted("time", fix=""))
        r = rows(run.stdout)
        after = [row for row in r if row[0] == 20][-1]
        warn = [l for l in run.output.splitlines() if "WARNING" in l and "reads LAMMPS's time" in l]
        if self.plugin_host:
            # time goes on: so does the radius, and nothing is said
            self.assertEqual(warn, [])
            self.assertAlmostEqual(after[3], 3 * 2.718281828459045 ** 0.05, delta=1e-12)
        else:
            # the radius jumped back to R(0) = 3; the warning says so, and
            # what it would be had every step been as long as the current
            # one (20 x 0.02: R = 3 exp(0.02) = 3.0606)
            self.assertEqual(after[3], 3.0)
            self.assertEqual(len(warn), 1, run.output[-3000:])
            for fragment in ("which is 0 at step 20", "The radius is 3, its value at time 0",
                             "at time 0.4 (20 steps of 0.02) it would be 3.0606",
                             "'fix ID all clock'", "read f_ID instead of time"):
                self.assertIn(fragment, warn[0])

    def test_restart_without_the_fix_of_the_file(self):
        # a clock defined anew after read_restart (another ID) starts at
        # LAMMPS's time when it is defined: on 4 Jul 2026 the file's, on
        # 29 Sep 2021 step x the file's timestep (its time before the first
        # run), 1.0 on both here
        script = restarted("f_clk").replace("read_restart r.bin\n" + SETUP.format(
            clock="f_clk", fix="fix clk all clock"), "read_restart r.bin\n" + SETUP.format(
            clock="f_c2", fix="fix c2 all clock"))
        run = self.run_lmp(script)
        after = [row for row in rows(run.stdout) if row[0] == 20][-1]
        self.assertAlmostEqual(after[2], 1.0, delta=1e-12)


class Runs(LammpsTestCase):

    def test_same_as_time_and_not_advanced_by_minimize(self):
        # three runs with two timesteps and a minimize between them: the
        # clock is LAMMPS's time to the last bit where that does not break,
        # and stands still during minimize; reset_timestep does not move it
        setup = SETUP.format(clock="f_clk", fix="fix clk all clock").replace(
            "thermo 10", "thermo 5")
        script = (CELLS + setup + "timestep 0.05\nrun 10\n"
                  "print \"AFTER1 $(f_clk:%.17g) $(time:%.17g)\"\n"
                  "minimize 0 0 7 7\nprint \"AFTERMIN $(f_clk:%.17g)\"\n"
                  "timestep 0.03\nrun 10\nprint \"AFTER2 $(f_clk:%.17g)\"\n"
                  "reset_timestep 0\nrun 5\nprint \"AFTER3 $(f_clk:%.17g)\"\n")
        run = self.run_lmp(script)
        printed = {l.split()[0]: [float(w) for w in l.split()[1:]]
                   for l in run.stdout.splitlines() if l.startswith("AFTER")}
        self.assertEqual(printed["AFTER1"][0], printed["AFTER1"][1])
        self.assertAlmostEqual(printed["AFTER1"][0], 0.5, delta=1e-12)
        self.assertEqual(printed["AFTERMIN"][0], printed["AFTER1"][0])
        self.assertAlmostEqual(printed["AFTER2"][0], 0.5 + 10 * 0.03, delta=1e-12)
        self.assertAlmostEqual(printed["AFTER3"][0], 0.5 + 15 * 0.03, delta=1e-12)
        # within the first run every thermo row: clock = time, bit for bit
        first = [row for row in rows(run.stdout) if row[0] <= 10][:3]
        self.assertEqual(len(first), 3)
        for step, t, clock, _ in first:
            self.assertEqual(clock, t)

    def test_follows_fix_dt_reset(self):
        # a timestep that changes every step: the clock is LAMMPS's time,
        # bit for bit, on every row
        setup = SETUP.format(clock="f_clk", fix="fix clk all clock").replace("thermo 10",
                                                                             "thermo 3")
        run = self.run_lmp(CELLS + setup + "fix dt all dt/reset 1 1e-4 0.05 0.01 units box\n"
                           "run 12\n")
        table = rows(run.stdout)
        self.assertEqual(len(table), 5)
        self.assertGreater(table[-1][1], 0.0)
        for step, t, clock, _ in table:
            self.assertEqual(clock, t)

    def test_arguments_refused(self):
        run = self.run_lmp(CELLS + "fix c all clock 5\n", ok=False)
        self.assertLammpsError(run, "fix clock: takes no arguments after the style",
                               "'fix c all clock'")


class Organoid(LammpsTestCase):

    def test_radius_continues_across_a_restart(self):
        # examples/organoid for 10 steps, a restart, 10 more: R(t) of the
        # continued run goes on from where the first part ended (it used to
        # jump back to R0 on LAMMPS 29 Sep 2021), on both hosts
        with open(os.path.join(EXAMPLES, "organoid", "in.organoid")) as f:
            text = f.read()
        text = text.replace("thermo          250", "thermo          5")
        text = re.sub(r"(?m)^dump.*\n", "", text)
        first = text + "write_restart r.bin\nclear\n"
        begin = text.index("units           lj")
        end = text.index("mass            1 1.0")
        second = text[:begin] + "read_restart r.bin\n" + text[end:].replace(
            "mass            1 1.0\n", "", 1).replace("run             ${nsteps}",
                                                       "run             10")
        run = self.run_lmp(first + second, variables={"tend": 0.2})
        table = []
        for line in run.stdout.splitlines():
            w = line.split()
            if len(w) == 7 and re.match(r"^\d+$", w[0]):
                table.append((int(w[0]), float(w[3])))
        steps = [s for s, _ in table]
        self.assertEqual(steps, [0, 5, 10, 10, 15, 20], run.stdout[-3000:])
        R0 = (200 / (4 * 3.141592653589793)) ** 0.5
        for step, R in table:
            self.assertAlmostEqual(R, R0 * 2.718281828459045 ** (0.5 * 0.01 * 0.02 * step),
                                   delta=1e-5 * R)
        self.assertNotIn("reads LAMMPS's time", run.output)


lmptest.main()
