# SPDX-License-Identifier: GPL-2.0-or-later
import gzip
import os
import tempfile
import unittest

import numpy as np

import helpers  # noqa: F401  (import path, Agg backend)
from tessera_tools.dump import Box, DumpFormatError, iter_dump, read_dump, read_frame, write_dump


def _frame_text(timestep, box_lines, names, table, extra_items=""):
    rows = "\n".join(" ".join(v if isinstance(v, str) else repr(v) for v in row) for row in table)
    return (f"ITEM: TIMESTEP\n{timestep}\n{extra_items}ITEM: NUMBER OF ATOMS\n{len(table)}\n"
            f"{box_lines}ITEM: ATOMS {' '.join(names)}\n{rows}\n")


class DumpReading(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.rng = np.random.default_rng(7)

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.tmp.name, name)

    def test_multiframe_shuffled_columns_and_image_flags(self):
        """Column order and row order change per frame; x + image flags give the known path."""
        lx, ly, n = 5.0, 4.0, 7
        box_lines = f"ITEM: BOX BOUNDS pp pp pp\n-1.0 {lx - 1.0}\n2.0 {2.0 + ly}\n-0.5 0.5\n"
        truth, text = [], ""
        start = self.rng.uniform([-1, 2], [lx - 1, 2 + ly], size=(n, 2))
        for k in range(4):
            # unwrapped positions that wander over several box lengths
            unwrapped = start + k * np.array([3.1, -2.7]) + self.rng.normal(0, 0.1, (n, 2))
            truth.append(unwrapped)
            s = (unwrapped - [-1.0, 2.0]) / [lx, ly]
            image = np.floor(s).astype(int)
            wrapped = unwrapped - image * [lx, ly]
            vel = self.rng.normal(size=(n, 2))
            cols = {"id": np.arange(1, n + 1), "type": np.full(n, 2), "x": wrapped[:, 0], "y": wrapped[:, 1],
                    "ix": image[:, 0], "iy": image[:, 1], "vx": vel[:, 0], "vy": vel[:, 1],
                    "c_v[1]": np.arange(n) * 0.5}
            names = list(cols)
            self.rng.shuffle(names)
            order = self.rng.permutation(n)
            table = [[cols[name][i].item() for name in names] for i in order]
            text += _frame_text(100 * k, box_lines, names, table)
        with open(self.path("d.dump"), "w") as f:
            f.write(text)
        frames = read_dump(self.path("d.dump"))
        self.assertEqual([f.timestep for f in frames], [0, 100, 200, 300])
        for frame, want in zip(frames, truth):
            np.testing.assert_array_equal(frame["id"], np.arange(1, n + 1))
            self.assertEqual(frame["id"].dtype.kind, "i")
            self.assertEqual(frame["ix"].dtype.kind, "i")
            np.testing.assert_allclose(frame["c_v[1]"], np.arange(n) * 0.5)
            np.testing.assert_allclose(frame.unwrapped(), want, atol=1e-12)
            wrapped = frame.positions()
            self.assertTrue(np.all(wrapped >= [-1.0, 2.0]) and np.all(wrapped < [lx - 1, 2 + ly]))
            self.assertTrue(frame.has_unwrapped())
        self.assertAlmostEqual(frames[0].box.area, lx * ly)
        self.assertEqual(frames[0].box.periodic, (True, True, True))

    def test_xu_yu_and_scaled_columns(self):
        box_lines = "ITEM: BOX BOUNDS pp pp pp\n0 10\n0 5\n-0.5 0.5\n"
        table = [[2, 0.25, 0.5, 12.5, -2.5], [1, 0.75, 0.1, 7.5, 0.5]]
        with open(self.path("s.dump"), "w") as f:
            f.write(_frame_text(3, box_lines, ["id", "xs", "ys", "xu", "yu"], table))
        frame = read_frame(self.path("s.dump"))
        np.testing.assert_allclose(frame.positions(), [[7.5, 0.5], [2.5, 2.5]])
        np.testing.assert_allclose(frame.unwrapped(), [[7.5, 0.5], [12.5, -2.5]])

    def test_triclinic_box_and_image_flags(self):
        # LAMMPS writes the bounding box of the tilted cell: xlo_bound = xlo + min(0, xy, ...)
        xy = -1.5
        box_lines = f"ITEM: BOX BOUNDS xy xz yz pp pp pp\n{0 + xy} 8.0 {xy}\n0 4 0\n-0.5 0.5 0\n"
        table = [[1, 1.0, 1.0, 1, -2], [2, 3.0, 2.0, 0, 1]]
        with open(self.path("t.dump"), "w") as f:
            f.write(_frame_text(0, box_lines, ["id", "x", "y", "ix", "iy"], table))
        frame = read_frame(self.path("t.dump"))
        box = frame.box
        self.assertTrue(box.triclinic)
        self.assertAlmostEqual(box.xlo, 0.0)
        self.assertAlmostEqual(box.xhi, 8.0)
        self.assertAlmostEqual(box.xy, xy)
        np.testing.assert_allclose(frame.unwrapped(), [[1 + 8 - 2 * xy, 1 - 8], [3 + xy, 2 + 4]])
        # round trip through the writer keeps the tilted box
        write_dump(self.path("t2.dump"), [frame])
        again = read_frame(self.path("t2.dump"))
        self.assertAlmostEqual(again.box.xy, xy)
        np.testing.assert_allclose(again.unwrapped(), frame.unwrapped())

    def test_gzip_time_item_and_selection(self):
        box_lines = "ITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n-0.5 0.5\n"
        text = "".join(_frame_text(t, box_lines, ["id", "x", "y"], [[1, 0.5, 0.5]],
                                   extra_items=f"ITEM: TIME\n{t * 0.01}\n") for t in range(0, 50, 10))
        with gzip.open(self.path("g.dump.gz"), "wt") as f:
            f.write(text)
        frames = list(iter_dump(self.path("g.dump.gz")))
        self.assertEqual(len(frames), 5)
        self.assertAlmostEqual(frames[2].time, 0.2)
        self.assertEqual(read_frame(self.path("g.dump.gz"), timestep=30).timestep, 30)
        self.assertEqual(read_frame(self.path("g.dump.gz"), index=1).timestep, 10)
        self.assertEqual(read_frame(self.path("g.dump.gz")).timestep, 40)
        self.assertEqual([f.timestep for f in read_dump(self.path("g.dump.gz"), every=2)], [0, 20, 40])

    def test_truncated_and_malformed(self):
        box_lines = "ITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n-0.5 0.5\n"
        text = _frame_text(0, box_lines, ["id", "x", "y"], [[1, 0.5, 0.5], [2, 0.1, 0.2]])
        with open(self.path("cut.dump"), "w") as f:
            f.write(text[:-12])
        with self.assertRaises(DumpFormatError):
            read_dump(self.path("cut.dump"))
        with open(self.path("junk.dump"), "w") as f:
            f.write("hello\n")
        with self.assertRaises(DumpFormatError):
            read_dump(self.path("junk.dump"))
        with open(self.path("ok.dump"), "w") as f:
            f.write(text)
        with self.assertRaises(KeyError) as ctx:
            read_frame(self.path("ok.dump")).unwrapped()
        self.assertIn("unwrapped", str(ctx.exception))

    def test_box_wrap_and_minimum_image(self):
        box = Box(0, 4, 0, 2, xy=1.0)
        pts = np.array([[4.5, 0.5], [-0.5, 2.5], [1.0, -0.1]])
        w = box.wrap(pts)
        s = box.to_fractional(w)
        self.assertTrue(np.all(s >= 0) and np.all(s < 1))
        # wrapping moves points by whole box vectors only
        shift = np.linalg.solve(box.matrix, (pts - w).T).T
        np.testing.assert_allclose(shift, np.round(shift), atol=1e-12)
        d = box.minimum_image(np.array([[3.9, 0.0], [0.0, 1.9]]))
        np.testing.assert_allclose(d, [[-0.1, 0.0], [-1.0, -0.1]], atol=1e-12)


class WritingZ(unittest.TestCase):
    """Dumps written by the tools carry z (ASE and other readers require it)."""

    def test_z_added_after_y(self):
        frame = helpers.frame_from(np.array([[0.5, 0.5], [1.5, 0.5]]), Box(0, 2, 0, 1))
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "z.dump")
            write_dump(path, [frame])
            (back,) = read_dump(path)
            self.assertEqual(back.names, ["id", "type", "x", "y", "z"])
            np.testing.assert_array_equal(back["z"], 0.0)
            np.testing.assert_array_equal(back["x"], frame["x"])
            write_dump(path, [frame], include_z=False)
            self.assertNotIn("z", read_dump(path)[0].names)


if __name__ == "__main__":
    unittest.main()
