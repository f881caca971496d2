#!/usr/bin/python3
# Tessera: LAMMPS's conventions for a package, checked on lammps/.
# SPDX-License-Identifier: GPL-2.0-or-later
"""LAMMPS's conventions for the files of a package (src/TESSERA is made of lammps/):

  headers   a style header (one that declares a style: PairStyle(...), FixStyle(...),
            ComputeStyle(...), CommandStyle(...)) includes LAMMPS's headers and
            standard ones only, and of the package's own headers at most that of its
            base class, which must follow the same rule (fix brownian/heun's base,
            compute vertex/loops/atom's): Tessera's types stay in the .cpp files; its
            macro line is kept from clang-format ('// clang-format off' before it)
  block     every lammps/*.cpp, *.h begins with the package's header block in
            LAMMPS's layout (tests/conventions/header_block.py), a header's first line
            with LAMMPS's `-*- c++ -*-` marker
  format    clang-format (version 14, the repository's .clang-format: LAMMPS's
            settings) leaves every lammps/*.cpp, *.h as it is, and no line of a file in
            lammps/ is longer than 100 characters; skipped (exit 77) without
            clang-format-14.  scripts/format fixes what it finds.
  --self-test  each check fails on a copy of lammps/ with a planted fault

    check_conventions.py headers|block|format [--root DIR]
    check_conventions.py --self-test
"""

import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import header_block  # noqa: E402

MACRO = re.compile(r"^(PairStyle|FixStyle|ComputeStyle|CommandStyle)\(([^,]+),(\w+)\);", re.M)
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)
SKIP = 77
FORMAT_FIX = "run scripts/format (clang-format-14 with LAMMPS's settings, and the header blocks)"


def read(path):
    with open(path) as f:
        return f.read()


def sources(root):
    lammps = os.path.join(root, "lammps")
    return sorted(glob.glob(os.path.join(lammps, "*.cpp")) + glob.glob(os.path.join(lammps, "*.h")))


# ---------------------------------------------------------------------------
# headers

def package_header(root, name):
    """Whether an include names one of Tessera's headers (the package's own, or
    the core's tessera/...)."""
    return name.startswith("tessera/") or os.path.exists(os.path.join(root, "lammps", name)) \
        or os.path.exists(os.path.join(root, "core", "include", name))


def base_classes(text):
    """The base classes of the classes a header defines."""
    out = set()
    for decl in re.findall(r"^class\s+\w+\s*(?:final\s*)?:\s*([^{;]*)\{", text, re.M):
        out |= {b.split()[-1] for b in decl.split(",") if b.split()}
    return out


def header_faults(root, path, seen=None):
    """Faults of a style header's includes (and of the base-class headers it
    includes), as messages."""
    seen = set() if seen is None else seen
    if path in seen:
        return []
    seen.add(path)
    text = read(path)
    name = os.path.basename(path)
    faults = []
    bases = base_classes(text)
    for kind, inc in INCLUDE.findall(text):
        if not package_header(root, inc):
            continue    # LAMMPS's own header, or a standard one
        inc_path = os.path.join(root, "lammps", inc)
        # the header of a base class that is itself a style's (it derives from
        # LAMMPS's Fix, Compute, ...), not of an interface such as CoupledDof
        declares = os.path.exists(inc_path) and any(
            re.search(r"^class\s+%s\s*(?:final\s*)?:" % re.escape(b), read(inc_path), re.M)
            for b in bases)
        if not declares:
            faults.append(f"lammps/{name} includes \"{inc}\", one of Tessera's headers: a style "
                          f"header includes only LAMMPS's and standard headers (and its base "
                          f"class's); declare the types it names (namespace tessera {{ struct "
                          f"Model; }}) and hold them by pointer or in a struct Impl defined in "
                          f"the .cpp, which includes \"{inc}\"")
        else:
            faults += header_faults(root, inc_path, seen)
    return faults


def check_headers(root):
    faults = []
    styles = 0
    for path in sources(root):
        text = read(path)
        if path.endswith(".h") and MACRO.search(text):
            styles += 1
            faults += header_faults(root, path)
            # LAMMPS's CMake reads the macro line as written: clang-format keeps off it
            for m in MACRO.finditer(text):
                before = text[:m.start()].rstrip("\n").rsplit("\n", 1)[-1]
                if before.strip() != "// clang-format off":
                    faults.append(f"lammps/{os.path.basename(path)}: '{m.group(0)}' without "
                                  f"'// clang-format off' on the line before (and '// "
                                  f"clang-format on' after), as LAMMPS's style headers have")
    if styles == 0:
        faults.append("no style header found in lammps/ (PairStyle(...) etc.)")
    return faults, f"{styles} style headers"


# ---------------------------------------------------------------------------
# block

def expected(path, text):
    desc, rest = header_block.split_head(text)
    return header_block.block(path.endswith(".h"), desc) + "\n" + rest


def check_block(root):
    faults = []
    files = sources(root)
    for path in files:
        text = read(path)
        if expected(path, text) != text:
            first = text.split("\n", 1)[0]
            faults.append(f"lammps/{os.path.basename(path)}: its head is not the package's header "
                          f"block (tests/conventions/header_block.py; first line {first!r}): "
                          f"{FORMAT_FIX}")
    return faults, f"{len(files)} files"


# ---------------------------------------------------------------------------
# format

def clang_format():
    """clang-format 14 (the version whose output the files are in), or None."""
    for exe in ("clang-format-14", "clang-format"):
        path = shutil.which(exe)
        if not path:
            continue
        out = subprocess.run([path, "--version"], capture_output=True, text=True).stdout
        m = re.search(r"version (\d+)", out)
        if m and m.group(1) == "14":
            return path
    return None


def long_lines(root):
    faults = []
    for dirpath, _, names in os.walk(os.path.join(root, "lammps")):
        for n in sorted(names):
            path = os.path.join(dirpath, n)
            try:
                lines = read(path).split("\n")
            except UnicodeDecodeError:
                continue
            for k, line in enumerate(lines, 1):
                if len(line) > 100:
                    faults.append(f"{os.path.relpath(path, root)}:{k}: {len(line)} characters "
                                  f"(at most 100)")
    return faults


def check_format(root, exe):
    faults = long_lines(root)
    files = sources(root)
    out = subprocess.run([exe, "--dry-run", "-Werror", "--style=file"] + files,
                         capture_output=True, text=True, cwd=root)
    if out.returncode != 0:
        bad = sorted({os.path.relpath(m, root) for m in
                      re.findall(r"^(\S+?):\d+:\d+: (?:error|warning)", out.stderr, re.M)})
        faults.append(f"clang-format would change {len(bad)} file(s): {' '.join(bad) or out.stderr}"
                      f"; {FORMAT_FIX}")
    return faults, f"{len(files)} files"


# ---------------------------------------------------------------------------

def run(check, root):
    if check == "headers":
        return check_headers(root)
    if check == "block":
        return check_block(root)
    exe = clang_format()
    if not exe:
        return None, ("clang-format 14 not found (apt-get install clang-format-14): the format "
                      "of lammps/ is not checked")
    return check_format(root, exe)


def copy_tree(dst):
    shutil.copytree(os.path.join(REPO, "lammps"), os.path.join(dst, "lammps"))
    shutil.copytree(os.path.join(REPO, "core", "include"), os.path.join(dst, "core", "include"))
    shutil.copy(os.path.join(REPO, ".clang-format"), dst)
    shutil.copytree(os.path.join(REPO, "tests", "conventions"),
                    os.path.join(dst, "tests", "conventions"))


def plant(path, old, new):
    text = read(path)
    assert old in text, (path, old)
    with open(path, "w") as f:
        f.write(text.replace(old, new, 1))


def self_test():
    """Each check passes on a copy of lammps/ and fails on a planted fault."""
    plants = [
        ("headers", "fix_clock.h", '#include "fix.h"\n', '#include "fix.h"\n#include "tessera/cells.h"\n'),
        ("headers", "pair_vertex_voronoi.h", '#include "pair.h"\n',
         '#include "pair.h"\n#include "cell_source.h"\n'),
        ("headers", "fix_brownian.h", '#include "fix.h"\n',    # in a style's base class
         '#include "fix.h"\n#include "integrator_chatter.h"\n'),
        ("headers", "fix_clock.h", "// clang-format off\nFixStyle", "FixStyle"),
        ("headers", "fix_polarity.h", '#include "fix.h"\n',    # an interface as a base class
         '#include "fix.h"\n#include "coupled_dof.h"\n',
         "class FixPolarity : public Fix {", "class FixPolarity : public Fix, public CoupledDof {"),
        ("block", "fix_clock.cpp", "   SPDX-License-Identifier: GPL-2.0-or-later\n", ""),
        ("block", "fix_clock.h", "/* -*- c++ -*- ---", "/* ----------"),
        ("format", "fix_clock.cpp", "\n}\n", "\n}\n// " + "x" * 98 + "\n"),
        ("format", "fix_clock.cpp", "\n{\n", "\n{\n      \n"),
    ]
    have_format = clang_format() is not None
    failures = []
    for check in ("headers", "block", "format"):
        if check == "format" and not have_format:
            print("self-test: clang-format 14 not found: the format check is not tested")
            continue
        with tempfile.TemporaryDirectory() as tmp:
            copy_tree(tmp)
            faults, _ = run(check, tmp)
            if faults:
                failures.append(f"{check}: fails on the unchanged lammps/: {faults[:3]}")
        for kind, name, *edits in plants:
            if kind != check:
                continue
            new = edits[1]
            with tempfile.TemporaryDirectory() as tmp:
                copy_tree(tmp)
                for k in range(0, len(edits), 2):
                    plant(os.path.join(tmp, "lammps", name), edits[k], edits[k + 1])
                faults, _ = run(check, tmp)
                mine = [f for f in faults if name in f]
                if not mine:
                    failures.append(f"{check}: finds nothing in {name}, with {new.strip()[:40]!r} "
                                    f"planted")
                else:
                    print(f"self-test: {check} finds the fault planted in {name}: {mine[0][:120]}")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("check", nargs="?", choices=("headers", "block", "format"))
    parser.add_argument("--root", default=REPO, help="the repository (default: this one)")
    parser.add_argument("--self-test", action="store_true")
    opts = parser.parse_args()
    if opts.self_test:
        return self_test()
    if not opts.check:
        parser.error("name a check, or --self-test")
    faults, what = run(opts.check, opts.root)
    if faults is None:
        print(f"check_conventions {opts.check}: skipped: {what}")
        return SKIP
    for f in faults:
        print(f)
    print(f"check_conventions {opts.check}: {what}, {len(faults)} fault(s)")
    return 1 if faults else 0


if __name__ == "__main__":
    sys.exit(main())
