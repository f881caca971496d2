#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Cells among atoms that are no cells (pair_style hybrid/overlay
vertex/voronoi ... with another style): what is an error and what is defined
at the interface.  (Forces, tessellations, ranks and restarts of every model
with particles: the particles features of test_feature_matrix.py; the hole
around a particle: test_compute_vertex_loops.py.)"""

import os

import numpy as np

import lmptest
from lmptest import LammpsTestCase, nprocs

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")


def tissue():
    """A 7 x 6 hexagonal tissue of cells of area 1, two types, an atom map."""
    return lmptest.tissue(7, 6, ntypes=2).replace("atom_style dipole\n",
                                                  "atom_style dipole\natom_modify map array\n")


def mixed(extra_coeffs="", cut=3.0, soft=1.0, particles="6 40"):
    """A 7 x 6 hexagonal tissue (type 1 cells) with atoms `particles`
    made type 2, repelled by pair soft."""
    return tissue() + f"""group p id {particles}
set group p type 2
group cells type 1
pair_style hybrid/overlay vertex/voronoi {cut} soft {soft}
pair_coeff 1 1 vertex/voronoi 1.0 1.0 0.1 -0.5
pair_coeff * 2 soft 2.0 {soft}
{extra_coeffs}
compute pv all pair vertex/voronoi
compute ps all pair soft
thermo_style custom step pe c_pv c_ps
thermo_modify norm no format float %.17g
"""


def printed(run, key):
    return [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
            if line.startswith(key + " ")]


class CellsAmongParticles(LammpsTestCase):

    def test_a_type_without_cell_parameters_alone(self):
        script = tissue() + """set atom 6 type 2
pair_style vertex/voronoi 3.0
pair_coeff 1 1 1.0 1.0 0.1 -0.5
run 0
"""
        run = self.run_lmp(script, ok=False)
        self.assertLammpsError(run, "no cell parameters for atom type 2",
                               "pair_style hybrid/overlay vertex/voronoi")

    def test_junction_tension_with_a_particle_type(self):
        run = self.run_lmp(mixed("pair_coeff 1 2 vertex/voronoi -0.3") + "run 0\n", ok=False)
        self.assertLammpsError(run, "pair_coeff 1 2 vertex/voronoi",
                               "type 2 has no cell parameters")

    def test_ghost_shell_inside_hybrid_names_the_cutoff(self):
        # A hole of deleted cells that a 1.2 ghost shell cannot see across.
        script = mixed(cut=1.2).replace("group p id", """region hole sphere 0.3 0.4 0 2.2 units box
delete_atoms region hole compress no
group p id""") + "run 0\n"
        run = self.run_lmp(script, ok=False)
        self.assertLammpsError(run, "inside pair_style hybrid/overlay the ghost shell cannot grow",
                               "'pair_style hybrid/overlay vertex/voronoi")

    def test_cell_only_fixes_leave_particles_in_their_group_alone(self):
        """fix cell/divide and cell/death on group all take its cells: the
        run is that of the same fix on the group of the cells, and the log
        says once how many atoms of the group are no cells."""
        end = ("dump d all custom 1 end.dump id type x y\n"
               "dump_modify d sort id format float %.17g\nrun 0\n")
        for fix in ("cell/divide rate 1.0 seed 5", "cell/death rate 1.0 seed 5"):
            with self.subTest(fix=fix):
                runs = [self.run_lmp(mixed() + f"fix d {group} {fix}\ntimestep 0.2\nrun 3\n" + end)
                        for group in ("all", "cells")]
                frames = [r.dump("end.dump")[0] for r in runs]
                self.assertNotEqual(frames[0]["id"].size, 42)    # cells divided or died
                for col in ("id", "type", "x", "y"):
                    np.testing.assert_array_equal(frames[0][col], frames[1][col], err_msg=col)
                self.assertEqual(sorted(frames[0]["id"][frames[0]["type"] == 2]), [6, 40])
                note = (f"fix d {fix.split()[0]}: group 'all' holds 2 atom(s) that are no cells "
                        "(type 2")
                self.assertEqual(runs[0].stdout.count(note), 1)
                self.assertNotIn("that are no cells", runs[1].stdout)

    def test_a_cell_type_also_in_another_sub_style(self):
        # Cells that also repel each other through soft: the energies add up
        # and forces are still the central differences of the total pe; for
        # confluent and finite cells.
        for radius in ("", " radius 0.7"):
            with self.subTest(model="finite" if radius else "confluent"):
                script = mixed("pair_coeff 1 1 soft 0.5 1.3", soft=1.3, cut="3.0" + radius) + """group a id 17
run 0
print "F $(fx[17]:%.17g) $(pe:%.17g) $(c_pv:%.17g) $(c_ps:%.17g)"
displace_atoms a move 1e-5 0 0 units box
run 0
print "EP $(pe:%.17g)"
displace_atoms a move -2e-5 0 0 units box
run 0
print "EM $(pe:%.17g)"
"""
                run = self.run_lmp(script)
                f, pe, pv, ps = printed(run, "F")[0]
                self.assertAlmostEqual(pe, pv + ps, delta=1e-12 * abs(pe))
                self.assertGreater(ps, 0.0)
                fd = -(printed(run, "EP")[0][0] - printed(run, "EM")[0][0]) / 2e-5
                self.assertAlmostEqual(f, fd, delta=1e-6 * (abs(f) + 1))

    def test_a_particle_at_a_cell_centre(self):
        # A particle on top of cell 17, or 0.3 from its centre (inside the
        # disc of radius 0.7 of finite cells): the cells do not see it (their
        # energy is that of the tissue without it); soft's force at zero
        # distance is 0.
        for radius in ("", " radius 0.7"):
            for dx in (0.0, 0.3):
                with self.subTest(model="finite" if radius else "confluent", offset=dx):
                    script = mixed(particles="6", cut="3.0" + radius) + f"""create_atoms 2 single $(x[17]+{dx}) $(y[17]) 0 units box
run 0
print "E $(c_pv:%.17g) $(fx[85]:%.17g) $(fy[85]:%.17g) $(atoms)"
"""
                    run = self.run_lmp(script)
                    pv, fx, fy, n = printed(run, "E")[0]
                    self.assertEqual(n, 85)
                    if dx == 0.0:
                        self.assertEqual((fx, fy), (0.0, 0.0))
                    else:
                        self.assertGreater(abs(fx), 0.1)    # soft pushes it away from cell 17
                    alone = tissue() + f"""group p id 6
delete_atoms group p compress no
pair_style vertex/voronoi 3.0{radius}
pair_coeff * * 1.0 1.0 0.1 -0.5
thermo_modify norm no format float %.17g
run 0
print "E $(pe:%.17g)"
"""
                    self.assertAlmostEqual(pv, printed(self.run_lmp(alone), "E")[0][0], delta=1e-10 * abs(pv))

    def test_per_cell_values_and_fix_adapt_inside_hybrid(self):
        # Particles need no d_area0 (theirs stays 0); fix adapt of a
        # sub-style's kappa acts as the same pair_coeff value would.
        def pv(script):
            return printed(self.run_lmp(script + 'run 0\nprint "E $(c_pv:%.17g)"\n'), "E")[0][0]
        plain = pv(mixed())
        area0 = pv(mixed() + "fix a0 all property/atom d_area0\nset group cells d_area0 1.0\n")
        self.assertAlmostEqual(area0, plain, delta=1e-12 * abs(plain))
        stiff = mixed().replace("vertex/voronoi 1.0 1.0 0.1 -0.5", "vertex/voronoi 2.0 1.0 0.1 -0.5")
        adapt = mixed() + ("variable k equal 2.0\n"
                           "fix ad all adapt 1 pair vertex/voronoi kappa 1 1 v_k reset no\n")
        self.assertNotAlmostEqual(pv(stiff), plain, delta=1e-6)
        self.assertAlmostEqual(pv(adapt), pv(stiff), delta=1e-12 * abs(plain))

    def test_integrators_move_particles(self):
        # An isolated particle (out of soft's reach) pushed by fix addforce
        # moves F dt / gamma_t per step under both overdamped integrators.
        for integ in ("brownian", "brownian/heun"):
            with self.subTest(integrator=integ):
                script = mixed(particles="6") + f"""set atom 6 x 3.7 y 5.6
group cells delete
group cells type 1
delete_atoms overlap 1.2 cells p
fix f p addforce 0.5 0 0
fix b all {integ} 1.0 1 gamma_t 2.0 rng none
timestep 0.01
run 0
print "X0 $(x[6]:%.17g) $(c_ps:%.17g)"
run 20
print "X1 $(x[6]:%.17g) $(c_ps:%.17g)"
"""
                run = self.run_lmp(script)
                x0, ps0 = printed(run, "X0")[0]
                x1, ps1 = printed(run, "X1")[0]
                self.assertEqual((ps0, ps1), (0.0, 0.0))
                self.assertAlmostEqual(x1 - x0, 20 * 0.01 * 0.5 / 2.0, delta=1e-12)


class DepositAmongCells(LammpsTestCase):
    """fix deposit during a run with particles present: deposited particles
    (type 2) never become cells, deposited cells (type 1) do.  The cells tile
    the periodic box whatever lies under them, so the cells' areas sum to the
    box area and their vertex energy is that of the same cells with the
    particles deleted, computed by pair_style vertex/voronoi alone."""

    def deposit(self, itype):
        script = mixed() + f"""compute cell all vertex/atom
variable iscell atom c_cell[1]>0
compute ncell all reduce sum v_iscell
compute asum all reduce sum c_cell[1]
thermo_style custom step pe c_pv c_ps c_ncell c_asum
thermo_modify norm no format float %.17g
region inside block 0.1 7.4 0.1 11.0 -0.1 0.1 units box
fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix dep all deposit 3 {itype} 5 4821 region inside near 0.3 attempt 200
timestep 0.005
run 0
print "A $(atoms) $(c_ncell) $(c_asum:%.17g) $(lx*ly:%.17g)"
run 20
print "B $(atoms) $(c_ncell) $(c_asum:%.17g) $(c_pv:%.17g)"
group newest type 2
delete_atoms group newest compress no
thermo_style custom step pe
thermo_modify norm no
uncompute pv
uncompute ps
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
run 0
print "C $(atoms) $(pe:%.17g)"
"""
        run = self.run_lmp(script)
        return printed(run, "A")[0], printed(run, "B")[0], printed(run, "C")[0]

    def test_deposited_particles_are_no_cells(self):
        (n0, c0, a0, box), (n1, c1, a1, pv), (n2, e2) = self.deposit(2)
        self.assertEqual(n1, n0 + 3)
        self.assertEqual(c1, c0)
        self.assertEqual(c0, n0 - 2)
        self.assertAlmostEqual(a1, box, delta=1e-9 * box)
        self.assertEqual(n2, c1)
        self.assertAlmostEqual(pv, e2, delta=1e-10 * abs(e2))

    def test_deposited_cells_with_particles_present(self):
        (n0, c0, a0, box), (n1, c1, a1, pv), (n2, e2) = self.deposit(1)
        self.assertEqual(n1, n0 + 3)
        self.assertEqual(c1, c0 + 3)
        self.assertAlmostEqual(a0, box, delta=1e-9 * box)
        self.assertAlmostEqual(a1, box, delta=1e-9 * box)
        self.assertEqual(n2, c1)
        self.assertAlmostEqual(pv, e2, delta=1e-10 * abs(e2))


class PillarExample(LammpsTestCase):
    """examples/pillar: the wound closes onto the pillar, where the same
    wound without it closes completely (test_finite.py), and a hole stays
    around the pillar, which does not move."""

    def test_hole_stays_around_the_pillar(self):
        with open(os.path.join(EXAMPLES, "pillar", "in.pillar")) as f:
            script = f.read().replace("dump_modify", "#").replace("dump ", "# dump ")
        script += ('print "P $(xcm(pillar,x):%.17g) $(xcm(pillar,y):%.17g) $(xlo+0.5*lx:%.17g) '
                   '$(ylo+0.5*ly:%.17g)"\n')
        run = self.run_lmp(script, args=["-var", "tend", "20"])
        data = np.loadtxt(run.path("hole.dat"))
        self.assertGreater(data[0, 2], 14.0)
        late = data[data[:, 0] >= 16.0]
        self.assertTrue(np.all(late[:, 2] > 0.5) and np.all(late[:, 2] < 0.15 * data[0, 2]))
        x, y, xc, yc = printed(run, "P")[0]
        np.testing.assert_allclose([x, y], [xc, yc], rtol=0, atol=1e-12)    # (xcm's rounding)


class FlowPillarsExample(LammpsTestCase):
    """examples/flow_pillars, briefly: a confluent tissue driven along +x by
    fix addforce past a fixed pillar.  The cells are overdamped, so their
    centre of mass moves by dt / gamma times the total force on them each
    step; the vertex forces between cells sum to zero (the energy does not
    change when every cell moves alike) and the pillar pushes the cells with
    minus the force they put on it (Newton's third law through pair soft).
    So the cells' summed displacement over the run is dt / gamma times the
    sum over steps of (N F - the pillar's force), that force read from the
    pillar atom, which is in no integrator's group and must not move; and no
    cell centre may cross into the core of the pillar's repulsion.  On two
    ranks the pillar's force also sums the pushes of cells owned by the other
    rank."""

    def check(self, nranks):
        with open(os.path.join(EXAMPLES, "flow_pillars", "in.flow")) as f:
            script = f.read()
        script = script[:script.index("run             $(round(v_tdump/v_dt))")]
        nsteps = 1500
        script += f"""variable r atom sqrt((x-v_xc)^2+(y-v_yc)^2)
compute rmin cells reduce min v_r
run 0
print "A $(count(cells)) $(xcm(cells,x):%.17g) $(c_fp[1]:%.17g) $(bound(pillar,xmin):%.17g) $(bound(pillar,ymin):%.17g)"
fix fstep all print 1 "$(c_fp[1]:%.17g) $(c_rmin:%.17g)" file steps.dat screen no
run {nsteps}
print "B $(xcm(cells,x):%.17g) $(bound(pillar,xmin):%.17g) $(bound(pillar,ymin):%.17g)"
"""
        run = self.run_lmp(script, nprocs=nranks, args=["-var", "tend", "1.0", "-var", "tdump", "1.0"])
        n, x0, fp0, px0, py0 = printed(run, "A")[0]
        x1, px1, py1 = printed(run, "B")[0]
        steps = np.loadtxt(run.path("steps.dat"))
        # fix print writes steps 0..n; the moves of steps 1..n use the forces of steps 0..n-1
        self.assertEqual(len(steps), nsteps + 1)
        self.assertEqual(steps[0, 0], fp0)
        fp = steps[:-1, 0]
        F, dt = 0.1, 0.01
        predicted = dt * np.sum(n * F - fp) / n
        self.assertGreater(np.mean(fp), 0.05 * n * F)    # the pillar does hold the tissue back
        self.assertAlmostEqual(x1 - x0, predicted, delta=1e-9 * abs(predicted))
        self.assertLess(x1 - x0, nsteps * dt * F)
        # the pillar stays where it was created
        self.assertEqual((px1, py1), (px0, py0))
        # the pillar's soft force (range 2) keeps every centre out of its core
        self.assertGreater(np.min(steps[:, 1]), 1.0)

    def test_pillar_reaction_balances_the_drive(self):
        self.check(1)

    @nprocs(2)
    def test_pillar_reaction_balances_the_drive_two_ranks(self):
        self.check(2)


if __name__ == "__main__":
    lmptest.main()
