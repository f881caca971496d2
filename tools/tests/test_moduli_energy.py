# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools moduli prints the energy LAMMPS's pe has (the written energy, with the
constant KP P0^2 per cell of the quadratic form): a state of tessera-lmp, its pe with
'thermo_modify norm no', and the energy moduli prints for the dump of that state, with the
types' parameters and with each cell's own d_kp and d_perim0.  Needs tessera-lmp and
tessera-hessian (skipped otherwise)."""

import os
import re
import tempfile
import unittest

from helpers import find_lmp, printed, run_lmp
from test_moduli_cli import have_hessian
from test_particles import run

SCRIPT = """
dimension 2
units lj
atom_style atomic
boundary p p p
lattice hex 1.0
region box block 0 5 0 4 -0.5 0.5
create_box 1 box
create_atoms 1 box
mass 1 1.0
displace_atoms all random 0.1 0.1 0 4821 units box
{extra}
pair_style vertex/voronoi 3.0
pair_coeff * * quadratic 1.0 0.9 0.3 3.9
thermo_modify norm no
run 0
write_dump all custom state.dump id type x y {columns} modify sort id format float %.17g
print "PE $(pe:%.17g)"
"""

PER_CELL = """fix props all property/atom d_kp d_perim0
variable kp atom 0.2+0.01*id
variable p0 atom 3.7+0.02*id
set group all d_kp v_kp
set group all d_perim0 v_p0
"""


@unittest.skipIf(find_lmp() is None or not have_hessian(), "needs tessera-lmp and tessera-hessian (scripts/build)")
class WrittenEnergy(unittest.TestCase):

    def check(self, extra, columns):
        with tempfile.TemporaryDirectory() as d:
            out = run_lmp(SCRIPT.format(extra=extra, columns=columns), d)
            pe = printed(out, "PE")[0][0]
            code, text, err = run(["moduli", os.path.join(d, "state.dump"), "--quadratic", "1.0", "0.9", "0.3",
                                   "3.9", "--fnorm-max", "1e9"])
        self.assertEqual(code, 0, err)
        energy = float(re.search(r"energy ([-0-9.e+]+) energy", text).group(1))
        self.assertAlmostEqual(energy, pe, delta=1e-9 * abs(pe))
        n = int(re.search(r": (\d+) cells", text).group(1))
        per = float(re.search(r"\(([-0-9.e+]+) per cell\)", text).group(1))
        self.assertAlmostEqual(per, pe / n, delta=1e-9 * abs(pe / n))
        self.assertIn("constant sum KP P0^2", text)
        return text

    def test_types_parameters(self):
        self.check("", "")

    def test_each_cells_own_kp_and_p0(self):
        text = self.check(PER_CELL, "d_kp d_perim0")
        self.assertIn("each cell's own d_kp and d_perim0", text)


if __name__ == "__main__":
    unittest.main()
