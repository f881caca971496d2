# SPDX-License-Identifier: GPL-2.0-or-later
"""Cell polygons from a ``dump local`` of ``compute vertex/local``.

Each row of such a dump is one junction of one cell: cell ID, neighbour ID,
the two end vertices (x1 y1 x2 y2, in the periodic image of the cell's own
coordinates) and the length.  :func:`junction_tessellation` turns the rows of
one frame, with the matching atom frame, into the same
:class:`~tessera_tools.voronoi.Tessellation` that the Python Voronoi builds,
so pictures and VTK files use the polygons LAMMPS computed (to the dump's
printed precision) instead of re-tessellating rounded positions.
"""

import re

import numpy as np

from .dump import iter_dump
from .voronoi import Tessellation

_COLUMN = re.compile(r"^c_(.+)\[(\d+)\]$")


def junction_columns(frame, compute=None):
    """Names of the 7 columns (cell, neighbour, x1, y1, x2, y2, length) of a local frame:
    ``c_ID[1]`` .. ``c_ID[7]`` of one compute (``compute`` names it when the dump has several),
    else the first 7 columns in order."""
    by_compute = {}
    for name in frame.names:
        m = _COLUMN.match(name)
        if m:
            by_compute.setdefault(m.group(1), {})[int(m.group(2))] = name
    candidates = {c: cols for c, cols in by_compute.items() if all(k in cols for k in range(1, 8))}
    if compute is not None:
        if compute not in candidates:
            raise KeyError(f"the local dump has no columns c_{compute}[1] .. c_{compute}[7] "
                           f"(columns: {' '.join(frame.names)})")
        return [candidates[compute][k] for k in range(1, 8)]
    if len(candidates) == 1:
        cols = next(iter(candidates.values()))
        return [cols[k] for k in range(1, 8)]
    if len(candidates) > 1:
        raise KeyError(f"the local dump has columns of several computes ({', '.join(sorted(candidates))}); "
                       "name the compute vertex/local one")
    if len(frame.names) >= 7:
        return list(frame.names[:7])
    raise KeyError(f"a local dump of compute vertex/local needs 7 columns (cell ID, neighbour ID, x1 y1 x2 y2, "
                   f"length), e.g. 'dump 2 all local N junctions.dump c_ID[*]'; this one has {' '.join(frame.names)}")


def junction_tessellation(atoms, local, compute=None):
    """A :class:`Tessellation` of the atom frame ``atoms`` from the rows of the local frame ``local``
    (same timestep).  Polygons are shifted with their cells into the box (by whole box vectors),
    counter-clockwise; ``sides`` and ``neighbours`` come from the rows (junctions of non-zero length)."""
    if atoms.timestep != local.timestep:
        raise ValueError(f"atom frame at timestep {atoms.timestep} paired with a local frame at {local.timestep}")
    names = junction_columns(local, compute)
    cell = np.asarray(local[names[0]]).astype(np.int64)
    other = np.asarray(local[names[1]]).astype(np.int64)
    start = np.column_stack([local[names[2]], local[names[3]]]).astype(float)
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
    owner, cell, other, start, length = owner[order], cell[order], other[order], start[order], length[order]
    bounds = np.searchsorted(owner, np.arange(len(ids) + 1))
    polygons, edge_cell, edge_other, edge_length = [], [], [], []
    for i in range(len(ids)):
        lo, hi = bounds[i], bounds[i + 1]
        verts = start[lo:hi]
        mid = verts.mean(axis=0)
        ccw = np.argsort(np.arctan2(verts[:, 1] - mid[1], verts[:, 0] - mid[0]), kind="stable")
        verts = verts[ccw]
        # into the image of the wrapped centre: a whole box vector, the one that brings the
        # polygon nearest to the centre
        d = centres[i] - mid
        shift = d - atoms.box.minimum_image(d[None, :])[0]
        polygons.append(verts + shift)
        edge_cell.append(np.full(hi - lo, i))
        edge_other.append(np.array([index.get(int(j), -1) for j in other[lo:hi][ccw]], dtype=int))
        edge_length.append(length[lo:hi][ccw])
    tess = Tessellation(atoms.box, centres, polygons,
                        np.concatenate(edge_cell) if edge_cell else np.zeros(0, dtype=int),
                        np.concatenate(edge_other) if edge_other else np.zeros(0, dtype=int),
                        np.concatenate(edge_length) if edge_length else np.zeros(0), 0.0)
    return tess


def paired_frames(atoms_path, local_path, frames=None):
    """(atom frame, local frame) pairs of the timesteps both dumps hold, in order;
    ``frames`` an optional slice over those pairs."""
    local = {}
    for f in iter_dump(local_path):
        local[f.timestep] = f
    pairs = [(a, local[a.timestep]) for a in iter_dump(atoms_path) if a.timestep in local]
    if not pairs:
        raise ValueError(f"{atoms_path} and {local_path} have no timestep in common")
    return pairs[frames] if frames is not None else pairs


def contact_lengths(atoms, local, compute=None, column="type"):
    """Total junction length between cells of each pair of values of ``column`` (default the
    cell type), from the rows of a compute vertex/local dump: {(a, b): length} with a <= b,
    each junction counted once (the dump lists it from both of its cells).  The fraction of
    heterotypic contacts is the sum over a != b divided by the sum over all pairs."""
    names = junction_columns(local, compute)
    cell = np.asarray(local[names[0]]).astype(np.int64)
    other = np.asarray(local[names[1]]).astype(np.int64)
    length = np.asarray(local[names[6]], dtype=float)
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
