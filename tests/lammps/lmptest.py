# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Harness for tests that run real LAMMPS input scripts through tessera-lmp.

A test module is a unittest module that ends with ``lmptest.main()``.  CTest
runs each test method as its own test (tests/lammps/CMakeLists.txt asks each
module for ``--list``).  Paths come from command-line options, which CMake
passes, or from the environment for running a module by hand:

    /usr/bin/python3 tests/lammps/test_fix_brownian.py --build build-lmp [Class.test]

Decorate a test that starts more than one MPI rank with ``@nprocs(n)`` so
CTest reserves that many cores and can skip it without mpiexec.

Every test runs on either host LAMMPS (``--host``, which CMake passes):
``tessera-lmp`` (Debian's LAMMPS with our styles built in; the default) or
``plugin`` (a current LAMMPS's ``lmp`` given by ``--lmp``, with
tesseraplugin.so loaded through LAMMPS_PLUGIN_PATH, and that LAMMPS's Python
module for run_python).  A test whose expectation differs by host asks
``Config.host`` (or ``self.plugin_host``) and checks each host's value.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

SKIP_RETURN_CODE = 77
TOOLS = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "tools")


class Config:
    host = "tessera-lmp"    # or "plugin"
    lmp = None          # tessera-lmp, or the plugin host's lmp
    lib = None          # libtessera_lammps.so (tessera-lmp host)
    plugin = None       # tesseraplugin.so (plugin host)
    build = None        # Tessera's build directory (tests/core_forces, ...)
    python_paths = {}   # plugin host: PYTHONPATH, LD_LIBRARY_PATH entries for run_python
    tessera_lmp = None  # plugin host: Debian's tessera-lmp, to compare the hosts
    intree_lmp = None   # plugin host: an lmp with the TESSERA package compiled in, or None
    mpiexec = None      # mpiexec, or None
    workdir = None      # where each test gets a fresh directory
    keep = False        # keep the directories of passing tests


def nprocs(n):
    """Marks a test that needs n MPI ranks."""
    def mark(func):
        func.nprocs = n
        return func
    return mark


def mpiexec_command(n):
    """The command prefix that starts n ranks, e.g. for OpenMPI as root
    ``env OMPI_MCA_orte_tmpdir_base=DIR mpiexec --allow-run-as-root --oversubscribe -n 2``.

    OpenMPI keeps a session directory per job under one machine-wide
    /tmp/ompi.<host>.<uid>, which the last job to finish removes: a job starting
    at that moment fails to create its own directory in it (a singleton's orted
    then dies, "Unable to start a daemon on the local node"; a daemonless one
    reports "orte_session_dir failed").  So every run of this test process keeps
    its session directories in a private DIR (orte_tmpdir_base), and one rank
    starts as a singleton without forking an orted (ess_singleton_isolated).
    Both settings are ignored by other MPI implementations."""
    if getattr(mpiexec_command, "private", None) is None:
        import atexit
        # in $TMPDIR, whose path is short: PMIx may put sockets there
        mpiexec_command.private = tempfile.mkdtemp(prefix="tessera-ompi-")
        atexit.register(shutil.rmtree, mpiexec_command.private, True)
    prefix = ["env", "OMPI_MCA_orte_tmpdir_base=" + mpiexec_command.private]
    if n == 1:
        return prefix + ["OMPI_MCA_ess_singleton_isolated=1"]
    if not Config.mpiexec:
        raise unittest.SkipTest("no mpiexec (CMake's MPIEXEC_EXECUTABLE) to start %d ranks" % n)
    cmd = [Config.mpiexec]
    version = subprocess.run([Config.mpiexec, "--version"], capture_output=True, text=True)
    if re.search(r"Open ?MPI|OpenRTE|open-mpi", version.stdout + version.stderr):
        if os.geteuid() == 0:
            cmd.append("--allow-run-as-root")
        cmd.append("--oversubscribe")    # CI machines may have fewer cores than ranks
    return prefix + cmd + ["-n", str(n)]


class Run:
    """The outcome of one tessera-lmp run in its own directory."""

    def __init__(self, workdir, proc):
        self.dir = workdir
        self.returncode = proc.returncode
        self.stdout = proc.stdout
        self.stderr = proc.stderr

    @property
    def output(self):
        return self.stdout + self.stderr

    def path(self, name):
        return os.path.join(self.dir, name)

    def text(self, name):
        with open(self.path(name)) as f:
            return f.read()

    def dump(self, name):
        """Frames of a text dump (dump custom / write_dump custom), in file
        order, as a list of dicts: 'step', 'box' (3x2 array) and one numpy
        array per column, rows sorted by atom id."""
        frames = []
        with open(self.path(name)) as f:
            lines = f.read().split("\n")
        i = 0
        while i < len(lines):
            if not lines[i].startswith("ITEM: TIMESTEP"):
                i += 1
                continue
            step = int(lines[i + 1])
            natoms = int(lines[i + 3])
            box = np.array([[float(w) for w in lines[i + 5 + k].split()[:2]] for k in range(3)])
            columns = lines[i + 8].split()[2:]
            rows = np.array([[float(w) for w in lines[i + 9 + k].split()] for k in range(natoms)])
            rows = rows.reshape(natoms, len(columns))
            frame = {"step": step, "box": box}
            for c, col in enumerate(columns):
                frame[col] = rows[:, c]
            if "id" in frame:
                order = np.argsort(frame["id"])
                for col in columns:
                    frame[col] = frame[col][order]
                frame["id"] = frame["id"].astype(int)
            frames.append(frame)
            i += 9 + natoms
        return frames


def tissue(nx, ny, lattice="hex", ntypes=1, tilt=None):
    """The start of an input script: a lattice ('hex' or 'sq') of cells of
    area 1 filling a periodic 2d box of nx x ny lattice cells, triclinic with
    a tilt (in lattice units) if given, atom style dipole."""
    region = ("region box block 0 %d 0 %d -0.5 0.5" % (nx, ny) if tilt is None else
              "region box prism 0 %d 0 %d -0.5 0.5 %g 0 0" % (nx, ny, tilt))
    return f"""
dimension 2
units lj
atom_style dipole
boundary p p p
lattice {lattice} 1.0
{region}
create_box {ntypes} box
create_atoms 1 box
mass * 1.0
"""


def use_plugin_host(plugin, lammps_python=None, lammps_libdir=None):
    """Every LAMMPS this process starts (lmp, or Python's lammps module)
    loads tesseraplugin.so: LAMMPS_PLUGIN_PATH names its directory.  For
    run_python, the host's Python module and liblammps.so come first on the
    search paths (only there: tessera-lmp must keep Debian's liblammps.so.0)."""
    os.environ["LAMMPS_PLUGIN_PATH"] = os.path.dirname(plugin)
    os.environ["TESSERA_PLUGIN"] = plugin
    Config.python_paths = {"PYTHONPATH": lammps_python, "LD_LIBRARY_PATH": lammps_libdir}


def _prepended(env, var, path):
    if path:
        env[var] = os.pathsep.join([path] + [p for p in env.get(var, "").split(os.pathsep) if p])


class LammpsTestCase(unittest.TestCase):
    """Base class: self.run_lmp() runs an input script in a fresh directory."""

    @property
    def plugin_host(self):
        """True when the tests run on a current LAMMPS through the plugin."""
        return Config.host == "plugin"

    def setUp(self):
        os.makedirs(Config.workdir, exist_ok=True)
        self._dirs = []

    def tearDown(self):
        outcome = getattr(self, "_outcome", None)
        failed = outcome is not None and not getattr(outcome, "success", True)
        for d in self._dirs:
            if failed or Config.keep:
                print("kept run directory", d, file=sys.stderr)
            else:
                shutil.rmtree(d, ignore_errors=True)

    def new_dir(self):
        d = tempfile.mkdtemp(prefix=self.id().split(".")[-1] + "-", dir=Config.workdir)
        self._dirs.append(d)
        return d

    def run_lmp(self, script, nprocs=1, variables=None, args=None, stdin=None, files=None,
                ok=True, timeout=240, lmp=None):
        """Runs the host's lmp (tessera-lmp) on `script` (written to in.test and passed with
        -in; None: no -in) on nprocs ranks, in a fresh directory that also
        holds `files` (name: text).  With ok=True a failing run fails the test
        and shows LAMMPS's output.  `lmp`: another executable than the host's
        (e.g. Config.tessera_lmp, to compare hosts)."""
        d = self.new_dir()
        for name, text in (files or {}).items():
            with open(os.path.join(d, name), "w") as f:
                f.write(text)
        cmd = mpiexec_command(nprocs) + [lmp or Config.lmp]
        if script is not None:
            with open(os.path.join(d, "in.test"), "w") as f:
                f.write(script)
            cmd += ["-in", "in.test"]
        for name, value in (variables or {}).items():
            cmd += ["-var", name, str(value)]
        cmd += list(args or [])
        proc = subprocess.run(cmd, cwd=d, input=stdin, capture_output=True, text=True,
                              timeout=timeout)
        return self._checked(Run(d, proc), cmd, os.path.basename(lmp or Config.lmp), ok)

    def run_python(self, code=None, nprocs=1, script=None, args=(), timeout=240, ok=True):
        """Runs Python `code` (or the file `script` with `args`) under the
        interpreter running these tests (Debian's /usr/bin/python3) in a fresh
        directory, on nprocs ranks.  libtessera_lammps.so is in the
        environment as TESSERA_LAMMPS_LIB (and, on the plugin host,
        tesseraplugin.so as TESSERA_PLUGIN, with that LAMMPS's Python module
        first on PYTHONPATH); tessera_tools.host.register(lmp) uses either."""
        d = self.new_dir()
        if script is None:
            script = os.path.join(d, "script.py")
            with open(script, "w") as f:
                f.write(code)
        env = dict(os.environ, TESSERA_LAMMPS_LIB=Config.lib, PYTHONDONTWRITEBYTECODE="1")
        for var, path in Config.python_paths.items():
            _prepended(env, var, path)
        # tessera_tools (tools/), for tessera_tools.host.register(lmp)
        env["PYTHONPATH"] = os.pathsep.join(p for p in (env.get("PYTHONPATH"), TOOLS) if p)
        cmd = mpiexec_command(nprocs) + [sys.executable, script] + list(args)
        proc = subprocess.run(cmd, cwd=d, capture_output=True, text=True, env=env,
                              timeout=timeout)
        return self._checked(Run(d, proc), cmd, "python", ok)

    def _checked(self, run, cmd, what, ok):
        """With ok=True a failing run fails the test and shows its output."""
        if ok and run.returncode != 0:
            self.fail("%s failed (exit %d): %s\n--- output ---\n%s"
                      % (what, run.returncode, " ".join(cmd), run.output[-4000:]))
        return run

    def assertLammpsError(self, run, *fragments):
        """The run failed with a LAMMPS ERROR line containing every fragment."""
        self.assertNotEqual(run.returncode, 0, "expected the run to fail:\n" + run.output[-3000:])
        errors = [line for line in run.output.splitlines() if "ERROR" in line]
        self.assertTrue(errors, "no ERROR line in output:\n" + run.output[-3000:])
        for fragment in fragments:
            self.assertTrue(any(fragment in line for line in errors),
                            "no ERROR line contains %r; ERROR lines:\n%s"
                            % (fragment, "\n".join(errors)))


def _iter_tests(suite):
    for test in suite:
        if isinstance(test, unittest.TestSuite):
            yield from _iter_tests(test)
        else:
            yield test


def main():
    """Entry point of a test module: ``--list`` prints 'Class.method nprocs'
    lines for CMake; otherwise runs the named tests (all by default) and exits
    with 0 (passed), 1 (failed) or 77 (everything skipped)."""
    parser = argparse.ArgumentParser()
    build = os.environ.get("TESSERA_BUILD", "build")
    parser.add_argument("--build", default=build, help="build directory (default $TESSERA_BUILD or build)")
    parser.add_argument("--lmp", default=os.environ.get("TESSERA_LMP"))
    parser.add_argument("--lib", default=os.environ.get("TESSERA_LAMMPS_LIB"))
    parser.add_argument("--host", choices=("tessera-lmp", "plugin"),
                        default=os.environ.get("TESSERA_TEST_HOST", "tessera-lmp"),
                        help="host LAMMPS: tessera-lmp (default) or plugin (--lmp is a current "
                        "LAMMPS's lmp, --plugin its tesseraplugin.so)")
    parser.add_argument("--plugin", default=os.environ.get("TESSERA_PLUGIN"))
    parser.add_argument("--lammps-python", default=os.environ.get("TESSERA_LAMMPS_PYTHON"),
                        help="plugin host: directory of that LAMMPS's Python module (default: "
                        "src-tree/python beside the install prefix of --lmp, if there)")
    parser.add_argument("--lammps-libdir", default=None,
                        help="plugin host: directory of its liblammps.so (default: ../lib of --lmp)")
    parser.add_argument("--tessera-lmp", default=os.environ.get("TESSERA_TEST_TESSERA_LMP"),
                        help="plugin host: Debian's tessera-lmp, for tests comparing the hosts")
    parser.add_argument("--intree-lmp", default=os.environ.get("TESSERA_TEST_INTREE_LMP"),
                        help="plugin host: also compare an lmp built with -D PKG_TESSERA=on")
    parser.add_argument("--mpiexec", default=os.environ.get("TESSERA_MPIEXEC", shutil.which("mpiexec")))
    parser.add_argument("--workdir", default=os.environ.get("TESSERA_TEST_WORKDIR"))
    parser.add_argument("--keep", action="store_true", help="keep run directories")
    parser.add_argument("--list", action="store_true")
    parser.add_argument("tests", nargs="*")
    opts = parser.parse_args()

    module = sys.modules["__main__"]
    suite = unittest.defaultTestLoader.loadTestsFromModule(module)
    if opts.list:
        for test in _iter_tests(suite):
            method = getattr(test, test._testMethodName)
            name = "%s.%s" % (type(test).__name__, test._testMethodName)
            print(name, getattr(method, "nprocs", 1))
        return

    Config.host = opts.host
    Config.build = os.path.abspath(opts.build)
    if opts.host == "plugin":
        if not opts.lmp:
            parser.error("--host plugin needs --lmp (the lmp of the LAMMPS the plugin is for)")
        Config.plugin = os.path.abspath(opts.plugin or os.path.join(opts.build, "lammps", "tesseraplugin.so"))
        libdir = opts.lammps_libdir or os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(opts.lmp))), "lib")
        python = opts.lammps_python    # default: scripts/lammps-current's layout
        guess = os.path.join(os.path.dirname(os.path.dirname(libdir)), "src-tree", "python")
        if not python and os.path.isdir(guess):
            python = guess
        use_plugin_host(Config.plugin, python, libdir)
        Config.tessera_lmp = opts.tessera_lmp and os.path.abspath(opts.tessera_lmp)
        Config.intree_lmp = opts.intree_lmp and os.path.abspath(opts.intree_lmp)
    Config.lmp = os.path.abspath(opts.lmp or os.path.join(opts.build, "lammps", "tessera-lmp"))
    Config.lib = os.path.abspath(opts.lib or os.path.join(opts.build, "lammps", "libtessera_lammps.so"))
    Config.mpiexec = opts.mpiexec
    Config.workdir = os.path.abspath(opts.workdir or os.path.join(opts.build, "tests", "lammps", "work"))
    Config.keep = opts.keep
    if opts.tests:
        suite = unittest.defaultTestLoader.loadTestsFromNames(opts.tests, module)
    result = unittest.TextTestRunner(verbosity=2).run(suite)
    if not result.wasSuccessful():
        sys.exit(1)
    if result.testsRun > 0 and len(result.skipped) == result.testsRun:
        sys.exit(SKIP_RETURN_CODE)
