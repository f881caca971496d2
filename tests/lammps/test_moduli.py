#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Elastic moduli by two routes that check each other: quasistatic strain steps
with LAMMPS commands (examples/moduli/in.moduli: change_box ... remap,
minimize, pxy / press) and the exact Hessian of the dumped minimum
(tessera-hessian through tools/tessera_tools/moduli.py); and both against the
closed-form moduli of the hexagonal lattice, also with particles (atoms that are
no cells) in the box."""

import math
import os
import re
import subprocess
import sys

import lmptest
from lmptest import LammpsTestCase, nprocs

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "tools"))
from tessera_tools.dump import read_frame  # noqa: E402
from tessera_tools.moduli import Model, fit_quasistatic, frame_moduli  # noqa: E402

EXAMPLE = os.path.join(ROOT, "examples", "moduli", "in.moduli")
PH = math.sqrt(8 * math.sqrt(3))  # perimeter of the regular hexagon of area 1


def hessian_exe():
    # scripts/build puts tessera-hessian into <build>/core/ (this build, the
    # plugin build, or the tessera-lmp build the plugin host compares with).
    candidates = [os.path.join(lmptest.Config.build or "", "core", "tessera-hessian")]
    for lmp in (lmptest.Config.lmp, lmptest.Config.tessera_lmp):
        if lmp:
            candidates.append(os.path.join(os.path.dirname(os.path.dirname(lmp)), "core",
                                           "tessera-hessian"))
    for path in candidates:
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    return candidates[0]


class ModuliRoutes(LammpsTestCase):

    def routes(self, p0, **variables):
        run = self.run_lmp(open(EXAMPLE).read(), variables=dict(p0=p0, **variables))
        qs = fit_quasistatic(run.path("qs.dat"))
        qs["path"] = run.path("qs.dat")
        ex = frame_moduli(read_frame(run.path("minimised.dump")), Model.quadratic(1, 1, 1, p0),
                          exe=hessian_exe())
        self.assertLess(ex["max_force"], 1e-9, "not minimised")
        return qs, ex

    def test_disordered_tissue_routes_agree(self):
        """64 random cells at p0 = 3.6, minimised: G and B of both routes agree
        within the quasistatic error bars (3 sigma), which are themselves small."""
        qs, ex = self.routes(3.6, N=64, seed=3)
        self.assertEqual(ex["negative_modes"], 0)
        self.assertEqual(ex["zero_modes"], 2)  # the translations: the tissue is rigid
        for name in ("G", "B"):
            msg = f"{name}: quasistatic {qs[name]} +- {qs[name + '_err']}, Hessian {ex[name]}"
            self.assertLess(qs[name + "_err"], 2e-3 * abs(ex[name]), msg)
            self.assertLess(abs(qs[name] - ex[name]), 3 * qs[name + "_err"] + 1e-9, msg)
        # The sparse-solve path (used above 4000 degrees of freedom) gives the same moduli.
        run_dir = os.path.dirname(qs["path"])
        sparse = frame_moduli(read_frame(os.path.join(run_dir, "minimised.dump")), Model.quadratic(1, 1, 1, 3.6),
                              exe=hessian_exe(), dense_limit=0)
        for name in ("G", "B"):
            self.assertAlmostEqual(sparse[name], ex[name], delta=1e-9 * abs(ex[name]))
        # The non-affine relaxation matters on a disordered tissue: G is
        # clearly below its affine (Born) value, so the check has power.
        self.assertLess(ex["G"], 0.97 * ex["G_affine"])

    @nprocs(2)
    def test_two_ranks_same_slopes(self):
        """The quasistatic slopes of the example on 2 ranks equal those on 1 rank
        (to 1e-9 relative: the minimiser's round-off differs between rank counts)."""
        fits = [fit_quasistatic(self.run_lmp(open(EXAMPLE).read(), nprocs=n, variables=dict(K=2)).path("qs.dat"))
                for n in (1, 2)]
        for name in ("G", "B"):
            self.assertAlmostEqual(fits[1][name], fits[0][name], delta=1e-9 * abs(fits[0][name]))

    def test_hexagonal_lattice_closed_form(self):
        """Hexagonal lattice at p0 = 3.5: G = (3/4) Ph (Ph - p0), B = 2 + Ph p0 / 2
        (second derivatives of the regular hexagon's energy) by both routes."""
        p0 = 3.5
        qs, ex = self.routes(p0, tissue="hex")
        G, B = 0.75 * PH * (PH - p0), 2 + PH * p0 / 2
        self.assertAlmostEqual(ex["G"], G, delta=1e-9)
        self.assertAlmostEqual(ex["B"], B, delta=1e-9)
        self.assertLess(abs(qs["G"] - G), 3 * qs["G_err"] + 1e-6, qs)
        self.assertLess(abs(qs["B"] - B), 3 * qs["B_err"] + 1e-6, qs)

    def test_hexagonal_lattice_unstable_above_its_shape_index(self):
        """Above p0 = 3.7224 the hexagonal lattice's G is negative and its Hessian
        has negative eigenvalues (long-wavelength shear modes lower the energy)."""
        run = self.run_lmp(open(EXAMPLE).read(), variables=dict(p0=3.8, tissue="hex", K=1))
        ex = frame_moduli(read_frame(run.path("minimised.dump")), Model.quadratic(1, 1, 1, 3.8),
                          exe=hessian_exe())
        self.assertAlmostEqual(ex["G"], 0.75 * PH * (PH - 3.8), delta=1e-9)
        self.assertGreater(ex["negative_modes"], 0)


    def test_hexagonal_lattice_with_particles(self):
        """The example's hexagonal tissue with three particles (type 2, pair soft under
        hybrid/overlay) at Voronoi vertices, out of soft's reach of every cell: the strain
        steps (LAMMPS's stress of every pair style) and tessera-tools moduli --cell-types 1 on
        the dump (the cells' Hessian, the particles left out) both give the closed form; without
        --cell-types the tool stops naming the particles' type and the option."""
        p0 = 3.5
        a = math.sqrt(2 / math.sqrt(3))
        h = a * math.sqrt(3) / 2
        spots = [(0.5 * a, h / 3), (2.5 * a, h / 3), (3 * a, 2 * h / 3)]    # a / sqrt(3) from three cells
        script = open(EXAMPLE).read().replace("create_box 1 box", "create_box 2 box")
        script = script.replace("mass            1 1.0\n", "mass            * 1.0\n" + "".join(
            f"create_atoms 2 single {x!r} {y!r} 0 units box\n" for x, y in spots))
        script = script.replace("pair_style      vertex/voronoi 4.0\npair_coeff      * * quadratic",
                                "pair_style      hybrid/overlay vertex/voronoi 4.0 soft 0.5\n"
                                "pair_coeff      * 2 soft 10.0 0.5\n"
                                "pair_coeff      1 1 vertex/voronoi quadratic")
        self.assertEqual(script.count("create_atoms 2 single"), 3)
        self.assertIn("hybrid/overlay", script)
        run = self.run_lmp(script, variables=dict(p0=p0, tissue="hex"))
        qs = fit_quasistatic(run.path("qs.dat"))
        G, B = 0.75 * PH * (PH - p0), 2 + PH * p0 / 2
        self.assertLess(abs(qs["G"] - G), 3 * qs["G_err"] + 1e-6, qs)
        self.assertLess(abs(qs["B"] - B), 3 * qs["B_err"] + 1e-6, qs)
        tool = os.path.join(ROOT, "tools", "tessera-tools")
        env = dict(os.environ, TESSERA_HESSIAN=hessian_exe())
        args = [sys.executable, tool, "moduli", "minimised.dump", "--quadratic", "1", "1", "1", str(p0)]
        proc = subprocess.run(args + ["--cell-types", "1"], cwd=run.dir, capture_output=True, text=True, env=env)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("left out 3 atom(s) of type 2", proc.stdout)
        found = re.search(r"Hessian: G = ([-0-9.e+]+) .*B = ([-0-9.e+]+)", proc.stdout)
        self.assertAlmostEqual(float(found.group(1)), G, delta=1e-6)
        self.assertAlmostEqual(float(found.group(2)), B, delta=1e-5)
        proc = subprocess.run(args, cwd=run.dir, capture_output=True, text=True, env=env)
        self.assertNotEqual(proc.returncode, 0)
        self.assertIn("type 2 (3 atoms)", proc.stderr)
        self.assertIn("--cell-types 1", proc.stderr)


if __name__ == "__main__":
    lmptest.main()
