# SPDX-License-Identifier: GPL-2.0-or-later
"""Holes of a tissue of finite cells and the hole around each particle.

The free boundary of finite cells (``pair_style vertex/voronoi ... radius r``) is made of
free arcs only.  :func:`free_loops` chains the arcs of a
:class:`~tessera_tools.finite.FiniteTessellation` into closed loops as compute
vertex/loops does in LAMMPS: each arc runs counter-clockwise around its cell and ends where
the contact edge with a neighbour begins; the next arc of the loop is the neighbour's arc
that starts at that corner.  The area a loop encloses is that of Green's theorem over its
arcs (exact: each arc contributes ``(c x (e - s) + r^2 theta) / 2``), positive for the
outer edge of a colony, negative for a hole; a loop that closes only after going around a
periodic direction encloses nothing (kind -1).

:func:`particle_holes` finds, for each particle (an atom that is no cell), the hole that
surrounds it: the smallest hole loop whose outline contains the particle (or one of its
periodic images), none when a cell's disc covers it.  The values are those of the loops of
the dumped centres; with the rows of a dump local of compute vertex/loops of the same step
(:func:`read_loops`) each hole is matched to the compute's row (nearest centroid, areas
agreeing) and the compute's index, area, length and cell count are taken.

:func:`particle_holes_indexed` needs no loops of its own: LAMMPS's compute vertex/loops/atom
dumped with the atoms (its column 1: the innermost loop that encloses each atom, numbered as
compute vertex/loops' rows) names each particle's loop, and the rows of the same step give
its values.  It is what the ``holes`` command uses when the dump has that column
(``--loop-column``); :func:`particle_holes` is the way for dumps without it.
"""

import math

import numpy as np

from .dump import iter_dump

LOOP_COLUMNS = ("index", "area", "length", "cells", "x", "y", "kind")


class Loop:
    """One closed loop of free boundary: ``area`` (> 0; 0 for a wrapping loop), ``signed``
    area, ``length``, ``cells`` (indices of the cells with an arc on it), ``kind`` (1 outer,
    0 hole, -1 wraps around the box), ``centroid`` (mapped into the box) and ``outline``
    (sampled points, unwrapped, in walking order)."""

    def __init__(self, signed, length, cells, kind, centroid, outline):
        self.signed, self.length, self.cells, self.kind = signed, length, cells, kind
        self.area = abs(signed) if kind >= 0 else 0.0
        self.centroid, self.outline = centroid, outline

    def contains(self, point, box):
        """True when ``point`` or one of its periodic images lies inside the outline."""
        from matplotlib.path import Path

        if self.kind < 0:
            return False
        path = Path(self.outline)
        lo, hi = self.outline.min(axis=0), self.outline.max(axis=0)
        for q in _images_within(point, box, lo, hi):
            if path.contains_point(q):
                return True
        return False


def _images_within(point, box, lo, hi):
    """The periodic images of ``point`` inside the rectangle [lo, hi]."""
    p = np.asarray(point, dtype=float)
    ranges = []
    for k in (0, 1):
        if box.periodic[k]:
            ranges.append(range(-2, 3))
        else:
            ranges.append(range(0, 1))
    a, b = box.matrix[:, 0], box.matrix[:, 1]
    out = []
    # enough images for loops up to about twice the box across; a hole larger than that wraps
    for m in ranges[0]:
        for n in ranges[1]:
            q = p + m * a + n * b
            if np.all(q >= lo) and np.all(q <= hi):
                out.append(q)
    return out


def free_loops(tess, arc_step=math.pi / 180):
    """The closed loops of free boundary of a FiniteTessellation, as a list of :class:`Loop`
    in the order of the lowest cell index with an arc on them."""
    r = tess.radius
    pts, allp, owner = tess.points, tess.image_points, tess.image_owner
    arcs = tess.free_arcs
    of_cell = {}
    for k, (i, _, _, _) in enumerate(arcs):
        of_cell.setdefault(i, []).append(k)

    def start_of(k, shift):
        i, phi, _, _ = arcs[k]
        return pts[i] + shift + r * np.array([math.cos(phi), math.sin(phi)])

    used = np.zeros(len(arcs), dtype=bool)
    loops = []
    for first in sorted(range(len(arcs)), key=lambda k: (arcs[k][0], k)):
        if used[first]:
            continue
        shift = np.zeros(2)
        k = first
        chain = []
        while True:
            used[k] = True
            chain.append((k, shift.copy()))
            i, phi, th, nb = arcs[k]
            if nb < 0:          # a whole disc: one arc, its own loop
                break
            end = pts[i] + shift + r * np.array([math.cos(phi + th), math.sin(phi + th)])
            j = int(owner[nb])
            # cell i was cut at pts[i] with its neighbour's image at allp[nb]: in the unwrapped
            # walk (cell i at pts[i] + shift) the neighbour sits at allp[nb] + shift
            shift = chain[-1][1] + (allp[nb] - pts[j])
            best, dist = None, math.inf
            for q in of_cell.get(j, ()):
                d = float(np.hypot(*(start_of(q, shift) - end)))
                if d < dist:
                    best, dist = q, d
            if best is None or dist > 1e-6 * r:
                raise ValueError(f"free arcs do not close into a loop at cell {j} (gap {dist:.3g}): a "
                                 "degenerate configuration")
            if best == first:
                break
            if used[best]:
                raise ValueError(f"free arcs of cell {j} are on two loops: a degenerate configuration")
            k = best
        closing = shift if arcs[chain[-1][0]][3] >= 0 else np.zeros(2)
        loops.append(_make_loop(tess, chain, closing, arc_step))
    return loops


def _make_loop(tess, chain, closing, arc_step):
    r = tess.radius
    pts = tess.points
    signed = length = 0.0
    outline = []
    cells = []
    for k, shift in chain:
        i, phi, th, _ = tess.free_arcs[k]
        c = pts[i] + shift
        s = c + r * np.array([math.cos(phi), math.sin(phi)])
        e = c + r * np.array([math.cos(phi + th), math.sin(phi + th)])
        signed += 0.5 * (c[0] * (e[1] - s[1]) - c[1] * (e[0] - s[0]) + r * r * th)
        length += r * th
        n = max(2, int(math.ceil(th / arc_step)) + 1)
        t = phi + np.linspace(0.0, th, n)[:-1]
        outline.append(c + r * np.column_stack([np.cos(t), np.sin(t)]))
        cells.append(i)
    outline = np.vstack(outline)
    wraps = bool(np.hypot(*closing) > 1e-9 * r)
    if wraps:
        kind, centroid = -1, outline.mean(axis=0)
    else:
        kind = 1 if signed > 0 else 0
        x, y = outline[:, 0], outline[:, 1]
        xn, yn = np.roll(x, -1), np.roll(y, -1)
        cross = x * yn - xn * y
        a = cross.sum() / 2.0
        centroid = np.array([((x + xn) * cross).sum(), ((y + yn) * cross).sum()]) / (6.0 * a)
    centroid = tess.box.wrap(centroid[None, :])[0] if any(tess.box.periodic[:2]) else centroid
    return Loop(signed, length, sorted(set(cells)), kind, centroid, outline)


def covered(point, tess):
    """True when ``point`` lies within the radius of a cell centre (or of an image of one):
    inside the union of the finite cells, so in no hole."""
    from scipy.spatial import cKDTree

    tree = cKDTree(tess.image_points)
    q = tess.box.wrap(np.asarray(point, dtype=float)[None, :])[0] if any(tess.box.periodic[:2]) else point
    d, _ = tree.query(q)
    return bool(d < tess.radius)


def read_loops(path):
    """{timestep: (M, 7) array} of a dump local of compute vertex/loops (columns: index,
    area, length, cells, x, y, kind; the seven c_ID[k] of one compute, else the first seven)."""
    import re

    out = {}
    for f in iter_dump(path):
        names = f.names
        by = {}
        for name in names:
            m = re.match(r"^c_(.+)\[(\d+)\]$", name)
            if m:
                by.setdefault(m.group(1), {})[int(m.group(2))] = name
        full = [cols for cols in by.values() if all(k in cols for k in range(1, 8))]
        if len(full) == 1:
            cols = [full[0][k] for k in range(1, 8)]
        elif len(names) >= 7 and not full:
            cols = names[:7]
        else:
            raise ValueError(f"{path}: expected the 7 columns of compute vertex/loops (c_ID[1] .. c_ID[7]: "
                             f"index, area, length, cells, x, y, kind), got {' '.join(names)}")
        out[f.timestep] = (np.column_stack([np.asarray(f[c], dtype=float) for c in cols])
                           if len(f) else np.zeros((0, 7)))
    if not out:
        raise ValueError(f"{path}: no frames")
    return out


def match_loop(loop, rows, box, r):
    """The row of compute vertex/loops (from :func:`read_loops`) that is ``loop``: a hole row
    whose centroid is the nearest (minimum image) and whose area agrees to 1e-3 relative (the
    dump's rounded positions); None if there is none."""
    holes = rows[rows[:, 6] == 0]
    if len(holes) == 0:
        return None
    d = box.minimum_image(holes[:, 4:6] - loop.centroid[None, :])
    dist = np.hypot(d[:, 0], d[:, 1])
    k = int(np.argmin(dist))
    scale = max(loop.area, 1e-6 * r * r)
    if dist[k] > 0.25 * r or abs(holes[k, 1] - loop.area) > 1e-3 * scale + 1e-9:
        return None
    return holes[k]


def loop_column(frame, name):
    """The dump column of compute vertex/loops/atom's loop index named ``name``: the column
    itself, or ``c_NAME[1]`` for a compute ID.  KeyError naming the columns if neither."""
    for col in (name, f"c_{name}[1]"):
        if col in frame:
            return col
    raise KeyError(f"the dump has no column '{name}' (nor c_{name}[1]) for the loop index of compute "
                   f"vertex/loops/atom (its columns: {' '.join(frame.names)})")


def covered_by_cells(points, cells, box, radius):
    """For each point (N, 2): whether a cell centre (minimum image) lies within ``radius``:
    the point is on the union of the finite cells, so in no hole."""
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    cells = np.asarray(cells, dtype=float).reshape(-1, 2)
    out = np.zeros(len(points), dtype=bool)
    if len(cells) == 0:
        return out
    for k, p in enumerate(points):
        d = box.minimum_image(cells - p[None, :])
        out[k] = bool(np.min(np.hypot(d[:, 0], d[:, 1])) < radius)
    return out


def particle_holes_indexed(frame, radius, column, loops_rows, particle_types=None):
    """As :func:`particle_holes`, with each particle's loop read from the dump column
    ``column`` of compute vertex/loops/atom (the innermost loop enclosing the atom, 0 for
    none) and its values from ``loops_rows`` (compute vertex/loops' rows of the same step, by
    index).  A particle whose loop is no hole (the outer loop of a colony whose cells cover
    it, or none) has index, area and length 0.  ``covered``: a cell centre lies within
    ``radius`` of it.  No loop is rebuilt from the centres."""
    from .dump import cell_mask

    particles = frame.particles
    if particles is None:
        raise ValueError("the frame holds no particles: read it with cell_types")
    if particle_types is not None and len(particles):
        particles = particles.subset(cell_mask(particles["type"], particle_types))
    col = loop_column(frame, column)
    rows = np.asarray(loops_rows, dtype=float).reshape(-1, 7)
    by_index = {int(r[0]): r for r in rows}
    ppos = particles.positions() if len(particles) else np.zeros((0, 2))
    cov = covered_by_cells(ppos, frame.positions(), frame.box, radius)
    out = []
    for k in range(len(particles)):
        pid = int(particles.ids[k])
        index = float(particles[col][k])
        if index != int(index) or index < 0:
            raise ValueError(f"column {col} of particle {pid} at timestep {frame.timestep} is {index:g}, not a "
                             "loop index: is it compute vertex/loops/atom's column 1?")
        row = dict(id=pid, type=int(particles["type"][k]) if "type" in particles else 0,
                   x=float(ppos[k][0]), y=float(ppos[k][1]), covered=bool(cov[k]), area=0.0, length=0.0,
                   cells=0, index=0, matched=False)
        if index:
            hit = by_index.get(int(index))
            if hit is None:
                raise ValueError(f"particle {pid} at timestep {frame.timestep} is in loop {int(index)}, which "
                                 f"has no row in the loops of that step ({len(rows)} rows): are the two dumps "
                                 "of the same run and steps?")
            if hit[6] == 0:
                row.update(area=float(hit[1]), length=float(hit[2]), cells=int(hit[3]), index=int(index),
                           matched=True)
        out.append(row)
    return out


def particle_holes(frame, radius, particle_types=None, loops_rows=None):
    """For each particle of ``frame`` (read with cell types: ``frame.particles``, optionally
    only those of ``particle_types``): a dict with id, type, x, y, covered, area, length, cells,
    index (the loop's: the compute's index with ``loops_rows``, else 1-based in this
    module's order), matched (whether a compute row was found).  A covered particle or one in
    no hole has area and length 0 and index 0."""
    from .dump import cell_mask
    from .finite import finite_voronoi

    particles = frame.particles
    if particles is None:
        raise ValueError("the frame holds no particles: read it with cell_types")
    if particle_types is not None and len(particles):
        particles = particles.subset(cell_mask(particles["type"], particle_types))
    tess = finite_voronoi(frame.positions(), frame.box, radius, frame.ids)
    loops = free_loops(tess)
    holes = [(n, lp) for n, lp in enumerate(loops, start=1) if lp.kind == 0]
    out = []
    ppos = particles.positions() if len(particles) else np.zeros((0, 2))
    for k in range(len(particles)):
        p = ppos[k]
        row = dict(id=int(particles.ids[k]), type=int(particles["type"][k]) if "type" in particles else 0,
                   x=float(p[0]), y=float(p[1]), covered=covered(p, tess), area=0.0, length=0.0, cells=0,
                   index=0, matched=False)
        if not row["covered"]:
            inside = [(lp.area, n, lp) for n, lp in holes if lp.contains(p, frame.box)]
            if inside:
                _, n, lp = min(inside, key=lambda t: t[0])
                row.update(area=lp.area, length=lp.length, cells=len(lp.cells), index=n)
                if loops_rows is not None:
                    hit = match_loop(lp, loops_rows, frame.box, radius)
                    if hit is not None:
                        row.update(area=float(hit[1]), length=float(hit[2]), cells=int(hit[3]),
                                   index=int(hit[0]), matched=True)
        out.append(row)
    return out
