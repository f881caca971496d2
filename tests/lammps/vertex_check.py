# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""A vertex tissue read from a write_data file, and the check, written here
in numpy independently of the core's check_tissue, that it is a valid
tissue: every ring has three or more distinct vertices, is a simple polygon
of positive area (no two non-adjacent edges cross), every directed edge is
held by one cell and its reverse by another, every vertex is in exactly three
cells, and the areas add up to the box's."""

import math

import numpy as np


def parse_data(text):
    """Box (xlo, xhi, ylo, yhi, xy), atoms {id: (type, x, y)}, rings {cell
    id: [vertex ids]} (atoms a T2 removed left out) and the per-atom double
    properties {name: {id: value}} of a write_data file (atom_style atomic
    or dipole)."""
    lines = text.split("\n")
    box = [0.0] * 5
    for line in lines:
        f = line.split()
        if line.endswith("xlo xhi"):
            box[0], box[1] = float(f[0]), float(f[1])
        elif line.endswith("ylo yhi"):
            box[2], box[3] = float(f[0]), float(f[1])
        elif line.endswith("xy xz yz"):
            box[4] = float(f[0])

    def section(prefix):
        heads = [k for k, l in enumerate(lines) if l.split("#")[0].strip() == prefix]
        if not heads:
            return [], ""
        i = heads[0]
        rows, k = [], i + 2
        while k < len(lines) and lines[k].strip():
            rows.append(lines[k].split())
            k += 1
        return rows, lines[i]

    rows, head = section("Atoms")
    col = 3 if "dipole" in head else 2    # dipole: id type q x y z ...
    atoms = {int(r[0]): (int(r[1]), float(r[col]), float(r[col + 1])) for r in rows}
    rings = {}
    for r in section("vring")[0]:
        ids = [int(v) for v in r[1:]]
        if ids[0] > 0:
            rings[int(r[0])] = [v for v in ids if v != 0]
    rings = {c: r for c, r in rings.items() if r}
    props = {}
    for k, l in enumerate(lines):
        w = l.split("#")
        if len(w) == 2 and w[1].split() and all(n.startswith("d_") for n in w[1].split()):
            rows, _ = section(w[0].strip())
            for j, name in enumerate(w[1].split()):
                props[name[2:]] = {int(r[0]): float(r[j + 1]) for r in rows}
    return box, atoms, rings, props


def polygon(box, atoms, ring):
    """The ring's corners unwrapped by the minimum image (tilted boxes too)."""
    lx, ly, xy = box[1] - box[0], box[3] - box[2], box[4]
    pts = [np.array(atoms[ring[0]][1:])]
    for v in ring[1:]:
        d = np.array(atoms[v][1:]) - pts[-1]
        j = math.floor(d[1] / ly + 0.5)
        d -= j * np.array([xy, ly])
        d[0] -= lx * math.floor(d[0] / lx + 0.5)
        pts.append(pts[-1] + d)
    return np.array(pts)


def area(p):
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def centroid(p):
    x, y = p[:, 0], p[:, 1]
    cr = x * np.roll(y, -1) - np.roll(x, -1) * y
    a = 0.5 * cr.sum()
    cx = ((x + np.roll(x, -1)) * cr).sum()
    cy = ((y + np.roll(y, -1)) * cr).sum()
    return np.array([cx, cy]) / (6 * a)


def _cross(p, q, r, s):
    def orient(a, b, c):
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    return (orient(p, q, r) * orient(p, q, s) < 0) and (orient(r, s, p) * orient(r, s, q) < 0)


def check_tissue(tc, text, what=""):
    """Asserts (through the unittest case tc) that the tissue of a
    write_data file is valid; returns (box, atoms, rings, props, areas)."""
    box, atoms, rings, props = parse_data(text)
    box_area = (box[1] - box[0]) * (box[3] - box[2])
    edges, count, areas = {}, {}, {}
    for c, r in rings.items():
        tc.assertGreaterEqual(len(r), 3, f"{what}: cell {c} ring {r}")
        tc.assertEqual(len(set(r)), len(r), f"{what}: cell {c} repeats a vertex: {r}")
        p = polygon(box, atoms, r)
        areas[c] = area(p)
        tc.assertGreater(areas[c], 0.0, f"{what}: cell {c} area {areas[c]}")
        n = len(r)
        for i in range(n):
            for j in range(i + 2, n):
                if i == 0 and j == n - 1:
                    continue
                tc.assertFalse(_cross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]),
                               f"{what}: cell {c} crosses itself: {r}")
        for i in range(n):
            e = (r[i], r[(i + 1) % n])
            tc.assertNotIn(e, edges, f"{what}: edge {e} held by cells {edges.get(e)} and {c}")
            edges[e] = c
            count[r[i]] = count.get(r[i], 0) + 1
    for a, b in edges:
        tc.assertIn((b, a), edges, f"{what}: edge {a} {b} of cell {edges[(a, b)]} has no twin")
    wrong = {v: k for v, k in count.items() if k != 3}
    tc.assertEqual(wrong, {}, f"{what}: vertices not in three cells")
    tc.assertAlmostEqual(sum(areas.values()), box_area, delta=1e-9 * box_area, msg=what)
    return box, atoms, rings, props, areas
