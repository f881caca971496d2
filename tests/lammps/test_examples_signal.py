#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The signalling examples, run briefly: examples/morphogen_organoid (a
morphogen from one pole of a tissue on a sphere steers growth and division)
to t = 20, checked against what its README says: the morphogen falls from
the source pole, each cell's preferred area is the README's function of its
morphogen, cells divide near the source and not at the far pole, and the
sphere's area is the sum of the preferred areas; examples/erk_waves (ERK
activity driven by stretch, preferred area falling with ERK, a persistent
random walk): its uniform state sits at the fixed point derived from its
equations, and the coupling 3 times the continuum model's threshold leaves
the uniform state for travelling ERK-density waves with the period of that
model's linear stability, where 0.5 times the threshold does not."""

import math
import os
import sys

import numpy as np

import lmptest
from lmptest import LammpsTestCase

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from tessera_tools.kymograph import measure_wave  # noqa: E402


class MorphogenOrganoid(LammpsTestCase):

    def test_growth_follows_the_gradient(self):
        with open(os.path.join(EXAMPLES, "morphogen_organoid", "in.morphogen_organoid")) as f:
            script = f.read()
        script = script.replace("dump            cells all custom 2500",
                                "dump            cells all custom 500")
        script = script.replace("dump_modify     cells sort id format float %.10g",
                                "dump_modify     cells sort id format float %.17g")
        script = script.replace("dump            edges", "# dump edges").replace(
            "dump_modify     edges", "# dump_modify edges")
        run = self.run_lmp(script, args=["-var", "tend", "20"])
        last = run.dump("dump.cells")[-1]
        self.assertEqual(last["step"], 1000)
        h, m, a0, gen = last["v_h"], last["c_sm"], last["d_area0"], last["f_div[2]"]
        # the preferred area is 1 + m / (0.5 + m), set at this step from this m
        np.testing.assert_allclose(a0, 1 + m / (0.5 + m), rtol=0, atol=1e-12)
        # the morphogen falls from the source pole to the far one
        self.assertGreater(m[h > 0.8].mean(), 20 * m[h < -0.8].mean())
        self.assertTrue(np.all(m > 0))
        # divisions near the source only: the far half keeps its first cells
        n = len(last["id"])
        self.assertGreater(n, 240)
        self.assertTrue(np.all(gen[h < -0.3] == 0))
        self.assertGreater(gen[h > 0.5].mean(), 2.0)
        # the cells lie on one sphere, whose area is the sum of the preferred
        # areas the cells had when they were placed on it (this step's
        # d_area0 were set after that, at the end of the step: 1e-3)
        r = np.linalg.norm(np.column_stack([last["x"], last["y"], last["z"]]) - 10.0, axis=1)
        np.testing.assert_allclose(r, r.mean(), rtol=1e-9)
        self.assertAlmostEqual(4 * math.pi * r.mean() ** 2 / a0.sum(), 1.0, delta=1e-3)
        self.assertGreater(r.mean(), 1.1 * math.sqrt(200 / (4 * math.pi)))

class ErkWaves(LammpsTestCase):
    """examples/erk_waves: dE/dt = -E - E^3 + beta (A - 1), tau_l dA0/dt = 1 - A0 - alpha E,
    the forces using max(A0, 0.1); alpha beta = n (tau_l + 1)(sqrt(tau_l) + 1)^2 / tau_l,
    alpha / beta = 18.5, tau_l = 20."""

    TAUL, RATIO, AMIN = 20.0, 18.5, 0.1

    def script(self):
        with open(os.path.join(EXAMPLES, "erk_waves", "in.erk_waves")) as f:
            return f.read().replace("format float %.7g", "format float %.15g")

    def couplings(self, n):
        abc = (self.TAUL + 1) * (math.sqrt(self.TAUL) + 1) ** 2 / self.TAUL
        beta = math.sqrt(n * abc / self.RATIO)
        return self.RATIO * beta, beta

    def test_uniform_state_at_the_fixed_point(self):
        # A perfect honeycomb of area a per cell, no activity, p0 = 3.5 (below the regular
        # hexagon's 3.72, where the honeycomb is stable): every cell keeps area a and
        # the chemistry goes to E* with E* + E*^3 = beta (a - 1), A0* = 1 - alpha E*
        # (below the floor the forces get 0.1; a uniform A0 exerts no force on a perfect lattice)
        floor = 0
        for n, area in ((0.0, 1.02), (0.5, 1.02), (3.0, 1.02), (3.0, 0.97)):
            with self.subTest(n=n, area=area):
                alpha, beta = self.couplings(n)
                s = self.script().replace("lattice         hex 1.0 ", f"lattice         hex {1 / area!r} ")
                run = self.run_lmp(s, args=["-var", "n", str(n), "-var", "fa", "0", "-var", "jitter", "0", "-var", "p0", "3.5",
                                            "-var", "nx", "6", "-var", "ny", "3", "-var", "tend", "400",
                                            "-var", "dt", "0.05", "-var", "every", "8000"])
                last = run.dump("dump.erk")[-1]
                self.assertEqual(last["step"], 8000)
                np.testing.assert_allclose(last["c_cell[1]"], area, rtol=1e-9)
                roots = np.roots([1.0, 0.0, 1.0, -beta * (area - 1.0)])
                estar = float(roots[np.argmin(abs(roots.imag))].real)
                a0star = 1.0 - alpha * estar
                np.testing.assert_allclose(last["v_E"], estar, rtol=0, atol=1e-9)
                # A0 relaxes over tau_l = 20: after 400, exp(-20) of its start 1 - A0*
                np.testing.assert_allclose(last["v_A0"], a0star, rtol=0, atol=1e-7)
                np.testing.assert_allclose(last["d_area0"], max(a0star, self.AMIN), rtol=0, atol=1e-7)
                floor += a0star < self.AMIN
        self.assertEqual(floor, 1)     # one row has the forces at the floor

    def wave_run(self, n):
        run = self.run_lmp(self.script(), args=["-var", "n", str(n), "-var", "tend", "150"])
        frames = run.dump("dump.erk")
        later = [f for f in frames if f["step"] * 0.01 >= 75 - 1e-9]
        times = np.array([f["step"] * 0.01 for f in later])
        lx = later[0]["box"][0, 1] - later[0]["box"][0, 0]
        bins = 24
        edges = np.linspace(0, lx, bins + 1)
        centres = 0.5 * (edges[1:] + edges[:-1])
        erk, rho = [], []
        for f in later:
            k = np.floor((f["x"] - later[0]["box"][0, 0]) / lx * bins).astype(int) % bins
            cnt = np.bincount(k, minlength=bins)
            erk.append(np.bincount(k, weights=f["v_E"], minlength=bins) / np.maximum(cnt, 1))
            rho.append(cnt)
        e = np.concatenate([f["v_E"] for f in later])
        return np.sqrt(np.mean(e ** 2)), measure_wave(times, centres, erk), measure_wave(times, centres, rho), lx

    def test_waves_at_strong_coupling_only(self):
        period = 2 * math.pi / math.sqrt(self.TAUL ** -0.5 + self.TAUL ** -1.5 + 1 / self.TAUL)
        weak, _, _, _ = self.wave_run(0.5)
        strong, we, wr, lx = self.wave_run(3.0)
        # the uniform state is left: ERK swings several times wider than the activity alone drives
        self.assertLess(weak, 0.06)
        self.assertGreater(strong, 4 * weak)
        # a travelling wave: one clear Fourier peak, a whole number of wavelengths in the box,
        # the period of the continuum model's linear stability (11.77) within 30 %
        self.assertGreater(we["power"], 0.3)
        self.assertAlmostEqual(lx / we["wavelength"], round(lx / we["wavelength"]), delta=0.05)
        self.assertTrue(math.isfinite(we["period"]))
        self.assertLess(abs(we["period"] / period - 1), 0.3)
        # the density travels with ERK: the same wavelength and period
        self.assertAlmostEqual(wr["wavelength"] / we["wavelength"], 1.0, delta=0.02)
        self.assertAlmostEqual(wr["period"] / we["period"], 1.0, delta=0.02)


if __name__ == "__main__":
    lmptest.main()
