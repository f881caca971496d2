# SPDX-License-Identifier: GPL-2.0-or-later
"""Cell trajectories coloured by coordination or orientation (thesis Figs. 18-23).

Definitions (doc/model.md, Observables; velocities v_i, unit vectors u_i = v_i / |v_i|):
  coordination  C_i = mean over Voronoi neighbours j of u_i . u_j, in [-1, 1]
  orientation   O_i = arccos(u_i . x_hat), in [0, pi]
A cell at rest has no direction: its values are NaN (drawn grey) and it is left
out of its neighbours' means.
"""

import math
import sys

import numpy as np

from .dump import iter_dump
from .voronoi import periodic_voronoi

ORIENTATION_TICKS = ([0.0, math.pi / 4, math.pi / 2, 3 * math.pi / 4, math.pi],
                     ["0", "π/4", "π/2", "3π/4", "π"])


def unit_vectors(v):
    """Rows of v divided by their length; NaN rows where the length is zero."""
    v = np.asarray(v, dtype=float)
    norm = np.linalg.norm(v, axis=1)
    out = np.full_like(v, np.nan)
    moving = norm > 0
    out[moving] = v[moving] / norm[moving, None]
    return out


def orientation(v):
    """O_i = arccos(v_x / |v|) in [0, pi]; NaN for cells at rest."""
    u = unit_vectors(v)
    return np.arccos(np.clip(u[:, 0], -1.0, 1.0))


def velocity_angle(v):
    """Direction of motion atan2(v_y, v_x) in (-pi, pi]; NaN for cells at rest."""
    u = unit_vectors(v)
    return np.arctan2(u[:, 1], u[:, 0])


def coordination(neighbours, v):
    """C_i from neighbour lists (sequence of index arrays, e.g. Tessellation.neighbours)."""
    u = unit_vectors(v)
    n = len(u)
    counts = np.array([len(nb) for nb in neighbours])
    i = np.repeat(np.arange(n), counts)
    j = np.concatenate(neighbours).astype(int) if n else np.zeros(0, dtype=int)
    dots = np.einsum("ij,ij->i", u[i], u[j])
    valid = ~np.isnan(dots)
    total = np.bincount(i[valid], weights=dots[valid], minlength=n)
    used = np.bincount(i[valid], minlength=n)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = total / used
    out[used == 0] = np.nan
    out[np.isnan(u[:, 0])] = np.nan
    return out


class Trajectory:
    """Per-frame arrays of the cells (matched by atom ID) across a dump.

    The cells are the union of the IDs of all frames (``ids``, sorted): in a
    dividing or dying tissue a frame's IDs may change, and the arrays hold NaN
    where a cell is absent (``present`` (F, N) says where it is).
    timesteps (F,), ids (N,), positions (F, N, 2) unwrapped, wrapped (F, N, 2),
    velocities (F, N, 2), boxes (list of F Box), columns: dict name -> (F, N)
    for extra per-atom columns that were requested.
    """

    def __init__(self, timesteps, ids, positions, wrapped, velocities, boxes, columns, present=None):
        self.timesteps = timesteps
        self.ids = ids
        self.positions = positions
        self.wrapped = wrapped
        self.velocities = velocities
        self.boxes = boxes
        self.columns = columns
        self.present = present if present is not None else np.ones(positions.shape[:2], dtype=bool)

    def __len__(self):
        return len(self.timesteps)

    @property
    def changing(self):
        """True when some cell is absent from some frame (division, death, cells leaving)."""
        return not bool(self.present.all())

    def orientation(self):
        return np.array([orientation(v) for v in self.velocities])

    def velocity_angle(self):
        return np.array([velocity_angle(v) for v in self.velocities])

    def coordination(self):
        """C_i per frame, neighbours from the periodic Voronoi tessellation of each frame's cells."""
        out = np.full(self.positions.shape[:2], np.nan)
        for k in range(len(self)):
            here = np.nonzero(self.present[k])[0]
            tess = periodic_voronoi(self.wrapped[k][here], self.boxes[k], self.ids[here])
            out[k, here] = coordination(tess.neighbours, self.velocities[k][here])
        return out

    def msd(self):
        """Mean-square displacement from the first frame: (msd (F,), count (F,)), where the mean
        at frame k runs over the cells present both in the first frame and in frame k (a cell born
        later has no displacement from the first frame; a cell that died has none at frame k)."""
        both = self.present[0][None, :] & self.present
        d2 = np.sum((self.positions - self.positions[0][None]) ** 2, axis=2)
        count = both.sum(axis=1)
        with np.errstate(invalid="ignore", divide="ignore"):
            msd = np.where(both, d2, 0.0).sum(axis=1) / count
        msd[count == 0] = np.nan
        return msd, count


def frame_axes(ax, points, pad_fraction):
    """Equal-aspect axes around ``points`` (M, 2) with a margin of
    ``pad_fraction`` of the larger extent, labelled x and y."""
    lo_xy, hi_xy = points.min(axis=0), points.max(axis=0)
    pad = pad_fraction * (hi_xy - lo_xy).max()
    ax.set_xlim(lo_xy[0] - pad, hi_xy[0] + pad)
    ax.set_ylim(lo_xy[1] - pad, hi_xy[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel(LENGTH_LABEL.format("x"))
    ax.set_ylabel(LENGTH_LABEL.format("y"))


#: axis label of a position in the model's reduced length unit
LENGTH_LABEL = r"${}$ ($\sqrt{{A_0}}$)"


def attach_colorbar(ax, mappable, label=None, ticks=None):
    """A colour bar exactly as tall as the (equal-aspect) axes beside it."""
    from mpl_toolkits.axes_grid1 import make_axes_locatable

    cax = make_axes_locatable(ax).append_axes("right", size="4%", pad=0.12)
    cb = ax.figure.colorbar(mappable, cax=cax)
    if label:
        cb.set_label(label)
    if ticks:
        cb.set_ticks(ticks[0])
        cb.set_ticklabels(ticks[1])
    return cb


def _warn(message):
    print(f"tessera-tools: {message}", file=sys.stderr)


def load_trajectory(path, start=None, stop=None, every=None, velocity=("vx", "vy"), extra=(), quiet=False,
                    cell_types=None):
    """Read a multi-frame dump into a :class:`Trajectory`.

    Cells are matched by atom ID; frames may hold different IDs (dividing or
    dying tissues): the trajectory covers the union of the IDs, NaN where a
    cell is absent.  Unwrapped positions come from xu/yu or image flags;
    failing that they are rebuilt by continuity (minimum-image steps between
    frames; a cell that appears starts at the image of its centre nearest to
    the unwrapped position of its nearest neighbour, e.g. its mother).
    Velocities come from the ``velocity`` columns; failing that from finite
    differences of the unwrapped positions (only their direction matters here;
    NaN where a cell is not in the neighbouring frames; ``velocity`` None: no velocities).
    ``cell_types`` (a set from
    :func:`tessera_tools.dump.parse_types`): only the atoms of these types are followed, the
    others (particles that are no cells) are left out.
    """
    import itertools

    frames = list(itertools.islice(iter_dump(path, cell_types), start, stop, every))
    if not frames:
        raise ValueError(f"{path}: no frames selected")
    ids = np.unique(np.concatenate([np.asarray(f.ids) for f in frames]))
    F, N = len(frames), len(ids)
    present = np.zeros((F, N), dtype=bool)
    wrapped = np.full((F, N, 2), np.nan)
    unwrapped = np.full((F, N, 2), np.nan)
    vel = np.full((F, N, 2), np.nan)
    extras = {name: np.full((F, N), np.nan) for name in extra}
    have_unwrapped = all(f.has_unwrapped() for f in frames)
    have_velocity = velocity is not None and all(velocity[0] in f and velocity[1] in f for f in frames)
    timesteps = np.array([f.timestep for f in frames])
    boxes = [f.box for f in frames]
    for k, frame in enumerate(frames):
        fids = np.asarray(frame.ids)
        if len(np.unique(fids)) != len(fids):
            raise ValueError(f"{path}: timestep {frame.timestep} holds repeated atom IDs")
        col = np.searchsorted(ids, fids)
        present[k, col] = True
        wrapped[k, col] = frame.positions()
        if have_unwrapped:
            unwrapped[k, col] = frame.unwrapped()
        if have_velocity:
            vel[k, col] = frame.vector(*velocity)
        for name in extra:
            extras[name][k, col] = np.asarray(frame[name], dtype=float)
    if have_unwrapped:
        positions = unwrapped
    else:
        if not quiet:
            _warn("no xu/yu or image flags in the dump: unwrapping by continuity "
                  "(wrong if a cell moves more than half a box between frames)")
        positions = _unwrap_by_continuity(wrapped, present, boxes)
    if have_velocity:
        velocities = vel
    elif velocity is None:      # not wanted (displacements only)
        velocities = None
    else:
        if F < 2:
            raise ValueError(f"{path}: no {' '.join(velocity)} columns and a single frame: no velocities")
        if not quiet:
            _warn(f"no {' '.join(velocity)} columns: velocities from finite differences of positions")
        velocities = np.gradient(positions, timesteps.astype(float), axis=0)
    if not quiet and not present.all():
        born = int(np.sum(~present[0] & present.any(axis=0)))
        gone = int(np.sum(present[0] & ~present[-1]))
        _warn(f"{path}: the frames hold different atom IDs ({N} in all, {int(present[0].sum())} in the first "
              f"frame, {int(present[-1].sum())} in the last; {born} appear, {gone} of the first are gone): "
              "each cell is followed while it is present")
    traj = Trajectory(timesteps, ids, positions, wrapped, velocities, boxes, extras, present)
    #: the dump's TIME of each frame, or None when a frame lacks it
    traj.times = (np.array([f.time for f in frames], dtype=float) if all(f.time is not None for f in frames)
                  else None)
    traj.unwrapped_columns = have_unwrapped
    return traj


def _unwrap_by_continuity(wrapped, present, boxes):
    """Unwrapped positions from wrapped ones: each cell steps by the minimum image from its last
    known position; a cell seen for the first time takes the image nearest to the unwrapped
    position of its nearest cell already followed."""
    F, N, _ = wrapped.shape
    positions = np.full_like(wrapped, np.nan)
    last = np.full((N, 2), np.nan)          # last unwrapped position of each cell
    for k in range(F):
        here = present[k]
        known = here & ~np.isnan(last[:, 0])
        if known.any():
            positions[k, known] = last[known] + boxes[k].minimum_image(wrapped[k, known] - boxes[k].wrap(last[known]))
        new = np.nonzero(here & ~known)[0]
        if len(new):
            ref = np.nonzero(known)[0]
            for i in new:
                if len(ref) == 0:
                    positions[k, i] = wrapped[k, i]
                    continue
                d = boxes[k].minimum_image(wrapped[k, ref] - wrapped[k, i])
                j = ref[np.argmin(np.sum(d ** 2, axis=1))]
                positions[k, i] = positions[k, j] + boxes[k].minimum_image((wrapped[k, i] - wrapped[k, j])[None])[0]
        last[here] = positions[k, here]
    return positions


def trajectory_segments(positions, values, wrapped=None, box=None):
    """Segments (frame k -> k+1 for every cell) and the value at frame k for each.

    With ``wrapped`` given (positions folded into ``box``) segments that jump
    across the periodic boundary are dropped.
    """
    f, n, _ = positions.shape
    if f < 2:
        return np.zeros((0, 2, 2)), np.zeros(0)
    pts = wrapped if wrapped is not None else positions
    seg = np.stack([pts[:-1], pts[1:]], axis=2)  # (F-1, N, 2 ends, 2 coords)
    seg = seg.reshape(-1, 2, 2)
    vals = np.asarray(values[:-1], dtype=float).reshape(-1)
    # a cell absent at either end (born or dead in between) has no segment
    keep = np.all(np.isfinite(seg.reshape(-1, 4)), axis=1)
    if wrapped is not None:
        step_unwrapped = (positions[1:] - positions[:-1]).reshape(-1, 2)
        step_wrapped = (wrapped[1:] - wrapped[:-1]).reshape(-1, 2)
        # a boundary crossing changes the step by a whole box vector; dumps
        # print few digits, so compare against half the box, not round-off
        with np.errstate(invalid="ignore"):
            keep &= np.linalg.norm(step_unwrapped - step_wrapped, axis=1) < 0.5 * min(box.lx, box.ly)
    return seg[keep], vals[keep]


def draw_trajectories(ax, traj, values, kind, cmap=None, vmin=None, vmax=None, linewidth=None,
                      wrap=False, colorbar=True, box=True):
    """Draw every cell's path as a LineCollection coloured by ``values`` (F, N)."""
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection
    from matplotlib.patches import Polygon

    label, default_cmap, lo, hi = {
        "coordination": ("coordination $C_i$", "jet", -1.0, 1.0),
        "orientation": ("orientation $O_i$ (rad)", "jet", 0.0, math.pi),
    }.get(kind, (kind, "viridis", np.nanmin(values), np.nanmax(values)))
    cmap = plt.get_cmap(cmap or default_cmap).copy()
    cmap.set_bad("0.6")
    seg, vals = trajectory_segments(traj.positions, values, wrapped=traj.wrapped if wrap else None,
                                    box=traj.boxes[0])
    n = traj.positions.shape[1]
    if linewidth is None:
        linewidth = float(np.clip(12.0 / math.sqrt(max(n, 1)), 0.4, 1.5))
    lc = LineCollection(seg, cmap=cmap, linewidths=linewidth, capstyle="round")
    lc.set_array(np.ma.masked_invalid(vals))
    lc.set_clim(lo if vmin is None else vmin, hi if vmax is None else vmax)
    ax.add_collection(lc)
    if box:
        ax.add_patch(Polygon(traj.boxes[0].corners(), closed=True, fill=False,
                             edgecolor="0.3", linestyle="--", linewidth=0.8))
        if not np.allclose(traj.boxes[-1].corners(), traj.boxes[0].corners()):
            # a deforming box (growth, shear): the last frame's box dotted
            ax.add_patch(Polygon(traj.boxes[-1].corners(), closed=True, fill=False,
                                 edgecolor="0.3", linestyle=":", linewidth=0.8))
    pts = seg.reshape(-1, 2) if len(seg) else traj.positions.reshape(-1, 2)
    pts = pts[np.all(np.isfinite(pts), axis=1)]
    corners = traj.boxes[0].corners()
    frame_axes(ax, np.vstack([pts, corners]) if box else pts, 0.02)
    if colorbar:
        attach_colorbar(ax, lc, label, ORIENTATION_TICKS if kind == "orientation" else None)
    return lc


def plot_trajectories(traj, out, kinds=("coordination", "orientation"), values=None, cmap=None,
                      wrap=False, dpi=150, title=None, linewidth=None):
    """Figure with one panel per kind; ``values`` may map kind -> (F, N) precomputed values."""
    import matplotlib.pyplot as plt

    values = dict(values or {})
    for kind in kinds:
        if kind not in values:
            values[kind] = traj.coordination() if kind == "coordination" else traj.orientation()
    pts = (traj.wrapped if wrap else traj.positions).reshape(-1, 2)
    pts = np.vstack([pts[np.all(np.isfinite(pts), axis=1)], traj.boxes[0].corners()])
    span = pts.max(axis=0) - pts.min(axis=0)
    aspect = float(np.clip(span[1] / max(span[0], 1e-300), 0.15, 4.0))
    # wide, flat trajectory sets (streams along x) read better stacked
    stacked = len(kinds) > 1 and aspect < 0.6
    panel_w = 9.0 if stacked else 6.0
    panel_h = panel_w * aspect
    if stacked:
        fig, axes = plt.subplots(len(kinds), 1, figsize=(panel_w + 1.2, len(kinds) * (panel_h + 1.0) + 0.6),
                                 squeeze=False)
        axes = axes[:, 0]
    else:
        fig, axes = plt.subplots(1, len(kinds), figsize=(len(kinds) * (panel_w + 1.2), panel_h + 1.4),
                                 squeeze=False)
        axes = axes[0]
    for ax, kind in zip(axes, kinds):
        draw_trajectories(ax, traj, values[kind], kind, cmap=cmap, wrap=wrap, linewidth=linewidth)
        ax.set_title(kind)
    cells = (f"{len(traj.ids)} cells" if not traj.changing else
             f"{int(traj.present[0].sum())}-{int(traj.present[-1].sum())} cells ({len(traj.ids)} IDs)")
    span = f"timesteps {traj.timesteps[0]}-{traj.timesteps[-1]}, {len(traj)} frames, {cells}"
    fig.suptitle(title if title is not None else span)
    fig.tight_layout()
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return values


def plot_angle_histogram(traj, out, skip=0, bins=36, dpi=150, title=None):
    """Histogram of orientation O in [0, pi] and a rose plot of the direction of motion."""
    import matplotlib.pyplot as plt

    vel = traj.velocities[skip:]
    o = np.concatenate([orientation(v) for v in vel])
    a = np.concatenate([velocity_angle(v) for v in vel])
    o, a = o[~np.isnan(o)], a[~np.isnan(a)]
    fig = plt.figure(figsize=(10, 4.2))
    ax = fig.add_subplot(1, 2, 1)
    ax.hist(o, bins=bins, range=(0, math.pi), density=True, color="tab:blue", edgecolor="white")
    ax.set_xlim(0, math.pi)
    ax.set_xticks(ORIENTATION_TICKS[0])
    ax.set_xticklabels(ORIENTATION_TICKS[1])
    ax.set_xlabel(r"orientation $O = \arccos(\hat v \cdot \hat x)$")
    ax.set_ylabel("probability density")
    polar = fig.add_subplot(1, 2, 2, projection="polar")
    counts, edges = np.histogram(a, bins=2 * bins, range=(-math.pi, math.pi), density=True)
    polar.bar(edges[:-1], counts, width=np.diff(edges), align="edge", color="tab:orange", edgecolor="white")
    polar.set_yticklabels([])
    polar.set_title("direction of motion atan2($v_y$, $v_x$)", fontsize=10)
    first = traj.timesteps[min(skip, len(traj) - 1)]
    fig.suptitle(title if title is not None else
                 f"velocity angles, timesteps {first}-{traj.timesteps[-1]} ({len(o)} samples)")
    fig.tight_layout()
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return o
