# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools moduli: elastic moduli of a minimised tissue (exact Hessian and strain steps)."""

import math
import sys

import numpy as np

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


def _types_text(types, sep=", "):
    """'1, 3' (or with sep ',': '1,3', as --cell-types takes them) or '2*' for a list of types
    (ints, or (lo, None) for lo and above)."""
    return sep.join(f"{t[0]}*" if isinstance(t, tuple) else str(t)
                     for t in sorted(types, key=lambda t: t[0] if isinstance(t, tuple) else t))


def _cells_and_particles(path, frame, cell_types, option):
    """Check which atoms of ``frame`` are cells for the one parameter set of ``option``
    (--quadratic or --coeff) and return the particles left out (a Frame) or None.

    Without --cell-types every atom is a cell, so atoms of several types are refused with the
    fix: particles (types without cell parameters) are left out with --cell-types.  With it,
    ``frame`` holds the cells (read_dump split them) and ``frame.particles`` the other atoms."""
    if "type" not in frame:
        return None
    if cell_types is None:
        present = sorted(set(np.asarray(frame["type"]).astype(int).tolist()))
        if len(present) > 1:
            counts = np.unique(np.asarray(frame["type"]).astype(int), return_counts=True)[1]
            listed = ", ".join(f"type {t} ({c} atoms)" for t, c in zip(present, counts))
            others = _types_text(present[1:])
            raise SystemExit(
                f"tessera-tools moduli: {path}: the dump has atoms of several types ({listed}) and {option} "
                f"gives the parameters of one cell type. If the atoms of type {others} are no cells (particles under "
                f"pair_style hybrid/overlay, without 'pair_coeff I I vertex/voronoi' cell parameters), give "
                f"--cell-types {present[0]} to leave them out; if all are cells with these parameters, give "
                f"--cell-types {_types_text(present, ',')}; cells with several parameter sets need the Python API "
                "(tessera_tools.moduli.run_hessian with a Model of several types, doc/howto_moduli.md)")
        return None
    particles = getattr(frame, "particles", None)
    if len(frame) == 0:
        ptypes = sorted(set(np.asarray(particles["type"]).astype(int).tolist())) if particles else []
        raise SystemExit(f"tessera-tools moduli: {path}: --cell-types {_types_text(cell_types, ',')}: no atom of the "
                         f"dump has these types (it has types {_types_text(ptypes)}); give the types that have "
                         "cell parameters in 'pair_coeff I I vertex/voronoi'")
    if particles is None or len(particles) == 0:
        return None
    return particles


def _particles_note(particles):
    ptypes = _types_text(sorted(set(np.asarray(particles["type"]).astype(int).tolist())))
    return f"{len(particles)} atom(s) of type {ptypes}"


def _particle_contact(m, particles, path, fnorm_max):
    """With particles left out, the Hessian route has the cells' vertex energy only.  When the
    dump's forces on the cells differ from that energy's, something else (the particles' pair
    style) pushes on them, and its stiffness is missing too: the error to stop with, or None."""
    if m.get("force_mismatch") is None or m["force_mismatch"] <= fnorm_max:
        return None
    return (f"{path}: the dump's forces on the cells (fx fy) differ from those of the cells' vertex energy by up "
            f"to {m['force_mismatch']:.3g} (> --fnorm-max {fnorm_max:g}): the particles left out "
            f"({_particles_note(particles)}) push on the cells through their pair style, whose stiffness the "
            "Hessian of the cells leaves out, so its G and B would not be the moduli of this state. Measure "
            "them with the strain steps of examples/moduli/in.moduli run with the particles (LAMMPS's stress "
            "includes every pair style) and give their qs.dat with --quasistatic")


def _written_energy(args, frame, m):
    """The cells' energy as LAMMPS's pe has it (doc/model.md, "The written energy") and what it
    holds, in words.  tessera-hessian's energy is the expanded form without the constant
    KP P0^2 per cell that completes the square of --quadratic; LAMMPS adds it (from each
    cell's own KP and P0 when the dump has d_kp / d_perim0), so it is added here too."""
    if args.quadratic:
        n = m["n"]
        kp = np.asarray(frame["d_kp"], dtype=float) if "d_kp" in frame else np.full(n, args.quadratic[2])
        p0 = np.asarray(frame["d_perim0"], dtype=float) if "d_perim0" in frame else np.full(n, args.quadratic[3])
        constant = float(np.sum(kp * p0 ** 2))
        own = [c for c in ("d_kp", "d_perim0") if c in frame]
        what = (f"the written energy sum KA (A - A0)^2 + KP (P - P0)^2, as LAMMPS's pe with 'thermo_modify norm "
                f"no' (per cell: pe with norm yes, the lj default); it includes the constant sum KP P0^2 = "
                f"{constant:.12g}" + (f" (each cell's own {' and '.join(own)})" if own else "")
                + f" of the squares, without it {m['energy']:.12g}")
        energy = m["energy"] + constant
    else:
        energy = m["energy"]
        what = ("the written energy of the thesis form (K A0 Gamma Lambda has no constant), as LAMMPS's pe with "
                "'thermo_modify norm no' (per cell: pe with norm yes, the lj default)")
    if m.get("particles"):
        what += "; the cells' vertex energy only: pe also holds the particles' pair styles"
    return energy, what


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

    option = "--quadratic" if args.quadratic else "--coeff"
    states = []
    for k, path in enumerate(dumps):
        frame = read_dump(path, cell_types=args.cell_types)[args.frame]
        particles = _cells_and_particles(path, frame, args.cell_types, option)
        state = dict(path=path, frame=frame, hessian=None, qs=None, particles=particles)
        try:
            state["hessian"] = frame_moduli(frame, model, exe=args.exe, use_types=False)
            state["hessian"]["particles"] = particles is not None
            contact = particles is not None and _particle_contact(state["hessian"], particles, path,
                                                                  args.fnorm_max)
            if contact:
                state["hessian"] = None
                if not qs_files:
                    raise SystemExit(f"tessera-tools moduli: {contact}")
                state["hessian_error"] = contact
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
            energy, note = _written_energy(args, s["frame"], m)
            print(f"{label}: {m['n']} cells, area {m['area']:.10g} length^2, energy {energy:.12g} energy "
                  f"({energy / m['n']:.12g} per cell), fnorm {m['fnorm']:.3g} energy/length (max |force| "
                  f"{m['max_force']:.3g})")
            print(f"  energy: {note}")
            print(f"  Hessian: G = {red(m['G'])}, B = {red(m['B'])} (affine G {m['G_affine']:.8g}, "
                  f"B {m['B_affine']:.8g} energy/length^2)")
            print(f"  E = {red(m['E'])}, nu = {m['nu']:.8g} (dimensionless); pressure {m['pressure']:.8g}, "
                  f"shear stress {m['shear_stress']:.8g} energy/length^2")
            if "eigenvalues" in m:
                print(f"  spectrum: {m['zero_modes']} zero modes (2 are translations), {m['negative_modes']} "
                      f"negative, lowest non-zero eigenvalue {m['lowest_nonzero']:.6g} energy/length^2 per mass")
            if s["particles"] is not None:
                checked = ("the dump's forces on the cells are those of their vertex energy: no particle "
                           "pushes on a cell" if "force_mismatch" in m else
                           "dump fx fy with the state to check that no particle pushes on a cell")
                print(f"  cells: {m['n']} atoms of --cell-types {_types_text(args.cell_types, ',')}; left out "
                      f"{_particles_note(s['particles'])}, no cells: G and B are those of the cells' vertex "
                      f"energy alone, without the particles' pair styles ({checked})")
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


def add_commands(sub):
    """Add this module's commands to the subparsers ``sub`` of tessera-tools."""
    from .cli_frames import CELL_TYPES_HELP, _types

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
    mo.add_argument("--cell-types", type=_types, metavar="TYPES",
                    help=CELL_TYPES_HELP + ". The cells take the parameters of --quadratic/--coeff; the Hessian "
                         "route then has the cells' vertex energy only, and stops if the dump's forces show "
                         "particles pushing on cells (measure those states with --quasistatic)")
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
