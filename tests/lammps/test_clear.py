#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Tessera's styles survive the input command `clear`, which deletes and
recreates LAMMPS's style maps: a script that runs, clears, defines its system
again and runs again; write_restart, clear, read_restart, run (the same
numbers as one uninterrupted run); and every style of Tessera's table is
still listed after `clear`.  tessera-lmp re-registers them after LAMMPS's
own clear (lammps/main.cpp); on the plugin host LAMMPS restores its plugins."""

import re

import lmptest
from lmptest import LammpsTestCase, nprocs, tissue
from test_package import table_entries

# 24 cells, displaced from the hexagonal lattice so that forces and torques act
SYSTEM = tissue(6, 4) + """
displace_atoms all random 0.15 0.15 0.0 4711 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
"""
DYNAMICS = """
pair_coeff * * 1.0 1.0 0.1 -0.5
fix move all brownian 1.0 1 gamma_t 1.0 rng none
fix act all polarity 0.3 1.0 neighbor 1.0
compute cell all vertex/atom
compute tissue all vertex/tissue
compute edges all vertex/local
thermo_style custom step pe c_tissue[1]
thermo_modify format float %.15g
thermo 5
timestep 0.01
"""
FINAL = "write_dump all custom final.dump id xu yu mux muy modify sort id format float %.15g\n"


def thermo(text):
    """{step: (pe, mean shape index)} of every thermo line."""
    rows = {}
    for m in re.finditer(r"^\s*(\d+)\s+(\S+)\s+(\S+)\s*$", text, re.M):
        try:
            rows[int(m.group(1))] = (float(m.group(2)), float(m.group(3)))
        except ValueError:
            pass
    return rows


def listed_styles(text, title):
    """The style names `info styles ...` prints under 'title:' (e.g. 'Pair styles')."""
    block = text.split(title)[-1].split("Info-Info")[0]
    return set(block.split()[1:])    # (the first word is the colon, if any)


class Clear(LammpsTestCase):

    def check_two_parts(self, nprocs):
        part = SYSTEM + DYNAMICS + "run 10\n"
        run = self.run_lmp(part + "clear\n" + part, nprocs=nprocs)
        self.assertNotIn("ERROR", run.output)
        self.assertEqual(run.stdout.count("Loop time"), 2, run.stdout[-3000:])
        # each part prints steps 0, 5, 10: the second part starts afresh and
        # repeats the first one's numbers exactly
        rows = re.findall(r"(?m)^\s*(0|5|10)\s+(\S+)\s+(\S+)\s*$", run.stdout)
        self.assertEqual(len(rows), 6, run.stdout[-3000:])
        self.assertEqual(rows[:3], rows[3:])
        self.assertNotEqual(rows[0][1], rows[2][1])    # the cells did move

    def test_run_clear_define_run(self):
        self.check_two_parts(1)

    @nprocs(2)
    def test_run_clear_define_run_two_ranks(self):
        self.check_two_parts(2)

    def test_restart_after_clear(self):
        whole = self.run_lmp(SYSTEM + DYNAMICS + "run 10\n" + FINAL)
        parts = self.run_lmp(SYSTEM + DYNAMICS + "run 5\nwrite_restart half.restart\nclear\n"
                             "read_restart half.restart\n" + DYNAMICS + "run 5\n" + FINAL)
        self.assertIn("restoring pair style vertex/voronoi", parts.stdout)
        expected, got = thermo(whole.stdout), thermo(parts.stdout)
        self.assertIn(10, got, parts.stdout[-3000:])
        for k in range(2):
            self.assertAlmostEqual(got[10][k], expected[10][k], delta=1e-10 * abs(expected[10][k]))
        (a,), (b,) = whole.dump("final.dump"), parts.dump("final.dump")
        for column in ("xu", "yu", "mux", "muy"):
            self.assertLess(abs(a[column] - b[column]).max(), 1e-10, column)

    def test_every_style_after_clear(self):
        run = self.run_lmp("clear\ninfo styles pair\ninfo styles fix\ninfo styles compute\n"
                           "info styles command\n")
        listed = {"pair_style": listed_styles(run.stdout, "Pair styles"),
                  "fix": listed_styles(run.stdout, "Fix styles"),
                  "compute": listed_styles(run.stdout, "Compute styles"),
                  "command": listed_styles(run.stdout, "Command styles")}
        entries = table_entries()
        self.assertGreaterEqual(len(entries), 7)
        for command, name, _, _ in entries:
            command = {"fix_style": "fix", "compute_style": "compute",
                       "command_style": "command"}.get(command, command)
            self.assertIn(name, listed[command], "%s %s is gone after clear" % (command, name))


if __name__ == "__main__":
    lmptest.main()
