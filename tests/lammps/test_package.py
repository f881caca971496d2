#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The in-tree package (scripts/install-lammps-package) sees the same styles as
tessera-lmp and the plugin: LAMMPS's CMake registers a style by the
PairStyle/FixStyle/ComputeStyle line of its header, while tessera-lmp and the
plugin use the table in lammps/tessera_styles.cpp.  Every table entry that
Tessera always serves must have that header line, naming the same class; and
the script must produce a tree in which CMake finds them (checked on a copy of
a LAMMPS tree's cmake/ and src/ skeleton, without building LAMMPS)."""

import os
import re
import subprocess

import lmptest
from lmptest import LammpsTestCase

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
LAMMPS_DIR = os.path.join(REPO, "lammps")
MACRO = {"pair_style": "PairStyle", "fix": "FixStyle", "compute": "ComputeStyle"}


def table_entries():
    """(command, name, class, policy) of every entry in the style table."""
    with open(os.path.join(LAMMPS_DIR, "tessera_styles.cpp")) as f:
        text = f.read()
    body = text[text.index("static const std::vector<Entry> table"):]
    body = body[:body.index("};")]
    return [(m.group(1), m.group(3), m.group(2), m.group(4) or "REPLACE") for m in re.finditer(
        r'(pair_style|fix_style|compute_style)<(\w+)>\("([^"]+)"(?:,\s*Policy::(\w+))?\)', body)]


def header_styles():
    """{(macro, name): class} from every lammps/*.h."""
    found = {}
    for name in os.listdir(LAMMPS_DIR):
        if name.endswith(".h"):
            with open(os.path.join(LAMMPS_DIR, name)) as f:
                for m in re.finditer(r"^(PairStyle|FixStyle|ComputeStyle)\(([^,]+),(\w+)\);",
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
        self.assertNotIn("fix_brownian.cpp", copied)
        self.assertTrue(os.path.exists(os.path.join(root, "lib", "tessera", "CMakeLists.txt")))
        self.assertTrue(os.path.exists(os.path.join(root, "cmake", "Modules", "Packages",
                                                    "TESSERA.cmake")))
        bad = subprocess.run([script, self.new_dir()], capture_output=True, text=True)
        self.assertNotEqual(bad.returncode, 0)
        self.assertIn("is not a LAMMPS source tree", bad.stderr)


if __name__ == "__main__":
    lmptest.main()
