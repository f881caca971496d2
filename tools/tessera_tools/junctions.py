# SPDX-License-Identifier: GPL-2.0-or-later
"""Cell polygons from a ``dump local`` of ``compute vertex/local``.

Each row of such a dump is one junction of one cell: cell ID, neighbour ID,
the two end vertices (x1 y1 x2 y2, in the periodic image of the cell's own
coordinates) and the length.  :func:`junction_tessellation` turns the rows of
one frame, with the matching atom frame, into the same
:class:`~tessera_tools.voronoi.Tessellation` that the Python Voronoi builds,
so pictures and VTK files use the polygons LAMMPS computed (to the dump's
printed precision) instead of re-tessellating rounded positions.

Finite cells (``pair_style vertex/voronoi ... radius r``) also have rows for
their free arcs, with neighbour ID 0: the arc is centred on the cell's
position and runs counter-clockwise from the row's start to its end; the
polygons sample it (:data:`ARC_STEP`), and the arcs are no junctions
(``sides``, ``neighbours``, :func:`contact_lengths` leave them out).  In 3d
the rows have 9 columns (cell, neighbour, one edge of a face polygon,
the face's area): :func:`face_areas` lists each face once.
"""

import math
import re

import numpy as np

from .dump import iter_dump
from .voronoi import Tessellation

_COLUMN = re.compile(r"^c_(.+)\[(\d+)\]$")

#: largest angle (radians) between consecutive samples of a free arc in a polygon: the
#: polygon's area is below the cell's by at most r^2 theta ARC_STEP^2 / 12 per arc of angle theta
ARC_STEP = 2.0 * np.pi / 256


def junction_columns(frame, compute=None):
    """Names of the columns of a local frame of compute vertex/local: 7 in 2d (cell,
    neighbour, x1, y1, x2, y2, length), 9 in 3d (cell, neighbour, x1 y1 z1, x2 y2 z2, face
    area): ``c_ID[1]`` .. of one compute (``compute`` names it when the dump has several),
    else the first columns in order (9 when the frame has 9 or more, else 7)."""
    by_compute = {}
    for name in frame.names:
        m = _COLUMN.match(name)
        if m:
            by_compute.setdefault(m.group(1), {})[int(m.group(2))] = name

    def width(cols):
        return 9 if all(k in cols for k in range(1, 10)) else 7

    candidates = {c: cols for c, cols in by_compute.items() if all(k in cols for k in range(1, 8))}
    if compute is not None:
        if compute not in candidates:
            raise KeyError(f"the local dump has no columns c_{compute}[1] .. c_{compute}[7] "
                           f"(columns: {' '.join(frame.names)})")
        cols = candidates[compute]
        return [cols[k] for k in range(1, width(cols) + 1)]
    if len(candidates) == 1:
        cols = next(iter(candidates.values()))
        return [cols[k] for k in range(1, width(cols) + 1)]
    if len(candidates) > 1:
        raise KeyError(f"the local dump has columns of several computes ({', '.join(sorted(candidates))}); "
                       "name the compute vertex/local one")
    if len(frame.names) >= 9:
        return list(frame.names[:9])
    if len(frame.names) >= 7:
        return list(frame.names[:7])
    raise KeyError(f"a local dump of compute vertex/local needs 7 columns (cell ID, neighbour ID, x1 y1 x2 y2, "
                   f"length; 9 in 3d), e.g. 'dump 2 all local N junctions.dump c_ID[*]'; this one has "
                   f"{' '.join(frame.names)}")


def _arc_points(centre, start, end, full):
    """Points strictly inside the counter-clockwise arc around ``centre`` from ``start`` to
    ``end`` (the whole circle when ``full``), at most ARC_STEP apart in angle."""
    r = float(np.hypot(*(start - centre)))
    a0 = math.atan2(start[1] - centre[1], start[0] - centre[0])
    a1 = math.atan2(end[1] - centre[1], end[0] - centre[0])
    theta = 2 * math.pi if full else (a1 - a0) % (2 * math.pi)
    n = max(1, int(math.ceil(theta / ARC_STEP)))
    t = a0 + theta * np.arange(1, n) / n
    return centre + r * np.column_stack([np.cos(t), np.sin(t)])


def junction_tessellation(atoms, local, compute=None):
    """A :class:`Tessellation` of the atom frame ``atoms`` from the rows of the local frame ``local``
    (same timestep, 2d).  Polygons are shifted with their cells into the box (by whole box
    vectors), counter-clockwise; free arcs (neighbour ID 0, finite cells) are sampled around the
    cell's position (:data:`ARC_STEP`), while ``area``, ``perimeter`` and ``shape_index`` of
    such cells are exact (corners' polygon plus the arcs' circular segments, the rows' lengths);
    ``sides`` and ``neighbours`` come from the junction rows (non-zero length, arcs left out)."""
    if atoms.timestep != local.timestep:
        raise ValueError(f"atom frame at timestep {atoms.timestep} paired with a local frame at {local.timestep}")
    names = junction_columns(local, compute)
    if len(names) == 9:
        raise ValueError("the local dump has the 9 columns of a 3d tissue (faces); polygons are for 2d "
                         "(tessera_tools.vtk.frame_cells3d reads 3d rows)")
    cell = np.asarray(local[names[0]]).astype(np.int64)
    other = np.asarray(local[names[1]]).astype(np.int64)
    start = np.column_stack([local[names[2]], local[names[3]]]).astype(float)
    end = np.column_stack([local[names[4]], local[names[5]]]).astype(float)
    length = np.asarray(local[names[6]], dtype=float)
    ids = np.asarray(atoms.ids).astype(np.int64)
    index = {int(i): k for k, i in enumerate(ids)}
    missing = sorted(set(cell.tolist()) - set(index))
    if missing:
        raise ValueError(f"timestep {atoms.timestep}: the local dump has junctions of cells {missing[:5]} "
                         "that are not in the atom dump")
    # every cell of the atom dump needs its polygon
    without = sorted(set(index) - set(cell.tolist()))
    if without:
        raise ValueError(f"timestep {atoms.timestep}: cells {without[:5]} of the atom dump have no junction rows "
                         "(was compute vertex/local defined on a smaller group?)")
    centres = atoms.positions()
    # a row order that survives 'dump_modify sort': by cell, then counter-clockwise by the
    # angle of the junction's first end around the cell's vertices (cells are convex)
    owner = np.array([index[int(c)] for c in cell], dtype=int)
    order = np.argsort(owner, kind="stable")
    owner, cell, other, start, end, length = (owner[order], cell[order], other[order], start[order],
                                              end[order], length[order])
    bounds = np.searchsorted(owner, np.arange(len(ids) + 1))
    polygons, edge_cell, edge_other, edge_length = [], [], [], []
    exact_area, exact_perimeter = np.zeros(len(ids)), np.zeros(len(ids))
    for i in range(len(ids)):
        lo, hi = bounds[i], bounds[i + 1]
        verts, ends = start[lo:hi], end[lo:hi]
        mid = verts.mean(axis=0)
        ccw = np.argsort(np.arctan2(verts[:, 1] - mid[1], verts[:, 0] - mid[0]), kind="stable")
        verts, ends, nb = verts[ccw], ends[ccw], other[lo:hi][ccw]
        # into the image of the wrapped centre: a whole box vector, the one that brings the
        # polygon nearest to the centre
        d = centres[i] - mid
        shift = d - atoms.box.minimum_image(d[None, :])[0]
        if np.any(nb == 0):
            # the cell's position in the image of its rows: the arcs' centre
            centre = centres[i] - shift
            pieces = []
            # exact area: the polygon of the corners plus each arc's circular segment
            x, y = verts[:, 0], verts[:, 1]
            area = 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
            for k in range(len(verts)):
                pieces.append(verts[k][None, :])
                if nb[k] == 0:
                    pieces.append(_arc_points(centre, verts[k], ends[k], full=len(verts) == 1))
                    r = float(np.hypot(*(verts[k] - centre)))
                    theta = length[lo:hi][ccw][k] / r
                    area += 0.5 * r * r * (theta - math.sin(theta))
            poly = np.vstack(pieces)
            exact_area[i] = area
            exact_perimeter[i] = float(length[lo:hi].sum())
        else:
            poly = verts
            exact_area[i] = np.nan
        polygons.append(poly + shift)
        junction = nb != 0
        edge_cell.append(np.full(int(junction.sum()), i))
        edge_other.append(np.array([index.get(int(j), -1) for j in nb[junction]], dtype=int))
        edge_length.append(length[lo:hi][ccw][junction])
    tess = Tessellation(atoms.box, centres, polygons,
                        np.concatenate(edge_cell) if edge_cell else np.zeros(0, dtype=int),
                        np.concatenate(edge_other) if edge_other else np.zeros(0, dtype=int),
                        np.concatenate(edge_length) if edge_length else np.zeros(0), 0.0)
    # cells with free arcs: the exact area and perimeter, not the sampled polygon's
    arcs = ~np.isnan(exact_area)
    if arcs.any():
        tess.area[arcs] = exact_area[arcs]
        tess.perimeter[arcs] = exact_perimeter[arcs]
        tess.shape_index = tess.perimeter / np.sqrt(tess.area)
    return tess


def face_cycles(starts, ends):
    """The face polygons of one cell towards one neighbour from their edges (rows of a 3d
    local dump: each edge's end is the next edge's start): a list of index arrays into the
    edges, one per polygon (two when the cell meets two images of the neighbour)."""
    starts = np.asarray(starts, dtype=float)
    ends = np.asarray(ends, dtype=float)
    n = len(starts)
    by_start = {}
    for k in range(n):
        by_start.setdefault(tuple(starts[k]), []).append(k)
    used = np.zeros(n, bool)
    cycles = []
    for first in range(n):
        if used[first]:
            continue
        cycle, k = [], first
        while not used[k]:
            used[k] = True
            cycle.append(k)
            nxt = [q for q in by_start.get(tuple(ends[k]), []) if not used[q] or q == first]
            if not nxt:
                # not printed identically: the nearest start
                free = np.nonzero(~used)[0].tolist() + [first]
                nxt = [free[int(np.argmin(np.linalg.norm(starts[free] - ends[k], axis=1)))]]
            k = nxt[0]
        cycles.append(np.array(cycle, dtype=int))
    return cycles


def face_areas(local, compute=None):
    """The faces of a 3d local frame of compute vertex/local, each once per cell: (cell IDs,
    neighbour IDs, areas), from the rows (one per edge of a face polygon, all with the face's
    area).  A cell with two faces towards one neighbour (periodic images) keeps both."""
    names = junction_columns(local, compute)
    if len(names) != 9:
        raise ValueError("face_areas needs the 9 columns of a 3d local dump")
    cell = np.asarray(local[names[0]]).astype(np.int64)
    other = np.asarray(local[names[1]]).astype(np.int64)
    start = np.column_stack([local[n] for n in names[2:5]]).astype(float)
    end = np.column_stack([local[n] for n in names[5:8]]).astype(float)
    area = np.asarray(local[names[8]], dtype=float)
    groups = {}
    for k, key in enumerate(zip(cell.tolist(), other.tolist())):
        groups.setdefault(key, []).append(k)
    out_c, out_j, out_a = [], [], []
    for (c, j), rows in groups.items():
        rows = np.array(rows)
        for cyc in face_cycles(start[rows], end[rows]):
            out_c.append(c)
            out_j.append(j)
            out_a.append(area[rows[cyc[0]]])
    return np.array(out_c, dtype=np.int64), np.array(out_j, dtype=np.int64), np.array(out_a, dtype=float)


def paired_frames(atoms_path, local_path, frames=None, cell_types=None):
    """(atom frame, local frame) pairs of the timesteps both dumps hold, in order;
    ``frames`` an optional slice over those pairs; ``cell_types``: the atom frames hold the
    cells only (their ``particles`` the other atoms), as the local dump does;
    :data:`tessera_tools.dump.SINGLE_TYPE`: every atom is a cell, which atoms of several types
    may be when every atom has rows in the local dump (its rows are the cells'); otherwise
    the atoms without rows are refused (:class:`tessera_tools.dump.CellTypesError`) with the
    types found and the option that leaves particles out."""
    from .dump import OneType

    local = {}
    for f in iter_dump(local_path):
        local[f.timestep] = f
    one = cell_types if isinstance(cell_types, OneType) else None
    pairs = [(a, local[a.timestep]) for a in iter_dump(atoms_path, None if one else cell_types)
             if a.timestep in local]
    if one is not None:
        for a, l in pairs:
            _check_rows_cover(a, l, f"{atoms_path} timestep {a.timestep}", one)
    if not pairs:
        raise ValueError(f"{atoms_path} and {local_path} have no timestep in common")
    return pairs[frames] if frames is not None else pairs


def _check_rows_cover(atoms, local, where, one):
    """Atoms of several types read without --cell-types are all cells when each has rows in
    the local dump; raise CellTypesError naming the types when some have none (particles,
    for which compute vertex/local writes no rows)."""
    from .dump import CellTypesError, types_text

    if "type" not in atoms or len(atoms) == 0:
        return
    types = np.asarray(atoms["type"]).astype(np.int64)
    if len(np.unique(types)) < 2:
        return
    try:
        first = junction_columns(local)[0]
    except KeyError:
        return
    rows = set(np.asarray(local[first]).astype(np.int64).tolist())
    without = np.array([int(i) not in rows for i in np.asarray(atoms.ids).astype(np.int64)])
    if not without.any():
        return
    present, counts = np.unique(types, return_counts=True)
    listed = ", ".join(f"type {t}: {c} atoms" for t, c in zip(present.tolist(), counts.tolist()))
    bare = np.unique(types[without]).tolist()
    cells = sorted(set(present.tolist()) - set(bare))
    raise CellTypesError(
        f"{where}: the dump holds atoms of several types ({listed}) and {int(without.sum())} atoms (of type "
        f"{types_text(bare)}) have no rows in the local dump, so they are no cells; without {one.option} every "
        f"atom would be taken for a cell. Give {one.option} with the cell types"
        + (f", e.g. {one.option} {types_text(cells)}" if cells else "")
        + ", to leave the others out as particles")


def contact_lengths(atoms, local, compute=None, column="type"):
    """Total junction length between cells of each pair of values of ``column`` (default the
    cell type), from the rows of a compute vertex/local dump: {(a, b): length} with a <= b,
    each junction counted once (the dump lists it from both of its cells).  The fraction of
    heterotypic contacts is the sum over a != b divided by the sum over all pairs.  Free arcs
    (neighbour ID 0) are no junctions; in 3d the faces' areas take the place of lengths."""
    names = junction_columns(local, compute)
    if len(names) == 9:
        cell, other, length = face_areas(local, compute)
    else:
        cell = np.asarray(local[names[0]]).astype(np.int64)
        other = np.asarray(local[names[1]]).astype(np.int64)
        length = np.asarray(local[names[6]], dtype=float)
    junction = other != 0
    cell, other, length = cell[junction], other[junction], length[junction]
    value = dict(zip(np.asarray(atoms.ids).astype(np.int64).tolist(), np.asarray(atoms[column]).tolist()))
    missing = sorted({int(j) for j in other if int(j) not in value})
    if missing:
        raise ValueError(f"timestep {atoms.timestep}: neighbours {missing[:5]} are not in the atom dump "
                         "(dump every cell, 'dump ... all custom')")
    out = {}
    for c, j, l in zip(cell.tolist(), other.tolist(), length.tolist()):
        a, b = sorted((value[c], value[j]))
        out[(a, b)] = out.get((a, b), 0.0) + 0.5 * l
    return out
