# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools converge: time averages of thermo samples at uneven times,
the flux through a section from unwrapped coordinates (against a count of the
crossings of the wrapped positions on a fine time grid), the agreement
verdict, and the command end to end with a stand-in for LAMMPS that writes a
log and a dump whose observables depend on the varied value as chosen."""

import math
import os
import subprocess
import sys
import tempfile
import textwrap
import unittest

import numpy as np

from helpers import TOOLS, is_png
from tessera_tools.cli_converge import (block_estimate, combine_starts, compare,
                                        piecewise_linear_means, section_flux)
from tessera_tools.dump import Box, Frame

TOOL = os.path.join(TOOLS, "tessera-tools")


class Averages(unittest.TestCase):
    def test_linear_function_exact(self):
        """The samples of y = 3 t + 1 at uneven times: each block's mean is
        y at the block's middle, whatever the sampling."""
        rng = np.random.default_rng(3)
        t = np.sort(np.concatenate([[0.0, 10.0], rng.uniform(0, 10, 37)]))
        edges = np.linspace(2.0, 9.0, 8)
        means = piecewise_linear_means(t, 3 * t + 1, edges)
        np.testing.assert_allclose(means, 3 * 0.5 * (edges[1:] + edges[:-1]) + 1, rtol=1e-13)

    def test_time_weighting(self):
        """A quantity that is 1 for t < 5 and 3 after, sampled densely before
        and sparsely after: the time average over 0..10 is 2 (a mean over
        samples would be near 1)."""
        t = np.concatenate([np.linspace(0, 5, 501), [5.0 + 1e-9, 7.5, 10.0]])
        y = np.where(t < 5 + 1e-10, 1.0, 3.0)
        (m,) = piecewise_linear_means(t, y, np.array([0.0, 10.0]))
        self.assertAlmostEqual(m, 2.0, delta=1e-8)

    def test_window_outside(self):
        with self.assertRaises(ValueError):
            piecewise_linear_means([0, 1, 2], [1, 1, 1], np.array([0.5, 3.0]))

    def test_block_error(self):
        m, e = block_estimate([1.0, 2.0, 3.0, 4.0])
        self.assertEqual(m, 2.5)
        self.assertAlmostEqual(e, np.std([1, 2, 3, 4], ddof=1) / 2)


def moving_frames(times, x0, v, types, box):
    """Frames of atoms at xu = x0 + v t (y fixed), with their times."""
    frames = []
    for k, t in enumerate(times):
        xu = x0 + v * t
        x = box.xlo + np.mod(xu - box.xlo, box.lx)
        cols = {"id": np.arange(1, len(x0) + 1), "type": types, "x": x,
                "y": np.full(len(x0), 0.5), "xu": xu}
        frames.append(Frame(k, box, cols, list(cols), time=float(t)))
    return frames


def crossings_by_walking(x0, v, types, atom_type, x_section, box, t0, t1, n=20000):
    """Net crossings of x = x_section by the wrapped positions on a fine grid:
    +1 where an atom moving right passes it (or wraps past it), -1 left."""
    total = 0
    grid = np.linspace(t0, t1, n + 1)
    for xi, vi, ti in zip(x0, v, types):
        if ti != atom_type:
            continue
        w = box.xlo + np.mod(xi + vi * grid - box.xlo, box.lx)
        for a, b in zip(w[:-1], w[1:]):
            if vi > 0:
                total += (a < x_section <= b) or (b < a and (x_section > a or x_section <= b))
            elif vi < 0:
                total -= (b < x_section <= a) or (a < b and (x_section > b or x_section <= a))
    return total


class Flux(unittest.TestCase):
    def setUp(self):
        rng = np.random.default_rng(11)
        self.box = Box(-1.0, 9.0, 0.0, 1.0)
        n = 12
        self.x0 = rng.uniform(-1, 9, n)
        self.v = rng.uniform(-0.8, 2.5, n)
        self.types = np.where(np.arange(n) % 4 == 0, 2, 1)
        self.times = np.sort(np.concatenate([[0.0, 20.0], rng.uniform(0, 20, 30)]))

    def test_against_walking(self):
        frames = moving_frames(self.times, self.x0, self.v, self.types, self.box)
        for x_section in (0.3, 4.0, 8.95):
            t0, t1 = self.times[3], self.times[-2]
            flux, err, blocks = section_flux(frames, 1, x_section, t0, t1, 4)
            want = crossings_by_walking(self.x0, self.v, self.types, 1, x_section, self.box, t0, t1)
            self.assertAlmostEqual(flux * (t1 - t0), want, delta=1e-9, msg=x_section)
            self.assertEqual(len(blocks), 4)

    def test_mean_velocity(self):
        """Over a long time the flux is sum(v) / Lx whatever the section."""
        times = np.linspace(0, 1000, 301)
        frames = moving_frames(times, self.x0, self.v, self.types, self.box)
        flux, _, _ = section_flux(frames, 1, 2.0, 0, 1000, 10)
        want = self.v[self.types == 1].sum() / self.box.lx
        self.assertAlmostEqual(flux, want, delta=len(self.x0) / 1000 / self.box.lx)

    def test_needs_time(self):
        frames = moving_frames(self.times, self.x0, self.v, self.types, self.box)
        for f in frames:
            f.time = None
        with self.assertRaisesRegex(ValueError, "time yes"):
            section_flux(frames, 1, 2.0, 0, 10, 2)
        # with a timestep the frames' step numbers give the time
        flux, _, _ = section_flux(frames, 1, 2.0, 0, 10, 2, dt=1.0)
        self.assertTrue(math.isfinite(flux))


class Verdict(unittest.TestCase):
    def test_compare(self):
        self.assertTrue(compare([1.0, 1.05, 1.0], [0.1, 0.1, 0.1])[1])
        z, ok = compare([1.5, 1.0], [0.1, 0.1])
        self.assertFalse(ok)
        self.assertAlmostEqual(z, 0.5 / math.hypot(0.1, 0.1))

    def test_combine_starts(self):
        """Three starts: the mean of their means; the error their spread's
        (std / sqrt 3) when it is the larger, else the block errors carried
        through (sqrt of the sum of squares over 3)."""
        m, e = combine_starts([(1.0, 0.1), (2.0, 0.1), (3.0, 0.1)])
        self.assertAlmostEqual(m, 2.0)
        self.assertAlmostEqual(e, 1.0 / math.sqrt(3))
        m, e = combine_starts([(1.0, 0.3), (1.01, 0.4), (0.99, 0.0)])
        self.assertAlmostEqual(m, 1.0)
        self.assertAlmostEqual(e, 0.5 / 3)
        self.assertEqual(combine_starts([(1.5, 0.2)]), (1.5, 0.2))


# A stand-in for LAMMPS: reads -var NAME VALUE pairs and writes log.lammps and
# a dump.  Thermo 'good' is 2 + noise whatever the value, 'bad' is 2 + 30
# value: the first converges, the second does not; atoms of type 1 move at
# speed 0.5, so the flux through any section is N 0.5 / Lx.
FAKE = textwrap.dedent('''\
    import random
    import sys
    a = sys.argv[1:]
    var = {a[i + 1]: a[i + 2] for i in range(len(a)) if a[i] == "-var"}
    value = float(var["dt"])
    shift = float(var.get("shift", "0")) + 0.1 * float(var.get("start", "0"))
    rng = random.Random(int(1e6 * value))
    with open("log.lammps", "w") as f:
        f.write("LAMMPS (fake)\\ntimestep " + repr(value) + "\\n")
        f.write("Step Time Dt good bad\\n")
        t, step = 0.0, 0
        while t <= 100.0:
            f.write(f"{step} {t} {value} {2 + shift + 0.01 * rng.gauss(0, 1)} {2 + 30 * value}\\n")
            step += 10
            t += 10 * value * (1 + 0.5 * rng.random())
        f.write("Loop time of 1 on 1 procs\\nTotal wall time: 0:00:01\\n")
    n, lx = 6, 5.0
    with open("dump.test", "w") as f:
        for k in range(201):
            t = 0.5 * k
            f.write(f"ITEM: TIME\\n{t}\\nITEM: TIMESTEP\\n{k}\\nITEM: NUMBER OF ATOMS\\n{n}\\n")
            f.write(f"ITEM: BOX BOUNDS pp pp pp\\n0 {lx}\\n0 1\\n-0.5 0.5\\nITEM: ATOMS id type xu\\n")
            for i in range(n):
                f.write(f"{i + 1} 1 {0.9 * i + 0.5 * t}\\n")
    ''')


def stand_in(tmp):
    """The stand-in LAMMPS (an executable tmp/bin/lmp) and an input tmp/in.test (the
    files beside an input are copied into the runs' directories: bin/ is not)."""
    os.makedirs(os.path.join(tmp, "bin"))
    fake = os.path.join(tmp, "bin", "fake_lmp.py")
    with open(fake, "w") as f:
        f.write(FAKE)
    lmp = os.path.join(tmp, "bin", "lmp")
    with open(lmp, "w") as f:
        f.write(f"#!/bin/sh\nexec {sys.executable} {fake} \"$@\"\n")
    os.chmod(lmp, 0o755)
    inp = os.path.join(tmp, "in.test")
    with open(inp, "w") as f:
        f.write("# read by the stand-in only through -var\n")
    return lmp, inp


class Command(unittest.TestCase):
    def test_end_to_end(self):
        with tempfile.TemporaryDirectory() as tmp:
            lmp, inp = stand_in(tmp)
            out = os.path.join(tmp, "runs")
            cmd = [sys.executable, TOOL, "converge", inp, "--halve", "dt=0.02", "--lmp", lmp,
                   "--out", out, "--window", "20", "90", "--flux", "1", "2.5", "--dump", "dump.test",
                   "--table", os.path.join(tmp, "t.md"), "--set", "shift=0"]
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
            self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
            rows = {line.split("|")[1].strip(): line for line in proc.stdout.splitlines()
                    if line.startswith("| ") and "observable" not in line}
            self.assertTrue(rows["good"].rstrip().endswith("| yes |"), rows["good"])
            self.assertTrue(rows["bad"].rstrip().endswith("| NO |"), rows["bad"])
            flux = rows["flux of type 1 through x = 2.5"]
            self.assertIn("0.6 +-", flux)    # 6 atoms at speed 0.5 in a box of length 5
            self.assertTrue(flux.rstrip().endswith("| yes |"))
            for v in ("0.02", "0.01", "0.005"):
                self.assertTrue(os.path.exists(os.path.join(out, f"dt_{v}", "log.lammps")))
            self.assertTrue(is_png(os.path.join(out, "converge.png")))
            with open(os.path.join(tmp, "t.md")) as f:
                self.assertEqual(f.read(), proc.stdout)
            # --reuse runs nothing: a broken executable is not called
            broken = os.path.join(tmp, "broken")
            with open(broken, "w") as f:
                f.write("#!/bin/sh\nexit 3\n")
            os.chmod(broken, 0o755)
            again = subprocess.run(cmd[:cmd.index("--lmp") + 1] + [broken] + cmd[cmd.index("--lmp") + 2:]
                                   + ["--reuse"], capture_output=True, text=True, timeout=120)
            self.assertEqual(again.returncode, 0, again.stderr)
            failing = subprocess.run(cmd[:cmd.index("--lmp") + 1] + [broken] + cmd[cmd.index("--lmp") + 2:],
                                     capture_output=True, text=True, timeout=120)
            self.assertNotEqual(failing.returncode, 0)
            self.assertIn("failed", failing.stderr)

    def test_seeds(self):
        # three starts per value (-var start S): their means 2.1, 2.2, 2.3 average
        # to 2.2 with the spread's error 0.1 / sqrt(3), and each start's own row
        with tempfile.TemporaryDirectory() as tmp:
            lmp, inp = stand_in(tmp)
            out = os.path.join(tmp, "runs")
            proc = subprocess.run([sys.executable, TOOL, "converge", inp, "--var", "dt",
                                   "--values", "0.02", "0.01", "--seeds", "1", "2", "3",
                                   "--seed-var", "start", "--lmp", lmp, "--out", out,
                                   "--window", "20", "90", "--thermo", "good", "--jobs", "2"],
                                  capture_output=True, text=True, timeout=120)
            self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
            rows = [line for line in proc.stdout.splitlines() if line.startswith("| good |")]
            cells = [c.split("+-") for c in rows[0].split("|")[2:4]]
            for mean, err in cells:
                self.assertAlmostEqual(float(mean), 2.2, delta=0.005)    # noise 0.01 per sample
                self.assertEqual(err.strip(), "0.058")
            self.assertTrue(rows[0].rstrip().endswith("| yes |"), rows[0])
            self.assertIn("3 starts (start = 1, 2, 3)", proc.stdout)
            self.assertEqual(len(rows), 3)    # the combined row and one per value
            self.assertRegex(rows[1], r"\| good \| 0.02 \| 2.1\d* \+- \S+ \| 2.2\d* \+- \S+ \| 2.3")
            for v in ("0.02", "0.01"):
                for k in ("1", "2", "3"):
                    self.assertTrue(os.path.exists(os.path.join(out, f"dt_{v}", f"start_{k}",
                                                                "log.lammps")))

    def test_relative_paths(self):
        # each run starts in its own directory, so --lmp relative to the
        # caller's directory must still name the same executable there
        with tempfile.TemporaryDirectory() as tmp:
            stand_in(tmp)
            proc = subprocess.run([sys.executable, TOOL, "converge", "in.test", "--var", "dt",
                                   "--values", "0.02", "0.01", "--lmp", "bin/lmp", "--out", "runs",
                                   "--window", "20", "90", "--thermo", "good",
                                   "--plot", "figures/c.png", "--table", "tables/c.md"],
                                  cwd=tmp, capture_output=True, text=True, timeout=120)
            self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
            # (directories of --plot and --table made as needed)
            self.assertTrue(is_png(os.path.join(tmp, "figures", "c.png")))
            self.assertTrue(os.path.exists(os.path.join(tmp, "tables", "c.md")))
            for v in ("0.02", "0.01"):
                self.assertTrue(os.path.exists(os.path.join(tmp, "runs", f"dt_{v}", "log.lammps")))

    def test_bad_arguments(self):
        proc = subprocess.run([sys.executable, TOOL, "converge", "no_such_input", "--var", "dt"],
                              capture_output=True, text=True, timeout=60)
        self.assertNotEqual(proc.returncode, 0)
        self.assertIn("at least two values", proc.stderr)


if __name__ == "__main__":
    unittest.main()
