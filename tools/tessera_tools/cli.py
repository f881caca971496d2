# SPDX-License-Identifier: GPL-2.0-or-later
"""Command line: ``tessera-tools {info,render,traj,log} ...`` (each has --help)."""

import argparse
import itertools
import math
import sys

import numpy as np


def _matplotlib():
    import matplotlib

    matplotlib.use("Agg")


def _slice(text):
    """'start:stop:step' (Python slice syntax, any part may be empty) or 'all'."""
    if text in ("all", ":"):
        return slice(None)
    parts = text.split(":")
    if len(parts) == 1:
        k = int(parts[0])
        return slice(k, k + 1 if k != -1 else None)
    if len(parts) > 3:
        raise argparse.ArgumentTypeError(f"bad frame slice '{text}'")
    try:
        return slice(*[int(p) if p.strip() else None for p in parts])
    except ValueError:
        raise argparse.ArgumentTypeError(f"bad frame slice '{text}'") from None


def _select_frames(path, sl):
    from .dump import iter_dump, read_dump

    if all(v is None or v >= 0 for v in (sl.start, sl.stop)) and (sl.step is None or sl.step > 0):
        frames = list(itertools.islice(iter_dump(path), sl.start, sl.stop, sl.step))
    else:
        frames = read_dump(path)[sl]
    if not frames:
        raise SystemExit(f"tessera-tools: no frames of {path} selected by the slice")
    return frames


def cmd_info(args):
    from .dump import iter_dump

    count, first, last = 0, None, None
    for frame in iter_dump(args.dump):
        if first is None:
            first = frame
        last = frame
        count += 1
    if first is None:
        raise SystemExit(f"tessera-tools: {args.dump} has no frames")
    print(f"{args.dump}: {count} frame(s), timesteps {first.timestep} .. {last.timestep}")
    print(f"atoms: {first.natoms} (last frame {last.natoms})")
    print(f"box (first frame): {first.box!r}, area {first.box.area:g}")
    print(f"columns: {' '.join(first.names)}")
    print(f"unwrapped positions: {'yes' if first.has_unwrapped() else 'no'}")
    if args.stats:
        from .voronoi import tessellate_frame

        tess = tessellate_frame(last)
        print(f"last frame: mean area {tess.area.mean():.6g} (box area / N = {last.box.area / last.natoms:.6g}), "
              f"mean shape index {tess.shape_index.mean():.6g}, sides {np.bincount(tess.sides).tolist()}")


def cmd_render(args):
    _matplotlib()
    from .dump import read_frame
    from .render import render_frame, render_series

    opts = dict(cmap=args.cmap, vmin=args.vmin, vmax=args.vmax, centres=args.centres,
                arrows=tuple(args.arrows) if args.arrows else None, highlight=args.highlight or (),
                colorbar=not args.no_colorbar, label=args.label, radius=args.radius)
    if args.frames is not None:
        frames = _select_frames(args.dump, args.frames)
        series = args.output.lower().endswith((".gif", ".mp4", ".m4v", ".mkv", ".webm")) or "{" in args.output
        if series:
            try:
                written = render_series(frames, args.output, field=args.field, view=args.view,
                                        dpi=args.dpi or 100, fps=args.fps, title=args.title, **opts)
            except RuntimeError as err:
                raise SystemExit(f"tessera-tools render: {err}") from None
            print(f"wrote {len(written)} file(s)" + (f": {written[0]}" if len(written) == 1 else
                                                     f", {written[0]} .. {written[-1]}"))
            return
        if len(frames) > 1:
            raise SystemExit("tessera-tools render: several frames selected but the output is a single "
                             "picture; use a .gif/.mp4 output or a pattern like 'frame_{index:04d}.png'")
        frame = frames[0]
    else:
        frame = read_frame(args.dump, index=args.frame, timestep=args.timestep)
    tess = render_frame(frame, args.output, field=args.field, view=args.view, dpi=args.dpi or 150,
                        title=args.title, **opts)
    print(f"wrote {args.output}: timestep {frame.timestep}, {len(tess)} cells, "
          f"mean area {tess.area.mean():.6g}, mean shape index {tess.shape_index.mean():.6g}")


def cmd_traj(args):
    _matplotlib()
    from .trajectories import load_trajectory, plot_angle_histogram, plot_trajectories

    sl = args.frames or slice(None)
    if any(v is not None and v < 0 for v in (sl.start, sl.stop, sl.step)):
        raise SystemExit("tessera-tools traj: --frames takes non-negative start:stop:step")
    extra = [c for c in (args.coordination_column, args.orientation_column) if c]
    traj = load_trajectory(args.dump, sl.start, sl.stop, sl.step, velocity=tuple(args.velocity), extra=extra)
    if len(traj) < 2:
        raise SystemExit("tessera-tools traj: need at least two frames for trajectories")
    kinds = ("coordination", "orientation") if args.kind == "both" else (args.kind,)
    values = {}
    if args.coordination_column:
        values["coordination"] = traj.columns[args.coordination_column]
    if args.orientation_column:
        # compute vertex/atom writes -1 for a cell at rest (outside [0, pi])
        col = traj.columns[args.orientation_column]
        values["orientation"] = np.where(col < 0, np.nan, col)
    if args.output:
        values = plot_trajectories(traj, args.output, kinds=kinds, values=values, cmap=args.cmap,
                                   wrap=args.wrap, dpi=args.dpi, title=args.title, linewidth=args.linewidth)
        summary = ", ".join(f"mean {k} {np.nanmean(values[k]):.4g}" for k in kinds)
        print(f"wrote {args.output}: {len(traj)} frames, {len(traj.ids)} cells, {summary}")
    if args.hist:
        o = plot_angle_histogram(traj, args.hist, skip=args.hist_skip, bins=args.bins, dpi=args.dpi)
        near = np.mean((o < math.pi / 4) | (o > 3 * math.pi / 4)) if len(o) else float("nan")
        print(f"wrote {args.hist}: {len(o)} velocity samples, fraction within pi/4 of the x axis {near:.3f}")
    if not args.output and not args.hist:
        raise SystemExit("tessera-tools traj: nothing to do, give -o and/or --hist")


def cmd_log(args):
    _matplotlib()
    from .logplot import parse_log, plot_logs, write_csv

    logs = [parse_log(p) for p in args.logs]
    if args.list:
        for log in logs:
            print(f"{log.path}: {len(log.runs)} run(s), rows per run {[len(r) for r in log.runs]}, "
                  f"timestep {[r.dt for r in log.runs]}")
            print("  columns: " + " ".join(log.names))
        return
    if args.csv:
        if len(logs) != 1:
            raise SystemExit("tessera-tools log: --csv takes a single log file")
        write_csv(logs[0], args.csv)
        print(f"wrote {args.csv}")
    if not args.output:
        if not args.csv:
            raise SystemExit("tessera-tools log: nothing to do, give -o, --csv or --list")
        return
    columns = None
    if args.columns:
        columns = []
        for spec in args.columns:
            name, _, label = spec.partition(":")
            columns.append((name, label or None))
    refs = {}
    for spec in args.ref or []:
        name, sep, value = spec.partition("=")
        if not sep:
            raise SystemExit(f"tessera-tools log: --ref takes NAME=VALUE, not '{spec}'")
        refs[name] = float(value)
    try:
        plot_logs(logs, args.output, columns=columns, x=args.x, refs=refs, dpi=args.dpi, title=args.title,
                  legend=args.legend, logy=set(args.logy or ()))
    except (KeyError, ValueError) as err:
        raise SystemExit(f"tessera-tools log: {err.args[0] if err.args else err}") from None
    print(f"wrote {args.output}")


def build_parser():
    p = argparse.ArgumentParser(
        prog="tessera-tools",
        description="Post-processing for Tessera (active Voronoi vertex model in LAMMPS): "
                    "tessellation pictures, trajectory plots, thermo plots.")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True

    q = sub.add_parser("info", help="summary of a dump file",
                       description="Print frames, atoms, box and columns of a LAMMPS dump file.")
    q.add_argument("dump")
    q.add_argument("--stats", action="store_true", help="also tessellate the last frame and print cell statistics")
    q.set_defaults(func=cmd_info)

    r = sub.add_parser("render", help="picture of the Voronoi tessellation of a frame (PNG), or a series (GIF/MP4)",
                       description="Draw the periodic Voronoi tessellation of a dump frame, cells coloured by a "
                                   "per-cell field, with a colour bar.",
                       epilog="Fields: area perimeter shape sides polarity orientation coordination speed axis "
                              "elongation none, or any dump column (e.g. c_v[1], type). Series: --frames '::10' "
                              "with -o movie.gif (Pillow), movie.mp4 (ffmpeg) or a pattern 'frame_{index:04d}.png' "
                              "/ 'frame_{timestep}.png'.")
    r.add_argument("dump", help="LAMMPS dump custom file (text, may be .gz)")
    r.add_argument("-o", "--output", required=True, help="output file (.png, .pdf, .svg; .gif/.mp4/pattern for series)")
    r.add_argument("-f", "--field", default="area", help="what colours the cells (default: area)")
    g = r.add_mutually_exclusive_group()
    g.add_argument("--frame", type=int, default=-1, help="frame index, negative from the end (default: -1, the last)")
    g.add_argument("--timestep", type=int, help="the frame at this timestep")
    g.add_argument("--frames", type=_slice, help="slice of frames for a series, e.g. '::10', '0:50', 'all'")
    r.add_argument("--view", choices=("box", "cells"), default="box",
                   help="box: periodic picture clipped to the box (default); cells: whole cells around their "
                        "centres, crossing the box edge")
    r.add_argument("--centres", "--centers", action="store_true", help="mark the cell centres")
    r.add_argument("--radius", type=float, metavar="R",
                   help="finite Voronoi cells of radius R (pair_style vertex/voronoi ... radius R): "
                        "free arcs drawn as arcs; open boxes (boundary s/f) work")
    r.add_argument("--arrows", nargs=2, metavar=("XCOL", "YCOL"),
                   help="unit arrows from two columns, e.g. --arrows mux muy (polarity) or vx vy")
    r.add_argument("--highlight", type=int, nargs="+", metavar="ID", help="outline these atom IDs in red")
    r.add_argument("--cmap", help="matplotlib colormap (default depends on the field)")
    r.add_argument("--vmin", type=float)
    r.add_argument("--vmax", type=float)
    r.add_argument("--label", help="colour bar label")
    r.add_argument("--no-colorbar", action="store_true")
    r.add_argument("--title", help="title; may use {timestep} {time} {field} {n}")
    r.add_argument("--dpi", type=int, help="resolution (default 150 for pictures, 100 for series)")
    r.add_argument("--fps", type=float, default=5, help="frames per second of an animation (default 5)")
    r.set_defaults(func=cmd_render)

    t = sub.add_parser("traj", help="trajectories coloured by coordination / orientation, velocity-angle histogram",
                       description="Draw each cell's unwrapped trajectory as segments coloured by coordination "
                                   "C_i = mean_j u_i.u_j over Voronoi neighbours (in [-1, 1]) and/or orientation "
                                   "O_i = arccos(u_i.x) (in [0, pi]), u = v/|v|.",
                       epilog="Positions: xu yu, or x y with ix iy (otherwise unwrapped by continuity). "
                              "Velocities: vx vy (otherwise finite differences of positions).")
    t.add_argument("dump", help="multi-frame LAMMPS dump custom file")
    t.add_argument("-o", "--output", help="trajectory picture (PNG)")
    t.add_argument("--kind", choices=("coordination", "orientation", "both"), default="both",
                   help="which colouring (default: both, side by side)")
    t.add_argument("--hist", metavar="PNG", help="also write a histogram of velocity angles")
    t.add_argument("--hist-skip", type=int, default=0, metavar="K",
                   help="leave the first K selected frames out of the histogram (transient)")
    t.add_argument("--bins", type=int, default=36, help="histogram bins over [0, pi] (default 36)")
    t.add_argument("--frames", type=_slice, help="slice of frames start:stop:step (non-negative)")
    t.add_argument("--velocity", nargs=2, default=["vx", "vy"], metavar=("XCOL", "YCOL"),
                   help="velocity columns (default: vx vy)")
    t.add_argument("--coordination-column", metavar="COL",
                   help="take coordination from this dump column (e.g. of compute vertex/atom) instead of computing it")
    t.add_argument("--orientation-column", metavar="COL", help="take orientation from this dump column")
    t.add_argument("--wrap", action="store_true", help="fold trajectories into the box (segments crossing it are cut)")
    t.add_argument("--cmap", help="colormap (default: jet, as in the thesis)")
    t.add_argument("--linewidth", type=float)
    t.add_argument("--title")
    t.add_argument("--dpi", type=int, default=150)
    t.set_defaults(func=cmd_traj)

    lg = sub.add_parser("log", help="thermo quantities against time from LAMMPS log files",
                        description="Parse the thermo blocks of one or more LAMMPS logs (runs concatenated) and "
                                    "plot columns against time, one panel per column, one line per log.")
    lg.add_argument("logs", nargs="+", help="log.lammps file(s); several are overlaid (e.g. different timesteps)")
    lg.add_argument("-o", "--output", help="picture (PNG)")
    lg.add_argument("-c", "--columns", nargs="+", metavar="NAME[:LABEL]",
                    help="thermo columns to plot (default: all but Step/Time/CPU-like ones, at most 6)")
    lg.add_argument("--x", choices=("auto", "time", "step"), default="auto",
                    help="abscissa: time (Time column or Step x timestep), step, or auto (default)")
    lg.add_argument("--ref", nargs="+", metavar="NAME=VALUE", help="grey reference line, e.g. c_q=3.81")
    lg.add_argument("--logy", nargs="+", metavar="NAME", help="columns drawn on a log scale")
    lg.add_argument("--legend", nargs="+", help="legend labels, one per log (default: file names)")
    lg.add_argument("--list", action="store_true", help="print runs and column names, plot nothing")
    lg.add_argument("--csv", help="write the concatenated thermo table (with a time column) as CSV")
    lg.add_argument("--title")
    lg.add_argument("--dpi", type=int, default=150)
    lg.set_defaults(func=cmd_log)
    return p


def main(argv=None):
    args = build_parser().parse_args(argv)
    try:
        args.func(args)
    except (OSError, KeyError, ValueError) as err:
        msg = err.args[0] if isinstance(err, KeyError) and err.args else err
        print(f"tessera-tools {args.command}: {msg}", file=sys.stderr)
        return 1
    return 0
