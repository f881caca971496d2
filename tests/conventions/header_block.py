# Tessera: the header block of lammps/ files, shared by check_conventions.py
# (which requires it) and scripts/format (which writes it).
# SPDX-License-Identifier: GPL-2.0-or-later
"""LAMMPS's layout of a source file's head: a framed block naming the package,
its copyright holders and licence (a header's first line carries the
`-*- c++ -*-` marker), then a framed block with the contributing authors and
what the file holds.  The copyright is Tessera's developers', not Sandia's:
the statement LAMMPS's developers ask of a contributed package is settled at
submission (doc/howto_lammps_package.md)."""

import re

TOP = "/* ----------------------------------------------------------------------"
TOP_H = "/* -*- c++ -*- ----------------------------------------------------------"
BOTTOM = "------------------------------------------------------------------------- */"

LICENCE = """\
   TESSERA package for LAMMPS: vertex models of cell tissues
   LAMMPS: https://www.lammps.org/

   Copyright (2026) the Tessera developers.  This software is distributed
   under the GNU General Public License, version 2 or (at your option) any
   later version.
   SPDX-License-Identifier: GPL-2.0-or-later

   See the README file in the package's directory (src/TESSERA)."""

AUTHORS = "   Contributing authors: the Tessera developers"


def block(is_header, description_lines):
    """The head of a file: the licence block, then the authors' block with the
    file's own description (lines without indentation; may be empty)."""
    out = [TOP_H if is_header else TOP, LICENCE, BOTTOM, "", TOP, AUTHORS]
    desc = list(description_lines)
    while desc and not desc[0].strip():
        desc.pop(0)
    while desc and not desc[-1].strip():
        desc.pop()
    if desc:
        out.append("")
        out += [("   " + d).rstrip() for d in desc]
    out.append(BOTTOM)
    return "\n".join(out) + "\n"


def split_head(text):
    """(description lines, rest) of a file whose head is either this block or an
    older one (a /* */ block, or // lines) naming Tessera and its SPDX line."""
    lines = text.split("\n")
    desc = []
    i = 0
    if lines and lines[0].startswith("//"):
        while i < len(lines) and lines[i].startswith("//"):
            desc.append(re.sub(r"^// ?", "", lines[i]))
            i += 1
    else:
        blocks = 0
        while i < len(lines) and lines[i].startswith("/*") and blocks < 2:
            j = i
            while "*/" not in lines[j]:
                j += 1
            body = [re.sub(r"^   ", "", l) for l in lines[i + 1:j]]
            if blocks == 0 or any("Contributing author" in l for l in body):
                desc += body
            else:
                break
            blocks += 1
            i = j + 1
            if i < len(lines) and lines[i].strip() == "" and i + 1 < len(lines) \
                    and lines[i + 1].startswith("/* ---") and blocks < 2:
                i += 1
            else:
                break
    drop = (r"^Tessera: active Voronoi", r"^SPDX-License-Identifier", r"^TESSERA package for",
            r"^LAMMPS: https://www.lammps.org/$", r"^Copyright \(2026\) the Tessera",
            r"^under the GNU General Public", r"^later version\.$",
            r"^See the README file in the package", r"^Contributing authors: the Tessera")
    desc = [d for d in desc if not any(re.search(p, d) for p in drop)]
    # collapse runs of blank lines left by the dropped lines
    clean = []
    for d in desc:
        if d.strip() or (clean and clean[-1].strip()):
            clean.append(d)
    rest = "\n".join(lines[i:]).lstrip("\n")
    return clean, rest
