# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools moduli: units, error bars over seeds, the quasistatic route where the
Hessian does not exist, the fnorm warning, where tessera-hessian is looked for, and dumps
with particles (atoms that are no cells).
Expected values are analytic (hexagon closed form, slopes of synthetic strain steps),
never the tool's own earlier output."""

import math
import os
import re
import stat
import tempfile
import unittest
from unittest import mock

import numpy as np

from helpers import frame_from, hex_lattice, square_lattice
from test_cli import run
from tessera_tools import moduli as moduli_mod
from tessera_tools.dump import write_dump
from tessera_tools.moduli import seed_average, young_poisson

PH = math.sqrt(8 * math.sqrt(3))    # shape index of the regular hexagon


def have_hessian():
    try:
        moduli_mod.find_hessian_exe()
        return True
    except FileNotFoundError:
        return False


def write_qs(path, G, B, noise=0.0, fnorm=1e-13, seed=0):
    """Strain steps with pxy = -G gamma and press = P0 - 2 B eps (+ noise)."""
    rng = np.random.default_rng(seed)
    steps = np.arange(-3, 4) * 2e-4
    with open(path, "w") as f:
        f.write("# kind strain pxy press pe fnorm\n")
        for g in steps:
            f.write(f"shear {g:.12e} {-G * g + noise * rng.standard_normal():.15e} -0.1 -5.0 {fnorm:.3e}\n")
        for e in steps:
            f.write(f"dilation {e:.12e} 0.0 {-0.1 - 2 * B * e + noise * rng.standard_normal():.15e} -5.0 "
                    f"{fnorm:.3e}\n")


def numbers_after(text, key):
    """Every float printed right after 'key = '."""
    return [float(v) for v in re.findall(re.escape(key) + r" = ([-+0-9.eE]+)", text)]


class Propagation(unittest.TestCase):

    def test_young_poisson_values_and_errors(self):
        """E = 4BG/(B+G), nu = (B-G)/(B+G); errors against central differences."""
        G, B, dG, dB = 0.7, 3.1, 1e-3, 2e-3
        r = young_poisson(G, B, dG, dB)
        self.assertAlmostEqual(r["E"], 4 * B * G / (B + G), places=14)
        self.assertAlmostEqual(r["nu"], (B - G) / (B + G), places=14)
        h = 1e-6
        dEdG = (young_poisson(G + h, B)["E"] - young_poisson(G - h, B)["E"]) / (2 * h)
        dEdB = (young_poisson(G, B + h)["E"] - young_poisson(G, B - h)["E"]) / (2 * h)
        self.assertAlmostEqual(r["E_err"], math.hypot(dEdG * dG, dEdB * dB), places=9)
        dndG = (young_poisson(G + h, B)["nu"] - young_poisson(G - h, B)["nu"]) / (2 * h)
        dndB = (young_poisson(G, B + h)["nu"] - young_poisson(G, B - h)["nu"]) / (2 * h)
        self.assertAlmostEqual(r["nu_err"], math.hypot(dndG * dG, dndB * dB), places=9)

    def test_seed_average(self):
        mean, err = seed_average([1.0, 2.0, 3.0])
        self.assertEqual(mean, 2.0)
        self.assertAlmostEqual(err, 1.0 / math.sqrt(3.0), places=14)
        self.assertTrue(math.isnan(seed_average([4.0])[1]))


class FindHessian(unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def fake_exe(self, where):
        os.makedirs(where, exist_ok=True)
        path = os.path.join(where, "tessera-hessian")
        with open(path, "w") as f:
            f.write("#!/bin/sh\nexit 3\n")
        os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)
        return path

    def test_not_found_names_every_place(self):
        empty = os.path.join(self.tmp.name, "repo")
        with mock.patch.object(moduli_mod, "ROOT", empty), \
                mock.patch.dict(os.environ, {"PATH": self.tmp.name}, clear=False):
            os.environ.pop("TESSERA_HESSIAN", None)
            os.environ.pop("TESSERA_BUILD", None)
            with self.assertRaises(FileNotFoundError) as ctx:
                moduli_mod.find_hessian_exe()
        msg = str(ctx.exception)
        for place in ("TESSERA_HESSIAN", os.path.join(empty, "build", "core", "tessera-hessian"), "PATH",
                      "--exe"):
            self.assertIn(place, msg)

    def test_order_repository_build_then_path(self):
        repo = os.path.join(self.tmp.name, "repo")
        on_path = self.fake_exe(os.path.join(self.tmp.name, "bin"))
        with mock.patch.object(moduli_mod, "ROOT", repo), \
                mock.patch.dict(os.environ, {"PATH": os.path.dirname(on_path)}, clear=False):
            os.environ.pop("TESSERA_HESSIAN", None)
            os.environ.pop("TESSERA_BUILD", None)
            self.assertEqual(moduli_mod.find_hessian_exe(), on_path)
            built = self.fake_exe(os.path.join(repo, "build", "core"))
            self.assertEqual(moduli_mod.find_hessian_exe(), built)
            os.environ["TESSERA_HESSIAN"] = on_path
            self.assertEqual(moduli_mod.find_hessian_exe(), on_path)
            os.environ["TESSERA_HESSIAN"] = os.path.join(self.tmp.name, "nothing")
            with self.assertRaisesRegex(FileNotFoundError, "TESSERA_HESSIAN=.*nothing"):
                moduli_mod.find_hessian_exe()
            os.environ.pop("TESSERA_HESSIAN", None)


class MissingExecutable(unittest.TestCase):
    """The quasistatic route needs no tessera-hessian: seeds averaged from qs files alone."""

    def test_seeds_from_strain_steps_alone(self):
        tmp = tempfile.TemporaryDirectory()
        self.addCleanup(tmp.cleanup)
        pts, box = hex_lattice(4, 4)
        Gs, Bs = [0.2, 0.3, 0.4], [2.0, 2.5, 3.0]
        for s, (G, B) in enumerate(zip(Gs, Bs), start=1):
            d = os.path.join(tmp.name, f"seed{s}")
            os.makedirs(d)
            write_dump(os.path.join(d, "minimised.dump"), [frame_from(pts, box)])
            write_qs(os.path.join(d, "qs.dat"), G, B)
        repo = os.path.join(tmp.name, "repo")
        with mock.patch.object(moduli_mod, "ROOT", repo), \
                mock.patch.dict(os.environ, {"PATH": tmp.name}, clear=False):
            os.environ.pop("TESSERA_HESSIAN", None)
            os.environ.pop("TESSERA_BUILD", None)
            code, out, err = run("moduli", os.path.join(tmp.name, "seed{seed}", "minimised.dump"),
                                 "--seeds", "3", "--quadratic", "2", "1", "1", "3.8",
                                 "--quasistatic", os.path.join(tmp.name, "seed{seed}", "qs.dat"))
        self.assertEqual(code, 0, err)
        summary = out.split("over 3 states")[1]
        g = re.search(r"G = ([-0-9.e+]+) \+- ([-0-9.e+]+) energy/length\^2 = ([-0-9.e+]+) \+- ([-0-9.e+]+) KA A0",
                      summary)
        self.assertIsNotNone(g, summary)
        self.assertAlmostEqual(float(g.group(1)), 0.3, places=6)
        self.assertAlmostEqual(float(g.group(2)), 0.1 / math.sqrt(3), places=2)    # std 0.1 / sqrt(3)
        self.assertAlmostEqual(float(g.group(3)), 0.15, places=6)                  # / (KA A0) = 2
        self.assertIn("units:", out)
        self.assertIn("tessera-hessian not found", err)

    def test_seeds_needs_a_pattern(self):
        code, out, err = run("moduli", "minimised.dump", "--seeds", "3", "--quadratic", "1", "1", "1", "3.8")
        self.assertNotEqual(code, 0)
        self.assertIn("{seed}", err)


@unittest.skipUnless(have_hessian(), "tessera-hessian not built")
class WithHessian(unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def path(self, name):
        return os.path.join(self.tmp.name, name)

    def test_hexagon_closed_form_in_both_units(self):
        """G = (3/4) KP Ph (Ph - p0), B = 2 KA + KP Ph p0 / 2 (cells of unit area);
        printed in the input's units and divided by KA A0."""
        a = math.sqrt(2 / math.sqrt(3))
        pts, box = hex_lattice(6, 4, a=a)
        write_dump(self.path("hex.dump"), [frame_from(pts, box)])
        KA, KP, p0 = 2.0, 3.0, 3.5
        code, out, err = run("moduli", self.path("hex.dump"), "--quadratic", str(KA), "1", str(KP), str(p0))
        self.assertEqual(code, 0, err)
        G = 0.75 * KP * PH * (PH - p0)
        B = 2 * KA + KP * PH * p0 / 2
        self.assertAlmostEqual(numbers_after(out, "G")[0], G, places=6)
        self.assertAlmostEqual(numbers_after(out, "B")[0], B, places=5)
        self.assertRegex(out, r"G = [-0-9.e+]+ energy/length\^2 = ([-0-9.e+]+) KA A0")
        reduced = float(re.search(r"G = [-0-9.e+]+ energy/length\^2 = ([-0-9.e+]+) KA A0", out).group(1))
        self.assertAlmostEqual(reduced, G / KA, places=6)
        self.assertNotIn("warning", err)

    def test_table_rows_for_plot_moduli(self):
        """--table appends p0 and the moduli in KA A0; two hexagon states give zero spread."""
        import csv

        a = math.sqrt(2 / math.sqrt(3))
        for s, (nx, ny) in enumerate(((6, 4), (4, 6)), start=1):
            pts, box = hex_lattice(nx, ny, a=a)
            write_dump(self.path(f"hex{s}.dump"), [frame_from(pts, box)])
        table = self.path("moduli.csv")
        KA, KP = 2.0, 1.0
        for p0 in (3.5, 3.6):
            code, out, err = run("moduli", self.path("hex{seed}.dump"), "--seeds", "2", "--quadratic", str(KA), "1",
                                 str(KP), str(p0), "--table", table)
            self.assertEqual(code, 0, err)
        with open(table) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual([float(r["p0"]) for r in rows], [3.5, 3.6])
        for r in rows:
            p0 = float(r["p0"])
            self.assertEqual(r["route"], "hessian")
            self.assertAlmostEqual(float(r["G"]), 0.75 * KP * PH * (PH - p0) / KA, places=6)
            self.assertAlmostEqual(float(r["B"]), (2 * KA + KP * PH * p0 / 2) / KA, places=5)
            self.assertLess(float(r["G_err"]), 1e-8)
        png = self.path("moduli.png")
        code, out, err = run("plot", "moduli", table, "-o", png)
        self.assertEqual(code, 0, err)

    def test_fnorm_warning(self):
        pts, box = hex_lattice(6, 4)
        pts = pts + np.random.default_rng(1).normal(scale=0.02, size=pts.shape)
        write_dump(self.path("off.dump"), [frame_from(pts, box)])
        code, out, err = run("moduli", self.path("off.dump"), "--quadratic", "1", "1", "1", "3.6")
        self.assertEqual(code, 0, err)
        fnorm = float(re.search(r"fnorm ([0-9.e+-]+) energy/length", out).group(1))
        self.assertGreater(fnorm, 1e-3)
        self.assertRegex(err, r"warning: .*off.dump: fnorm [0-9.e+-]+ > 1e-06.*not an energy minimum")

    def per_cell_state(self):
        """A jittered hexagonal tissue of one type whose cells carry two sets of quadratic-form
        parameters (KA, A0, KP, P0) as the per-cell columns d_ka d_area0 d_kp d_perim0."""
        a = math.sqrt(2 / math.sqrt(3))
        pts, box = hex_lattice(4, 4, a=a)
        pts = pts + np.random.default_rng(7).normal(scale=0.03, size=pts.shape)
        sets = np.array([(1.0, 1.0, 1.0, 3.7), (1.6, 1.1, 0.5, 3.95)])
        kind = np.arange(len(pts)) % 3 == 0
        par = sets[kind.astype(int)]
        return pts, box, kind, sets, par

    def test_per_cell_parameters(self):
        """The Hessian route uses the dump's per-cell parameters: G equals that of the same
        tissue written with two types (the per-type rewrite), and the affine (Born) shear
        modulus equals central differences of the quadratic-form energy of scipy's Voronoi
        cells under x += gamma y.  The types' own values (--quadratic) differ from both sets."""
        from tessera_tools.dump import Box
        from tessera_tools.voronoi import periodic_voronoi, polygon_area, _polygon_perimeter

        pts, box, kind, sets, par = self.per_cell_state()
        write_dump(self.path("pc.dump"), [frame_from(pts, box, d_ka=par[:, 0], d_area0=par[:, 1],
                                                     d_kp=par[:, 2], d_perim0=par[:, 3])])
        code, out, err = run("moduli", self.path("pc.dump"), "--quadratic", "1", "1", "1", "3.6")
        self.assertEqual(code, 0, err)
        self.assertIn("per-cell parameters from the dump: d_area0 d_ka d_kp d_perim0", out)
        G = numbers_after(out, "G")[0]
        G_affine = float(re.search(r"affine G ([-0-9.e+]+)", out).group(1))
        # The per-type rewrite: type t has set t; heterotypic Lambda is the mean of the two.
        types = [moduli_mod.Model.quadratic(*row) for row in sets]
        lam = np.array([[types[0].Lambda[0, 0], 0.0], [0.0, types[1].Lambda[0, 0]]])
        lam[0, 1] = lam[1, 0] = 0.5 * (lam[0, 0] + lam[1, 1])
        model = moduli_mod.Model([t.K[0] for t in types], [t.A0[0] for t in types],
                                 [t.Gamma[0] for t in types], lam)
        ref = moduli_mod.moduli(moduli_mod.run_hessian(box, pts, model, kind.astype(int) + 1))
        self.assertAlmostEqual(G, ref["G"], places=7)
        self.assertAlmostEqual(G_affine, ref["G_affine"], places=7)

        def energy(gamma):
            b = Box(box.xlo, box.xhi, box.ylo, box.yhi, xy=gamma * box.ly)
            q = pts + np.column_stack([gamma * (pts[:, 1] - box.ylo), np.zeros(len(pts))])
            t = periodic_voronoi(q, b)
            A = np.array([polygon_area(p) for p in t.polygons])
            P = np.array([_polygon_perimeter(p) for p in t.polygons])
            return float(np.sum(par[:, 0] * (A - par[:, 1]) ** 2 + par[:, 2] * (P - par[:, 3]) ** 2))

        h = 1e-4
        born = (energy(h) - 2 * energy(0.0) + energy(-h)) / h ** 2
        self.assertAlmostEqual(G_affine, born / box.area, places=5)
        # Ignoring the per-cell columns gives another G (what the route did before).
        write_dump(self.path("plain.dump"), [frame_from(pts, box)])
        code, out0, err0 = run("moduli", self.path("plain.dump"), "--quadratic", "1", "1", "1", "3.6")
        self.assertGreater(abs(numbers_after(out0, "G")[0] - G), 1e-3)

    def test_other_energy_is_refused_with_its_cause(self):
        """A dump whose own forces vanish where the energy given here has forces was run with
        another energy: refused (no table row), naming the per-cell columns it lacks.  Without
        fx fy the warning names both possible causes."""
        a = math.sqrt(2 / math.sqrt(3))
        pts, box = hex_lattice(4, 4, a=a)
        pts = pts + np.random.default_rng(2).normal(scale=0.03, size=pts.shape)
        n = len(pts)
        write_dump(self.path("f.dump"), [frame_from(pts, box, fx=np.zeros(n), fy=np.zeros(n))])
        table = self.path("t.csv")
        code, out, err = run("moduli", self.path("f.dump"), "--quadratic", "1", "1", "1", "3.6", "--table", table)
        self.assertNotEqual(code, 0)
        self.assertRegex(err, r"dump's own forces \(fx fy\) have fnorm 0.*d_area0 d_ka d_kp d_perim0")
        self.assertFalse(os.path.exists(table))
        write_dump(self.path("nf.dump"), [frame_from(pts, box)])
        code, out, err = run("moduli", self.path("nf.dump"), "--quadratic", "1", "1", "1", "3.6")
        self.assertEqual(code, 0, err)
        self.assertRegex(err, r"not minimised.*per-cell parameters the dump does not carry.*dump fx fy")

    def test_multifold_vertex_uses_the_strain_steps(self):
        """A square lattice has multifold vertices: no Hessian; with --quasistatic the slopes are
        the moduli (here of synthetic steps, G = 0.25, B = 1.5), without it a clear error."""
        pts, box = square_lattice(4)
        write_dump(self.path("sq.dump"), [frame_from(pts, box)])
        write_qs(self.path("qs.dat"), 0.25, 1.5, noise=1e-9)
        code, out, err = run("moduli", self.path("sq.dump"), "--quadratic", "1", "1", "1", "3.9")
        self.assertNotEqual(code, 0)
        self.assertIn("multifold", err)
        self.assertIn("--quasistatic", err)
        code, out, err = run("moduli", self.path("sq.dump"), "--quadratic", "1", "1", "1", "3.9",
                             "--quasistatic", self.path("qs.dat"))
        self.assertEqual(code, 0, err)
        self.assertAlmostEqual(numbers_after(out, "G")[0], 0.25, places=5)
        self.assertAlmostEqual(numbers_after(out, "B")[0], 1.5, places=5)
        self.assertIn("multifold", err)
        self.assertRegex(out, r"G = [0-9.e+-]+ \+- [0-9.e+-]+ energy/length\^2")


@unittest.skipUnless(have_hessian(), "tessera-hessian not built")
class WithParticles(unittest.TestCase):
    """A dump with atoms that are no cells (particles of other types, under pair_style
    hybrid/overlay): refused without --cell-types with the fix; with it the particles are left
    out and the cells' moduli are the hexagon's closed form whatever their own type; a dump whose
    forces show particles pushing on cells is refused for the Hessian route (no stiffness of the
    particles' pair style there) and measured by the strain steps with --quasistatic."""

    KP, P0 = 1.0, 3.5

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)

    def path(self, name):
        return os.path.join(self.tmp.name, name)

    def dump(self, name, cell_type=1, particle_types=(2, 2, 3), push=0.0):
        """A 6 x 4 hexagonal tissue of unit-area cells with particles at three Voronoi vertices
        (IDs mixed with the cells'); forces fx fy: zero, but `push` on cell 5 along x."""
        a = math.sqrt(2 / math.sqrt(3))
        cells, box = hex_lattice(6, 4, a=a)
        h = a * math.sqrt(3) / 2
        particles = np.array([[0.5 * a, h / 3], [2.5 * a, h / 3], [3.0 * a, 2 * h / 3]])
        pos = np.vstack([particles, cells])
        n, m = len(cells), len(particles)
        types = np.concatenate([particle_types, np.full(n, cell_type)])
        ids = np.concatenate([[2, 9, 20], [i for i in range(1, n + m + 1) if i not in (2, 9, 20)]])
        fx = np.zeros(n + m)
        fx[m + 5] = push
        write_dump(self.path(name), [frame_from(pos, box, id=ids, type=types, fx=fx, fy=np.zeros(n + m))])
        return self.path(name)

    def moduli(self, *args):
        return run("moduli", *args, "--quadratic", "1", "1", str(self.KP), str(self.P0))

    def test_several_types_refused_with_the_fix(self):
        code, out, err = self.moduli(self.dump("p.dump"))
        self.assertNotEqual(code, 0)
        self.assertIn("type 1 (24 atoms), type 2 (2 atoms), type 3 (1 atoms)", err)
        self.assertIn("If the atoms of type 2, 3 are no cells", err)
        self.assertIn("give --cell-types 1 to leave them out", err)
        code, out, err = self.moduli(self.dump("p.dump"), "--cell-types", "4")
        self.assertNotEqual(code, 0)
        self.assertIn("--cell-types 4: no atom of the dump has these types (it has types 1, 2, 3)", err)

    def test_particles_left_out(self):
        G = 0.75 * self.KP * PH * (PH - self.P0)
        B = 2 + self.KP * PH * self.P0 / 2
        for cell_type, particle_types, option in ((1, (2, 2, 3), "1"), (2, (1, 3, 3), "2"),
                                                  (2, (1, 1, 1), "2*")):
            with self.subTest(cells=option):
                code, out, err = self.moduli(self.dump("p.dump", cell_type, particle_types), "--cell-types", option)
                self.assertEqual(code, 0, err)
                self.assertAlmostEqual(numbers_after(out, "G")[0], G, places=6)
                self.assertAlmostEqual(numbers_after(out, "B")[0], B, places=5)
                self.assertIn(f"24 cells, area {24:.10g} length^2", out)
                self.assertIn(f"cells: 24 atoms of --cell-types {option}; left out 3 atom(s) of type", out)
                self.assertIn("no particle pushes on a cell", out)
                self.assertNotIn("warning", err)

    def test_particles_pushing_on_cells(self):
        path = self.dump("push.dump", push=0.3)
        code, out, err = self.moduli(path, "--cell-types", "1")
        self.assertNotEqual(code, 0)
        self.assertRegex(err, r"differ from those of the cells' vertex energy by up to 0.3 .*the particles left "
                              r"out \(3 atom\(s\) of type 2, 3\) push on the cells.*--quasistatic")
        write_qs(self.path("qs.dat"), 0.4, 2.5, noise=1e-9)
        code, out, err = self.moduli(path, "--cell-types", "1", "--quasistatic", self.path("qs.dat"))
        self.assertEqual(code, 0, err)
        self.assertAlmostEqual(numbers_after(out, "G")[0], 0.4, places=5)
        self.assertAlmostEqual(numbers_after(out, "B")[0], 2.5, places=5)
        self.assertIn("no Hessian route", err)


if __name__ == "__main__":
    unittest.main()
