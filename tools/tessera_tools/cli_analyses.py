# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools flux, velocity, msd, holes, divisions: the analyses of how atoms of any type
move (flux through sections, velocity field, drift and MSD), of the hole of compute
vertex/loops around each particle, and of where and when cells divided."""

import csv

import numpy as np

from .cli_common import _slice

TYPES_HELP = ("the atom types to follow, e.g. 2 or 1,3 or 2* (cells, beads, a colloid: any type); needs a "
              "'type' column. Default: every atom, and a dump of several types is refused")


def _types_option(parser):
    from .cli_frames import _types
    from .dump import OneType

    parser.add_argument("--types", type=_types, metavar="TYPES", default=OneType("--types", "atoms"),
                        help=TYPES_HELP)


def _common(parser, csv_help):
    parser.add_argument("-o", "--output", help="picture (.png, .pdf, .svg)")
    parser.add_argument("--csv", metavar="FILE", help=csv_help)
    parser.add_argument("--dpi", type=int, default=300, help="resolution (default 300)")
    parser.add_argument("--vector", metavar="EXT", help="also write a vector copy (pdf or svg)")
    parser.add_argument("--title")


def _need_output(args, what):
    if not (args.output or args.csv):
        raise SystemExit(f"tessera-tools {what}: nothing to do: give -o PICTURE and/or --csv FILE")


def _write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for row in rows:
            w.writerow([(f"{v:.10g}" if isinstance(v, (float, np.floating)) else v) for v in row])


def _trajectory(args):
    from .transport import frame_times, load_atoms

    traj = load_atoms(args.dump, args.types, args.frames)
    if len(traj) < 2:
        raise SystemExit(f"tessera-tools {args.command}: {args.dump}: need at least two frames")
    if not traj.unwrapped_columns:
        print("note: no xu yu or image flags in the dump: positions unwrapped by continuity (wrong for an "
              "atom that moves more than half a box between frames)")
    times, known = frame_times(traj, args.dt)
    return traj, times, known


def _atoms_text(traj):
    n0, n1 = int(traj.present[0].sum()), int(traj.present[-1].sum())
    return (f"{len(traj.ids)} atoms" if not traj.changing else
            f"{len(traj.ids)} atom IDs ({n0} in the first frame, {n1} in the last; pairs of frames use the "
            "atoms present in both)")


def cmd_flux(args):
    _need_output(args, "flux")
    from .transport import section_flux

    if not (args.x or args.y):
        raise SystemExit("tessera-tools flux: give the sections: --x C [C ...] (lines x = C) and/or --y C [C ...]")
    traj, times, known = _trajectory(args)
    unit = "time" if known else "timestep"
    results = []
    for axis, where in (("x", args.x), ("y", args.y)):
        if where:
            results.append(section_flux(traj, times, axis, where, args.blocks))
    print(f"{args.dump}: {len(traj)} frames, {_atoms_text(traj)}; flux = net crossings in +x (+y) per unit "
          f"{unit}, error from {results[0]['blocks']} blocks of the record")
    rows = []
    for res in results:
        for s, c in enumerate(res["sections"]):
            per = res["flux"][s] / res["length"]
            per_err = res["flux_err"][s] / res["length"]
            print(f"  {res['axis']} = {c:g}: net {res['net'][s]:+.0f} ({res['plus'][s]:.0f} in +{res['axis']}, "
                  f"{res['minus'][s]:.0f} in -{res['axis']}) over {res['duration']:.6g} {unit}: flux "
                  f"{res['flux'][s]:.6g} +- {res['flux_err'][s]:.2g} per {unit}, {per:.6g} +- {per_err:.2g} "
                  f"per {unit} and unit length")
            rows.append([res["axis"], c, res["net"][s], res["plus"][s], res["minus"][s], res["duration"],
                         res["flux"][s], res["flux_err"][s], res["length"], per, per_err])
    if args.csv:
        _write_csv(args.csv, ["axis", "position", "net", "plus", "minus", "duration", "flux", "flux_err",
                              "section_length", "flux_per_length", "flux_per_length_err"], rows)
        print(f"wrote {args.csv}")
    if args.output:
        from .analysis_plots import plot_flux

        if len(results) == 2:
            import os

            stem, ext = os.path.splitext(args.output)
            outs = [f"{stem}_x{ext}", f"{stem}_y{ext}"]
        else:
            outs = [args.output]
        for res, out in zip(results, outs):
            plot_flux(res, times, out, known, args.dpi, args.vector, args.title)
            print(f"wrote {out}")


def cmd_velocity(args):
    _need_output(args, "velocity")
    from .transport import velocity_field

    traj, times, known = _trajectory(args)
    field = velocity_field(traj, times, args.bins)
    nx, ny = field["bins"]
    empty = int(np.sum(field["count"] == 0))
    unit = "time" if known else "timestep"
    print(f"{args.dump}: {len(traj)} frames, {_atoms_text(traj)}; {field['samples']} displacements in "
          f"{nx} x {ny} bins ({empty} empty); mean velocity ({field['mean'][0]:.6g}, {field['mean'][1]:.6g}) "
          f"length per {unit}")
    if args.csv:
        rows = []
        for j in range(ny):
            for i in range(nx):
                rows.append([i, j, field["centres"][j, i, 0], field["centres"][j, i, 1], field["vx"][j, i],
                             field["vy"][j, i], field["vx_err"][j, i], field["vy_err"][j, i],
                             int(field["count"][j, i])])
        _write_csv(args.csv, ["ix", "iy", "x", "y", "vx", "vy", "vx_err", "vy_err", "samples"], rows)
        print(f"wrote {args.csv}")
    if args.output:
        from .analysis_plots import plot_velocity_field

        plot_velocity_field(field, traj.boxes[0], args.output, args.dpi, args.vector, args.title)
        print(f"wrote {args.output}")


def cmd_msd(args):
    _need_output(args, "msd")
    from .transport import diffusion_fit, msd

    traj, times, known = _trajectory(args)
    res = msd(traj, times, args.max_lag)
    unit = "time" if known else "timestep"
    fit = None
    try:
        fit = diffusion_fit(res["tau"], res["msd_nodrift"], args.fit_max)
    except ValueError as err:
        print(f"no diffusion fit: {err}")
    V, Ve = res["drift"], res["drift_err"]
    print(f"{args.dump}: {len(traj)} frames, {_atoms_text(traj)}; lags up to {res['tau'][-1]:.6g} {unit}")
    print(f"  drift V = ({V[0]:.6g} +- {Ve[0]:.2g}, {V[1]:.6g} +- {Ve[1]:.2g}) length per {unit} (all "
          f"displacements over the {res['followed']:.6g} {unit} the atoms were followed)")
    print(f"  MSD at the first lag {res['msd'][0]:.6g}, drift removed {res['msd_nodrift'][0]:.6g}; at the last "
          f"{res['msd'][-1]:.6g}, drift removed {res['msd_nodrift'][-1]:.6g} length^2")
    if fit is not None:
        print(f"  D = {fit['D']:.6g} +- {fit['D_err']:.2g} length^2 per {unit} (MSD without drift = 4 D tau + c "
              f"over tau <= {fit['tmax']:.6g}, {fit['points']} lags; c = {fit['intercept']:.3g})")
    if args.csv:
        rows = [[int(res["lag"][k]), res["tau"][k], int(res["count"][k]), res["msd"][k], res["msd_err"][k],
                 res["msd_nodrift"][k], res["msd_nodrift_err"][k], res["mean"][k, 0], res["mean"][k, 1]]
                for k in range(len(res["lag"]))]
        _write_csv(args.csv, ["lag", "tau", "pairs", "msd", "msd_err", "msd_nodrift", "msd_nodrift_err",
                              "mean_dx", "mean_dy"], rows)
        print(f"wrote {args.csv}")
    if args.output:
        from .analysis_plots import plot_msd_drift

        plot_msd_drift(res, fit, args.output, known, args.dpi, args.vector, args.title)
        print(f"wrote {args.output}")


def cmd_holes(args):
    _need_output(args, "holes")
    from .dump import iter_dump, selects
    from .holes import loop_column, particle_holes, particle_holes_indexed, read_loops
    from .measure import frame_time

    if not selects(args.cell_types):
        raise SystemExit("tessera-tools holes: give --cell-types (the cell types; the other atoms are the "
                         "particles whose holes are measured)")
    if args.loop_column and not args.loops:
        raise SystemExit("tessera-tools holes: --loop-column needs --loops (the dump local of compute "
                         "vertex/loops of the same steps: the loops' area, length and cells by index)")
    loops = read_loops(args.loops) if args.loops else None
    rows, frames, unmatched, known = [], 0, 0, bool(args.dt)
    sl = args.frames or slice(None)
    import itertools

    for frame in itertools.islice(iter_dump(args.dump, args.cell_types), sl.start, sl.stop, sl.step):
        lrows = None
        if loops is not None:
            if frame.timestep not in loops:
                continue
            lrows = loops[frame.timestep]
        frames += 1
        known = known or frame.time is not None
        t = frame_time(frame, args.dt)
        if args.loop_column:
            try:
                loop_column(frame, args.loop_column)
                found = particle_holes_indexed(frame, args.radius, args.loop_column, lrows, args.particle_types)
            except (KeyError, ValueError) as e:
                raise SystemExit(f"tessera-tools holes: {args.dump}: {e.args[0]}")
        else:
            found = particle_holes(frame, args.radius, args.particle_types, lrows)
        for r in found:
            r.update(timestep=frame.timestep, time=t)
            if loops is not None and r["index"] and not r["matched"]:
                unmatched += 1
            rows.append(r)
    if not frames:
        raise SystemExit(f"tessera-tools holes: no frame of {args.dump}" +
                         (f" at a timestep of {args.loops}" if args.loops else "") + " selected")
    if not rows:
        raise SystemExit(f"tessera-tools holes: {args.dump}: no particles (atoms of types other than the cells'"
                         + (" and of --particle-types" if args.particle_types else "") + ")")
    source = (f"the loop index {args.loop_column} of compute vertex/loops/atom and the rows of {args.loops}"
              if args.loop_column else
              f"compute vertex/loops rows of {args.loops}" if loops is not None else
              f"the loops of the finite cells (radius {args.radius:g}) of the dumped centres")
    print(f"{args.dump}: {frames} frame(s), {len({r['id'] for r in rows})} particle(s); holes from {source}")
    last = {}
    for r in rows:
        last[r["id"]] = r
    for i, r in sorted(last.items()):
        where = ("covered by a cell" if r["covered"] else "in no hole" if not r["index"] else
                 f"hole {r['index']}: area {r['area']:.6g}, length {r['length']:.6g}, {r['cells']} cells")
        print(f"  particle {i} (type {r['type']}) at timestep {r['timestep']}: {where}")
    if unmatched:
        print(f"warning: {unmatched} hole(s) found around particles have no row of {args.loops} with that "
              "centroid and area; their values are those of the dumped centres")
    if args.csv:
        _write_csv(args.csv, ["timestep", "time", "id", "type", "x", "y", "covered", "loop", "area", "length",
                              "cells", "from_compute"],
                   [[r["timestep"], r["time"], r["id"], r["type"], r["x"], r["y"], int(r["covered"]), r["index"],
                     r["area"], r["length"], r["cells"], int(r["matched"])] for r in rows])
        print(f"wrote {args.csv}")
    if args.output:
        from .analysis_plots import plot_holes

        plot_holes(rows, args.output, known, args.dpi, args.vector, args.title)
        print(f"wrote {args.output}")


def cmd_divisions(args):
    _need_output(args, "divisions")
    from .divisions import division_table, rate_histogram

    centre = tuple(args.centre) if args.centre else "header"
    table = division_table(args.logs, centre)
    n = len(table["step"])
    if n == 0:
        raise SystemExit(f"tessera-tools divisions: no division in {' '.join(args.logs)}")
    where = ""
    if table["centre"] is not None:
        c = table["centre"]
        where = (f"; on the sphere of centre ({c[0]:g}, {c[1]:g}, {c[2]:g})"
                 + (" (from --centre)" if args.centre else " (named by the log's header)"))
    print(f"{n} divisions from step {table['step'][0]} to {table['step'][-1]} (time {table['time'][0]:.6g} to "
          f"{table['time'][-1]:.6g}){where}")
    span = (args.tmin if args.tmin is not None else float(table["time"].min()),
            args.tmax if args.tmax is not None else float(table["time"].max()))
    hist = rate_histogram(table["time"], args.bins, span)
    if table["centre"] is not None:
        lat = table["latitude"]
        print(f"  latitude mean {lat.mean():.4g} degrees (std {lat.std():.3g}); northern hemisphere "
              f"{int(np.sum(lat > 0))}, southern {int(np.sum(lat < 0))}")
    if args.csv:
        cols = ["step", "time", "id", "daughter1", "daughter2", "x", "y", "z"]
        if table["centre"] is not None:
            cols += ["latitude", "longitude"]
        _write_csv(args.csv, cols, [[table[c][k] for c in cols] for k in range(n)])
        print(f"wrote {args.csv}")
    if args.output:
        from .analysis_plots import plot_divisions

        plot_divisions(table, hist, args.output, True, args.dpi, args.vector, args.title)
        print(f"wrote {args.output}")


def add_commands(sub):
    """Add this module's commands to the subparsers ``sub`` of tessera-tools."""
    moving = ("Atoms are matched by ID across frames and unwrapped (xu yu, or x y with ix iy; else by "
              "continuity); atoms may appear and disappear: each pair of frames uses the atoms in both. Times: "
              "the dump's TIME, else timestep x --dt, else timesteps.")

    def dump_options(p):
        p.add_argument("dump", help="dump custom file with id, type and positions (xu yu, or x y ix iy)")
        _types_option(p)
        p.add_argument("--frames", type=_slice, help="slice of frames start:stop:step (non-negative)")
        p.add_argument("--dt", type=float, help="timestep size (else the dump's TIME, else timesteps)")

    fl = sub.add_parser("flux", help="net crossings per unit time of atoms of a type through sections x = C / y = C",
                        description="Net number of atoms crossing each section (in +x or +y) per unit time, "
                                    "with error bars from blocks of the record. In a periodic direction a "
                                    "section is the lines C + m L (an atom going once around the box crosses "
                                    "it once).", epilog=moving)
    dump_options(fl)
    fl.add_argument("--x", type=float, nargs="+", metavar="C", help="sections x = C")
    fl.add_argument("--y", type=float, nargs="+", metavar="C", help="sections y = C")
    fl.add_argument("--blocks", type=int, default=10, help="blocks of the record for the error bars (default 10)")
    _common(fl, "one row per section: axis, position, net, plus, minus, duration, flux, flux_err, "
                "section_length, flux_per_length, its error")
    fl.set_defaults(func=cmd_flux)

    ve = sub.add_parser("velocity", help="binned, time-averaged velocity field of atoms of a type (quiver plot)",
                        description="Displacements between consecutive frames over their time difference, "
                                    "binned by the position at the earlier frame (equal fractions of the box) "
                                    "and averaged over atoms and frames; error bars are standard errors of "
                                    "the samples of a bin.", epilog=moving)
    dump_options(ve)
    ve.add_argument("--bins", type=int, nargs=2, default=[10, 10], metavar=("NX", "NY"),
                    help="bins along x and y (default 10 10)")
    _common(ve, "one row per bin: ix, iy, x, y, vx, vy, vx_err, vy_err, samples")
    ve.set_defaults(func=cmd_velocity)

    ms = sub.add_parser("msd", help="drift and mean-squared displacement (with and without drift) against lag time",
                        description="MSD over all time origins against lag time, with and without the drift "
                                    "(the constant velocity: all displacements over the time the atoms were "
                                    "followed), the mean displacement, and D from MSD = 4 D tau + c (2d).",
                        epilog=moving + " The frames must be equally spaced in time.")
    dump_options(ms)
    ms.add_argument("--max-lag", type=int, metavar="K", help="largest lag in frames (default: all)")
    ms.add_argument("--fit-max", type=float, metavar="TAU",
                    help="fit D over lags up to TAU (default: the first quarter of the lags)")
    _common(ms, "one row per lag: lag, tau, pairs, msd, msd_err, msd_nodrift, msd_nodrift_err, mean_dx, mean_dy")
    ms.set_defaults(func=cmd_msd)

    ho = sub.add_parser("holes", help="area and length of the hole of compute vertex/loops around each particle",
                        description="For each particle (atom that is no cell), the hole of the finite cells "
                                    "that surrounds it, against time.  With --loop-column (compute "
                                    "vertex/loops/atom's column 1 in the dump: the loop each atom is in) and "
                                    "--loops, the hole is the row of that index; otherwise the loops of free "
                                    "boundary of the dumped centres, matched (nearest centroid, equal area) to "
                                    "the rows of a dump local of compute vertex/loops when given with --loops, "
                                    "whose index, area, length and cell count are then reported.")
    ho.add_argument("dump", help="dump custom file with id, type, x y of the cells and the particles")
    from .cli_frames import _types, add_cell_types

    add_cell_types(ho, "; the atoms of other types are the particles")
    ho.add_argument("--radius", type=float, required=True, help="radius of the finite cells (pair_style ... radius R)")
    ho.add_argument("--loops", metavar="DUMP",
                    help="dump local of compute vertex/loops (c_ID[1] .. c_ID[7]) at the same timesteps")
    ho.add_argument("--loop-column", metavar="COLUMN",
                    help="the dump's column of compute vertex/loops/atom's loop index (e.g. c_inloop[1], or "
                         "the compute ID inloop); needs --loops")
    ho.add_argument("--particle-types", type=_types, metavar="TYPES", help="only the particles of these types")
    ho.add_argument("--frames", type=_slice, help="slice of frames start:stop:step (non-negative)")
    ho.add_argument("--dt", type=float, help="timestep size (else the dump's TIME, else timesteps)")
    _common(ho, "one row per particle and frame: timestep, time, id, type, x, y, covered, loop, area, length, "
                "cells, from_compute")
    ho.set_defaults(func=cmd_holes)

    dv = sub.add_parser("divisions", help="division events with their positions (latitude/longitude on a sphere)",
                        description="The divisions of fix cell/divide's event log (keyword file): step, time, "
                                    "mother's centre, daughters; on a sphere latitude and longitude about its "
                                    "centre (--centre, else named by the log's header); a map coloured by time "
                                    "and the division rate against time.")
    dv.add_argument("logs", nargs="+", help="event log(s) of fix cell/divide")
    dv.add_argument("--centre", "--center", type=float, nargs=3, metavar=("CX", "CY", "CZ"),
                    help="the sphere's centre (surface sphere cx cy cz R): latitude and longitude about it")
    dv.add_argument("--bins", type=int, default=20, help="time bins of the rate (default 20)")
    dv.add_argument("--tmin", type=float, help="rate histogram from this time")
    dv.add_argument("--tmax", type=float, help="rate histogram up to this time")
    _common(dv, "one row per division: step, time, id, daughter1, daughter2, x, y, z (latitude, longitude)")
    dv.set_defaults(func=cmd_divisions)
