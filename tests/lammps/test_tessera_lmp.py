#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The tessera-lmp driver: lmp's command-line flags, our styles in -h, MPI.
On the plugin host the same runs go through that LAMMPS's own lmp, with the
plugin loaded from LAMMPS_PLUGIN_PATH; where lmp itself differs from
tessera-lmp (help, argument errors), each host's behaviour is checked."""

import os
import re

import lmptest
from lmptest import LammpsTestCase, nprocs

# Prints its variable and moves one atom by a known amount with fix brownian.
SCRIPT = """
units lj
dimension 2
atom_style atomic
atom_modify map yes
region box block 0 10 0 10 -0.5 0.5
create_box 1 box
create_atoms 1 single 1.0 2.0 0.0
mass 1 1.0
fix f all addforce 3.0 0.0 0.0
fix 1 all brownian 1.0 5 gamma_t 2.0 rng none
timestep 0.1
run 10
variable x equal x[1]
print "VALUE of greeting: ${greeting}"
print "POSITION x = $(v_x:%.12f)"
"""


class Driver(LammpsTestCase):

    def position(self, text):
        match = re.search(r"^POSITION x = (\S+)$", text, re.M)
        self.assertIsNotNone(match, text[-2000:])
        return float(match.group(1))

    def test_help_lists_our_styles(self):
        run = self.run_lmp(None, args=["-h"])
        out = run.stdout
        if self.plugin_host:
            # lmp's -h is printed before plugins load: it lists upstream's
            # styles; `plugin list` names ours.
            fixes = out.split("* Fix styles")[1].split("* Compute styles")[0]    # no ':' in 2026
            self.assertIn("brownian", fixes.split())    # upstream BROWNIAN's
            self.assertRegex(out, r"(?m)^Installed packages:\s*\n\s*\n?.*\bPLUGIN\b")
            self.assertFalse(os.path.exists(run.path("log.lammps")))
            listed = self.run_lmp("plugin list\n").stdout
            for style in ("pair style plugin vertex/voronoi", "fix style plugin polarity",
                          "compute style plugin vertex/atom"):
                self.assertIn(style, listed)
            self.assertNotRegex(listed, r"(?m)fix style plugin brownian$")
            return
        ours = out.split("Tessera's styles:")[1].split("OS:")[0]
        self.assertRegex(ours, r"(?m)^  fix brownian +Tessera$")
        fixes = out.split("* Fix styles:")[1].split("* Compute styles:")[0]
        self.assertIn("brownian", fixes.split())
        self.assertIn("addforce", fixes.split())    # LAMMPS's own are still listed
        self.assertIn("-var name value", out)
        self.assertIn("Installed packages:", out)
        self.assertFalse(os.path.exists(run.path("log.lammps")))    # -h writes no log

    @nprocs(2)
    def test_help_on_two_ranks_prints_once(self):
        run = self.run_lmp(None, args=["-help"], nprocs=2)
        self.assertEqual(run.stdout.count("Usage example:"), 1)
        if not self.plugin_host:
            self.assertEqual(run.stdout.count("Tessera's styles:"), 1)

    def test_in_var_and_default_log(self):
        run = self.run_lmp(SCRIPT, variables={"greeting": "hello"})
        self.assertIn("VALUE of greeting: hello", run.stdout)
        self.assertAlmostEqual(self.position(run.stdout), 1.0 + 10 * 0.1 * 3.0 / 2.0, places=10)
        log = run.text("log.lammps")
        if self.plugin_host:    # fix brownian is upstream's
            self.assertRegex(log, r"(?m)^Tessera \S+ styles: .*pair_style vertex/voronoi")
            self.assertRegex(log, r"(?m)^  kept the host LAMMPS's own: fix brownian$")
        else:
            self.assertRegex(log, r"(?m)^Tessera \S+ styles: .*fix brownian")
        self.assertIn("VALUE of greeting: hello", log)

    def test_log_file(self):
        run = self.run_lmp(SCRIPT, variables={"greeting": "x"}, args=["-log", "my.log"])
        self.assertFalse(os.path.exists(run.path("log.lammps")))
        self.assertIn("VALUE of greeting: x", run.text("my.log"))

    def test_log_none(self):
        run = self.run_lmp(SCRIPT, variables={"greeting": "x"}, args=["-log", "none"])
        self.assertEqual([f for f in os.listdir(run.dir) if f.startswith("log")], [])

    def test_screen_file(self):
        run = self.run_lmp(SCRIPT, variables={"greeting": "x"}, args=["-screen", "out.txt"])
        self.assertNotIn("VALUE of greeting", run.stdout)
        self.assertIn("VALUE of greeting: x", run.text("out.txt"))

    def test_echo_screen(self):
        run = self.run_lmp(SCRIPT, variables={"greeting": "x"}, args=["-echo", "screen"])
        self.assertIn("fix 1 all brownian 1.0 5 gamma_t 2.0 rng none", run.stdout)
        quiet = self.run_lmp(SCRIPT, variables={"greeting": "x"})
        self.assertNotIn("fix 1 all brownian 1.0 5 gamma_t 2.0 rng none", quiet.stdout)

    def test_short_flags(self):
        run = self.run_lmp(None, args=["-i", "in.test", "-v", "greeting", "short", "-l", "s.log"],
                           files={"in.test": SCRIPT})
        self.assertIn("VALUE of greeting: short", run.text("s.log"))

    def test_input_from_stdin(self):
        run = self.run_lmp(None, variables={"greeting": "stdin"}, stdin=SCRIPT)
        self.assertIn("VALUE of greeting: stdin", run.stdout)

    # A restart file that names Tessera's pair style: plain lmp cannot read it.
    RESTART = """
dimension 2
units lj
atom_style dipole
lattice hex 1.0
region box block 0 6 0 3 -0.5 0.5
create_box 1 box
create_atoms 1 box
mass 1 1.0
pair_style vertex/voronoi 6.0
pair_coeff * * 1.0 1.0 0.1 -1.5
fix move all brownian 1.0 12908410 gamma_t 1.0 rng none
timestep 0.01
run 5
write_restart rs.restart
"""

    def test_restart2data(self):
        made = self.run_lmp(self.RESTART)
        run = self.run_lmp(None, args=["-r2data", made.path("rs.restart"), "out.data"])
        self.assertIn("restoring pair style vertex/voronoi", run.stdout)
        data = run.text("out.data")
        self.assertIn("timestep = 5", data)
        self.assertRegex(data, r"(?m)^36 atoms$")

    def test_restart2dump(self):
        made = self.run_lmp(self.RESTART)
        run = self.run_lmp(None, args=["-restart2dump", made.path("rs.restart"), "remap", "all",
                                       "custom", "out.dump", "id", "x", "y"])
        (frame,) = run.dump("out.dump")
        self.assertEqual(frame["step"], 5)
        self.assertEqual(sorted(frame["id"]), list(range(1, 37)))

    def test_restart2data_missing_file(self):
        run = self.run_lmp(None, args=["-r2data", "rs.restart"], ok=False)
        self.assertLammpsError(run, "Invalid command-line argument" if self.plugin_host
                               else "-restart2data needs the data file")

    def test_error_exit_status(self):
        run = self.run_lmp("region b block 0 1 0 1 0 1\ncreate_box 1 b\nfix 1 all nosuchstyle\n",
                           ok=False)
        self.assertLammpsError(run, "Unrecognized fix style 'nosuchstyle'")

    def test_plugin_load_banner_once(self):
        """`plugin load` prints LAMMPS's "Loading plugin" line once, not once per
        style, and registers every style (plugin host only)."""
        if not self.plugin_host:
            self.skipTest("tessera-lmp has its styles built in: no plugin load")
        saved = os.environ.pop("LAMMPS_PLUGIN_PATH", None)    # not loaded at start-up
        try:
            run = self.run_lmp("plugin load %s\nplugin list\n" % lmptest.Config.plugin)
        finally:
            if saved is not None:
                os.environ["LAMMPS_PLUGIN_PATH"] = saved
        self.assertEqual(run.stdout.count("Loading plugin: Tessera"), 1, run.stdout)
        listed = re.findall(r"(?m)^\s*\d+: (\w+) style plugin (\S+)$", run.stdout)
        self.assertIn(("pair", "vertex/voronoi"), listed)
        self.assertGreaterEqual(len(listed), 7, run.stdout)
        self.assertEqual(run.stdout.count("Tessera %s styles:" % self.version(run)), 1)

    def version(self, run):
        match = re.search(r"^Tessera (\S+) styles:", run.stdout, re.M)
        self.assertIsNotNone(match, run.stdout)
        return match.group(1)

    @nprocs(2)
    def test_two_ranks(self):
        run = self.run_lmp(SCRIPT, variables={"greeting": "mpi"}, nprocs=2)
        self.assertIn("on 2 procs", run.stdout)
        self.assertEqual(run.stdout.count("VALUE of greeting: mpi"), 1)
        self.assertAlmostEqual(self.position(run.stdout), 2.5, places=10)


if __name__ == "__main__":
    lmptest.main()
