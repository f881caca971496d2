# SPDX-License-Identifier: GPL-2.0-or-later
"""Figure conventions of the studies (studies/studylib.py): legends end up where they cover no
line, multi-panel figures get panel letters, and every figure is saved as a PNG at the dpi asked
for plus a vector PDF."""

import os
import sys
import tempfile
import unittest

import numpy as np

import helpers  # noqa: F401 (path, Agg backend)

sys.path.insert(0, os.path.join(os.path.dirname(helpers.TOOLS), "studies"))
import studylib  # noqa: E402
from studylib import plt  # noqa: E402


class Figures(unittest.TestCase):

    def test_legend_moved_off_the_data(self):
        fig, ax = plt.subplots(figsize=(4, 3))
        x = np.linspace(0, 1, 200)
        # lines everywhere: no free corner inside the axes
        for k in range(12):
            ax.plot(x, k / 11 + 0.0 * x, label=f"line {k}")
        ax.plot(x, x, label="diagonal")
        ax.legend(loc="center")
        renderer = fig.canvas.get_renderer()
        fig.canvas.draw()
        self.assertGreater(studylib._overlap(ax, ax.get_legend(), renderer), 0)
        studylib.place_legends(fig)
        self.assertEqual(studylib._overlap(ax, ax.get_legend(), renderer), 0)
        # and it is outside the axes, below them
        self.assertLess(ax.get_legend().get_window_extent(renderer).y1, ax.get_window_extent(renderer).y0)
        plt.close(fig)

    def test_legend_kept_inside_when_free(self):
        fig, ax = plt.subplots(figsize=(4, 3))
        x = np.linspace(0, 1, 50)
        ax.plot(x, x ** 4, label="low then high")
        ax.legend(loc="lower right")    # covers the curve's end
        studylib.place_legends(fig)
        renderer = fig.canvas.get_renderer()
        legend = ax.get_legend().get_window_extent(renderer)
        self.assertEqual(studylib._overlap(ax, ax.get_legend(), renderer), 0)
        self.assertTrue(ax.get_window_extent(renderer).contains(legend.x0 + 1, legend.y0 + 1))
        plt.close(fig)

    def test_panel_letters_and_files(self):
        with tempfile.TemporaryDirectory() as d:
            study = studylib.Study.__new__(studylib.Study)
            study.name, study.figures, study.out = "test", d, d
            fig, axes = plt.subplots(1, 3)
            im = axes[2].imshow(np.eye(3))
            fig.colorbar(im, ax=axes[2])
            study.savefig(fig, "three.png", dpi=72)
            letters = [t.get_text() for ax in axes for t in ax.texts]
            self.assertEqual(letters, ["a", "b", "c"])    # not on the colour bar
            self.assertTrue(helpers.is_png(os.path.join(d, "three.png")))
            with open(os.path.join(d, "three.pdf"), "rb") as f:
                self.assertEqual(f.read(5), b"%PDF-")
            fig, ax = plt.subplots()
            study.savefig(fig, "one.png", dpi=72)
            self.assertEqual(len(ax.texts), 0)


if __name__ == "__main__":
    unittest.main()
