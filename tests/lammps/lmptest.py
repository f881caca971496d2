# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Harness for tests that run real LAMMPS input scripts through tessera-lmp.

A test module is a unittest module that ends with ``lmptest.main()``.  CTest
runs each test method as its own test (tests/lammps/CMakeLists.txt asks each
module for ``--list``).  Paths come from command-line options, which CMake
passes, or from the environment for running a module by hand:

    /usr/bin/python3 tests/lammps/test_fix_brownian.py --build build-lmp [Class.test]

Decorate a test that starts more than one MPI rank with ``@nprocs(n)`` so
CTest reserves that many cores and can skip it without mpiexec.
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


class Config:
    lmp = None          # tessera-lmp
    lib = None          # libtessera_lammps.so
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
    ``mpiexec --allow-run-as-root --oversubscribe -n 2``."""
    if n == 1:
        return []
    if not Config.mpiexec:
        raise unittest.SkipTest("no mpiexec (CMake's MPIEXEC_EXECUTABLE) to start %d ranks" % n)
    cmd = [Config.mpiexec]
    version = subprocess.run([Config.mpiexec, "--version"], capture_output=True, text=True)
    if re.search(r"Open ?MPI|OpenRTE|open-mpi", version.stdout + version.stderr):
        if os.geteuid() == 0:
            cmd.append("--allow-run-as-root")
        cmd.append("--oversubscribe")    # CI machines may have fewer cores than ranks
    return cmd + ["-n", str(n)]


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


class LammpsTestCase(unittest.TestCase):
    """Base class: self.run_lmp() runs an input script in a fresh directory."""

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
                ok=True, timeout=240):
        """Runs tessera-lmp on `script` (written to in.test and passed with
        -in; None: no -in) on nprocs ranks, in a fresh directory that also
        holds `files` (name: text).  With ok=True a failing run fails the test
        and shows LAMMPS's output."""
        d = self.new_dir()
        for name, text in (files or {}).items():
            with open(os.path.join(d, name), "w") as f:
                f.write(text)
        cmd = mpiexec_command(nprocs) + [Config.lmp]
        if script is not None:
            with open(os.path.join(d, "in.test"), "w") as f:
                f.write(script)
            cmd += ["-in", "in.test"]
        for name, value in (variables or {}).items():
            cmd += ["-var", name, str(value)]
        cmd += list(args or [])
        proc = subprocess.run(cmd, cwd=d, input=stdin, capture_output=True, text=True,
                              timeout=timeout)
        return self._checked(Run(d, proc), cmd, "tessera-lmp", ok)

    def run_python(self, code=None, nprocs=1, script=None, args=(), timeout=240, ok=True):
        """Runs Python `code` (or the file `script` with `args`) under the
        interpreter running these tests (Debian's /usr/bin/python3) in a fresh
        directory, on nprocs ranks.  libtessera_lammps.so is in the
        environment as TESSERA_LAMMPS_LIB."""
        d = self.new_dir()
        if script is None:
            script = os.path.join(d, "script.py")
            with open(script, "w") as f:
                f.write(code)
        env = dict(os.environ, TESSERA_LAMMPS_LIB=Config.lib, PYTHONDONTWRITEBYTECODE="1")
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
