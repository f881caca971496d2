# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools log: thermo quantities of LAMMPS logs against time."""

from .cli_common import _matplotlib

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


def add_commands(sub):
    """Add this module's commands to the subparsers ``sub`` of tessera-tools."""
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
