#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Every model with every feature: one test per line of feature_matrix.txt.

A model is the start of an input script (a jittered tissue of that model,
two cell types, atom style dipole); a feature is a check that can fail
against something independent of the code's own output: central
differences of pe for forces and the virial, sums that must equal the total
energy or the box, rows that must close each cell's boundary, a second run
that must agree (restart, rank counts, pair_coeff instead of fix adapt), the
geometry of a division.  A line whose expectation is "error <fragment>" must
stop with a LAMMPS ERROR line that contains the fragment."""

import math
import os
import re

import numpy as np

import lmptest
from feature_adaptive import AdaptiveChecks
from feature_outputs import OutputChecks
from feature_state import StateChecks
from feature_models import (COEFFS_2D, COEFFS_3D, COEFFS_FINITE, PARTICLE_IDS, POLYGON_CELLS,
                            PARTICLE_PROBES, PROBES, SPHERE_C, SPHERE_R, dim_of, is_polygon,
                            local_rows, model_script, polygon_death, polygon_groups, printed,
                            read_matrix)
from vertex_check import check_tissue
from feature_cellfix import check_particles_fixes
from feature_particles import check_polygon_particles, probe_particles
from feature_signal import check_signal
from lmptest import LammpsTestCase

HERE = os.path.dirname(os.path.abspath(__file__))


class FeatureMatrix(AdaptiveChecks, OutputChecks, StateChecks, LammpsTestCase):
    """One test per (model, feature); methods are added from the data file."""

    model = None    # the model of the running test

    def run_lmp(self, script, **kw):
        if is_polygon(self.model):
            script = polygon_groups(script)
        # thermo_style resets thermo_modify: pe is the total energy (norm no)
        # after every thermo_style too.
        script = re.sub(r"^(thermo_style .*)$", r"\1\nthermo_modify norm no format float %.17g",
                        script, flags=re.M)
        return super().run_lmp(script, **kw)

    # ---- the checks: each gets the model and returns nothing (asserts) ----

    def check_forces(self, model, particles=False):
        d = dim_of(model)
        h = 1e-5
        if model == "sphere" and particles:
            # A moved cell is put back on the sphere: the two displaced
            # points are symmetric only to O(h^2/R), an O(h) error in the
            # difference quotient (4e-6 at h = 1e-5 for atom 17, with or
            # without the particles) that the smaller forces of a particle
            # no longer hide in the tolerance.
            h = 1e-6
        moves = ""
        # (With particles atom 5 is one: the force on it is soft's alone.)
        probes = PARTICLE_PROBES if particles else PROBES
        for atom in probes.get(model, (5, 17)):
            moves += f"group a{atom} id {atom}\nrun 0\n"
            moves += f'print "F {atom} $(fx[{atom}]:%.17g) $(fy[{atom}]:%.17g) $(fz[{atom}]:%.17g)"\n'
            moves += f'print "X {atom} $(x[{atom}]:%.17g) $(y[{atom}]:%.17g) $(z[{atom}]:%.17g)"\n'
            for k, axis in enumerate("xyz"[:d]):
                v = ["0", "0", "0"]
                v[k] = repr(h)
                moves += f"displace_atoms a{atom} move {' '.join(v)} units box\nrun 0\n"
                moves += f'print "EP {atom} {k} $(pe:%.17g)"\n'
                v[k] = repr(-2 * h)
                moves += f"displace_atoms a{atom} move {' '.join(v)} units box\nrun 0\n"
                moves += f'print "EM {atom} {k} $(pe:%.17g)"\n'
                v[k] = repr(h)
                moves += f"displace_atoms a{atom} move {' '.join(v)} units box\n"
        run = self.run_lmp(model_script(model, particles=particles) +
                           "thermo_style custom step pe\nrun 0\n" + moves)
        forces = {int(r[0]): r[1:] for r in printed(run, "F")}
        if model == "sphere":
            # A cell is put back on the sphere after a move: central
            # differences see the force's tangent part, (1 - u u) F (the
            # pair style's own forces are tangent; another style's need not be).
            for atom, x in ((int(r[0]), np.array(r[1:])) for r in printed(run, "X")):
                if particles and atom in PARTICLE_IDS:
                    continue
                u = (x - SPHERE_C) / np.linalg.norm(x - SPHERE_C)
                f = np.array(forces[atom])
                forces[atom] = list(f - np.dot(f, u) * u)
        ep = {(int(r[0]), int(r[1])): r[2] for r in printed(run, "EP")}
        em = {(int(r[0]), int(r[1])): r[2] for r in printed(run, "EM")}
        scale = max(abs(x) for f in forces.values() for x in f) + 1e-3
        for (atom, k), e_plus in ep.items():
            fd = -(e_plus - em[(atom, k)]) / (2 * h)
            self.assertAlmostEqual(forces[atom][k], fd, delta=1e-6 * scale,
                                   msg=f"atom {atom} component {k}")
        self.assertGreater(scale, 1e-3)    # a check with forces to check

    def check_virial(self, model):
        e = 1e-6
        # A uniform strain along x: in a triclinic box the tilts of the
        # vectors with an x part (xy, xz) scale with lx.
        def strain(s):
            tilt = ""
            if model.endswith("_tri"):
                tilt = " xy final $(xy*%r)" % s + (" xz final $(xz*%r)" % s if dim_of(model) == 3 else "")
            return f"change_box all x scale {s!r}{tilt} remap units box\n"
        script = model_script(model) + f"""thermo_style custom step pe pxx vol
run 0
print "P $(pxx:%.17g) $(vol:%.17g) $(lx:%.17g)"
{strain(1 + e)}run 0
print "EP $(pe:%.17g)"
{strain((1 - e) / (1 + e))}run 0
print "EM $(pe:%.17g)"
"""
        run = self.run_lmp(script)
        pxx, vol, _ = printed(run, "P")[0]
        dedx = (printed(run, "EP")[0][0] - printed(run, "EM")[0][0]) / (2 * e)
        # (vol is the area in 2d, as LAMMPS's pressure divides by it.)
        self.assertAlmostEqual(pxx, -dedx / vol, delta=1e-5 * (abs(pxx) + 1e-3))

    def check_vertex_atom(self, model):
        script = model_script(model) + """compute c all vertex/atom
compute t all vertex/tissue
compute e all reduce sum c_c[5]
compute a all reduce sum c_c[1]
thermo_style custom step pe c_e c_a c_t[1] c_t[2] c_t[3] c_t[4] c_t[5] vol
dump d all custom 1 cells.dump id type x y z c_c[1] c_c[2] c_c[3] c_c[4] c_c[5] c_c[6] c_c[7] c_c[8] c_c[9]
dump_modify d format float %.17g
run 0
print "T $(pe:%.17g) $(c_e:%.17g) $(c_a:%.17g) $(vol:%.17g)"
print "V $(c_t[1]:%.17g) $(c_t[2]:%.17g) $(c_t[3]:%.17g) $(c_t[4]:%.17g) $(c_t[5]:%.17g)"
"""
        run = self.run_lmp(script)
        pe, esum, asum, vol = printed(run, "T")[0]
        # The cells' energies add up to pe (constants of the quadratic form included).
        self.assertAlmostEqual(esum, pe, delta=1e-10 * abs(pe))
        if model == "sphere":    # the cells tile the sphere
            self.assertAlmostEqual(asum, 4 * math.pi * SPHERE_R ** 2, delta=1e-9 * asum)
        elif model not in ("finite_open", "finite_per"):
            self.assertAlmostEqual(asum, vol, delta=1e-9 * vol)    # the cells tile the box
        else:
            self.assertLess(asum, vol)
        f = run.dump("cells.dump")[0]
        d = dim_of(model)
        if is_polygon(model):
            # the vertex atoms' rows are zero; the cells' rows are checked
            vertex = f["type"] == 3
            for col in ("c_c[%d]" % k for k in range(1, 10)):
                self.assertTrue(np.all(f[col][vertex] == 0.0), col)
            f = {k: v[~vertex] if k.startswith("c_c") else v for k, v in f.items()}
        meas, bound, shape, nb = f["c_c[1]"], f["c_c[2]"], f["c_c[3]"], f["c_c[4]"]
        for col in ("c_c[%d]" % k for k in range(1, 10)):
            self.assertTrue(np.all(np.isfinite(f[col])), col)
        expect = bound / meas ** 0.5 if d == 2 or model == "sphere" else bound / meas ** (2.0 / 3.0)
        np.testing.assert_allclose(shape, expect, rtol=1e-12)
        self.assertTrue(np.all(nb >= (0 if model == "finite_open" else 3)))
        np.testing.assert_allclose(f["c_c[5]"].sum(), pe, rtol=1e-10)
        free, edge = f["c_c[8]"], f["c_c[9]"]
        if model.startswith("finite"):
            self.assertTrue(np.all(free <= bound + 1e-12))
            np.testing.assert_array_equal(edge, (free > 0).astype(float))
            if model == "finite_open":
                self.assertGreater(edge.sum(), 0)
        else:
            self.assertTrue(np.all(free == 0) and np.all(edge == 0))
        mean_shape = printed(run, "V")[0][0]
        self.assertAlmostEqual(mean_shape, shape.mean(), delta=1e-9)

    def check_vertex_local(self, model):
        d = dim_of(model)
        cols = "c_l[1] c_l[2] c_l[3] c_l[4] c_l[5] c_l[6] c_l[7]" + (" c_l[8] c_l[9]" if d == 3 else "")
        script = model_script(model) + f"""compute c all vertex/atom
compute l all vertex/local
dump d all local 1 faces.dump {cols}
dump_modify d format float %.17g
dump e all custom 1 cells.dump id c_c[1] c_c[2]
dump_modify e format float %.17g
run 0
"""
        run = self.run_lmp(script)
        rows = local_rows(run, "faces.dump")[0]
        cells = run.dump("cells.dump")[0]
        perim = dict(zip(cells["id"], cells["c_c[2]"]))
        if is_polygon(model):    # vertex atoms are no cells: no rows, zero perimeter
            self.assertTrue(all(perim[i] == 0.0 for i in perim if i > POLYGON_CELLS))
            perim = {i: p for i, p in perim.items() if i <= POLYGON_CELLS}
        ids = rows[:, 0].astype(int)
        self.assertEqual(set(ids), set(perim))
        if model == "sphere":
            # Each row a geodesic edge: its length R times the angle of its
            # ends; each cell's rows close into its boundary, lengths add up
            # to the perimeter.
            c = np.full(3, SPHERE_C)
            for cid in set(ids):
                r = rows[ids == cid]
                a, b = r[:, 2:5] - c, r[:, 5:8] - c
                np.testing.assert_allclose(np.linalg.norm(a, axis=1), SPHERE_R, rtol=1e-12)
                ang = np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.einsum("ij,ij->i", a, b))
                np.testing.assert_allclose(r[:, 8], SPHERE_R * ang, rtol=1e-9, atol=1e-12)
                np.testing.assert_allclose(r[:-1, 5:8], r[1:, 2:5], atol=1e-9)
                np.testing.assert_allclose(r[-1, 5:8], r[0, 2:5], atol=1e-9)
                self.assertAlmostEqual(r[:, 8].sum(), perim[cid], delta=1e-10 * perim[cid])
        elif d == 2:
            # Each cell's rows close into its boundary; lengths add up to the perimeter.
            for cid in set(ids):
                r = rows[ids == cid]
                np.testing.assert_allclose(r[:-1, 4:6], r[1:, 2:4], atol=1e-12)
                np.testing.assert_allclose(r[-1, 4:6], r[0, 2:4], atol=1e-12)
                self.assertAlmostEqual(r[:, 6].sum(), perim[cid], delta=1e-10 * perim[cid])
                arcs = r[r[:, 1] == 0]
                if not model.startswith("finite"):
                    self.assertEqual(len(arcs), 0)
            if model == "finite_open":
                self.assertGreater(int((rows[:, 1] == 0).sum()), 0)
        else:
            # Each face's edges close into a polygon; face areas add up to the surface.
            for cid in set(ids):
                r = rows[ids == cid]
                surface = 0.0
                for nb in set(r[:, 1].astype(int)):
                    face = r[r[:, 1] == nb]
                    starts = {tuple(np.round(p, 9)) for p in face[:, 2:5]}
                    ends = {tuple(np.round(p, 9)) for p in face[:, 5:8]}
                    self.assertEqual(starts, ends)
                    surface += face[0, 8]
                    # The polygon's area (fan from its first corner) is the face area.
                    p0 = face[0, 2:5]
                    vec = sum(np.cross(a - p0, b - p0) for a, b in zip(face[:, 2:5], face[:, 5:8]))
                    self.assertAlmostEqual(0.5 * np.linalg.norm(vec), face[0, 8], delta=1e-9)
                self.assertAlmostEqual(surface, perim[cid], delta=1e-8 * perim[cid])

    def dynamics(self, model, integrator, steps=30, extra=""):
        return model_script(model) + f"""fix p all polarity 0.3 1.0 neighbor 0.5 noise 0.2 77
fix b all {integrator} 1.0 1 gamma_t 1.0 rng none
timestep 0.005
{extra}
thermo_style custom step pe
run {steps}
write_dump all custom end.dump id x y z mux muy muz modify format float %.17g
"""

    def check_unit_polarities(self, model, frame):
        if is_polygon(model):    # the cells carry the polarities
            cell = frame["id"] <= POLYGON_CELLS
            frame = {k: v[cell] for k, v in frame.items() if k in ("mux", "muy", "muz")}
        n = np.sqrt(frame["mux"] ** 2 + frame["muy"] ** 2 + frame["muz"] ** 2)
        np.testing.assert_allclose(n, 1.0, atol=1e-12)
        if dim_of(model) == 2:
            self.assertTrue(np.all(frame["muz"] == 0.0))
        if model == "sphere" and "x" in frame:    # tangent to the sphere
            r = np.column_stack([frame[c] for c in "xyz"]) - SPHERE_C
            mu = np.column_stack([frame["mux"], frame["muy"], frame["muz"]])
            np.testing.assert_allclose(np.linalg.norm(r, axis=1), SPHERE_R, rtol=1e-12)
            np.testing.assert_allclose(np.einsum("ij,ij->i", r, mu), 0.0, atol=1e-11)

    def check_polarity(self, model):
        start = self.run_lmp(model_script(model) + "run 0\nwrite_dump all custom s.dump id mux muy muz\n")
        run = self.run_lmp(self.dynamics(model, "brownian"))
        f = run.dump("end.dump")[0]
        self.check_unit_polarities(model, f)
        s = start.dump("s.dump")[0]
        self.assertGreater(np.abs(f["mux"] - s["mux"]).max(), 1e-3)    # they turned

    def check_brownian(self, model):
        run = self.run_lmp(self.dynamics(model, "brownian"))
        self.check_unit_polarities(model, run.dump("end.dump")[0])

    def check_heun(self, model):
        # Second order without noise: halving dt changes the end state ~4x less.
        def state(dt, steps):
            script = model_script(model) + f"""fix p all polarity 0.3 1.0 neighbor 0.5
fix b all brownian/heun 1.0 1 gamma_t 1.0 rng none
timestep {dt}
run {steps}
write_dump all custom end.dump id xu yu zu mux muy muz modify format float %.17g
"""
            f = self.run_lmp(script).dump("end.dump")[0]
            return np.concatenate([f[c] for c in ("xu", "yu", "zu", "mux", "muy", "muz")])
        # Against the finest of dt, dt/2, dt/4 the errors shrink by
        # (1 - 1/16) / (1/4 - 1/16) = 5 for second order, 3 for first.
        a, b, c = state(0.004, 10), state(0.002, 20), state(0.001, 40)
        e1, e2 = np.abs(a - c).max(), np.abs(b - c).max()
        self.assertGreater(e1, 0.0)
        self.assertGreater(e1 / e2, 4.2, f"errors {e1} {e2}: not second order")

    def check_divide(self, model):
        cases = [("rate 20.0", "random"), ("cycle 0.05 spread 0.01", "long"),
                 ("area 0.5", "short"), ("rate 20.0", "polarity")]
        for trigger, axis in cases:
            script = model_script(model) + f"""fix b all brownian 1.0 1 gamma_t 1.0 rng none
compute c all vertex/atom
fix div all cell/divide {trigger} seed 4821 axis {axis} separation 0.1 max 110
timestep 0.005
thermo_style custom step atoms pe
print "N0 $(atoms)"
run 4
print "N1 $(atoms)"
write_data end.data
"""
            run = self.run_lmp(script)
            n0, n1 = printed(run, "N0")[0][0], printed(run, "N1")[0][0]
            self.assertGreater(n1, n0, f"{trigger} axis {axis}: no division")
            if is_polygon(model):    # the cuts leave a valid tissue
                check_tissue(self, run.text("end.data"), f"{model} {trigger} axis {axis}")
        if model in ("confluent", "3d"):
            self.check_division_axis(model)

    def check_division_axis(self, model):
        """With the area trigger every cell divides, along its long axis
        (Hertwig): the daughter sits at +h u from the mother's centre, with u
        the long principal axis of the mother's cell, computed here from the
        cell's boundary (vertex/local rows) by numpy."""
        d = dim_of(model)
        cols = "c_l[1] c_l[2] c_l[3] c_l[4] c_l[5] c_l[6] c_l[7]" + (" c_l[8] c_l[9]" if d == 3 else "")
        h = 0.005
        script = model_script(model) + f"""compute l all vertex/local
dump f all local 1 faces.dump {cols}
dump_modify f format float %.17g
run 0
undump f
write_dump all custom before.dump id x y z modify format float %.17g
fix div all cell/divide area 0.5 seed 4821 axis long separation {2 * h!r} max 100000
run 1
write_dump all custom after.dump id x y z modify format float %.17g
"""
        run = self.run_lmp(script)
        rows = local_rows(run, "faces.dump")[0]
        before, after = run.dump("before.dump")[0], run.dump("after.dump")[0]
        n = len(before["id"])
        self.assertEqual(len(after["id"]), 2 * n)
        lengths = run.dump("before.dump")[0]["box"]
        L = lengths[:, 1] - lengths[:, 0]
        xb = np.stack([before[c] for c in "xyz"], axis=1)
        xa = np.stack([after[c] for c in "xyz"], axis=1)
        checked = 0
        for k in range(n, 2 * n):
            # The daughter's mother: the old centre 2h away (minimum image).
            diff = xa[k] - xb
            diff -= L * np.round(diff / L)
            m = int(np.argmin(np.linalg.norm(diff[:, :d], axis=1)))
            u = diff[m, :d] / np.linalg.norm(diff[m, :d])
            axis = self.long_axis(rows, int(before["id"][m]), xb[m, :d], d)
            if axis is None:
                continue
            self.assertAlmostEqual(abs(float(np.dot(u, axis))), 1.0, delta=1e-6)
            checked += 1
        self.assertGreater(checked, n // 2)

    @staticmethod
    def long_axis(rows, cid, centre, d):
        """The long principal axis of a cell's second moments from its rows."""
        r = rows[rows[:, 0].astype(int) == cid]
        m0, m1, m2 = 0.0, np.zeros(d), np.zeros((d, d))
        if d == 2:
            for a, b in zip(r[:, 2:4] - centre, r[:, 4:6] - centre):
                cr = a[0] * b[1] - a[1] * b[0]
                m0 += cr / 2
                m1 += cr * (a + b) / 6
                m2 += cr / 24 * (2 * np.outer(a, a) + 2 * np.outer(b, b) + np.outer(a, b) + np.outer(b, a))
        else:
            for nb in set(r[:, 1].astype(int)):
                face = r[r[:, 1] == nb][:, 2:5] - centre
                for q in range(1, len(face) - 1):
                    a, b, c = face[0], face[q], face[q + 1]
                    v = np.dot(a, np.cross(b, c)) / 6
                    s = a + b + c
                    m0 += v
                    m1 += v * s / 4
                    m2 += v / 20 * (np.outer(a, a) + np.outer(b, b) + np.outer(c, c) + np.outer(s, s))
        cov = m2 - np.outer(m1, m1) / m0
        w, vec = np.linalg.eigh(cov)
        if w[-1] - w[-2] < 1e-6 * w.sum():
            return None
        return vec[:, -1]

    def check_death(self, model):
        if is_polygon(model):
            return self.check_death_vertex(model)
        for trigger in ("rate 5.0", "area 100.0"):
            script = model_script(model) + f"""fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix die all cell/death {trigger} seed 77 min 10
timestep 0.005
thermo_style custom step atoms pe
print "N0 $(atoms)"
run 5
print "N1 $(atoms)"
"""
            run = self.run_lmp(script)
            n0, n1 = printed(run, "N0")[0][0], printed(run, "N1")[0][0]
            self.assertLess(n1, n0, trigger)
            self.assertGreaterEqual(n1, 10)

    def check_death_vertex(self, model):
        """A dying vertex-model cell shrinks (through its own d_area0 and
        d_perim0) and leaves by T1s and a T2: fewer atoms, at least min 10
        living cells, and a valid tissue (vertex_check, numpy)."""
        for trigger in ("rate 0.2", "area 0.97"):
            script = polygon_death(model_script(model), trigger, 10) + """\
thermo_style custom step atoms pe
print "N0 $(atoms)"
run 2000
print "N1 $(atoms)"
write_data end.data
"""
            run = self.run_lmp(script)
            n0, n1 = printed(run, "N0")[0][0], printed(run, "N1")[0][0]
            self.assertLess(n1, n0, trigger)
            _, _, rings, _, _ = check_tissue(self, run.text("end.data"), f"{model} {trigger}")
            self.assertGreaterEqual(len(rings), 10)

    def check_area0(self, model):
        # Per-cell preferred measures: the energy of each cell follows its own
        # A0 (FD of forces checked with them), and a uniform d_area0 equal to
        # the types' values gives the same pe as no d_area0.
        base = model_script(model)
        same = self.run_lmp(base + """fix a0 all property/atom d_area0
set type 1 d_area0 1.0
set type 2 d_area0 0.9
thermo_style custom step pe
run 0
print "E $(pe:%.17g)"
""")
        finite = model.startswith("finite")
        if finite:
            same_types = self.run_lmp(base.replace("quadratic 1.0 1.2", "quadratic 1.0 1.0")
                                      .replace("quadratic 1.2 1.1", "quadratic 1.2 0.9")
                                      + "run 0\nprint \"E $(pe:%.17g)\"\n")
        else:
            same_types = self.run_lmp(base + "run 0\nprint \"E $(pe:%.17g)\"\n")
        self.assertAlmostEqual(printed(same, "E")[0][0], printed(same_types, "E")[0][0],
                               delta=1e-12 * abs(printed(same, "E")[0][0]))
        h = 1e-5
        d = dim_of(model)
        script = base + """fix a0 all property/atom d_area0
variable a atom 0.8+0.05*(id%7)
set group all d_area0 v_a
thermo_style custom step pe
run 0
group a5 id {probe}
print "F $(fx[{probe}]:%.17g) $(fy[{probe}]:%.17g) $(fz[{probe}]:%.17g)"
""".replace("{probe}", str(PROBES.get(model, (5,))[0]))
        for k in range(d):
            v = ["0", "0", "0"]
            v[k] = repr(h)
            script += f"displace_atoms a5 move {' '.join(v)} units box\nrun 0\nprint \"EP $(pe:%.17g)\"\n"
            v[k] = repr(-2 * h)
            script += f"displace_atoms a5 move {' '.join(v)} units box\nrun 0\nprint \"EM $(pe:%.17g)\"\n"
            v[k] = repr(h)
            script += f"displace_atoms a5 move {' '.join(v)} units box\n"
        run = self.run_lmp(script)
        force = printed(run, "F")[0]
        for k, (ep, em) in enumerate(zip(printed(run, "EP"), printed(run, "EM"))):
            self.assertAlmostEqual(force[k], -(ep[0] - em[0]) / (2 * h), delta=2e-5 * (abs(force[k]) + 1))
        self.assertNotAlmostEqual(printed(same, "E")[0][0], printed(run, "EP")[0][0], places=3)

    def check_percell(self, model):
        # Per-cell KA, KP, P0 (d_ka, d_kp, d_perim0; 3d: KV, KS, S0): the
        # types' values given per atom give the types' pe, and random values
        # give forces = central differences of pe.
        three = model.startswith("3d")
        coeffs = {"3d": COEFFS_3D, "3d_tri": COEFFS_3D, "finite_open": COEFFS_FINITE,
                  "finite_per": COEFFS_FINITE}.get(model, COEFFS_2D)
        base = model_script(model)
        setv = "fix pc all property/atom d_ka d_kp d_perim0\n"
        for line in coeffs.splitlines():
            w = line.split()
            if w[1] == w[2]:
                setv += (f"set type {w[1]} d_ka {w[4]}\nset type {w[1]} d_kp {w[6]}\n"
                         f"set type {w[1]} d_perim0 {w[7]}\n")
        out = "thermo_style custom step pe\nrun 0\nprint \"E $(pe:%.17g)\"\n"
        same, plain = self.run_lmp(base + setv + out), self.run_lmp(base + out)
        e0 = printed(plain, "E")[0][0]
        self.assertAlmostEqual(printed(same, "E")[0][0], e0, delta=1e-12 * abs(e0))
        p0 = "5.3+0.1*(id%6)" if three else "3.4+0.15*(id%6)"
        kp = "0.03+0.01*(id%4)" if three else "0.06+0.02*(id%4)"
        script = base + f"""fix pc all property/atom d_ka d_kp d_perim0
variable ka atom 0.8+0.1*(id%5)
variable kp atom {kp}
variable p0 atom {p0}
set atom * d_ka v_ka
set atom * d_kp v_kp
set atom * d_perim0 v_p0
thermo_style custom step pe
run 0
group a5 id {{probe}}
print "F $(fx[{{probe}}]:%.17g) $(fy[{{probe}}]:%.17g) $(fz[{{probe}}]:%.17g)"
""".replace("{probe}", str(PROBES.get(model, (5,))[0]))
        h = 1e-5
        for k in range(dim_of(model)):
            v = ["0", "0", "0"]
            v[k] = repr(h)
            script += f"displace_atoms a5 move {' '.join(v)} units box\nrun 0\nprint \"EP $(pe:%.17g)\"\n"
            v[k] = repr(-2 * h)
            script += f"displace_atoms a5 move {' '.join(v)} units box\nrun 0\nprint \"EM $(pe:%.17g)\"\n"
            v[k] = repr(h)
            script += f"displace_atoms a5 move {' '.join(v)} units box\n"
        run = self.run_lmp(script)
        force = printed(run, "F")[0]
        for k, (ep, em) in enumerate(zip(printed(run, "EP"), printed(run, "EM"))):
            self.assertAlmostEqual(force[k], -(ep[0] - em[0]) / (2 * h), delta=2e-5 * (abs(force[k]) + 1))
        self.assertNotAlmostEqual(e0, printed(run, "EP")[0][0], places=3)

    def check_adapt(self, model):
        # fix adapt to a new value gives the energy of pair_coeff with that value.
        base = self.thesis_form(model)
        style = "vertex/polygon" if is_polygon(model) else "vertex/voronoi"
        for param, pair, value in (("kappa", "1 1", 1.7), ("area0", "2 2", 1.3),
                                   ("gamma", "1 1", 0.4), ("lambda", "1 2", 0.25)):
            adapted = self.run_lmp(base + f"""variable v equal {value}
fix ad all adapt 1 pair {style} {param} {pair} v_v reset no
thermo_style custom step pe
run 0
print "E $(pe:%.17g)"
""")
            direct = self.run_lmp(self.thesis_form(model, (param, pair, value))
                                  + "run 0\nprint \"E $(pe:%.17g)\"\n")
            a, b = printed(adapted, "E")[0][0], printed(direct, "E")[0][0]
            self.assertAlmostEqual(a, b, delta=1e-11 * abs(b), msg=param)

    @staticmethod
    def thesis_lines(model, change=None):
        """The model's pair_coeff lines in the thesis form (K = 2 KA, Gamma =
        2 KP, Lambda = -2 KP P0 / w with w = 1/2; free F less 2 KP P0): the
        same forces, no constant.  change = (param, "I I", value) replaces one
        per-type value."""
        coeffs = {"3d": COEFFS_3D, "3d_tri": COEFFS_3D, "finite_open": COEFFS_FINITE,
                  "finite_per": COEFFS_FINITE}.get(model, COEFFS_2D)
        lines = []
        for line in coeffs.splitlines():
            w = line.split()
            if w[1] != w[2]:
                lines.append(line)
                continue
            t = int(w[1])
            ka, a0, kp, p0 = (float(x) for x in w[4:8])
            vals = {"kappa": 2 * ka, "area0": a0, "gamma": 2 * kp}
            lam = -4 * kp * p0
            if change and change[0] in vals and change[1] == f"{t} {t}":
                vals[change[0]] = change[2]
            free = " free %r" % (float(w[9]) - 2 * kp * p0) if len(w) > 8 else ""
            lines.append(f"pair_coeff {t} {t} {vals['kappa']!r} {vals['area0']!r} "
                         f"{vals['gamma']!r} {lam!r}{free}")
        if change and change[0] == "lambda":
            lines.append("pair_coeff %s %r" % (change[1], change[2]))
        return "\n".join(lines) + "\n"

    def thesis_form(self, model, change=None):
        script = model_script(model)
        coeffs = {"3d": COEFFS_3D, "3d_tri": COEFFS_3D, "finite_open": COEFFS_FINITE,
                  "finite_per": COEFFS_FINITE}.get(model, COEFFS_2D)
        return script.replace(coeffs, self.thesis_lines(model, change))

    def check_restart(self, model, particles=False):
        dyn = """fix p all polarity 0.3 1.0 neighbor 0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.005
thermo_style custom step pe
"""
        end = "write_dump all custom end.dump id xu yu zu mux muy muz modify format float %.17g\n"
        start = model_script(model, particles=particles)
        whole = self.run_lmp(start + dyn + "run 20\n" + end).dump("end.dump")[0]
        first = self.run_lmp(start + dyn + "run 10\nwrite_restart half.restart\n")
        head = "dimension 2\n" if dim_of(model) == 2 else ""
        # pair_style hybrid keeps its sub-styles' settings in restart files,
        # not their coefficients (LAMMPS's rule): they are given again.
        coeffs = "".join(line + "\n" for line in start.split("\n")
                         if particles and line.startswith("pair_coeff"))
        second = self.run_lmp(head + f"read_restart {first.path('half.restart')}\n" + coeffs + dyn +
                              "run 10\n" + end)
        f = second.dump("end.dump")[0]
        for col in ("xu", "yu", "zu", "mux", "muy", "muz"):
            np.testing.assert_allclose(f[col], whole[col], rtol=0, atol=1e-10, err_msg=col)

    def check_ranks(self, model, particles=False):
        data = self.run_lmp(model_script(model, particles=particles) +
                            "write_data cfg.data\n").text("cfg.data")
        results = []
        for n in (1, 2, 4):
            script = model_script(model, data="cfg.data", particles=particles) + """compute c all vertex/atom
compute t all vertex/tissue
thermo_style custom step pe c_t[1]
dump d all custom 1 f.dump id fx fy fz c_c[1] c_c[2]
dump_modify d format float %.17g sort id
run 0
print "E $(pe:%.17g)"
"""
            run = self.run_lmp(script, nprocs=n, files={"cfg.data": data})
            results.append((printed(run, "E")[0][0], run.dump("f.dump")[0]))
        for e, f in results[1:]:
            self.assertAlmostEqual(e, results[0][0], delta=1e-10 * abs(results[0][0]))
            for col in ("fx", "fy", "fz", "c_c[1]", "c_c[2]"):
                np.testing.assert_allclose(f[col], results[0][1][col], rtol=0, atol=1e-10, err_msg=col)

    def check_particles(self, model):
        """Atoms that are no cells (pair_style hybrid/overlay vertex/voronoi
        ... soft): forces = central differences of the total pe, on a
        particle and on a cell; the particles never enter a tessellation:
        the cells' energy and areas are those of the same cells with the
        particles deleted and pair_style vertex/voronoi alone, and the
        particles' rows of compute vertex/atom are zero."""
        if is_polygon(model):
            return check_polygon_particles(self, model)
        self.check_forces(model, particles=True)
        pv, vol, f, part = probe_particles(self, model, "vertex/voronoi", 3)
        self.assertTrue(np.all(f["c_c[1]"][~part] > 0.0))
        # The same cells without the particles, the pair style alone.
        coeffs = {"3d": COEFFS_3D, "3d_tri": COEFFS_3D, "finite_open": COEFFS_FINITE,
                  "finite_per": COEFFS_FINITE}.get(model, COEFFS_2D)
        alone = model_script(model).replace("create_box 2 box", "create_box 3 box")
        ids = " ".join(str(i) for i in PARTICLE_IDS)
        alone = alone.replace("mass * 1.0\n", f"group p id {ids}\ndelete_atoms group p compress no\nmass * 1.0\n")
        alone = alone.replace(coeffs, coeffs + "pair_coeff 3 3 1.0 1.0 0.0 0.0\n")
        ref = self.run_lmp(alone + """compute c all vertex/atom
dump d all custom 1 cells.dump id c_c[1] c_c[2]
dump_modify d format float %.17g sort id
run 0
print "E $(pe:%.17g)"
""")
        self.assertAlmostEqual(pv, printed(ref, "E")[0][0], delta=1e-10 * abs(pv))
        g = ref.dump("cells.dump")[0]
        np.testing.assert_array_equal(g["id"], f["id"][~part])
        for col in ("c_c[1]", "c_c[2]"):
            np.testing.assert_allclose(f[col][~part], g[col], rtol=1e-12, err_msg=col)
        if model in ("confluent", "confluent_tri", "3d", "3d_tri"):
            # The cells tile the box whatever lies among them.
            self.assertAlmostEqual(f["c_c[1]"].sum(), vol, delta=1e-9 * vol)

    def check_particles_ranks(self, model):
        self.check_ranks(model, particles=True)

    def check_particles_restart(self, model):
        self.check_restart(model, particles=True)

    def check_rosette(self, model):
        # compute vertex/tissue rosette L: clusters of Voronoi vertices joined by
        # junctions shorter than L, counted as (nearly) multifold vertices;
        # more with a longer L, and 0 on a jittered tissue for a tiny L.
        script = model_script(model) + """compute r1 all vertex/tissue rosette 1e-9
compute r2 all vertex/tissue rosette 0.15
compute r3 all vertex/tissue rosette 0.5
thermo_style custom step c_r1[2] c_r2[2] c_r3[2]
run 0
print "R $(c_r1[2]) $(c_r2[2]) $(c_r3[2])"
"""
        r1, r2, r3 = printed(self.run_lmp(script), "R")[0]
        self.assertEqual(r1, 0)
        self.assertLessEqual(r2, r3)
        self.assertGreater(r3, 0)

    def check_loops(self, model):
        # compute vertex/loops after a few Brownian steps: the loops' areas
        # against the cells' (compute vertex/atom): in an open box the outer
        # loops less the holes enclose exactly the cells; in a periodic box
        # the cells and the holes tile the box.
        script = model_script(model) + """fix b all brownian 1.0 1 gamma_t 1.0 rng none
compute c all vertex/atom
compute a all reduce sum c_c[1]
compute l all vertex/loops
timestep 0.005
thermo_style custom step pe c_a c_l[2]
run 5
dump d all local 1 loops.dump c_l[1] c_l[2] c_l[3] c_l[4] c_l[5] c_l[6] c_l[7]
dump_modify d format float %.17g
run 0
print "A $(c_a:%.17g) $(vol:%.17g) $(c_l[2]:%.17g)"
"""
        run = self.run_lmp(script)
        cells, box, holes = printed(run, "A")[0]
        rows = local_rows(run, "loops.dump")[-1]
        kind, area = rows[:, 6], rows[:, 1]
        self.assertAlmostEqual(area[kind == 0].sum(), holes, delta=1e-12 * box)
        if model == "finite_open":
            self.assertGreaterEqual((kind == 1).sum(), 1)
            self.assertAlmostEqual(area[kind == 1].sum() - holes, cells, delta=1e-9 * cells)
        else:
            self.assertGreater(holes, 0.0)    # r below the hexagons' circumradius: gaps
            self.assertAlmostEqual(cells + holes, box, delta=1e-9 * box)

    def check_minimize(self, model):
        # minimize (FIRE): pe falls, the minimiser's last energy is the energy
        # of the final positions (a fresh run 0 gives it again), and on the
        # sphere the atoms stay on it.
        script = model_script(model) + f"""variable r atom sqrt((x-{SPHERE_C})^2+(y-{SPHERE_C})^2+(z-{SPHERE_C})^2)
compute rmin all reduce min v_r
compute rmax all reduce max v_r
thermo_style custom step pe fnorm c_rmin c_rmax
run 0
print "E0 $(pe:%.17g)"
min_style fire
minimize 0 1e-10 300 3000
print "E1 $(pe:%.17g) $(c_rmin:%.17g) $(c_rmax:%.17g)"
run 0
print "E2 $(pe:%.17g)"
"""
        if is_polygon(model):
            # The vertex model minimises at fixed topology: the T1s that a
            # strained start needs are done first, by a short Brownian run.
            script = script.replace("run 0\nprint \"E0", "fix r all brownian 1.0 1 gamma_t 1.0 "
                                    "rng none\ntimestep 0.01\nrun 3000\nunfix r\nrun 0\nprint \"E0")
        run = self.run_lmp(script)
        e0 = printed(run, "E0")[0][0]
        e1, rmin, rmax = printed(run, "E1")[0]
        e2 = printed(run, "E2")[0][0]
        self.assertLess(e1, e0)
        self.assertAlmostEqual(e1, e2, delta=1e-12 * abs(e0))
        if model == "sphere":
            self.assertAlmostEqual(rmin, SPHERE_R, delta=1e-12 * SPHERE_R)
            self.assertAlmostEqual(rmax, SPHERE_R, delta=1e-12 * SPHERE_R)

    def check_deposit(self, model):
        d = dim_of(model)
        region = ("region ins block 1.5 2.5 0.5 1.5 0.5 1.5 units box" if d == 3 else
                  "region ins block 1 5 1 5 -0.1 0.1 units box")
        if model == "sphere":    # a slab across the sphere's top
            top = SPHERE_C + SPHERE_R
            region = f"region ins block 4.5 7.5 4.5 7.5 {top - 0.5} {top + 0.1} units box"
        script = model_script(model) + f"""{region}
fix p all polarity 0.3 1.0 neighbor 0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix dep all deposit 3 1 4 4821 region ins near 0.45 attempt 500
timestep 0.005
thermo_style custom step atoms pe
run 1
print "N0 $(atoms)"
run 12
print "N1 $(atoms)"
"""
        run = self.run_lmp(script)
        n0, n1 = printed(run, "N0")[0][0], printed(run, "N1")[0][0]
        self.assertTrue(n0 + 1 <= n1 <= n0 + 3, f"{n0} -> {n1}")

    def check_vtk(self, model):
        """tessera-tools vtk on a short run's dumps (per-atom + dump local of
        compute vertex/local), the .vtu files read back with meshio: 2d polygon
        areas (shoelace of the read-back points) equal compute vertex/atom's
        (finite cells: below them by no more than the arc-sampling bound
        r^2 theta step^2 / 12 summed over the cell's free arcs), 3d polyhedron
        volumes (divergence theorem over the read-back faces) equal them to 1e-9;
        the area / volume cell data equal them to 1e-9 in every model."""
        import subprocess
        import sys
        try:
            import meshio
        except ImportError:
            self.skipTest("needs meshio (Debian: python3-meshio)")
        d = dim_of(model)
        cols = " ".join("c_l[%d]" % k for k in range(1, 10 if d == 3 else 8))
        group = "cells" if is_polygon(model) else "all"    # vertex atoms are no cells
        script = model_script(model) + f"""compute c all vertex/atom
compute l all vertex/local
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.005
dump a {group} custom 2 cells.dump id type x y z c_c[1] c_c[8]
dump_modify a format float %.17g
dump f all local 2 cells.local {cols}
dump_modify f format float %.17g
thermo_style custom step pe
run 4
"""
        run = self.run_lmp(script)
        tool = os.path.join(lmptest.TOOLS, "tessera-tools")
        out = subprocess.run([sys.executable, tool, "vtk", run.path("cells.dump"), "--local",
                              run.path("cells.local"), "-o", run.path("vtk/cells"), "-q"],
                             capture_output=True, text=True, timeout=240)
        self.assertEqual(out.returncode, 0, out.stdout + out.stderr)
        frames = run.dump("cells.dump")
        self.assertEqual(len(frames), 3)
        step = 2 * math.pi / 256
        radius = {"finite_open": 0.7, "finite_per": 0.58}.get(model)
        checked = 0
        for f in frames:
            names = sorted(n for n in os.listdir(run.path("vtk")) if n.endswith(".vtu"))
            match = [n for n in names if int(n.rsplit("_", 1)[1][:-4]) == f["step"]]
            self.assertEqual(len(match), 1, names)
            mesh = meshio.read(run.path(os.path.join("vtk", match[0])))
            measure = dict(zip(f["id"].astype(int).tolist(), f["c_c[1]"].tolist()))
            free = dict(zip(f["id"].astype(int).tolist(), f["c_c[8]"].tolist()))
            got = {}
            stored = mesh.cell_data["volume" if d == 3 and model != "sphere" else "area"]
            for block, ids, cell_measure in zip(mesh.cells, mesh.cell_data["id"], stored):
                # the cell data holds the exact measure (finite cells: arcs, not samples)
                for i, m in zip(ids, cell_measure):
                    self.assertAlmostEqual(m, measure[int(i)], delta=1e-9 * measure[int(i)], msg=f"cell {i}")
                for conn, i in zip(block.data, ids):
                    if model == "sphere":
                        # the spherical polygon of the read-back corners (on the sphere)
                        u = mesh.points[conn] - SPHERE_C
                        u /= np.linalg.norm(u, axis=1)[:, None]
                        area = 0.0
                        for q in range(1, len(u) - 1):
                            a, b, c = u[0], u[q], u[q + 1]
                            area += 2 * math.atan2(a @ np.cross(b, c), 1 + a @ b + b @ c + c @ a)
                        got[int(i)] = SPHERE_R ** 2 * area
                    elif d == 3:
                        self.assertTrue(block.type.startswith("polyhedron"))
                        vol = 0.0
                        for face in conn:
                            p = mesh.points[np.asarray(face)]
                            for q in range(1, len(p) - 1):
                                vol += np.dot(p[0], np.cross(p[q], p[q + 1])) / 6
                        got[int(i)] = vol
                    else:
                        p = mesh.points[conn]
                        got[int(i)] = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
            self.assertEqual(sorted(got), sorted(measure))
            for i, want in measure.items():
                if radius is None:
                    self.assertAlmostEqual(got[i], want, delta=1e-9 * want, msg=f"cell {i}")
                else:
                    bound = radius * free[i] * step ** 2 / 12    # r^2 theta step^2 / 12, theta = free / r
                    self.assertLessEqual(got[i], want + 1e-9, msg=f"cell {i}")
                    self.assertGreaterEqual(got[i], want - bound - 1e-9, msg=f"cell {i}")
                checked += 1
        self.assertGreater(checked, 0)


MODEL_NAMES = {"confluent": "confluent 2d", "confluent_tri": "confluent 2d, triclinic",
               "finite_open": "finite 2d, open box", "finite_per": "finite 2d, periodic",
               "3d": "3d", "3d_tri": "3d, triclinic", "sphere": "sphere",
               "vertex_polygon": "vertex model", "vertex_polygon_tri": "vertex model, triclinic"}
DOC = os.path.join(os.path.dirname(os.path.dirname(HERE)), "doc", "model.md")
BEGIN, END = "<!-- feature matrix: begin -->", "<!-- feature matrix: end -->"


def markdown_table():
    """The matrix as the Markdown table doc/model.md shows (between BEGIN and
    END), generated from feature_matrix.txt: 'yes' or the error's fragment."""
    cells = read_matrix()
    models = list(dict.fromkeys(m for m, _, _ in cells))
    features = list(dict.fromkeys(f for _, f, _ in cells))
    got = {(m, f): e for m, f, e in cells}
    lines = ["| feature | " + " | ".join(MODEL_NAMES.get(m, m) for m in models) + " |",
             "|---" * (len(models) + 1) + "|"]
    for f in features:
        row = []
        for m in models:
            e = got.get((m, f), "-")
            row.append("yes" if e == "ok" else ("error: " + e.split(None, 1)[1] if e.startswith("error") else e))
        lines.append(f"| {f} | " + " | ".join(row) + " |")
    return "\n".join(lines)


class DocTable(LammpsTestCase):
    def test_doc_shows_the_matrix(self):
        """doc/model.md's table is the one generated from feature_matrix.txt
        (regenerate: test_feature_matrix.py --markdown)."""
        with open(DOC) as f:
            text = f.read()
        self.assertIn(BEGIN, text)
        shown = text.split(BEGIN, 1)[1].split(END, 1)[0].strip()
        self.assertEqual(shown, markdown_table())


def _make(model, feature, expect):
    check = getattr(FeatureMatrix, "check_" + feature)
    if expect == "ok":
        def test(self):
            self.model = model
            check(self, model)
    else:
        fragment = expect.split(None, 1)[1] if " " in expect else ""

        def test(self):
            # The feature's scripts must stop with the named error.
            self.model = model
            with self.assertRaises(AssertionError) as caught:
                check(self, model)
            self.assertIn(fragment, str(caught.exception))
    if feature.endswith("ranks") or feature == "fix_order":
        test.nprocs = 4
    test.__doc__ = f"{model} x {feature}: {expect}"
    return test


FeatureMatrix.check_signal = check_signal
FeatureMatrix.check_particles_fixes = check_particles_fixes

for _model, _feature, _expect in read_matrix():
    setattr(FeatureMatrix, f"test_{_model}__{_feature}", _make(_model, _feature, _expect))


if __name__ == "__main__":
    import sys
    if "--markdown" in sys.argv:
        print(markdown_table())
        sys.exit(0)
    lmptest.main()
