# SPDX-License-Identifier: GPL-2.0-or-later
"""Division events with their positions, from the event logs of fix cell/divide (keyword
``file``; read by :func:`tessera_tools.lineage.read_events`).

Each division line gives the step, the time and the mother's centre at the event (the
daughters sit on either side of it).  On a sphere of centre c (cells of ``pair_style
vertex/voronoi ... surface sphere cx cy cz R``) the position is also given as latitude
(asin of (z - cz) / |r - c|, from -90 to 90 degrees, +90 on the +z axis) and longitude
(atan2(y - cy, x - cx), from -180 to 180 degrees), the sphere's own radius not needed.
The centre is given, or read from a comment line of the log that names it (``sphere cx cy
cz``, see :func:`sphere_centre`).
"""

import re

import numpy as np

from .lineage import read_events

_NUMBER = r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
_SPHERE = re.compile(r"\bsphere\s+" + r"\s+".join([_NUMBER] * 3))


def sphere_centre(paths):
    """The centre (cx, cy, cz) named by a comment line of the logs ('# ... sphere cx cy cz ...'),
    or None when no header names one; several logs naming different centres are an error."""
    if isinstance(paths, str):
        paths = [paths]
    found = {}
    for path in paths:
        with open(path) as f:
            for line in f:
                if not line.startswith("#"):
                    if line.strip():
                        break
                    continue
                m = _SPHERE.search(line)
                if m:
                    found[path] = tuple(float(v) for v in m.groups())
    centres = set(found.values())
    if len(centres) > 1:
        raise ValueError("the logs name different sphere centres: "
                         + "; ".join(f"{p}: {c}" for p, c in found.items()))
    return centres.pop() if centres else None


def lat_lon(positions, centre):
    """Latitude and longitude in degrees of points (N, 3) about ``centre`` (polar axis +z)."""
    d = np.asarray(positions, dtype=float).reshape(-1, 3) - np.asarray(centre, dtype=float)
    r = np.linalg.norm(d, axis=1)
    if np.any(r == 0):
        raise ValueError("a division at the sphere's centre has no latitude: is the centre right?")
    lat = np.degrees(np.arcsin(np.clip(d[:, 2] / r, -1.0, 1.0)))
    lon = np.degrees(np.arctan2(d[:, 1], d[:, 0]))
    return lat, lon


def division_table(paths, centre=None):
    """The divisions of the logs as a dict of arrays: step, time, id, daughter1, daughter2, x,
    y, z, and latitude, longitude when a centre is given (or named by the logs' header:
    ``centre='header'``)."""
    if centre == "header":
        centre = sphere_centre(paths)
    events = [e for e in read_events(paths) if e.kind == "divide"]
    out = dict(step=np.array([e.step for e in events], dtype=np.int64),
               time=np.array([e.time for e in events], dtype=float),
               id=np.array([e.id for e in events], dtype=np.int64),
               daughter1=np.array([e.d1 for e in events], dtype=np.int64),
               daughter2=np.array([e.d2 for e in events], dtype=np.int64))
    pos = np.array([e.pos for e in events], dtype=float).reshape(-1, 3)
    out["x"], out["y"], out["z"] = pos[:, 0], pos[:, 1], pos[:, 2]
    out["centre"] = centre
    if centre is not None:
        out["latitude"], out["longitude"] = lat_lon(pos, centre) if len(pos) else (np.zeros(0), np.zeros(0))
    return out


def rate_histogram(times, bins=20, span=None):
    """Divisions per unit time in equal time bins: (edges, rate, error), error sqrt(n) / width
    (Poisson counting)."""
    times = np.asarray(times, dtype=float)
    lo, hi = span if span is not None else ((times.min(), times.max()) if len(times) else (0.0, 1.0))
    if hi <= lo:
        hi = lo + 1.0
    counts, edges = np.histogram(times, bins=bins, range=(lo, hi))
    width = np.diff(edges)
    return edges, counts / width, np.sqrt(counts) / width


