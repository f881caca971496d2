# SPDX-License-Identifier: GPL-2.0-or-later
"""A vertex tissue from a segmented image: the label image of a confluent,
periodic patch of cells (one integer label per pixel, each cell one label)
becomes the rings of pair_style vertex/polygon.

The junctions are the pixel corners where three or more labels meet; a
cell's ring is the junctions met in order along its boundary, traced
counter-clockwise, and its polygon the straight lines between them (the
staircase of pixels between two junctions becomes one edge).  A corner where
four labels meet becomes two vertices 0.5 pixel apart joined by a short edge
between two opposite cells (every vertex of the model is in three cells;
the run's first T1s settle such edges).  Row 0 of the array is the bottom of
the image (y grows with the row), column 0 its left side; the image is
periodic in both directions (a patch cut from a larger tissue is not: the
model needs a periodic box).

What stops with an error naming the label or pixel: a label in two pieces or
with a hole (another label inside it), a label whose boundary touches itself
at a corner (two of its pixels meeting only diagonally: join_pinches()
resolves these first by giving it one more pixel), a cell with fewer
than three junctions, and a polygon that is not simple or has no positive
area once its junctions are joined by straight lines.  Label 0 can be the
segmentation's boundary pixels (watershed lines): fill_boundaries() gives each
of them a neighbouring cell's label first.
"""

import numpy as np

from .vertex_data import unwrap
from .voronoi import polygon_area

# The four pixels around corner (i, j) (the lower left corner of pixel
# (i, j)), counter-clockwise from the upper right: (row offset, column offset).
AROUND = ((0, 0), (0, -1), (-1, -1), (-1, 0))    # NE, NW, SW, SE


def fill_boundaries(labels, boundary=0):
    """Each pixel of label `boundary` takes the label of a neighbour (right,
    up, left, down: the first that is a cell), sweep after sweep, until none
    is left.  Returns a new array."""
    lab = np.array(labels, copy=True)
    if np.all(lab == boundary):
        raise ValueError(f"every pixel has the boundary label {boundary}: no cells")
    while True:
        empty = lab == boundary
        if not empty.any():
            return lab
        filled = lab.copy()
        for shift in ((0, -1), (-1, 0), (0, 1), (1, 0)):
            nb = np.roll(lab, shift, axis=(0, 1))
            take = empty & (filled == boundary) & (nb != boundary)
            filled[take] = nb[take]
        lab = filled


def _pinches(lab):
    """Corners where a label holds two diagonal pixels and not the other
    two: [(row, column, k)] with k = 0 (NE and SW) or 1 (NW and SE)."""
    around = np.stack([np.roll(lab, (-di, -dj), axis=(0, 1)) for di, dj in AROUND], axis=-1)
    found = []
    for k, l in ((0, 2), (1, 3)):
        pinch = (around[..., k] == around[..., l]) & (around[..., k] != around[..., (k + 1) % 4]) \
            & (around[..., k] != around[..., (k + 3) % 4])
        found += [(int(i), int(j), k) for i, j in np.argwhere(pinch)]
    return found


def join_pinches(labels, max_sweeps=100):
    """Each corner where a label's pixels meet only diagonally (a staircase
    boundary at 45 degrees, common in segmentations) gets one of the other two
    pixels given to that label, the one whose own label has more pixels, so
    that the label is connected through sides there.  Returns (the new array,
    the number of pixels changed)."""
    lab = np.array(labels, copy=True)
    ny, nx = lab.shape
    changed = 0
    for _ in range(max_sweeps):
        found = _pinches(lab)
        if not found:
            return lab, changed
        counts = dict(zip(*np.unique(lab, return_counts=True)))
        for i, j, k in found:
            cells = [((i + di) % ny, (j + dj) % nx) for di, dj in AROUND]
            a, b = lab[cells[k]], lab[cells[k + 2]]
            others = [cells[(k + 1) % 4], cells[(k + 3) % 4]]
            if a != b or any(lab[o] == a for o in others):
                continue    # an earlier change this sweep resolved it
            take = max(others, key=lambda o: (counts.get(lab[o], 0), o))
            counts[lab[take]] -= 1
            lab[take] = a
            changed += 1
    raise ValueError(f"labels still touch themselves at corners after {max_sweeps} sweeps")


class Tissue:
    """The vertex tissue of a label image: vertices (n, 2) positions in
    length units, rings {label: [vertex indices]} counter-clockwise, box (lx, ly)."""

    def __init__(self, vertices, rings, box):
        self.vertices, self.rings, self.box = vertices, rings, box

    def polygon(self, label):
        """The ring's corners unwrapped from its first (minimum image)."""
        return unwrap(self.vertices[self.rings[label]], self.box)


def centroid_of(p):
    x, y = p[:, 0], p[:, 1]
    cr = x * np.roll(y, -1) - np.roll(x, -1) * y
    a = 0.5 * cr.sum()
    return np.array([((x + np.roll(x, -1)) * cr).sum(), ((y + np.roll(y, -1)) * cr).sum()]) / (6 * a)


def _crosses(p, q, r, s):
    def orient(a, b, c):
        return np.sign((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    return orient(p, q, r) * orient(p, q, s) < 0 and orient(r, s, p) * orient(r, s, q) < 0


def tissue_from_labels(labels, pixel=1.0):
    """The Tissue of a periodic label image (see the module's text)."""
    lab = np.asarray(labels)
    if lab.ndim != 2 or min(lab.shape) < 2:
        raise ValueError(f"the labels must be a 2d array of at least 2 x 2 pixels, got shape {lab.shape}")
    ny, nx = lab.shape
    box = (nx * pixel, ny * pixel)
    # The labels around every corner (ny, nx, 4): NE, NW, SW, SE.
    around = np.stack([np.roll(lab, (-di, -dj), axis=(0, 1)) for di, dj in AROUND], axis=-1)
    ordered = np.sort(around, axis=-1)
    distinct = 1 + np.count_nonzero(ordered[..., 1:] != ordered[..., :-1], axis=-1)
    found = _pinches(lab)
    if found:
        i, j, k = found[0]
        raise ValueError(f"label {lab[(i + AROUND[k][0]) % ny, (j + AROUND[k][1]) % nx]} touches "
                         f"itself at the corner below and left of pixel (row {i}, column {j}): two "
                         "of its pixels meet only diagonally (join_pinches() gives one of the "
                         "other two pixels to it)")
    # Vertices: one per 3-label corner, two per 4-label corner (v1 in NE, NW,
    # SW offset towards NW; v2 in SW, SE, NE offset towards SE).
    index = {}
    positions = []
    for i, j in np.argwhere(distinct >= 3):
        x, y = j * pixel, i * pixel
        if distinct[i, j] == 3:
            index[(i, j)] = (len(positions),)
            positions.append((x, y))
        else:
            d = 0.25 * pixel
            index[(i, j)] = (len(positions), len(positions) + 1)
            positions += [(x - d, y + d), (x + d, y - d)]
    vertices = np.array(positions, dtype=float).reshape(-1, 2)
    vertices[:, 0] %= box[0]
    vertices[:, 1] %= box[1]
    # Directed boundary steps of each label, the label on their left:
    # step from corner a to corner b, keyed by a.
    steps = {}
    up = np.roll(lab, -1, axis=0) != lab       # the side above pixel (i, j) is a boundary
    right = np.roll(lab, -1, axis=1) != lab    # the side to its right
    down = np.roll(lab, 1, axis=0) != lab
    left = np.roll(lab, 1, axis=1) != lab
    for side, (a_off, b_off) in ((up, ((1, 1), (1, 0))), (left, ((1, 0), (0, 0))),
                                 (down, ((0, 0), (0, 1))), (right, ((0, 1), (1, 1)))):
        for i, j in np.argwhere(side):
            c = lab[i, j]
            a = ((i + a_off[0]) % ny, (j + a_off[1]) % nx)
            b = ((i + b_off[0]) % ny, (j + b_off[1]) % nx)
            steps.setdefault(c, {})[a] = b    # (no pinches: one step per corner)
    rings = {}
    for c in sorted(steps):
        todo = dict(steps[c])
        start = min(todo)
        loop, a = [], start
        while True:
            loop.append(a)
            a = todo.pop(a)
            if a == start:
                break
        if todo:
            raise ValueError(f"label {c} has more than one boundary: it is in several pieces, or "
                             "another label lies inside it (a hole); every cell must be one "
                             "piece without holes")
        ring = []
        for corner in loop:
            if corner not in index:
                continue
            ids = index[corner]
            if len(ids) == 1:
                ring.append(ids[0])
                continue
            ne, nw, sw, se = (lab[(corner[0] + di) % ny, (corner[1] + dj) % nx] for di, dj in AROUND)
            ring += {ne: [ids[0], ids[1]], sw: [ids[1], ids[0]], nw: [ids[0]], se: [ids[1]]}[c]
        if len(ring) < 3:
            raise ValueError(f"label {c} meets {len(ring)} junction(s) along its boundary; a cell of "
                             "the vertex model needs at least three (a cell lying inside another, "
                             "or between only two others)")
        rings[int(c)] = ring
    t = Tissue(vertices, rings, box)
    for c in rings:
        p = t.polygon(c)
        if not polygon_area(p) > 0.0:
            raise ValueError(f"label {c}: its junctions joined by straight lines enclose no "
                             f"positive area ({polygon_area(p):.4g})")
        n = len(p)
        for k in range(n):
            for m in range(k + 2, n):
                if k == 0 and m == n - 1:
                    continue
                if _crosses(p[k], p[(k + 1) % n], p[m], p[(m + 1) % n]):
                    raise ValueError(f"label {c}: its junctions joined by straight lines cross "
                                     "(a cell too concave for straight edges)")
    return t


def write_data(t, path, cell_type=1, vertex_type=2, ntypes=2, width=16, atom_style="atomic",
               title="a vertex tissue from a segmented image (tessera-tools segmented)"):
    """A LAMMPS data file: cells first (IDs 1..N in label order, at their
    polygons' centroids), then the vertices; the rings in section 'vring'
    (read_data FILE fix vring NULL vring, with 'fix vring all property/atom
    i2_vring W' defined before).  Returns {label: cell atom ID}."""
    longest = max(len(r) for r in t.rings.values())
    if longest > width:
        raise ValueError(f"a cell has {longest} sides, more than the rings' width {width}: "
                         f"give --maxsides {longest} (and the same W to fix vring)")
    if atom_style not in ("atomic", "dipole"):
        raise ValueError(f"atom style {atom_style!r}: atomic or dipole")
    lx, ly = t.box
    labels = sorted(t.rings)
    ids = {c: k + 1 for k, c in enumerate(labels)}
    nc, nv = len(labels), len(t.vertices)

    def atom_line(i, typ, x, y):
        if atom_style == "atomic":
            return f"{i} {typ} {x!r} {y!r} 0.0"
        return f"{i} {typ} 0.0 {x!r} {y!r} 0.0 0.0 0.0 0.0"

    out = [f"LAMMPS data file: {title}", "", f"{nc + nv} atoms", f"{ntypes} atom types", "",
           f"0.0 {lx!r} xlo xhi", f"0.0 {ly!r} ylo yhi", "-0.5 0.5 zlo zhi", "",
           f"Atoms # {atom_style}", ""]
    for c in labels:
        x, y = centroid_of(t.polygon(c))
        out.append(atom_line(ids[c], cell_type, x % lx, y % ly))
    for v, (x, y) in enumerate(t.vertices):
        out.append(atom_line(nc + 1 + v, vertex_type, x, y))
    out += ["", "vring", ""]
    for c in labels:
        ring = [nc + 1 + v for v in t.rings[c]] + [0] * (width - len(t.rings[c]))
        out.append(f"{ids[c]} " + " ".join(map(str, ring)))
    for v in range(nv):
        out.append(f"{nc + 1 + v} " + " ".join(["0"] * width))
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    return ids
