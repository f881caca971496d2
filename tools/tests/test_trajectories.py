# SPDX-License-Identifier: GPL-2.0-or-later
import math
import os
import tempfile
import unittest

import numpy as np

from helpers import frame_from, hex_lattice, square_lattice
from tessera_tools.dump import Box, Frame, write_dump
from tessera_tools.trajectories import (coordination, load_trajectory, orientation, trajectory_segments,
                                        velocity_angle)
from tessera_tools.voronoi import periodic_voronoi


class Observables(unittest.TestCase):
    def test_uniform_velocity_gives_coordination_one(self):
        rng = np.random.default_rng(2)
        box = Box(0, 7, 0, 5)
        pts = rng.uniform(0, 1, (50, 2)) * [7, 5]
        tess = periodic_voronoi(pts, box)
        speed = rng.uniform(0.1, 3.0, 50)[:, None]  # only directions matter
        v = speed * np.array([math.cos(0.7), math.sin(0.7)])
        np.testing.assert_allclose(coordination(tess.neighbours, v), 1.0, rtol=1e-12)

    def test_orientation_of_axis_velocities(self):
        v = np.array([[2.0, 0.0], [-0.5, 0.0], [0.0, 3.0], [0.0, -1.0], [1.0, 1.0], [0.0, 0.0]])
        o = orientation(v)
        np.testing.assert_allclose(o[:5], [0.0, math.pi, math.pi / 2, math.pi / 2, math.pi / 4], atol=1e-12)
        self.assertTrue(np.isnan(o[5]))
        a = velocity_angle(v)
        np.testing.assert_allclose(a[:4], [0.0, math.pi, math.pi / 2, -math.pi / 2], atol=1e-12)

    def test_antiparallel_rows(self):
        """Square lattice, rows moving +x and -x in turn: two neighbours agree, two oppose -> C = 0.
        Hexagonal lattice, same rows: two neighbours in the row, four in the rows around -> C = -1/3."""
        pts, box = square_lattice(6)
        sign = np.where((np.floor(pts[:, 1]) % 2) == 0, 1.0, -1.0)
        v = np.column_stack([sign, np.zeros(len(pts))])
        c = coordination(periodic_voronoi(pts, box).neighbours, v)
        np.testing.assert_allclose(c, 0.0, atol=1e-12)
        pts, box = hex_lattice(6, 6)
        row = np.round(pts[:, 1] / (math.sqrt(3) / 2)).astype(int)
        v = np.column_stack([np.where(row % 2 == 0, 1.0, -1.0), np.zeros(len(pts))])
        c = coordination(periodic_voronoi(pts, box).neighbours, v)
        np.testing.assert_allclose(c, -1.0 / 3.0, atol=1e-12)
        np.testing.assert_allclose(orientation(v)[row % 2 == 1], math.pi)

    def test_cells_at_rest(self):
        pts, box = square_lattice(4)
        v = np.tile([1.0, 0.0], (16, 1))
        v[5] = 0.0
        c = coordination(periodic_voronoi(pts, box).neighbours, v)
        self.assertTrue(np.isnan(c[5]))
        np.testing.assert_allclose(np.delete(c, 5), 1.0)


class TrajectoryLoading(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def _write(self, name, columns, steps=6, velocity=(0.9, -0.4)):
        """Cells of a hexagonal lattice drifting with one velocity across the boundary."""
        pts, box = hex_lattice(4, 4)
        vel = np.array(velocity)
        frames, truth = [], []
        for k in range(steps):
            unwrapped = pts + k * vel
            truth.append(unwrapped)
            s = box.to_fractional(unwrapped)
            image = np.floor(s).astype(np.int64)
            wrapped = box.to_cartesian(s - image)
            f = frame_from(wrapped, box, timestep=10 * k, ix=image[:, 0], iy=image[:, 1],
                           xu=unwrapped[:, 0], yu=unwrapped[:, 1],
                           vx=np.full(len(pts), vel[0]), vy=np.full(len(pts), vel[1]))
            frames.append(f)
        path = os.path.join(self.tmp.name, name)
        write_dump(path, frames, columns=columns)
        return path, np.array(truth)

    def test_unwrapped_from_image_flags(self):
        path, truth = self._write("a.dump", ["id", "vx", "iy", "x", "vy", "ix", "y"])
        traj = load_trajectory(path, quiet=True)
        np.testing.assert_allclose(traj.positions, truth, atol=1e-12)
        np.testing.assert_allclose(traj.coordination(), 1.0)
        np.testing.assert_allclose(traj.orientation(), math.acos(0.9 / math.hypot(0.9, 0.4)))

    def test_continuity_unwrapping_and_finite_difference_velocities(self):
        path, truth = self._write("b.dump", ["id", "x", "y"])
        traj = load_trajectory(path, quiet=True)
        np.testing.assert_allclose(traj.positions - traj.positions[0], truth - truth[0], atol=1e-12)
        u = traj.velocities / np.linalg.norm(traj.velocities, axis=2)[..., None]
        np.testing.assert_allclose(u.reshape(-1, 2), np.tile([0.9, -0.4] / np.hypot(0.9, 0.4), (u.size // 2, 1)),
                                   atol=1e-12)

    def test_segments_cut_at_the_boundary_when_wrapped(self):
        path, truth = self._write("c.dump", ["id", "x", "y", "xu", "yu", "vx", "vy"], velocity=(1.5, 0.0))
        traj = load_trajectory(path, quiet=True)
        values = np.zeros(traj.positions.shape[:2])
        seg, vals = trajectory_segments(traj.positions, values)
        self.assertEqual(len(seg), (len(traj) - 1) * len(traj.ids))
        seg_w, _ = trajectory_segments(traj.positions, values, wrapped=traj.wrapped, box=traj.boxes[0])
        # box length 4, step 1.5 over 5 steps: every cell crosses x = 4 once or twice
        self.assertLess(len(seg_w), len(seg))
        steps = np.linalg.norm(seg_w[:, 1] - seg_w[:, 0], axis=1)
        np.testing.assert_allclose(steps, 1.5, rtol=1e-9)

    def test_changing_atom_ids_followed(self):
        """IDs 1-9, then 2-10 (cell 1 gone, cell 10 new): the union of IDs, each cell where it is
        present (division and death; test_changing_ids.py has the full cases)."""
        pts, box = square_lattice(3)
        f0 = frame_from(pts, box, 0)
        f1 = Frame(1, box, dict(f0.columns, id=np.arange(2, 11)), f0.names)
        path = os.path.join(self.tmp.name, "d.dump")
        write_dump(path, [f0, f1])
        traj = load_trajectory(path, quiet=True)
        np.testing.assert_array_equal(traj.ids, np.arange(1, 11))
        np.testing.assert_array_equal(traj.present[:, 0], [True, False])
        np.testing.assert_array_equal(traj.present[:, 9], [False, True])
        np.testing.assert_allclose(traj.wrapped[1, 1], pts[0])      # ID 2 sits where row 0 is
        msd, count = traj.msd()
        np.testing.assert_array_equal(count, [9, 8])


if __name__ == "__main__":
    unittest.main()
