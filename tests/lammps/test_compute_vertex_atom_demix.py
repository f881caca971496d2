#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""compute vertex/tissue's heterotypic junction values (values 6-8)
through tessera-lmp: hexagonal tissues in stripes of w rows of each type,
where a cell's three junctions (counted once) are one in its row and two to
the row above, so the heterotypic fraction is 2/(3w) and the lengths follow
from the regular hexagon (confluent) or the chord of two discs (finite
cells, whose free arcs are no junctions), on 1 and 2 ranks; and disordered
2d and 3d tissues against the junction lengths summed here from a dump local
of compute vertex/local with the types of a dump custom."""

import math

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

A = math.sqrt(2.0 / math.sqrt(3.0))    # hexagonal spacing, unit area per cell
H = A * math.sqrt(3.0) / 2.0
EDGE = math.sqrt(2.0 / (3.0 * math.sqrt(3.0)))    # side of a regular hexagon of area 1


def stripes(nx, ny, w):
    xy, types = [], []
    for j in range(ny):
        for i in range(nx):
            xy.append(((i + 0.5 * (j % 2)) * A + 0.1, j * H + 0.2))
            types.append(1 + (j // w) % 2)
    lines = ["stripes", "", "%d atoms" % len(xy), "2 atom types", "",
             "0.0 %r xlo xhi" % (nx * A), "0.0 %r ylo yhi" % (ny * H), "-0.5 0.5 zlo zhi", "",
             "Masses", "", "1 1.0", "2 1.0", "", "Atoms # atomic", ""]
    for k, ((x, y), t) in enumerate(zip(xy, types)):
        lines.append("%d %d %r %r 0.0" % (k + 1, t, x, y))
    return "\n".join(lines) + "\n"


def script(pair, extra=""):
    return f"""
dimension 2
units lj
atom_style atomic
boundary p p p
{extra}
read_data cells.data
{pair}
compute va all vertex/tissue
thermo_style custom step pe c_va[6] c_va[7] c_va[8]
run 0
print "D $(c_va[6]:%.17g) $(c_va[7]:%.17g) $(c_va[8]:%.17g)"
"""


CONFLUENT = "pair_style vertex/voronoi 3.0\npair_coeff * * 1.0 1.0 0.1 -0.5"
R_FINITE = 0.58
FINITE = f"pair_style vertex/voronoi {2.2 * R_FINITE} radius {R_FINITE}\n" \
         "pair_coeff * * quadratic 1.0 1.0 0.1 3.9 free 0.2"


def printed(run, key):
    return [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
            if line.startswith(key + " ")]


class Demixing(LammpsTestCase):

    def check_stripes(self, pair, junction, nprocs):
        nx, ny = 8, 12
        n = nx * ny
        for w in (1, 2, 3):
            extra = "processors 2 1 1" if nprocs == 2 else ""
            run = self.run_lmp(script(pair, extra), nprocs=nprocs, files={"cells.data": stripes(nx, ny, w)})
            frac, het, total = printed(run, "D")[0]
            self.assertAlmostEqual(frac, 2.0 / (3.0 * w), delta=1e-12, msg=f"w = {w}")
            self.assertAlmostEqual(het, n * 2 * junction / w, delta=1e-10, msg=f"w = {w}")
            self.assertAlmostEqual(total, 3 * n * junction, delta=1e-10, msg=f"w = {w}")

    def test_confluent_stripes(self):
        self.check_stripes(CONFLUENT, EDGE, 1)

    def test_finite_stripes(self):
        # r below the hexagon's corner distance: junctions are chords of the discs
        self.assertLess(R_FINITE, EDGE)
        self.check_stripes(FINITE, 2 * math.sqrt(R_FINITE ** 2 - A * A / 4), 1)

    @nprocs(2)
    def test_stripes_on_two_ranks(self):
        self.check_stripes(CONFLUENT, EDGE, 2)
        self.check_stripes(FINITE, 2 * math.sqrt(R_FINITE ** 2 - A * A / 4), 2)

    def disordered(self, three, nprocs):
        if three:
            head = """units lj
atom_style atomic
boundary p p p
lattice bcc 1.0
region box block 0 3 0 3 0 3
create_box 2 box
create_atoms 1 box
displace_atoms all random 0.05 0.05 0.05 4821 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.05 5.6
"""
            cols = " ".join("c_l[%d]" % k for k in range(1, 10))
        else:
            head = """dimension 2
units lj
atom_style atomic
boundary p p p
lattice hex 1.0
region box block 0 7 0 6 -0.5 0.5
create_box 2 box
create_atoms 1 box
displace_atoms all random 0.1 0.1 0 4821 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
"""
            cols = " ".join("c_l[%d]" % k for k in range(1, 8))
        script_ = head + f"""mass * 1.0
set type 1 type/fraction 2 0.4 7731
compute va all vertex/tissue
compute l all vertex/local
dump f all local 1 faces.dump {cols}
dump_modify f format float %.17g
dump a all custom 1 atoms.dump id type
thermo_style custom step pe c_va[6]
run 0
print "D $(c_va[6]:%.17g) $(c_va[7]:%.17g) $(c_va[8]:%.17g)"
"""
        run = self.run_lmp(script_, nprocs=nprocs)
        frac, het, total = printed(run, "D")[0]
        atoms = run.dump("atoms.dump")[0]
        kind = dict(zip(atoms["id"].astype(int).tolist(), atoms["type"].astype(int).tolist()))
        lines = run.text("faces.dump").split("\n")
        start = next(k for k, line in enumerate(lines) if line.startswith("ITEM: ENTRIES")) + 1
        rows = np.array([[float(w) for w in line.split()] for line in lines[start:] if line.strip()])
        size = 8 if three else 6
        # 3d: one row per edge of a face polygon, the face's area on each
        if three:
            seen = {}
            for r in rows:
                seen[(int(r[0]), int(r[1]), round(r[size], 12))] = r[size]
            pieces = [(c, j, s) for (c, j, _), s in seen.items()]
        else:
            pieces = [(int(r[0]), int(r[1]), r[size]) for r in rows]
        want_total = 0.5 * sum(s for _, _, s in pieces)
        want_het = 0.5 * sum(s for c, j, s in pieces if kind[c] != kind[j])
        self.assertGreater(want_het, 0.1 * want_total)
        self.assertAlmostEqual(total, want_total, delta=1e-9 * want_total)
        self.assertAlmostEqual(het, want_het, delta=1e-9 * want_total)
        self.assertAlmostEqual(frac, want_het / want_total, delta=1e-9)
        return frac, het, total

    def test_disordered_2d_and_3d_against_the_local_rows(self):
        for three in (False, True):
            with self.subTest(three=three):
                self.disordered(three, 1)

    @nprocs(2)
    def test_disordered_on_two_ranks(self):
        for three in (False, True):
            with self.subTest(three=three):
                one = self.disordered(three, 1)
                two = self.disordered(three, 2)
                np.testing.assert_allclose(two, one, rtol=1e-12)


if __name__ == "__main__":
    lmptest.main()
