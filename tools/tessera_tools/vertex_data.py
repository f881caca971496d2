# SPDX-License-Identifier: GPL-2.0-or-later
"""A vertex tissue's data file (pair_style vertex/polygon; written by
write_data or tessera-tools segmented): the box, the atoms and the rings of
section 'vring', and each cell's polygon unwrapped by the minimum image."""

import numpy as np

# Columns of x and y in the Atoms section, per atom style.
XY_COLUMN = {"atomic": 2, "dipole": 3, "sphere": 4, "full": 4, "molecular": 3}


class VertexData:
    """box: xlo, ylo, lx, ly (orthogonal boxes); atoms {id: (type, x, y)};
    rings {cell id: [vertex ids]} (cells only)."""

    def __init__(self, path):
        with open(path) as f:
            lines = f.read().split("\n")
        bounds = {}
        style = "atomic"
        for line in lines:
            w = line.split()
            if line.rstrip().endswith(("xlo xhi", "ylo yhi")):
                bounds[w[2]] = (float(w[0]), float(w[1]))
            if line.startswith("Atoms") and "#" in line:
                style = line.split("#")[1].strip().split()[0]
        if style not in XY_COLUMN:
            raise ValueError(f"{path}: atom style {style!r} is not one of {sorted(XY_COLUMN)}")
        self.xlo, self.lx = bounds["xlo"][0], bounds["xlo"][1] - bounds["xlo"][0]
        self.ylo, self.ly = bounds["ylo"][0], bounds["ylo"][1] - bounds["ylo"][0]

        def section(name):
            i = [k for k, l in enumerate(lines) if l.split("#")[0].strip() == name][0] + 2
            rows = []
            while i < len(lines) and lines[i].strip():
                rows.append(lines[i].split())
                i += 1
            return rows

        c = XY_COLUMN[style]
        self.atoms = {int(r[0]): (int(r[1]), float(r[c]), float(r[c + 1])) for r in section("Atoms")}
        rings = {int(r[0]): [int(v) for v in r[1:] if int(v) > 0] for r in section("vring")}
        self.rings = {cell: ring for cell, ring in rings.items() if ring}

    def polygon(self, cell):
        """The cell's corners, each the image closest to the one before."""
        return unwrap([self.atoms[v][1:] for v in self.rings[cell]], (self.lx, self.ly))


def unwrap(points, box):
    """Points of a ring in an orthogonal periodic box (lx, ly), each moved to
    its image closest to the one before: the polygon in one piece."""
    box = np.asarray(box, dtype=float)
    pts = [np.asarray(points[0], dtype=float)]
    for q in points[1:]:
        d = np.asarray(q, dtype=float) - pts[-1]
        d -= box * np.round(d / box)
        pts.append(pts[-1] + d)
    return np.array(pts)
