#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""fix cell/divide and fix cell/death on the cells of the vertex model
(pair_style vertex/polygon): after every division the tissue is valid
(vertex_check, in numpy), the new edge runs through the mother's centroid
normal to her long axis (second moments in numpy), the halves' areas add up to
the mother's and forces equal central differences of pe; a dying cell shrinks
and leaves by a T2; min N counts living cells; the same events on 1, 2 and 4
ranks; a restart continues the run; a long active run with hundreds of
divisions and deaths stays valid; bad input stops with an error naming the
fix."""

import os
import subprocess
import tempfile

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs
from vertex_check import area, centroid, check_tissue, parse_data, polygon

NCELLS = 84    # the hexagonal start: cells 1..84, vertices 85..252


def start(tilt=False):
    """A jittered hexagonal tissue (84 cells of area 0.87 in a 7 x 6 box,
    two cell types, random polarities) written to start.data."""
    region = ("region box prism 0 7 0 6 -0.5 0.5 1.5 0 0" if tilt
              else "region box block 0 7 0 6 -0.5 0.5")
    return f"""dimension 2
units lj
atom_style dipole
atom_modify map yes
boundary p p p
lattice hex 1.0
{region}
create_box 3 box
create_atoms 1 box
set type 1 type/fraction 2 0.4 7731
displace_atoms all random 0.1 0.1 0 4821 units box
set group all dipole/random 3313 1.0
create_vertices all 3
mass * 1.0
write_data start.data nocoeff
"""


def head(p0=3.0):
    """The tissue from start.data (the same atom IDs on any number of
    ranks), per-cell A0 and P0, T1s and T2s."""
    return f"""dimension 2
units lj
atom_style dipole
atom_modify map yes
boundary p p p
fix vring all property/atom i2_vring 16
read_data start.data fix vring NULL vring
mass * 1.0
group cells type 1 2
group vertices type 3
fix pc all property/atom d_area0 d_perim0
set group cells d_area0 1.0
set group cells d_perim0 {p0}
pair_style vertex/polygon 4.0 t1 0.04 0.06 t2 0.05
pair_coeff 1 1 quadratic 1.0 1.0 1.0 {p0}
pair_coeff 2 2 quadratic 1.2 0.9 0.8 {p0}
pair_coeff 1 2 quadratic 0.3
pair_coeff 3 3 vertex
compute t all pair vertex/polygon
"""


def printed(run, key):
    return [[float(v) for v in l.split()[1:]] for l in run.stdout.splitlines()
            if l.startswith(key + " ")]


def long_axis(p):
    """The long principal axis of a polygon's second moments of area."""
    c = centroid(p)
    q = p - c
    m = np.zeros((2, 2))
    for a, b in zip(q, np.roll(q, -1, axis=0)):
        cr = a[0] * b[1] - a[1] * b[0]
        m += cr / 24 * (2 * np.outer(a, a) + 2 * np.outer(b, b) + np.outer(a, b) + np.outer(b, a))
    w, vec = np.linalg.eigh(m)
    return None if w[1] - w[0] < 1e-6 * w.sum() else vec[:, 1]


class Data:
    """start.data, made once per test class."""

    @classmethod
    def data(cls, tc, tilt=False):
        key = "_data_tilt" if tilt else "_data"
        if not hasattr(cls, key):
            setattr(cls, key, tc.run_lmp(start(tilt)).text("start.data"))
        return getattr(cls, key)


class Division(LammpsTestCase):

    def steps(self, fix, nsteps, tilt=False, extra=""):
        """The tissue before and after each of nsteps steps without motion
        (no integrator: the vertices stay where the cut puts them)."""
        # No T1 or T2: nothing but the cuts changes the tissue.
        script = (head().replace(" t1 0.04 0.06 t2 0.05", "") + extra + fix
                  + "\nthermo_style custom step atoms f_div c_t[3]\n")
        script += "thermo_modify norm no\nrun 0\nwrite_data d0.data\n"
        for k in range(1, nsteps + 1):
            script += f"run 1\nwrite_data d{k}.data\nprint \"S{k} $(f_div) $(atoms)\"\n"
        run = self.run_lmp(script, files={"start.data": Data.data(self, tilt)})
        frames = [run.text(f"d{k}.data") for k in range(nsteps + 1)]
        counts = [printed(run, f"S{k}")[0] for k in range(1, nsteps + 1)]
        return frames, counts

    def check_cuts(self, frames, counts, axis_long):
        """Every step: a valid tissue; 1 cell and 2 vertices per division;
        each daughter's ring ends with her two new vertices (IDs daughter + 1,
        + 2), which her mother holds the other way round; mother and daughter
        share the mother's area, the neighbours keep theirs; with axis long,
        the new edge is normal to the mother's long axis and its line passes
        through her centroid unless a new vertex was kept a tenth of an edge
        from a corner."""
        before = check_tissue(self, frames[0], "start")
        ncut = 0
        for k in range(1, len(frames)):
            after = check_tissue(self, frames[k], f"step {k}")
            box, atoms0, rings0, _, areas0 = before
            _, atoms1, rings1, _, areas1 = after
            ndiv, natoms = counts[k - 1]
            self.assertEqual(len(rings1), NCELLS + ndiv)
            self.assertEqual(natoms, 3 * NCELLS + 3 * ndiv)
            for d in sorted(set(rings1) - set(rings0)):
                r = rings1[d]
                v1, v2 = d + 1, d + 2
                self.assertEqual(r[-2:], [v2, v1], f"daughter {d}: {r}")
                mother = [c for c, rr in rings1.items() if c != d and v1 in rr and v2 in rr
                          and rr[(rr.index(v1) + 1) % len(rr)] == v2]
                self.assertEqual(len(mother), 1, f"daughter {d}")
                m = mother[0]
                self.assertIn(m, rings0)
                self.assertAlmostEqual(areas1[m] + areas1[d], areas0[m], delta=1e-10)
                for c, rr in rings1.items():
                    if c not in (m, d) and c in rings0 and (v1 in rr or v2 in rr):
                        self.assertAlmostEqual(areas1[c], areas0[c], delta=1e-10)
                if axis_long:
                    old = polygon(box, atoms0, rings0[m])
                    u = long_axis(old)
                    if u is None:
                        continue
                    if self.clamped(box, atoms0, atoms1, rings0[m], v1, v2):
                        continue    # a new vertex kept a tenth of an edge from a corner
                    e = polygon(box, atoms1, [v1, v2])
                    t = (e[1] - e[0]) / np.linalg.norm(e[1] - e[0])
                    self.assertLess(abs(float(np.dot(t, u))), 1e-9, f"mother {m}")
                    c0 = centroid(old)
                    g = polygon(box, {0: (0, *c0), 1: atoms1[v1]}, [0, 1])
                    off = abs(float(np.cross(t, g[1] - g[0])))
                    self.assertLess(off, 1e-9, f"mother {m}: the cut misses her centroid")
                    ncut += 1
            before = after
        return ncut

    @staticmethod
    def clamped(box, atoms0, atoms1, ring, v1, v2):
        """Whether one of the new vertices sits at 0.1 or 0.9 of its edge."""
        for v in (v1, v2):
            x = np.array(atoms1[v][1:])
            for a, b in zip(ring, ring[1:] + ring[:1]):
                seg = polygon(box, {0: (0, *x), a: atoms0[a], b: atoms0[b]}, [0, a, b])
                e = seg[2] - seg[1]
                s = np.dot(seg[0] - seg[1], e) / np.dot(e, e)
                dist = np.linalg.norm(seg[1] + s * e - seg[0])
                if dist < 1e-9 and (abs(s - 0.1) < 1e-9 or abs(s - 0.9) < 1e-9):
                    return True
        return False

    def test_each_division_valid_random_axis(self):
        frames, counts = self.steps("fix div cells cell/divide rate 20.0 seed 4821 axis random",
                                    6)
        self.check_cuts(frames, counts, False)
        self.assertGreater(counts[-1][0], 20)

    def test_long_axis_through_centroid(self):
        # The area trigger: every cell above 0.5 wants to divide at once; the
        # ones that share a cell with an earlier one wait for the next step.
        frames, counts = self.steps("fix div cells cell/divide area 0.5 seed 4821 axis long", 5)
        ncut = self.check_cuts(frames, counts, True)
        self.assertGreater(counts[-1][0], 40)
        self.assertGreater(ncut, 20)

    def test_tilted_box(self):
        frames, counts = self.steps("fix div cells cell/divide rate 20.0 seed 7 axis short", 4,
                                    tilt=True)
        self.check_cuts(frames, counts, False)
        self.assertGreater(counts[-1][0], 10)

    def test_lineage_and_state(self):
        """The daughter is a copy of her mother (type, A0, P0) with a new ID;
        both are one generation on, with the mother's ID and age 0; the
        event log lists the division."""
        script = head() + """fix div cells cell/divide rate 20.0 seed 4821 file div.log
run 1
write_data d1.data
write_dump cells custom cells.dump id type f_div[2] f_div[5] f_div[1] modify sort id
"""
        run = self.run_lmp(script, files={"start.data": Data.data(self)})
        _, atoms0, rings0, props0 = parse_data(Data.data(self))
        _, atoms1, rings1, props1 = parse_data(run.text("d1.data"))
        frame = run.dump("cells.dump")[0]
        row = {int(i): k for k, i in enumerate(frame["id"])}
        new = sorted(set(rings1) - set(rings0))
        self.assertGreater(len(new), 3)
        log = run.text("div.log")
        for d in new:
            m = int(frame["f_div[5]"][row[d]])
            self.assertIn(m, rings0)
            self.assertEqual(atoms1[d][0], atoms1[m][0])
            self.assertEqual(int(frame["f_div[5]"][row[m]]), m)
            for k in (d, m):
                self.assertEqual(frame["f_div[2]"][row[k]], 1.0)
                # (born at the start of the step, which ages them by dt)
                self.assertEqual(frame["f_div[1]"][row[k]], 0.005)
            for name in ("area0", "perim0"):
                self.assertEqual(props1[name][d], props1[name][m])
            self.assertRegex(log, rf"(?m)^\S+\s+\S+\s+divide\s+{m}\s+{m}\s+{d}\b")

    def test_forces_after_division(self):
        """Right after divisions (new vertices on straight edges, new rings),
        the forces on new and old vertices equal central differences of pe."""
        script = head() + """fix div cells cell/divide rate 20.0 seed 4821
run 1
unfix div
thermo_style custom step pe
thermo_modify norm no format float %.17g
run 0
write_data d1.data
"""
        run = self.run_lmp(script, files={"start.data": Data.data(self)})
        _, atoms, rings, _ = parse_data(run.text("d1.data"))
        new = [v for v in atoms if v > 3 * NCELLS and atoms[v][0] == 3][:4]
        self.assertEqual(len(new), 4)
        probes = new + [100, 200]
        h = 1e-5
        fd = head() + """fix div cells cell/divide rate 20.0 seed 4821
run 1
unfix div
thermo_style custom step pe
thermo_modify norm no
"""
        for a in probes:
            fd += f"""group g{a} id {a}
run 0
print "F{a} $(fx[{a}]:%.17g) $(fy[{a}]:%.17g)"
"""
            for k, (dx, dy) in enumerate(((h, 0), (-h, 0), (0, h), (0, -h))):
                fd += f"""displace_atoms g{a} move {dx} {dy} 0 units box
run 0
print "E{a}_{k} $(pe:%.17g)"
displace_atoms g{a} move {-dx} {-dy} 0 units box
"""
        run = self.run_lmp(fd, files={"start.data": Data.data(self)})
        for a in probes:
            f = printed(run, f"F{a}")[0]
            e = [printed(run, f"E{a}_{k}")[0][0] for k in range(4)]
            self.assertAlmostEqual(f[0], -(e[0] - e[1]) / (2 * h), delta=1e-5 * (1 + abs(f[0])))
            self.assertAlmostEqual(f[1], -(e[2] - e[3]) / (2 * h), delta=1e-5 * (1 + abs(f[1])))


ACTIVE = """fix b vertices brownian 1.0 1 gamma_t 1.0 rng none
fix p cells polarity 0.3 1.0
fix div cells cell/divide rate {rate} seed 4821 axis random
fix die cells cell/death rate {rate} seed 77
timestep {dt}
thermo_style custom step atoms pe f_div f_die c_t[1] c_t[2] c_t[3]
thermo_modify norm no format float %.17g
thermo 100
"""


class Death(LammpsTestCase):

    def test_dying_cell_leaves_by_t2(self):
        """One cell (in a region around cell 40) dies: it shrinks and a T2
        takes it; no other cell leaves; the tissue stays valid."""
        _, atoms, _, _ = parse_data(Data.data(self))
        x, y = atoms[40][1:]
        region = f"{x - 0.2} {x + 0.2} {y - 0.2} {y + 0.2} -1 1"
        script = head() + f"""region one block {region} units box
fix b vertices brownian 1.0 1 gamma_t 1.0 rng none
fix die cells cell/death rate 1000 seed 77 region one file die.log
thermo_style custom step atoms c_t[2]
timestep 0.002
run 1
print "D $(f_die)"
unfix die
run 1000
print "N $(c_t[2]) $(atoms)"
write_data end.data
"""
        run = self.run_lmp(script, files={"start.data": Data.data(self)})
        _, _, rings, _, _ = check_tissue(self, run.text("end.data"), "end")
        self.assertNotIn(40, rings)
        self.assertEqual(len(rings), NCELLS - 1)
        self.assertEqual(printed(run, "D")[0], [1.0])
        self.assertEqual(printed(run, "N")[0], [1.0, 3 * NCELLS - 3])
        self.assertRegex(run.text("die.log"), r"(?m)^\S+\s+\S+\s+death\s+40\b")

    def test_floor_counts_living_cells(self):
        """min 80: four cells begin to die, and no more while they linger
        (dying cells are no longer living cells); a dying cell does not
        divide."""
        script = head() + """fix b vertices brownian 1.0 1 gamma_t 1.0 rng none
fix die cells cell/death rate 1000 seed 77 min 80
fix div cells cell/divide rate 1000 seed 5 max 1
timestep 0.002
run 3
print "N $(f_die) $(f_div)"
"""
        run = self.run_lmp(script, files={"start.data": Data.data(self)})
        self.assertEqual(printed(run, "N")[0], [4.0, 0.0])

    def test_dying_cell_does_not_divide(self):
        """Every cell decides to die and to divide at step 0: all begin to
        die at step 1 (fix die comes first), and none divides then or later."""
        script = head() + """fix die cells cell/death rate 1000 seed 77 min 0
fix div cells cell/divide rate 1000 seed 5
run 3
print "N $(f_die) $(f_div)"
"""
        run = self.run_lmp(script, files={"start.data": Data.data(self)})
        self.assertEqual(printed(run, "N")[0], [float(NCELLS), 0.0])

    def test_long_active_run(self):
        """Fast polarity, divisions and deaths at the same rate: hundreds of
        events, every cell valid every step (the pair style checks each cell
        at each force computation and stops otherwise) and at the end (numpy);
        the dying cells leave."""
        script = head() + ACTIVE.format(rate=0.2, dt=0.003) + """run 5000
print "N $(f_div) $(f_die) $(c_t[2])"
write_data end.data
"""
        run = self.run_lmp(script, files={"start.data": Data.data(self)})
        ndiv, ndie, nt2 = printed(run, "N")[0]
        self.assertGreater(ndiv, 150)
        self.assertGreater(ndie, 150)
        self.assertGreater(nt2, 0.8 * ndie)
        _, _, rings, props, _ = check_tissue(self, run.text("end.data"), "end")
        self.assertEqual(len(rings), NCELLS + ndiv - nt2)


class Parallel(LammpsTestCase):

    @nprocs(4)
    def test_same_on_1_2_4_ranks(self):
        """The same divisions and deaths, with the same IDs, and the same
        positions to round-off on 1, 2 and 4 ranks (4 ranks on this tissue:
        many cuts straddle a rank boundary)."""
        script = head() + ACTIVE.format(rate=2.0, dt=0.002) + """run 600
print "N $(f_div) $(f_die) $(c_t[1]) $(c_t[2]) $(atoms)"
write_dump all custom end.dump id type x y modify format float %.17g sort id
"""
        results = []
        for n in (1, 2, 4):
            run = self.run_lmp(script, nprocs=n, files={"start.data": Data.data(self)})
            results.append((printed(run, "N")[0], run.dump("end.dump")[0]))
        self.assertGreater(results[0][0][0], 50)
        self.assertGreater(results[0][0][1], 50)
        for counts, frame in results[1:]:
            self.assertEqual(counts, results[0][0])
            np.testing.assert_array_equal(frame["id"], results[0][1]["id"])
            np.testing.assert_array_equal(frame["type"], results[0][1]["type"])
            for col in ("x", "y"):
                np.testing.assert_allclose(frame[col], results[0][1][col], rtol=0, atol=1e-9)

    @nprocs(2)
    def test_restart_continues(self):
        """A run written to a restart file half-way and continued makes the
        same events and ends at the same positions as one run."""
        fixes = ACTIVE.format(rate=2.0, dt=0.002)
        end = """print "N $(f_div) $(f_die) $(c_t[2]) $(atoms)"
write_dump all custom end.dump id type x y modify format float %.17g sort id
"""
        whole = self.run_lmp(head() + fixes + "run 400\n" + end,
                             files={"start.data": Data.data(self)})
        first = self.run_lmp(head() + fixes + "run 200\nwrite_restart half.restart\n",
                             files={"start.data": Data.data(self)})
        cont = f"""read_restart {first.path("half.restart")}
fix pc all property/atom d_area0 d_perim0
group cells type 1 2
group vertices type 3
compute t all pair vertex/polygon
""" + fixes + "run 200\n" + end
        second = self.run_lmp(cont, nprocs=2)
        self.assertEqual(printed(second, "N")[0][:2], printed(whole, "N")[0][:2])
        self.assertEqual(printed(second, "N")[0][3], printed(whole, "N")[0][3])
        a, b = whole.dump("end.dump")[0], second.dump("end.dump")[0]
        np.testing.assert_array_equal(a["id"], b["id"])
        for col in ("x", "y"):
            np.testing.assert_allclose(a[col], b[col], rtol=0, atol=1e-9)


EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")
TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools")


class Example(LammpsTestCase):

    def test_vertex_growth(self):
        """examples/vertex_growth, shortened (t = 8, cap 70): the cells divide
        (one cell atom and two vertex atoms each), the box follows the cell
        number (mean area 1) and the tissue at the end is valid."""
        with open(os.path.join(EXAMPLES, "vertex_growth", "in.vertex_growth")) as f:
            script = f.read()
        script += 'print "N $(v_ncell) $(f_div[2]) $(atoms) $(lx*ly)"\n'
        run = self.run_lmp(script, variables={"tend": "8", "Nmax": "70"})
        ncell, ndiv, natoms, area = printed(run, "N")[0]
        self.assertGreater(ndiv, 10)
        self.assertEqual(ncell, 50 + ndiv)
        self.assertEqual(natoms, 3 * ncell)
        self.assertAlmostEqual(area / ncell, 1.0, delta=1e-6)
        _, _, rings, _, _ = check_tissue(self, run.text("vertex_growth.data"), "example")
        self.assertEqual(len(rings), ncell)


    def test_vertex_bead(self):
        """examples/vertex_bead, shortened (100 + 300 steps): the pull moves
        the bead along the force; every pair force inside the system cancels
        (soft's pairs, the vertex model's translation invariance) and no
        force is lost on a cell atom, so the movers' summed displacement
        (their centre of mass, masses 1) grows by exactly F t / gamma_t (overdamped Euler without noise); the
        solid makes no T1, the fluid does; the tissue stays valid."""
        with open(os.path.join(EXAMPLES, "vertex_bead", "in.vertex_bead")) as f:
            script = f.read()
        script = script.replace("fix             pull", """variable s0 equal $(xcm(movers,x)*count(movers):%.17g)
fix             pull""")
        script = script.replace("write_data", 'print "B $(v_dx:%.17g) '
                                '$(xcm(movers,x)*count(movers)-v_s0:%.17g) $(c_topo[1])"\n'
                                "write_data")
        for p0, t1s in (("3.7", False), ("3.95", True)):
            with self.subTest(p0=p0):
                run = self.run_lmp(script, variables={"relax": "100", "pull": "300", "p0": p0})
                dx, moved, nt1 = printed(run, "B")[0]
                self.assertGreater(dx, 0.0)
                pull_time = 300 * 0.01
                # (the sum of about 1e4 unwrapped coordinates: round-off 1e-12 of it)
                self.assertAlmostEqual(moved, 0.3 * pull_time, delta=1e-7)
                self.assertEqual(nt1 > 0, t1s)
                check_tissue(self, run.text(f"vertex_bead_{p0}.data"), f"bead p0 {p0}")


    def test_vertex_segmented(self):
        """examples/vertex_segmented, shortened (500 + 200 steps): the data
        file tessera-tools made from the label image reads as a valid vertex
        tissue whose cells' areas (compute vertex/atom) are the tool's
        polygons' (numpy), and the relaxation keeps it valid."""
        d = os.path.join(EXAMPLES, "vertex_segmented")
        with open(os.path.join(d, "in.vertex_segmented")) as f:
            script = f.read()
        # The data file as the example's README makes it.
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run(["/usr/bin/python3", os.path.join(TOOLS, "tessera-tools"), "segmented",
                            os.path.join(d, "labels.txt"), "--boundary-label", "0", "--pixel",
                            "0.0645497", "-o", os.path.join(tmp, "tissue.data")],
                           check=True, stdout=subprocess.DEVNULL)
            with open(os.path.join(tmp, "tissue.data")) as f:
                data = f.read()
        script = script.replace("timestep        0.001\n", """dump a cells custom 1 a0.dump id c_va[1]
dump_modify a format float %.17g sort id
run 0
undump a
timestep        0.001
""")
        run = self.run_lmp(script, variables={"steps": "200"}, files={"tissue.data": data})
        box, atoms, rings, _, areas = check_tissue(self, data, "segmented start")
        f = run.dump("a0.dump")[0]
        for cid, a in zip(f["id"].astype(int), f["c_va[1]"]):
            self.assertAlmostEqual(a, areas[cid], delta=1e-12)
        self.assertEqual(len(f["id"]), 80)
        check_tissue(self, run.text("relaxed_3.7.data"), "segmented relaxed")


class BadInput(LammpsTestCase):

    def fails(self, script, *fragments):
        run = self.run_lmp(head() + script + "run 1\n", ok=False,
                           files={"start.data": Data.data(self)})
        out = run.stdout + run.stderr
        self.assertIn("ERROR", out)
        for f in fragments:
            self.assertIn(f, out)

    def test_death_needs_area0_and_perim0(self):
        run = self.run_lmp(head().replace("fix pc all property/atom d_area0 d_perim0",
                                          "fix pc all property/atom d_area0")
                           .replace("set group cells d_perim0 3.0\n", "")
                           + "fix die cells cell/death rate 1 seed 3\nrun 1\n", ok=False,
                           files={"start.data": Data.data(self)})
        out = run.stdout + run.stderr
        self.assertIn("fix cell/death die", out)
        self.assertIn("missing: d_perim0", out)

    def test_death_needs_t2(self):
        run = self.run_lmp(head().replace(" t2 0.05", "")
                           + "fix die cells cell/death rate 1 seed 3\nrun 1\n", ok=False,
                           files={"start.data": Data.data(self)})
        out = run.stdout + run.stderr
        self.assertIn("fix cell/death die", out)
        self.assertIn("t2 0", out)

    def test_one_divide_fix(self):
        self.fails("fix d1 cells cell/divide rate 1 seed 3\n"
                   "fix d2 cells cell/divide rate 1 seed 4\n",
                   "fix cell/divide d1", "takes one fix cell/divide (2 are defined)")


if __name__ == "__main__":
    lmptest.main()
