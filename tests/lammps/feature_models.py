#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The models of the feature matrix (test_feature_matrix.py): the start of
an input script per model (a jittered tissue, two cell types, atom style
dipole) and the small readers the checks share."""

import math
import os
import re

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))

# Two types in the quadratic form (so that pe includes its constant), a
# heterotypic tension between them.  2d: KA A0 KP P0; 3d: KV V0 KS S0.
COEFFS_2D = """pair_coeff 1 1 quadratic 1.0 1.0 0.1 3.7
pair_coeff 2 2 quadratic 1.2 0.9 0.12 3.8
pair_coeff 1 2 quadratic 0.05
"""
COEFFS_FINITE = """pair_coeff 1 1 quadratic 1.0 1.2 0.1 3.9 free 0.2
pair_coeff 2 2 quadratic 1.2 1.1 0.12 3.8 free 0.3
pair_coeff 1 2 quadratic 0.05
"""
COEFFS_3D = """pair_coeff 1 1 quadratic 1.0 1.0 0.05 5.6
pair_coeff 2 2 quadratic 1.2 0.9 0.06 5.5
pair_coeff 1 2 quadratic 0.05
"""


# Particles: atoms 5, 30 and 51 of the tissue made type 3, no cells, which
# repel every atom through pair soft (A, cutoff per model) under
# hybrid/overlay; groups 'particles' and 'cells'.
PARTICLE_IDS = (5, 30, 51)
SOFT_CUT = {"3d": 1.3, "3d_tri": 1.3, "sphere": 1.7}


def with_particles(model, script):
    """A model's script with three of its atoms turned into particles."""
    if is_polygon(model):
        return polygon_particles(script)
    script = script.replace("create_box 2 box", "create_box 3 box")
    ids = " ".join(str(i) for i in PARTICLE_IDS)
    if "read_data" not in script:
        script = script.replace("mass * 1.0\n", f"group p id {ids}\nset group p type 3\n"
                                "group p delete\nmass * 1.0\n")
    script = script.replace("mass * 1.0\n", "mass * 1.0\ngroup particles type 3\n"
                            "group cells type 1 2\n")
    rc = SOFT_CUT.get(model, 1.0)
    out = []
    for line in script.split("\n"):
        if line.startswith("pair_style vertex/voronoi"):
            line = line.replace("pair_style vertex/voronoi",
                                "pair_style hybrid/overlay vertex/voronoi") + f" soft {rc}"
        elif line.startswith("pair_coeff"):
            w = line.split()
            line = " ".join(w[:3] + ["vertex/voronoi"] + w[3:])
        out.append(line)
    script = "\n".join(out)
    return script.replace("thermo_modify norm no", f"pair_coeff * 3 soft 2.0 {rc}\n"
                          "thermo_modify norm no", 1)


# The vertex model (pair_style vertex/polygon): cells 1 to 84 (types 1 and
# 2, atoms at their polygons' centroids, carrying polarity and per-cell
# values), vertices 85 to 252 (type 3, the degrees of freedom).  Fixes and
# outputs given 'all' in the checks take the groups that have a meaning
# (polygon_groups); the probes of forces are vertices.
POLYGON_CELLS = 84
PROBES = {"vertex_polygon": (93, 170), "vertex_polygon_tri": (93, 170)}
# With particles: a particle and a vertex within its reach (soft's cutoff).
PARTICLE_PROBES = {"vertex_polygon": (5, 98), "vertex_polygon_tri": (5, 95)}


def polygon_script(head, data=None, tilt=False):
    head += "boundary p p p\n"
    region = ("region box prism 0 7 0 6 -0.5 0.5 1.5 0 0" if tilt
              else "region box block 0 7 0 6 -0.5 0.5")
    if data:
        body = f"fix vring all property/atom i2_vring 16\nread_data {data} fix vring NULL vring\n"
    else:
        body = f"""lattice hex 1.0
{region}
create_box 3 box
create_atoms 1 box
set type 1 type/fraction 2 0.4 7731
displace_atoms all random 0.1 0.1 0 4821 units box
set group all dipole/random 3313 1.0
create_vertices all 3
"""
    body += "mass * 1.0\ngroup cells type 1 2\ngroup vertices type 3\ngroup movers type 3\n"
    pair = ("pair_style vertex/polygon 4.0 t1 0.04 0.06\n" + COEFFS_2D +
            "pair_coeff 3 3 vertex\n")
    return head + body + pair + "thermo_modify norm no format float %.17g\n"


def polygon_groups(script):
    """A check's script for the vertex model: polarity and cell fixes on the
    cells, integrators on the vertices and particles (group movers; an
    integrator on a cell atom is an error: it sits at its polygon's
    centroid)."""
    out = []
    for line in script.split("\n"):
        w = line.split()
        if len(w) > 3 and w[0] == "fix" and w[2] == "all":
            if w[3] in ("brownian", "brownian/heun"):
                w[2] = "movers"
            elif w[3] == "polarity":
                w[2] = "cells"
            line = " ".join(w)
        out.append(line)
    return "\n".join(out)


def polygon_particles(script):
    """Three cell centres made particles (type 4) before the vertices are
    created, under pair_style hybrid/overlay vertex/polygon ... soft: the
    vertex model with atoms that are no cells.  Soft acts between the
    particles and the vertices and among the particles; the cell types
    take no other style (an error otherwise), so they are given 'none'.
    The particles move with the vertices (group movers)."""
    ids = " ".join(str(i) for i in PARTICLE_IDS)
    script = script.replace("create_box 3 box", "create_box 4 box")
    if "read_data" not in script:
        script = script.replace("create_vertices all 3\n", f"group p id {ids}\nset group p type 4\n"
                                "group p delete\ngroup tissue type 1 2\n"
                                "create_vertices tissue 3\n")
    script = script.replace("mass * 1.0\n", "mass * 1.0\ngroup particles type 4\n"
                            "group movers type 4\n")
    out = []
    for line in script.split("\n"):
        if line.startswith("pair_style vertex/polygon"):
            line = line.replace("pair_style", "pair_style hybrid/overlay") + " soft 1.0"
        elif line.startswith("pair_coeff"):
            w = line.split()
            line = " ".join(w[:3] + ["vertex/polygon"] + w[3:])
        out.append(line)
    return "\n".join(out).replace("thermo_modify norm no", "pair_coeff 3*4 4 soft 2.0 1.0\n"
                                   "pair_coeff 1*2 4 none\nthermo_modify norm no", 1)


def polygon_death(script, trigger, floor):
    """A vertex-model script with T2s on and cells that die by fix cell/death
    (trigger, min floor): each shrinks through its own d_area0 and d_perim0
    and leaves by T1s and a T2 (integrated at dt 0.002; the run is the
    caller's)."""
    script = re.sub(r"( t1 0\.04 0\.06)( |\n)", r"\1 t2 0.05\2", script, count=1)
    return script + f"""fix pc all property/atom d_area0 d_perim0
set group cells d_area0 1.0
set group cells d_perim0 3.7
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix die all cell/death {trigger} seed 77 min {floor}
timestep 0.002
"""


def is_polygon(model):
    return model.startswith("vertex_polygon")


def model_script(model, data=None, particles=False):
    """The input script of a model's tissue up to the pair style; from a
    data file if given (the same atom IDs on any number of ranks); with
    particles (atoms that are no cells) if asked."""
    if particles:
        return with_particles(model, model_script(model, data))
    three = model.startswith("3d")
    finite = model.startswith("finite")
    head = "units lj\natom_style dipole\natom_modify map array\n"
    if model == "sphere":
        return sphere_script(head, data)
    if is_polygon(model):
        return polygon_script("dimension 2\n" + head, data, tilt=model.endswith("_tri"))
    if not three:
        head = "dimension 2\n" + head
    if model == "finite_open":
        head += "boundary f f p\n"
    else:
        head += "boundary p p p\n"
    if data:
        body = f"read_data {data}\n"
    elif three:
        # BCC: generic Voronoi vertices (a cubic lattice's are co-spherical,
        # whose jittered cells change topology all the time).
        region = ("region box prism 0 3 0 3 0 3 1.0 1.0 0.0" if model == "3d_tri"
                  else "region box block 0 3 0 3 0 3")
        body = f"""lattice bcc 1.0
{region}
create_box 2 box
create_atoms 1 box
set type 1 type/fraction 2 0.4 7731
displace_atoms all random 0.05 0.05 0.05 4821 units box
set group all dipole/random 3313 1.0
"""
    elif model == "finite_open":
        body = """lattice hex 1.0
region box block -3 10 -3 9 -0.5 0.5
create_box 2 box
region tissue block 0 7 0 6 -0.5 0.5
create_atoms 1 region tissue
set type 1 type/fraction 2 0.4 7731
displace_atoms all random 0.08 0.08 0 4821 units box
set group all dipole/random 3313 1.0
"""
    else:
        region = ("region box prism 0 7 0 6 -0.5 0.5 1.5 0 0" if model == "confluent_tri"
                  else "region box block 0 7 0 6 -0.5 0.5")
        body = f"""lattice hex 1.0
{region}
create_box 2 box
create_atoms 1 box
set type 1 type/fraction 2 0.4 7731
displace_atoms all random 0.1 0.1 0 4821 units box
set group all dipole/random 3313 1.0
"""
    body += "mass * 1.0\n"
    if three:
        pair = "pair_style vertex/voronoi 3.0\n" + COEFFS_3D
    elif finite:
        r = 0.7 if model == "finite_open" else 0.58
        pair = f"pair_style vertex/voronoi {2.2 * r:.3f} radius {r}\n" + COEFFS_FINITE
    else:
        pair = "pair_style vertex/voronoi 3.0\n" + COEFFS_2D
    return head + body + pair + "thermo_modify norm no format float %.17g\n"


# Cells on a sphere: centre and radius (the centre is the box's, so that
# change_box scales positions about it).
SPHERE_C, SPHERE_R = 6.0, 4.0


def sphere_script(head, data=None):
    """96 cells on a sphere in an open box: a Fibonacci lattice (nearly
    uniform, so that the short runs see few neighbour exchanges) turned and
    jittered, the jitter partly off the sphere (the pair style projects the
    points onto it)."""
    head += "boundary f f f\n"
    if data:
        body = f"read_data {data}\n"
    else:
        n = 96
        k = np.arange(n) + 0.5
        z = 1 - 2 * k / n
        ph = math.pi * (1 + 5 ** 0.5) * k
        u = np.column_stack([np.sqrt(1 - z * z) * np.cos(ph), np.sqrt(1 - z * z) * np.sin(ph), z])
        rng = np.random.default_rng(8231)
        x = SPHERE_C + SPHERE_R * u + rng.uniform(-0.08, 0.08, size=(n, 3))
        body = "region box block 0 12 0 12 0 12\ncreate_box 2 box\n"
        body += "".join(f"create_atoms 1 single {p[0]!r} {p[1]!r} {p[2]!r} units box\n" for p in x)
        body += """set type 1 type/fraction 2 0.4 7731
set group all dipole/random 3313 1.0
"""
    body += "mass * 1.0\n"
    pair = (f"pair_style vertex/voronoi 3.0 surface sphere {SPHERE_C} {SPHERE_C} {SPHERE_C} "
            f"{SPHERE_R}\n" + COEFFS_2D)
    return head + body + pair + "thermo_modify norm no format float %.17g\n"


def dim_of(model):
    return 3 if model.startswith("3d") or model == "sphere" else 2


def printed(run, key):
    return [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
            if line.startswith(key + " ")]


def read_matrix():
    cells = []
    with open(os.path.join(HERE, "feature_matrix.txt")) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            model, feature, expect = line.split(None, 2)
            cells.append((model, feature, expect))
    return cells


def local_rows(run, name):
    """Rows of a dump local file: a list of frames, each an array."""
    frames, rows, n = [], [], 0
    lines = run.text(name).split("\n")
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: NUMBER OF ENTRIES"):
            n = int(lines[i + 1])
        if lines[i].startswith("ITEM: ENTRIES"):
            rows = [[float(w) for w in lines[i + 1 + k].split()] for k in range(n)]
            frames.append(np.array(rows).reshape(n, -1))
            i += 1 + n
            continue
        i += 1
    return frames
