#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Per-cell preferred areas (fix property/atom d_area0), fix cell/divide and
fix cell/death: forces against central finite differences of pe with
per-cell A0 (before and after events), the same N(t) and events on 1, 2 and
4 ranks from one data file, growth at rate R against exp(R t) within its
statistical error, confluence (areas sum to the box), division axes against
the cell's shape, restart continuation, finite polarities of new cells, and
the errors."""

import math

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

PAIR = """
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.12 -0.45
thermo_modify norm no
"""

# Per-cell preferred areas, different for every cell and independent of the
# number of ranks (a function of the atom ID).
AREA0 = """
fix a0 all property/atom d_area0
variable a0 atom 0.7+0.05*(id%13)
set group all d_area0 v_a0
"""


def tissue(nx=6, ny=4, disp=0.15, seed=4821):
    """A displaced hexagonal lattice of cells of area 1 (2 nx ny cells)."""
    return lmptest.tissue(nx, ny, "hex") + f"""
displace_atoms all random {disp} {disp} 0 {seed} units box
"""


def data_header():
    return """
dimension 2
units lj
atom_style dipole
boundary p p p
read_data cfg.data
"""


def thermo_table(run):
    """Rows of the thermo output of every run in the log, as dicts."""
    rows = []
    header = None
    for line in run.stdout.splitlines():
        words = line.split()
        if words and words[0] == "Step":
            header = words
            continue
        if header and words and len(words) == len(header):
            try:
                values = [float(w) for w in words]
            except ValueError:
                header = None
                continue
            rows.append(dict(zip(header, values)))
        elif header and line.startswith("Loop time"):
            header = None
    return rows


def printed(run, key):
    return [float(line.split()[1]) for line in run.stdout.splitlines()
            if line.startswith(key + " ")]


def fd_script(atoms, h=1e-6):
    """Central differences of pe for displacements of the given atoms (run 0
    before each pe); 'E' lines in the order +x, -x, +y, -y per atom."""
    script = ""
    for a in atoms:
        for dim, move in (("x", f"{h} 0 0"), ("y", f"0 {h} 0")):
            back = " ".join("-%r" % (2 * float(w)) if float(w) else "0" for w in move.split())
            script += f"""
group g{a}{dim} id {a}
displace_atoms g{a}{dim} move {move} units box
run 0
print "E $(pe:%.17g)"
displace_atoms g{a}{dim} move {back} units box
run 0
print "E $(pe:%.17g)"
displace_atoms g{a}{dim} move {move} units box
"""
    return script


class PerCellArea0(LammpsTestCase):
    """pair vertex/voronoi uses d_area0 when it exists; forces are -dE/dx."""

    def check_fd(self, run, atoms, h=1e-6):
        frame = run.dump("cfg.dump")[0]
        e = printed(run, "E")
        self.assertEqual(len(e), 4 * len(atoms))
        k = 0
        for a in atoms:
            row = np.where(frame["id"] == a)[0][0]
            for col in ("fx", "fy"):
                fd = -(e[k] - e[k + 1]) / (2 * h)
                k += 2
                self.assertAlmostEqual(frame[col][row], fd, delta=1e-6 * max(1.0, abs(fd)),
                                       msg=f"atom {a} {col}")

    def test_finite_differences(self):
        atoms = [1, 5, 12, 19, 30]
        run = self.run_lmp(tissue() + PAIR + AREA0 + """
dump d all custom 1 cfg.dump id x y fx fy d_area0
dump_modify d sort id format float %.17g
run 0
undump d
""" + fd_script(atoms))
        self.check_fd(run, atoms)
        frame = run.dump("cfg.dump")[0]
        np.testing.assert_allclose(frame["d_area0"], 0.7 + 0.05 * (frame["id"] % 13))

    def test_energy_uses_per_cell_area0(self):
        """E = sum K/2 (A_i - A0_i)^2 + ...: the change of pe when d_area0
        changes from the type's A0 is the analytic sum over cells, with
        areas from compute vertex/atom."""
        run = self.run_lmp(tissue() + PAIR + """
compute c all vertex/atom
dump d all custom 1 a.dump id c_c[1]
dump_modify d sort id format float %.17g
run 0
print "E $(pe:%.17g)"
undump d
""" + AREA0 + """
run 0
print "E $(pe:%.17g)"
""")
        e0, e1 = printed(run, "E")
        frame = run.dump("a.dump")[0]
        area = frame["c_c[1]"]
        a0 = 0.7 + 0.05 * (frame["id"] % 13)
        expected = 0.5 * np.sum((area - a0) ** 2 - (area - 1.0) ** 2)
        self.assertGreater(abs(expected), 0.1)
        self.assertAlmostEqual(e1 - e0, expected, delta=1e-10)

    def test_nonpositive_area0_is_an_error(self):
        run = self.run_lmp(tissue() + PAIR + """
fix a0 all property/atom d_area0
run 0
""", ok=False)
        self.assertLammpsError(run, "d_area0", "must be > 0")


lmptest.main()
