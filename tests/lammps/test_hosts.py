#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Both host LAMMPS: Debian's 29 Sep 2021 through tessera-lmp, and a current
LAMMPS (4 Jul 2026 in CI) through tesseraplugin.so.

* The examples print the same thermo output on both hosts, on 1 and 2 ranks:
  every thermo value as the same printed number (the 2026 thermo pads its
  columns differently, so values are compared token by token).  The examples
  use `fix brownian`, where upstream BROWNIAN's fix brownian and Tessera's
  compute the same floating-point operations, with `rng none` or with noise
  (examples/3d, examples/spheroid_beads: the same generator and seed).  These run on the
  plugin host, which knows both executables (--tessera-lmp); with
  --intree-lmp also an lmp with the TESSERA package compiled in.
* The `plugin` command: `plugin load` registers every style of the table
  (fix brownian only where the host has none); Debian's LAMMPS has no such
  command, which is why tessera-lmp exists.
"""

import os
import re
import subprocess
import tempfile

import numpy as np
import unittest

import lmptest
from lmptest import Config, LammpsTestCase, nprocs

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")

# Every examples/<dir>/in.* as shipped (so new examples are compared too), and
# variants the example READMEs give: name -> (directory, input, variables)
CASES = {}
for _dir in sorted(os.listdir(EXAMPLES)):
    if os.path.isdir(os.path.join(EXAMPLES, _dir)):
        for _input in sorted(os.listdir(os.path.join(EXAMPLES, _dir))):
            # (an in.*.continue input continues from the restart file its
            # example's main input writes: not a run of its own)
            if _input.startswith("in.") and not _input.endswith(".continue"):
                _name = _dir if _input == "in." + _dir else _dir + "_" + _input[3:]
                CASES[re.sub(r"\W", "_", _name)] = (_dir, _input, {})
VARIANTS = {"shear_fluid": ("shear", "in.shear", {"p0": 4.0})}    # examples/shear/README.md
CASES.update({k: v for k, v in VARIANTS.items() if os.path.exists(os.path.join(EXAMPLES, v[0], v[1]))})
# Examples whose full run takes long are compared over a shorter run of the
# same input (the hosts must agree to every printed digit whatever the length).
SHORTER = {"erk_waves": {"tend": 20.0}, "fibre_network": {"tend": 2.0}}
for _case, _vars in SHORTER.items():
    if _case in CASES:
        CASES[_case] = (CASES[_case][0], CASES[_case][1], dict(CASES[_case][2], **_vars))


# Examples whose input reads a file that a script of theirs writes (not
# committed): directory -> (script, its output option, the file).
# (script, its arguments before the output option, the option, the file); the
# script runs in the example's directory.
GENERATED = {
    "fibre_network": ("make_network.py", [], "-o", "fibres.data"),
    "vertex_segmented": (os.path.join("..", "..", "tools", "tessera-tools"),
                         ["segmented", "labels.txt", "--boundary-label", "0", "--pixel",
                          "0.0645497"], "-o", "tissue.data"),
}


def example_files(directory):
    """The text files an example's input may read (data files, includes), not
    its reference logs or outputs; and the files its own scripts generate."""
    files = {}
    if directory in GENERATED:
        script, before, option, name = GENERATED[directory]
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run(["/usr/bin/python3", os.path.join(EXAMPLES, directory, script),
                            *before, option, os.path.join(tmp, name)], check=True,
                           stdout=subprocess.DEVNULL, cwd=os.path.join(EXAMPLES, directory))
            with open(os.path.join(tmp, name)) as f:
                files[name] = f.read()
    path = os.path.join(EXAMPLES, directory)
    for name in os.listdir(path):
        if name.startswith(("log.", "dump.")) or name.endswith((".md", ".png", ".gif")):
            continue
        full = os.path.join(path, name)
        if os.path.isfile(full) and os.path.getsize(full) < 10 ** 7:
            try:
                with open(full) as f:
                    files[name] = f.read()
            except UnicodeDecodeError:
                pass
    return files


def thermo_rows(text):
    """The thermo blocks of a LAMMPS screen output: for each run, its header
    words, its rows of printed values (as strings) and its number of steps
    (from the 'Loop time' line; None if there is none)."""
    blocks, rows, header = [], None, None
    for line in text.splitlines():
        words = line.split()
        if words and words[0] == "Step":
            header, rows = words, []
            blocks.append([header, rows, None])
        elif rows is not None:
            if line.startswith("Loop time"):
                m = re.search(r" for (\d+) steps", line)
                blocks[-1][2] = int(m.group(1)) if m else None
                rows = None
            elif len(words) == len(header) and re.match(r"^-?\d", words[0]):
                rows.append(words)
    return blocks


class ExamplesOnBothHosts(LammpsTestCase):

    def compare(self, case, nranks):
        if not self.plugin_host:
            raise unittest.SkipTest("compares the hosts: runs in the plugin build (--host plugin)")
        if not Config.tessera_lmp or not os.path.exists(Config.tessera_lmp):
            self.fail("--host plugin needs --tessera-lmp (Debian's tessera-lmp) to compare the "
                      "hosts; CMake's TESSERA_TEST_TESSERA_LMP is '%s'" % Config.tessera_lmp)
        directory, script, variables = CASES[case]
        with open(os.path.join(EXAMPLES, directory, script)) as f:
            text = f.read()
        outputs = {}
        hosts = [("plugin", Config.lmp), ("tessera-lmp", Config.tessera_lmp)]
        if Config.intree_lmp:    # the in-tree package (scripts/lammps-intree), if given
            hosts.append(("in-tree", Config.intree_lmp))
        for host, lmp in hosts:
            run = self.run_lmp(text, nprocs=nranks, variables=variables, lmp=lmp,
                               files=example_files(directory))
            self.assertIn("LAMMPS (", run.stdout)
            outputs[host] = (run.stdout, thermo_rows(run.stdout))
        # really two LAMMPS versions
        versions = {host: re.search(r"LAMMPS \(([^)]*)\)", out).group(1)
                    for host, (out, _) in outputs.items()}
        self.assertTrue(versions["tessera-lmp"].startswith("29 Sep 2021"), versions)
        self.assertNotEqual(versions["plugin"], versions["tessera-lmp"])
        theirs = outputs["tessera-lmp"][1]
        # LAMMPS's minimizers changed between the versions (same model, other
        # line searches), so after 'minimize' the values agree only to the
        # minimizer's tolerance; dynamics must agree to every printed digit.
        minimized = re.search(r"(?m)^\s*minimize\s", text) is not None
        for host in outputs:
            ours = outputs[host][1]
            self.assertTrue(ours, "no thermo output:\n" + outputs[host][0][-2000:])
            self.assertEqual(len(ours), len(theirs))
            for (h1, r1, n1), (h2, r2, n2) in zip(ours, theirs):
                self.assertEqual(h1, h2)
                self.assertEqual(n1, n2)
                # a run prints its first and last step; 'run 0' (e.g. the
                # state at the end time of a run fix halt stopped) its one
                self.assertGreater(len(r1), 1 if n1 != 0 else 0)
                message = "%s on %d rank(s): thermo differs between %s and tessera-lmp" % (
                    case, nranks, host)
                if minimized:
                    np.testing.assert_allclose(np.array(r1, dtype=float), np.array(r2, dtype=float),
                                               rtol=1e-3, atol=1e-6, err_msg=message)
                else:
                    self.assertEqual(r1, r2, message)



def _add_example_tests():
    """test_<case> on 1 rank and test_<case>_two_ranks on 2, for every case."""
    for case in CASES:
        def serial(self, case=case):
            self.compare(case, 1)

        @nprocs(2)
        def two_ranks(self, case=case):
            self.compare(case, 2)
        setattr(ExamplesOnBothHosts, "test_" + case, serial)
        setattr(ExamplesOnBothHosts, "test_%s_two_ranks" % case, two_ranks)


_add_example_tests()


class PluginCommand(LammpsTestCase):
    """`plugin load` by hand (LAMMPS_PLUGIN_PATH unset for these runs)."""

    SCRIPT = lmptest.tissue(4, 2) + """
plugin load {plugin}
plugin list
pair_style vertex/voronoi 4.0
pair_coeff * * 1.0 1.0 0.1 -0.5
fix move all brownian 1.0 5 gamma_t 1.0 rng none
fix act all polarity 0.5 1.0
compute cell all vertex/atom
compute tissue all vertex/tissue
thermo_style custom step pe c_tissue[1]
run 0
print "Q $(c_tissue[1]:%.10f)"
run 2
"""

    def run_without_path(self, script, **kw):
        saved = os.environ.pop("LAMMPS_PLUGIN_PATH", None)
        try:
            return self.run_lmp(script, **kw)
        finally:
            if saved is not None:
                os.environ["LAMMPS_PLUGIN_PATH"] = saved

    def test_plugin_load(self):
        if not self.plugin_host:
            # Debian's LAMMPS has no PLUGIN package: tessera-lmp has the styles built in
            run = self.run_without_path("plugin load tesseraplugin.so\n", ok=False)
            self.assertLammpsError(run, "Unknown command", "plugin")
            return
        run = self.run_without_path(self.SCRIPT.format(plugin=Config.plugin))
        out = run.stdout
        line = re.search(r"(?m)^Tessera \S+ styles: (.*)$", out).group(1).split(", ")
        self.assertEqual(line[:2], ["pair_style vertex/voronoi", "fix polarity"])
        self.assertIn("compute vertex/atom", line)
        self.assertNotIn("fix brownian", line)    # the host's BROWNIAN serves it
        self.assertRegex(out, r"(?m)^  kept the host LAMMPS's own: fix brownian$")
        for style in ("pair style plugin vertex/voronoi", "fix style plugin polarity",
                      "compute style plugin vertex/atom"):
            self.assertIn(style, out)
        self.assertNotRegex(out, r"(?m)fix style plugin brownian$")
        # a hexagonal lattice of area-1 cells: shape index sqrt(8 sqrt 3)
        q = float(re.search(r"(?m)^Q (\S+)$", out).group(1))
        self.assertAlmostEqual(q, (8 * 3 ** 0.5) ** 0.5, places=8)

    def test_plugin_load_twice(self):
        if not self.plugin_host:
            raise unittest.SkipTest("no plugin command in Debian's LAMMPS (see test_plugin_load)")
        script = "plugin load {plugin}\n".format(plugin=Config.plugin) + \
            self.SCRIPT.format(plugin=Config.plugin)
        run = self.run_without_path(script)
        self.assertEqual(len(re.findall(r"(?m)^Tessera \S+ styles:", run.stdout)), 1,
                         run.stdout[-2000:])
        self.assertEqual(run.stdout.count("pair style plugin vertex/voronoi"), 1)


if __name__ == "__main__":
    lmptest.main()
