# SPDX-License-Identifier: GPL-2.0-or-later
"""Cells on a sphere (pair_style vertex/voronoi ... surface sphere) from the rows of
compute vertex/local: each row is one geodesic edge (cell, neighbour, start x y z, end
x y z, length), so every (cell, neighbour) pair has one row, where a 3d tissue's face
polygons have three or more.  Each cell is written as the polygon of its Voronoi
vertices (corners on the sphere, joined by straight chords in the file); its
``area`` is the spherical one, computed from the corners and the sphere, which is
fitted to all corners of the frame (they all lie on it)."""

import numpy as np

from .junctions import junction_columns


def is_sphere_local(local, compute=None):
    """True when a 9-column local frame holds edges of cells on a sphere (one row per
    cell and neighbour) rather than face polygons of 3d cells."""
    names = junction_columns(local, compute)
    if len(names) != 9 or len(local[names[0]]) == 0:
        return False
    pairs = np.column_stack([np.asarray(local[names[0]]), np.asarray(local[names[1]])]).astype(np.int64)
    return len(np.unique(pairs, axis=0)) == len(pairs)


def fit_sphere(points):
    """Centre and radius of the sphere through points (least squares of
    |p|^2 = 2 c.p + k, exact for points on a sphere)."""
    p = np.asarray(points, dtype=float)
    a = np.column_stack([2 * p, np.ones(len(p))])
    sol = np.linalg.lstsq(a, (p * p).sum(1), rcond=None)[0]
    c = sol[:3]
    return c, float(np.sqrt(sol[3] + c @ c))


def solid_angle(a, b, c):
    """Signed solid angle of the geodesic triangle of unit vectors a, b, c."""
    d = a @ np.cross(b, c)
    s = 1 + a @ b + b @ c + c @ a
    return 2 * np.arctan2(d, s)


def spherical_polygon_area(corners, centre, radius):
    """Area of the spherically convex polygon with these corners (in order) on the sphere."""
    u = np.asarray(corners, dtype=float) - centre
    u /= np.linalg.norm(u, axis=1)[:, None]
    return radius * radius * sum(solid_angle(u[0], u[k], u[k + 1]) for k in range(1, len(u) - 1))


class SphereCells:
    """Polygons on a sphere: ``ids``, ``polygons`` (list of (m, 3) arrays), ``area``,
    ``perimeter`` (sum of the rows' geodesic lengths), ``shape_index``, ``sides``,
    ``centre`` and ``radius``."""

    def __init__(self, ids, polygons, perimeter):
        self.ids = ids
        self.polygons = polygons
        allp = np.vstack(polygons) if polygons else np.zeros((0, 3))
        self.centre, self.radius = fit_sphere(allp) if len(allp) >= 4 else (np.zeros(3), 0.0)
        self.area = np.array([spherical_polygon_area(p, self.centre, self.radius) for p in polygons])
        self.perimeter = np.asarray(perimeter, dtype=float)
        self.shape_index = np.where(self.area > 0, self.perimeter / np.sqrt(np.maximum(self.area, 1e-300)), 0.0)
        self.sides = np.array([len(p) for p in polygons], dtype=np.int64)

    def __len__(self):
        return len(self.ids)


def frame_sphere_cells(atoms, local, compute=None):
    """:class:`SphereCells` of the atom frame ``atoms`` from the local frame ``local``."""
    if atoms.timestep != local.timestep:
        raise ValueError(f"atom frame at timestep {atoms.timestep} paired with a local frame at {local.timestep}")
    names = junction_columns(local, compute)
    cell = np.asarray(local[names[0]]).astype(np.int64)
    start = np.column_stack([local[n] for n in names[2:5]]).astype(float)
    length = np.asarray(local[names[8]], dtype=float)
    ids = np.asarray(atoms.ids).astype(np.int64)
    index = {int(i): k for k, i in enumerate(ids)}
    missing = sorted(set(cell.tolist()) - set(index))
    if missing:
        raise ValueError(f"timestep {atoms.timestep}: the local dump has edges of cells {missing[:5]} "
                         "that are not in the atom dump")
    rows_of = [[] for _ in ids]
    for k, c in enumerate(cell.tolist()):
        rows_of[index[c]].append(k)
    without = [int(ids[i]) for i, r in enumerate(rows_of) if not r]
    if without:
        raise ValueError(f"timestep {atoms.timestep}: cells {without[:5]} of the atom dump have no edge rows "
                         "(was compute vertex/local defined on a smaller group?)")
    # The rows of a cell are its edges in boundary order (counter-clockwise seen from outside).
    polygons = [start[np.array(r)] for r in rows_of]
    perimeter = [length[np.array(r)].sum() for r in rows_of]
    return SphereCells(ids, polygons, perimeter)


def frame_mesh_sphere(frame, cells, vectors, time=None):
    """A meshio.Mesh of one frame's polygons on the sphere with per-cell data."""
    from .vtk import cells_mesh, frame_columns, polygon_block

    n = len(cells)
    data = frame_columns(frame, n)
    data["area"] = cells.area
    data["perimeter"] = cells.perimeter
    data["shape_index"] = cells.shape_index
    data["sides"] = cells.sides
    for vec, comps in vectors.items():
        if all(c in frame for c in comps):
            data[vec] = np.column_stack([np.asarray(frame[c], dtype=float) for c in comps])
    points = np.vstack(cells.polygons) if n else np.zeros((0, 3))
    return cells_mesh(points, np.asarray(cells.sides, dtype=int), data, polygon_block, time)
