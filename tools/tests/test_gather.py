# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera_tools.gather.gather_local in a Python-driven LAMMPS under '-screen none' without
any dump of the compute: it used to end the process with status 1 and no message (LAMMPS's
write_dump refuses a compute that nothing invoked at the last step); now it invokes the
compute itself.  The rows equal those a dump local writes at the same step, each cell's row
lengths add up to its perimeter (compute vertex/atom), and compute vertex/loops' holes and
the cells tile the box.  A missing compute and a wrong column count are errors that say so.
Needs python3-lammps and the build's libtessera_lammps.so (skipped otherwise)."""

import json
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from helpers import TOOLS

REPO = os.path.dirname(TOOLS)
BUILD = os.environ.get("TESSERA_BUILD") or os.path.join(REPO, "build")

SCRIPT = r"""
import json, sys
import numpy as np
from lammps import lammps
from tessera_tools import host
from tessera_tools.gather import gather_local, gather_per_atom

lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
host.register(lmp)
lmp.commands_string('''
dimension 2
units lj
atom_style atomic
boundary p p p
lattice hex 1.0
region box block 0 6 0 4 -0.5 0.5
create_box 1 box
create_atoms 1 box
mass 1 1.0
displace_atoms all random 0.1 0.1 0 4821 units box
pair_style vertex/voronoi 2.0 radius 0.56
pair_coeff * * quadratic 1.0 1.0 0.1 3.8
fix move all brownian 1.0 1 gamma_t 1.0 rng none
timestep 0.01
compute loc all vertex/local
compute loops all vertex/loops
compute cell all vertex/atom
run 7
''')
out = {}
out["rows"] = gather_local(lmp, "loc", 7).tolist()
out["loops"] = gather_local(lmp, "loops", 7).tolist()
ids, cell = gather_per_atom(lmp, "c_cell", 9)
out["ids"], out["area"], out["perimeter"] = ids.tolist(), cell[:, 0].tolist(), cell[:, 1].tolist()
lo, hi = lmp.extract_global("boxlo"), lmp.extract_global("boxhi")
out["box"] = (hi[0] - lo[0]) * (hi[1] - lo[1])
for bad in (("nothere", 7), ("loc", 9)):
    try:
        gather_local(lmp, *bad)
        out[bad[0]] = "no error"
    except ValueError as err:
        out[bad[0] + str(bad[1])] = str(err)
lmp.command("dump d all local 1 rows.dump c_loc[*]")
lmp.command("dump_modify d format float %.17g")
lmp.command("run 0")
json.dump(out, open("out.json", "w"))
"""


def have_lammps():
    return subprocess.run([sys.executable, "-c", "import lammps"], capture_output=True).returncode == 0


@unittest.skipIf(not have_lammps() or not os.path.exists(os.path.join(BUILD, "lammps", "libtessera_lammps.so")),
                 "needs python3-lammps and the build's libtessera_lammps.so (scripts/build)")
class GatherWithoutDump(unittest.TestCase):

    def test_rows_without_a_dump_under_screen_none(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "run.py"), "w") as f:
                f.write(SCRIPT)
            env = dict(os.environ, PYTHONPATH=TOOLS, TESSERA_BUILD=BUILD)
            proc = subprocess.run([sys.executable, "run.py"], cwd=d, env=env, capture_output=True, text=True,
                                  timeout=120)
            self.assertEqual(proc.returncode, 0, proc.stdout + proc.stderr)
            with open(os.path.join(d, "out.json")) as f:
                out = json.load(f)
            with open(os.path.join(d, "rows.dump")) as f:
                lines = f.read().split("\n")
        k = lines.index("ITEM: NUMBER OF ENTRIES")
        n = int(lines[k + 1])
        start = [i for i, line in enumerate(lines) if line.startswith("ITEM: ENTRIES")][0] + 1
        dumped = np.array([[float(v) for v in line.split()] for line in lines[start:start + n]])
        dumped = dumped[np.lexsort(dumped.T[::-1])]
        rows = np.array(out["rows"])
        np.testing.assert_array_equal(rows, dumped)
        # each cell's rows (junctions and free arcs) add up to its perimeter
        per = {i: 0.0 for i in out["ids"]}
        for r in rows:
            per[int(r[0])] += r[6]
        np.testing.assert_allclose([per[i] for i in out["ids"]], out["perimeter"], rtol=1e-12)
        # compute vertex/loops without a dump: the holes and the cells tile the box
        loops = np.array(out["loops"])
        holes = loops[loops[:, 6] == 0, 1].sum()
        box = out["box"]
        self.assertGreater(holes, 0.0)
        self.assertAlmostEqual(holes + sum(out["area"]), box, delta=1e-9 * box)
        self.assertIn("compute 'nothere'", out["nothere7"])
        self.assertIn("Define a local compute", out["nothere7"])
        self.assertIn("has 7 local column(s), not ncols=9", out["loc9"])


if __name__ == "__main__":
    unittest.main()
