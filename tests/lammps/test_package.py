#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The in-tree package (scripts/install-lammps-package) sees the same styles as
tessera-lmp and the plugin: LAMMPS's CMake registers a style by the
PairStyle/FixStyle/ComputeStyle line of its header, while tessera-lmp and the
plugin use the table in lammps/tessera_styles.cpp.  Every table entry that
Tessera always serves must have that header line, naming the same class; and
the script must produce a tree in which CMake finds them (checked on a copy of
a LAMMPS tree's cmake/ and src/ skeleton, without building LAMMPS), and a real
current LAMMPS tree with the package must configure and Tessera's files in it
compile (the full in-tree build is scripts/lammps-intree's, in scripts/test's
stage 2)."""

import glob
import json
import os
import re
import shlex
import shutil
import subprocess
import unittest

import lmptest
from lmptest import LammpsTestCase

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
LAMMPS_DIR = os.path.join(REPO, "lammps")
MACRO = {"pair_style": "PairStyle", "fix": "FixStyle", "compute": "ComputeStyle",
         "command": "CommandStyle"}


def lammps_source():
    """A current LAMMPS source (a tarball or a tree) to install the package into:
    $TESSERA_LAMMPS_TARBALL, else what build-cache/ holds (a lammps-*.tar.xz, the
    tree of scripts/setup --lammps-src, or the src-tree/ that scripts/lammps-current
    unpacked there); None if there is none."""
    tarball = os.environ.get("TESSERA_LAMMPS_TARBALL")
    if tarball and os.path.isfile(tarball):
        return tarball
    cache = os.environ.get("TESSERA_CACHE", os.path.join(REPO, "build-cache"))
    found = sorted(glob.glob(os.path.join(cache, "lammps-*.tar.xz")))
    if found:
        return found[0]
    recorded = os.path.join(cache, "lammps-src-dir")
    trees = []
    if os.path.isfile(recorded):
        with open(recorded) as f:
            trees.append(f.read().strip())
    trees += sorted(glob.glob(os.path.join(cache, "lammps-*", "src-tree")))
    for tree in trees:
        if os.path.isfile(os.path.join(tree, "cmake", "CMakeLists.txt")) and \
                not os.path.isdir(os.path.join(tree, "src", "TESSERA")):
            return tree
    return None


def table_entries():
    """(command, name, class, policy) of every entry in the style table."""
    with open(os.path.join(LAMMPS_DIR, "tessera_styles.cpp")) as f:
        text = f.read()
    body = text[text.index("static const std::vector<Entry> table"):]
    body = body[:body.index("};")]
    return [(m.group(1), m.group(3), m.group(2), m.group(4) or "REPLACE") for m in re.finditer(
        r'(pair_style|fix_style|compute_style|command_style)<(\w+)>\("([^"]+)"(?:,\s*Policy::(\w+))?\)',
        body)]


def header_styles():
    """{(macro, name): class} from every lammps/*.h."""
    found = {}
    for name in os.listdir(LAMMPS_DIR):
        if name.endswith(".h"):
            with open(os.path.join(LAMMPS_DIR, name)) as f:
                for m in re.finditer(r"^(PairStyle|FixStyle|ComputeStyle|CommandStyle)\(([^,]+),(\w+)\);",
                                     f.read(), re.M):
                    found[(m.group(1), m.group(2).strip())] = m.group(3)
    return found


class InTreePackage(LammpsTestCase):

    def test_every_table_style_has_its_header_line(self):
        entries = table_entries()
        self.assertGreaterEqual(len(entries), 4)
        headers = header_styles()
        for command, name, cls, policy in entries:
            command = command.replace("_style", "") if command != "pair_style" else command
            macro = MACRO[command]
            if policy == "IF_MISSING":
                # stand-ins for upstream styles: in-tree the upstream package serves them
                self.assertNotIn((macro, name), headers)
                continue
            self.assertEqual(headers.get((macro, name)), cls,
                             "lammps/*.h: no '%s(%s,%s);' line, so an in-tree build would lack "
                             "%s %s" % (macro, name, cls, command, name))

    def test_install_script(self):
        # a skeleton with the two lines of LAMMPS's cmake/CMakeLists.txt the script edits
        root = self.new_dir()
        for d in ("src", "cmake/Modules/Packages"):
            os.makedirs(os.path.join(root, d))
        with open(os.path.join(root, "src", "version.h"), "w") as f:
            f.write('#define LAMMPS_VERSION "4 Jul 2026"\n')
        os.makedirs(os.path.join(root, "src", "BROWNIAN"))
        with open(os.path.join(root, "src", "BROWNIAN", "fix_brownian.h"), "w") as f:
            f.write("// upstream's\n")
        with open(os.path.join(root, "cmake", "CMakeLists.txt"), "w") as f:
            f.write("set(STANDARD_PACKAGES\n  ADIOS\n  YAFF)\n"
                    "foreach(PKG_WITH_INCL GRAPHICS KSPACE)\nendforeach()\n"
                    "foreach(PKG_WITH_INCL CORESHELL OPT)\nendforeach()\n")
        script = os.path.join(REPO, "scripts", "install-lammps-package")
        for _ in range(2):    # a second run changes nothing
            proc = subprocess.run([script, root], capture_output=True, text=True)
            self.assertEqual(proc.returncode, 0, proc.stderr)
        with open(os.path.join(root, "cmake", "CMakeLists.txt")) as f:
            cml = f.read()
        self.assertEqual(cml.count("  TESSERA\n"), 1)
        self.assertIn("foreach(PKG_WITH_INCL TESSERA GRAPHICS KSPACE)", cml)
        self.assertIn("foreach(PKG_WITH_INCL CORESHELL OPT)", cml)    # only the first list
        copied = set(os.listdir(os.path.join(root, "src", "TESSERA")))
        self.assertIn("pair_vertex_voronoi.h", copied)
        self.assertIn("tessera_compat.h", copied)
        self.assertNotIn("main.cpp", copied)
        self.assertNotIn("tessera_plugin.cpp", copied)
        self.assertNotIn("tessera_styles.cpp", copied)
        # fix brownian/heun builds on Tessera's fix brownian, whose file name is
        # BROWNIAN's (in the skeleton too): it comes under another name
        self.assertNotIn("fix_brownian.h", copied)
        self.assertIn("fix_brownian_tessera.h", copied)
        self.assertIn("fix_brownian_tessera.cpp", copied)
        with open(os.path.join(root, "src", "TESSERA", "fix_brownian_heun.h")) as f:
            self.assertIn('#include "fix_brownian_tessera.h"', f.read())
        # every source file that the plugin is built from (less its registration)
        for name in os.listdir(LAMMPS_DIR):
            if name.endswith((".h", ".cpp")) and name not in (
                    "main.cpp", "tessera_plugin.cpp", "tessera_styles.cpp", "tessera_styles.h"):
                self.assertTrue(name in copied or name.replace(".", "_tessera.") in copied, name)
        # all of the core, whatever its CMakeLists.txt builds (core/tools/ too)
        core = os.path.join(REPO, "core")
        for top, _, files in os.walk(core):
            for name in files:
                rel = os.path.relpath(os.path.join(top, name), core)
                self.assertTrue(os.path.exists(os.path.join(root, "lib", "tessera", rel)), rel)
        self.assertTrue(os.path.exists(os.path.join(root, "lib", "tessera", "CMakeLists.txt")))
        self.assertTrue(os.path.exists(os.path.join(root, "cmake", "Modules", "Packages",
                                                    "TESSERA.cmake")))
        bad = subprocess.run([script, self.new_dir()], capture_output=True, text=True)
        self.assertNotEqual(bad.returncode, 0)
        self.assertIn("is not a LAMMPS source tree", bad.stderr)

    def test_configure_current_lammps_with_package(self):
        source = lammps_source()
        if source is None:
            raise unittest.SkipTest("no current LAMMPS source ($TESSERA_LAMMPS_TARBALL, or "
                                    "build-cache/ after scripts/lammps-current)")
        work = self.new_dir()
        tree = os.path.join(work, "lammps")
        if os.path.isdir(source):
            shutil.copytree(source, tree, symlinks=True,
                            ignore=shutil.ignore_patterns("build", "doc", "examples", "potentials"))
        else:
            os.makedirs(tree)
            subprocess.run(["tar", "-xf", source, "-C", tree, "--strip-components=1"], check=True)
        script = os.path.join(REPO, "scripts", "install-lammps-package")
        proc = subprocess.run([script, tree], capture_output=True, text=True)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        build = os.path.join(work, "build")
        proc = subprocess.run(
            ["cmake", "-S", os.path.join(tree, "cmake"), "-B", build, "-D", "CMAKE_BUILD_TYPE=Release",
             "-D", "BUILD_MPI=on", "-D", "PKG_TESSERA=on", "-D", "PKG_BROWNIAN=on", "-D", "PKG_DIPOLE=on",
             "-D", "DOWNLOAD_POTENTIALS=off", "-D", "CMAKE_EXPORT_COMPILE_COMMANDS=on"],
            capture_output=True, text=True, timeout=240)
        self.assertEqual(proc.returncode, 0, "cmake -D PKG_TESSERA=on failed:\n"
                         + (proc.stdout + proc.stderr)[-3000:])
        self.assertRegex(proc.stdout, r"Enabled packages: .*\bTESSERA\b")
        # no file of the package shadows, or is shadowed by, one of LAMMPS's
        package = os.path.join(tree, "src", "TESSERA")
        ours = set(n for n in os.listdir(package) if n.endswith((".h", ".cpp")))
        for top, dirs, files in os.walk(os.path.join(tree, "src")):
            if os.path.abspath(top) != os.path.abspath(package):
                self.assertFalse(ours & set(files), "%s: same names as in %s" % (ours & set(files), top))
        # each style is in LAMMPS's generated style headers
        styles = ""
        for name in ("style_pair.h", "style_fix.h", "style_compute.h"):
            with open(os.path.join(build, "styles", name)) as f:
                styles += f.read()
        declaring = []
        for header in sorted(n for n in ours if n.endswith(".h")):
            with open(os.path.join(package, header)) as f:
                if re.search(r"^(Pair|Fix|Compute)Style\(", f.read(), re.M):
                    declaring.append(header)
        self.assertGreaterEqual(len(declaring), len([e for e in table_entries() if e[3] != "IF_MISSING"]))
        for header in declaring:
            self.assertIn('"%s"' % header, styles)
        # Tessera's sources compile with the tree's flags and include paths (a
        # header of LAMMPS's found instead of Tessera's fails here)
        with open(os.path.join(build, "compile_commands.json")) as f:
            commands = json.load(f)
        chosen = [c for c in commands
                  if os.path.dirname(os.path.abspath(c["file"])) == os.path.abspath(package)]
        self.assertEqual(len(chosen), len([n for n in ours if n.endswith(".cpp")]))
        # (through ccache where there is one, with paths relative to this test's
        # directory: a later run recompiles only what changed)
        ccache = shutil.which("ccache")
        env = dict(os.environ, CCACHE_BASEDIR=work)
        for n, c in enumerate(chosen):
            args = shlex.split(c["command"])
            out = args.index("-o")
            args[out + 1] = os.path.join(work, "check-%d.o" % n)
            args = ["-O0" if re.fullmatch(r"-O[1-3s]|-Ofast", a) else a for a in args]    # quicker
            if ccache and os.path.basename(args[0]) != "ccache":
                args = [ccache] + args
            proc = subprocess.run(args, cwd=c["directory"], capture_output=True, text=True,
                                  timeout=240, env=env)
            self.assertEqual(proc.returncode, 0, "%s does not compile in-tree:\n%s"
                             % (c["file"], proc.stderr[-3000:]))


if __name__ == "__main__":
    lmptest.main()
