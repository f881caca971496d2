#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""tessera_tools.gather in a Python-driven LAMMPS after divisions and deaths (atom IDs
with gaps, where LAMMPS's gather_atoms needs 1..N): on 1 and 2 ranks every rank gets
every cell's per-atom columns (compute vertex/atom, positions) and every junction row of
compute vertex/local, and they equal what LAMMPS's own dumps of the same step hold
(dump custom sorted by ID, dump local), at full precision; 1 and 2 ranks agree."""

import json

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

SCRIPT = r"""
import json
import numpy as np
from lammps import lammps
from tessera_tools import host
from tessera_tools.gather import gather_local, gather_per_atom

lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
host.register(lmp)
lmp.commands_string('''
dimension 2
units lj
atom_style dipole
boundary p p p
lattice hex 1.0
region box block 0 6 0 4 -0.5 0.5
create_box 1 box
create_atoms 1 box
mass 1 1.0
displace_atoms all random 0.15 0.15 0 4821 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.12 -0.45
timestep 0.02
fix move all brownian 1.0 1 gamma_t 1.0 rng none
fix div all cell/divide rate 0.5 seed 7 max 70
fix die all cell/death rate 0.3 seed 9 min 40
compute cell all vertex/atom
compute loc all vertex/local
run 60
dump a all custom 1 atoms.dump id x y c_cell[*]
dump_modify a sort id format float %.17g
dump l all local 1 local.dump c_loc[*]
dump_modify l format float %.17g
run 0
''')
me = lmp.extract_setting("world_rank")
ids, cells = gather_per_atom(lmp, "c_cell", 9)
_, x = gather_per_atom(lmp, "x", 3)
rows = gather_local(lmp, "loc", 7)
mine = lmp.extract_setting("nlocal")
out = dict(rank=me, ids=ids.tolist(), cells=cells.tolist(), x=x[:, :2].tolist(), rows=rows.tolist(),
           nlocal=mine)
with open(f"result{me}.json", "w") as f:    # one file per rank: their stdout lines may interleave
    json.dump(out, f)
lmp.close()
"""


def read_local(path):
    with open(path) as f:
        lines = f.read().split("\n")
    for k, line in enumerate(lines):
        if line.startswith("ITEM: NUMBER OF ENTRIES"):
            n = int(lines[k + 1])
        if line.startswith("ITEM: ENTRIES"):
            a = np.array([[float(v) for v in r.split()] for r in lines[k + 1:k + 1 + n]])
            return a[np.lexsort(a.T[::-1])]
    raise AssertionError("no entries in " + path)


class Gather(LammpsTestCase):

    def check(self, n):
        run = self.run_python(SCRIPT, nprocs=n)
        res = [json.loads(run.text(f"result{k}.json")) for k in range(n)]
        if n > 1:
            self.assertTrue(all(r["nlocal"] < len(r["ids"]) for r in res))    # each rank owns a part
        frames = run.dump("atoms.dump")
        last = frames[-1]
        local = read_local(run.path("local.dump"))
        ids = last["id"]
        self.assertFalse(np.array_equal(ids, np.arange(1, len(ids) + 1)), "IDs without gaps: no test")
        for r in res:
            np.testing.assert_array_equal(r["ids"], ids)
            cells = np.array(r["cells"])
            for c in range(9):
                np.testing.assert_array_equal(cells[:, c], last[f"c_cell[{c + 1}]"], err_msg=f"column {c + 1}")
            np.testing.assert_array_equal(np.array(r["x"])[:, 0], last["x"])
            np.testing.assert_array_equal(np.array(r["x"])[:, 1], last["y"])
            np.testing.assert_array_equal(np.array(r["rows"]), local)
        return res[0]

    @nprocs(2)
    def test_one_and_two_ranks(self):
        one = self.check(1)
        two = self.check(2)
        self.assertEqual(one["ids"], two["ids"])
        np.testing.assert_allclose(np.array(two["cells"]), np.array(one["cells"]), rtol=0, atol=1e-9)
        np.testing.assert_allclose(np.array(two["rows"]), np.array(one["rows"]), rtol=0, atol=1e-9)


if __name__ == "__main__":
    lmptest.main()
