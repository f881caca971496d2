#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Input that used to be accepted without a word or answered with a
misleading message: each now stops with an error naming the argument, the
value and the fix (or prints the settings that apply).  Most cases are rows
of one table, CASES: a script, whether it fails, the fragments its ERROR or
WARNING line must contain and those it must not."""

import os
import re

import lmptest
from lmptest import LammpsTestCase, nprocs

BASE = lmptest.tissue(6, 3) + "pair_style vertex/voronoi 3.0\n"

COEFF = "pair_coeff * * 1 1 0.1 -0.5\n"
BROWNIAN = "fix b all brownian 1.0 1 gamma_t 1.0 rng none\n"


def cubes(cutoff=3.0, region="region box block 0 4 0 4 0 4", extra=""):
    """A 3d simple cubic lattice of unit cubes (or 64 of them in `region`'s box)."""
    return f"""units lj
atom_style dipole
boundary p p p
{region}
create_box 1 box
lattice sc 1.0
region cube block 0 4 0 4 0 4
create_atoms 1 region cube
mass 1 1.0
pair_style vertex/voronoi {cutoff}{extra}
pair_coeff * * 1 1 0.1 -0.5
"""


def sphere(extra="", a0=2.8):
    """40 cells at random places of a box, put on a sphere of radius 3
    (area 113, about 2.8 per cell) by the pair style."""
    return f"""units lj
atom_style dipole
boundary f f f
region box block 0 20 0 20 0 20
create_box 1 box
create_atoms 1 random 40 123 box
mass 1 1.0
set group all dipole/random 5 1.0
pair_style vertex/voronoi 8 surface sphere 10 10 10 3{extra}
pair_coeff * * 1 {a0} 0.1 -0.2
"""


# (name, script, fails, fragments of the ERROR (fails) or WARNING line, fragments it must not have)
CASES = [
    # cutoffs LAMMPS cannot use: rejected before LAMMPS's communication sees them
    ("cutoff_1e300", lmptest.tissue(6, 3) + "pair_style vertex/voronoi 1e300\n" + COEFF + "run 0\n",
     True, ["cutoff 1e+300 is outside the usable range 0.01 to 100", "sqrt(A0) = 1",
            "'pair_style vertex/voronoi 3'"], ["far too small"]),
    ("cutoff_1e10", lmptest.tissue(6, 3) + "pair_style vertex/voronoi 1e10\n" + COEFF + "run 0\n",
     True, ["outside the usable range", "multiplies the ghost atoms"], ["far too small"]),
    ("cutoff_1e-6", lmptest.tissue(6, 3) + "pair_style vertex/voronoi 1e-6\n" + COEFF + "run 0\n",
     True, ["cutoff 1e-06 is outside the usable range", "cannot grow that far"],
     ["did not converge"]),
    ("cutoff_3d_1e10", cubes(1e10) + "run 0\n",
     True, ["outside the usable range", "cbrt(V0) = 1"], ["far too small"]),
    ("cutoff_inf", lmptest.tissue(6, 3) + "pair_style vertex/voronoi 1e400\n",
     # (current LAMMPS's own number parser already names the value as out of range)
     True, ["1e400"], []),
    # LAMMPS's atom sort overflows its bin count for a huge box (no neighbor
    # list: LAMMPS's own check of the box against the bins is skipped)
    ("box_1e12_3d", cubes(region="region box block 0 1e12 0 1e12 0 1e12") + "run 0\n",
     True, ["too large for LAMMPS's atom sort", "2147483647", "'atom_modify sort 0 0.0'"], []),
    # pair_coeff quadratic without its values
    ("quadratic_without_sigma", lmptest.tissue(6, 3, ntypes=2) +
     "pair_style vertex/voronoi 3.0\n" + COEFF + "pair_coeff 1 2 quadratic\nrun 0\n",
     True, ["pair_coeff 1 2: 'quadratic' needs a value", "sigma", "pair_coeff 1 2 quadratic 0.1"],
     ["Expected floating point"]),
    ("quadratic_without_values", BASE + "pair_coeff 1 1 quadratic\n",
     True, ["'quadratic' needs the four values KA A0 KP P0"], ["Expected floating point"]),
    # two integrators on the same cells
    ("brownian_and_heun", BASE + COEFF + BROWNIAN +
     "fix h all brownian/heun 1.0 1 gamma_t 1.0 rng none\nrun 1\n",
     True, ["fix b (brownian, group all) and fix h (brownian/heun, group all)",
            "36 cells", "'unfix'"], []),
    ("heun_and_nve", BASE + COEFF + "fix h all brownian/heun 1.0 1 gamma_t 1.0 rng none\n"
     "fix n all nve\nrun 1\n", True, ["fix h (brownian/heun", "fix n (nve"], []),
    # keywords the model does not use
    ("incremental_on_sphere", sphere(" incremental no") + "run 0\n",
     True, ["'incremental'", "on a sphere", "remove 'incremental'"], []),
    ("free_on_confluent_cells", BASE + "pair_coeff * * 1 1 0.1 -0.5 free 0.3\nrun 0\n",
     False, ["'free' tensions are ignored without 'radius r'"], []),
    # daughters placed past a periodic box
    ("separation_past_the_box", BASE + COEFF + BROWNIAN +
     "fix d all cell/divide rate 1.0 seed 5 separation 30\nrun 5\n",
     True, ["fix cell/divide: separation 30 is not smaller than the periodic box length",
            "below a cell diameter"], ["timestep"]),
    # atoms put out of the box between runs: not the timestep's fault
    ("lost_by_set", BASE + COEFF + "set atom 5 x 1e6\nrun 0\n",
     True, ["35 of 36 atoms are left at step 0", "before the first step of this run", "set,"],
     ["timestep"]),
    # fix cell/death on a sphere: 4 cells at least
    ("death_min_0_on_sphere", sphere() + BROWNIAN + "fix d all cell/death rate 5.0 seed 7 min 0\n"
     "run 1\n", True, ["fix cell/death: min 0 is below the 4 cells", "'min 4'"], []),
    ("death_default_floor_on_sphere", sphere() + BROWNIAN +
     "fix d all cell/death rate 5.0 seed 7\ntimestep 0.1\nrun 50\n",
     False, ["fix cell/death d:", "the floor 'min 4' (the default)", "at least 4 cells"], []),
    # a bath of fix cell/signal on cells without free arcs would never act
    ("bath_on_confluent_cells", BASE + COEFF + "fix sp all property/atom d_u\n"
     "fix s all cell/signal exchange d_u 1.0 bath d_u 2.0 1.0\nrun 1\n",
     True, ["fix cell/signal s: bath d_u", "these cells have none", "without 'radius r'",
            "remove 'bath d_u ...'"], []),
    # fix cell/divide growth linear overwrites the d_area0 fix cell/adapt sets
    ("adapt_area0_with_growth_linear", BASE + COEFF + "fix sp all property/atom d_area0\n"
     "set group all d_area0 1.0\nvariable a atom 1.1\nfix ad all cell/adapt 1 d_area0 v_a\n"
     "fix div all cell/divide rate 0.1 seed 5 growth linear\nrun 1\n",
     False, ["fix ad cell/adapt sets d_area0", "fix div cell/divide 'growth linear'",
             "leave out one of the two"], []),
    # pair_style hybrid (not overlay) giving a pair of cell types to another style alone:
    # their cells would still share junctions
    # an atom that is no cell jumps by the force of another sub-style: the
    # message names its type and the forces that moved it, not the cells'
    ("particle_jump", lmptest.tissue(6, 3, ntypes=2) + "create_atoms 2 single 2.0 2.0 0.0 units box\n"
     "create_atoms 2 single 2.3 2.0 0.0 units box\nmass * 1.0\n"
     "pair_style hybrid/overlay vertex/voronoi 3.0 lj/cut 1.0\npair_coeff 1 1 vertex/voronoi 1 1 0.1 -0.5\n"
     "pair_coeff * 2 lj/cut 1.0 1.0\npair_coeff 1 1 lj/cut 0.0 1.0\n" + BROWNIAN + "run 5\n",
     True, ["of type 2, which is no cell", "bonds and angles"], ["finite cells", "Voronoi forces grow"]),
    ("hybrid_takes_a_pair_of_cell_types", lmptest.tissue(6, 3, ntypes=2) + "set type 1 type/fraction 2 0.5 5\n"
     "pair_style hybrid vertex/voronoi 3.0 soft 1.0\npair_coeff * * vertex/voronoi 1 1 0.1 -0.5\n"
     "pair_coeff 1 2 soft 1.0 1.0\nrun 0\n",
     True, ["pair_style hybrid: pair_coeff 1 2 gives the type pair 1 2, both cell types, to another style",
            "'pair_style hybrid/overlay'"], ["All pair coeffs are not set"]),
    ("hybrid_particles_given_cell_parameters", lmptest.tissue(6, 3, ntypes=2) + "set atom 5 type 2\n"
     "pair_style hybrid vertex/voronoi 3.0 soft 1.0\npair_coeff * * vertex/voronoi 1 1 0.1 -0.5\n"
     "pair_coeff * 2 soft 1.0 1.0\nrun 0\n",
     True, ["pair_coeff 1 2 gives the type pair 1 2", "if type 2's atoms are no cells",
            "'pair_coeff I I vertex/voronoi ...' instead of '* *'"], []),
    # one vertex/voronoi for all cells: a second one under hybrid stops at pair_coeff
    ("hybrid_two_vertex_voronoi", lmptest.tissue(6, 3, ntypes=2) +
     "set type 1 type/fraction 2 0.5 5\npair_style hybrid vertex/voronoi 3.0 vertex/voronoi 3.0\n"
     "pair_coeff 1 1 vertex/voronoi 1 1 1 0.1 -0.5\npair_coeff 2 2 vertex/voronoi 2 1 1 0.1 -0.5\n"
     "run 0\n",
     True, ["pair_style hybrid: vertex/voronoi is given more than once",
            "'pair_coeff I I vertex/voronoi ...'"], ["no cell parameters", "junction tension"]),
    ("hybrid_overlay_two_vertex_voronoi", lmptest.tissue(6, 3) +
     "pair_style hybrid/overlay vertex/voronoi 3.0 vertex/voronoi 3.0\n"
     "pair_coeff * * vertex/voronoi 1 1 1 0.1 -0.5\nrun 0\n",
     True, ["pair_style hybrid/overlay: vertex/voronoi is given more than once"], []),
    # fix cell/signal's substeps: bounded as 'substeps auto' is
    ("signal_substeps_1e8", BASE + COEFF + "fix sp all property/atom d_m\nset group all d_m 1.0\n"
     "fix sig all cell/signal exchange d_m 1.0 substeps 100000000\n",
     True, ["fix cell/signal: substeps 100000000 is not below 10000000", "'substeps auto'"], []),
    # a cell that leaves through a fixed boundary: the boundary and the atom
    # (the box is 6 lattice constants of 1.0745699 wide: 6.44742)
    ("left_through_fixed_boundary",
     lmptest.tissue(6, 3).replace("boundary p p p", "boundary f f p") +
     "region inner block 0.5 5.5 0.5 2.5 -0.5 0.5\ndelete_atoms group all\n"
     "create_atoms 1 region inner\npair_style vertex/voronoi 1.5 radius 0.7\n"
     "pair_coeff * * quadratic 1 1 0.1 3.8 free 0.2\n" + BROWNIAN +
     "fix push all addforce 2.0 0.0 0.0\ntimestep 0.05\nrun 200\n",
     True, ["left the box through its fixed ('f') upper x boundary at step 8", "past 6.44742",
            "fix wall", "shrink-wrapped"], ["command or fix that sets positions"]),
    # area-triggered divisions below the preferred area, with a radius that
    # follows the preferred areas: they run away, and the message says so
    # (the sphere's area per cell is the mean preferred area, 1, exactly)
    ("divisions_run_away_on_sphere", sphere(a0=1.0).replace(
        "pair_style", "fix sp all property/atom d_area0\nset group all d_area0 1.0\n"
        "compute pa0 all property/atom d_area0\ncompute a0sum all reduce sum c_pa0\n"
        "variable R equal sqrt(c_a0sum/(4*PI))\npair_style").replace(
        "surface sphere 10 10 10 3", "surface sphere 10 10 10 v_R") + BROWNIAN +
     "fix div all cell/divide area 0.8 seed 3301 axis long separation 0.1\ntimestep 0.02\n"
     "run 3000\n",
     True, ["reaches past the box", "since step 0 the atoms grew from 40 to",
            "the radius from 1.784 to", "fix cell/divide div divides cells whose area exceeds 0.8",
            "mean area on the sphere is 1 and their mean preferred area 1",
            "below the preferred area", "the divisions run away"], []),
    ("hybrid_cell_type_own_pair_to_another_style", lmptest.tissue(6, 3, ntypes=2) + "set atom 5 type 2\n"
     "pair_style hybrid vertex/voronoi 3.0 soft 1.0\npair_coeff * * vertex/voronoi 1 1 0.1 -0.5\n"
     "pair_coeff 1 2 vertex/voronoi -0.5\npair_coeff 2 2 soft 1.0 1.0\nrun 0\n",
     True, ["pair_coeff 2 2 gives the type pair 2 2"], ["All pair coeffs are not set"]),
]


class Table(LammpsTestCase):
    def check(self, name, script, fails, want, avoid, nprocs=1):
        run = self.run_lmp(script, nprocs=nprocs, ok=not fails)
        kind = "ERROR" if fails else "WARNING"
        if fails:
            self.assertNotEqual(run.returncode, 0, run.output[-3000:])
        lines = [l for l in run.output.splitlines() if kind in l and all(w in l for w in want)]
        self.assertTrue(lines, "%s: no %s line with all of %r:\n%s"
                        % (name, kind, want, run.output[-3000:]))
        for a in avoid:
            self.assertNotIn(a, lines[0], name)
        return run

    def test_cases(self):
        for name, script, fails, want, avoid in CASES:
            with self.subTest(name):
                self.check(name, script, fails, want, avoid)

    @nprocs(4)
    def test_daughters_lost_past_a_rank(self):
        # separation 5 in an 8.6 x 5.6 box on 4 ranks along x (sub-domains
        # 2.1 wide): a daughter 2.5 from its mother can be lost on the
        # exchange; the error points at the atoms added, not at the timestep
        script = lmptest.tissue(8, 3).replace("lattice", "processors 4 1 1\nlattice") + \
            "pair_style vertex/voronoi 3.0\n" + COEFF + BROWNIAN + \
            "fix d all cell/divide rate 2.0 seed 5 separation 5\ntimestep 0.01\nrun 20\n"
        self.check("daughters_lost", script, True,
                   ["atoms are left at step", "atoms were added since the last force computation",
                    "separation d"], ["timestep"], nprocs=4)

    def test_cutoff_at_the_lower_bound_grows(self):
        # 1/100 cell diameter is still usable: the shell grows to a complete
        # one and the energy is that of a run with a wide cutoff
        pe, out = [], []
        for cut in (0.0101, 3.0):
            run = self.run_lmp(lmptest.tissue(6, 3) + f"pair_style vertex/voronoi {cut}\n" + COEFF +
                               "thermo_modify norm no\nrun 0\nprint \"E $(pe:%.15g)\"\n")
            pe.append(float([l for l in run.stdout.splitlines() if l.startswith("E ")][0].split()[1]))
            out.append(run.stdout)
        self.assertIn("cutoff grown from 0.0101", out[0])
        self.assertAlmostEqual(pe[0], pe[1], delta=1e-10)

    def test_settings_line_3d_names_incremental(self):
        for mode in ("no", "check"):
            run = self.run_lmp(cubes(extra=f" incremental {mode}") + "run 0\n")
            line = [l for l in run.stdout.splitlines()
                    if l.startswith("pair_style vertex/voronoi: cutoff")][0]
            self.assertIn(f"incremental {mode}", line)
            self.assertIn("(3d cells)", line)

    def test_sphere_step_guard(self):
        # active cells on a sphere of R = 3 with fix brownian/heun and a
        # timestep far too large: the move is measured on the sphere (a chord,
        # at most 2R), the cell size is sqrt(A0), the step is from 0 to 1,
        # and fix brownian/heun is not suggested to its own user
        run = self.run_lmp(sphere() + "fix h all brownian/heun 1.0 1 gamma_t 1.0 rng none\n"
                           "fix p all polarity 300 1.0\ntimestep 1\nrun 3\n")
        warn = [l for l in run.output.splitlines() if "WARNING" in l and "moved by" in l]
        self.assertEqual(len(warn), 1, run.output[-3000:])
        self.assertIn("sqrt(A0) = 1.67", warn[0])
        self.assertIn("on the sphere", warn[0])
        self.assertIn("the step from 0 to 1", warn[0])
        self.assertNotIn("cbrt", warn[0])
        self.assertNotIn("fix brownian/heun", warn[0])
        moved = float(re.search(r"moved by (\S+)", warn[0]).group(1))
        self.assertLessEqual(moved, 6.0 * (1 + 1e-3))


# A compute read through the library (Python's extract_compute) between runs,
# where LAMMPS's own check that a compute is current does not apply: the cells
# of the last 'run 0' no longer describe the atoms.  One message for every
# reader of the cells, naming the reader, the step and why.
# (name, setup after BASE (defines compute c, then 'run 0'), what changes,
#  extract_compute style and type, ranks, fragments of the ERROR line)
STALE_PY = r"""
import sys
from lammps import lammps
from tessera_tools import host
setup, between, style, kind = open(sys.argv[1]).read().split("@@")
lmp = lammps(cmdargs=["-log", "none", "-nocite"])
host.register(lmp)
lmp.commands_string(setup)
lmp.commands_string(between)
lmp.extract_compute("c", int(style), int(kind))
print("EXTRACTED")
lmp.close()
"""
READS = "reads the cells of pair_style vertex/voronoi at step"
INVOKE = "invoke it on a timestep when pair vertex/voronoi computed forces"
FINITE = (lmptest.tissue(6, 3).replace("boundary p p p", "boundary f f p") +
          "pair_style vertex/voronoi 1.5 radius 0.7\n"
          "pair_coeff * * quadratic 1 1 0.1 3.8 free 0.2\n")
STALE_CASES = [
    # read before any run: no pair style has been set up (once a segmentation fault)
    ("vertex_atom_before_any_run", BASE + COEFF + "compute c all vertex/atom\n", "", 1, 2, 1,
     ["compute vertex/atom c", "no cells yet", "'run 0'"]),
    ("vertex_tissue_before_any_run", BASE + COEFF + "compute c all vertex/tissue\n", "", 0, 1, 1,
     ["compute vertex/tissue c", "no cells yet", "'run 0'"]),
    ("vertex_atom_reset_timestep", BASE + COEFF + "compute c all vertex/atom\n", "reset_timestep 5",
     1, 2, 1, ["compute vertex/atom c " + READS + " 5", "its cells are those of step 0", INVOKE]),
    ("vertex_local_reset_timestep", BASE + COEFF + "compute c all vertex/local\n",
     "reset_timestep 5", 2, 2, 1,
     ["compute vertex/local c " + READS + " 5", "its cells are those of step 0", INVOKE]),
    ("neighbor_mean_reset_timestep", BASE + COEFF +
     "variable xx atom x\ncompute c all cell/neighbor/mean v_xx\n", "reset_timestep 5", 1, 1, 1,
     ["compute cell/neighbor/mean c " + READS + " 5", "its cells are those of step 0", INVOKE]),
    ("vertex_loops_reset_timestep", FINITE + "compute c all vertex/loops\n", "reset_timestep 5",
     0, 1, 1, ["compute vertex/loops c " + READS + " 5", "its cells are those of step 0", INVOKE]),
    ("vertex_tissue_delete_atoms", BASE + COEFF + "compute c all vertex/tissue\n",
     "group g id 1\ndelete_atoms group g", 0, 1, 1,
     ["compute vertex/tissue c " + READS + " 0", "the atoms changed", "delete_atoms", INVOKE]),
    # the last atom is on the second rank: rank 0's own atoms are unchanged
    ("vertex_tissue_delete_atoms_2_ranks", BASE + COEFF + "compute c all vertex/tissue\n",
     "group g id 18\ndelete_atoms group g", 0, 1, 2,
     ["compute vertex/tissue c " + READS + " 0", "the atoms changed", INVOKE]),
    # displace_atoms redistributes the atoms (the ghost atoms are gone): not
    # the ghost shell's fault
    ("vertex_atom_displace_atoms", BASE + COEFF + "compute c all vertex/atom\n",
     "displace_atoms all move 0.1 0 0", 1, 2, 1,
     ["compute vertex/atom c " + READS + " 0", "the atoms changed", "displace_atoms", INVOKE]),
]


class StaleCells(LammpsTestCase):
    def test_cases(self):
        if self.plugin_host:
            self.skipTest("the plugin host's Python module is tested by test_python")
        for name, setup, between, style, kind, ranks, want in STALE_CASES:
            with self.subTest(name):
                case = os.path.join(self.new_dir(), "case.txt")
                with open(case, "w") as f:
                    first = "" if name.endswith("before_any_run") else "run 0\n"
                    f.write("@@".join([setup + first, between, str(style), str(kind)]))
                run = self.run_python(STALE_PY, nprocs=ranks, ok=False, args=(case,))
                self.assertNotIn("EXTRACTED", run.stdout, name)
                lines = [l for l in run.output.splitlines()
                         if "ERROR" in l and all(w in l for w in want)]
                self.assertTrue(lines, "%s: no ERROR line with all of %r:\n%s"
                                % (name, want, run.output[-3000:]))
                self.assertNotIn("ghost shell", lines[0], name)


class Messages(LammpsTestCase):
    def test_free_without_value(self):
        run = self.run_lmp(BASE + "pair_coeff * * 1 1 0.1 -0.5 free\nrun 0\n", ok=False)
        self.assertLammpsError(run, "pair_coeff * *", "'free' needs a value")

    def test_negative_gamma(self):
        run = self.run_lmp(BASE + "pair_coeff * * 1 1 -0.1 0.18\nrun 0\n", ok=False)
        self.assertLammpsError(run, "Gamma must be >= 0", "-0.1")

    def test_nonpositive_timestep(self):
        # (timestep 0 with 'run 0' is fine: no step is taken)
        for dt in ("-0.01", "0"):
            run = self.run_lmp(BASE + f"""pair_coeff * * 1 1 0.1 -0.5
fix p all polarity 0.3 1.0 noise 0.1 7
fix b all brownian 1.0 1 gamma_t 1.0 rng none
timestep {dt}
run 2
""", ok=False)
            self.assertLammpsError(run, "timestep must be > 0")
            self.assertNotIn("nan", run.output.lower().split("error")[0][-2000:])

    def test_settings_line_of_finite_cells(self):
        run = self.run_lmp(lmptest.tissue(6, 3).replace("boundary p p p", "boundary f f p") +
                           "pair_style vertex/voronoi 1.5 radius 0.7\n"
                           "pair_coeff * * quadratic 1 1 0.1 3.8 free 0.2\nrun 0\n")
        line = [l for l in run.stdout.splitlines() if l.startswith("pair_style vertex/voronoi: cutoff")][0]
        self.assertIn("radius 0.7", line)
        self.assertNotIn("incremental", line)
        self.assertIn("free F", run.stdout)

    def test_adapt_area0_with_d_area0(self):
        run = self.run_lmp(BASE + """pair_coeff * * 1 1 0.1 -0.5
fix a0 all property/atom d_area0
set group all d_area0 1.0
variable v equal 1.5
fix ad all adapt 1 pair vertex/voronoi area0 * * v_v
run 1
""")
        self.assertIn("adapt d_area0 instead", run.output)


lmptest.main()
