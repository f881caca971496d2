#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""LAMMPS's force-style test stages (its unittest/force-styles pair-style tester) for
pair_style vertex/voronoi, as input scripts that any lmp runs: tessera-lmp (LAMMPS
29 Sep 2021), a current LAMMPS with tesseraplugin.so, or one with the TESSERA package
compiled in.  One YAML file per model in tests/lammps/force-styles/, in LAMMPS's
schema (the file LAMMPS's own tester reads), holds the references.

The stages, in the tester's order and with its commands:
  init     the input file, pair_style, pair_coeff, `run 0`; write_restart, write_data,
           write_coeff
  run      compute pe/atom, its sum, fix nve, `run 4`
  restart  clear, newton on, read_restart, pair_coeff again (the style writes no
           coefficients to data files), `run 0`: the init references
  nofdotr  the same with `pair_modify nofdotr`: the virial without f dot r
  data     clear, the input file with the written data file, `run 0`
  reissue  pair_style and pair_coeff given again to the same style, `run 0`
Each stage records the pair energy, the sum of compute pe/atom, the six virial
components of the pair style (compute pressure NULL pair times the volume) and every
atom's force.

A reference that only recorded today's output could not fail, so every YAML file is
checked against the energy itself: each force against central differences of the
energy in that atom's coordinates, and each virial component against central
differences of the energy under a homogeneous strain (of the box and the atoms in
periodic directions, of the atoms alone about a centre otherwise).  The generator
(`main`, below) checks every atom and component before it writes a file; the test
(test_force_styles.py) checks a few each time.

Regenerate the references (after a deliberate change of the model):
    /usr/bin/python3 tests/lammps/force_styles.py --lmp build/lammps/tessera-lmp [model ...]
(--new-data draws the configuration again from its seed: data.vertex_<model>).
"""

import argparse
import datetime
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
FORCE_DIR = os.path.join(HERE, "force-styles")
INPUT_FILE = "in.vertex"

# LAMMPS's key order (the tester's YAML writer); the values of pair styles only.
KEYS = ("lammps_version", "date_generated", "epsilon", "prerequisites", "pre_commands",
        "post_commands", "input_file", "pair_style", "pair_coeff", "extract", "natoms",
        "init_vdwl", "init_coul", "init_stress", "init_forces", "run_vdwl", "run_coul",
        "run_stress", "run_forces")
BLOCKS = {"prerequisites", "pre_commands", "post_commands", "pair_coeff", "extract",
          "init_stress", "init_forces", "run_stress", "run_forces"}
STRESS = ("xx", "yy", "zz", "xy", "xz", "yz")

# Central differences: step (length units, or strain) and the largest difference
# from the stored value they accept (energy units per length; the forces and virials
# of these systems are of order 0.01 to 10).  Truncation (h^2 E''') and rounding
# (1e-16 E / h) both stay below 1e-8 here.
FD_STEP = 1e-5
FD_TOL = 2e-7


def models():
    """The models with a YAML file: {name: path}."""
    return {f[len("vertex_"):-len(".yaml")]: os.path.join(FORCE_DIR, f)
            for f in sorted(os.listdir(FORCE_DIR))
            if f.startswith("vertex_") and f.endswith(".yaml")}


# ---------------------------------------------------------------------------
# YAML in LAMMPS's form: `key: value` or `key: ! |` with an indented block

def read_yaml(path):
    """{key: str}; a block's lines without their two-space indent."""
    cfg, key, lines = {}, None, []
    with open(path) as f:
        text = f.read().split("\n")
    for line in text:
        if line in ("---", "...") or (key is None and not line.strip()):
            continue
        m = re.match(r"^(\w+):\s?(.*)$", line)
        if m and not line.startswith(" "):
            if key is not None:
                cfg[key] = "\n".join(lines)
            key, value = m.group(1), m.group(2)
            if value.startswith("! |") or value.startswith("! \"\""):
                lines = []
                if value.startswith("! \"\""):
                    cfg[key] = ""
                    key = None
            else:
                cfg[key] = value
                key = None
            continue
        if key is not None:
            lines.append(line[2:] if line.startswith("  ") else line.strip())
    if key is not None:
        cfg[key] = "\n".join(lines)
    for k in list(cfg):
        if k in BLOCKS:
            cfg[k] = "\n".join(l for l in cfg[k].split("\n") if l.strip())
    return cfg


def write_yaml(path, cfg):
    out = ["---"]
    for key in KEYS:
        value = cfg[key]
        if key in BLOCKS:
            lines = [l for l in str(value).split("\n") if l.strip()]
            if not lines:
                out.append('%s: ! ""' % key)
                continue
            # a block whose first line starts with a space needs the indent given
            head = "! |2" if lines[0].startswith(" ") else "! |"
            if key.endswith("_stress"):
                head += "-"
            out.append("%s: %s" % (key, head))
            out += ["  " + l for l in lines]
        else:
            out.append("%s: %s" % (key, value))
    out.append("...")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def format_stress(w):
    w = [0.0 if abs(v) < 1e-13 else v for v in w]    # as LAMMPS's generator
    return " ".join("%23.16e" % v for v in w)


def format_forces(ids, f):
    return "\n".join("%3d %23.16e %23.16e %23.16e" % (i, *row) for i, row in zip(ids, f))


def parse_stress(block):
    return np.array([float(w) for w in block.split()])


def parse_forces(block):
    """(ids, n x 3 array), sorted by ID."""
    rows = [l.split() for l in block.split("\n") if l.strip()]
    rows.sort(key=lambda r: int(r[0]))
    return (np.array([int(r[0]) for r in rows]),
            np.array([[float(w) for w in r[1:4]] for r in rows]))


def lines(block):
    return [l for l in block.split("\n") if l.strip()]


def fp_error(a, b):
    """LAMMPS's tester's measure (EXPECT_FP_LE_WITH_EPS): the difference relative to
    the smaller magnitude, or absolute where either value is zero."""
    a, b = np.broadcast_arrays(np.asarray(a, float), np.asarray(b, float))
    diff = np.abs(a - b)
    div = np.minimum(np.abs(a), np.abs(b))
    return np.where(div == 0.0, diff, diff / np.where(div == 0.0, 1.0, div))


# ---------------------------------------------------------------------------
# Input scripts

def probe(stage):
    """After a run: the stage's energies, virial and forces (thermo printed c_tess_pv
    at this step, so the variables may read it)."""
    vir = " ".join("$(c_tess_pv[%d]*vol:%%.17g)" % (k + 1) for k in range(6))
    return ("print \"TESS_PROBE %s $(evdwl:%%.17g) $(ecoul:%%.17g) %s\"\n"
            "write_dump all custom tess_%s.dump id x y z fx fy fz modify format float %%.17g "
            "sort id\n" % (stage, vir, stage))


def thermo(extra="", define=True):
    return (("compute tess_pv all pressure NULL pair\n" if define else "") +
            "thermo_style custom step temp pe press %s c_tess_pv[1] c_tess_pv[2] c_tess_pv[3] "
            "c_tess_pv[4] c_tess_pv[5] c_tess_pv[6] vol\n"
            "thermo_modify norm no\n" % extra)


def setup_commands(cfg, newton=True, input_dir=FORCE_DIR):
    """The tester's init_lammps(): the YAML's setup up to `run 0`."""
    s = ["variable newton_pair index %s" % ("on" if newton else "off"),
         "variable input_dir index %s" % input_dir]
    s += lines(cfg["pre_commands"])
    s.append("include %s" % os.path.join(input_dir, cfg["input_file"]))
    s.append("pair_style " + cfg["pair_style"])
    s += ["pair_coeff " + c for c in lines(cfg["pair_coeff"])]
    s += ["pair_modify table 0", "pair_modify table/disp 0"]
    s += lines(cfg["post_commands"])
    return "\n".join(s) + "\n"


def stage_script(cfg, input_dir=FORCE_DIR, base="tess"):
    """Every stage of one newton-on test in one input script."""
    coeffs = "".join("pair_coeff %s\n" % c for c in lines(cfg["pair_coeff"]))
    post = "".join(c + "\n" for c in lines(cfg["post_commands"]))
    pre = "".join(c + "\n" for c in lines(cfg["pre_commands"]))
    s = setup_commands(cfg, True, input_dir)
    s += thermo() + "run 0 post no\n" + probe("init")
    s += ("variable write_data_pair index ii\n"
          "write_restart %s.restart\n"
          "write_data %s.data pair ${write_data_pair}\n"
          "write_coeff %s-coeffs.in\n" % (base, base, base))
    # run
    s += ("compute pe all pe/atom pair\n"
          "compute sum all reduce sum c_pe\n" + thermo("c_sum", False) +
          "thermo 2\nfix 1 all nve\nrun 4 post no\n" + probe("run") +
          "print \"TESS_SUM run $(c_sum:%.17g)\"\n")
    # restart, and restart with pair_modify nofdotr
    for stage, extra in (("restart", ""), ("nofdotr", "pair_modify nofdotr\n")):
        s += ("clear\nnewton on\nread_restart %s.restart\n" % base + coeffs + post + extra +
              thermo() + "run 0 post no\n" + probe(stage))
    # data
    s += ("clear\nvariable pair_style delete\nvariable data_file delete\n"
          "variable newton_pair delete\nvariable newton_pair index on\n" + pre +
          "variable pair_style index '%s'\nvariable data_file index %s.data\n"
          % (cfg["pair_style"], base) +
          "include %s\n" % os.path.join(input_dir, cfg["input_file"]) + coeffs + post +
          "print \"TESS_DATA_FILE ${data_file}\"\n" +
          thermo() + "run 0 post no\n" + probe("data"))
    # the same style given again (settings() and coeff() on the existing style)
    s += ("pair_style %s\n" % cfg["pair_style"] + coeffs + "run 0 post no\n" +
          probe("reissue"))
    return s


def read_probes(run):
    """{stage: {'vdwl', 'coul', 'stress' (6), 'ids', 'forces' (n x 3), 'x' (n x 3)}};
    the data stage's also 'file', the data file it read."""
    out, data_file = {}, None
    for line in run.stdout.splitlines():
        if line.startswith("TESS_PROBE "):
            w = line.split()
            out[w[1]] = {"vdwl": float(w[2]), "coul": float(w[3]),
                         "stress": np.array([float(v) for v in w[4:10]])}
        elif line.startswith("TESS_SUM "):
            w = line.split()
            out[w[1]]["sum"] = float(w[2])
        elif line.startswith("TESS_DATA_FILE "):
            data_file = line.split()[1]
    for stage, values in out.items():
        frame = read_dump(run.path("tess_%s.dump" % stage))
        values.update(frame)
    if "data" in out:
        out["data"]["file"] = data_file
    return out


def read_dump(path):
    with open(path) as f:
        text = f.read().split("\n")
    n = int(text[3])
    cols = text[8].split()[2:]
    rows = np.array([[float(w) for w in l.split()] for l in text[9:9 + n]])
    order = np.argsort(rows[:, cols.index("id")])
    rows = rows[order]
    return {"ids": rows[:, cols.index("id")].astype(int),
            "x": rows[:, [cols.index(c) for c in ("x", "y", "z")]],
            "forces": rows[:, [cols.index(c) for c in ("fx", "fy", "fz")]]}


# ---------------------------------------------------------------------------
# Central differences of the energy

def derivative_plan(atoms, components, strains):
    """The states at which central differences need the energy: a list of (label,
    sign), label ('f', atom ID, component) or ('w', strain component 'ab')."""
    plan = []
    for i in atoms:
        for a in components:
            for sign in (1, -1):
                plan.append((("f", i, a), sign))
    for ab in strains:
        for sign in (1, -1):
            plan.append((("w", ab), sign))
    return plan


def fd_script(cfg, dimension, box, periodic, plan, centre, h=FD_STEP, input_dir=FORCE_DIR):
    """One input script that sets up the YAML's system, stores the positions and
    evaluates the energy at every state of the plan: an atom's coordinate moved by
    +-h, or a homogeneous strain +-h of one component (x_a += h (x_b - c_b)), applied
    to the box and the atoms in periodic directions and to the atoms alone (about
    `centre`) otherwise.  Each state is set from the stored base exactly."""
    lo, hi, tilt = box
    s = setup_commands(cfg, True, input_dir)
    s += ("thermo_style custom step pe\nthermo_modify norm no\n"
          "run 0 post no\nfix tess_x0 all store/state 0 x y z\n")
    triclinic = any(t != 0.0 for t in tilt) or any(
        lab[0] == "w" and lab[1][0] != lab[1][1] and periodic[ord(lab[1][0]) - ord("x")]
        for lab, _ in plan)
    if triclinic:
        s += "change_box all triclinic\n"
    s += "print \"TESS_FD base $(evdwl:%.17g)\"\n"
    names = "xyz"

    def state(pos, newbox):
        t = ""
        if newbox is not None:
            nlo, nhi, ntilt = newbox
            t += "change_box all"
            for d in range(dimension):
                if periodic[d]:
                    t += " %s final %r %r" % (names[d], nlo[d], nhi[d])
            if triclinic:
                t += " xy final %r" % ntilt[0]
                if dimension == 3:
                    t += " xz final %r yz final %r" % (ntilt[1], ntilt[2])
            t += " units box\n"
        for d in range(3):
            t += "variable tess_p%s atom %s\n" % (names[d], pos[d])
        t += "set group all x v_tess_px y v_tess_py z v_tess_pz\n"
        return t

    base_pos = ["f_tess_x0[%d]" % (d + 1) for d in range(3)]
    for k, ((kind, *detail), sign) in enumerate(plan):
        pos = list(base_pos)
        newbox = None
        if kind == "f":
            i, a = detail
            pos[a] = "f_tess_x0[%d]+(%r)*(id==%d)" % (a + 1, sign * h, i)
        else:
            (ab,) = detail
            a, b = names.index(ab[0]), names.index(ab[1])
            eps = sign * h
            if periodic[b] and periodic[a]:
                # the box and the atoms: x_a += eps (x_b - lo_b)
                nlo, nhi, ntilt = list(lo), list(hi), list(tilt)
                if a == b:
                    c = 0.5 * (lo[a] + hi[a])
                    nlo[a] = c + (1 + eps) * (lo[a] - c)
                    nhi[a] = c + (1 + eps) * (hi[a] - c)
                    if a == 0:
                        ntilt[0] *= 1 + eps
                        ntilt[1] *= 1 + eps
                    elif a == 1:
                        ntilt[2] *= 1 + eps
                    pos[a] = "%r+(%r)*(f_tess_x0[%d]-(%r))" % (c, 1 + eps, a + 1, c)
                else:
                    c = lo[b]
                    length = hi[b] - lo[b]
                    if (a, b) == (0, 1):
                        ntilt[0] += eps * length
                        ntilt[1] += eps * tilt[2]
                    elif (a, b) == (0, 2):
                        ntilt[1] += eps * length
                    elif (a, b) == (1, 2):
                        ntilt[2] += eps * length
                    else:
                        raise ValueError("strain %s: only the upper triangle" % ab)
                    pos[a] = "f_tess_x0[%d]+(%r)*(f_tess_x0[%d]-(%r))" % (a + 1, eps, b + 1, c)
                newbox = (nlo, nhi, ntilt)
            elif not periodic[a] and not periodic[b]:
                c = centre[b]
                pos[a] = "f_tess_x0[%d]+(%r)*(f_tess_x0[%d]-(%r))" % (a + 1, eps, b + 1, c)
            else:
                raise ValueError("strain %s mixes periodic and open directions" % ab)
        s += state(pos, newbox)
        s += "run 0 post no\nprint \"TESS_FD %d $(evdwl:%%.17g)\"\n" % k
        if newbox is not None:
            s += state(base_pos, (lo, hi, tilt))
    return s


def fd_values(run, plan, h=FD_STEP):
    """{('f', id, component): -dE/dx, ('w', 'ab'): -dE/d strain} from the run."""
    e = {}
    for line in run.stdout.splitlines():
        if line.startswith("TESS_FD "):
            w = line.split()
            e[w[1]] = float(w[2])
    out = {}
    for k, (label, sign) in enumerate(plan):
        out.setdefault(label, [0.0, 0.0])[0 if sign > 0 else 1] = e[str(k)]
    return {label: -(ep - em) / (2 * h) for label, (ep, em) in out.items()}, e.get("base")


def box_header(path):
    """(lo, hi, tilt (xy xz yz), periodic) from a dump's BOX BOUNDS lines; lo/hi of a
    triclinic box are those of its parallelepiped's origin and extent."""
    with open(path) as f:
        text = f.read().split("\n")
    head = text[4].split()
    tri = "xy" in head
    b = [[float(w) for w in text[5 + d].split()] for d in range(3)]
    periodic = [flag == "pp" for flag in head[-3:]]
    if not tri:
        return [r[0] for r in b], [r[1] for r in b], [0.0, 0.0, 0.0], periodic
    xy, xz, yz = b[0][2], b[1][2], b[2][2]
    # dump bounds are those of the bounding box: undo as LAMMPS's docs describe
    xlo = b[0][0] - min(0.0, xy, xz, xy + xz)
    xhi = b[0][1] - max(0.0, xy, xz, xy + xz)
    ylo = b[1][0] - min(0.0, yz)
    yhi = b[1][1] - max(0.0, yz)
    return [xlo, ylo, b[2][0]], [xhi, yhi, b[2][1]], [xy, xz, yz], periodic


def dimension_of(cfg):
    m = re.search(r"variable\s+dimension\s+index\s+(\d)", cfg["pre_commands"])
    return int(m.group(1)) if m else 2


def centre_of(cfg):
    """Open directions are strained about this point: the sphere's centre, if any."""
    m = re.search(r"surface\s+sphere\s+(\S+)\s+(\S+)\s+(\S+)", cfg["pair_style"])
    return [float(v) for v in m.groups()] if m else None


def strains_of(dimension):
    return ["xx", "yy", "xy"] if dimension == 2 else list(STRESS)


def check_derivatives(values, stress, ids, forces, tol=FD_TOL):
    """The differences beyond tol: a list of strings, empty if none."""
    bad = []
    index = {i: k for k, i in enumerate(ids)}
    for label, d in values.items():
        if label[0] == "f":
            ref = forces[index[label[1]], label[2]]
            what = "force of atom %d, %s" % (label[1], "xyz"[label[2]])
        else:
            ref = stress[STRESS.index(label[1])]
            what = "virial %s" % label[1]
        if not abs(ref - d) <= tol * max(1.0, abs(ref)):
            bad.append("%s: stored %.12g, central differences %.12g" % (what, ref, d))
    return bad


# ---------------------------------------------------------------------------
# The configurations (data files), drawn once from a seed

def data_file(model, seed):
    """A LAMMPS data file (atom_style atomic, velocities) of a model's system."""
    rng = np.random.default_rng(seed)
    tilt = None
    if model == "confluent":
        # 32 cells of area ~1 on a jittered hexagonal lattice, a tilted periodic box
        a = math.sqrt(2 / math.sqrt(3))
        nx, ny = 4, 4
        pts = [((i + 0.5 * (j % 2)) * a, j * a * math.sqrt(3) / 2)
               for j in range(2 * ny) for i in range(nx)]
        lo, hi = [0.0, 0.0, -0.5], [nx * a, ny * a * math.sqrt(3), 0.5]
        tilt = (0.6, 0.0, 0.0)
        x = np.array([[p[0] + 0.6 * p[1] / hi[1], p[1], 0.0] for p in pts])
        x[:, :2] += rng.uniform(-0.12, 0.12, size=(len(x), 2))
        v = np.zeros_like(x)
        v[:, :2] = rng.uniform(-0.05, 0.05, size=(len(x), 2))
    elif model == "finite":
        # a colony of 29 cells (6 x 5, one missing inside: a hole) in an open box
        a = 1.0
        pts = [((i + 0.5 * (j % 2)) * a, j * a * math.sqrt(3) / 2)
               for j in range(5) for i in range(6)]
        del pts[14]
        x = np.array([[p[0], p[1], 0.0] for p in pts])
        x[:, :2] += rng.uniform(-0.08, 0.08, size=(len(x), 2))
        lo, hi = [-3.0, -3.0, -0.5], [9.0, 7.0, 0.5]
        v = np.zeros_like(x)
        v[:, :2] = rng.uniform(-0.05, 0.05, size=(len(x), 2))
    elif model == "3d":
        # 54 cells of volume ~1: a jittered BCC lattice (generic Voronoi vertices)
        c = 2 ** (1 / 3)
        n = 3
        base = [(0, 0, 0), (0.5, 0.5, 0.5)]
        x = np.array([[(i + b[0]) * c, (j + b[1]) * c, (k + b[2]) * c]
                      for k in range(n) for j in range(n) for i in range(n) for b in base])
        x += rng.uniform(-0.06, 0.06, size=x.shape)
        lo, hi = [0.0] * 3, [n * c] * 3
        v = rng.uniform(-0.05, 0.05, size=x.shape)
    elif model == "sphere":
        # 32 cells of area ~1 on a sphere of radius 1.6: a turned Fibonacci lattice,
        # jittered partly off the sphere (the style projects the points onto it)
        n, R, c = 32, 1.6, 4.0
        k = np.arange(n) + 0.5
        z = 1 - 2 * k / n
        ph = math.pi * (1 + 5 ** 0.5) * k + 0.3
        u = np.column_stack([np.sqrt(1 - z * z) * np.cos(ph), np.sqrt(1 - z * z) * np.sin(ph), z])
        x = c + R * u + rng.uniform(-0.05, 0.05, size=(n, 3))
        lo, hi = [0.0] * 3, [8.0] * 3
        v = np.zeros_like(x)
    else:
        raise ValueError(model)
    types = np.where(rng.uniform(size=len(x)) < 0.4, 2, 1)
    out = ["LAMMPS data file: pair_style vertex/voronoi force-style test, %s "
           "(tests/lammps/force_styles.py, seed %d)" % (model, seed), "",
           "%d atoms" % len(x), "2 atom types", ""]
    for d, name in enumerate("xyz"):
        out.append("%r %r %slo %shi" % (lo[d], hi[d], name, name))
    if tilt is not None:
        out.append("%r %r %r xy xz yz" % tilt)
    out += ["", "Masses", "", "1 1.0", "2 1.0", "", "Atoms # atomic", ""]
    out += ["%d %d %r %r %r" % (i + 1, t, *p) for i, (t, p) in enumerate(zip(types, x))]
    out += ["", "Velocities", ""]
    out += ["%d %r %r %r" % (i + 1, *q) for i, q in enumerate(v)]
    return "\n".join(out) + "\n"


SEEDS = {"confluent": 2811, "finite": 4637, "3d": 9203, "sphere": 1577}


# ---------------------------------------------------------------------------
# The generator

class Run:
    def __init__(self, workdir, proc):
        self.dir, self.returncode = workdir, proc.returncode
        self.stdout, self.stderr = proc.stdout, proc.stderr

    def path(self, name):
        return os.path.join(self.dir, name)


def run_lmp(lmp, script, workdir):
    with open(os.path.join(workdir, "in.test"), "w") as f:
        f.write(script)
    proc = subprocess.run([lmp, "-in", "in.test", "-log", "log.lammps"], cwd=workdir,
                          capture_output=True, text=True, timeout=600)
    run = Run(workdir, proc)
    if proc.returncode != 0:
        sys.exit("lmp failed (exit %d):\n%s"
                 % (proc.returncode, (proc.stdout + proc.stderr)[-4000:]))
    return run


def lammps_version(run):
    """The version a run's output starts with, as LAMMPS's YAML files give it."""
    m = re.search(r"^LAMMPS \((.+?)\)", run.stdout, re.M)
    return m.group(1).split(" - ")[0].strip() if m else "unknown"


def generate(model, path, lmp, new_data=False):
    cfg = read_yaml(path)
    dim = dimension_of(cfg)
    data = os.path.join(FORCE_DIR, "data.vertex_%s" % model)
    if new_data or not os.path.exists(data):
        with open(data, "w") as f:
            f.write(data_file(model, SEEDS[model]))
    with tempfile.TemporaryDirectory() as work:
        first = run_lmp(lmp, stage_script(cfg), work)
        version = lammps_version(first)
        stages = read_probes(first)
        init = stages["init"]
        box = box_header(os.path.join(work, "tess_init.dump"))
        plan = derivative_plan(init["ids"], range(dim), strains_of(dim))
        fd = run_lmp(lmp, fd_script(cfg, dim, box[:3], box[3], plan, centre_of(cfg) or
                                    [0.5 * (a + b) for a, b in zip(box[0], box[1])]), work)
        values, base = fd_values(fd, plan)
    bad = check_derivatives(values, init["stress"], init["ids"], init["forces"])
    if base is None or abs(base - init["vdwl"]) > 1e-9 * max(1.0, abs(base)):
        bad.append("the energy of the derivatives' base state %r is not init's %r"
                   % (base, init["vdwl"]))
    # the stages that must reproduce init (as the test will ask)
    eps = float(cfg["epsilon"])
    for stage in ("restart", "nofdotr", "data", "reissue"):
        for key in ("forces", "stress", "vdwl"):
            err = float(np.max(fp_error(stages[stage][key], init[key])))
            if err > eps:
                bad.append("%s %s differ from init's by %.3g (epsilon %g)" % (stage, key, err, eps))
    if os.path.basename(stages["data"]["file"]) != "tess.data":
        bad.append("the data stage read %s, not the file write_data wrote" % stages["data"]["file"])
    if abs(stages["run"]["sum"] - stages["run"]["vdwl"]) > eps * abs(stages["run"]["vdwl"]):
        bad.append("the sum of compute pe/atom is not the pair energy")
    if bad:
        sys.exit("%s: not written:\n  %s"
                 % (os.path.basename(path), "\n  ".join(bad)))
    worst = max(abs(values[l] - (init["forces"][list(init["ids"]).index(l[1]), l[2]]
                                 if l[0] == "f" else init["stress"][STRESS.index(l[1])]))
                for l in values)
    cfg["lammps_version"] = version
    cfg["date_generated"] = datetime.datetime.now().strftime("%a %b %d %H:%M:%S %Y")
    cfg["natoms"] = str(len(init["ids"]))
    for stage in ("init", "run"):
        values_ = stages[stage]
        cfg[stage + "_vdwl"] = "%.17g" % values_["vdwl"]
        cfg[stage + "_coul"] = "%.17g" % values_["coul"]
        cfg[stage + "_stress"] = format_stress(values_["stress"])
        cfg[stage + "_forces"] = format_forces(values_["ids"], values_["forces"])
    write_yaml(path, cfg)
    print("%s: written (%d atoms; %d central differences, largest difference %.2g)"
          % (os.path.basename(path), len(init["ids"]), len(values), worst))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--lmp", required=True, help="tessera-lmp, or an lmp with Tessera's styles")
    parser.add_argument("--new-data", action="store_true",
                        help="draw the configurations again (data.vertex_<model>)")
    parser.add_argument("models", nargs="*", help="default: every vertex_*.yaml")
    opts = parser.parse_args()
    available = models()
    for model in opts.models or sorted(available):
        if model not in available:
            sys.exit("no %s" % os.path.join(FORCE_DIR, "vertex_%s.yaml" % model))
        generate(model, available[model], os.path.abspath(opts.lmp), opts.new_data)


if __name__ == "__main__":
    main()
