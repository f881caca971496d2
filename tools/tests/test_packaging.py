# SPDX-License-Identifier: GPL-2.0-or-later
"""tools/ is an installable package: a wheel built from pyproject.toml (with Debian's
setuptools, no network) holds every module of tessera_tools/ and the tessera-tools entry point."""

import os
import shutil
import subprocess
import sys
import tempfile
import unittest
import zipfile

TOOLS = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class Wheel(unittest.TestCase):

    def test_wheel_has_every_module_and_the_entry_point(self):
        if subprocess.run([sys.executable, "-m", "pip", "--version"], capture_output=True).returncode:
            self.skipTest("pip is not installed (Debian package python3-pip)")
        with tempfile.TemporaryDirectory() as d:
            src = os.path.join(d, "src")
            os.makedirs(src)
            for name in ("pyproject.toml", "README.md"):
                shutil.copy(os.path.join(TOOLS, name), src)
            shutil.copytree(os.path.join(TOOLS, "tessera_tools"), os.path.join(src, "tessera_tools"),
                            ignore=shutil.ignore_patterns("__pycache__"))
            proc = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-build-isolation", "--no-deps",
                                   "--no-index", "-w", os.path.join(d, "dist"), src],
                                  capture_output=True, text=True, timeout=240)
            self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
            (wheel,) = os.listdir(os.path.join(d, "dist"))
            with zipfile.ZipFile(os.path.join(d, "dist", wheel)) as z:
                names = z.namelist()
                entry = [n for n in names if n.endswith("entry_points.txt")]
                self.assertTrue(entry, names)
                self.assertIn("tessera-tools = tessera_tools.cli:main", z.read(entry[0]).decode())
        modules = sorted(f for f in os.listdir(os.path.join(TOOLS, "tessera_tools")) if f.endswith(".py"))
        self.assertIn("cli.py", modules)
        for module in modules:
            self.assertIn("tessera_tools/" + module, names)


if __name__ == "__main__":
    unittest.main()
