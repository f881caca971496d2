# SPDX-License-Identifier: GPL-2.0-or-later
"""Kymographs of a per-cell species and of the cell density (tessera-tools plot kymograph) on a
dump written here with a known travelling wave c = cos(k x - w t): the binned means equal the
closed form of the mean of the cosine over each bin's evenly spaced cells, the density the
cells placed per bin over the bin's area, and the measured wavelength and period 2 pi / k and
2 pi / w (the density pattern, which does not move, has an infinite period)."""

import contextlib
import io
import math
import os
import tempfile
import unittest

import numpy as np

from helpers import is_png  # noqa: F401 (sets the path)
from tessera_tools.cli import main
from tessera_tools.dump import Box, Frame, write_dump
from tessera_tools.kymograph import kymograph, measure_wave

L, H, BINS, NY = 24.0, 4.0, 12, 2
WIDTH = L / BINS
PER_BIN = [3 + b % 3 for b in range(BINS)]     # cells per bin and row: 3, 4, 5, 3, ...
K = 2 * math.pi * 3 / L                        # three wavelengths across the box
FRAMES, EVERY, DT = 20, 100, 0.005             # frames 0.5 apart: a record of 10
W = 2 * math.pi * 2 / (FRAMES * EVERY * DT)    # two periods over the record


def wave_frames(sign=1.0, k=K, w=W):
    x = np.concatenate([b * WIDTH + (np.arange(m) + 0.5) * WIDTH / m for b, m in enumerate(PER_BIN)])
    pts = np.array([(xx, (r + 0.5) * H / NY) for r in range(NY) for xx in x])
    n = len(pts)
    order = np.random.default_rng(1).permutation(n)
    box = Box(0.0, L, 0.0, H)
    frames = []
    for f in range(FRAMES):
        t = f * EVERY * DT
        c = np.cos(k * pts[:, 0] - sign * w * t)
        cols = {"id": np.arange(1, n + 1)[order], "type": np.ones(n, dtype=np.int64), "x": pts[order, 0],
                "y": pts[order, 1], "d_erk": c[order]}
        frames.append(Frame(f * EVERY, box, cols, list(cols)))
    return frames


def bin_means(t, sign=1.0):
    """Mean of cos(k x - w t) over the bin's m cells at x = a + (j + 1/2) h, h = WIDTH / m:
    sin(k m h / 2) / (m sin(k h / 2)) cos(k (a + WIDTH / 2) - w t)."""
    out = []
    for b, m in enumerate(PER_BIN):
        h = WIDTH / m
        out.append(math.sin(K * m * h / 2) / (m * math.sin(K * h / 2))
                   * math.cos(K * (b + 0.5) * WIDTH - sign * W * t))
    return np.array(out)


class Kymograph(unittest.TestCase):

    def test_bins_equal_the_closed_form(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "cells.dump")
            write_dump(path, wave_frames(), include_z=False)
            kymo = kymograph(path, "d_erk", "x", BINS, dt=DT)
        np.testing.assert_allclose(kymo.times, np.arange(FRAMES) * EVERY * DT, rtol=1e-14)
        np.testing.assert_allclose(kymo.centres, (np.arange(BINS) + 0.5) * WIDTH, rtol=1e-14)
        for f, t in enumerate(kymo.times):
            np.testing.assert_allclose(kymo.values[f], bin_means(t), atol=1e-12)
        density = np.array(PER_BIN) * NY / (WIDTH * H)
        np.testing.assert_allclose(kymo.density, np.tile(density, (FRAMES, 1)), rtol=1e-14)
        # along y: every bin holds a whole row of cells, the species averages over x
        kymo_y = kymograph(wave_frames(), "d_erk", "y", NY, dt=DT)
        self.assertEqual(kymo_y.density.shape, (FRAMES, NY))
        np.testing.assert_allclose(kymo_y.density, sum(PER_BIN) / (L * H / NY), rtol=1e-14)

    def test_wavelength_and_period(self):
        for sign in (1.0, -1.0):
            with self.subTest(direction=sign):
                kymo = kymograph(wave_frames(sign), "d_erk", "x", BINS, dt=DT)
                got = measure_wave(kymo.times, kymo.centres, kymo.values)
                self.assertAlmostEqual(got["wavelength"], 2 * math.pi / K, places=10)
                self.assertAlmostEqual(got["period"], 2 * math.pi / W, places=10)
                self.assertAlmostEqual(got["velocity"], sign * W / K, places=10)
                self.assertGreater(got["power"], 0.999)
                # the density: cells 3, 4, 5 per bin repeating, a pattern of 3 bins that stays put
                dens = measure_wave(kymo.times, kymo.centres, kymo.density)
                self.assertAlmostEqual(dens["wavelength"], 3 * WIDTH, places=10)
                self.assertEqual(dens["period"], math.inf)

    def test_off_grid_wave_within_a_twentieth_of_the_resolution(self):
        """A wave between the transform's samples (2.6 wavelengths, 1.7 periods) is placed by the
        parabola through the logarithms of the peak and its neighbours (Hann window), to better
        than a twentieth of a sample; so is a wave of 1.5 wavelengths and 4.5 periods."""
        k, w = 2 * math.pi * 2.6 / L, 2 * math.pi * 1.7 / (FRAMES * EVERY * DT)
        kymo = kymograph(wave_frames(k=k, w=w), "d_erk", "x", BINS, dt=DT)
        got = measure_wave(kymo.times, kymo.centres, kymo.values)
        self.assertLess(abs(L / got["wavelength"] - 2.6), 0.05)
        self.assertLess(abs(FRAMES * EVERY * DT / got["period"] - 1.7), 0.05)
        k, w = 2 * math.pi * 1.5 / L, 2 * math.pi * 4.5 / (FRAMES * EVERY * DT)
        got = measure_wave(*(lambda q: (q.times, q.centres, q.values))(
            kymograph(wave_frames(k=k, w=w), "d_erk", "x", BINS, dt=DT)))
        self.assertLess(abs(L / got["wavelength"] - 1.5), 0.05)
        self.assertLess(abs(FRAMES * EVERY * DT / got["period"] - 4.5), 0.05)

    def test_empty_bins(self):
        """Cells of bin 4 removed from every other frame: NaN mean, count and density 0 there, the
        other bins unchanged, and the wave still measured (the hole interpolated) to 0.05 sample."""
        frames = wave_frames()
        for f in frames[::2]:
            keep = np.floor(np.asarray(f["x"]) / WIDTH) != 4
            f.columns = {k: v[keep] for k, v in f.columns.items()}
        kymo = kymograph(frames, "d_erk", "x", BINS, dt=DT)
        self.assertTrue(np.isnan(kymo.values[::2, 4]).all())
        np.testing.assert_array_equal(kymo.density[::2, 4], 0.0)
        np.testing.assert_allclose(kymo.values[1::2, 4], [bin_means(t)[4] for t in kymo.times[1::2]], atol=1e-12)
        np.testing.assert_allclose(np.delete(kymo.values[0], 4), np.delete(bin_means(0.0), 4), atol=1e-12)
        got = measure_wave(kymo.times, kymo.centres, kymo.values)
        self.assertLess(abs(L / got["wavelength"] - L * K / (2 * math.pi)), 0.05)
        self.assertLess(abs(FRAMES * EVERY * DT / got["period"] - FRAMES * EVERY * DT * W / (2 * math.pi)), 0.05)
        with tempfile.TemporaryDirectory() as d:
            kymo.write_csv(os.path.join(d, "k.csv"))
            with open(os.path.join(d, "k.csv")) as f:
                rows = f.read().splitlines()
            self.assertEqual(rows[1 + 4].split(",")[3:], ["", "0", "0"])

    def test_errors(self):
        kymo = kymograph(wave_frames(), "d_erk", "x", BINS, dt=DT)
        with self.assertRaisesRegex(ValueError, "equally spaced"):
            measure_wave(kymo.times[[0, 1, 3]], kymo.centres, kymo.values[[0, 1, 3]])
        with self.assertRaisesRegex(ValueError, "uniform"):
            measure_wave(kymo.times, kymo.centres, np.ones_like(kymo.values))
        with self.assertRaisesRegex(KeyError, "d_notch"):
            kymograph(wave_frames(), "d_notch", "x", BINS)
        with self.assertRaisesRegex(ValueError, "bins"):
            kymograph(wave_frames(), "d_erk", "x", 0)

    def test_command(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "cells.dump")
            write_dump(path, wave_frames(), include_z=False)
            png, csv, npz = (os.path.join(d, n) for n in ("k.png", "k.csv", "k.npz"))
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                self.assertEqual(main(["plot", "kymograph", path, "-c", "d_erk", "--bins", str(BINS),
                                       "--dt", str(DT), "-o", png, "--csv", csv, "--npz", npz,
                                       "--measure", "--dpi", "60"]), 0)
            text = out.getvalue()
            self.assertTrue(is_png(png))
            self.assertIn(f"d_erk: wavelength {2 * math.pi / K:.6g}, period {2 * math.pi / W:.6g} time", text)
            self.assertIn("density: wavelength 6, period inf", text)
            rows = np.genfromtxt(csv, delimiter=",", names=True)
            self.assertEqual(len(rows), FRAMES * BINS)
            last = rows[-BINS:]
            np.testing.assert_allclose(last["d_erk"], bin_means(last["time"][0]), atol=1e-9)
            np.testing.assert_array_equal(last["count"], np.array(PER_BIN) * NY)
            saved = np.load(npz)
            np.testing.assert_allclose(saved["values"][3], bin_means(saved["times"][3]), atol=1e-12)
            with self.assertRaises(SystemExit) as caught:
                main(["plot", "kymograph", path, "-c", "d_erk"])
            self.assertIn("nothing to do", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
