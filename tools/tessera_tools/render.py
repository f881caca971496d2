# SPDX-License-Identifier: GPL-2.0-or-later
"""Pictures of the Voronoi tessellation of a frame, cells coloured by a per-cell field.

Fields computed on the fly (see :func:`cell_field`): area, perimeter, shape
(index P/sqrt(A)), sides, polarity (angle of mu), orientation and coordination
(from velocities), speed, axis (long-axis angle), elongation; or any dump
column by its name (``c_v[1]``, ``type``, ...); or ``none``.

Two views: ``box`` tiles the periodic cells and clips them to the box (what
the periodic tissue looks like); ``cells`` draws each whole cell around its
wrapped centre, so boundary cells stick out of the drawn box.
"""

import math
import os

import numpy as np

from .trajectories import ORIENTATION_TICKS, attach_colorbar, coordination, frame_axes, orientation
from .finite import finite_voronoi
from .voronoi import tessellate_frame as _voronoi_frame


def tessellate_frame(frame, radius=None):
    """Voronoi cells of a frame, or finite Voronoi cells of radius ``radius``
    (pair_style vertex/voronoi ... radius r; open or periodic box)."""
    if radius:
        return finite_voronoi(frame.positions(), frame.box, radius, frame.ids)
    return _voronoi_frame(frame)

FIELDS = {
    # name: (label, colormap, vmin, vmax); None = from the data
    "area": ("cell area $A$ ($A_0$)", "viridis", None, None),
    "perimeter": (r"perimeter $P$ ($\sqrt{A_0}$)", "viridis", None, None),
    "shape": (r"shape index $q = P/\sqrt{A}$", "plasma", None, None),
    "sides": ("number of sides $z$", "coolwarm", 3, 9),
    "polarity": (r"polarity angle $\theta = $ atan2($\mu_y, \mu_x$)", "twilight", -math.pi, math.pi),
    "orientation": (r"orientation $O = \arccos(\hat v \cdot \hat x)$", "jet", 0.0, math.pi),
    "coordination": ("coordination $C$", "jet", -1.0, 1.0),
    "speed": ("speed $|v|$", "viridis", None, None),
    "axis": ("long-axis angle", "twilight", 0.0, math.pi),
    "elongation": ("elongation (aspect ratio)", "viridis", 1.0, None),
    "none": ("", None, None, None),
    "free": ("free arc length $L$", "viridis", None, None),
}
CATEGORICAL = {"type", "mol", "proc"}
ALIASES = {"q": "shape", "shape_index": "shape", "z": "sides", "A": "area", "P": "perimeter",
           "theta": "polarity", "angle": "polarity"}
ANGLE_FIELDS = {"polarity": ([-math.pi, -math.pi / 2, 0, math.pi / 2, math.pi], ["-π", "-π/2", "0", "π/2", "π"]),
                "orientation": ORIENTATION_TICKS,
                "axis": ([0, math.pi / 2, math.pi], ["0", "π/2", "π"])}


def _need(frame, names, field):
    missing = [n for n in names if n not in frame]
    if missing:
        raise KeyError(f"field '{field}' needs dump columns {' '.join(names)} "
                       f"(missing {' '.join(missing)}; the dump has {' '.join(frame.names)})")
    return frame.vector(*names)


def cell_field(frame, tess, field):
    """Values of ``field`` for every cell and its (label, cmap, vmin, vmax)."""
    name = ALIASES.get(field, field)
    if name in FIELDS:
        meta = FIELDS[name]
        if name == "area":
            values = tess.area
        elif name == "perimeter":
            values = tess.perimeter
        elif name == "shape":
            values = tess.shape_index
        elif name == "sides":
            values = tess.sides.astype(float)
        elif name == "polarity":
            mu = _need(frame, ("mux", "muy"), field)
            values = np.arctan2(mu[:, 1], mu[:, 0])
            values[np.linalg.norm(mu, axis=1) == 0] = np.nan
        elif name == "orientation":
            values = orientation(_need(frame, ("vx", "vy"), field))
        elif name == "coordination":
            values = coordination(tess.neighbours, _need(frame, ("vx", "vy"), field))
        elif name == "speed":
            values = np.linalg.norm(_need(frame, ("vx", "vy"), field), axis=1)
        elif name == "axis":
            values = tess.long_axis_angle()
        elif name == "elongation":
            values = tess.elongation()
        elif name == "free":
            if not hasattr(tess, "free_length"):
                raise KeyError("field 'free' needs finite cells (render --radius r)")
            values = tess.free_length
        else:
            values = None
        return values, meta
    if field in frame:
        values = np.asarray(frame[field])
        if values.dtype.kind not in "iuf":
            raise ValueError(f"column '{field}' is not numeric")
        return values.astype(float), (field, "viridis", None, None)
    raise KeyError(f"unknown field '{field}': use one of {', '.join(sorted(FIELDS))} "
                   f"or a dump column ({' '.join(frame.names)})")


def _tiles(tess, view):
    """Polygons to draw and, for each, the index of its cell."""
    if view == "cells":
        return list(tess.polygons), np.arange(len(tess))
    if view != "box":
        raise ValueError(f"view must be 'box' or 'cells', not '{view}'")
    box = tess.box
    if not (box.periodic[0] and box.periodic[1]):
        return list(tess.polygons), np.arange(len(tess))    # open box: nothing to tile
    matrix = box.matrix
    polys, owner = [], []
    for i, poly in enumerate(tess.polygons):
        s = box.to_fractional(poly)
        smin, smax = s.min(axis=0), s.max(axis=0)
        for a in (-1, 0, 1):
            if smin[0] + a >= 1 or smax[0] + a <= 0:
                continue
            for b in (-1, 0, 1):
                if smin[1] + b >= 1 or smax[1] + b <= 0:
                    continue
                polys.append(poly + matrix @ np.array([a, b], dtype=float))
                owner.append(i)
    return polys, np.array(owner, dtype=int)


def draw_tessellation(ax, frame, tess, field="area", view="box", cmap=None, vmin=None, vmax=None,
                      centres=False, arrows=None, highlight=(), edgecolor="k", linewidth=None,
                      colorbar=True, label=None, norm_from=None, categorical=None):
    """Draw one frame's cells on ``ax``; returns the PolyCollection.

    ``arrows``: None, or a pair of column names (e.g. ("mux", "muy")) drawn as unit arrows.
    ``norm_from``: values fixing the colour range (for series with a common scale).
    ``categorical``: colour by distinct values (one colour and one legend entry each, beside the
    picture) instead of a colour scale; default for ``type``, ``mol`` and ``proc``.
    """
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.patches import Polygon

    values, (default_label, default_cmap, lo, hi) = cell_field(frame, tess, field)
    if categorical is None:
        categorical = field in CATEGORICAL
    n = len(tess)
    if linewidth is None:
        linewidth = float(np.clip(8.0 / math.sqrt(n), 0.15, 1.0))
    polys, owner = _tiles(tess, view)
    coll = PolyCollection(polys, edgecolors=edgecolor, linewidths=linewidth)
    categories = None
    if values is None:
        coll.set_facecolor("#cfe3f2")
    elif categorical:
        ref = np.asarray(values if norm_from is None else norm_from, dtype=float)
        categories = np.unique(ref[np.isfinite(ref)])
        palette = plt.get_cmap(cmap or ("tab10" if len(categories) <= 10 else "tab20"))
        colours = {c: palette(k % palette.N) for k, c in enumerate(categories)}
        coll.set_facecolor([colours.get(v, (0.75, 0.75, 0.75, 1.0)) for v in values[owner]])
    else:
        cm = plt.get_cmap(cmap or default_cmap).copy()
        cm.set_bad("0.75")
        coll.set_cmap(cm)
        coll.set_array(np.ma.masked_invalid(values[owner]))
        ref = values if norm_from is None else norm_from
        finite = np.asarray(ref, dtype=float)
        finite = finite[np.isfinite(finite)]
        lo = vmin if vmin is not None else (lo if lo is not None else (finite.min() if len(finite) else 0.0))
        hi = vmax if vmax is not None else (hi if hi is not None else (finite.max() if len(finite) else 1.0))
        if hi - lo <= 1e-3 * max(abs(lo), abs(hi), 1e-300):
            # a field uniform to 0.1% (a relaxed lattice; dumps print 6 digits) gets a
            # +-5% scale, so it looks uniform instead of showing amplified round-off
            mid = 0.5 * (lo + hi)
            pad = 0.05 * abs(mid) if mid != 0 else 1.0
            lo, hi = mid - pad, mid + pad
        coll.set_clim(lo, hi)
    periodic = tess.box.periodic[0] and tess.box.periodic[1]
    boxpatch = Polygon(tess.box.corners(), closed=True, fill=False, edgecolor="0.2",
                       linewidth=1.0 if periodic else 0.0)
    ax.add_patch(boxpatch)
    ax.add_collection(coll)
    clip = view == "box" and periodic
    if clip:
        coll.set_clip_path(boxpatch)
    arcs = getattr(tess, "arcs", None)
    if arcs is not None:
        # The free boundary of finite cells: arcs drawn as arcs, in a heavier line.
        from matplotlib.collections import LineCollection
        segs = [a for i in owner for a in arcs[i]] if not clip else []
        if clip:
            shift = {}
            for poly, i in zip(polys, owner):
                d = poly[0] - tess.polygons[i][0]
                shift.setdefault(i, []).append(d)
            segs = [a + d for i, ds in shift.items() for d in ds for a in arcs[i]]
        free = LineCollection(segs, colors="#b2182b", linewidths=1.6 * linewidth + 0.4)
        ax.add_collection(free)
        if clip:
            free.set_clip_path(boxpatch)
    pts = tess.points
    if highlight:
        chosen = set(np.nonzero(np.isin(frame.ids, list(highlight)))[0].tolist())
        sel = [p for p, o in zip(polys, owner) if o in chosen]
        hcoll = PolyCollection(sel, facecolors="none", edgecolors="red", linewidths=2.0 * linewidth + 0.8)
        ax.add_collection(hcoll)
        if clip:
            hcoll.set_clip_path(boxpatch)
    if centres:
        ax.plot(pts[:, 0], pts[:, 1], ".", color="k", ms=max(1.0, 12.0 / math.sqrt(n)))
    particles = getattr(frame, "particles", None)
    if particles is not None and particles.natoms:
        # atoms that are no cells (obstacles, beads): black discs with a white rim, never tiles
        q = particles.positions()
        ax.plot(q[:, 0], q[:, 1], "o", mfc="k", mec="w", mew=0.6, ms=max(2.0, 40.0 / math.sqrt(n)), zorder=4)
    if arrows:
        vec = _need(frame, arrows, "arrows")
        unit = np.zeros_like(vec)
        length = np.linalg.norm(vec, axis=1)
        moving = length > 0
        unit[moving] = vec[moving] / length[moving, None]
        scale = 0.45 * math.sqrt(tess.box.area / n)
        ax.quiver(pts[:, 0], pts[:, 1], unit[:, 0] * scale, unit[:, 1] * scale, angles="xy",
                  scale_units="xy", scale=1.0, width=0.004, color="k", pivot="middle")
    frame_axes(ax, np.vstack([tess.box.corners()] +
                             ([np.vstack(polys)] if (view == "cells" or not periodic) else [])),
               0.01)
    if colorbar and categories is not None:
        from matplotlib.patches import Patch

        name = label or default_label
        handles = [Patch(facecolor=colours[c], edgecolor="k", linewidth=0.5,
                         label=f"{name} {int(c) if float(c).is_integer() else c:g}") for c in categories]
        # outside the axes, so it covers no cell
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0,
                  frameon=False)
    elif colorbar and values is not None:
        attach_colorbar(ax, coll, label or default_label, ANGLE_FIELDS.get(ALIASES.get(field, field)))
    return coll


def _figure(box, view):
    import matplotlib.pyplot as plt

    width = box.lx + abs(box.xy)
    aspect = box.ly / width
    # about 1.7 in of the width go to the colour bar and labels
    fig, ax = plt.subplots(figsize=(7.0, max(2.5, min(5.3 * aspect + 1.1, 12.0))))
    return fig, ax


def _title(frame, field, title):
    if title is not None:
        return title.format(timestep=frame.timestep, time=frame.time, field=field, n=frame.natoms)
    when = f"timestep {frame.timestep}" + (f", t = {frame.time:g}" if frame.time is not None else "")
    particles = getattr(frame, "particles", None)
    others = f", {particles.natoms} particles" if particles is not None else ""
    return f"{frame.natoms} cells{others}, {when}"


def render_frame(frame, out, field="area", view="box", dpi=300, title=None, tess=None, vector=None,
                 radius=None, **kwargs):
    """Write one PNG (or any format matplotlib knows from the extension) of ``frame``.

    ``tess``: the cells to draw (e.g. from :func:`tessera_tools.junctions.junction_tessellation`,
    LAMMPS's own polygons); by default the periodic Voronoi tessellation of the dumped centres,
    or with ``radius`` the finite Voronoi cells of that radius.
    ``vector``: also write a vector copy next to ``out`` with this extension ('pdf' or 'svg')."""
    import matplotlib.pyplot as plt

    if tess is None:
        tess = tessellate_frame(frame, radius)
    fig, ax = _figure(frame.box, view)
    draw_tessellation(ax, frame, tess, field=field, view=view, **kwargs)
    ax.set_title(_title(frame, field, title))
    fig.tight_layout()
    fig.savefig(out, dpi=dpi)
    if vector:
        fig.savefig(vector_path(out, vector))
    plt.close(fig)
    return tess


def vector_path(out, ext):
    """``out`` with its extension replaced by ``ext`` ('pdf' or 'svg')."""
    ext = ext.lower().lstrip(".")
    if ext not in ("pdf", "svg", "eps"):
        raise ValueError(f"vector format must be pdf, svg or eps, not '{ext}'")
    return os.path.splitext(out)[0] + "." + ext


def animation_writer(out, fps):
    """A matplotlib writer for ``.gif`` (Pillow) or ``.mp4`` (ffmpeg), or a RuntimeError saying what is missing."""
    from matplotlib import animation

    ext = out.rsplit(".", 1)[-1].lower()
    if ext == "gif":
        if animation.writers.is_available("pillow"):
            return animation.PillowWriter(fps=fps)
        if animation.writers.is_available("imagemagick"):
            return animation.ImageMagickWriter(fps=fps)
        raise RuntimeError("writing a GIF needs Pillow (Debian package python3-pil) or ImageMagick; "
                           "neither is installed. Write one PNG per frame instead, e.g. -o 'frame_{index:04d}.png'")
    if ext in ("mp4", "m4v", "mkv", "webm"):
        if animation.writers.is_available("ffmpeg"):
            return animation.FFMpegWriter(fps=fps)
        raise RuntimeError(f"writing .{ext} needs ffmpeg (Debian package ffmpeg), which is not installed. "
                           "Use a .gif output (needs python3-pil) or one PNG per frame, e.g. -o 'frame_{index:04d}.png'")
    raise RuntimeError(f"unknown animation format '.{ext}': use .gif or .mp4")


def render_series(frames, out, field="area", view="box", dpi=100, fps=5, title=None, common_scale=True,
                  tessellations=None, progress=None, radius=None, **kwargs):
    """An animation (.gif/.mp4) of several frames, or one file per frame when ``out``
    contains a ``{timestep}`` / ``{index}`` pattern.  ``tessellations``: the cells of each frame
    (default: Voronoi of the centres); ``progress``: a callable wrapping an iterable (e.g. tqdm)."""
    import matplotlib.pyplot as plt

    wrap = progress or (lambda it, **kw: it)
    if tessellations is None:
        tessellations = [tessellate_frame(f, radius) for f in wrap(frames, desc="tessellating")]
    norm_from = None
    if common_scale and ALIASES.get(field, field) != "none":
        norm_from = np.concatenate([cell_field(f, t, field)[0] for f, t in zip(frames, tessellations)])
    if "{" in out:
        written = []
        for k, (frame, tess) in enumerate(wrap(list(zip(frames, tessellations)), desc="drawing")):
            path = out.format(index=k, timestep=frame.timestep)
            fig, ax = _figure(frame.box, view)
            draw_tessellation(ax, frame, tess, field=field, view=view, norm_from=norm_from, **kwargs)
            ax.set_title(_title(frame, field, title))
            fig.tight_layout()
            fig.savefig(path, dpi=dpi)
            plt.close(fig)
            written.append(path)
        return written
    writer = animation_writer(out, fps)
    fig, ax = _figure(frames[0].box, view)
    # the colour bar is drawn once, from the first frame, on a fixed scale
    draw_tessellation(ax, frames[0], tessellations[0], field=field, view=view, norm_from=norm_from, **kwargs)
    ax.set_title(_title(frames[0], field, title))
    fig.tight_layout()
    kwargs_nobar = dict(kwargs, colorbar=False)
    last_box = None
    with writer.saving(fig, out, dpi):
        for frame, tess in wrap(list(zip(frames, tessellations)), desc="drawing"):
            ax.clear()
            draw_tessellation(ax, frame, tess, field=field, view=view, norm_from=norm_from, **kwargs_nobar)
            ax.set_title(_title(frame, field, title))
            # each frame as it is: a box that changes (growth, shear) changes the tick labels,
            # so the layout is redone for it (a fixed box keeps one layout: no jitter)
            box = (frame.box.xlo, frame.box.xhi, frame.box.ylo, frame.box.yhi, frame.box.xy)
            if last_box is not None and box != last_box:
                fig.tight_layout()
            last_box = box
            writer.grab_frame()
    plt.close(fig)
    return [out]
