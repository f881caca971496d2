# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera_tools.host.register picks the route from the LAMMPS it is given:
`plugin load` where the PLUGIN package is installed (once), ctypes otherwise.
A stand-in lammps object records the commands; the real routes run in
tests/lammps (test_python, test_examples_python) on both hosts."""

import os
import tempfile
import unittest
from unittest import mock

import helpers  # noqa: F401  (import path)
from tessera_tools import host


class FakeLammps:
    def __init__(self, packages, loaded=False, loads=True):
        self.installed_packages = packages
        self.commands = []
        self.loaded = loaded
        self.loads = loads
        self.lmp = object()

    def has_style(self, category, name):
        return self.loaded and (category, name) == ("pair", "vertex/voronoi")

    def command(self, text):
        self.commands.append(text)
        if text.startswith("plugin load") and self.loads:
            self.loaded = True


class Register(unittest.TestCase):

    def setUp(self):
        fd, self.plugin = tempfile.mkstemp(suffix="plugin.so")
        os.close(fd)
        self.addCleanup(os.remove, self.plugin)

    def test_plugin_host_loads_the_plugin_once(self):
        lmp = FakeLammps(["BROWNIAN", "PLUGIN"])
        with mock.patch.dict(os.environ, {"TESSERA_PLUGIN": self.plugin}):
            self.assertEqual(host.register(lmp), "plugin")
            self.assertEqual(host.register(lmp), "plugin")
        self.assertEqual(lmp.commands, ['plugin load "%s"' % self.plugin])

    def test_already_loaded_through_plugin_path(self):
        lmp = FakeLammps(["PLUGIN"], loaded=True)
        self.assertEqual(host.register(lmp, plugin="/nonexistent/tesseraplugin.so"), "plugin")
        self.assertEqual(lmp.commands, [])

    def test_plugin_that_adds_nothing_is_an_error(self):
        lmp = FakeLammps(["PLUGIN"], loads=False)
        with self.assertRaisesRegex(RuntimeError, "did not add Tessera's styles"):
            host.register(lmp, plugin=self.plugin)

    def test_missing_plugin_names_the_fix(self):
        lmp = FakeLammps(["PLUGIN"])
        with mock.patch.dict(os.environ, {"TESSERA_PLUGIN": "/nonexistent/tesseraplugin.so"}):
            with self.assertRaisesRegex(FileNotFoundError, "TESSERA_PLUGIN"):
                host.register(lmp)

    def test_without_plugin_package_uses_ctypes(self):
        lmp = FakeLammps(["MOLECULE"])
        calls = []

        class Lib:
            class tessera_register:    # noqa: N801  (a ctypes function stand-in)
                argtypes = restype = None

                def __new__(cls, handle):
                    calls.append(handle)
                    return 4

        with mock.patch.object(host.ctypes, "CDLL", return_value=Lib) as cdll:
            self.assertEqual(host.register(lmp, library="/x/libtessera_lammps.so"), "ctypes")
        cdll.assert_called_once()
        self.assertEqual(calls, [lmp.lmp])
        self.assertEqual(lmp.commands, [])


if __name__ == "__main__":
    unittest.main()
