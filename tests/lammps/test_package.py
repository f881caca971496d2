#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The package TESSERA in the form LAMMPS asks of a package (scripts/lammps-package
writes its layout: src/TESSERA, lib/tessera, the CMake module, doc pages, examples,
and the edits of LAMMPS's own files), complete; and the in-tree package
(scripts/install-lammps-package) sees the same styles as tessera-lmp and the
plugin: LAMMPS's CMake registers a style by the PairStyle/FixStyle/ComputeStyle
line of its header, while tessera-lmp and the plugin use the table in
lammps/tessera_styles.cpp.  Every table entry that
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
from lmptest import Config, LammpsTestCase, nprocs

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
LAMMPS_DIR = os.path.join(REPO, "lammps")
SCRIPT = os.path.join(REPO, "scripts", "lammps-package")
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


def user_styles_of_headers():
    """{(kind, name)} of the styles users type, from the headers' macros."""
    kinds = {"PairStyle": "pair_style", "FixStyle": "fix", "ComputeStyle": "compute",
             "CommandStyle": "command"}
    found = set()
    for name in os.listdir(LAMMPS_DIR):
        if name.endswith(".h"):
            with open(os.path.join(LAMMPS_DIR, name)) as f:
                for m in re.finditer(r"^(\w+Style)\(([^,]+),\w+\);", f.read(), re.M):
                    if m.group(1) in kinds and m.group(2) == m.group(2).lower():
                        found.add((kinds[m.group(1)], m.group(2).strip()))
    return found


def read_text(path):
    with open(path) as f:
        return f.read()


class Layout(LammpsTestCase):
    """scripts/lammps-package's layout is complete and in LAMMPS's form."""

    def layout(self, *args, env=None):
        out = os.path.join(self.new_dir(), "layout")
        proc = subprocess.run([SCRIPT, out] + list(args), capture_output=True, text=True,
                              env=env, timeout=900)
        self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
        return out

    def test_layout_complete(self):
        out = self.layout()
        files = set()
        for top, _, names in os.walk(out):
            files |= {os.path.relpath(os.path.join(top, n), out) for n in names}
        # MANIFEST lists exactly what is there
        self.assertEqual(set(read_text(os.path.join(out, "MANIFEST")).split()), files)
        # the styles: every source of the plugin less its registration; a stand-in
        # for an upstream style (fix brownian) under another name, and the includes
        # of the copies name it so
        package = os.path.join(out, "src", "TESSERA")
        for name in os.listdir(LAMMPS_DIR):
            if not name.endswith((".h", ".cpp")):
                continue
            registration = name in ("main.cpp", "tessera_plugin.cpp", "tessera_styles.cpp",
                                    "tessera_styles.h")
            present = (os.path.exists(os.path.join(package, name)) or
                       os.path.exists(os.path.join(package, name.replace(".", "_tessera."))))
            self.assertEqual(present, not registration, name)
        self.assertFalse(os.path.exists(os.path.join(package, "fix_brownian.h")))
        self.assertIn('#include "fix_brownian_tessera.h"',
                      read_text(os.path.join(package, "fix_brownian_heun.h")))
        # README in LAMMPS's form, naming every style; Install.sh refuses the make build
        readme = read_text(os.path.join(package, "README"))
        styles = user_styles_of_headers()
        self.assertGreaterEqual(len(styles), 10)
        for kind, name in styles:
            self.assertIn("%s %s\n" % (kind, name), readme)
        self.assertIn("License: GPL-2.0-or-later", readme)
        install_sh = os.path.join(package, "Install.sh")
        self.assertEqual(os.stat(install_sh).st_mode & 0o777, 0o644)
        work = os.path.join(self.new_dir(), "src")
        shutil.copytree(package, os.path.join(work, "TESSERA"))
        proc = subprocess.run(["/bin/sh", "Install.sh", "1"], cwd=os.path.join(work, "TESSERA"),
                              capture_output=True, text=True)
        self.assertNotEqual(proc.returncode, 0)
        self.assertIn("CMake only", proc.stdout)
        # the core: all of it, and a README
        for top, _, names in os.walk(os.path.join(REPO, "core")):
            for name in names:
                rel = os.path.relpath(os.path.join(top, name), os.path.join(REPO, "core"))
                self.assertIn(os.path.join("lib", "tessera", rel), files)
        self.assertIn("lib/tessera/README", files)
        self.assertEqual(read_text(os.path.join(out, "cmake/Modules/Packages/TESSERA.cmake")),
                         read_text(os.path.join(LAMMPS_DIR, "package", "TESSERA.cmake")))

    def test_docs(self):
        out = self.layout()
        docs = os.path.join(out, "doc", "src")
        pages = {}
        for name in sorted(os.listdir(docs)):
            text = read_text(os.path.join(docs, name))
            with self.subTest(page=name):
                # LAMMPS's doc pages are ASCII
                self.assertTrue(all(ord(c) < 128 for c in text))
                for m in re.finditer(r"^\.\. index:: (pair_style|fix|compute)?\s*(\S+)$", text,
                                     re.M):
                    pages[(m.group(1) or "command", m.group(2))] = name
                self.assertRegex(text, r"Restrictions\n\"+\n\nThis [a-z ]+ is part of the "
                                 r"TESSERA package\.  It is only enabled if LAMMPS")
                self.assertNotRegex(text, r"Part\s+of\s+Tessera|tessera-lmp|plugin load")
                # Tessera's own files are named as Tessera's (LAMMPS's tree has none)
                for m in re.finditer(r"(?<![\w/])((?:doc|studies|tools|bench|examples)/[\w./-]+)",
                                     text):
                    before = text[max(0, m.start() - 12):m.start()]
                    self.assertTrue(before.endswith("Tessera's ``"), "%s: %s" % (name, m.group(1)))
                # a link to one of Tessera's pages is to a page of the layout, or to
                # LAMMPS's own for a stand-in (fix brownian: BROWNIAN's)
                for target in re.findall(r":doc:`[^`<]*<([\w-]+)>`", text):
                    if os.path.exists(os.path.join(REPO, "doc", target + ".rst")):
                        self.assertTrue(os.path.exists(os.path.join(docs, target + ".rst")) or
                                        target == "fix_brownian", target)
        # one page for every style users type, none for the stand-in
        self.assertEqual(set(pages), user_styles_of_headers())
        self.assertNotIn("fix_brownian.rst", os.listdir(docs))
        # every style in LAMMPS's lists (lammps/package/styles.txt has its description)
        edits = os.path.join(out, "EDITS")
        lists = {"pair_style": ("Commands_pair", "pair_style"), "fix": ("Commands_fix", "fix"),
                 "compute": ("Commands_compute", "compute"), "command": ("Commands_all", None)}
        details = read_text(os.path.join(edits, "doc__src__Packages_details.rst"))
        for (kind, name), page in pages.items():
            stem = page[:-4]
            table, listing = lists[kind]
            self.assertIn("* :doc:`%s <%s>`\n" % (name, stem),
                          read_text(os.path.join(edits, "doc__src__%s.rst" % table)))
            if listing:
                self.assertRegex(read_text(os.path.join(edits, "doc__src__%s.rst" % listing)),
                                 r"\* :doc:`%s <%s>` - \w" % (re.escape(name), stem))
            self.assertIn("<%s>`" % stem, details)
        for target in ("cmake__CMakeLists.txt", "doc__src__Packages_list.rst",
                       "doc__src__Build_extras.rst", "doc__src__Build_package.rst"):
            self.assertIn("TESSERA", read_text(os.path.join(edits, target)))

    def test_styles_described(self):
        # lammps/package/styles.txt: one line per style users type, none stale
        described = set()
        for line in read_text(os.path.join(LAMMPS_DIR, "package", "styles.txt")).splitlines():
            if line.strip() and not line.startswith("#"):
                head, text = line.split("|", 1)
                self.assertTrue(text.strip())
                described.add(tuple(head.split()))
        missing = user_styles_of_headers() - described
        self.assertFalse(missing, "add a line '<kind> <name> | <short description>' to "
                         "lammps/package/styles.txt for each of %s" % sorted(missing))
        self.assertFalse(described - user_styles_of_headers(), "styles.txt names styles that "
                         "no header declares")

    def test_examples(self):
        out = self.layout()
        ex = os.path.join(out, "examples", "PACKAGES", "tessera")
        inputs = [n for n in os.listdir(ex) if n.startswith("in.")]
        self.assertGreaterEqual(len(inputs), 4)
        self.assertIn("README", os.listdir(ex))
        for name in inputs:
            # LAMMPS's rules for example inputs: no log, echo, package, processors or
            # suffix commands, output commands commented out, thermo without CPU time
            text = read_text(os.path.join(ex, name))
            lines = [l.split("#", 1)[0].split() for l in text.split("\n")]
            commands = [l[0] for l in lines if l]
            for forbidden in ("log", "echo", "package", "processors", "suffix", "dump",
                              "write_dump", "write_restart", "write_data", "plugin"):
                self.assertNotIn(forbidden, commands, name)
            for l in lines:
                if l and l[0] == "thermo_style":
                    self.assertFalse({"cpu", "cpuremain", "part", "timeremain"} & set(l), name)

    @nprocs(4)
    def test_example_logs(self):
        # the examples run on 1 and 4 ranks with the host's lmp (or the in-tree one),
        # and their logs are named as LAMMPS names them
        lmp = Config.intree_lmp or Config.lmp
        # (the 1-rank runs as lmptest starts them: Open MPI's session directories apart)
        env = dict(os.environ, OMPI_MCA_ess_singleton_isolated="1",
                   OMPI_MCA_orte_tmpdir_base=lmptest.mpiexec_command(1)[1].split("=")[1])
        out = self.layout("--logs", lmp, "--mpiexec", shlex.join(lmptest.mpiexec_command(4)[:-2]),
                          env=env)
        ex = os.path.join(out, "examples", "PACKAGES", "tessera")
        inputs = sorted(n[3:] for n in os.listdir(ex) if n.startswith("in."))
        logs = sorted(n for n in os.listdir(ex) if n.startswith("log."))
        self.assertEqual(len(logs), 2 * len(inputs), logs)
        for name in inputs:
            for n in (1, 4):
                form = r"log\.\d{1,2}[A-Z][a-z]{2}\d\d\.%s\.g\+\+\.%d" % (re.escape(name), n)
                match = [l for l in logs if re.fullmatch(form, l)]
                self.assertEqual(len(match), 1, (name, n, logs))
                text = read_text(os.path.join(ex, match[0]))
                self.assertIn("Total wall time", text)
                self.assertIn("on %d procs" % n, text)
                self.assertNotIn(ex, text)    # no path of this machine's layout

    def test_install_into_lammps_docs(self):
        # a tree with LAMMPS's doc/src lists in their form: the package's entries go in
        # alphabetically, once (a second install changes nothing)
        root = self.new_dir()
        os.makedirs(os.path.join(root, "src", "BROWNIAN"))
        os.makedirs(os.path.join(root, "cmake", "Modules", "Packages"))
        os.makedirs(os.path.join(root, "doc", "src"))
        with open(os.path.join(root, "src", "version.h"), "w") as f:
            f.write('#define LAMMPS_VERSION "4 Jul 2026"\n')
        with open(os.path.join(root, "src", "BROWNIAN", "fix_brownian.h"), "w") as f:
            f.write("// upstream's\n")
        with open(os.path.join(root, "cmake", "CMakeLists.txt"), "w") as f:
            f.write("set(STANDARD_PACKAGES\n  ADIOS\n  YAFF)\n"
                    "foreach(PKG_WITH_INCL GRAPHICS KSPACE)\nendforeach()\n")
        skeleton = {
            "Commands_pair.rst": ".. table_from_list::\n   :columns: 4\n\n"
                                 "   * :doc:`tersoff (giko) <pair_tersoff>`\n"
                                 "   * :doc:`yukawa (gko) <pair_yukawa>`\n",
            "Commands_fix.rst": ".. table_from_list::\n   :columns: 4\n\n"
                                "   * :doc:`adapt (k) <fix_adapt>`\n"
                                "   * :doc:`property/atom (k) <fix_property_atom>`\n"
                                "   * :doc:`wall/reflect <fix_wall_reflect>`\n",
            "Commands_compute.rst": ".. table_from_list::\n   :columns: 5\n\n"
                                    "   * :doc:`ackland/atom <compute_ackland_atom>`\n"
                                    "   * :doc:`voronoi/atom <compute_voronoi_atom>`\n",
            "pair_style.rst": "list:\n\n* :doc:`tersoff <pair_tersoff>` - Tersoff\n"
                              "* :doc:`yukawa <pair_yukawa>` - Yukawa\n\nend\n",
            "fix.rst": "list:\n\n* :doc:`adapt <fix_adapt>` - adapt\n"
                       "* :doc:`wall/reflect <fix_wall_reflect>` - reflect\n\nend\n",
            "compute.rst": "list:\n\n* :doc:`ackland/atom <compute_ackland_atom>` - a\n"
                           "* :doc:`voronoi/atom <compute_voronoi_atom>` - v\n\nend\n",
            "Packages_list.rst": ".. list-table::\n\n"
                                 "   * - :ref:`BROWNIAN <PKG-BROWNIAN>`\n     - b\n     - d\n"
                                 "     - PACKAGES/brownian\n     - no\n"
                                 "   * - :ref:`VORONOI <PKG-VORONOI>`\n     - v\n     - d\n"
                                 "     - voronoi\n     - ext\n\nend\n",
            "Packages_details.rst": ".. table_from_list::\n   :columns: 6\n\n"
                                    "   * :ref:`BROWNIAN <PKG-BROWNIAN>`\n"
                                    "   * :ref:`VORONOI <PKG-VORONOI>`\n\n----------\n\n"
                                    ".. _PKG-BROWNIAN:\n\nBROWNIAN package\n------\n\nb\n\n"
                                    "----------\n\n"
                                    ".. _PKG-VORONOI:\n\nVORONOI package\n------\n\nv\n",
            "Build_extras.rst": ".. table_from_list::\n   :columns: 6\n\n"
                                "   * :ref:`COLVARS <colvar>`\n   * :ref:`VTK <vtk>`\n\n"
                                "----------\n\n.. _colvar:\n\nCOLVARS package\n---\n\nc\n\n"
                                "----------\n\n.. _vtk:\n\nVTK package\n---\n\nv\n",
            "Build_package.rst": ".. table_from_list::\n   :columns: 6\n\n"
                                 "   * :ref:`COLVARS <colvar>`\n   * :ref:`VTK <vtk>`\n\nend\n",
        }
        for name, text in skeleton.items():
            with open(os.path.join(root, "doc", "src", name), "w") as f:
                f.write(text)
        script = os.path.join(REPO, "scripts", "install-lammps-package")
        for _ in range(2):
            proc = subprocess.run([script, root], capture_output=True, text=True)
            self.assertEqual(proc.returncode, 0, proc.stderr)
        doc = lambda name: read_text(os.path.join(root, "doc", "src", name))
        def ordered(text, *words):
            pos = [text.index(w) for w in words]
            self.assertEqual(pos, sorted(pos), words)
            for w in words:
                self.assertEqual(text.count(w), 1, w)
        ordered(doc("Commands_pair.rst"), ":doc:`tersoff",
                ":doc:`vertex/voronoi <pair_vertex_voronoi>`", ":doc:`yukawa")
        ordered(doc("Commands_fix.rst"), ":doc:`adapt", ":doc:`brownian/heun <",
                ":doc:`cell/adapt <", ":doc:`polarity <", ":doc:`property/atom",
                ":doc:`wall/reflect")
        ordered(doc("Commands_compute.rst"), ":doc:`ackland", ":doc:`cell/neighbor/mean <",
                ":doc:`vertex/atom <", ":doc:`vertex/tissue <", ":doc:`voronoi/atom")
        ordered(doc("pair_style.rst"), ":doc:`tersoff",
                "* :doc:`vertex/voronoi <pair_vertex_voronoi>` - ", ":doc:`yukawa")
        ordered(doc("fix.rst"), ":doc:`adapt <", "* :doc:`polarity <fix_polarity>` - ",
                ":doc:`wall/reflect")
        ordered(doc("compute.rst"), ":doc:`ackland",
                "* :doc:`vertex/local <compute_vertex_local>` - ", ":doc:`voronoi/atom")
        ordered(doc("Packages_list.rst"), ":ref:`BROWNIAN <", ":ref:`TESSERA <PKG-TESSERA>`",
                ":ref:`VORONOI <")
        details = doc("Packages_details.rst")
        ordered(details, "* :ref:`BROWNIAN", "* :ref:`TESSERA <PKG-TESSERA>`", "* :ref:`VORONOI",
                ".. _PKG-BROWNIAN:", ".. _PKG-TESSERA:", ".. _PKG-VORONOI:")
        self.assertIn(":doc:`fix polarity <fix_polarity>`", details)
        ordered(doc("Build_extras.rst"), "* :ref:`COLVARS", "* :ref:`TESSERA <tessera>`",
                "* :ref:`VTK", ".. _colvar:", ".. _tessera:", ".. _vtk:")
        ordered(doc("Build_package.rst"), "* :ref:`COLVARS", "* :ref:`TESSERA <tessera>`",
                "* :ref:`VTK")
        # the pages themselves, and the examples
        self.assertTrue(os.path.exists(os.path.join(root, "doc", "src", "pair_vertex_voronoi.rst")))
        self.assertTrue(os.path.exists(os.path.join(root, "examples", "PACKAGES", "tessera",
                                                    "in.active")))

    def test_intree_built_from_layout(self):
        # scripts/lammps-intree builds the in-tree LAMMPS from the layout it keeps
        # beside it: that layout's package is today's, and the lmp has its styles
        if not Config.intree_lmp:
            raise unittest.SkipTest("no lmp with the in-tree package (--intree-lmp)")
        layout = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(Config.intree_lmp))),
                              "layout")
        self.assertTrue(os.path.isfile(os.path.join(layout, "MANIFEST")), layout)
        fresh = self.layout()
        for sub in ("src/TESSERA", "lib/tessera/src", "lib/tessera/include/tessera"):
            a, b = os.path.join(layout, sub), os.path.join(fresh, sub)
            self.assertEqual(sorted(os.listdir(a)), sorted(os.listdir(b)), sub)
            for name in os.listdir(a):
                if name != "README":
                    self.assertEqual(read_text(os.path.join(a, name)),
                                     read_text(os.path.join(b, name)),
                                     "%s/%s: the in-tree build is not today's layout" % (sub, name))
        proc = subprocess.run([Config.intree_lmp, "-h"], capture_output=True, text=True)
        for kind, name in user_styles_of_headers():
            self.assertIn(name, proc.stdout)


if __name__ == "__main__":
    lmptest.main()
