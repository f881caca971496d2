#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""pair_style vertex/polygon (the vertex model) and create_vertices through
LAMMPS, against independent results: pe against the energy written out in
numpy from the data file (areas, perimeters and junctions of the rings),
forces against central differences of pe under displace_atoms, the virial
against central differences of pe under box strain; the same trajectory with
T1s and T2s on 1, 2 and 4 ranks from one data file; write_data/read_data and
restart files continuing a run; fix brownian/heun and minimize; and the
errors for bad input, each naming the atoms."""

import math
import re

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs
from vertex_check import parse_data as read_data, polygon

# Cell types 1 and 2 (quadratic form KA A0 KP P0), a heterotypic sigma;
# type 3 is the vertex type.
TYPES = {1: (1.0, 1.0, 0.8, 3.7), 2: (0.8, 1.1, 0.6, 3.6)}
SIGMA = 0.3


def start(nx=8, ny=4, jitter=0.2, seed=4321, two_types=True, tilt=None, extra_types=0):
    """A jittered hexagonal tissue of cells of area 1 in a periodic box, made
    a vertex tissue by create_vertices (vertex type 3 + extra_types)."""
    region = ("region box block 0 %d 0 %d -0.5 0.5" % (nx, ny) if tilt is None else
              "region box prism 0 %d 0 %d -0.5 0.5 %g 0 0" % (nx, ny, tilt))
    vtype = 3 + extra_types
    return f"""
dimension 2
units lj
atom_style atomic
atom_modify map yes
boundary p p p
lattice hex 1.0
{region}
create_box {vtype} box
create_atoms 1 box
{"set type 1 type/fraction 2 0.4 7731" if two_types else ""}
displace_atoms all random {jitter} {jitter} 0 {seed} units box
mass * 1.0
create_vertices all {vtype}
group vertices type {vtype}
"""


def coeffs(pair="pair_style vertex/polygon 4.0", vtype=3):
    return f"""{pair}
pair_coeff 1 1 quadratic {TYPES[1][0]} {TYPES[1][1]} {TYPES[1][2]} {TYPES[1][3]}
pair_coeff 2 2 quadratic {TYPES[2][0]} {TYPES[2][1]} {TYPES[2][2]} {TYPES[2][3]}
pair_coeff 1 2 quadratic {SIGMA}
pair_coeff {vtype} {vtype} vertex
thermo_modify norm no format float %.17g
"""


# read_data() (vertex_check.parse_data) and polygon(): vertex_check.py, shared with
# the division and death tests


def written_energy(text, types=None, sigma=None, percell=False):
    """E = sum_c KA (A - A0)^2 + KP (P - P0)^2 + sigma * (length of the 1-2
    junctions), each cell's values its type's (types: {type: (KA, A0, KP,
    P0)}, default TYPES) or, with percell, PERCELL's formulas of its ID."""
    types = TYPES if types is None else types
    sigma = SIGMA if sigma is None else sigma
    box, atoms, rings, _ = read_data(text)
    props = {}
    if percell:
        for name, f in (("area0", lambda i: 1.0 + 0.1 * math.sin(i)),
                        ("ka", lambda i: 1.0 + 0.3 * math.cos(2 * i)),
                        ("kp", lambda i: 0.5 + 0.2 * math.sin(3 * i)),
                        ("perim0", lambda i: 3.6 + 0.2 * math.cos(i))):
            props[name] = {c: f(c) for c in rings}
    edge_cell = {}
    for c, r in rings.items():
        for k in range(len(r)):
            edge_cell[(r[k], r[(k + 1) % len(r)])] = c
    e = 0.0
    for c, r in rings.items():
        t = atoms[c][0]
        ka, a0, kp, p0 = types[t]
        ka = props.get("ka", {}).get(c, ka)
        a0 = props.get("area0", {}).get(c, a0)
        kp = props.get("kp", {}).get(c, kp)
        p0 = props.get("perim0", {}).get(c, p0)
        pts = polygon(box, atoms, r)
        nxt = np.roll(pts, -1, axis=0)
        area = 0.5 * np.sum(pts[:, 0] * nxt[:, 1] - nxt[:, 0] * pts[:, 1])
        lengths = np.linalg.norm(nxt - pts, axis=1)
        e += ka * (area - a0) ** 2 + kp * (lengths.sum() - p0) ** 2
        for k in range(len(r)):
            other = edge_cell[(r[(k + 1) % len(r)], r[k])]
            if atoms[other][0] != t:
                e += 0.5 * sigma * lengths[k]    # each junction seen from both cells
    return e


def printed(run, tag):
    """The numbers of every 'tag ...' line the run printed."""
    return [[float(v) for v in line.split()[1:]] for line in run.stdout.splitlines()
            if line.startswith(tag + " ")]


PERCELL = """fix p all property/atom d_area0 d_ka d_kp d_perim0
variable a0 atom 1.0+0.1*sin(id)
variable ka atom 1.0+0.3*cos(2*id)
variable kp atom 0.5+0.2*sin(3*id)
variable p0 atom 3.6+0.2*cos(id)
set type 1*2 d_area0 v_a0
set type 1*2 d_ka v_ka
set type 1*2 d_kp v_kp
set type 1*2 d_perim0 v_p0
"""


class Energy(LammpsTestCase):
    """pe against the energy written out, forces against central differences."""

    def check(self, nprocs=1, percell=False, tilt=None):
        # (create_atoms numbers atoms by rank: every run of a check has the
        # same number of ranks)
        script = start(tilt=tilt) + (PERCELL if percell else "") + coeffs() + """
run 0
print "E $(pe:%.17g)"
write_data cfg.data
write_dump vertices custom f.dump id x y fx fy modify format float %.17g sort id
"""
        run = self.run_lmp(script, nprocs=nprocs)
        e = printed(run, "E")[0][0]
        want = written_energy(run.text("cfg.data"), percell=percell)
        self.assertAlmostEqual(e, want, delta=1e-10 * abs(want))
        frame = run.dump("f.dump")[0]
        ids = [int(i) for i in frame["id"][::23]]    # a sample of vertices
        h = 1e-5
        fd_script = start(tilt=tilt) + (PERCELL if percell else "") + coeffs() + "run 0\n"
        for v in ids:
            fd_script += f"group g{v} id {v}\n"
            for d, (dx, dy) in enumerate(((h, 0), (0, h))):
                fd_script += f"""displace_atoms g{v} move {dx} {dy} 0 units box
run 0
variable ep equal $(pe:%.17g)
displace_atoms g{v} move {-2 * dx} {-2 * dy} 0 units box
run 0
print "F {v} {d} $((v_ep-pe)/{-2 * h}:%.17g)"
displace_atoms g{v} move {dx} {dy} 0 units box
"""
        fd = {(int(r[0]), int(r[1])): r[2]
              for r in printed(self.run_lmp(fd_script, nprocs=nprocs), "F")}
        scale = max(np.abs(frame["fx"]).max(), np.abs(frame["fy"]).max())
        for k, v in enumerate(frame["id"]):
            for d, col in enumerate(("fx", "fy")):
                if (int(v), d) in fd:
                    self.assertAlmostEqual(frame[col][k], fd[(int(v), d)], delta=1e-6 * scale,
                                           msg=f"vertex {int(v)} {col}")

    def test_types(self):
        self.check()

    @nprocs(2)
    def test_types_two_ranks(self):
        self.check(2)

    def test_per_cell_values(self):
        self.check(percell=True)

    def test_tilted_box(self):
        self.check(tilt=2)

    def test_virial(self):
        # pxx, pyy (orthogonal box) and pxy (tilted box) against
        # -dE/d(strain) / area; with 'pair_modify nofdotr' the style sums its
        # cells' own virials (LAMMPS no longer computes f dot r for it).
        for tilt, nofdotr in ((None, False), (2, False), (None, True), (2, True)):
            eps = 1e-6
            script = start(tilt=tilt) + coeffs() + ("pair_modify nofdotr\n" if nofdotr else "")
            script += f"""
thermo_style custom step pe pxx pyy pxy
thermo_modify norm no
run 0
print "P $(pxx:%.17g) $(pyy:%.17g) $(pxy:%.17g) $(vol:%.17g)"
change_box all x scale {1 + eps} remap
run 0
variable exp equal $(pe:%.17g)
change_box all x scale {(1 - eps) / (1 + eps)} remap
run 0
variable exm equal $(pe:%.17g)
change_box all x scale {1 / (1 - eps)} y scale {1 + eps} remap
run 0
variable eyp equal $(pe:%.17g)
change_box all y scale {(1 - eps) / (1 + eps)} remap
run 0
print "D $((v_exp-v_exm)/{2 * eps}:%.17g) $((v_eyp-pe)/{2 * eps}:%.17g)"
"""
            if tilt is not None:
                script += f"""change_box all y scale {1 / (1 - eps)} remap
change_box all xy delta $({eps}*ly) remap units box
run 0
variable sp equal $(pe:%.17g)
change_box all xy delta $({-2 * eps}*ly) remap units box
run 0
print "S $((v_sp-pe)/{2 * eps}:%.17g)"
"""
            run = self.run_lmp(script)
            pxx, pyy, pxy, vol = printed(run, "P")[0]
            dx, dy = printed(run, "D")[0]
            if tilt is None:    # (scaling x of a tilted box also shears it)
                self.assertAlmostEqual(pxx * vol, -dx, delta=1e-5 * (1 + abs(dx)), msg=nofdotr)
                self.assertAlmostEqual(pyy * vol, -dy, delta=1e-5 * (1 + abs(dy)), msg=nofdotr)
            else:
                ds = printed(run, "S")[0][0]
                self.assertAlmostEqual(pxy * vol, -ds, delta=1e-5 * (1 + abs(ds)), msg=nofdotr)


DYNAMICS_TYPES = {1: (1.0, 1.0, 1.0, 3.7), 2: (1.0, 0.001, 1.0, 0.1)}


def dynamics(steps, integrator="fix move vertices brownian 1.0 1 gamma_t 1.0 rng none",
             pair="pair_style vertex/polygon 4.0 t1 0.04 0.06 t2 0.02"):
    """T1s (a solid near its minimum flips its short edges) and T2s (type-2
    cells with a tiny preferred area shrink to triangles and go)."""
    return f"""{pair}
pair_coeff 1 1 quadratic 1.0 1.0 1.0 3.7
pair_coeff 2 2 quadratic 1.0 0.001 1.0 0.1
pair_coeff 3 3 vertex
{integrator}
timestep 0.005
compute t all pair vertex/polygon
thermo_style custom step pe c_t[1] c_t[2] c_t[3] atoms
thermo_modify norm no format float %.17g
thermo 100
run {steps}
print "N $(c_t[1]) $(c_t[2]) $(atoms)"
"""


def data_start():
    """One cell type; 8% of the cells are made type 2, which shrinks away."""
    return start(two_types=False) + "set type 1 type/fraction 2 0.08 99\nwrite_data start.data\n"


def from_data(data_name="start.data"):
    return f"""dimension 2
units lj
atom_style atomic
atom_modify map yes
boundary p p p
fix vring all property/atom i2_vring 16
read_data {data_name} fix vring NULL vring
group vertices type 3
"""


def continuation(restart, steps):
    """A run from a restart file: the pair style and the rings come back with
    it; fixes, computes and thermo settings are given again."""
    return f"""read_restart {restart}
group vertices type 3
fix move vertices brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.005
compute t all pair vertex/polygon
thermo_style custom step pe c_t[1] c_t[2] c_t[3] atoms
thermo_modify norm no format float %.17g
thermo 100
run {steps}
print "N $(c_t[1]) $(c_t[2]) $(atoms)"
write_dump all custom end.dump id xu yu modify format float %.17g sort id
"""


class Ranks(LammpsTestCase):
    """One data file, 1, 2 and 4 ranks: the same T1s and T2s, the same
    positions to round-off (4 ranks on 64 cells: many events straddle a
    rank boundary)."""

    @nprocs(4)
    def test_same_trajectory(self):
        data = self.run_lmp(data_start()).text("start.data")
        results = []
        for n in (1, 2, 4):
            script = from_data() + dynamics(600) + """
write_dump all custom end.dump id type xu yu modify format float %.17g sort id
"""
            run = self.run_lmp(script, nprocs=n, files={"start.data": data})
            results.append((printed(run, "N")[0], run.dump("end.dump")[0]))
        t1, t2, natoms = results[0][0]
        self.assertGreater(t1, 5)
        self.assertGreater(t2, 0)
        self.assertLess(natoms, 192)
        for counts, frame in results[1:]:
            self.assertEqual(counts, results[0][0])
            np.testing.assert_array_equal(frame["id"], results[0][1]["id"])
            for col in ("xu", "yu"):
                np.testing.assert_allclose(frame[col], results[0][1][col], rtol=0, atol=1e-9)


class DataAndRestart(LammpsTestCase):
    """write_data/read_data carry the rings; a restart file continues the run."""

    def test_data_file_round_trip(self):
        energy = 'print "E $(pe:%.17g)"\n'
        first = self.run_lmp(data_start() + dynamics(200) + energy + "write_data mid.data\n")
        mid = first.text("mid.data")
        again = self.run_lmp(from_data("mid.data") + dynamics(0) + energy,
                             files={"mid.data": mid})
        e1, e2 = printed(first, "E")[0][0], printed(again, "E")[0][0]
        self.assertAlmostEqual(e1, e2, delta=1e-12 * abs(e1))
        self.assertAlmostEqual(e2, written_energy(mid, DYNAMICS_TYPES, 0.0), delta=1e-10 * abs(e2))

    @nprocs(2)
    def test_restart_continues(self):
        # Restart files every step of the first 60 (where T1s and T2s happen),
        # and a continuation from the first one written while a topology step
        # was scheduled for the next step, and from step 60.
        data = self.run_lmp(data_start()).text("start.data")
        first = dynamics(60).replace("thermo 100", "thermo 1").replace(
            "thermo_style custom step pe c_t[1] c_t[2] c_t[3] atoms",
            "thermo_style custom step pe c_t[1] c_t[2] c_t[3] atoms c_t[4]")
        full = self.run_lmp(from_data() + "restart 1 r.*\n" + first + "restart 0\nrun 240\n"
                            'print "N $(c_t[1]) $(c_t[2]) $(atoms)"\n' + """
write_dump all custom end.dump id xu yu modify format float %.17g sort id
""", files={"start.data": data})
        final = printed(full, "N")[-1]
        self.assertGreater(final[0], 5)    # T1s ...
        self.assertGreater(final[1], 0)    # ... and T2s
        steps = {int(m.group(1)): float(m.group(2)) for m in re.finditer(
            r"(?m)^\s*(\d+)(?:\s+[-+.\deE]+){4}\s+\d+\s+([-+.\deE]+)\s*$", full.stdout)}
        scheduled = [s for s in range(1, 60) if steps.get(s + 1, 0) > steps.get(s, 0)]
        self.assertTrue(scheduled, "no topology step in the first 60 steps")
        for start_step, n in ((scheduled[0], 1), (60, 2)):
            rest = self.run_lmp(continuation(full.path("r.%d" % start_step), 300 - start_step),
                                nprocs=n)
            a, b = full.dump("end.dump")[0], rest.dump("end.dump")[0]
            self.assertEqual(final, printed(rest, "N")[0])
            np.testing.assert_array_equal(a["id"], b["id"])
            for col in ("xu", "yu"):
                np.testing.assert_allclose(a[col], b[col], rtol=0, atol=1e-9,
                                           err_msg="from step %d" % start_step)


class Integrators(LammpsTestCase):

    def test_heun_is_second_order(self):
        # Without noise both integrate dr/dt = F/gamma; to t = 0.1 the error
        # against a fine Heun run halves with dt for Euler (fix brownian) and
        # falls four times for Heun (fix brownian/heun).
        def end(fix, dt):
            steps = int(round(0.1 / dt))
            run = self.run_lmp(start(two_types=False) + coeffs() + f"""
fix move vertices {fix} 1.0 1 gamma_t 1.0 rng none
timestep {dt}
run {steps}
write_dump vertices custom end.dump id xu yu modify format float %.17g sort id
""")
            f = run.dump("end.dump")[0]
            return np.concatenate([f["xu"], f["yu"]])

        ref = end("brownian/heun", 0.00025)
        err = {(fix, dt): np.abs(end(fix, dt) - ref).max()
               for fix in ("brownian", "brownian/heun") for dt in (0.002, 0.001)}
        euler = err[("brownian", 0.002)] / err[("brownian", 0.001)]
        heun = err[("brownian/heun", 0.002)] / err[("brownian/heun", 0.001)]
        self.assertGreater(err[("brownian", 0.002)], 1e-6)
        self.assertTrue(1.7 < euler < 2.3, euler)
        self.assertTrue(3.4 < heun < 4.6, heun)

    def test_minimize(self):
        run = self.run_lmp(start() + coeffs() + """
thermo_style custom step pe fnorm fmax
thermo_modify norm no
run 0
print "E0 $(pe:%.17g)"
min_style cg
minimize 0 1e-10 5000 50000
print "E1 $(pe:%.17g) $(fmax:%.17g)"
write_data min.data
""")
        e0, e1, fmax = printed(run, "E0")[0][0], *printed(run, "E1")[0]
        self.assertLess(e1, 0.9 * e0)
        self.assertLess(fmax, 1e-8)
        self.assertAlmostEqual(e1, written_energy(run.text("min.data")), delta=1e-10 * e0)


class Errors(LammpsTestCase):
    """Bad input stops with an error naming the atoms (table: what is wrong,
    the lines that make it wrong, fragments of the error).  start() makes
    cells 1-64 and vertices 65-192."""

    CASES = [
        ("vertex in no cell", "create_atoms 3 single 0.3 0.3 0 units box\n",
         ["vertex 193 is in 0 cells", "a vertex in no cell"]),
        ("ring names a missing ID", "set atom 5 i_vring[2] 9999\n",
         ["vertex 9999 of cell 5", "does not exist"]),
        ("ring names a cell", "set atom 5 i_vring[2] 7\n",
         ["cell 5 lists atom 7", "not a vertex"]),
        ("ring runs clockwise", "REVERSE", ["both hold the edge", "clockwise"]),
        ("ring names a vertex twice", "REPEAT", ["cell 5 lists vertex", "twice in its ring"]),
        ("cell crosses itself", "MOVE", ["at step 0: cell", "vertices"]),
        ("cell without a ring", "create_atoms 1 single 0.3 0.3 0 units box\n",
         ["cell 193", "has 0 vertices"]),
        ("vertex with a ring", "set atom 70 i_vring[1] 71\n", ["atom 70 of vertex type 3"]),
    ]

    def ring_edit(self, how):
        """'set' lines that write cell 5's ring reversed (REVERSE), or move its
        first vertex through the cell to the far side (MOVE), or name its
        first vertex again in place of its fourth (REPEAT), read from a first
        run."""
        box, atoms, rings, _ = read_data(
            self.run_lmp(start() + "write_data s.data\n").text("s.data"))
        r = rings[5]
        if how == "REVERSE":
            return "".join(f"set atom 5 i_vring[{k + 1}] {v}\n" for k, v in enumerate(r[::-1]))
        if how == "REPEAT":
            return f"set atom 5 i_vring[4] {r[0]}\n"
        pts = polygon(box, atoms, r)
        x, y = pts.mean(axis=0) + 1.5 * (pts.mean(axis=0) - pts[0])
        return f"set atom {r[0]} x {x!r} y {y!r}\n"

    def test_cases(self):
        for name, lines, fragments in self.CASES:
            with self.subTest(name):
                if lines in ("REVERSE", "MOVE", "REPEAT"):
                    lines = self.ring_edit(lines)
                run = self.run_lmp(start() + lines + coeffs() + "run 0\n", ok=False)
                self.assertLammpsError(run, *fragments)
                if name == "cell crosses itself":
                    self.assertTrue(re.search(r"crosses itself|negative area", run.output))

    def test_settings(self):
        for pair, fragment in (
                ("pair_style vertex/polygon 4.0 t1 0.5 0.8", "comparable to the cells' size"),
                ("pair_style vertex/polygon 4.0 t1 0.05 0.04", "l_new must be larger than l_T1"),
                ("pair_style vertex/polygon 4.0 t2 0.5", "comparable to the cells' preferred area"),
                ("pair_style vertex/polygon 4.0 t3 1", "unknown keyword 't3'")):
            with self.subTest(pair):
                run = self.run_lmp(start() + coeffs(pair) + "run 0\n", ok=False)
                self.assertLammpsError(run, fragment)

    def test_types_mixed_up(self):
        script = start() + """pair_style vertex/polygon 4.0
pair_coeff 1 1 vertex
pair_coeff 2 2 quadratic 1 1 1 3.7
pair_coeff 3 3 quadratic 1 1 1 3.7
run 0
"""
        self.assertLammpsError(self.run_lmp(script, ok=False), "vertex and cell types mixed up")

    def test_integrator_on_cells(self):
        run = self.run_lmp(start() + coeffs() + "fix b all brownian 1.0 1 gamma_t 1.0\nrun 1\n",
                           ok=False)
        self.assertLammpsError(run, "fix b (brownian) integrates cell atom 1",
                               "integrate the vertex atoms only")

    def test_no_rings(self):
        script = start().replace("create_vertices all 3", "") + coeffs() + "run 0\n"
        self.assertLammpsError(self.run_lmp(script, ok=False), "no rings")

    # pair_style hybrid/overlay with particles (type 4, none of this style):
    # (what is wrong, the lines after the tissue, fragments of the error).
    HYBRID = "pair_style hybrid/overlay vertex/polygon 4.0 soft 1.0\n"
    HYBRID_CASES = [
        ("another style on a cell type", "pair_coeff * 4 soft 2.0 1.0\n",
         ["gives the type pair 1 4 to pair style soft", "type 1 is a cell type",
          "pair_coeff 1 4 none"]),
        ("a particle with a ring",
         "pair_coeff 3*4 4 soft 2.0 1.0\npair_coeff 1*2 4 none\nset atom 1 type 4\n",
         ["atom 1 of type 4", "has a ring in i_vring"]),
        ("a tension with a particle type",
         "pair_coeff 3*4 4 soft 2.0 1.0\npair_coeff 1*2 4 none\n"
         "pair_coeff 1 4 vertex/polygon 0.05\n",
         ["junction tension between types 1 and 4", "type 4 is no type of this style"]),
    ]

    def hybrid_start(self):
        """start() with a fourth (particle) type and the cell and vertex types'
        pair_coeffs under HYBRID; the particles' coefficients are the test's."""
        t1, t2 = TYPES[1], TYPES[2]
        return start().replace("create_box 3 box", "create_box 4 box") + self.HYBRID + f"""\
pair_coeff 1 1 vertex/polygon quadratic {t1[0]} {t1[1]} {t1[2]} {t1[3]}
pair_coeff 2 2 vertex/polygon quadratic {t2[0]} {t2[1]} {t2[2]} {t2[3]}
pair_coeff 3 3 vertex/polygon vertex
"""

    def test_hybrid(self):
        for name, lines, fragments in self.HYBRID_CASES:
            with self.subTest(name):
                run = self.run_lmp(self.hybrid_start() + lines + "run 0\n", ok=False)
                self.assertLammpsError(run, *fragments)

    def test_deposit_particles(self):
        """fix deposit may add particles (type 4, soft with the vertices) to a
        vertex tissue: the atoms grow by the deposits, the cells stay as they
        were (their count and total area), and the energy stays finite; a
        deposit of the cell or the vertex type stops with an error naming
        the type."""
        head = self.hybrid_start() + """pair_coeff 3*4 4 soft 2.0 1.0
pair_coeff 1*2 4 none
group cells type 1 2
"""
        run_part = """region ins block 1 6 1 3 -0.1 0.1 units box
fix b vertices brownian 1.0 1 gamma_t 1.0 rng none
fix dep all deposit 3 {type} 4 4821 region ins near 0.05 attempt 500
compute c all vertex/atom
compute a all reduce sum c_c[1]
variable ncell equal count(cells)
timestep 0.005
thermo_style custom step atoms pe c_a
thermo_modify norm no
run 0
print "N0 $(atoms) $(v_ncell) $(c_a:%.17g) $(vol:%.17g)"
run 13
print "N1 $(atoms) $(v_ncell) $(c_a:%.17g) $(pe:%.17g)"
"""
        script = head + run_part.format(type=4)
        run = self.run_lmp(script)
        n0, c0, a0, vol = printed(run, "N0")[0]
        n1, c1, a1, pe = printed(run, "N1")[0]
        self.assertEqual(n1, n0 + 3)
        self.assertEqual(c1, c0)
        self.assertAlmostEqual(a0, vol, delta=1e-9 * vol)
        self.assertAlmostEqual(a1, vol, delta=1e-9 * vol)
        self.assertTrue(math.isfinite(pe))
        for t, what in ((1, "type 1 is a cell type"), (3, "type 3 is a vertex type")):
            with self.subTest(type=t):
                run = self.run_lmp(head + run_part.format(type=t), ok=False)
                self.assertLammpsError(run, "fix dep (deposit) adds atoms during the run", what)

    def test_cutoff_too_small(self):
        run = self.run_lmp(start() + coeffs("pair_style vertex/polygon 0.3") + "run 0\n",
                           ok=False)
        self.assertLammpsError(run, "beyond the cutoff 0.3")


class Consumers(LammpsTestCase):
    """The computes and fixes that read cells work on the vertex model's cells
    (the same view as pair_style vertex/voronoi's)."""

    def test_vertex_atom_and_local(self):
        # Areas, perimeters, neighbour counts and energies of compute
        # vertex/atom, and the junctions of compute vertex/local, against the
        # polygons written out from the data file; vertex atoms have zero rows.
        run = self.run_lmp(start() + coeffs() + """
compute a all vertex/atom
compute l all vertex/local
dump d all custom 1 a.dump id type c_a[1] c_a[2] c_a[3] c_a[4] c_a[5]
dump_modify d format float %.17g sort id
dump j all local 1 j.dump c_l[1] c_l[2] c_l[3] c_l[4] c_l[5] c_l[6] c_l[7]
dump_modify j format float %.17g
run 0
print "E $(pe:%.17g)"
write_data cfg.data
""")
        box, atoms, rings, _ = read_data(run.text("cfg.data"))
        frame = run.dump("a.dump")[0]
        e = printed(run, "E")[0][0]
        self.assertAlmostEqual(frame["c_a[5]"].sum(), e, delta=1e-10 * abs(e))
        for k, i in enumerate(frame["id"]):
            i = int(i)
            row = [frame["c_a[%d]" % c][k] for c in range(1, 6)]
            if i not in rings:
                self.assertEqual(row, [0.0] * 5)
                continue
            pts = polygon(box, atoms, rings[i])
            nxt = np.roll(pts, -1, axis=0)
            area = 0.5 * np.sum(pts[:, 0] * nxt[:, 1] - nxt[:, 0] * pts[:, 1])
            lengths = np.linalg.norm(nxt - pts, axis=1)
            self.assertAlmostEqual(row[0], area, delta=1e-12)
            self.assertAlmostEqual(row[1], lengths.sum(), delta=1e-12)
            self.assertAlmostEqual(row[2], lengths.sum() / math.sqrt(area), delta=1e-12)
            self.assertEqual(row[3], len(rings[i]))
        # Junctions: one row per edge, from each side, lengths of the polygons.
        rows = np.loadtxt(run.path("j.dump"), skiprows=9)
        self.assertEqual(len(rows), sum(len(r) for r in rings.values()))
        for i, r in rings.items():
            mine = rows[rows[:, 0] == i]
            self.assertEqual(len(mine), len(r))
            np.testing.assert_allclose(mine[:, 2:4], np.roll(mine[:, 4:6], 1, axis=0), atol=1e-12)
            np.testing.assert_allclose(np.sort(mine[:, 6]), np.sort(np.linalg.norm(
                np.roll(polygon(box, atoms, r), -1, axis=0) - polygon(box, atoms, r), axis=1)),
                atol=1e-12)

    def test_tissue_counts_the_t1s(self):
        # compute vertex/tissue's neighbour exchanges, counted every step,
        # against the pair style's own count of T1s (an active fluid, no T2s).
        dipole = "atom_style hybrid dipole sphere"
        data = self.run_lmp(start(two_types=False).replace("atom_style atomic", dipole) +
                            "write_data start.data\n").text("start.data")
        script = from_data().replace("atom_style atomic", dipole) + """group cells type 1
fix act cells polarity 0.5 1.0 neighbor 0.2 noise 1.0 7
""" + dynamics(3000).replace(" t2 0.02", "").replace("1.0 1.0 1.0 3.7", "1.0 1.0 1.0 3.85").replace(
            "compute t all pair vertex/polygon",
            "compute t all pair vertex/polygon\ncompute tis all vertex/tissue\n"
            "variable n equal c_tis[3]\nfix sum all ave/time 1 1 1 v_n mode scalar ave running")
        script = script.replace('print "N', 'print "S $(f_sum*(step+1))"\nprint "N')
        run = self.run_lmp(script, files={"start.data": data})
        t1, t2, _ = printed(run, "N")[0]
        self.assertGreater(t1, 10)
        self.assertEqual(t2, 0)
        self.assertAlmostEqual(printed(run, "S")[0][0], t1, delta=1e-6)

    def test_cell_forces_go_to_the_vertices(self):
        # fix addforce on the cell atoms: each vertex, in three cells, gets a
        # third of each, i.e. the whole force; the cell atoms keep none.
        base = start() + coeffs() + "group cells type 1 2\n"
        dump = ("run 0\nwrite_dump all custom f.dump id fx fy modify format float %.17g "
                "sort id\n")
        plain = self.run_lmp(base + dump).dump("f.dump")[0]
        pushed = self.run_lmp(base + "fix push cells addforce 0.3 -0.2 0\n" + dump).dump("f.dump")[0]
        cells = plain["id"] <= 64
        np.testing.assert_allclose(pushed["fx"][cells], 0.0, atol=1e-14)
        np.testing.assert_allclose(pushed["fx"][~cells] - plain["fx"][~cells], 0.3, atol=1e-12)
        np.testing.assert_allclose(pushed["fy"][~cells] - plain["fy"][~cells], -0.2, atol=1e-12)

    def polarity_run(self, fix, after=""):
        """start() with dipoles, fix polarity (fix) on the cell atoms, run 0,
        then 'after'; the forces, polarities and the data file of step 0."""
        dipole = "atom_style hybrid dipole sphere"
        script = start().replace("atom_style atomic", dipole) + coeffs() + \
            "group cells type 1 2\n" + fix + """
run 0
write_dump all custom f.dump id fx fy mux muy modify format float %.17g sort id
write_data cfg.data
""" + after
        return self.run_lmp(script)

    def test_polarity_force_by_bartons_rule(self):
        # The active force f_a n_c of each cell goes to its vertices, a third
        # to each (Barton et al.): a vertex moves with the mean of its three
        # cells' active forces; so the forces handed to a cell's n vertices
        # add up to n/3 of its own, and the cell atoms keep none.  Expected
        # values from the rings of the data file and the dumped polarities.
        fa = 0.4
        plain = self.polarity_run("").dump("f.dump")[0]
        run = self.polarity_run(f"fix act cells polarity {fa} 1.0 seed 5\n")
        pushed = run.dump("f.dump")[0]
        _, atoms, rings, _ = read_data(run.text("cfg.data"))
        index = {int(i): k for k, i in enumerate(pushed["id"])}
        expect = {v: np.zeros(2) for v in atoms if v not in rings}
        angles = []
        for c, r in rings.items():
            k = index[c]
            n = np.array([pushed["mux"][k], pushed["muy"][k]])
            n /= np.linalg.norm(n)
            angles.append(math.atan2(n[1], n[0]))
            for v in r:
                expect[v] += fa * n / 3.0
        self.assertGreater(np.std(angles), 1.0)    # random polarities, not one direction
        for v, e in expect.items():
            k = index[v]
            got = np.array([pushed["fx"][k] - plain["fx"][k], pushed["fy"][k] - plain["fy"][k]])
            np.testing.assert_allclose(got, e, rtol=0, atol=1e-12, err_msg="vertex %d" % v)
        for c in rings:
            self.assertEqual((pushed["fx"][index[c]], pushed["fy"][index[c]]), (0.0, 0.0))
        total = sum(expect.values())
        cells = sum(len(r) / 3.0 * fa * np.array([math.cos(a), math.sin(a)])
                    for r, a in zip(rings.values(), angles))
        np.testing.assert_allclose(total, cells, rtol=0, atol=1e-12)

    def test_neighbor_alignment_one_step(self):
        # One Euler step of the angles: theta_i += dt / gamma_R * J_S *
        # sum_j sin(theta_j - theta_i) over the cells j sharing an edge with
        # i (from the rings of the data file).
        js, gr, dt = 2.0, 1.5, 0.01
        run = self.polarity_run(f"fix act cells polarity 0.3 {gr} neighbor {js} seed 5\n",
                                f"""fix move vertices brownian 1.0 1 gamma_t 1.0 rng none
timestep {dt}
run 1
write_dump all custom g.dump id mux muy modify format float %.17g sort id
""")
        a, b = run.dump("f.dump")[0], run.dump("g.dump")[0]
        _, _, rings, _ = read_data(run.text("cfg.data"))
        index = {int(i): k for k, i in enumerate(a["id"])}
        theta = {c: math.atan2(a["muy"][index[c]], a["mux"][index[c]]) for c in rings}
        owner = {}
        for c, r in rings.items():
            for k in range(len(r)):
                owner[(r[k], r[(k + 1) % len(r)])] = c
        for c, r in rings.items():
            nbrs = {owner[(r[(k + 1) % len(r)], r[k])] for k in range(len(r))}
            self.assertEqual(len(nbrs), len(r))
            want = theta[c] + dt / gr * js * sum(math.sin(theta[j] - theta[c]) for j in nbrs)
            got = math.atan2(b["muy"][index[c]], b["mux"][index[c]])
            d = (got - want + math.pi) % (2 * math.pi) - math.pi
            self.assertAlmostEqual(d, 0.0, delta=1e-12, msg="cell %d" % c)

    def test_signal_exchange_one_step(self):
        # fix cell/signal between the cells (vertex atoms are no cells): one
        # explicit step of du_i/dt = P sum_j s_ij (u_j - u_i), s_ij the
        # length of the edge cells i and j share (from the rings and
        # positions of the data file; nothing moves).
        P, dt = 0.3, 0.05
        run = self.run_lmp(start() + coeffs() + f"""fix sp all property/atom d_u
variable u0 atom (type<3)*(1+((id*37)%11))
set group all d_u v_u0
fix s all cell/signal exchange d_u {P}
timestep {dt}
run 0
write_data cfg.data
run 1
write_dump all custom u.dump id d_u modify format float %.17g sort id
""")
        box, atoms, rings, _ = read_data(run.text("cfg.data"))
        got = {int(i): u for i, u in zip(*(run.dump("u.dump")[0][c] for c in ("id", "d_u")))}
        u0 = {c: 1 + (c * 37) % 11 for c in rings}
        owner, length = {}, {}
        for c, r in rings.items():
            pts = polygon(box, atoms, r)
            for k in range(len(r)):
                owner[(r[k], r[(k + 1) % len(r)])] = c
                length[(r[k], r[(k + 1) % len(r)])] = np.linalg.norm(pts[(k + 1) % len(r)] - pts[k])
        for c, r in rings.items():
            flux = sum(length[(r[k], r[(k + 1) % len(r)])] *
                       (u0[owner[(r[(k + 1) % len(r)], r[k])]] - u0[c]) for k in range(len(r)))
            self.assertAlmostEqual(got[c], u0[c] + dt * P * flux, delta=1e-12, msg="cell %d" % c)
        self.assertAlmostEqual(sum(got[c] for c in rings), sum(u0.values()), delta=1e-10)
        self.assertTrue(all(got[v] == 0.0 for v in got if v not in rings))

    @nprocs(2)
    def test_polarity_flocks_alike_on_two_ranks(self):
        # fix polarity on the cell atoms (active force, neighbour alignment
        # through the cells' junctions): the same run on 1 and 2 ranks.
        data = self.run_lmp(start(two_types=False).replace("atom_style atomic",
                            "atom_style hybrid dipole sphere") + "write_data start.data\n"
                            ).text("start.data")
        script = from_data().replace("atom_style atomic", "atom_style hybrid dipole sphere") + \
            """group cells type 1
fix act cells polarity 0.3 1.0 neighbor 0.5 seed 11
""" + dynamics(300).replace("t2 0.02", "") + """
print "P $(f_act[1]:%.17g)"
write_dump all custom end.dump id xu yu mux muy modify format float %.17g sort id
"""
        ends = []
        for n in (1, 2):
            run = self.run_lmp(script, nprocs=n, files={"start.data": data})
            ends.append((printed(run, "P")[0][0], run.dump("end.dump")[0]))
        self.assertGreater(ends[0][0], 0.3)
        self.assertAlmostEqual(ends[0][0], ends[1][0], delta=1e-9)
        for col in ("xu", "yu", "mux", "muy"):
            np.testing.assert_allclose(ends[0][1][col], ends[1][1][col], rtol=0, atol=1e-9)

    def test_cell_velocity_and_velocity_alignment(self):
        # A cell atom's velocity is the mean of its vertices' (fix brownian
        # sets theirs to dr/dt): against the rings of the data file; compute
        # vertex/atom's orientation reads it; one Euler step of velocity
        # alignment, theta += -dt / gamma_R * J_V * sin(theta - psi), with
        # psi the direction of that velocity at the step before.
        jv, gr, dt = 1.5, 1.2, 0.01
        run = self.polarity_run(f"fix act cells polarity 0.3 {gr} velocity {jv} seed 5\n", f"""
fix move vertices brownian 1.0 1 gamma_t 1.0 rng none
compute a all vertex/atom
timestep {dt}
dump d all custom 1 v1.dump id vx vy mux muy c_a[7]
dump_modify d format float %.17g sort id
run 1
undump d
write_data end.data
run 1
write_dump all custom v2.dump id mux muy modify format float %.17g sort id
""")
        a, b = run.dump("v1.dump")[-1], run.dump("v2.dump")[0]
        _, _, rings, _ = read_data(run.text("end.data"))
        index = {int(i): k for k, i in enumerate(a["id"])}
        for c, r in rings.items():
            k = index[c]
            want = [np.mean([a[col][index[v]] for v in r]) for col in ("vx", "vy")]
            np.testing.assert_allclose([a["vx"][k], a["vy"][k]], want, rtol=0, atol=1e-12)
            speed = math.hypot(*want)
            self.assertGreater(speed, 1e-3)
            self.assertAlmostEqual(a["c_a[7]"][k], math.acos(want[0] / speed), delta=1e-9)
            theta = math.atan2(a["muy"][k], a["mux"][k])
            psi = math.atan2(want[1], want[0])
            expect = theta - dt / gr * jv * math.sin(theta - psi)
            got = math.atan2(b["muy"][k], b["mux"][k])
            d = (got - expect + math.pi) % (2 * math.pi) - math.pi
            self.assertAlmostEqual(d, 0.0, delta=1e-12, msg="cell %d" % c)


if __name__ == "__main__":
    lmptest.main()
