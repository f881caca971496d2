#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""What fix polarity's doc says about reproducibility, exactly: an input built
with create_atoms gives the same run on 1 and 2 ranks without noise (initial
angles from positions) or after reset_atom_ids sort yes, to round-off; with
noise and create_atoms' own numbering it does not (the noise is keyed by atom
ID).  A split run and a restart agree with one run to round-off, and up to the
split bitwise (the to-round-off parts across ranks, splits and restarts are
also in test_fix_polarity.ActiveTissue)."""

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

SCRIPT = lmptest.tissue(10, 5) + """
{reset}
pair_style vertex/voronoi 3.5
pair_coeff * * 1.0 1.0 0.1 -0.56
timestep 0.01
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix p all polarity 0.05 1.0 neighbor 1.0 groove 0.5 20 {noise}
dump d all custom 10 pol.dump id x y xu yu mux muy
dump_modify d sort id format float %.17g
run 10
"""


def by_position(frame):
    """The frame's columns ordered by the initial lattice site (rounded
    position), so that runs with different atom IDs can be compared."""
    order = np.lexsort((np.round(frame["y"], 3), np.round(frame["x"], 3)))
    return {k: frame[k][order] for k in ("xu", "yu", "mux", "muy")}


class CreateAtomsRanks(LammpsTestCase):

    def pair(self, reset="", noise=""):
        script = SCRIPT.format(reset=reset, noise=noise)
        one = self.run_lmp(script).dump("pol.dump")
        two = self.run_lmp(script, nprocs=2).dump("pol.dump")
        return ([by_position(f) for f in one], [by_position(f) for f in two])

    @nprocs(2)
    def test_without_noise_same(self):
        one, two = self.pair()
        for a, b in zip(one, two):
            for col in a:
                np.testing.assert_allclose(a[col], b[col], rtol=0, atol=1e-12)

    @nprocs(2)
    def test_with_noise_differs(self):
        # the rotational noise of a cell depends on its ID, which create_atoms
        # assigns differently on 2 ranks
        one, two = self.pair(noise="noise 0.2 991")
        differ = np.abs(one[-1]["mux"] - two[-1]["mux"]) > 1e-6
        self.assertGreater(differ.sum(), 25)

    @nprocs(2)
    def test_with_noise_after_reset_atom_ids_same(self):
        one, two = self.pair(reset="reset_atom_ids sort yes", noise="noise 0.2 991")
        for a, b in zip(one, two):
            for col in a:
                np.testing.assert_allclose(a[col], b[col], rtol=0, atol=1e-12)


class SplitRun(LammpsTestCase):
    """run 10; run 10 against run 20: bitwise equal up to the split (unwrapped
    positions: the setup wraps atoms into the box), then
    equal to round-off (the second run's setup re-acquires the ghost atoms and
    triangulates from scratch, which changes the order of sums)."""

    def test_split(self):
        base = SCRIPT.format(reset="", noise="velocity 0.3 noise 0.2 991").replace(
            "dump d all custom 10", "dump d all custom 1").replace("run 10\n", "")
        one = self.run_lmp(base + "run 20\n").dump("pol.dump")
        two = self.run_lmp(base + "run 10\nrun 10\n").dump("pol.dump")
        two = {f["step"]: f for f in two}    # the repeated step 10 is the same state
        for a in one:
            b = two[a["step"]]
            for col in ("xu", "yu", "mux", "muy"):
                if a["step"] <= 10:
                    np.testing.assert_array_equal(a[col], b[col])
                else:
                    np.testing.assert_allclose(a[col], b[col], rtol=0, atol=1e-13)


if __name__ == "__main__":
    lmptest.main()
