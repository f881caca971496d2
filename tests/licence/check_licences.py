#!/usr/bin/env python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The licences hold: nothing that runs inside LAMMPS (GPL-2.0-only) includes a CGAL
header (GPL-3.0-or-later triangulations; LGPL-3.0-or-later kernels) or MPFR's
(LGPL-3.0-or-later), and nothing it links is outside allowed_libraries.txt.

  check_licences.py --build DIR [--build DIR ...] [--binary FILE ...]
                    [--reference FILE]
  check_licences.py --self-test

--build: a CMake build tree; the compiler's dependency files (*.o.d) of the objects
that go into Tessera's LAMMPS artefacts (targets tessera_core, tessera_lammps,
tesseraplugin, and in a LAMMPS build tree the package TESSERA's objects) are read:
every header each object was compiled with.  --binary: a shared library or
executable whose linked libraries (ldd) are checked; libraries that --reference (a
LAMMPS executable or library without Tessera; default: the liblammps.so the binary
loads) brings too are LAMMPS's own and only listed.  --self-test plants a CGAL
include and an MPFR library and checks that both are refused.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
# Headers that must not reach anything LAMMPS links.
FORBIDDEN_HEADERS = [
    (re.compile(r"/CGAL/"), "CGAL (GPL-3.0-or-later / LGPL-3.0-or-later)"),
    (re.compile(r"/(mpfr|mpf2mpfr|gmpfrxx|mpreal)\.h$"), "MPFR (LGPL-3.0-or-later)"),
]
# Object directories (CMake's <target>.dir) whose objects are part of the artefacts.
TARGET_DIRS = re.compile(r"/CMakeFiles/(tessera_core|tessera_lammps|tesseraplugin)\.dir/")
# In a LAMMPS build tree: the package's sources (src/TESSERA) compiled into lammps.
INTREE_OBJECT = re.compile(r"/CMakeFiles/lammps\.dir/.*/TESSERA/[^/]+\.o\.d$")


def read_allowed():
    allowed = {}
    with open(os.path.join(HERE, "allowed_libraries.txt")) as f:
        for line in f:
            line = line.split("#", 1)[0].strip() if line.lstrip().startswith("#") else line.strip()
            if not line:
                continue
            name, licence = line.split(None, 1)
            allowed[name] = licence
    return allowed


def depfiles(build):
    """The dependency files of the objects that go into the artefacts."""
    found = []
    for root, _dirs, files in os.walk(build):
        for name in files:
            if not name.endswith(".o.d"):
                continue
            path = os.path.join(root, name)
            if TARGET_DIRS.search(path) or INTREE_OBJECT.search(path):
                found.append(path)
    return sorted(found)


def headers_of(depfile):
    with open(depfile) as f:
        text = f.read().replace("\\\n", " ")
    # "target.o: source header header ..."; paths have no spaces in these builds
    _, _, deps = text.partition(":")
    return deps.split()


def source_path(depfile, source):
    """The source named first in a dependency file: a relative path is relative to the
    directory the compiler ran in, the one that holds the target's CMakeFiles/."""
    if os.path.isabs(source):
        return source
    cut = depfile.find(os.sep + "CMakeFiles" + os.sep)
    return os.path.join(depfile[:cut] if cut >= 0 else os.path.dirname(depfile), source)


def check_includes(builds):
    problems, nobjects, stale = [], 0, []
    for build in builds:
        files = depfiles(build)
        for d in files:
            deps = headers_of(d)
            # An object whose source is gone (a file removed since this tree was built) is in
            # no artefact any more: CMake rebuilds the library from the sources it has.
            if deps and not os.path.exists(source_path(d, deps[0])):
                stale.append(os.path.relpath(d, build)[: -len(".d")])
                continue
            nobjects += 1
            hits = {}
            for h in deps:
                for pattern, what in FORBIDDEN_HEADERS:
                    if pattern.search(h):
                        hits.setdefault(what, []).append(h)
                        break
            obj = os.path.relpath(d, build)[: -len(".d")]
            for what, hs in hits.items():
                problems.append(f"{obj} (in {build}) includes {len(hs)} header(s) of {what}, "
                                f"first {hs[0]}")
    if nobjects == 0:
        problems.append("no dependency files (*.o.d) of tessera_core, tessera_lammps, tesseraplugin "
                        "or the package TESSERA in " + ", ".join(builds) +
                        ": build first (scripts/build), or point --build at a build tree")
    if stale:
        print(f"check_licences: {len(stale)} object(s) left from sources that are gone, not "
              f"checked (in no artefact): {' '.join(stale)}")
    return problems, nobjects


def soname_key(path_or_name):
    base = os.path.basename(path_or_name)
    return base.split(".so")[0]


def ldd(binary):
    """{soname key: resolved path} of every library the binary loads."""
    out = subprocess.run(["ldd", binary], capture_output=True, text=True)
    if out.returncode != 0:
        raise SystemExit(f"check_licences: ldd {binary} failed: {out.stderr.strip()}")
    libs = {}
    for line in out.stdout.splitlines():
        line = line.strip()
        if not line or line.startswith("linux-vdso") or "statically linked" in line:
            continue
        if "=>" in line:
            name, _, rest = line.partition("=>")
            path = rest.split("(")[0].strip()
            if path == "not found":
                raise SystemExit(f"check_licences: {binary} needs {name.strip()}, which ldd cannot find")
            libs[soname_key(name.strip())] = path
        else:
            path = line.split("(")[0].strip()
            libs[soname_key(path)] = path
    return libs


def needed(binary):
    out = subprocess.run(["readelf", "-d", binary], capture_output=True, text=True, check=True)
    return [soname_key(m) for m in re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", out.stdout)]


def check_libraries(binaries, reference, allowed):
    problems, report = [], []
    for binary in binaries:
        libs = ldd(binary)
        ref = reference or libs.get("liblammps")
        lammps_own = set(ldd(ref)) | {soname_key(ref)} if ref else set()
        ours = set(needed(binary)) | (set(libs) - lammps_own)
        for key in sorted(ours):
            if key in allowed:
                report.append(f"  {os.path.basename(binary)}: {key} ({allowed[key]})")
            else:
                problems.append(f"{binary} links {libs.get(key, key)}, which is not in "
                                f"tests/licence/allowed_libraries.txt (libraries that may be "
                                f"combined with GPL-2.0-only LAMMPS)")
        extra = sorted(set(libs) & lammps_own - ours)
        if extra:
            report.append(f"  {os.path.basename(binary)}: through LAMMPS ({ref}): " + " ".join(extra))
    return problems, report


def self_test():
    """A planted CGAL include and a planted MPFR library must be refused."""
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        objdir = os.path.join(tmp, "core", "CMakeFiles", "tessera_core.dir", "src")
        os.makedirs(objdir)
        src = os.path.join(tmp, "planted.cpp")
        with open(src, "w") as f:
            f.write("#include <CGAL/config.h>\nint planted() { return 0; }\n")
        dep = os.path.join(objdir, "planted.cpp.o.d")
        compiled = subprocess.run(["c++", "-std=c++17", "-MD", "-MF", dep, "-c", src, "-o",
                                   os.path.join(objdir, "planted.cpp.o")], capture_output=True)
        if compiled.returncode != 0:    # no CGAL installed: the compiler's view of it, by hand
            with open(dep, "w") as f:
                f.write(f"{objdir}/planted.cpp.o: {src} \\\n /usr/include/CGAL/config.h\n")
        problems, n = check_includes([tmp])
        if n != 1 or not any("CGAL" in p for p in problems):
            print("self-test: a planted #include <CGAL/config.h> was not refused:", problems)
            ok = False
        else:
            print("self-test: planted CGAL include refused:", problems[0])
        # the same object after its source is removed is left over from an older tree
        os.rename(src, src + ".gone")
        problems, n = check_includes([tmp])
        if n != 0 or problems and "no dependency files" not in problems[0]:
            print("self-test: an object whose source is gone was checked:", problems)
            ok = False
        os.rename(src + ".gone", src)
        # a source named relative to the directory the compiler ran in (the in-tree build's
        # Makefiles do so) is found there and checked
        with open(dep) as f:
            text = f.read()
        with open(dep, "w") as f:
            f.write(text.replace(src, os.path.join("..", "planted.cpp"), 1))
        problems, n = check_includes([tmp])
        if n != 1 or not any("CGAL" in p for p in problems):
            print("self-test: an object whose source is named by a relative path was not checked:",
                  problems)
            ok = False
        # an object of another target (a test's oracle) may include CGAL
        other = os.path.join(tmp, "tests", "CMakeFiles", "test_core.dir")
        os.makedirs(other)
        os.rename(dep, os.path.join(other, "planted.cpp.o.d"))
        problems, n = check_includes([tmp])
        if n != 0:
            print("self-test: a test's object was taken for an artefact's")
            ok = False
    allowed = read_allowed()
    if "libmpfr" in allowed or any(k.startswith("libCGAL") for k in allowed):
        print("self-test: allowed_libraries.txt lists MPFR or CGAL")
        ok = False
    # a planted library: a shared object that links MPFR, when MPFR is installed
    with tempfile.TemporaryDirectory() as tmp:
        src = os.path.join(tmp, "p.cpp")
        with open(src, "w") as f:
            f.write("extern \"C\" int mpfr_get_default_prec(); int p() { return mpfr_get_default_prec(); }\n")
        so = os.path.join(tmp, "libplanted.so")
        built = subprocess.run(["c++", "-shared", "-fPIC", src, "-o", so, "-Wl,--no-as-needed", "-lmpfr"],
                               capture_output=True)
        if built.returncode == 0:
            problems, _ = check_libraries([so], None, allowed)
            if not any("mpfr" in p for p in problems):
                print("self-test: a planted link to libmpfr was not refused:", problems)
                ok = False
            else:
                print("self-test: planted MPFR library refused:", problems[0])
        else:
            print("self-test: (libmpfr not installed: the planted library is skipped)")
    return ok


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", action="append", default=[])
    ap.add_argument("--binary", action="append", default=[])
    ap.add_argument("--reference")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        return 0 if self_test() else 1
    if not a.build and not a.binary:
        ap.error("give --build DIR and/or --binary FILE (or --self-test)")
    problems = []
    if a.build:
        p, n = check_includes(a.build)
        problems += p
        print(f"check_licences: {n} objects' headers read")
    if a.binary:
        for b in a.binary:
            if not os.path.exists(b):
                problems.append(f"{b}: no such file (build first)")
        present = [b for b in a.binary if os.path.exists(b)]
        p, report = check_libraries(present, a.reference, read_allowed())
        problems += p
        print("check_licences: libraries linked (licence):")
        print("\n".join(report))
    if problems:
        print(f"check_licences: {len(problems)} problem(s): what is compiled into or linked by "
              "Tessera's LAMMPS artefacts must be GPL-2.0-compatible (no CGAL, no MPFR):")
        for p in problems[:40]:
            print("  " + p)
        if len(problems) > 40:
            print(f"  ... and {len(problems) - 40} more")
        return 1
    print("check_licences: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
