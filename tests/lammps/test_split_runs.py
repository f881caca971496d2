#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""What a split run reproduces (doc/model.md, "Split runs and restarts"):
write_restart at the end of step n and read_restart continue exactly as a
second run command of the same input with the same fixes defined anew
(round-off), also with divisions and fix deform; one uninterrupted run is
reproduced only when nothing changed the box or the positions after the
forces of step n: with fix deform the uninterrupted step n+1 moves the cells
with the forces of the box before deform's change at the end of step n, the
split run with those of the box after it."""

import numpy as np

import lmptest
from feature_models import model_script
from lmptest import LammpsTestCase

DYN = """fix p all polarity 0.3 1.0 neighbor 0.5
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix div all cell/divide rate 2.0 seed 4821 separation 0.1
timestep 0.005
thermo_style custom step atoms pe
"""
DEFORM = "fix def all deform 1 x vel 0.5 y vel -0.3 remap x units box\n"
END = "write_dump all custom end.dump id xu yu zu mux muy muz modify format float %.17g\n"
COLUMNS = ("xu", "yu", "zu", "mux", "muy", "muz")


class SplitRuns(LammpsTestCase):
    def ends(self, deform):
        """The end states of one run of 20 steps, of 10 + 10 steps in one
        input (fix deform defined anew for the second run, as a restarted
        input defines it) and of 10 steps, write_restart, read_restart, 10."""
        head = model_script("confluent") + DYN
        whole = self.run_lmp(head + deform + "run 20\n" + END)
        split = self.run_lmp(head + deform + "run 10\n" + (f"unfix def\n{deform}" if deform else "")
                             + "run 10\n" + END)
        first = self.run_lmp(head + deform + "run 10\nwrite_restart half.restart\n")
        second = self.run_lmp(f"dimension 2\nread_restart {first.path('half.restart')}\n" + DYN
                              + deform + "run 10\n" + END)
        out = []
        for run in (whole, split, second):
            f = run.dump("end.dump")[0]
            out.append(np.column_stack([f[c] for c in COLUMNS]))
        self.assertGreater(len(out[0]), 94)    # cells divided in the second half
        return out

    def test_restart_is_a_second_run_with_deform_and_divisions(self):
        whole, split, restarted = self.ends(DEFORM)
        np.testing.assert_allclose(restarted, split, rtol=0, atol=1e-10)
        # and not the uninterrupted run: the forces of step 11 differ
        self.assertGreater(np.abs(whole - split).max(), 1e-7)

    def test_restart_is_the_uninterrupted_run_without_deform(self):
        whole, split, restarted = self.ends("")
        np.testing.assert_allclose(split, whole, rtol=0, atol=1e-10)
        np.testing.assert_allclose(restarted, whole, rtol=0, atol=1e-10)


# fix cell/adapt sets d_area0 at the end of a step from the cells' areas and a
# species; a run's setup computes the forces of its first step again, which
# must use the d_area0 that step's own forces used.
ADAPT_SPECIES = """fix sp all property/atom d_area0 d_u
set group all d_area0 1.0
variable u0 atom 1+((id*37)%11)
set group all d_u v_u0
"""
ADAPT = """fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix s all cell/signal exchange d_u 1.0 degrade d_u 0.1
compute v all vertex/atom
compute pu all property/atom d_u
variable a0 atom 0.8+0.02*c_pu*c_v[1]
fix ad all cell/adapt {every} d_area0 v_a0
timestep 0.02
"""
ADAPT_END = ("write_dump all custom end.dump id xu yu d_area0 d_u modify format float %.17g\n")


class SplitRunsAdapt(LammpsTestCase):
    """run 10 = run n; run 10-n = run n, write_restart, read_restart, run
    10-n, with fix cell/adapt every N steps (split at a step where it set
    the parameters and at one where it did not), on 1 and 2 ranks, and with
    divisions (the daughters keep what the fix kept for their mother)."""

    DIVIDE = "fix div all cell/divide rate 3.0 seed 4821 separation 0.1\n"
    CASES = [(1, 5, 1, ""), (1, 5, 2, ""), (3, 5, 1, ""), (3, 6, 1, ""),
             (1, 5, 1, DIVIDE)]    # N, split step, ranks, divisions

    def ends(self, every, n, ranks, data, divide):
        files = {"cfg.data": data}
        head = model_script("confluent", data="cfg.data") + ADAPT_SPECIES
        law = ADAPT.format(every=every) + divide
        runs = [self.run_lmp(head + law + "run 10\n" + ADAPT_END, nprocs=ranks, files=files),
                self.run_lmp(head + law + f"run {n}\nrun {10 - n}\n" + ADAPT_END, nprocs=ranks,
                             files=files)]
        first = self.run_lmp(head + law + f"run {n}\nwrite_restart half.restart\n",
                             nprocs=ranks, files=files)
        runs.append(self.run_lmp(f"dimension 2\nread_restart {first.path('half.restart')}\n"
                                 "fix sp all property/atom d_area0 d_u\n" + law
                                 + f"run {10 - n}\n" + ADAPT_END, nprocs=ranks))
        self.assertNotIn("unused", runs[2].output)    # the fixes took their restart state
        out = []
        for run in runs:
            f = run.dump("end.dump")[0]
            out.append(np.column_stack([f[c] for c in ("xu", "yu", "d_area0", "d_u")]))
        return out

    def check(self, every, n, ranks, divide):
        data = self.run_lmp(model_script("confluent") + "write_data cfg.data\n").text("cfg.data")
        whole, split, restarted = self.ends(every, n, ranks, data, divide)
        if divide:
            self.assertGreater(len(whole), 42 + 5)
        self.assertGreater(np.ptp(whole[:, 2]), 0.01)    # d_area0 differs among cells
        np.testing.assert_allclose(split, whole, rtol=0, atol=1e-12)
        np.testing.assert_allclose(restarted, whole, rtol=0, atol=1e-12)


def _adapt_case(every, n, ranks, divide):
    def test(self):
        self.check(every, n, ranks, divide)
    test.nprocs = ranks
    test.__doc__ = f"fix cell/adapt every {every}, split at {n}, {ranks} rank(s)" + (
        ", divisions" if divide else "")
    return test


for _every, _n, _ranks, _divide in SplitRunsAdapt.CASES:
    setattr(SplitRunsAdapt, f"test_every_{_every}_split_{_n}_ranks_{_ranks}"
            + ("_divisions" if _divide else ""), _adapt_case(_every, _n, _ranks, _divide))


if __name__ == "__main__":
    lmptest.main()
