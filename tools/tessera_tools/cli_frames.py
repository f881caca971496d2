# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools info, render, vtk, traj: pictures and files of dump frames."""

import math

import numpy as np

from .cli_common import _matplotlib, _progress, _select_frames, _slice

CELL_TYPES_HELP = ("the atom types that are cells, e.g. 1 or 1,3 or 1*2 (the types with cell parameters in "
                   "pair_coeff I I vertex/voronoi); other atoms are particles, never tessellated. Needs a "
                   "'type' column. Default: every atom is a cell, and a dump of several types is refused "
                   "(with --local it is accepted when every atom has rows there)")


def add_cell_types(parser, extra=""):
    """The --cell-types option of a command that reads cells from a dump: without it every atom
    is a cell and a dump of several types is refused (dump.SINGLE_TYPE)."""
    from .dump import SINGLE_TYPE

    parser.add_argument("--cell-types", type=_types, metavar="TYPES", default=SINGLE_TYPE,
                        help=CELL_TYPES_HELP + extra)


def _types(text):
    import argparse

    from .dump import parse_types

    try:
        return parse_types(text)
    except ValueError as err:
        raise argparse.ArgumentTypeError(str(err)) from None


def cmd_info(args):
    from .dump import iter_dump, selects

    cell_types = args.cell_types
    count, first, last = 0, None, None
    # info says what a dump holds: atoms of several types are counted by type, and only what
    # takes them for cells (--stats, --local) needs to know which are cells
    for frame in iter_dump(args.dump, cell_types if selects(cell_types) else None):
        if first is None:
            first = frame
        last = frame
        count += 1
    if first is None:
        raise SystemExit(f"tessera-tools: {args.dump} has no frames")
    print(f"{args.dump}: {count} frame(s), timesteps {first.timestep} .. {last.timestep}")
    if not selects(cell_types):
        def by_type(f):
            if "type" not in f:
                return ""
            t, c = np.unique(np.asarray(f["type"]).astype(int), return_counts=True)
            return "" if len(t) < 2 else " (" + ", ".join(f"type {a}: {b}" for a, b in zip(t, c)) + ")"
        print(f"atoms: {first.natoms}{by_type(first)} (last frame {last.natoms}{by_type(last)})")
        if by_type(first) or by_type(last):
            print("  several atom types: give --cell-types (e.g. --cell-types 1) to count cells and particles; "
                  "--stats and --local need it unless every atom is a cell")
    else:
        def kinds(f):
            types = sorted(set(np.asarray(f.particles["type"]).astype(int).tolist()))
            return (f"{f.natoms} cells, {f.particles.natoms} particles"
                    + (f" (types {','.join(map(str, types))})" if types else ""))
        print(f"atoms: {kinds(first)} (last frame {kinds(last)})")
    print(f"box (first frame): {first.box!r}, area {first.box.area:g}")
    print(f"columns: {' '.join(first.names)}")
    print(f"unwrapped positions: {'yes' if first.has_unwrapped() else 'no'}")
    if args.local:
        from .junctions import contact_lengths, junction_columns, paired_frames
        from .measure import demix_series

        atoms, local = paired_frames(args.dump, args.local, cell_types=cell_types)[-1]
        contacts = contact_lengths(atoms, local)
        print(f"timestep {atoms.timestep}: junction length by type pair "
              + ", ".join(f"{a}-{b} {v:.6g}" for (a, b), v in sorted(contacts.items()))
              + (" (face area, area units)" if len(junction_columns(local)) == 9 else " (length units)"))
        steps, times, frac, het, tot = demix_series(args.dump, args.local, cell_types=cell_types)
        print(f"heterotypic junction fraction, {len(steps)} frame(s) both dumps hold:")
        print("# timestep " + ("time " if times is not None else "") + "fraction heterotypic_length total_length")
        for k in range(len(steps)):
            t = f"{times[k]:.10g} " if times is not None else ""
            print(f"{steps[k]} {t}{frac[k]:.6f} {het[k]:.8g} {tot[k]:.8g}")
    if args.stats:
        if args.local:
            from .junctions import junction_columns, junction_tessellation, paired_frames
            from .vtk import frame_cells3d

            atoms, local = paired_frames(args.dump, args.local, cell_types=cell_types)[-1]
            if len(junction_columns(local)) == 9:
                cells = frame_cells3d(atoms, local)
                print(f"timestep {atoms.timestep} (cells of {args.local}): mean volume "
                      f"{cells.volume.mean():.6g}, total {cells.volume.sum():.6g}, mean surface "
                      f"{cells.surface.mean():.6g}, faces {np.bincount(cells.nfaces).tolist()}")
                return
            tess = junction_tessellation(atoms, local)
            print(f"timestep {atoms.timestep} (cells of {args.local}): mean area {tess.area.mean():.6g}, "
                  f"total {tess.area.sum():.6g}, mean shape index {tess.shape_index.mean():.6g}, "
                  f"neighbours {np.bincount(tess.sides).tolist()}")
            return
        from .dump import check_one_type

        if not selects(cell_types):
            check_one_type(last, f"{args.dump} timestep {last.timestep}")
        if not (last.box.periodic[0] and last.box.periodic[1]):
            raise SystemExit(f"tessera-tools info: {args.dump}: --stats re-tessellates the centres, which "
                             "needs a box periodic in x and y; for this box give the cells LAMMPS "
                             "computed with --local (a dump local of compute vertex/local)")
        from .voronoi import tessellate_frame

        tess = tessellate_frame(last)
        print(f"last frame: mean area {tess.area.mean():.6g} (box area / N = {last.box.area / last.natoms:.6g}), "
              f"mean shape index {tess.shape_index.mean():.6g}, sides {np.bincount(tess.sides).tolist()}")


def _local_frames(args):
    """(atom frames, tessellations) of the frames selected by --frame/--timestep/--frames that
    both the atom dump and the --local dump hold, cells from the local dump's polygons."""
    from .junctions import junction_tessellation, paired_frames

    pairs = paired_frames(args.dump, args.local, cell_types=args.cell_types)
    if args.frames is not None:
        pairs = pairs[args.frames]
    elif args.timestep is not None:
        pairs = [p for p in pairs if p[0].timestep == args.timestep]
        if not pairs:
            raise SystemExit(f"tessera-tools render: no frame at timestep {args.timestep} in both dumps")
    else:
        pairs = [pairs[args.frame]]
    if not pairs:
        raise SystemExit("tessera-tools render: no frames selected by the slice")
    frames = [a for a, _ in pairs]
    return frames, [junction_tessellation(a, l, args.junction_compute) for a, l in pairs]


def cmd_render(args):
    _matplotlib()
    from .dump import read_frame
    from .render import render_frame, render_series

    opts = dict(cmap=args.cmap, vmin=args.vmin, vmax=args.vmax, centres=args.centres,
                arrows=tuple(args.arrows) if args.arrows else None, highlight=args.highlight or (),
                colorbar=not args.no_colorbar, label=args.label,
                categorical=True if args.categorical else None, radius=args.radius)
    tessellations = None
    if args.local:
        frames, tessellations = _local_frames(args)
    elif args.frames is not None:
        frames = _select_frames(args.dump, args.frames, args.cell_types)
    else:
        frames = [read_frame(args.dump, index=args.frame, timestep=args.timestep, cell_types=args.cell_types)]
    series = args.output.lower().endswith((".gif", ".mp4", ".m4v", ".mkv", ".webm")) or "{" in args.output
    if series:
        try:
            written = render_series(frames, args.output, field=args.field, view=args.view,
                                    dpi=args.dpi or 100, fps=args.fps, title=args.title,
                                    tessellations=tessellations, progress=_progress(not args.quiet), **opts)
        except RuntimeError as err:
            raise SystemExit(f"tessera-tools render: {err}") from None
        print(f"wrote {len(written)} file(s)" + (f": {written[0]}" if len(written) == 1 else
                                                 f", {written[0]} .. {written[-1]}"))
        return
    if len(frames) > 1:
        raise SystemExit("tessera-tools render: several frames selected but the output is a single "
                         "picture; use a .gif/.mp4 output or a pattern like 'frame_{index:04d}.png'")
    frame = frames[0]
    tess = render_frame(frame, args.output, field=args.field, view=args.view, dpi=args.dpi or 300,
                        title=args.title, tess=tessellations[0] if tessellations else None,
                        vector=args.vector, **opts)
    if args.vector:
        from .render import vector_path

        print(f"wrote {vector_path(args.output, args.vector)}")
    print(f"wrote {args.output}: timestep {frame.timestep}, {len(tess)} cells, "
          f"mean area {tess.area.mean():.6g}, mean shape index {tess.shape_index.mean():.6g}")


def cmd_vtk(args):
    from .dump import selects
    from .vtk import write_vtk

    try:
        written = write_vtk(args.dump, args.output, local_path=args.local, frames=args.frames or slice(None),
                            dt=args.dt, compute=args.junction_compute, progress=_progress(not args.quiet),
                            radius=args.radius, cell_types=args.cell_types)
    except (RuntimeError, ValueError, KeyError) as err:
        raise SystemExit(f"tessera-tools vtk: {err.args[0] if err.args else err}") from None
    source = ("the cells of " + args.local if args.local else
              f"the finite Voronoi cells (radius {args.radius:g}) of the centres" if args.radius else
              "the Voronoi tessellation of the centres")
    print(f"wrote {len(written)} frame(s) from {source}: {written[0]}" +
          (f" .. {written[-1]}" if len(written) > 1 else "") +
          f"; time series {args.output}.pvd and {args.output}.vtu.series"
          + (f"; particles {args.output}_particles_*.vtu ({args.output}_particles.pvd)"
             if selects(args.cell_types) else ""))


def cmd_traj(args):
    _matplotlib()
    from .trajectories import load_trajectory, plot_angle_histogram, plot_trajectories

    sl = args.frames or slice(None)
    if any(v is not None and v < 0 for v in (sl.start, sl.stop, sl.step)):
        raise SystemExit("tessera-tools traj: --frames takes non-negative start:stop:step")
    extra = [c for c in (args.coordination_column, args.orientation_column) if c]
    traj = load_trajectory(args.dump, sl.start, sl.stop, sl.step, velocity=tuple(args.velocity), extra=extra,
                           cell_types=args.cell_types)
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
        cells = (f"{len(traj.ids)} cells" if not traj.changing else
                 f"{len(traj.ids)} cell IDs ({int(traj.present[0].sum())} in the first frame, "
                 f"{int(traj.present[-1].sum())} in the last), each drawn while present")
        print(f"wrote {args.output}: {len(traj)} frames, {cells}, {summary}")
    if args.hist:
        o = plot_angle_histogram(traj, args.hist, skip=args.hist_skip, bins=args.bins, dpi=args.dpi)
        near = np.mean((o < math.pi / 4) | (o > 3 * math.pi / 4)) if len(o) else float("nan")
        print(f"wrote {args.hist}: {len(o)} velocity samples, fraction within pi/4 of the x axis {near:.3f}")
    if args.msd:
        msd, count = traj.msd()
        dt = args.dt
        t = (traj.timesteps - traj.timesteps[0]) * (dt if dt else 1.0)
        if args.msd.lower().endswith((".png", ".pdf", ".svg")):
            from .plots import plot_msd

            from .plots import STEP, TIME

            plot_msd(t, msd, count, args.msd, time_label=TIME if dt else STEP, dpi=max(300, args.dpi))
        else:
            np.savetxt(args.msd, np.column_stack([traj.timesteps, t, msd, count]), fmt=["%d", "%.10g", "%.10g", "%d"],
                       header="timestep time MSD count: mean-square displacement from the first selected frame "
                              "(length^2), averaged over the count cells present in both frames")
        note = ("" if not traj.changing else
                f"; IDs change, so the mean at each frame runs over the cells present in both frames "
                f"({int(count.min())}-{int(count.max())} cells)")
        print(f"wrote {args.msd}: MSD from timestep {traj.timesteps[0]}, last {msd[-1]:.6g} length^2{note}")
    if not args.output and not args.hist and not args.msd:
        raise SystemExit("tessera-tools traj: nothing to do, give -o, --hist and/or --msd")


def add_commands(sub):
    """Add this module's commands to the subparsers ``sub`` of tessera-tools."""
    q = sub.add_parser("info", help="summary of a dump file",
                       description="Print frames, atoms, box and columns of a LAMMPS dump file.")
    q.add_argument("dump")
    q.add_argument("--stats", action="store_true",
                   help="also print cell statistics of the last frame (with --local: of the cells of the local "
                        "dump, any model and box; without: the periodic Voronoi tessellation of the centres)")
    q.add_argument("--local", metavar="DUMP",
                   help="dump local of compute vertex/local: also print the junction length between each pair "
                        "of cell types at the last common timestep, and the heterotypic junction fraction of "
                        "every frame both dumps hold (one line per frame)")
    add_cell_types(q)
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
    r.add_argument("--dpi", type=int, help="resolution (default 300 for pictures, print quality; 100 for series)")
    r.add_argument("--vector", choices=("pdf", "svg", "eps"),
                   help="also write a vector copy of a single picture (same name, this extension)")
    r.add_argument("--fps", type=float, default=5, help="frames per second of an animation (default 5)")
    r.add_argument("--local", metavar="DUMP",
                   help="dump local of compute vertex/local: draw LAMMPS's own polygons instead of "
                        "re-tessellating the dumped (rounded) centres")
    r.add_argument("--junction-compute", metavar="ID",
                   help="which compute's columns c_ID[1..7] of the local dump to use (if it has several)")
    r.add_argument("--categorical", action="store_true",
                   help="one colour per distinct value with a legend (default for type, mol, proc)")
    r.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    add_cell_types(r, "; particles are drawn as black discs")
    r.set_defaults(func=cmd_render)

    v = sub.add_parser("vtk", help="VTK cell files (.vtu per frame, .pvd time series) for ParaView/OVITO",
                       description="Write one .vtu file per frame: each cell a polygon (2d; finite cells with "
                                   "their free arcs sampled) or a polyhedron (3d), every numeric per-atom "
                                   "column as cell data (plus area, perimeter, shape_index, sides, and the "
                                   "vectors velocity and polarity when vx vy / mux muy are dumped), and a "
                                   "ParaView time series (PREFIX.pvd, PREFIX.vtu.series).",
                       epilog="With --local (a dump local of compute vertex/local) the cells are LAMMPS's "
                              "own, for every model and box (open, periodic, 2d, 3d); without it they are "
                              "the periodic Voronoi tessellation of the dumped centres (2d, periodic in x "
                              "and y). Needs meshio (Debian: python3-meshio).")
    v.add_argument("dump", help="LAMMPS dump custom file of the cells (id, x y, any per-cell columns)")
    v.add_argument("-o", "--output", required=True, metavar="PREFIX",
                   help="output prefix: writes PREFIX_<timestep>.vtu, PREFIX.pvd, PREFIX.vtu.series")
    v.add_argument("--local", metavar="DUMP", help="dump local of compute vertex/local (the cell polygons)")
    v.add_argument("--junction-compute", metavar="ID",
                   help="which compute's columns c_ID[1..7] of the local dump to use (if it has several)")
    v.add_argument("--radius", type=float, metavar="R",
                   help="without --local: finite Voronoi cells of radius R (pair_style vertex/voronoi ... "
                        "radius R) of the dumped centres; open boxes work")
    v.add_argument("--frames", type=_slice, help="slice of frames, e.g. '::10' (default: all)")
    v.add_argument("--dt", type=float,
                   help="timestep, for the time of each frame (default: the dump's TIME item, else the step)")
    v.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    add_cell_types(v, "; particles go to PREFIX_particles_<timestep>.vtu (points with their per-atom "
                      "columns) and PREFIX_particles.pvd")
    v.set_defaults(func=cmd_vtk)

    t = sub.add_parser("traj", help="trajectories coloured by coordination / orientation, velocity-angle histogram",
                       description="Draw each cell's unwrapped trajectory as segments coloured by coordination "
                                   "C_i = mean_j u_i.u_j over Voronoi neighbours (in [-1, 1]) and/or orientation "
                                   "O_i = arccos(u_i.x) (in [0, pi]), u = v/|v|.",
                       epilog="Positions: xu yu, or x y with ix iy (otherwise unwrapped by continuity). "
                              "Velocities: vx vy (otherwise finite differences of positions). Frames may hold "
                              "different atom IDs (division, death): each cell is drawn while present, and "
                              "--msd averages over the cells present in both frames.")
    t.add_argument("dump", help="multi-frame LAMMPS dump custom file")
    t.add_argument("-o", "--output", help="trajectory picture (PNG)")
    t.add_argument("--kind", choices=("coordination", "orientation", "both"), default="both",
                   help="which colouring (default: both, side by side)")
    t.add_argument("--hist", metavar="PNG", help="also write a histogram of velocity angles")
    t.add_argument("--msd", metavar="FILE",
                   help="mean-square displacement from the first selected frame: a plot (.png/.pdf/.svg) or a "
                        "table (any other name); with changing IDs (division, death) averaged over the cells "
                        "present in both frames")
    t.add_argument("--dt", type=float, help="timestep size, for times in --msd (default: timesteps)")
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
    add_cell_types(t, "; only the cells' trajectories are drawn")
    t.set_defaults(func=cmd_traj)
