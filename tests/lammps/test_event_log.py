#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The event logs of fix cell/divide and fix cell/death (keyword file): the same
events on 1, 2 and 4 ranks; every event against dumps of every step (new and
vanished atom IDs, the daughters' mother column, the logged position as the
midpoint of the daughters); tessera-tools lineage's living leaves are the
cells of the last frame; a run continued from a restart file (written while
the first run went on) ends with the log of the uninterrupted run; two fixes
on one file are an error."""

import os
import sys

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from tessera_tools.lineage import Lineage, read_events  # noqa: E402

SEP = 0.05

HEAD = """
dimension 2
units lj
atom_style dipole
boundary p p p
"""

START = HEAD + """
read_data cfg.data
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.12 -0.45
timestep 0.02
"""

FIXES = f"""
fix move all brownian 1.0 1 gamma_t 1.0 rng none
fix act all polarity 0.3 1.0 neighbor 0.5 noise 0.5 4821
fix div all cell/divide rate 0.5 seed 7 separation {SEP} max 80 file {{div}}
fix die all cell/death rate 0.3 seed 9 min 40 file {{die}}
thermo_style custom step atoms f_div[2] f_die[2]
thermo 10
"""

DUMP = """
dump d all custom 1 every.dump id x y f_div[5]
dump_modify d sort id format float %.17g
"""


def data_file(test):
    return test.run_lmp(lmptest.tissue(6, 4, "hex") + """
displace_atoms all random 0.15 0.15 0 4821 units box
write_data cfg.data
""").text("cfg.data")


def rows(text):
    """The event lines of a log as (step, time, event, id, d1, d2) tuples and an array of x y z."""
    ev, pos = [], []
    for line in text.splitlines():
        if line.startswith("#") or not line.strip():
            continue
        w = line.split()
        ev.append((int(w[0]), w[1], w[2], int(w[3]), int(w[4]), int(w[5])))
        pos.append([float(v) for v in w[6:9]])
    return ev, np.array(pos).reshape(-1, 3)


def min_image(d, box):
    length = box[:2, 1] - box[:2, 0]
    return d - length * np.round(d / length)


class EventLog(LammpsTestCase):

    def run_on(self, n, data, steps=150, dump=True):
        return self.run_lmp(START + FIXES.format(div="div.log", die="die.log") + (DUMP if dump else "")
                            + f"run {steps}\n", nprocs=n, files={"cfg.data": data})

    @nprocs(4)
    def test_ranks_dumps_and_tree(self):
        data = data_file(self)
        runs = [self.run_on(n, data, dump=(n == 1)) for n in (1, 2, 4)]
        logs = {name: [rows(r.text(name)) for r in runs] for name in ("div.log", "die.log")}
        for name, per_rank in logs.items():
            ref_ev, ref_pos = per_rank[0]
            self.assertGreater(len(ref_ev), 5, name)
            for ev, pos in per_rank[1:]:
                self.assertEqual(ev, ref_ev, name)
                np.testing.assert_allclose(pos, ref_pos, rtol=0, atol=1e-6, err_msg=name)
        self.assertEqual(runs[0].text("div.log").splitlines()[:2],
                         ["# Tessera event log of fix div cell/divide (units lj)",
                          "# step time event id daughter1 daughter2 x y z"])

        # every event against the dumps of every step
        frames = runs[0].dump("every.dump")
        self.assertEqual([f["step"] for f in frames], list(range(151)))
        div, div_pos = logs["div.log"][0]
        die, _ = logs["die.log"][0]
        by_step = {}
        for k, e in enumerate(div):
            by_step.setdefault(e[0], []).append(("divide", e, div_pos[k]))
        for e in die:
            by_step.setdefault(e[0], []).append(("death", e, None))
        for before, after in zip(frames[:-1], frames[1:]):
            step = after["step"]
            events = by_step.get(step, [])
            for kind, e, _ in events:
                self.assertAlmostEqual(float(e[1]), 0.02 * step, delta=1e-9)    # thermo's time
            born = set(after["id"]) - set(before["id"])
            gone = set(before["id"]) - set(after["id"])
            self.assertEqual(born, {e[5] for kind, e, _ in events if kind == "divide"}, f"step {step}")
            # a cell that divided and died at one step leaves its new sister only
            self.assertEqual(gone, {e[3] for kind, e, _ in events if kind == "death"}, f"step {step}")
            where = {int(i): k for k, i in enumerate(after["id"])}
            xa = np.column_stack([after["x"], after["y"]])
            for kind, e, pos in events:
                if kind != "divide":
                    continue
                self.assertEqual(e[3], e[4])
                new = where[e[5]]
                self.assertEqual(int(after["f_div[5]"][new]), e[3])
                if e[4] in where:    # (unless the sister died at once)
                    old = where[e[4]]
                    d = min_image(xa[new] - xa[old], after["box"])
                    self.assertAlmostEqual(np.hypot(*d), SEP, delta=1e-9)
                    mid = xa[old] + 0.5 * d
                    np.testing.assert_allclose(min_image(mid - pos[:2], after["box"]), 0.0, atol=1e-8)

        # the tree: its living leaves are the cells of the last frame
        tree = Lineage(read_events([runs[0].path("div.log"), runs[0].path("die.log")]),
                       start_ids=frames[0]["id"])
        self.assertEqual(sorted(tree.alive_by_id()), sorted(int(i) for i in frames[-1]["id"]))
        self.assertEqual(len(tree.leaves()), len(frames[-1]["id"]))
        self.assertGreater(max(c.generation for c in tree.cells.values()), 1)

    def test_restart_continues_the_log(self):
        data = data_file(self)
        whole = self.run_on(1, data, steps=140, dump=False)
        # the first run goes on past its restart file, as a crashed or longer run would
        first = self.run_lmp(START + FIXES.format(div="div.log", die="die.log")
                             + "run 100\nwrite_restart r.restart\nrun 30\n", files={"cfg.data": data})
        self.assertGreater(max(e[0] for e in rows(first.text("div.log"))[0]), 100)
        second = self.run_lmp(f"read_restart {first.path('r.restart')}\n"
                              + FIXES.format(div=first.path("div.log"), die=first.path("die.log")) + "run 40\n")
        self.assertTrue(second.returncode == 0)
        for name in ("div.log", "die.log"):
            ev_w, pos_w = rows(whole.text(name))
            ev_s, pos_s = rows(first.text(name))
            self.assertEqual(ev_s, ev_w, name)
            np.testing.assert_allclose(pos_s, pos_w, rtol=0, atol=1e-6, err_msg=name)
            self.assertEqual(first.text(name).count("# step time"), 1)
        self.assertGreater(sum(1 for e in rows(whole.text("div.log"))[0] if e[0] > 100), 3)

    def test_two_fixes_one_file(self):
        data = data_file(self)
        run = self.run_lmp(START + """
fix div all cell/divide rate 0.5 seed 7 file ev.log
fix die all cell/death rate 0.3 seed 9 file ev.log
run 1
""", files={"cfg.data": data}, ok=False)
        self.assertLammpsError(run, "fix die cell/death: file ev.log is already the event log of fix div")


lmptest.main()
