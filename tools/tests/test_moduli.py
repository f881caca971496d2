# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera_tools.moduli without the tessera-hessian executable: the quasistatic
fits and the parameter mapping (the Hessian route is tested in tests/lammps/test_moduli.py)."""
import os
import tempfile
import unittest

import numpy as np

from tessera_tools.moduli import Model, fit_quasistatic


class FitQuasistatic(unittest.TestCase):

    def write(self, rows):
        fd, path = tempfile.mkstemp(suffix=".dat")
        with os.fdopen(fd, "w") as f:
            f.write("# kind strain pxy press pe fnorm\n")
            for r in rows:
                f.write(" ".join(str(v) for v in r) + "\n")
        self.addCleanup(os.remove, path)
        return path

    def test_slopes_and_errors(self):
        """G = -d pxy/d gamma, B = -(1/2) d press/d eps; the error is the standard
        error of the slope, ~ noise / sqrt(sum (x - mean)^2)."""
        rng = np.random.default_rng(3)
        g = np.arange(-5, 6) * 1e-4
        noise = 1e-8
        rows = [("shear", x, 0.1 - 0.7 * x + noise * rng.standard_normal(), -0.5, 0, 0) for x in g]
        rows += [("dilation", x, 0.1, -0.5 - 2 * 8.2 * x + noise * rng.standard_normal(), 0, 0) for x in g]
        q = fit_quasistatic(self.write(rows))
        expected_err = noise / np.sqrt(np.sum((g - g.mean()) ** 2))
        self.assertAlmostEqual(q["G"], 0.7, delta=5 * expected_err)
        self.assertAlmostEqual(q["B"], 8.2, delta=5 * expected_err)
        self.assertGreater(q["G_err"], 0.3 * expected_err)
        self.assertLess(q["G_err"], 3 * expected_err)

    def test_too_few_points(self):
        path = self.write([("shear", 0, 0, 0, 0, 0), ("shear", 1e-4, 0, 0, 0, 0), ("dilation", 0, 0, 0, 0, 0)])
        with self.assertRaisesRegex(ValueError, "at least 3 'shear' lines"):
            fit_quasistatic(path)


class QuadraticMapping(unittest.TestCase):

    def test_energy_is_the_quadratic_form_up_to_a_constant(self):
        """K/2 (A - A0)^2 + Gamma/2 P^2 + w Lambda P = KA (A - A0)^2 + KP (P - P0)^2 - KP P0^2
        with w = 1/2 (tension edge) or 1 (cell)."""
        for tension, w in (("edge", 0.5), ("cell", 1.0)):
            m = Model.quadratic(1.3, 0.9, 0.7, 3.6, tension=tension)
            for A, P in ((1.0, 3.7), (0.8, 4.1)):
                e = m.K[0] / 2 * (A - m.A0[0]) ** 2 + m.Gamma[0] / 2 * P ** 2 + w * m.Lambda[0, 0] * P
                q = 1.3 * (A - 0.9) ** 2 + 0.7 * (P - 3.6) ** 2 - 0.7 * 3.6 ** 2
                self.assertAlmostEqual(e, q, places=12)

    def test_bad_tension(self):
        with self.assertRaisesRegex(ValueError, "tension must be 'edge' or 'cell'"):
            Model(1, 1, 0.1, -0.5, tension="junction")


if __name__ == "__main__":
    unittest.main()
