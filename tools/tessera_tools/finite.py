# SPDX-License-Identifier: GPL-2.0-or-later
"""Finite Voronoi cells: each cell is its Voronoi cell cut by the disc of
radius r around its centre (pair_style vertex/voronoi ... radius r).

Each cell starts as its disc and is cut by the bisector half-plane of every
centre closer than 2r (periodic images included along periodic directions).
The boundary is kept exactly, as straight contact edges and circular free
arcs, so areas, perimeters and free lengths are exact, and the drawn outline
follows the arcs (sampled finely) instead of their chords.
"""

import math

import numpy as np
from scipy.spatial import cKDTree

from .voronoi import Tessellation, VoronoiError, _neighbour_lists

TWO_PI = 2.0 * math.pi
TOUCH_TOL = 1e-9      # half-chords below this times r: not touching (as the pair style)


def _offset(angle, start):
    t = math.fmod(angle - start, TWO_PI)
    if t < 0:
        t += TWO_PI
    return 0.0 if t >= TWO_PI else t


def _clamp(t, lo, hi):
    if lo <= t <= hi:
        return t
    circ = lambda a, b: min(abs(a - b), TWO_PI - abs(a - b))
    return lo if circ(t, lo) <= circ(t, hi) else hi


def _clip(cell, j, D, r, tol):
    """Cut cell (list of [neighbour or -1, start (x, y) relative, phi, theta])
    by the half-plane of point j at relative position D.  Returns the new
    list, or None when round-off made the cut inconsistent."""
    d2 = D[0] * D[0] + D[1] * D[1]
    h2 = r * r - 0.25 * d2
    if not h2 > (TOUCH_TOL * r) ** 2:
        return cell
    d, h = math.sqrt(d2), math.sqrt(h2)
    half = 0.5 * d
    e = (D[0] / d, D[1] / d)
    tp = (-e[1], e[0])
    u1 = (half * e[0] - h * tp[0], half * e[1] - h * tp[1])
    u2 = (half * e[0] + h * tp[0], half * e[1] + h * tp[1])
    phi_e = math.atan2(e[1], e[0])
    alpha = math.atan2(h, half)
    phi1, phi2 = phi_e - alpha, phi_e + alpha
    if len(cell) == 1 and cell[0][0] < 0:
        return [[j, u1, 0.0, 0.0], [-1, u2, phi2, TWO_PI - 2 * alpha]]
    s_of = lambda u: u[0] * e[0] + u[1] * e[1] - half
    out, exits, entries = [], [], []
    n = len(cell)
    for k, (nb, a, phi, th) in enumerate(cell):
        b = cell[(k + 1) % n][1]
        sa, sb = s_of(a), s_of(b)
        ina, inb = sa <= tol, sb <= tol
        if nb >= 0:
            if ina and inb:
                out.append([nb, a, 0.0, 0.0])
            elif ina != inb:
                f = min(1.0, max(0.0, sa / (sa - sb)))
                q = (a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]))
                if ina:
                    out.append([nb, a, 0.0, 0.0])
                    exits.append((len(out) - 1, q))
                else:
                    out.append([nb, q, 0.0, 0.0])
                    entries.append(len(out) - 1)
            continue
        if ina and not inb:
            t1 = _clamp(_offset(phi1, phi), 0.0, th)
            out.append([-1, a, phi, t1])
            exits.append((len(out) - 1, u1))
        elif inb and not ina:
            t2 = _clamp(_offset(phi2, phi), 0.0, th)
            out.append([-1, u2, phi + t2, th - t2])
            entries.append(len(out) - 1)
        elif ina and inb:
            tc = _offset(phi_e, phi)
            if tc < th:
                t1 = _clamp(_offset(phi1, phi), 0.0, tc)
                t2 = _clamp(_offset(phi2, phi), tc, th)
                out.append([-1, a, phi, t1])
                exits.append((len(out) - 1, u1))
                out.append([-1, u2, phi + t2, th - t2])
                entries.append(len(out) - 1)
            else:
                out.append([-1, a, phi, th])
        else:
            ti = _offset(phi_e + math.pi, phi)
            if ti < th:
                t2 = _clamp(_offset(phi2, phi), 0.0, ti)
                t1 = _clamp(_offset(phi1, phi), ti, th)
                out.append([-1, u2, phi + t2, t1 - t2])
                entries.append(len(out) - 1)
                exits.append((len(out) - 1, u1))
    if not exits and not entries:
        return out if out else None
    m = len(out)
    if len(exits) != 1 or len(entries) != 1 or entries[0] != (exits[0][0] + 1) % m:
        return None
    out.insert(exits[0][0] + 1, [j, exits[0][1], 0.0, 0.0])
    merged = []
    for p in out:
        if merged and p[0] < 0 and merged[-1][0] < 0:
            merged[-1][3] += p[3]
        else:
            merged.append(p)
    if len(merged) > 1 and merged[0][0] < 0 and merged[-1][0] < 0:
        merged[-1][3] += merged[0][3]
        merged.pop(0)
    return merged


def finite_cell(centre, others, r):
    """Pieces [neighbour, start, phi, theta] of the finite cell at ``centre``
    cut by ``others``: a list of (index, (x, y)) of the centres within 2r."""
    cell = [[-1, (r, 0.0), 0.0, TWO_PI]]
    order = sorted(others, key=lambda o: (o[1][0] - centre[0]) ** 2 + (o[1][1] - centre[1]) ** 2)
    for j, p in order:
        D = (p[0] - centre[0], p[1] - centre[1])
        if D == (0.0, 0.0):
            raise VoronoiError("coincident cell centres")
        for tol in (1e-12 * r, 0.0, 1e-9 * r):
            new = _clip(cell, j, D, r, tol)
            if new is not None:
                cell = new
                break
        else:
            raise VoronoiError("a finite cell could not be cut consistently (degenerate input)")
    return cell


class FiniteTessellation:
    """Finite Voronoi cells of the N centres of one frame, with the
    attributes of :class:`~tessera_tools.voronoi.Tessellation` (polygons are
    outlines with the arcs sampled) plus ``radius``, ``free_length``,
    ``at_edge`` and ``arcs`` (per cell: list of (K, 2) arrays of its free
    arcs, for drawing the tissue's boundary)."""

    def __init__(self, box, points, radius, ids=None, arc_step=math.pi / 90):
        self.box = box
        self.points = points
        self.radius = r = float(radius)
        n = len(points)
        if not r > 0:
            raise VoronoiError(f"the radius of finite cells must be > 0, got {radius}")
        # Images along periodic directions within 2r of the box.
        allp, owner = [points], [np.arange(n)]
        if box.periodic[0] or box.periodic[1]:
            frac = box.to_fractional(points)
            grad = np.linalg.norm(np.linalg.inv(box.matrix), axis=1)
            margin = 2.0 * r * grad
            reach = [int(math.ceil(margin[k])) + 1 if box.periodic[k] else 0 for k in (0, 1)]
            for a in range(-reach[0], reach[0] + 1):
                for b in range(-reach[1], reach[1] + 1):
                    if a == 0 and b == 0:
                        continue
                    s = frac + np.array([a, b], dtype=float)
                    keep = np.all((s > -margin) & (s < 1 + margin), axis=1)
                    if keep.any():
                        allp.append(box.to_cartesian(s[keep]))
                        owner.append(np.nonzero(keep)[0])
        allp = np.vstack(allp)
        owner = np.concatenate(owner)
        tree = cKDTree(allp)
        # images and their cells, for chaining free arcs across the periodic boundary
        self.image_points, self.image_owner = allp, owner
        self.polygons, self.arcs = [], []
        #: every free arc as (cell, start angle, span, image index of the next contact's neighbour
        #: or -1 for a whole disc): counter-clockwise around its cell, so the arc ends where the
        #: contact edge with that neighbour begins (tessera_tools.holes chains them into loops)
        self.free_arcs = []
        area, per, free, cells, others, lengths = [], [], [], [], [], []
        for i in range(n):
            near = [(int(k), tuple(allp[k])) for k in tree.query_ball_point(points[i], 2 * r)
                    if k != i]
            for k, p in near:
                if p == tuple(points[i]):
                    who = f"atom IDs {ids[i]} and {ids[owner[k]]}" if ids is not None else "two centres"
                    raise VoronoiError(f"coincident cell centres: {who}")
            pieces = finite_cell(tuple(points[i]), near, r)
            A = P = L = 0.0
            outline, arcs = [], []
            m = len(pieces)
            for k, (nb, a, phi, th) in enumerate(pieces):
                b = pieces[(k + 1) % m][1]
                if nb >= 0:
                    length = math.hypot(b[0] - a[0], b[1] - a[1])
                    A += 0.5 * (a[0] * b[1] - a[1] * b[0])
                    outline.append(a)
                    cells.append(i)
                    others.append(int(owner[nb]))
                    lengths.append(length)
                else:
                    length = r * th
                    following = pieces[(k + 1) % m][0] if m > 1 else -1
                    self.free_arcs.append((i, phi, th, int(following)))
                    A += 0.5 * r * r * th
                    L += length
                    ang = phi + np.linspace(0.0, th, max(2, int(math.ceil(th / arc_step)) + 1))
                    arc = np.column_stack([r * np.cos(ang), r * np.sin(ang)])
                    outline.extend(map(tuple, arc[:-1]))
                    arcs.append(arc + points[i])
                P += length
            self.polygons.append(np.array(outline) + points[i])
            self.arcs.append(arcs)
            area.append(A)
            per.append(P)
            free.append(L)
        self.area = np.array(area)
        self.perimeter = np.array(per)
        self.free_length = np.array(free)
        self.at_edge = self.free_length > 0
        self.shape_index = self.perimeter / np.sqrt(self.area)
        self.edge_cell = np.array(cells, dtype=int)
        self.edge_other = np.array(others, dtype=int)
        self.edge_length = np.array(lengths)
        real = self.edge_length > 1e-9 * r
        self.sides = np.bincount(self.edge_cell[real], minlength=n)
        self.neighbours = _neighbour_lists(n, self.edge_cell[real], self.edge_other[real])

    def __len__(self):
        return len(self.points)

    # Shape measures from the outline, as for Voronoi polygons.
    long_axis_angle = Tessellation.long_axis_angle
    elongation = Tessellation.elongation
    neighbour_pairs = Tessellation.neighbour_pairs


def finite_voronoi(points, box, radius, ids=None):
    """Finite Voronoi cells of ``points`` (N, 2), images along the box's
    periodic directions only (an open box has none)."""
    points = np.asarray(points, dtype=float)
    if len(points) < 1:
        raise VoronoiError("no cell centres")
    if box.periodic[0] or box.periodic[1]:
        points = box.wrap(points)
    return FiniteTessellation(box, points, radius, ids)
