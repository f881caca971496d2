# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools plot: measurement figures (wound, growth, shape, demix, moduli; kymograph and field
in cli_signal)."""

import numpy as np

from .cli_common import _select_frames, _slice

def _is_dump(path):
    """True for a LAMMPS dump (first line 'ITEM: ...'), False for anything else (a log)."""
    from .dump import _open

    with _open(path) as f:
        for line in f:
            if line.strip():
                return line.startswith("ITEM:")
    return False


def _log_series(path, column, x="auto"):
    """(t, values, time known) of a thermo column over all runs of a log."""
    from .logplot import parse_log

    log = parse_log(path)
    table = log.combined()
    if column not in table:
        raise SystemExit(f"tessera-tools plot: {path} has no thermo column '{column}' "
                         f"(columns: {' '.join(log.names)}); name one with -c")
    t = table["time"]
    known = x != "step" and not np.all(np.isnan(t))
    if not known:
        t = table["Step"]
    ok = np.isfinite(table[column])
    return t[ok], table[column][ok], known


def _dump_time_label(path, dt):
    from .dump import iter_dump

    first = next(iter_dump(path))
    return first.time is not None or bool(dt)


def cmd_plot_wound(args):
    from .measure import frame_series, half_time
    from .plots import TIME, STEP, plot_wound

    if _is_dump(args.input):
        value = args.value or ("open" if args.radius else None)
        if value is None:
            raise SystemExit("tessera-tools plot wound: for a dump give --radius R (the open area: box area "
                             "minus the finite cells' area) or --value sum:COLUMN / mean:COLUMN / count")
        steps, t, y = frame_series(args.input, value, dt=args.dt, radius=args.radius, cell_types=args.cell_types)
        known = _dump_time_label(args.input, args.dt)
        what = {"open": "open area (box minus cells)", "holes": "total hole area",
                "largest": "largest hole area"}.get(value, value)
    else:
        if not args.column:
            raise SystemExit("tessera-tools plot wound: for a log name the thermo column with -c, e.g. -c v_wound "
                             "(see 'tessera-tools log LOG --list')")
        t, y, known = _log_series(args.input, args.column, args.x)
        what = args.column
    half = half_time(t, y, args.fraction)
    ylabel = args.ylabel or (r"wound area ($A_0$)" if not args.column and (args.value or "open") in
                             ("open", "holes", "largest") else what)
    plot_wound(t, y, args.output, ylabel, xlabel=TIME if known else STEP, half=half if args.fraction == 0.5
               else None, dpi=args.dpi, vector=args.vector, title=args.title)
    unit = "time" if known else "timesteps"
    print(f"wrote {args.output}: {what} from {y[0]:.6g} to {y[-1]:.6g} over {len(t)} points; falls to "
          f"{args.fraction:g} of its first value at {half:.6g} {unit}"
          + (" (never)" if not np.isfinite(half) else ""))


def cmd_plot_growth(args):
    from .measure import exponential_fit, frame_series
    from .plots import TIME, STEP, plot_growth

    if _is_dump(args.input):
        _, t, n = frame_series(args.input, "count", dt=args.dt, cell_types=args.cell_types)
        known = _dump_time_label(args.input, args.dt)
    else:
        t, n, known = _log_series(args.input, args.column, args.x)
    fit = exponential_fit(t, n, args.tmin, args.tmax, args.cap)
    plot_growth(t, n, fit, args.output, xlabel=TIME if known else STEP, dpi=args.dpi, vector=args.vector,
                title=args.title)
    unit = "per unit time" if known else "per timestep"
    print(f"wrote {args.output}: N from {n[0]:.0f} to {n[-1]:.0f}; fit N0 exp(r t) over t = {fit['tmin']:g} .. "
          f"{fit['tmax']:g} ({fit['points']} points): r = {fit['rate']:.6g} +- {fit['rate_err']:.2g} {unit}, "
          f"N0 = {fit['N0']:.4g}, doubling time ln2/r = {fit['doubling']:.6g} +- {fit['doubling_err']:.2g} "
          f"{'time' if known else 'timesteps'} (errors from the scatter about the line)")


def cmd_plot_shape(args):
    from .measure import shape_samples
    from .plots import plot_shape

    frames = _select_frames(args.dump, args.frames or slice(-1, None), args.cell_types)
    q, z, rim = shape_samples(frames, args.q, args.z, args.edge, args.radius)
    groups = plot_shape(q, z, rim, args.output, dpi=args.dpi, vector=args.vector, title=args.title)
    print(f"wrote {args.output}: {len(frames)} frame(s), {len(q)} cells")
    for name, (qq, zz) in groups.items():
        if len(qq):
            counts = {int(v): int(c) for v, c in zip(*np.unique(zz.astype(int), return_counts=True))}
            print(f"  {name}: {len(qq)} cells, shape index mean {np.mean(qq):.6g} (std {np.std(qq):.3g}), "
                  f"neighbours mean {np.mean(zz):.4g}, counts {counts}")
    if not rim.any() and not (args.edge or args.radius):
        print("  (no rim: a periodic confluent tissue; for open tissues give --edge COL, the edge flag column "
              "of compute vertex/atom, e.g. c_cell[9], or --radius R)")


def cmd_plot_demix(args):
    from .dump import iter_dump, selects
    from .measure import demix_series
    from .plots import TIME, STEP, plot_demix

    steps, times, frac, het, tot = demix_series(args.dump, args.local, cell_types=args.cell_types)
    known = times is not None or bool(args.dt)
    t = times if times is not None else steps * (args.dt or 1.0)
    first = next(iter_dump(args.dump, args.cell_types if selects(args.cell_types) else None))
    _, counts = np.unique(np.asarray(first["type"]), return_counts=True)
    x = counts / counts.sum()
    reference = None if args.no_reference else float(1.0 - np.sum(x ** 2))
    plot_demix([(args.label or "heterotypic fraction", t, frac)], args.output, xlabel=TIME if known else STEP,
               dpi=args.dpi, vector=args.vector, reference=reference, title=args.title)
    if args.csv:
        np.savetxt(args.csv, np.column_stack([steps, t, frac, het, tot]), fmt=["%d", "%.10g", "%.8f", "%.10g", "%.10g"],
                   delimiter=",", comments="",
                   header="timestep,time,heterotypic_fraction,heterotypic_length,total_length")
        print(f"wrote {args.csv}")
    ref = f"; a random mixture of these types would give {reference:.4g}" if reference is not None else ""
    print(f"wrote {args.output}: {len(steps)} frames, heterotypic junction fraction {frac[0]:.4f} -> {frac[-1]:.4f}{ref}")


def cmd_plot_moduli(args):
    import csv

    from .plots import plot_moduli

    rows = []
    for path in args.tables:
        with open(path, newline="") as f:
            for r in csv.DictReader(f):
                try:
                    rows.append(dict(p0=float(r["p0"]), route=r["route"], unit=r.get("unit", "KA A0"),
                                     **{k: float(r[k]) for k in ("G", "G_err", "B", "B_err")}))
                except (KeyError, ValueError) as err:
                    raise SystemExit(f"tessera-tools plot moduli: {path}: unreadable row {r} ({err}); "
                                     "write the table with 'tessera-tools moduli ... --table FILE'") from None
    if not rows:
        raise SystemExit(f"tessera-tools plot moduli: no rows in {' '.join(args.tables)}")
    if args.route != "both":
        rows = [r for r in rows if r["route"] == args.route]
    units = sorted({r["unit"] for r in rows})
    if len(units) > 1:
        raise SystemExit(f"tessera-tools plot moduli: the rows mix units {units}; plot them separately")
    unit = {"KA A0": r"$K_A A_0$", "K A0": r"$K A_0$"}.get(units[0], units[0])
    drawn = plot_moduli(rows, args.output, unit=unit, dpi=args.dpi, vector=args.vector, title=args.title)
    print(f"wrote {args.output}: " + "; ".join(f"{route}: {len(v[0])} values of p0" for route, v in drawn.items())
          + f" (moduli in {units[0]})")


def add_commands(sub):
    """Add this module's commands to the subparsers ``sub`` of tessera-tools."""
    from .cli_frames import add_cell_types

    pl = sub.add_parser("plot", help="measurement figures: wound area, growth N(t), shapes, demixing, moduli vs p0, kymographs, fields",
                        description="One figure per command, print quality (300 dpi, --vector pdf for a vector "
                                    "copy), axes in the model's reduced units. See doc/howto_measure.md.")
    psub = pl.add_subparsers(dest="what", metavar="WHAT")
    psub.required = True

    def common(p, required=True):
        p.add_argument("-o", "--output", "--out", required=required, help="picture (.png, .pdf, .svg)")
        p.add_argument("--dpi", type=int, default=300, help="resolution (default 300)")
        p.add_argument("--vector", metavar="EXT", help="also write a vector copy (pdf or svg)")
        p.add_argument("--title")

    pw = psub.add_parser("wound", help="wound (hole) area against time, with the half-closure time",
                         description="From a log: a thermo column (-c v_wound). From a dump: the open area "
                                     "(box area minus the finite Voronoi cells of --radius R), or a per-frame "
                                     "value --value sum:COL / mean:COL / count.")
    pw.add_argument("input", help="log.lammps or a dump custom file")
    pw.add_argument("-c", "--column", help="thermo column of a log (e.g. v_wound)")
    pw.add_argument("--radius", type=float, help="dump: radius of the finite cells (pair_style ... radius R)")
    pw.add_argument("--value", help="dump: per-frame value: open (default with --radius: box minus cells), holes "
                                    "(total hole area), largest (largest hole), sum:COL, mean:COL, count")
    pw.add_argument("--dt", type=float, help="dump: timestep size (time = timestep x dt; else the dump's TIME)")
    pw.add_argument("--x", choices=("auto", "step"), default="auto", help="log: time (default) or step")
    pw.add_argument("--fraction", type=float, default=0.5,
                    help="report when the value falls to this fraction of its first value (default 0.5)")
    pw.add_argument("--ylabel")
    add_cell_types(pw, "; particles cover no area (the open area is then compute vertex/loops' total hole "
                       "area in a periodic box)")
    common(pw)
    pw.set_defaults(func=cmd_plot_wound)

    pg = psub.add_parser("growth", help="number of cells N(t) with the exponential fit and doubling time",
                         description="N(t) from a log column (default Atoms) or the cells of each dump frame; "
                                     "fits ln N = ln N0 + r t by least squares up to the first maximum of N "
                                     "(a 'max' cap does not bend it) or over --tmin/--tmax.")
    pg.add_argument("input", help="log.lammps (thermo with Atoms) or a dump")
    pg.add_argument("-c", "--column", default="Atoms", help="log: thermo column of the cell count (default Atoms)")
    pg.add_argument("--tmin", type=float, help="fit from this time")
    pg.add_argument("--tmax", type=float, help="fit up to this time (default: the first maximum of N)")
    pg.add_argument("--cap", type=float, metavar="N",
                    help="leave out samples with N >= this (the 'max N' of fix cell/divide)")
    pg.add_argument("--dt", type=float, help="dump: timestep size")
    pg.add_argument("--x", choices=("auto", "step"), default="auto", help="log: time (default) or step")
    add_cell_types(pg, "; dump: only the cells are counted")
    common(pg)
    pg.set_defaults(func=cmd_plot_growth)

    ps = psub.add_parser("shape", help="shape-index and neighbour-number histograms (interior and rim apart)",
                         description="From dump columns of compute vertex/atom (--q c_cell[3] --z c_cell[4] "
                                     "--edge c_cell[9]) or from the Voronoi tessellation of the frames (finite "
                                     "cells with --radius R: cells with a free arc are the rim).")
    ps.add_argument("dump")
    ps.add_argument("--frames", type=_slice, help="frames pooled (default: the last), e.g. '-10:' or 'all'")
    ps.add_argument("--q", metavar="COL", help="shape index column (default: computed)")
    ps.add_argument("--z", metavar="COL", help="neighbour number column (default: computed)")
    ps.add_argument("--edge", metavar="COL",
                    help="edge flag column (compute vertex/atom column 9): 1 = rim, 0 = interior")
    ps.add_argument("--radius", type=float, help="finite Voronoi cells of this radius (open tissues)")
    add_cell_types(ps)
    common(ps)
    ps.set_defaults(func=cmd_plot_shape)

    pd = psub.add_parser("demix", help="heterotypic junction fraction against time (cell sorting)",
                         description="From a per-atom dump with 'type' and a dump local of compute vertex/local "
                                     "(rows: cell ID, neighbour ID, x1 y1 x2 y2, length) at the same timesteps.")
    pd.add_argument("dump", help="per-atom dump with id and type")
    pd.add_argument("local", help="dump local of compute vertex/local")
    pd.add_argument("--dt", type=float, help="timestep size (else the dump's TIME, else timesteps)")
    pd.add_argument("--csv", help="also write the series as CSV")
    pd.add_argument("--label")
    pd.add_argument("--no-reference", action="store_true",
                    help="no line at the random-mixture value 1 - sum_t x_t^2")
    add_cell_types(pd, "; the type fractions of the reference are the cells'")
    common(pd)
    pd.set_defaults(func=cmd_plot_demix)

    pm = psub.add_parser("moduli", help="G and B against p0 with error bars",
                         description="From tables written by 'tessera-tools moduli ... --table FILE' (one run "
                                     "per p0, e.g. with --seeds N).")
    pm.add_argument("tables", nargs="+", help="CSV table(s) of tessera-tools moduli --table")
    pm.add_argument("--route", choices=("hessian", "quasistatic", "both"), default="both")
    common(pm)
    pm.set_defaults(func=cmd_plot_moduli)

    from .cli_signal import add_plot_commands

    add_plot_commands(psub, common, add_cell_types)
