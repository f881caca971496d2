# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools flux, velocity and msd on synthetic dumps with known answers: atoms moving at
a known velocity cross each section a known number of times; a velocity field sampled at bin
centres comes back exactly; random walks with a known D and drift give MSD = 4 D tau with the
drift removed and 4 D tau + V^2 tau^2 without; atoms that appear and disappear are handled by
ID (checked against a hand computation).  Several atom types share every dump: the commands
follow the type asked for, and refuse the dump without --types."""

import csv
import math
import os
import tempfile
import unittest

import numpy as np

from helpers import is_png
from test_particles import run
from tessera_tools.dump import Box, Frame, write_dump
from tessera_tools.transport import diffusion_fit, frame_times, load_atoms, msd, section_flux
from tessera_tools.dump import parse_types


def write_frames(path, steps, box, ids, types, unwrapped, present=None):
    """A dump of frames with id type x y ix iy (wrapped positions and image flags) from
    unwrapped positions (F, N, 2); present (F, N) leaves atoms out of frames."""
    frames = []
    for k, step in enumerate(steps):
        keep = np.ones(len(ids), bool) if present is None else present[k]
        u = unwrapped[k][keep]
        s = box.to_fractional(u)
        img = np.floor(s).astype(np.int64)
        w = box.to_cartesian(s - img)
        cols = {"id": np.asarray(ids)[keep], "type": np.asarray(types)[keep], "x": w[:, 0], "y": w[:, 1],
                "ix": img[:, 0], "iy": img[:, 1]}
        frames.append(Frame(step, box, cols, list(cols)))
    write_dump(path, frames)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


class Flux(unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.dir = self.tmp.name

    def test_uniform_motion_known_crossings(self):
        # type 2 moves at +0.5 in x, type 3 at -0.25, type 1 rests; Lx = 10, 40 time units:
        # every type-2 atom goes twice around the box (2 crossings of every section), every
        # type-3 atom once backwards (-1)
        rng = np.random.default_rng(3)
        box = Box(0.0, 10.0, 0.0, 5.0)
        n1, n2, n3 = 5, 30, 12
        x0 = rng.uniform(0, 10, (n1 + n2 + n3, 2)) * [1.0, 0.5]
        types = np.array([1] * n1 + [2] * n2 + [3] * n3)
        vel = np.zeros((len(types), 2))
        vel[types == 2] = [0.5, 0.0]
        vel[types == 3] = [-0.25, 0.0]
        t = np.arange(0.0, 40.5, 1.0)      # 41 frames, dt 1 (steps 0, 10, 20, ... with dt 0.1)
        pos = x0[None] + t[:, None, None] * vel[None]
        dump = os.path.join(self.dir, "flux.dump")
        write_frames(dump, (t * 10).astype(int), box, np.arange(1, len(types) + 1), types, pos)
        traj = load_atoms(dump, parse_types("2"))
        times, known = frame_times(traj, 0.1)
        self.assertTrue(known)
        res = section_flux(traj, times, "x", [0.0, 2.5, 7.3], blocks=4)
        np.testing.assert_array_equal(res["net"], [2 * n2] * 3)
        np.testing.assert_allclose(res["flux"], 2 * n2 / 40.0, rtol=1e-12)
        self.assertTrue(np.all(np.isfinite(res["flux_err"])))
        res3 = section_flux(load_atoms(dump, parse_types("3")), times, "x", [4.0])
        self.assertEqual(res3["net"][0], -n3)
        self.assertEqual(res3["minus"][0], n3)
        self.assertEqual(section_flux(traj, times, "y", [1.0])["net"][0], 0)
        # the command: both types at once, a table and pictures; without --types: refused
        out = os.path.join(self.dir, "flux.csv")
        code, text, err = run(["flux", dump, "--types", "2,3", "--x", "2.5", "--y", "1", "--dt", "0.1",
                               "--csv", out, "-o", os.path.join(self.dir, "flux.png"), "--dpi", "50"])
        self.assertEqual(code, 0, err)
        rows = read_csv(out)
        self.assertEqual([r["axis"] for r in rows], ["x", "y"])
        self.assertAlmostEqual(float(rows[0]["flux"]), (2 * n2 - n3) / 40.0, places=12)
        self.assertAlmostEqual(float(rows[0]["flux_per_length"]), (2 * n2 - n3) / 40.0 / 5.0, places=12)
        self.assertEqual(float(rows[1]["net"]), 0.0)
        self.assertTrue(is_png(os.path.join(self.dir, "flux_x.png")))
        code, _, err = run(["flux", dump, "--x", "2.5", "--csv", out])
        self.assertNotEqual(code, 0)
        self.assertIn("type 1: 5 atoms, type 2: 30 atoms, type 3: 12 atoms", err)
        self.assertIn("--types", err)

    def test_open_box_and_error_bars(self):
        # an open box: atoms cross x = 5 once when they pass it; a Poisson-like stream of
        # atoms entering at random times gives error bars that cover the exact rate
        box = Box(0.0, 10.0, 0.0, 2.0, periodic=(False, True, True))
        rng = np.random.default_rng(11)
        starts = np.sort(rng.uniform(0, 200, 400))      # each atom starts at x = 0 at its own time
        t = np.arange(0.0, 201.0, 1.0)
        pos = np.zeros((len(t), len(starts), 2))
        pos[..., 0] = np.clip((t[:, None] - starts[None]) * 1.0, 0, 9.9)
        pos[..., 1] = 1.0
        dump = os.path.join(self.dir, "open.dump")
        write_frames(dump, t.astype(int), box, np.arange(1, len(starts) + 1), np.ones(len(starts), int), pos)
        traj = load_atoms(dump, None)
        res = section_flux(traj, t, "x", [5.0], blocks=10)
        exact = np.sum(starts + 5.0 <= 200.0)          # those that reached x = 5 by t = 200
        self.assertEqual(res["net"][0], exact)
        self.assertLess(abs(res["flux"][0] - 2.0), 4 * res["flux_err"][0])    # 400 atoms / 200: 2 per unit time

    def test_tilted_box_x_sections_refused(self):
        box = Box(0.0, 4.0, 0.0, 4.0, xy=1.0)
        pos = np.zeros((2, 1, 2)) + 1.0
        dump = os.path.join(self.dir, "tilt.dump")
        write_frames(dump, [0, 1], box, [1], [1], pos)
        traj = load_atoms(dump, None)
        with self.assertRaises(ValueError) as ctx:
            section_flux(traj, [0.0, 1.0], "x", [1.0])
        self.assertIn("y = const", str(ctx.exception))


class VelocityField(unittest.TestCase):

    def test_field_at_bin_centres(self):
        # vx = A sin(2 pi y / Ly) + 0.1, vy = Ly/ny per frame: every atom moves one bin up per
        # frame, so it always sits at a bin centre in y and each bin's mean is exact
        nx, ny, A = 4, 8, 0.7
        box = Box(0.0, 8.0, 0.0, 4.0)
        rng = np.random.default_rng(5)
        n = 64
        x0 = rng.uniform(0, 8, n)
        y0 = (rng.integers(0, ny, n) + 0.5) * box.ly / ny
        F, dt = 12, 0.5
        pos = np.zeros((F, n, 2))
        pos[0] = np.column_stack([x0, y0])
        for k in range(1, F):
            y = pos[k - 1, :, 1]
            pos[k, :, 0] = pos[k - 1, :, 0] + (A * np.sin(2 * math.pi * y / box.ly) + 0.1) * dt
            pos[k, :, 1] = y + box.ly / ny
        types = np.where(np.arange(n) % 2 == 0, 1, 4)
        with tempfile.TemporaryDirectory() as d:
            dump = os.path.join(d, "v.dump")
            write_frames(dump, np.arange(F) * 10, box, np.arange(1, n + 1), types, pos)
            out = os.path.join(d, "v.csv")
            code, text, err = run(["velocity", dump, "--types", "1*", "--bins", str(nx), str(ny), "--dt", "0.05",
                                   "--csv", out, "-o", os.path.join(d, "v.png"), "--dpi", "50"])
            self.assertEqual(code, 0, err)
            self.assertTrue(is_png(os.path.join(d, "v.png")))
            rows = read_csv(out)
            self.assertEqual(len(rows), nx * ny)
            for r in rows:
                if int(r["samples"]) == 0:
                    continue
                yc = (int(r["iy"]) + 0.5) * box.ly / ny
                self.assertAlmostEqual(float(r["y"]), yc, places=12)
                self.assertAlmostEqual(float(r["vx"]), A * math.sin(2 * math.pi * yc / box.ly) + 0.1, places=9)
                self.assertAlmostEqual(float(r["vy"]), box.ly / ny / dt, places=9)
            self.assertEqual(sum(int(r["samples"]) for r in rows), n * (F - 1))


class MSD(unittest.TestCase):

    def walk(self, n, F, D, v, dt=1.0, seed=1):
        rng = np.random.default_rng(seed)
        steps = rng.normal(0.0, math.sqrt(2 * D * dt), (F - 1, n, 2)) + np.asarray(v) * dt
        start = rng.uniform(0, 20, (n, 2))
        return np.concatenate([start[None], start[None] + np.cumsum(steps, axis=0)])

    def test_random_walk_with_drift(self):
        D, v, dt = 0.25, (0.3, -0.1), 0.5
        n, F = 300, 201
        colloid = self.walk(n, F, D, v, dt)
        cells = self.walk(40, F, 2.0, (0.0, 0.0), dt, seed=2)      # another type, other D
        box = Box(0.0, 20.0, 0.0, 20.0)
        pos = np.concatenate([colloid, cells], axis=1)
        types = [3] * n + [1] * 40
        with tempfile.TemporaryDirectory() as d:
            dump = os.path.join(d, "w.dump")
            write_frames(dump, np.arange(F) * 5, box, np.arange(1, n + 41), types, pos)
            traj = load_atoms(dump, parse_types("3"))
            times, _ = frame_times(traj, dt / 5)
            res = msd(traj, times, max_lag=40)
            tau = res["tau"]
            np.testing.assert_allclose(tau, dt * np.arange(1, 41))
            for k in range(20):
                self.assertAlmostEqual(res["msd_nodrift"][k] / (4 * D * tau[k]), 1.0, delta=0.05, msg=f"lag {k + 1}")
                full = 4 * D * tau[k] + (v[0] ** 2 + v[1] ** 2) * tau[k] ** 2
                self.assertAlmostEqual(res["msd"][k] / full, 1.0, delta=0.05, msg=f"lag {k + 1}")
                # the error bar is that of the scatter: the deviation is within 4 of them
                self.assertLess(abs(res["msd_nodrift"][k] - 4 * D * tau[k]), 4 * res["msd_nodrift_err"][k] + 1e-12)
            for c in (0, 1):
                self.assertLess(abs(res["drift"][c] - v[c]), 4 * res["drift_err"][c])
            fit = diffusion_fit(tau, res["msd_nodrift"], 5.0)
            self.assertLess(abs(fit["D"] - D), 4 * fit["D_err"] + 0.02 * D)
            out = os.path.join(d, "m.csv")
            code, text, err = run(["msd", dump, "--types", "3", "--dt", str(dt / 5), "--max-lag", "40",
                                   "--csv", out, "-o", os.path.join(d, "m.png"), "--dpi", "50"])
            self.assertEqual(code, 0, err)
            self.assertIn("D = ", text)
            rows = read_csv(out)
            self.assertAlmostEqual(float(rows[3]["msd_nodrift"]), res["msd_nodrift"][3], places=9)
            self.assertTrue(is_png(os.path.join(d, "m.png")))

    def test_appearing_and_disappearing_by_id(self):
        # atom 1 is in every frame, atom 2 only in frames 1 and 2, atom 3 in frames 0 and 2
        box = Box(0.0, 10.0, 0.0, 10.0)
        pos = np.array([[[1.0, 1.0], [0.0, 0.0], [5.0, 5.0]],
                        [[2.0, 1.0], [3.0, 3.0], [0.0, 0.0]],
                        [[2.0, 3.0], [3.0, 4.0], [5.0, 8.0]]])
        present = np.array([[1, 0, 1], [1, 1, 0], [1, 1, 1]], bool)
        with tempfile.TemporaryDirectory() as d:
            dump = os.path.join(d, "ids.dump")
            write_frames(dump, [0, 1, 2], box, [1, 2, 3], [1, 1, 1], pos, present)
            traj = load_atoms(dump, None)
            res = msd(traj, [0.0, 1.0, 2.0])
        # lag 1: atom 1 (0->1): 1; atom 1 (1->2): 4; atom 2 (1->2): 1  -> pairs 3, mean 2
        # lag 2: atom 1 (0->2): 1 + 4 = 5; atom 3 (0->2): 9               -> pairs 2, mean 7
        np.testing.assert_array_equal(res["count"], [3, 2])
        np.testing.assert_allclose(res["msd"], [2.0, 7.0])
        # drift: increments (1,0), (0,2), (0,1) over 3 time units
        np.testing.assert_allclose(res["drift"], [1.0 / 3.0, 1.0])
        V = res["drift"]
        d1 = [np.array([1.0, 0.0]), np.array([0.0, 2.0]), np.array([0.0, 1.0])]
        d2 = [np.array([1.0, 2.0]), np.array([0.0, 3.0])]
        self.assertAlmostEqual(res["msd_nodrift"][0], np.mean([np.sum((x - V) ** 2) for x in d1]), places=12)
        self.assertAlmostEqual(res["msd_nodrift"][1], np.mean([np.sum((x - 2 * V) ** 2) for x in d2]), places=12)

    def test_unequal_spacing_refused(self):
        box = Box(0.0, 10.0, 0.0, 10.0)
        pos = np.zeros((3, 1, 2))
        with tempfile.TemporaryDirectory() as d:
            dump = os.path.join(d, "u.dump")
            write_frames(dump, [0, 1, 3], box, [1], [1], pos)
            code, _, err = run(["msd", dump, "--csv", os.path.join(d, "m.csv")])
        self.assertNotEqual(code, 0)
        self.assertIn("equally spaced", err)


if __name__ == "__main__":
    unittest.main()
