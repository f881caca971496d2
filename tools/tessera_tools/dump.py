# SPDX-License-Identifier: GPL-2.0-or-later
"""Reader for LAMMPS ``dump custom`` text files (also ``dump atom`` and ``dump local``).

A file holds one or more frames.  Each frame becomes a :class:`Frame` with
numpy arrays keyed by column name exactly as written in the ``ITEM: ATOMS``
header (``id``, ``x``, ``mux``, ``c_v[1]`` ...), the timestep and a
:class:`Box`.  Rows are sorted by ``id`` when an ``id`` column exists, so the
same index means the same cell in every frame.

Only the x-y plane matters here (``dimension 2``); z columns are kept but
never used for geometry.  A ``dump local`` frame (``ITEM: ENTRIES``) is read
the same way, one row per entry in file order.
"""

import gzip
import itertools

import numpy as np

INTEGER_COLUMNS = {"id", "type", "mol", "proc", "procp1", "ix", "iy", "iz"}


class DumpFormatError(ValueError):
    """The file is not a LAMMPS text dump this reader understands."""


class Box:
    """Simulation box in the x-y plane, orthogonal or triclinic (tilt xy).

    Edge vectors a = (lx, 0) and b = (xy, ly); a point is
    lo + s0 * a + s1 * b with fractional coordinates s in [0, 1).
    """

    def __init__(self, xlo, xhi, ylo, yhi, xy=0.0, periodic=(True, True, True),
                 zlo=-0.5, zhi=0.5, xz=0.0, yz=0.0, triclinic=None):
        self.xlo, self.xhi = float(xlo), float(xhi)
        self.ylo, self.yhi = float(ylo), float(yhi)
        self.zlo, self.zhi = float(zlo), float(zhi)
        self.xy, self.xz, self.yz = float(xy), float(xz), float(yz)
        self.periodic = tuple(bool(p) for p in periodic)
        self.triclinic = bool(triclinic) if triclinic is not None else self.xy != 0.0
        if self.lx <= 0 or self.ly <= 0:
            raise ValueError(f"box has non-positive extent lx={self.lx} ly={self.ly}")

    @property
    def lx(self):
        return self.xhi - self.xlo

    @property
    def ly(self):
        return self.yhi - self.ylo

    @property
    def lo(self):
        return np.array([self.xlo, self.ylo])

    @property
    def matrix(self):
        """2x2 matrix whose columns are the edge vectors a and b."""
        return np.array([[self.lx, self.xy], [0.0, self.ly]])

    @property
    def area(self):
        return self.lx * self.ly

    def to_fractional(self, points):
        points = np.asarray(points, dtype=float)
        return np.linalg.solve(self.matrix, (points - self.lo).T).T

    def to_cartesian(self, fractional):
        fractional = np.asarray(fractional, dtype=float)
        return fractional @ self.matrix.T + self.lo

    def wrap(self, points):
        """Map points into the box along the periodic directions."""
        s = self.to_fractional(points)
        for k in range(2):
            if self.periodic[k]:
                s[:, k] -= np.floor(s[:, k])
                # floor can leave exactly 1.0 for tiny negative inputs
                s[s[:, k] >= 1.0, k] = 0.0
        return self.to_cartesian(s)

    def minimum_image(self, delta):
        """Shortest periodic representative of displacement vectors."""
        s = np.linalg.solve(self.matrix, np.asarray(delta, dtype=float).T).T
        for k in range(2):
            if self.periodic[k]:
                s[:, k] -= np.round(s[:, k])
        return s @ self.matrix.T

    def corners(self):
        """The four corners, counter-clockwise from lo."""
        a, b = self.matrix[:, 0], self.matrix[:, 1]
        lo = self.lo
        return np.array([lo, lo + a, lo + a + b, lo + b])

    def __repr__(self):
        tilt = f", xy={self.xy:g}" if self.triclinic else ""
        return (f"Box(x=[{self.xlo:g}, {self.xhi:g}], y=[{self.ylo:g}, {self.yhi:g}]{tilt}, "
                f"periodic={self.periodic[:2]})")


class Frame:
    """One snapshot: ``frame['x']``, ``frame.timestep``, ``frame.box``."""

    def __init__(self, timestep, box, columns, names=None, time=None, units=None):
        self.timestep = int(timestep)
        #: the LAMMPS units style (``dump_modify units yes`` writes it), else None
        self.units = units
        self.box = box
        self.columns = dict(columns)
        self.names = list(names) if names is not None else list(self.columns)
        self.time = time
        #: the atoms that are no cells (a Frame), when the frame was read with ``cell_types``
        self.particles = None

    @property
    def natoms(self):
        return len(next(iter(self.columns.values()))) if self.columns else 0

    def __len__(self):
        return self.natoms

    def __contains__(self, name):
        return name in self.columns

    def __getitem__(self, name):
        try:
            return self.columns[name]
        except KeyError:
            raise KeyError(f"column '{name}' is not in the dump (columns: {' '.join(self.names)})") from None

    @property
    def ids(self):
        if "id" in self.columns:
            return self.columns["id"]
        return np.arange(1, self.natoms + 1)

    def _cartesian(self, xname, yname, scaled):
        p = np.column_stack([self.columns[xname], self.columns[yname]]).astype(float)
        return self.box.to_cartesian(p) if scaled else p

    def positions(self):
        """Positions wrapped into the box, shape (N, 2)."""
        for xname, yname, scaled in (("x", "y", False), ("xs", "ys", True),
                                     ("xu", "yu", False), ("xsu", "ysu", True)):
            if xname in self.columns and yname in self.columns:
                return self.box.wrap(self._cartesian(xname, yname, scaled))
        raise KeyError("dump has no position columns (x y, xs ys, xu yu or xsu ysu)")

    def has_unwrapped(self):
        c = self.columns
        return (("xu" in c and "yu" in c) or ("xsu" in c and "ysu" in c)
                or ("ix" in c and "iy" in c and (("x" in c and "y" in c) or ("xs" in c and "ys" in c))))

    def unwrapped(self):
        """Unwrapped positions (xu yu, xsu ysu, or wrapped + image flags), shape (N, 2)."""
        c = self.columns
        if "xu" in c and "yu" in c:
            return self._cartesian("xu", "yu", False)
        if "xsu" in c and "ysu" in c:
            return self._cartesian("xsu", "ysu", True)
        if "ix" in c and "iy" in c:
            if "x" in c and "y" in c:
                p = self._cartesian("x", "y", False)
            elif "xs" in c and "ys" in c:
                p = self._cartesian("xs", "ys", True)
            else:
                p = None
            if p is not None:
                images = np.column_stack([c["ix"], c["iy"]]).astype(float)
                return p + images @ self.box.matrix.T
        raise KeyError("dump has no unwrapped positions: write xu yu, or x y with ix iy")

    def subset(self, mask):
        """A Frame of the rows where ``mask`` is true (same timestep, box and column names)."""
        mask = np.asarray(mask, dtype=bool)
        return Frame(self.timestep, self.box, {k: v[mask] for k, v in self.columns.items()},
                     self.names, self.time, self.units)

    def vector(self, xname, yname):
        return np.column_stack([self[xname], self[yname]]).astype(float)

    def __repr__(self):
        return f"Frame(timestep={self.timestep}, natoms={self.natoms}, {self.box!r}, columns={self.names})"


def _open(path):
    path = str(path)
    if path.endswith(".gz"):
        return gzip.open(path, "rt")
    return open(path, "r")


def _parse_box(header, lines, where):
    flags = header.split()[3:]
    tilt_names = [f for f in flags if f in ("xy", "xz", "yz")]
    if "abc" in flags or "origin" in flags:
        raise DumpFormatError(f"{where}: general triclinic boxes (BOX BOUNDS abc origin) are not supported")
    bounds = flags[len(tilt_names):]
    periodic = [True, True, True]
    if len(bounds) == 3:
        periodic = [b == "pp" for b in bounds]
    try:
        values = [[float(v) for v in line.split()] for line in lines]
    except ValueError:
        raise DumpFormatError(f"{where}: unreadable box bounds {lines!r}") from None
    need = 3 if tilt_names else 2
    if len(values) != 3 or any(len(v) < need for v in values):
        raise DumpFormatError(f"{where}: box bounds need 3 lines of {need} numbers, got {lines!r}")
    if tilt_names:
        (xlob, xhib, xy), (ylob, yhib, xz), (zlob, zhib, yz) = [v[:3] for v in values]
        # dump files hold the bounding box of the tilted cell; undo that
        xlo = xlob - min(0.0, xy, xz, xy + xz)
        xhi = xhib - max(0.0, xy, xz, xy + xz)
        ylo = ylob - min(0.0, yz)
        yhi = yhib - max(0.0, yz)
        return Box(xlo, xhi, ylo, yhi, xy=xy, xz=xz, yz=yz, zlo=zlob, zhi=zhib,
                   periodic=periodic, triclinic=True)
    (xlo, xhi), (ylo, yhi), (zlo, zhi) = [v[:2] for v in values]
    return Box(xlo, xhi, ylo, yhi, zlo=zlo, zhi=zhi, periodic=periodic, triclinic=False)


def _columns(names, rows, where):
    n, ncol = len(rows), len(names)
    tokens = "".join(rows).split()
    if len(tokens) != n * ncol:
        raise DumpFormatError(f"{where}: expected {n} rows of {ncol} columns, got {len(tokens)} values")
    try:
        table = np.array(tokens, dtype=float).reshape(n, ncol)
        raw = None
    except ValueError:
        table = None
        raw = np.array(tokens, dtype=object).reshape(n, ncol)
    out = {}
    for k, name in enumerate(names):
        if table is not None:
            col = table[:, k]
        else:
            try:
                col = raw[:, k].astype(float)
            except ValueError:
                col = raw[:, k].astype(str)
        if name in INTEGER_COLUMNS and col.dtype.kind == "f":
            col = col.astype(np.int64)
        out[name] = col
    return out


def parse_types(text):
    """Atom types from a LAMMPS-like list: '1,2', '1*3', '2*' (open upper end), '*2'."""
    if text is None:
        return None
    if not isinstance(text, str):
        return frozenset(int(t) for t in text)
    out = set()
    for part in text.replace(" ", "").split(","):
        if not part:
            continue
        try:
            if "*" in part:
                lo, hi = part.split("*", 1)
                lo = int(lo) if lo else 1
                if not hi:
                    out.add((lo, None))
                    continue
                out.update(range(lo, int(hi) + 1))
            else:
                out.add(int(part))
        except ValueError:
            raise ValueError(f"cell types '{text}': '{part}' is no type, a range I*J, I* or *J") from None
    if not out:
        raise ValueError(f"cell types '{text}': no type given (e.g. --cell-types 1 or 1,3 or 1*2)")
    return frozenset(out)


def cell_mask(types, cell_types):
    """True for the rows whose type is one of ``cell_types`` (from :func:`parse_types`; a
    string such as '1,3' or '2*', an int or a list of ints is read with it)."""
    if isinstance(cell_types, (int, np.integer)):
        cell_types = frozenset([int(cell_types)])
    elif not isinstance(cell_types, frozenset):
        cell_types = parse_types(cell_types)
    types = np.asarray(types).astype(np.int64)
    mask = np.zeros(len(types), dtype=bool)
    for t in cell_types:
        if isinstance(t, tuple):
            mask |= types >= t[0]
        else:
            mask |= types == t
    return mask


class CellTypesError(ValueError):
    """A dump of several atom types read without saying which types are cells."""


class OneType:
    """The ``cell_types`` of a reader that was told nothing: every atom is a cell (or, for the
    commands that follow atoms of any type, every atom is taken), and a frame holding atoms of
    several types is refused (:class:`CellTypesError`), naming the types found and ``option``,
    the command-line option that says which to take."""

    def __init__(self, option="--cell-types", what="cells"):
        self.option, self.what = option, what

    def __repr__(self):
        return f"OneType({self.option!r})"


#: every atom is a cell, and a dump of several types is refused (the tessera-tools commands)
SINGLE_TYPE = OneType()


def selects(cell_types):
    """True when ``cell_types`` picks some types (a set from :func:`parse_types`), False for
    None and :data:`SINGLE_TYPE` (every atom)."""
    return cell_types is not None and not isinstance(cell_types, OneType)


def types_text(types, sep=","):
    """'1,3' (as --cell-types takes them) or '2*' for types from :func:`parse_types`."""
    return sep.join(f"{t[0]}*" if isinstance(t, tuple) else str(t)
                    for t in sorted(types, key=lambda t: t[0] if isinstance(t, tuple) else t))


def check_one_type(frame, where, one=SINGLE_TYPE):
    """Raise :class:`CellTypesError` when ``frame`` holds atoms of several types: the message
    names them (with their counts) and the option ``one.option`` that picks the types."""
    if "type" not in frame or len(frame) == 0:
        return
    present, counts = np.unique(np.asarray(frame["type"]).astype(np.int64), return_counts=True)
    if len(present) < 2:
        return
    listed = ", ".join(f"type {t}: {c} atoms" for t, c in zip(present.tolist(), counts.tolist()))
    rest = types_text(present[1:].tolist())
    if one.what == "cells":
        raise CellTypesError(
            f"{where}: the dump holds atoms of several types ({listed}) and without {one.option} every "
            f"atom would be taken for a cell. Give {one.option} with the types that are cells (those with "
            f"'pair_coeff I I vertex/voronoi' parameters): e.g. {one.option} {present[0]} leaves the atoms "
            f"of type {rest} out as particles (no cells, never tessellated); {one.option} "
            f"{types_text(present.tolist())} takes them all for cells")
    raise CellTypesError(
        f"{where}: the dump holds atoms of several types ({listed}); say which to follow with "
        f"{one.option}, e.g. {one.option} {present[0]}, or {one.option} {types_text(present.tolist())} "
        "for all of them")


def split_cells(frame, cell_types, where="dump"):
    """The frame's cells (the atoms of ``cell_types``) as a Frame whose ``particles`` holds every
    other atom (a Frame, possibly empty).  ``cell_types`` None: every atom is a cell;
    a :class:`OneType` (e.g. :data:`SINGLE_TYPE`): every atom is a cell, and a frame of several
    types is an error (:class:`CellTypesError`)."""
    if cell_types is None:
        return frame
    if isinstance(cell_types, OneType):
        check_one_type(frame, where, cell_types)
        return frame
    if "type" not in frame:
        raise ValueError(f"{where}: --cell-types needs a 'type' column in the dump "
                         "(dump custom ... id type x y ...)")
    mask = cell_mask(frame["type"], cell_types)
    cells = frame.subset(mask)
    cells.particles = frame.subset(~mask)
    return cells


def iter_dump(path, cell_types=None):
    """Yield the frames of a dump file one by one (``.gz`` is read transparently).

    ``cell_types`` (a set from :func:`parse_types`): each frame holds only the atoms of those
    types (the cells) and its ``particles`` the other atoms, which are never tessellated.  None:
    every atom is a cell; :data:`SINGLE_TYPE`: the same, and a frame of several atom types is
    an error (:class:`CellTypesError`).  Dump local frames (``ITEM: ENTRIES``) are never split."""
    with _open(path) as f:
        lineno = 0

        def next_line():
            nonlocal lineno
            line = f.readline()
            lineno += 1
            return line

        line = next_line()
        while line:
            if not line.strip():
                line = next_line()
                continue
            timestep, natoms, box, time, units = None, None, None, None, None
            while True:
                if not line:
                    raise DumpFormatError(f"{path}:{lineno}: file ends inside a frame header")
                if not line.startswith("ITEM:"):
                    raise DumpFormatError(f"{path}:{lineno}: expected an ITEM: line, got {line.strip()[:60]!r}")
                item = line[5:].strip()
                where = f"{path}:{lineno}"
                if item.startswith("TIMESTEP"):
                    timestep = int(next_line().split()[0])
                elif item.startswith("NUMBER OF ATOMS") or item.startswith("NUMBER OF ENTRIES"):
                    natoms = int(next_line().split()[0])
                elif item.startswith("BOX BOUNDS"):
                    box = _parse_box(line.strip(), [next_line() for _ in range(3)], where)
                elif item.startswith("UNITS"):
                    units = next_line().split()[0]
                elif item.startswith("TIME"):
                    time = float(next_line().split()[0])
                elif item.startswith("ATOMS") or item.startswith("ENTRIES"):
                    # ENTRIES: a dump local (e.g. of compute vertex/local), rows kept in file order
                    local = item.startswith("ENTRIES")
                    names = item.split()[1:]
                    break
                else:
                    next_line()  # ITEM: UNITS and friends carry one value line
                line = next_line()
            if timestep is None or natoms is None or box is None:
                raise DumpFormatError(f"{path}:{lineno}: frame header lacks TIMESTEP, NUMBER OF ATOMS or BOX BOUNDS")
            if len(set(names)) != len(names):
                raise DumpFormatError(f"{path}:{lineno}: repeated column names in {names}")
            rows = list(itertools.islice(f, natoms))
            lineno += len(rows)
            if len(rows) != natoms:
                raise DumpFormatError(f"{path}: frame at timestep {timestep} has {len(rows)} of {natoms} rows")
            columns = _columns(names, rows, f"{path} timestep {timestep}")
            if "id" in columns and not local:
                order = np.argsort(columns["id"], kind="stable")
                columns = {k: v[order] for k, v in columns.items()}
            frame = Frame(timestep, box, columns, names, time, units)
            if cell_types is not None and not local:
                frame = split_cells(frame, cell_types, f"{path} timestep {timestep}")
            yield frame
            line = next_line()


def read_dump(path, start=None, stop=None, every=None, cell_types=None):
    """All frames of a dump (optionally a slice ``[start:stop:every]``) as a list."""
    frames = itertools.islice(iter_dump(path, cell_types), start, stop, every)
    out = list(frames)
    if not out:
        raise DumpFormatError(f"{path}: no frames")
    return out


def read_frame(path, index=-1, timestep=None, cell_types=None):
    """One frame: by position (``index``, negative counts from the end) or by ``timestep``."""
    if timestep is not None:
        for frame in iter_dump(path, cell_types):
            if frame.timestep == timestep:
                return frame
        raise KeyError(f"{path}: no frame at timestep {timestep}")
    if index >= 0:
        for k, frame in enumerate(iter_dump(path, cell_types)):
            if k == index:
                return frame
        raise IndexError(f"{path}: frame index {index} out of range")
    frames = read_dump(path, cell_types=cell_types)
    return frames[index]


def write_dump(path, frames, columns=None, include_z=True):
    """Write frames in ``dump custom`` format (used by the tests and for conversions).

    With ``include_z`` a frame with x y (or xs ys, xu yu) but no matching z column gets one of
    zeros after y: the tissue is 2d, but readers such as ASE require z."""
    with open(path, "w") as f:
        for frame in frames:
            names = list(columns or frame.names)
            extra = {}
            if include_z:
                for xname, yname, zname in (("x", "y", "z"), ("xs", "ys", "zs"), ("xu", "yu", "zu"),
                                            ("xsu", "ysu", "zsu")):
                    if xname in names and yname in names and zname not in names:
                        names.insert(names.index(yname) + 1, zname)
                        extra[zname] = np.zeros(frame.natoms)
            box = frame.box
            f.write(f"ITEM: TIMESTEP\n{frame.timestep}\n")
            f.write(f"ITEM: NUMBER OF ATOMS\n{frame.natoms}\n")
            flags = " ".join("pp" if p else "ff" for p in box.periodic)
            if box.triclinic:
                xy, xz, yz = box.xy, box.xz, box.yz
                xlob = box.xlo + min(0.0, xy, xz, xy + xz)
                xhib = box.xhi + max(0.0, xy, xz, xy + xz)
                ylob = box.ylo + min(0.0, yz)
                yhib = box.yhi + max(0.0, yz)
                f.write(f"ITEM: BOX BOUNDS xy xz yz {flags}\n")
                f.write(f"{xlob:.16g} {xhib:.16g} {xy:.16g}\n{ylob:.16g} {yhib:.16g} {xz:.16g}\n"
                        f"{box.zlo:.16g} {box.zhi:.16g} {yz:.16g}\n")
            else:
                f.write(f"ITEM: BOX BOUNDS {flags}\n")
                f.write(f"{box.xlo:.16g} {box.xhi:.16g}\n{box.ylo:.16g} {box.yhi:.16g}\n"
                        f"{box.zlo:.16g} {box.zhi:.16g}\n")
            f.write("ITEM: ATOMS " + " ".join(names) + "\n")
            cols = [extra[n] if n in extra else frame[n] for n in names]
            for row in zip(*cols):
                f.write(" ".join(_format_value(v) for v in row) + "\n")


def _format_value(v):
    if isinstance(v, (np.integer, int)):
        return str(int(v))
    if isinstance(v, (np.floating, float)):
        return f"{v:.16g}"
    return str(v)
