# SPDX-License-Identifier: GPL-2.0-or-later
"""Command line: ``tessera-tools {info,render,vtk,traj,log} ...`` (each has --help)."""

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
    if args.local:
        from .junctions import contact_lengths, junction_columns, paired_frames
        from .measure import demix_series

        atoms, local = paired_frames(args.dump, args.local)[-1]
        contacts = contact_lengths(atoms, local)
        print(f"timestep {atoms.timestep}: junction length by type pair "
              + ", ".join(f"{a}-{b} {v:.6g}" for (a, b), v in sorted(contacts.items()))
              + (" (face area, area units)" if len(junction_columns(local)) == 9 else " (length units)"))
        steps, times, frac, het, tot = demix_series(args.dump, args.local)
        print(f"heterotypic junction fraction, {len(steps)} frame(s) both dumps hold:")
        print("# timestep " + ("time " if times is not None else "") + "fraction heterotypic_length total_length")
        for k in range(len(steps)):
            t = f"{times[k]:.10g} " if times is not None else ""
            print(f"{steps[k]} {t}{frac[k]:.6f} {het[k]:.8g} {tot[k]:.8g}")
    if args.stats:
        if args.local:
            from .junctions import junction_columns, junction_tessellation, paired_frames
            from .vtk import frame_cells3d

            atoms, local = paired_frames(args.dump, args.local)[-1]
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
        if not (last.box.periodic[0] and last.box.periodic[1]):
            raise SystemExit(f"tessera-tools info: {args.dump}: --stats re-tessellates the centres, which "
                             "needs a box periodic in x and y; for this box give the cells LAMMPS "
                             "computed with --local (a dump local of compute vertex/local)")
        from .voronoi import tessellate_frame

        tess = tessellate_frame(last)
        print(f"last frame: mean area {tess.area.mean():.6g} (box area / N = {last.box.area / last.natoms:.6g}), "
              f"mean shape index {tess.shape_index.mean():.6g}, sides {np.bincount(tess.sides).tolist()}")


def _progress(enabled=True):
    """tqdm progress bars on stderr when tqdm is installed (Debian: python3-tqdm) and wanted."""
    if not enabled:
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    return lambda it, desc=None, **kw: tqdm(it, desc=desc, unit="frame", leave=False, **kw)


def _local_frames(args):
    """(atom frames, tessellations) of the frames selected by --frame/--timestep/--frames that
    both the atom dump and the --local dump hold, cells from the local dump's polygons."""
    from .junctions import junction_tessellation, paired_frames

    pairs = paired_frames(args.dump, args.local)
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
        frames = _select_frames(args.dump, args.frames)
    else:
        frames = [read_frame(args.dump, index=args.frame, timestep=args.timestep)]
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
    from .vtk import write_vtk

    try:
        written = write_vtk(args.dump, args.output, local_path=args.local, frames=args.frames or slice(None),
                            dt=args.dt, compute=args.junction_compute, progress=_progress(not args.quiet),
                            radius=args.radius)
    except (RuntimeError, ValueError, KeyError) as err:
        raise SystemExit(f"tessera-tools vtk: {err.args[0] if err.args else err}") from None
    source = ("the cells of " + args.local if args.local else
              f"the finite Voronoi cells (radius {args.radius:g}) of the centres" if args.radius else
              "the Voronoi tessellation of the centres")
    print(f"wrote {len(written)} frame(s) from {source}: {written[0]}" +
          (f" .. {written[-1]}" if len(written) > 1 else "") +
          f"; time series {args.output}.pvd and {args.output}.vtu.series")


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


def _seed_paths(pattern, seeds, first, option):
    """The file of each seed: ``pattern`` with {seed} replaced by first .. first+seeds-1."""
    if seeds is None:
        return [pattern]
    if "{seed}" not in pattern:
        raise SystemExit(f"tessera-tools moduli: --seeds {seeds} needs '{{seed}}' in {option} "
                         f"(got '{pattern}'), e.g. 'seed{{seed}}/minimised.dump' for seed1/, seed2/, ...")
    return [pattern.replace("{seed}", str(s)) for s in range(first, first + seeds)]


def _pm(value, err):
    """'value +- err', err omitted when it is not a number."""
    if err is None or not np.isfinite(err):
        return f"{value:.8g}"
    return f"{value:.8g} +- {err:.2g}"


def _moduli_table(args, states, ref, ref_name):
    """Append one row per route (Hessian, quasistatic) to args.table (CSV, reduced units)."""
    import csv
    import os

    from .moduli import seed_average

    if args.quadratic:
        p0 = args.quadratic[3] / math.sqrt(args.quadratic[1])
    else:
        w = 0.5 if args.tension == "edge" else 1.0
        p0 = -w * args.coeff[3] / args.coeff[2] / math.sqrt(args.coeff[1])
    rows = []
    hs = [s["hessian"] for s in states if s["hessian"] is not None]
    if hs:
        row = dict(p0=p0, route="hessian", states=len(hs))
        for key in ("G", "B", "E", "nu"):
            mean, err = seed_average([h[key] for h in hs])
            scale = 1.0 if key == "nu" else ref
            row[key], row[key + "_err"] = mean / scale, err / scale
        rows.append(row)
    qs = [s["qs"] for s in states if s["qs"] is not None]
    if qs:
        row = dict(p0=p0, route="quasistatic", states=len(qs))
        if len(qs) == 1:
            q = qs[0]
            for key in ("G", "B", "E", "nu"):
                scale = 1.0 if key == "nu" else ref
                row[key], row[key + "_err"] = q[key] / scale, q[key + "_err"] / scale
        else:
            for key in ("G", "B", "E", "nu"):
                mean, err = seed_average([q[key] for q in qs])
                scale = 1.0 if key == "nu" else ref
                row[key], row[key + "_err"] = mean / scale, err / scale
        rows.append(row)
    fields = ["p0", "route", "states", "G", "G_err", "B", "B_err", "E", "E_err", "nu", "nu_err", "unit"]
    new = not os.path.exists(args.table) or os.path.getsize(args.table) == 0
    with open(args.table, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        if new:
            w.writeheader()
        for row in rows:
            row["unit"] = ref_name
            w.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in row.items()})
    print(f"appended {len(rows)} row(s) to {args.table} (moduli in {ref_name}; errors: "
          + ("standard errors over the states)" if len(states) > 1 else "fit errors, none for one Hessian state)"))


def _other_energy(m, fnorm_max):
    """The error when the dump's own forces (fx fy) vanish but those of the energy given here do
    not: the run minimised another energy, so G and B of this one are not its moduli."""
    if "dump_fnorm" not in m or m["dump_fnorm"] > fnorm_max:
        return None
    missing = [c for c in ("d_area0", "d_ka", "d_kp", "d_perim0") if c not in m["cells"]]
    return (f"the dump's own forces (fx fy) have fnorm {m['dump_fnorm']:.3g}, a minimum, but the energy "
            f"given here has fnorm {m['fnorm']:.3g} there (forces differ by up to {m['force_mismatch']:.3g}): "
            "the run's energy is not this one, so its moduli would be wrong. Give the run's pair_coeff values "
            "(--coeff or --quadratic, --tension) and dump the per-cell properties the run defines"
            + (f" (of {' '.join(missing)})" if missing else "")
            + " with the state; positions written with fewer digits than 'format float %.17g' also "
              "shift the forces")


def _fnorm_cause(m):
    """The likely cause of a large fnorm at a Hessian state, in words."""
    tail = "so G and B are not its moduli"
    if "dump_fnorm" in m:
        return (f"not an energy minimum (the dump's own forces fx fy have fnorm {m['dump_fnorm']:.3g} too), "
                f"{tail}; minimise further (smaller ftol, min_style fire) or raise --fnorm-max")
    missing = [c for c in ("d_area0", "d_ka", "d_kp", "d_perim0") if c not in m["cells"]]
    return (f"not an energy minimum for the energy given here, {tail}. Either the state is not minimised (minimise "
            "further: smaller ftol, min_style fire) or the run's energy differs from this one: other "
            "pair_coeff values than --coeff/--quadratic, or per-cell parameters the dump does not carry"
            + (f" ({' '.join(missing)})" if missing else "")
            + "; dump fx fy with the state to tell which, or raise --fnorm-max")


def cmd_moduli(args):
    from .dump import read_dump
    from .moduli import Model, fit_quasistatic, frame_moduli, seed_average

    if args.seeds is not None and args.seeds < 1:
        raise SystemExit(f"tessera-tools moduli: --seeds {args.seeds}: give the number of states, 1 or more")
    dumps = _seed_paths(args.dump, args.seeds, args.first_seed, "the dump name")
    qs_files = _seed_paths(args.quasistatic, args.seeds, args.first_seed, "--quasistatic") if args.quasistatic else None
    if args.quadratic:
        ka, a0 = args.quadratic[0], args.quadratic[1]
        model = Model.quadratic(*args.quadratic, tension=args.tension)
        ref, ref_name = ka * a0, "KA A0"     # KA of KA (A - A0)^2
    else:
        ka, a0 = args.coeff[0], args.coeff[1]
        model = Model(*([v] for v in args.coeff[:3]), args.coeff[3], tension=args.tension)
        ref, ref_name = ka * a0, "K A0"      # K of K/2 (A - A0)^2
    if ref <= 0:
        raise SystemExit(f"tessera-tools moduli: the area stiffness times A0 is {ref:g}; it must be positive")

    states = []
    for k, path in enumerate(dumps):
        frame = read_dump(path)[args.frame]
        state = dict(path=path, frame=frame, hessian=None, qs=None)
        try:
            state["hessian"] = frame_moduli(frame, model, exe=args.exe)
        except (RuntimeError, FileNotFoundError) as err:
            if not qs_files or isinstance(err, FileNotFoundError) and args.exe:
                if isinstance(err, FileNotFoundError):
                    raise
                raise SystemExit(f"tessera-tools moduli: {path}: {err}\n"
                                 "The exact Hessian does not exist at this state. Give the strain steps of "
                                 "examples/moduli/in.moduli with --quasistatic qs.dat: their slopes are the "
                                 "moduli (doc/howto_moduli.md)") from None
            state["hessian_error"] = str(err)
        if qs_files:
            state["qs"] = fit_quasistatic(qs_files[k])
            state["qs_path"] = qs_files[k]
        states.append(state)

    units = states[0]["frame"].units
    where = f"LAMMPS 'units {units}'" if units else "the LAMMPS units of the run (the dump does not name them)"
    print(f"units: moduli, pressure and stress in energy/length^2 of {where}; energies in energy, areas in "
          f"length^2. In the model's reduced units (energy {ref_name}^2, length sqrt(A0), so moduli in "
          f"{ref_name}) they are the values divided by {ref_name} = {ref:g}")

    def red(value, err=None):
        """value (+- err) in the input's units, then in units of KA A0."""
        if ref == 1:
            return f"{_pm(value, err)} energy/length^2 (= {ref_name})"
        e = None if err is None else err / ref
        return f"{_pm(value, err)} energy/length^2 = {_pm(value / ref, e)} {ref_name}"

    bad = []
    for s in states:
        label = s["path"]
        m = s["hessian"]
        if m is not None:
            print(f"{label}: {m['n']} cells, area {m['area']:.10g} length^2, energy {m['energy']:.12g} energy, "
                  f"fnorm {m['fnorm']:.3g} energy/length (max |force| {m['max_force']:.3g})")
            print(f"  Hessian: G = {red(m['G'])}, B = {red(m['B'])} (affine G {m['G_affine']:.8g}, "
                  f"B {m['B_affine']:.8g} energy/length^2)")
            print(f"  E = {red(m['E'])}, nu = {m['nu']:.8g} (dimensionless); pressure {m['pressure']:.8g}, "
                  f"shear stress {m['shear_stress']:.8g} energy/length^2")
            if "eigenvalues" in m:
                print(f"  spectrum: {m['zero_modes']} zero modes (2 are translations), {m['negative_modes']} "
                      f"negative, lowest non-zero eigenvalue {m['lowest_nonzero']:.6g} energy/length^2 per mass")
            if m["cells"]:
                print(f"  per-cell parameters from the dump: {' '.join(m['cells'])} (they replace the types' "
                      "values, as in pair vertex/voronoi)")
            if m["fnorm"] > args.fnorm_max:
                other = _other_energy(m, args.fnorm_max)
                if other:
                    raise SystemExit(f"tessera-tools moduli: {label}: {other}")
                bad.append(f"{label}: fnorm {m['fnorm']:.3g} > {args.fnorm_max:g}: " + _fnorm_cause(m))
        else:
            print(f"{label}: no Hessian ({s['hessian_error'].splitlines()[0][:160]}); quasistatic route only")
        q = s["qs"]
        if q is not None:
            print(f"  quasistatic ({s['qs_path']}, fit errors): G = {red(q['G'], q['G_err'])}, "
                  f"B = {red(q['B'], q['B_err'])}")
            print(f"  quasistatic: E = {red(q['E'], q['E_err'])}, nu = {_pm(q['nu'], q['nu_err'])} (dimensionless); "
                  f"largest fnorm of the steps {q['fnorm']:.3g} energy/length")
            if q["fnorm"] > args.fnorm_max:
                bad.append(f"{s['qs_path']}: fnorm {q['fnorm']:.3g} > {args.fnorm_max:g} in a strain step")
        if m is not None and args.spectrum and "eigenvalues" in m:
            path = args.spectrum if len(states) == 1 else f"{args.spectrum}.{states.index(s) + args.first_seed}"
            np.savetxt(path, m["eigenvalues"], fmt="%.12e",
                       header="eigenvalues of the Hessian d2E/dr dr (squared angular frequencies at unit mass), "
                              "energy/length^2 per mass")
            print(f"  wrote {path}")

    if len(states) > 1:
        n = len(states)
        print(f"over {n} states (mean +- standard error of the mean, sample std / sqrt(n)):")
        hs = [s["hessian"] for s in states if s["hessian"] is not None]
        if hs:
            parts = []
            for key in ("G", "B", "E"):
                mean, err = seed_average([h[key] for h in hs])
                parts.append(f"{key} = {red(mean, err)}")
            mean, err = seed_average([h["nu"] for h in hs])
            parts.append(f"nu = {_pm(mean, err)}")
            print(f"  Hessian ({len(hs)} of {n} states): " + ", ".join(parts))
        qs = [s["qs"] for s in states if s["qs"] is not None]
        if qs:
            parts = []
            for key in ("G", "B", "E"):
                mean, err = seed_average([q[key] for q in qs])
                fit = float(np.sqrt(np.sum([q[key + "_err"] ** 2 for q in qs]))) / len(qs)
                parts.append(f"{key} = {red(mean, err)} (fit error of the mean {fit / ref:.2g} {ref_name})")
            mean, err = seed_average([q["nu"] for q in qs])
            parts.append(f"nu = {_pm(mean, err)}")
            print(f"  quasistatic ({len(qs)} states): " + ", ".join(parts))
    elif states[0]["hessian"] is not None:
        print("  (the Hessian values are exact for this state; --seeds N gives error bars over N states)")
    if args.table:
        _moduli_table(args, states, ref, ref_name)
    for line in bad:
        print(f"warning: {line}", file=sys.stderr)
    for s in states:
        if s["hessian"] is None:
            print(f"warning: {s['path']}: no Hessian route ({s['hessian_error'].splitlines()[0][:160]}); "
                  "the moduli above are the quasistatic slopes", file=sys.stderr)


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
        steps, t, y = frame_series(args.input, value, dt=args.dt, radius=args.radius)
        known = _dump_time_label(args.input, args.dt)
        what = "open area (box minus cells)" if value == "open" else value
    else:
        if not args.column:
            raise SystemExit("tessera-tools plot wound: for a log name the thermo column with -c, e.g. -c v_wound "
                             "(see 'tessera-tools log LOG --list')")
        t, y, known = _log_series(args.input, args.column, args.x)
        what = args.column
    half = half_time(t, y, args.fraction)
    ylabel = args.ylabel or (r"wound area ($A_0$)" if not args.column and (args.value or "open") == "open"
                             else what)
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
        _, t, n = frame_series(args.input, "count", dt=args.dt)
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

    frames = _select_frames(args.dump, args.frames or slice(-1, None))
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
    from .dump import iter_dump
    from .measure import demix_series
    from .plots import TIME, STEP, plot_demix

    steps, times, frac, het, tot = demix_series(args.dump, args.local)
    known = times is not None or bool(args.dt)
    t = times if times is not None else steps * (args.dt or 1.0)
    first = next(iter_dump(args.dump))
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


def cmd_env(args):
    """Shell lines that let any python3 import tessera_tools and find Tessera's build."""
    import os
    import shlex

    tools = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    repo = os.path.dirname(tools)
    build = os.environ.get("TESSERA_BUILD") or os.path.join(repo, "build")
    lines = []
    if os.path.isfile(os.path.join(tools, "tessera-tools")):     # a source tree, not an installed copy
        lines.append(f'export PYTHONPATH={shlex.quote(tools)}"${{PYTHONPATH:+:$PYTHONPATH}}"')
        lines.append(f'export PATH={shlex.quote(tools)}":$PATH"')
    if os.path.isdir(os.path.join(build, "lammps")):
        lines.append(f"export TESSERA_BUILD={shlex.quote(build)}")
        lines.append(f'export PATH={shlex.quote(os.path.join(build, "lammps"))}":$PATH"')
    else:
        print(f"# no build found at {build}: run scripts/build in the repository, or set TESSERA_BUILD",
              file=sys.stderr)
    print("\n".join(lines))


def build_parser():
    p = argparse.ArgumentParser(
        prog="tessera-tools",
        description="Post-processing for Tessera (active Voronoi vertex model in LAMMPS): "
                    "tessellation pictures, VTK polygon files, trajectory plots, thermo plots.")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True

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
    mo = sub.add_parser("moduli", help="elastic moduli and vibrational spectrum of a minimised tissue (exact Hessian)",
                        description="Shear, bulk and Young's modulus, Poisson's ratio and the Hessian's spectrum of "
                                    "an energy-minimised periodic configuration, from the exact Hessian "
                                    "(tessera-hessian); see doc/howto_moduli.md.")
    mo.add_argument("dump", help="LAMMPS dump with x y (and type) at full precision, e.g. write_dump ... format "
                                 "float %%.17g; with --seeds a pattern with {seed}, e.g. 'seed{seed}/minimised.dump'")
    mo.add_argument("--frame", type=int, default=-1, help="frame index (default: the last)")
    mp = mo.add_mutually_exclusive_group(required=True)
    mp.add_argument("--quadratic", type=float, nargs=4, metavar=("KA", "A0", "KP", "P0"),
                    help="one cell type, pair_coeff * * quadratic KA A0 KP P0")
    mp.add_argument("--coeff", type=float, nargs=4, metavar=("K", "A0", "GAMMA", "LAMBDA"),
                    help="one cell type, pair_coeff * * K A0 Gamma Lambda")
    mo.add_argument("--tension", choices=("edge", "cell"), default="edge", help="pair_style's tension (default edge)")
    mo.add_argument("--quasistatic", metavar="QS.DAT",
                    help="also fit the strain steps of examples/moduli/in.moduli (its qs.dat; with --seeds a "
                         "pattern with {seed}); this route also works where the Hessian does not exist "
                         "(multifold vertices)")
    mo.add_argument("--seeds", type=int, metavar="N",
                    help="average over N independent states: the dump (and --quasistatic) names hold {seed}, "
                         "replaced by 1..N (see --first-seed); error bars are standard errors over the states")
    mo.add_argument("--table", metavar="CSV",
                    help="append p0, G, B, E, nu with errors (in KA A0 or K A0) to this CSV, one row per route; "
                         "'tessera-tools plot moduli CSV' draws G and B against p0")
    mo.add_argument("--first-seed", type=int, default=1, metavar="S", help="first seed for --seeds (default 1)")
    mo.add_argument("--fnorm-max", type=float, default=1e-6, metavar="F",
                    help="warn when the force norm (LAMMPS fnorm) of a state or strain step exceeds F "
                         "(default 1e-6)")
    mo.add_argument("--spectrum", help="write the eigenvalues of the Hessian to this file")
    mo.add_argument("--exe", help="tessera-hessian executable (default: $TESSERA_HESSIAN, else build/core/ of the "
                         "repository, else PATH)")
    mo.set_defaults(func=cmd_moduli)

    en = sub.add_parser("env", help="shell settings for running from anywhere (eval \"$(tessera-tools env)\")",
                        description="Print export lines: PYTHONPATH (this tools/ directory, so any python3 can "
                                    "import tessera_tools, e.g. the Python examples copied elsewhere), "
                                    "TESSERA_BUILD (where libtessera_lammps.so and tessera-hessian are) and PATH "
                                    "(tessera-tools, tessera-lmp).")
    en.set_defaults(func=cmd_env)

    pl = sub.add_parser("plot", help="measurement figures: wound area, growth N(t), shapes, demixing, moduli vs p0",
                        description="One figure per command, print quality (300 dpi, --vector pdf for a vector "
                                    "copy), axes in the model's reduced units. See doc/howto_measure.md.")
    psub = pl.add_subparsers(dest="what", metavar="WHAT")
    psub.required = True

    def common(p):
        p.add_argument("-o", "--output", required=True, help="picture (.png, .pdf, .svg)")
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
    pw.add_argument("--value", help="dump: per-frame value: open (default with --radius), sum:COL, mean:COL, count")
    pw.add_argument("--dt", type=float, help="dump: timestep size (time = timestep x dt; else the dump's TIME)")
    pw.add_argument("--x", choices=("auto", "step"), default="auto", help="log: time (default) or step")
    pw.add_argument("--fraction", type=float, default=0.5,
                    help="report when the value falls to this fraction of its first value (default 0.5)")
    pw.add_argument("--ylabel")
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
    common(pd)
    pd.set_defaults(func=cmd_plot_demix)

    pm = psub.add_parser("moduli", help="G and B against p0 with error bars",
                         description="From tables written by 'tessera-tools moduli ... --table FILE' (one run "
                                     "per p0, e.g. with --seeds N).")
    pm.add_argument("tables", nargs="+", help="CSV table(s) of tessera-tools moduli --table")
    pm.add_argument("--route", choices=("hessian", "quasistatic", "both"), default="both")
    common(pm)
    pm.set_defaults(func=cmd_plot_moduli)
    return p


def main(argv=None):
    args = build_parser().parse_args(argv)
    try:
        args.func(args)
    except (OSError, KeyError, ValueError, RuntimeError) as err:
        msg = err.args[0] if isinstance(err, KeyError) and err.args else err
        what = args.command + (" " + args.what if getattr(args, "what", None) else "")
        print(f"tessera-tools {what}: {msg}", file=sys.stderr)
        return 1
    return 0
