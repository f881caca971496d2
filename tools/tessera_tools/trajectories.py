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
    """Per-frame arrays for the same cells (matched by atom ID) across a dump.

    timesteps (F,), ids (N,), positions (F, N, 2) unwrapped, wrapped (F, N, 2),
    velocities (F, N, 2), boxes (list of F Box), columns: dict name -> (F, N)
    for extra per-atom columns that were requested.
    """

    def __init__(self, timesteps, ids, positions, wrapped, velocities, boxes, columns):
        self.timesteps = timesteps
        self.ids = ids
        self.positions = positions
        self.wrapped = wrapped
        self.velocities = velocities
        self.boxes = boxes
        self.columns = columns

    def __len__(self):
        return len(self.timesteps)

    def orientation(self):
        return np.array([orientation(v) for v in self.velocities])

    def velocity_angle(self):
        return np.array([velocity_angle(v) for v in self.velocities])

    def coordination(self):
        """C_i per frame, neighbours from the periodic Voronoi tessellation of each frame."""
        out = np.empty(self.positions.shape[:2])
        for k in range(len(self)):
            tess = periodic_voronoi(self.wrapped[k], self.boxes[k], self.ids)
            out[k] = coordination(tess.neighbours, self.velocities[k])
        return out


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


def load_trajectory(path, start=None, stop=None, every=None, velocity=("vx", "vy"), extra=(), quiet=False):
    """Read a multi-frame dump into a :class:`Trajectory`.

    Unwrapped positions come from xu/yu or image flags; failing that they are
    rebuilt by continuity (minimum-image steps between frames).  Velocities come
    from the ``velocity`` columns; failing that from finite differences of the
    unwrapped positions (only their direction matters here).
    """
    import itertools

    timesteps, ids, unwrapped, wrapped, vel, boxes = [], None, [], [], [], []
    extras = {name: [] for name in extra}
    have_unwrapped = have_velocity = True
    for frame in itertools.islice(iter_dump(path), start, stop, every):
        if ids is None:
            ids = frame.ids
        elif len(frame.ids) != len(ids) or np.any(frame.ids != ids):
            raise ValueError(f"{path}: timestep {frame.timestep} holds different atom IDs than the first frame")
        timesteps.append(frame.timestep)
        boxes.append(frame.box)
        pos = frame.positions()
        wrapped.append(pos)
        if have_unwrapped and frame.has_unwrapped():
            unwrapped.append(frame.unwrapped())
        else:
            have_unwrapped = False
        if have_velocity and velocity[0] in frame and velocity[1] in frame:
            vel.append(frame.vector(*velocity))
        else:
            have_velocity = False
        for name in extra:
            extras[name].append(np.asarray(frame[name], dtype=float))
    if not timesteps:
        raise ValueError(f"{path}: no frames selected")
    timesteps = np.array(timesteps)
    wrapped = np.array(wrapped)
    if have_unwrapped:
        positions = np.array(unwrapped)
    else:
        if not quiet:
            _warn("no xu/yu or image flags in the dump: unwrapping by continuity "
                  "(wrong if a cell moves more than half a box between frames)")
        positions = np.empty_like(wrapped)
        positions[0] = wrapped[0]
        for k in range(1, len(wrapped)):
            step = boxes[k].minimum_image(wrapped[k] - wrapped[k - 1])
            positions[k] = positions[k - 1] + step
    if have_velocity:
        velocities = np.array(vel)
    else:
        if len(timesteps) < 2:
            raise ValueError(f"{path}: no {' '.join(velocity)} columns and a single frame: no velocities")
        if not quiet:
            _warn(f"no {' '.join(velocity)} columns: velocities from finite differences of positions")
        velocities = np.gradient(positions, timesteps.astype(float), axis=0)
    columns = {name: np.array(values) for name, values in extras.items()}
    return Trajectory(timesteps, ids, positions, wrapped, velocities, boxes, columns)


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
    if wrapped is not None:
        step_unwrapped = (positions[1:] - positions[:-1]).reshape(-1, 2)
        step_wrapped = (wrapped[1:] - wrapped[:-1]).reshape(-1, 2)
        # a boundary crossing changes the step by a whole box vector; dumps
        # print few digits, so compare against half the box, not round-off
        keep = np.linalg.norm(step_unwrapped - step_wrapped, axis=1) < 0.5 * min(box.lx, box.ly)
        seg, vals = seg[keep], vals[keep]
    return seg, vals


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
    pts = seg.reshape(-1, 2) if len(seg) else traj.positions.reshape(-1, 2)
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
    pts = np.vstack([pts, traj.boxes[0].corners()])
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
    span = f"timesteps {traj.timesteps[0]}-{traj.timesteps[-1]}, {len(traj)} frames, {len(traj.ids)} cells"
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
