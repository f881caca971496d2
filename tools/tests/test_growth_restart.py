# SPDX-License-Identifier: GPL-2.0-or-later
"""examples/growth is restart-safe: run in.growth part of the way, continue with
in.growth.continue from its restart file, and the box keeps obeying lx ly = N a at the
starting aspect ratio (no jump), as in one uninterrupted run.  Needs tessera-lmp (skipped
otherwise)."""

import math
import os
import shutil
import subprocess
import tempfile
import unittest

from helpers import TOOLS
from tessera_tools.logplot import parse_log

REPO = os.path.dirname(TOOLS)
EXAMPLE = os.path.join(REPO, "examples", "growth")


def find_lmp():
    build = os.environ.get("TESSERA_BUILD") or os.path.join(REPO, "build")
    for path in (os.environ.get("TESSERA_LMP"), os.path.join(build, "lammps", "tessera-lmp")):
        if path and os.access(path, os.X_OK):
            return path
    return None


@unittest.skipIf(find_lmp() is None, "tessera-lmp is not built (scripts/build)")
class GrowthRestart(unittest.TestCase):

    def run_lmp(self, d, script, log, **variables):
        cmd = [find_lmp(), "-in", script, "-log", log, "-screen", "none", "-nocite"]
        for k, v in variables.items():
            cmd += ["-var", k, str(v)]
        proc = subprocess.run(cmd, cwd=d, capture_output=True, text=True, timeout=600)
        self.assertEqual(proc.returncode, 0, proc.stdout[-2000:] + proc.stderr[-2000:])
        return parse_log(os.path.join(d, log)).combined()

    def test_box_follows_n_across_a_restart(self):
        with tempfile.TemporaryDirectory() as d:
            for name in ("in.growth", "in.growth.continue"):
                shutil.copy(os.path.join(EXAMPLE, name), d)
            first = self.run_lmp(d, "in.growth", "log.first", tend=6)
            self.assertTrue(os.path.exists(os.path.join(d, "restart.growth")))
            second = self.run_lmp(d, "in.growth.continue", "log.second", tend=12)
            # the analytic rule, from the very first row: lx = sqrt(N a r), ly = sqrt(N a / r)
            a = first["Lx"][0] * first["Ly"][0] / first["Atoms"][0]
            r = first["Lx"][0] / first["Ly"][0]
            for table in (first, second):
                for n, lx, ly in zip(table["Atoms"], table["Lx"], table["Ly"]):
                    self.assertAlmostEqual(lx / math.sqrt(n * a * r), 1.0, delta=2e-5)    # thermo prints 6 digits
                    self.assertAlmostEqual(ly / math.sqrt(n * a / r), 1.0, delta=2e-5)    # thermo prints 6 digits
            # no jump: the continued run starts where the first ended, and goes on growing
            self.assertEqual(second["Step"][0], first["Step"][-1])
            self.assertAlmostEqual(second["Lx"][0], first["Lx"][-1], delta=1e-5 * first["Lx"][-1])
            self.assertEqual(second["Step"][-1], 600)
            self.assertGreater(second["Atoms"][-1], first["Atoms"][-1])


if __name__ == "__main__":
    unittest.main()
