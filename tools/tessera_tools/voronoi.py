# SPDX-License-Identifier: GPL-2.0-or-later
"""Periodic Voronoi tessellation of cell centres in a 2D (possibly tilted) box.

scipy's Voronoi runs on the centres plus the periodic images that lie within a
margin of the box; the margin grows until every original cell is provably
exact: each of its Voronoi vertices v (a circumcentre, radius R to the centre)
must have its whole empty circle inside the region covered by images, otherwise
a missing image could cut the cell.  Only the cells of the original centres are
kept; polygons are given around the wrapped centre, so cells on the boundary
stick out of the box.
"""

import math

import numpy as np
from scipy.spatial import QhullError, Voronoi, cKDTree

#: hexagon perimeter / sqrt(area): sqrt(8 sqrt 3)
HEXAGON_SHAPE_INDEX = math.sqrt(8.0 * math.sqrt(3.0))


class VoronoiError(ValueError):
    """Input the tessellation cannot handle (coincident or too few centres)."""


class Tessellation:
    """Voronoi cells of the N centres of one frame.

    Attributes (arrays of length N unless said otherwise):
      points      centres wrapped into the box, (N, 2)
      polygons    list of (m_i, 2) vertex arrays, counter-clockwise, around points[i]
      area, perimeter, shape_index (P / sqrt(A)), sides (edges of non-zero length)
      neighbours  list of sorted int arrays: other cells sharing an edge of non-zero length
      edge_cell, edge_other, edge_length   one entry per (cell, edge): the cell,
                  the index of the cell across the edge, the edge length
    """

    def __init__(self, box, points, polygons, edge_cell, edge_other, edge_length, length_tol):
        self.box = box
        self.points = points
        self.polygons = polygons
        n = len(points)
        self.area = np.array([polygon_area(p) for p in polygons])
        self.perimeter = np.array([_polygon_perimeter(p) for p in polygons])
        self.shape_index = self.perimeter / np.sqrt(self.area)
        self.edge_cell = edge_cell
        self.edge_other = edge_other
        self.edge_length = edge_length
        real = edge_length > length_tol
        self.sides = np.bincount(edge_cell[real], minlength=n)
        self.neighbours = _neighbour_lists(n, edge_cell[real], edge_other[real])

    def __len__(self):
        return len(self.points)

    def long_axis_angle(self):
        """Angle in [0, pi) of each cell's long axis (from the polygon's second moments of area)."""
        out = np.empty(len(self))
        for i, poly in enumerate(self.polygons):
            ixx, iyy, ixy = _central_moments(poly)
            out[i] = 0.5 * math.atan2(2.0 * ixy, ixx - iyy) % math.pi
        return out

    def elongation(self):
        """sqrt(lambda_max / lambda_min) of the second-moment tensor: 1 for regular polygons."""
        return np.array([polygon_elongation(poly) for poly in self.polygons])

    def neighbour_pairs(self):
        """(i, j) index arrays listing each neighbour relation of every cell once per direction."""
        i = np.repeat(np.arange(len(self)), [len(nb) for nb in self.neighbours])
        j = np.concatenate(self.neighbours) if len(self.neighbours) else np.zeros(0, dtype=int)
        return i, j.astype(int)


def polygon_area(p):
    """Signed area of a polygon (positive counter-clockwise)."""
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _polygon_perimeter(p):
    return float(np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1).sum())


def _central_moments(p):
    """Second moments of area about the centroid of a CCW polygon."""
    x, y = p[:, 0], p[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    a = 0.5 * cross.sum()
    cx = ((x + xn) * cross).sum() / (6.0 * a)
    cy = ((y + yn) * cross).sum() / (6.0 * a)
    ixx = ((x * x + x * xn + xn * xn) * cross).sum() / 12.0 - a * cx * cx
    iyy = ((y * y + y * yn + yn * yn) * cross).sum() / 12.0 - a * cy * cy
    ixy = ((x * yn + 2 * x * y + 2 * xn * yn + xn * y) * cross).sum() / 24.0 - a * cx * cy
    return ixx, iyy, ixy


def polygon_elongation(p):
    """sqrt(lambda_max / lambda_min) of a CCW polygon's second-moment tensor
    about its centroid (long over short axis): 1 for regular polygons."""
    ixx, iyy, ixy = _central_moments(p)
    half_tr, det = 0.5 * (ixx + iyy), ixx * iyy - ixy * ixy
    root = math.sqrt(max(half_tr * half_tr - det, 0.0))
    return math.sqrt((half_tr + root) / max(half_tr - root, 1e-300))


def _neighbour_lists(n, cell, other):
    keep = cell != other
    cell, other = cell[keep], other[keep]
    order = np.lexsort((other, cell))
    cell, other = cell[order], other[order]
    if len(cell):
        first = np.ones(len(cell), dtype=bool)
        first[1:] = (cell[1:] != cell[:-1]) | (other[1:] != other[:-1])
        cell, other = cell[first], other[first]
    bounds = np.searchsorted(cell, np.arange(n + 1))
    return [other[bounds[k]:bounds[k + 1]] for k in range(n)]


def _images(frac, margins):
    """Original fractional points first, then every periodic image within the margins."""
    n = len(frac)
    reach = [int(math.ceil(m)) for m in margins]
    pts, owner = [frac], [np.arange(n)]
    for i in range(-reach[0], reach[0] + 1):
        for j in range(-reach[1], reach[1] + 1):
            if i == 0 and j == 0:
                continue
            s = frac + np.array([i, j], dtype=float)
            inside = ((s[:, 0] >= -margins[0]) & (s[:, 0] <= 1 + margins[0])
                      & (s[:, 1] >= -margins[1]) & (s[:, 1] <= 1 + margins[1]))
            pts.append(s[inside])
            owner.append(np.nonzero(inside)[0])
    return np.concatenate(pts), np.concatenate(owner)


def periodic_voronoi(points, box, ids=None):
    """Tessellate centres ``points`` (N, 2) in the periodic ``box``.

    ``ids`` (atom IDs) only serve error messages.  Raises :class:`VoronoiError`
    for coincident centres, naming their IDs.
    """
    if not (box.periodic[0] and box.periodic[1]):
        raise VoronoiError("the Voronoi tools need a box periodic in x and y (boundary p p p)")
    points = np.asarray(points, dtype=float)
    n = len(points)
    if n < 1:
        raise VoronoiError("no cell centres")
    ids = np.arange(1, n + 1) if ids is None else np.asarray(ids)
    frac = box.to_fractional(points)
    frac -= np.floor(frac)
    frac[frac >= 1.0] = 0.0
    wrapped = box.to_cartesian(frac)
    matrix = box.matrix
    # gradient of each fractional coordinate: converts distances to fractional units
    grad = np.linalg.norm(np.linalg.inv(matrix), axis=1)
    spacing = math.sqrt(box.area / n)
    length_tol = 1e-9 * spacing
    distance = 3.0 * spacing
    checked_duplicates = False
    while True:
        margins = distance * grad
        sfrac, owner = _images(frac, margins)
        cart = box.to_cartesian(sfrac)
        if not checked_duplicates:
            _check_coincident(cart, owner, ids, length_tol)
            checked_duplicates = True
        if len(cart) >= 4:
            try:
                vor = Voronoi(cart)
            except QhullError as err:
                raise VoronoiError(f"Qhull failed on {n} centres: {str(err).splitlines()[0]}") from None
            polygons = _exact_cells(vor, n, box, margins, grad)
            if polygons is not None:
                break
        distance *= 2.0
        if distance > 64.0 * max(box.lx, box.ly, spacing):
            raise VoronoiError(f"could not tessellate {n} centres (collinear or degenerate input?)")
    edge_cell, edge_other, edge_length = _edges(vor, n, owner)
    for k in range(n):
        polygons[k] = _tidy_polygon(polygons[k], wrapped[k], length_tol)
    return Tessellation(box, wrapped, polygons, edge_cell, edge_other, edge_length, length_tol)


def _check_coincident(cart, owner, ids, tol):
    pairs = cKDTree(cart).query_pairs(r=max(tol, 1e-12))
    bad = sorted({tuple(sorted((int(ids[owner[p]]), int(ids[owner[q]])))) for p, q in pairs})
    if bad:
        listing = ", ".join(f"{a} and {b}" if a != b else f"{a} and its own periodic image"
                            for a, b in bad[:10])
        raise VoronoiError(f"coincident cell centres: atom IDs {listing}"
                           + (f" (and {len(bad) - 10} more pairs)" if len(bad) > 10 else ""))


def _exact_cells(vor, n, box, margins, grad):
    """Polygons of the first n points if all are provably exact, else None."""
    polygons = []
    inverse = np.linalg.inv(box.matrix)
    lo = box.lo
    for k in range(n):
        region = vor.regions[vor.point_region[k]]
        if not region or -1 in region:
            return None
        verts = vor.vertices[region]
        radius = np.linalg.norm(verts - vor.points[k], axis=1)
        s = (verts - lo) @ inverse.T
        reach = radius[:, None] * grad[None, :]
        if np.any(s - reach < -margins) or np.any(s + reach > 1.0 + margins):
            return None
        polygons.append(verts)
    return polygons


def _edges(vor, n, owner):
    rp = vor.ridge_points
    rv = np.array(vor.ridge_vertices, dtype=int)
    mine = (rp[:, 0] < n) | (rp[:, 1] < n)
    rp, rv = rp[mine], rv[mine]
    length = np.linalg.norm(vor.vertices[rv[:, 0]] - vor.vertices[rv[:, 1]], axis=1)
    cells, others, lengths = [], [], []
    for a, b in ((0, 1), (1, 0)):
        sel = rp[:, a] < n
        cells.append(rp[sel, a])
        others.append(owner[rp[sel, b]])
        lengths.append(length[sel])
    return np.concatenate(cells), np.concatenate(others), np.concatenate(lengths)


def _tidy_polygon(verts, centre, tol):
    """Counter-clockwise order around the centre, coincident vertices merged."""
    d = verts - centre
    verts = verts[np.argsort(np.arctan2(d[:, 1], d[:, 0]))]
    keep = np.linalg.norm(verts - np.roll(verts, 1, axis=0), axis=1) > tol
    if keep.sum() >= 3:
        verts = verts[keep]
    return verts


def tessellate_frame(frame):
    """Tessellation of a :class:`~tessera_tools.dump.Frame` from its wrapped positions."""
    return periodic_voronoi(frame.positions(), frame.box, frame.ids)
