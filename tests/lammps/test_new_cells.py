#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Cells that appear during a run under fix polarity (fix deposit, create_atoms
before 'run N pre no'): on their first step they get the angle that the seed
and their atom ID give (computed here independently from the documented
hash), unit |mu|, finite polarities for the rest of the run, on 1 and 2
ranks; a non-zero mu given by whatever created the cell is kept."""

import math

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

M64 = (1 << 64) - 1


def mix(z):
    """The 64-bit finaliser of fix polarity's counter-based random numbers
    (splitmix64)."""
    z = (z + 0x9E3779B97F4A7C15) & M64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M64
    return z ^ (z >> 31)


def fresh_angle(seed, tag):
    """The angle of a new cell: 2 pi u, u = uniform01(seed, ID, 0, stream 5)."""
    h = mix(mix(mix(mix(seed) ^ tag) ^ 0) ^ 5)
    return 2 * math.pi * (((h >> 11) + 0.5) / 9007199254740992.0)


SEED = 31
RUN = """
dimension 2
units lj
atom_style dipole
boundary p p p
read_data cfg.data
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
timestep 0.01
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix p all polarity 0.5 1.0 {terms} seed %d
dump d all custom 1 pol.dump id x y mux muy mu
dump_modify d sort id format float %%.17g
""" % SEED


class Deposit(LammpsTestCase):
    """fix deposit adds 4 cells, one every 5 steps."""

    def data(self):
        return self.run_lmp(lmptest.tissue(10, 5) +
                            "displace_atoms all random 0.05 0.05 0 4821 units box\n"
                            "write_data cfg.data\n").text("cfg.data")

    def deposit(self, nprocs, data):
        script = RUN.format(terms="neighbor 1.0 groove 0.5 20 noise 0.1 77") + """
fix dep all deposit 4 1 5 4821 region box near 0.4 attempt 200
run 30
"""
        script = script.replace("read_data cfg.data", "read_data cfg.data\n"
                                "region box block 0.1 10.6 0.1 9.2 -0.1 0.1 units box")
        return self.run_lmp(script, nprocs=nprocs, files={"cfg.data": data}).dump("pol.dump")

    def check(self, frames):
        n0 = len(frames[0]["id"])
        last = frames[-1]
        self.assertEqual(len(last["id"]), n0 + 4)
        for f in frames:
            mu = np.hypot(f["mux"], f["muy"])
            self.assertTrue(np.all(np.isfinite(f["mux"])) and np.all(np.isfinite(f["muy"])))
            np.testing.assert_allclose(mu, 1.0, rtol=0, atol=1e-14)
            np.testing.assert_allclose(f["mu"], 1.0, rtol=0, atol=1e-14)
        # each new cell's angle at the end of the step it appeared in
        seen = set(frames[0]["id"])
        new = 0
        for f in frames[1:]:
            for k, tag in enumerate(f["id"]):
                if tag in seen:
                    continue
                seen.add(tag)
                new += 1
                th = math.atan2(f["muy"][k], f["mux"][k])
                d = (th - fresh_angle(SEED, int(tag)) + math.pi) % (2 * math.pi) - math.pi
                self.assertLess(abs(d), 1e-13, "cell %d at step %d" % (tag, f["step"]))
        self.assertEqual(new, 4)

    def test_serial(self):
        self.check(self.deposit(1, self.data()))

    @nprocs(2)
    def test_two_ranks(self):
        data = self.data()
        one, two = self.deposit(1, data), self.deposit(2, data)
        self.check(two)
        for a, b in zip(one, two):
            np.testing.assert_array_equal(a["id"], b["id"])
            for col in ("x", "y", "mux", "muy"):
                np.testing.assert_allclose(a[col], b[col], rtol=0, atol=1e-8)


class CreateAtomsPreNo(LammpsTestCase):
    """create_atoms between runs, then 'run N pre no': the new cell with
    mu = 0 gets its angle on its first step; one given a dipole keeps it."""

    def test_angles(self):
        data = self.run_lmp(lmptest.tissue(10, 5) + "write_data cfg.data\n").text("cfg.data")
        # no torque terms: every angle stays what it was given
        script = RUN.format(terms="") + """
run 5
create_atoms 1 single 0.31 0.29 0 units box
create_atoms 1 single 5.13 4.07 0 units box
set atom 102 dipole 0.0 1.0 0.0
run 5 pre no
"""
        frames = self.run_lmp(script, files={"cfg.data": data}).dump("pol.dump")
        last = frames[-1]
        self.assertEqual(len(last["id"]), 102)
        self.assertTrue(np.all(np.isfinite(last["mux"])))
        np.testing.assert_allclose(np.hypot(last["mux"], last["muy"]), 1.0, atol=1e-14)
        th = math.atan2(last["muy"][100], last["mux"][100])
        self.assertAlmostEqual(th, fresh_angle(SEED, 101), delta=1e-13)
        self.assertEqual((last["mux"][101], last["muy"][101]), (0.0, 1.0))

    def test_added_with_neighbour_alignment_named(self):
        data = self.run_lmp(lmptest.tissue(10, 5) + "write_data cfg.data\n").text("cfg.data")
        script = RUN.format(terms="neighbor 1.0") + """
run 2
create_atoms 1 single 0.31 0.29 0 units box
run 2 pre no
"""
        run = self.run_lmp(script, files={"cfg.data": data}, ok=False)
        self.assertLammpsError(run, "atoms were added without a setup", "pre yes")


if __name__ == "__main__":
    lmptest.main()
