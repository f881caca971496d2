#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""compute vertex/atom run through tessera-lmp, against analytic values (hexagonal
and square lattices, uniform velocities) and against an independent periodic
Voronoi tessellation computed here with scipy (Qhull) for disordered
configurations: per-atom columns (also read by atom-style variables), ghost
velocities; compute vertex/tissue's multifold vertices counted once over ranks
and periodic images and neighbour exchanges with memory that migrates between
ranks (also while cells divide and die); 1 rank == 2 ranks == 4 ranks, and
the errors (including scripts written for the former global vector)."""

import math

import numpy as np
from scipy.spatial import Voronoi

import lmptest
from feature_models import local_rows
from feature_outputs import exchanges, neighbour_pairs
from lmptest import LammpsTestCase, nprocs

# pair_coeff * * K A0 Gamma Lambda used throughout (edge tension convention).
K, A0, GAMMA, LAMBDA = 1.0, 1.0, 0.1, -0.5
HEX_PERIMETER = math.sqrt(8.0 * math.sqrt(3.0))    # regular hexagon of area 1
COLUMNS = ["area", "perimeter", "q", "z", "energy", "coordination", "orientation"]


def cell_energy(area, perimeter):
    return K / 2 * (area - A0) ** 2 + GAMMA / 2 * perimeter ** 2 + LAMBDA / 2 * perimeter


def tissue(lattice="hex", ny=5, extra=""):
    """A 2D periodic tissue of cells on a lattice of area 1 per cell (100 cells
    for hex with ny = 5; 10 x ny for sq), with compute va all vertex/atom."""
    return f"""
units lj
dimension 2
atom_style dipole
boundary p p p
lattice {lattice} 1.0
region box block 0 10 0 {ny} -0.5 0.5
create_box 1 box
create_atoms 1 box
mass 1 1.0
pair_style vertex/voronoi 3.0
pair_coeff * * {K} {A0} {GAMMA} {LAMBDA}
{extra}
compute va all vertex/atom
compute vt all vertex/tissue
thermo_style custom step pe c_vt[1] c_vt[2] c_vt[3]
thermo_modify format float %.15g
"""


def dump_columns(name="cells.dump", every=1, group="all"):
    cols = " ".join("c_va[%d]" % (k + 1) for k in range(len(COLUMNS)))
    return (f"dump d {group} custom {every} {name} id x y vx vy {cols}\n"
            f"dump_modify d sort id format float %.17g\n")


def columns(frame):
    """The 7 per-atom columns of a dump frame as a dict by name."""
    return {name: frame["c_va[%d]" % (k + 1)] for k, name in enumerate(COLUMNS)}


def by_position(frame):
    """The columns of a dump frame with rows ordered by position instead of id."""
    order = np.lexsort((frame["y"], frame["x"]))
    return {k: v[order] for k, v in frame.items() if isinstance(v, np.ndarray) and v.ndim == 1}


def thermo_rows(text):
    """Thermo rows of every run in a LAMMPS output, as dicts keyed by column."""
    rows, header = [], None
    for line in text.splitlines():
        words = line.split()
        if words and words[0] == "Step":
            header = words
            continue
        if header is None:
            continue
        try:
            values = [float(w) for w in words]
        except ValueError:
            header = None
            continue
        if len(values) == len(header):
            rows.append(dict(zip(header, values)))
        else:
            header = None
    return rows


class PeriodicVoronoi:
    """Reference tessellation of points in a periodic rectangle, from Qhull on the
    points and their 8 periodic images (fine for boxes several cells wide)."""

    def __init__(self, x, y, box):
        lo, hi = box[:2, 0], box[:2, 1]
        length = hi - lo
        pts = np.column_stack([x, y]) - lo
        pts -= np.floor(pts / length) * length
        n = len(pts)
        shifts = [(0, 0)] + [(i, j) for i in (-1, 0, 1) for j in (-1, 0, 1) if (i, j) != (0, 0)]
        allpts = np.vstack([pts + np.array(s) * length for s in shifts])
        origin = np.tile(np.arange(n), len(shifts))
        vor = Voronoi(allpts)
        self.n = n
        self.area = np.zeros(n)
        self.perimeter = np.zeros(n)
        for c in range(n):
            poly = vor.vertices[vor.regions[vor.point_region[c]]]
            centre = poly.mean(axis=0)
            poly = poly[np.argsort(np.arctan2(poly[:, 1] - centre[1], poly[:, 0] - centre[0]))]
            nxt = np.roll(poly, -1, axis=0)
            self.area[c] = 0.5 * np.sum(poly[:, 0] * nxt[:, 1] - nxt[:, 0] * poly[:, 1])
            self.perimeter[c] = np.sum(np.hypot(*(nxt - poly).T))
        self.neighbors = [set() for _ in range(n)]
        for (p, q), ridge in zip(vor.ridge_points, vor.ridge_vertices):
            if p >= n and q >= n:
                continue
            length = np.hypot(*(vor.vertices[ridge[0]] - vor.vertices[ridge[1]]))
            if length > 1e-9:
                for a, b in ((p, q), (q, p)):
                    if a < n:
                        self.neighbors[a].add(origin[b])

    def pairs(self):
        return {(min(a, b), max(a, b)) for a in range(self.n) for b in self.neighbors[a]}


def id_pairs(frame):
    """Pairs of Voronoi neighbours of a dump frame, by atom ID."""
    ids = frame["id"]
    return {(min(ids[a], ids[b]), max(ids[a], ids[b]))
            for a, b in PeriodicVoronoi(frame["x"], frame["y"], frame["box"]).pairs()}


def reference(frame):
    """Expected per-atom columns for a dump frame (atoms sorted by id 1..n)."""
    ref = PeriodicVoronoi(frame["x"], frame["y"], frame["box"])
    v = np.column_stack([frame["vx"], frame["vy"]])
    speed = np.hypot(v[:, 0], v[:, 1])
    unit = v / speed[:, None]
    coordination = np.array([np.mean([unit[c] @ unit[j] for j in ref.neighbors[c]])
                             for c in range(ref.n)])
    return ref, {
        "area": ref.area,
        "perimeter": ref.perimeter,
        "q": ref.perimeter / np.sqrt(ref.area),
        "z": np.array([len(s) for s in ref.neighbors], dtype=float),
        "energy": cell_energy(ref.area, ref.perimeter),
        "coordination": coordination,
        "orientation": np.arccos(np.clip(unit[:, 0], -1, 1)),
    }


# A hexagonal tissue with random displacements and random velocities; both are
# drawn per atom (displace_atoms random and velocity loop geom), so the
# configuration is the same on any number of ranks.
DISORDERED = tissue(extra="""displace_atoms all random 0.2 0.2 0 6553
velocity all create 1.0 90211 loop geom""")


class Lattices(LammpsTestCase):
    """Perfect lattices: every column known in closed form."""

    def test_hexagonal_lattice(self):
        run = self.run_lmp(tissue(extra="velocity all set 1 0 0") + dump_columns() + "run 0\n")
        (frame,) = run.dump("cells.dump")
        self.assertEqual(len(frame["id"]), 100)
        col = columns(frame)
        np.testing.assert_allclose(col["area"], 1.0, rtol=1e-12)
        np.testing.assert_allclose(col["perimeter"], HEX_PERIMETER, rtol=1e-12)
        np.testing.assert_allclose(col["q"], 3.7224194364, rtol=1e-10)
        np.testing.assert_array_equal(col["z"], 6)
        np.testing.assert_allclose(col["energy"], cell_energy(1.0, HEX_PERIMETER), rtol=1e-12)
        np.testing.assert_allclose(col["coordination"], 1.0, rtol=1e-14)
        np.testing.assert_allclose(col["orientation"], 0.0, atol=1e-14)
        (row,) = thermo_rows(run.stdout)
        self.assertAlmostEqual(row["c_vt[1]"], HEX_PERIMETER, places=12)
        self.assertEqual(row["c_vt[2]"], 0)
        self.assertEqual(row["c_vt[3]"], 0)    # the first computation
        # pe is normalised per atom in lj units: the mean cell energy
        self.assertAlmostEqual(row["PotEng"], cell_energy(1.0, HEX_PERIMETER), places=12)

    def check_square(self, nprocs):
        run = self.run_lmp(tissue("sq", ny=10, extra="velocity all set -1 0 0")
                           + dump_columns() + "run 0\n", nprocs=nprocs)
        (frame,) = run.dump("cells.dump")
        self.assertEqual(len(frame["id"]), 100)
        col = columns(frame)
        np.testing.assert_allclose(col["area"], 1.0, rtol=1e-12)
        np.testing.assert_allclose(col["perimeter"], 4.0, rtol=1e-12)
        np.testing.assert_allclose(col["q"], 4.0, rtol=1e-12)
        # each cell has 4 edges of length 1 and up to 4 of length 0
        np.testing.assert_array_equal(col["z"], 4)
        np.testing.assert_allclose(col["energy"], cell_energy(1.0, 4.0), rtol=1e-12)
        np.testing.assert_allclose(col["coordination"], 1.0, rtol=1e-14)
        np.testing.assert_allclose(col["orientation"], math.pi, rtol=1e-14)
        (row,) = thermo_rows(run.stdout)
        self.assertAlmostEqual(row["c_vt[1]"], 4.0, places=12)
        # 4 cells meet at every vertex and each cell has 4: as many vertices as
        # cells, each counted once across periodic images and ranks
        self.assertEqual(row["c_vt[2]"], 100)

    def test_square_lattice(self):
        self.check_square(1)

    @nprocs(2)
    def test_square_lattice_two_ranks(self):
        self.check_square(2)

    @nprocs(4)
    def test_square_lattice_four_ranks(self):
        self.check_square(4)

    def check_square_one_moved(self, nprocs, atom):
        """Moving one cell off the square lattice breaks the 4 fourfold
        vertices of its corners into pairs of threefold ones."""
        extra = (f"group moved id {atom}\n"
                 "displace_atoms moved move 0.1 0.05 0 units box")
        run = self.run_lmp(tissue("sq", ny=10, extra=extra) + "run 0\n", nprocs=nprocs)
        (row,) = thermo_rows(run.stdout)
        self.assertEqual(row["c_vt[2]"], 96)

    def test_square_lattice_one_cell_moved(self):
        for atom in (1, 55, 100):    # corner of the box, middle, opposite corner
            with self.subTest(atom=atom):
                self.check_square_one_moved(1, atom)

    @nprocs(4)
    def test_square_lattice_one_cell_moved_four_ranks(self):
        for atom in (1, 55, 100):
            with self.subTest(atom=atom):
                self.check_square_one_moved(4, atom)

    def check_group(self, nprocs):
        """Group = the left half (columns x = 0..4): only vertices where four
        group cells meet count (between columns 0|1 .. 3|4: 4 x 10), and atoms
        outside the group get zeros."""
        extra = ("region left block INF 4.5 INF INF INF INF\n"
                 "group left region left\n"
                 "velocity all set 0 1 0")
        script = tissue("sq", ny=10, extra=extra).replace(
            "compute va all vertex/atom", "compute va left vertex/atom").replace(
            "compute vt all vertex/tissue", "compute vt left vertex/tissue")
        run = self.run_lmp(script + dump_columns() + "run 0\n", nprocs=nprocs)
        (frame,) = run.dump("cells.dump")
        inside = frame["x"] < 4.5
        self.assertEqual(np.count_nonzero(inside), 50)
        col = columns(frame)
        for name in COLUMNS:
            np.testing.assert_array_equal(col[name][~inside], 0.0, err_msg=name)
        np.testing.assert_allclose(col["area"][inside], 1.0, rtol=1e-12)
        np.testing.assert_array_equal(col["z"][inside], 4)
        np.testing.assert_allclose(col["orientation"][inside], math.pi / 2, rtol=1e-14)
        (row,) = thermo_rows(run.stdout)
        self.assertAlmostEqual(row["c_vt[1]"], 4.0, places=12)
        self.assertEqual(row["c_vt[2]"], 40)

    def test_group(self):
        self.check_group(1)

    @nprocs(2)
    def test_group_two_ranks(self):
        self.check_group(2)


class Velocities(LammpsTestCase):
    """Coordination and orientation, which need the velocities of ghost atoms."""

    def test_zero_velocity(self):
        run = self.run_lmp(tissue() + dump_columns() + "run 0\n")
        col = columns(run.dump("cells.dump")[0])
        np.testing.assert_array_equal(col["coordination"], 0.0)
        np.testing.assert_array_equal(col["orientation"], -1.0)

    def test_orientation_of_uniform_velocity(self):
        for (vx, vy), angle in (((1, 0), 0.0), ((-2, 0), math.pi), ((0, -1), math.pi / 2),
                                ((1, 1), math.pi / 4), ((-1, 1), 3 * math.pi / 4)):
            with self.subTest(v=(vx, vy)):
                run = self.run_lmp(tissue(extra=f"velocity all set {vx} {vy} 0 units box")
                                   + dump_columns() + "run 0\n")
                col = columns(run.dump("cells.dump")[0])
                np.testing.assert_allclose(col["orientation"], angle, rtol=1e-14, atol=1e-15)
                np.testing.assert_allclose(col["coordination"], 1.0, rtol=1e-14)

    def test_stripes_anticoordinated(self):
        """Rows of the hexagonal lattice moving alternately along +x and -x:
        each cell has 2 neighbours in its own row and 4 in the adjacent rows, so
        C = (2 - 4) / 6 = -1/3."""
        extra = ("variable row atom round(y/v_ry)\n"
                 "variable ry equal ylat/2\n"
                 "variable vx atom 1-2*(v_row%2)\n"
                 "velocity all set v_vx 0 0 units box")
        run = self.run_lmp(tissue(extra=extra) + dump_columns() + "run 0\n")
        col = columns(run.dump("cells.dump")[0])
        np.testing.assert_allclose(col["coordination"], -1.0 / 3.0, rtol=1e-13)


class Disordered(LammpsTestCase):
    """Random configurations against the scipy reference tessellation."""

    def check_against_reference(self, frame):
        ref, expected = reference(frame)
        col = columns(frame)
        for name in COLUMNS:
            np.testing.assert_allclose(col[name], expected[name], rtol=1e-9, atol=1e-12,
                                       err_msg=name)
        return ref

    def test_against_reference(self):
        run = self.run_lmp(DISORDERED + dump_columns() + "run 0\n")
        (frame,) = run.dump("cells.dump")
        self.check_against_reference(frame)
        col = columns(frame)
        self.assertGreater(np.ptp(col["z"]), 0)    # the disorder changed neighbour counts
        (row,) = thermo_rows(run.stdout)
        self.assertAlmostEqual(row["c_vt[1]"], np.mean(col["q"]), places=12)
        self.assertEqual(row["c_vt[2]"], 0)

    def test_cell_energy_is_pe_atom(self):
        """Column 5 is the pair style's per-atom energy, also under hybrid/overlay."""
        script = DISORDERED.replace(
            "pair_style vertex/voronoi 3.0",
            "pair_style hybrid/overlay vertex/voronoi 3.0 zero 1.0\npair_coeff * * zero")
        script = script.replace("pair_coeff * * 1.0", "pair_coeff * * vertex/voronoi 1.0")
        script += ("compute pe all pe/atom\n"
                   "dump e all custom 1 pe.dump id c_va[5] c_pe\n"
                   "dump_modify e sort id format float %.17g\nrun 0\n")
        run = self.run_lmp(script)
        self.assertIn("hybrid/overlay", run.text("in.test"))
        (frame,) = run.dump("pe.dump")
        np.testing.assert_allclose(frame["c_va[5]"], frame["c_pe"], rtol=1e-14, atol=1e-15)
        self.assertGreater(np.ptp(frame["c_pe"]), 1e-3)

    def check_ranks(self, n):
        serial = self.run_lmp(DISORDERED + dump_columns() + "run 0\n").dump("cells.dump")[0]
        parallel = self.run_lmp(DISORDERED + dump_columns() + "run 0\n",
                                nprocs=n).dump("cells.dump")[0]
        # create_atoms numbers atoms rank by rank: match them by position
        one, many = by_position(serial), by_position(parallel)
        np.testing.assert_array_equal(many["x"], one["x"])
        np.testing.assert_array_equal(many["y"], one["y"])
        for name in ["c_va[%d]" % (k + 1) for k in range(len(COLUMNS))]:
            np.testing.assert_allclose(many[name], one[name], rtol=1e-12, atol=1e-13,
                                       err_msg=name)
        self.check_against_reference(parallel)

    @nprocs(2)
    def test_two_ranks_equal_one(self):
        self.check_ranks(2)

    @nprocs(4)
    def test_four_ranks_equal_one(self):
        self.check_ranks(4)


class NeighbourExchanges(LammpsTestCase):
    """compute vertex/tissue's element 3: neighbour pairs that are new since
    the previous computation of the global vector."""

    def test_solid_with_tiny_motion(self):
        extra = "fix b all brownian 1e-5 4321 gamma_t 1.0\ntimestep 0.01\nthermo 50"
        run = self.run_lmp(tissue(extra=extra) + "run 500\n")
        rows = thermo_rows(run.stdout)
        self.assertEqual(len(rows), 11)
        for row in rows:
            self.assertEqual(row["c_vt[3]"], 0)
            self.assertEqual(row["c_vt[2]"], 0)
            self.assertAlmostEqual(row["c_vt[1]"], HEX_PERIMETER, places=3)

    def check_displaced(self, nprocs):
        """Two configurations far apart, so that many atoms change rank
        between them; the count must equal the reference's new pairs."""
        script = DISORDERED + """thermo_style custom step c_vt[3]
run 0
write_dump all custom first.dump id x y modify sort id format float %.17g
displace_atoms all random 0.35 0.35 0 9127
run 0
write_dump all custom second.dump id x y modify sort id format float %.17g
run 0
"""
        run = self.run_lmp(script, nprocs=nprocs)
        counts = [row["c_vt[3]"] for row in thermo_rows(run.stdout)]
        first = run.dump("first.dump")[0]
        second = run.dump("second.dump")[0]
        before = PeriodicVoronoi(first["x"], first["y"], first["box"]).pairs()
        after = PeriodicVoronoi(second["x"], second["y"], second["box"]).pairs()
        new = len(after - before)
        self.assertGreater(new, 5)
        self.assertEqual(counts, [0, new, 0])
        return counts

    def test_displaced_configuration(self):
        self.check_displaced(1)

    @nprocs(2)
    def test_displaced_configuration_two_ranks(self):
        self.check_displaced(2)

    @nprocs(4)
    def test_displaced_configuration_four_ranks(self):
        self.check_displaced(4)

    def check_fluid(self, nprocs):
        """A fluid tissue (p0 = -Lambda / (2 Gamma) = 4 > 3.81) with noise: T1
        transitions happen; the count at each thermo step equals the new
        reference pairs between the dumps of the previous and this step."""
        extra = ("pair_coeff * * 1.0 1.0 0.1 -0.8\n"
                 "fix b all brownian 0.1 4321 gamma_t 1.0\n"
                 "timestep 0.01\n"
                 "thermo 100\n"
                 "dump d all custom 100 traj.dump id x y\n"
                 "dump_modify d sort id format float %.17g")
        run = self.run_lmp(tissue(extra=extra) + "run 600\n", nprocs=nprocs)
        rows = thermo_rows(run.stdout)
        frames = run.dump("traj.dump")
        self.assertEqual([int(r["Step"]) for r in rows], [f["step"] for f in frames])
        pairs = [PeriodicVoronoi(f["x"], f["y"], f["box"]).pairs() for f in frames]
        expected = [0] + [len(pairs[k] - pairs[k - 1]) for k in range(1, len(pairs))]
        counts = [int(r["c_vt[3]"]) for r in rows]
        self.assertEqual(counts, expected)
        self.assertGreater(sum(counts), 10)

    def test_fluid(self):
        self.check_fluid(1)

    @nprocs(2)
    def test_fluid_two_ranks(self):
        self.check_fluid(2)

    def check_fluid_with_events(self, nprocs):
        """A fluid tissue whose cells also divide and die during the run: the
        count at each thermo step equals the new neighbour pairs between the
        dumped junctions of the previous and this step among the cells that
        existed at both and that no birth or death touched
        (feature_outputs.exchanges, written from the documented rule)."""
        extra = ("pair_coeff * * 1.0 1.0 0.1 -0.8\n"
                 "fix b all brownian 0.1 4321 gamma_t 1.0\n"
                 "fix div all cell/divide rate 0.4 seed 771 separation 0.05\n"
                 "fix die all cell/death rate 0.3 seed 772\n"
                 "timestep 0.01\n"
                 "thermo 25\n"
                 "compute l all vertex/local\n"
                 "dump a all custom 25 ids.dump id\n"
                 "dump f all local 25 junctions.dump c_l[1] c_l[2] c_l[3] c_l[4] c_l[5] c_l[6] c_l[7]\n"
                 "dump_modify f format float %.17g")
        script = tissue(extra=extra).replace("thermo_style custom step pe c_vt[1] c_vt[2] c_vt[3]",
                                             "thermo_style custom step atoms c_vt[3] f_div[2] f_die[2]")
        run = self.run_lmp(script + "run 300\n", nprocs=nprocs)
        rows = thermo_rows(run.stdout)
        ids = [f["id"] for f in run.dump("ids.dump")]
        frames = local_rows(run, "junctions.dump")
        self.assertEqual(len(rows), 13)
        self.assertEqual((len(ids), len(frames)), (13, 13))
        pairs = [neighbour_pairs(f, 2, False) for f in frames]
        expected = [0] + [exchanges(pairs[k - 1], pairs[k], ids[k - 1], ids[k])[0]
                          for k in range(1, len(pairs))]
        counts = [int(r["c_vt[3]"]) for r in rows]
        self.assertEqual(counts, expected)
        self.assertGreater(sum(counts), 10)
        self.assertGreater(rows[-1]["f_div[2]"], 5)
        self.assertGreater(rows[-1]["f_die[2]"], 5)

    def test_fluid_with_divisions_and_deaths(self):
        self.check_fluid_with_events(1)

    @nprocs(2)
    def test_fluid_with_divisions_and_deaths_two_ranks(self):
        self.check_fluid_with_events(2)

    def test_created_atom(self):
        """A cell created between computations makes new pairs with its
        neighbours: a birth, not a neighbour exchange, so not counted."""
        script = tissue("sq", ny=10, extra="displace_atoms all random 0.1 0.1 0 771") + """
thermo_style custom step atoms c_vt[3]
run 0
write_dump all custom first.dump id x y modify sort id format float %.17g
create_atoms 1 single 0.5 0.5 0 units box
run 0
write_dump all custom second.dump id x y modify sort id format float %.17g
run 0
"""
        run = self.run_lmp(script)
        rows = thermo_rows(run.stdout)
        self.assertEqual([int(r["Atoms"]) for r in rows], [100, 101, 101])
        first, second = run.dump("first.dump")[0], run.dump("second.dump")[0]
        before = id_pairs(first)
        after = id_pairs(second)
        new = after - before
        self.assertGreaterEqual(len(new), 3)    # the new cell's own edges
        self.assertTrue(all(101 in pair for pair in new))
        self.assertEqual([r["c_vt[3]"] for r in rows], [0, 0, 0])

    def test_deleted_atom(self):
        """When a cell is removed its neighbours close the gap and make new
        pairs among themselves: a death, not a neighbour exchange."""
        script = tissue("hex", ny=10, extra="displace_atoms all random 0.1 0.1 0 771") + """
thermo_style custom step atoms c_vt[3]
run 0
write_dump all custom first.dump id x y modify sort id format float %.17g
group gone id 37
delete_atoms group gone compress no
run 0
write_dump all custom second.dump id x y modify sort id format float %.17g
run 0
"""
        run = self.run_lmp(script)
        rows = thermo_rows(run.stdout)
        first, second = run.dump("first.dump")[0], run.dump("second.dump")[0]
        before = id_pairs(first)
        after = id_pairs(second)
        self.assertGreaterEqual(len(after - before), 1)    # the gap closed by new pairs
        self.assertEqual([r["c_vt[3]"] for r in rows], [0, 0, 0])


class AtomStyleVariables(LammpsTestCase):
    """c_ID[I] of compute vertex/atom in an atom-style variable is per-atom
    column I on every host: the compute has no global vector for the
    variable to read instead (those values are compute vertex/tissue's)."""

    def test_neighbour_deficit_on_a_hexagonal_lattice(self):
        # every cell of a perfect hexagonal lattice has 6 neighbours
        script = tissue() + """variable q atom 6-c_va[4]
compute qsum all reduce sum v_q
compute qmax all reduce max v_q
compute qmin all reduce min v_q
thermo_style custom step c_qsum c_qmin c_qmax
dump v all custom 1 q.dump id v_q c_va[4]
dump_modify v sort id
run 0
"""
        run = self.run_lmp(script)
        (row,) = thermo_rows(run.stdout)
        self.assertEqual((row["c_qsum"], row["c_qmin"], row["c_qmax"]), (0, 0, 0))
        (frame,) = run.dump("q.dump")
        self.assertEqual(len(frame["id"]), 100)
        np.testing.assert_array_equal(frame["v_q"], 0)
        np.testing.assert_array_equal(frame["c_va[4]"], 6)

    def test_every_column_beyond_the_old_vector(self):
        # column 9 (edge flag) was out of range of the 8 global values
        script = tissue() + """variable e atom c_va[9]+c_va[3]
compute esum all reduce sum v_e
thermo_style custom step c_esum
run 0
print "E $(c_esum:%.17g)"
"""
        out = self.run_lmp(script).stdout
        (esum,) = [float(line.split()[1]) for line in out.splitlines() if line.startswith("E ")]
        self.assertAlmostEqual(esum, 100 * 3.7224194364, delta=1e-7)


class Migration(LammpsTestCase):
    """Scripts written for the compute's former global vector stop."""

    def test_thermo_of_vertex_atom_stops(self):
        script = tissue().replace("thermo_style custom step pe c_vt[1]", "thermo_style custom step pe c_va[1]")
        # LAMMPS 2021: "Thermo compute does not compute vector"; 2026: "Thermo
        # custom compute va does not compute a vector".
        self.assertLammpsError(self.run_lmp(script + "run 0\n", ok=False),
                               "does not compute")

    def test_variable_and_fix_ave_time_of_vertex_atom_stop(self):
        for extra in ("variable q equal c_va[3]\nthermo_style custom step v_q\nrun 0\n",
                      "run 0\nprint \"$(c_va[4])\"\n",
                      "fix a all ave/time 1 1 1 c_va[3]\nrun 0\n"):
            with self.subTest(extra=extra):
                run = self.run_lmp(tissue() + extra, ok=False)
                self.assertLammpsError(run, "compute")

    def test_rosette_names_vertex_tissue(self):
        script = tissue().replace("compute va all vertex/atom", "compute va all vertex/atom rosette 0.05")
        self.assertLammpsError(self.run_lmp(script + "run 0\n", ok=False),
                               "compute vertex/atom va", "'rosette'", "vertex/tissue rosette L")


class Errors(LammpsTestCase):

    def test_extra_argument(self):
        script = tissue().replace("compute va all vertex/atom", "compute va all vertex/atom 3")
        self.assertLammpsError(self.run_lmp(script + "run 0\n", ok=False),
                               "compute vertex/atom", "unknown keyword", "'3'")

    def test_needs_pair_vertex_voronoi(self):
        script = tissue().replace("pair_style vertex/voronoi 3.0", "pair_style zero 3.0")
        script = script.replace(f"pair_coeff * * {K} {A0} {GAMMA} {LAMBDA}", "pair_coeff * *")
        self.assertLammpsError(self.run_lmp(script + "run 0\n", ok=False),
                               "compute vertex/atom va", "pair_style vertex/voronoi", "'zero'")

    def test_not_current(self):
        """fix move evaluates the variable before the forces of the step."""
        extra = "variable vx atom 0*c_va[1]\n"
        script = tissue() + extra + "fix m all move variable NULL NULL NULL v_vx NULL NULL\nrun 2\n"
        self.assertLammpsError(self.run_lmp(script, ok=False),
                               "compute vertex/atom va", "timestep when pair vertex/voronoi")

    @nprocs(2)
    def test_not_current_two_ranks(self):
        extra = "variable vx atom 0*c_va[1]\n"
        script = tissue() + extra + "fix m all move variable NULL NULL NULL v_vx NULL NULL\nrun 2\n"
        self.assertLammpsError(self.run_lmp(script, nprocs=2, ok=False),
                               "compute vertex/atom va", "timestep when pair vertex/voronoi")


class Rosettes(LammpsTestCase):
    """compute vertex/tissue rosette L: a square lattice jittered by 1e-6 has
    no exactly four-fold vertex, but every vertex is a cluster of vertices
    joined by a junction far shorter than 1e-3 -- one per cell, counted once
    over ranks and images."""

    SCRIPT = lmptest.tissue(10, 10, "sq") + """
displace_atoms all random 1e-6 1e-6 0 8812 units box
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
compute exact all vertex/tissue
compute near all vertex/tissue rosette 1e-3
compute tiny all vertex/tissue rosette 1e-9
thermo_style custom step c_exact[2] c_near[2] c_tiny[2]
run 0
"""

    def check(self, nprocs):
        run = self.run_lmp(self.SCRIPT, nprocs=nprocs)
        row = run.stdout.split("Step")[1].splitlines()[1].split()
        self.assertEqual([float(w) for w in row[1:]], [0.0, 100.0, 0.0])

    def test_serial(self):
        self.check(1)

    @nprocs(2)
    def test_two_ranks(self):
        self.check(2)

    def test_bad_length(self):
        run = self.run_lmp(self.SCRIPT.replace("rosette 1e-3", "rosette -1"), ok=False)
        self.assertLammpsError(run, "rosette length must be > 0")


if __name__ == "__main__":
    lmptest.main()
