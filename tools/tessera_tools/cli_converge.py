# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools converge: is a result of a run the model's, or the integrator's?

Runs one LAMMPS input at three (or more) values of one variable (the timestep:
dt, dt/2, dt/4; or the tolerance of fix brownian/heun's adaptive step), each in
its own directory, and compares observables between the runs:

* thermo columns: time averages over a window [t0, t1] (the thermo samples
  joined linearly in time, so runs with a varying timestep are weighted by
  time, not by step), with the standard error from block averages (the
  window cut into equal blocks of time, the error the spread of the block
  means over the square root of their number);
* from a dump with unwrapped coordinates (xu): the net number of atoms of a
  type that cross the section x = X per unit time, counted exactly from the
  unwrapped positions (an atom crossed floor((xu1 - X)/Lx) - floor((xu0 - X)/Lx)
  times between two frames), with block errors the same way.

An observable agrees when each run's value is within two standard errors
(combined) of the finest run's (the smallest value of the variable).  The
table goes to stdout (and --table), the plot to --plot.
"""

import math
import os
import shutil
import subprocess
import sys

import numpy as np

#: thermo columns that are bookkeeping, not observables
SKIP = {"Step", "Time", "Dt", "CPU", "Elapsed", "Elaplong", "CPULeft", "TpCPU", "SpCPU", "Atoms"}
#: an observable agrees when every run is within this many combined standard errors
Z_AGREE = 2.0


def piecewise_linear_means(t, y, edges):
    """Means of the piecewise-linear function through (t, y) over the intervals
    between successive edges (trapezoid rule on the samples plus the
    function's values at the edges)."""
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    good = np.isfinite(t) & np.isfinite(y)
    t, y = t[good], y[good]
    order = np.argsort(t, kind="stable")
    t, y = t[order], y[order]
    if len(t) < 2 or edges[0] < t[0] - 1e-12 * abs(t[0]) or edges[-1] > t[-1] + 1e-12 * abs(t[-1]):
        raise ValueError(f"the window {edges[0]:g}..{edges[-1]:g} is not inside the samples' "
                         f"times {t[0] if len(t) else float('nan'):g}..{t[-1] if len(t) else float('nan'):g}")
    means = []
    for a, b in zip(edges[:-1], edges[1:]):
        inside = (t > a) & (t < b)
        tt = np.concatenate([[a], t[inside], [b]])
        yy = np.concatenate([[np.interp(a, t, y)], y[inside], [np.interp(b, t, y)]])
        means.append(np.sum(0.5 * (yy[1:] + yy[:-1]) * np.diff(tt)) / (b - a))
    return np.array(means)


def block_estimate(block_means):
    """Mean of equal blocks and its standard error (spread over sqrt(n))."""
    m = np.asarray(block_means, dtype=float)
    err = m.std(ddof=1) / math.sqrt(len(m)) if len(m) > 1 else float("nan")
    return float(m.mean()), float(err)


def section_flux(frames, atom_type, x_section, t0, t1, nblocks, dt=None):
    """Net number of atoms of atom_type crossing x = x_section per unit time
    between t0 and t1, from unwrapped x (column xu): (flux, error, block
    fluxes).  Frames need id, type, xu and a time (dump_modify time yes), or
    a timestep and dt.  Each interval between successive frames goes to the
    block that holds its midpoint."""
    times, crossings, spans = [], [], []
    eps = 1e-9 * max(1.0, abs(t0), abs(t1))
    prev = None
    for frame in frames:
        for col in ("id", "type", "xu"):
            if col not in frame:
                raise ValueError(f"the dump has no column '{col}' (the flux needs id, type and xu)")
        if frame.box.xy != 0.0 or frame.box.xz != 0.0:
            raise ValueError("the box is triclinic: a section x = const is not periodic there")
        t = frame.time if frame.time is not None else (frame.timestep * dt if dt else None)
        if t is None:
            raise ValueError("the dump frames have no time (add 'dump_modify ID time yes') and no "
                             "timestep was given (--dump-dt)")
        if t > t1 + eps:
            break
        sel = frame["type"] == atom_type
        cur = (t, dict(zip(frame["id"][sel].tolist(), frame["xu"][sel].tolist())), frame.box.lx)
        if prev is not None and prev[0] >= t0 - eps:
            a, b, lx = prev[1], cur[1], cur[2]
            n = 0
            for i in a.keys() & b.keys():
                n += math.floor((b[i] - x_section) / lx) - math.floor((a[i] - x_section) / lx)
            times.append(0.5 * (prev[0] + t))
            crossings.append(n)
            spans.append(t - prev[0])
        prev = cur
    if not spans:
        raise ValueError(f"no two dump frames between t = {t0:g} and {t1:g}")
    times, crossings, spans = np.array(times), np.array(crossings, float), np.array(spans)
    covered = spans.sum()
    edges = np.linspace(times[0] - 0.5 * spans[0], times[-1] + 0.5 * spans[-1], nblocks + 1)
    which = np.clip(np.searchsorted(edges, times, side="right") - 1, 0, nblocks - 1)
    blocks = []
    for k in range(nblocks):
        m = which == k
        if spans[m].sum() > 0:
            blocks.append(crossings[m].sum() / spans[m].sum())
    flux = crossings.sum() / covered
    _, err = block_estimate(blocks)
    return flux, err, np.array(blocks)


def compare(values, errors):
    """Largest |v - v_ref| / sqrt(e^2 + e_ref^2) over the runs, the reference
    being the last (finest) run, and whether every run agrees with it."""
    ref, eref = values[-1], errors[-1]
    zmax = 0.0
    for v, e in zip(values[:-1], errors[:-1]):
        s = math.hypot(e, eref)
        if s > 0 and math.isfinite(s):
            z = abs(v - ref) / s
        else:
            z = 0.0 if v == ref else math.inf
        zmax = max(zmax, z)
    return zmax, zmax <= Z_AGREE


def _input_files(directory):
    """The small text files beside an input that it may read (includes,
    data files), not logs, dumps or pictures."""
    out = []
    for name in sorted(os.listdir(directory)):
        full = os.path.join(directory, name)
        if (not os.path.isfile(full) or name.startswith(("log.", "dump.")) or
                name.endswith((".png", ".gif", ".md")) or os.path.getsize(full) > 10 ** 7):
            continue
        out.append(full)
    return out


def run_dirs(args):
    """(value, directory, seed) of each run, in the order given: one run per
    value, or with --seeds one per value and seed (OUT/NAME_VALUE/SEEDVAR_S)."""
    out = []
    for v in args.values:
        base = os.path.join(args.out, f"{args.var}_{v}")
        if args.seeds:
            for s in args.seeds:
                out.append((v, os.path.join(base, f"{args.seed_var}_{s}"), s))
        else:
            out.append((v, base, None))
    return out


def combine_starts(estimates):
    """One value and its standard error from the (mean, block error) of runs
    from independent starts: the mean of the means, and the larger of their
    spread's standard error and the block errors carried through.  The spread
    sees what blocks cannot: an event longer than a block (a stall) that one
    run has and another has not."""
    means = np.array([m for m, _ in estimates], dtype=float)
    errs = np.array([e for _, e in estimates], dtype=float)
    n = len(means)
    if n == 1:
        return float(means[0]), float(errs[0])
    spread = means.std(ddof=1) / math.sqrt(n)
    carried = math.sqrt(np.nansum(errs ** 2)) / n
    return float(means.mean()), float(max(spread, carried))


def finished(log):
    if not os.path.exists(log):
        return False
    with open(log, errors="replace") as f:
        return "Total wall time" in f.read()


def launch(args, value, directory, seed=None):
    """Start one run of the input with -var VAR value (and --set, and the
    seed's variable) in directory."""
    os.makedirs(directory, exist_ok=True)
    for path in _input_files(os.path.dirname(os.path.abspath(args.input))):
        shutil.copy(path, directory)
    cmd = []
    if args.np > 1:
        cmd += [args.mpirun, "-np", str(args.np)]
    cmd += [args.lmp, "-in", os.path.basename(args.input), "-var", args.var, str(value),
            "-log", "log.lammps", "-screen", "none"]
    for spec in args.set or []:
        name, sep, val = spec.partition("=")
        if not sep:
            raise ValueError(f"--set takes NAME=VALUE, not '{spec}'")
        cmd += ["-var", name, val]
    if seed is not None:
        cmd += ["-var", args.seed_var, str(seed)]
    return subprocess.Popen(cmd, cwd=directory, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True), cmd


def analyse(args, runs):
    """{observable: [(value, error), ...]} in the order of the values, the
    window, and with --seeds each run's own {observable: [(value, error), ...]}
    in the order of runs (else None)."""
    from .dump import iter_dump
    from .logplot import parse_log

    tables = []
    for _, directory, _ in runs:
        log = os.path.join(directory, "log.lammps")
        tables.append(parse_log(log).combined())
    ends = [float(np.nanmax(t["time"])) for t in tables]
    if any(not math.isfinite(e) for e in ends):
        raise ValueError("a log has no time (thermo 'time' or a 'timestep' echo)")
    t0, t1 = args.window if args.window else (0.5 * min(ends), min(ends))
    if not t1 > t0:
        raise ValueError(f"empty window {t0:g}..{t1:g}")
    edges = np.linspace(t0, t1, args.blocks + 1)
    columns = args.thermo
    if columns is None:
        columns = [c for c in tables[0] if c not in SKIP and c != "time" and
                   all(c in t for t in tables)]
    results = {}
    for col in columns:
        row = []
        for t, (_, directory, _) in zip(tables, runs):
            if col not in t:
                raise KeyError(f"thermo column '{col}' is not in {directory}/log.lammps")
            row.append(block_estimate(piecewise_linear_means(t["time"], t[col], edges)))
        results[col] = row
    for atom_type, x in args.flux or []:
        atom_type = int(atom_type)
        name = f"flux of type {atom_type} through x = {x:g}"
        row = []
        for _, directory, _ in runs:
            path = os.path.join(directory, args.dump)
            if not os.path.exists(path):
                raise ValueError(f"{path} does not exist (--dump names the dump file the input writes)")
            flux, err, _ = section_flux(iter_dump(path), atom_type, x, t0, t1, args.blocks,
                                        args.dump_dt)
            row.append((flux, err))
        results[name] = row
    per_start = None
    if args.seeds:
        # runs are value-major: each value's starts are consecutive
        ns = len(args.seeds)
        per_start = results
        results = {name: [combine_starts(row[k * ns:(k + 1) * ns]) for k in range(len(args.values))]
                   for name, row in per_start.items()}
    return results, (t0, t1), per_start


def table_text(args, results, window, per_start=None):
    head = f"{args.var}: " + ", ".join(str(v) for v in args.values)
    if args.seeds:
        errors_from = (f"each value's {len(args.seeds)} starts ({args.seed_var} = "
                       f"{', '.join(str(s) for s in args.seeds)}) averaged, standard errors the "
                       f"larger of their spread's and of {args.blocks} blocks per run")
    else:
        errors_from = f"standard errors from {args.blocks} blocks"
    lines = [f"# tessera-tools converge {os.path.basename(args.input)}: {head}; time averages over "
             f"t = {window[0]:g}..{window[1]:g}, {errors_from}",
             "| observable | " + " | ".join(f"{args.var} = {v}" for v in args.values) +
             " | largest z vs finest | agrees |",
             "|---" * (len(args.values) + 3) + "|"]
    for name, row in results.items():
        values = [v for v, _ in row]
        errors = [e for _, e in row]
        zmax, ok = compare(values, errors)
        cells = [f"{v:.5g} +- {e:.2g}" for v, e in row]
        lines.append(f"| {name} | " + " | ".join(cells) + f" | {zmax:.2f} | {'yes' if ok else 'NO'} |")
    if args.seeds:
        lines += ["", "Each start on its own (time average +- block error):", "",
                  "| observable | " + f"{args.var} | " +
                  " | ".join(f"{args.seed_var} = {s}" for s in args.seeds) + " |",
                  "|---" * (len(args.seeds) + 2) + "|"]
        ns = len(args.seeds)
        for name, row in per_start.items():
            for k, v in enumerate(args.values):
                cells = [f"{m:.4g} +- {e:.2g}" for m, e in row[k * ns:(k + 1) * ns]]
                lines.append(f"| {name} | {v} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def plot(args, results, path):
    from .cli_common import _matplotlib

    _matplotlib()
    import matplotlib.pyplot as plt

    names = list(results)
    fig, axes = plt.subplots(len(names), 1, figsize=(5.5, 1.0 + 2.2 * len(names)), squeeze=False)
    xs = [float(v) for v in args.values]
    for ax, name in zip(axes[:, 0], names):
        vals = np.array([v for v, _ in results[name]])
        errs = np.array([e for _, e in results[name]])
        ax.axhspan(vals[-1] - Z_AGREE * errs[-1], vals[-1] + Z_AGREE * errs[-1], color="0.88", zorder=0)
        ax.errorbar(xs, vals, yerr=errs, fmt="o-", capsize=3, color="C0")
        if all(x > 0 for x in xs):
            ax.set_xscale("log")
        ax.set_ylabel(name, fontsize=8)
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel(args.var)
    fig.suptitle("values with standard errors; grey: finest run +- 2 errors", fontsize=9)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def cmd_converge(args):
    if args.halve:
        name, sep, val = args.halve.partition("=")
        if not sep or args.var or args.values:
            raise ValueError("give either --halve NAME=DT or --var NAME --values V1 V2 ...")
        args.var = name
        v = float(val)
        args.values = [repr(v), repr(v / 2), repr(v / 4)]
    if not args.var or not args.values or len(args.values) < 2:
        raise ValueError("name the variable and at least two values: --var NAME --values V1 V2 V3 "
                         "(or --halve NAME=DT for DT, DT/2, DT/4)")
    if args.flux and not args.dump:
        raise ValueError("--flux needs --dump (the name of the dump file the input writes)")
    if not os.path.isfile(args.input):
        raise OSError(f"input {args.input} does not exist")
    args.out = args.out or f"converge_{args.var}"
    runs = run_dirs(args)
    if not args.analyse_only:
        if not args.lmp:
            raise ValueError("no LAMMPS executable: give --lmp (e.g. build/lammps/tessera-lmp)")
        # each run starts in its own directory: a path relative to here would miss
        if os.sep in args.lmp:
            args.lmp = os.path.abspath(args.lmp)
        pending = []
        for value, directory, seed in runs:
            if args.reuse and finished(os.path.join(directory, "log.lammps")):
                continue
            pending.append((value, directory, seed))
        while pending:
            batch, pending = pending[:args.jobs], pending[args.jobs:]
            procs = [(launch(args, v, d, s), d) for v, d, s in batch]
            for (proc, cmd), d in procs:
                _, err = proc.communicate()
                if proc.returncode != 0:
                    raise RuntimeError(f"{' '.join(cmd)} failed in {d} (exit {proc.returncode}): "
                                       f"{err.strip()[-500:]}; see {d}/log.lammps")
    results, window, per_start = analyse(args, runs)
    text = table_text(args, results, window, per_start)
    sys.stdout.write(text)
    if args.table:
        os.makedirs(os.path.dirname(os.path.abspath(args.table)), exist_ok=True)
        with open(args.table, "w") as f:
            f.write(text)
    plot(args, results, args.plot or os.path.join(args.out, "converge.png"))


def add_commands(sub):
    """Add the converge command to the subparsers ``sub`` of tessera-tools."""
    p = sub.add_parser(
        "converge", help="run an input at dt, dt/2, dt/4 (or three tolerances) and compare observables",
        description="Run a LAMMPS input at several values of one variable (-var NAME VALUE; e.g. "
                    "the timestep, or the tolerance of fix brownian/heun ... adapt tol ${tol}), each in "
                    "OUT/NAME_VALUE/, then compare time averages of thermo columns and the flux of a "
                    "type through a section (from a dump with id type xu) over a window, with "
                    "standard errors from block averages.  An observable agrees when every run is "
                    "within two combined standard errors of the run at the smallest value.")
    p.add_argument("input", help="the LAMMPS input (files beside it are copied into each run's directory)")
    p.add_argument("--var", help="the input's variable to vary (an index variable the input defines)")
    p.add_argument("--values", nargs="+", help="its values, coarsest first, finest last")
    p.add_argument("--halve", metavar="NAME=DT", help="shorthand: --var NAME --values DT DT/2 DT/4")
    p.add_argument("--set", nargs="+", metavar="NAME=VALUE", help="other -var settings for every run")
    p.add_argument("--window", nargs=2, type=float, metavar=("T0", "T1"),
                   help="time window of the averages (default: the second half of the shortest run)")
    p.add_argument("--seeds", nargs="+", metavar="S",
                   help="run every value from several starts (-var SEED_VAR S each) and average "
                        "them; the errors include the spread between starts")
    p.add_argument("--seed-var", default="seed",
                   help="the input's variable that sets the start (default seed)")
    p.add_argument("--blocks", type=int, default=10, help="blocks of the error estimate (default 10)")
    p.add_argument("--thermo", nargs="+", metavar="COLUMN",
                   help="thermo columns to compare (default: every column but Step/Time/Dt/CPU)")
    p.add_argument("--flux", nargs=2, action="append", type=float, metavar=("TYPE", "X"),
                   help="the net flux of atoms of TYPE through x = X per unit time (repeatable)")
    p.add_argument("--dump", help="the dump file (id type xu ...) each run writes, for --flux")
    p.add_argument("--dump-dt", type=float,
                   help="timestep, for dumps without 'dump_modify time yes' (fixed timestep only)")
    p.add_argument("--lmp", default=os.environ.get("TESSERA_LMP") or shutil.which("tessera-lmp"),
                   help="LAMMPS executable (default $TESSERA_LMP, else tessera-lmp on PATH)")
    p.add_argument("--np", type=int, default=1, help="MPI ranks per run (default 1)")
    p.add_argument("--mpirun", default="mpirun", help="MPI launcher for --np > 1")
    p.add_argument("--jobs", type=int, default=1, help="runs at a time (default 1)")
    p.add_argument("--out", help="directory of the runs (default converge_NAME)")
    p.add_argument("--reuse", action="store_true", help="keep runs whose log.lammps is complete")
    p.add_argument("--analyse-only", action="store_true",
                   help="run nothing: analyse the runs already in OUT")
    p.add_argument("--table", help="also write the table to this file")
    p.add_argument("--plot", help="picture (PNG; default OUT/converge.png)")
    p.set_defaults(func=cmd_converge)
