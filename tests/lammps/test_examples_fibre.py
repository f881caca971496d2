#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""examples/fibre_network, run briefly: finite cells crawling on a
bead-spring fibre network (atom_style hybrid dipole angle, bond_style
harmonic, angle_style cosine, fix spring/self at the fibre ends), checked
against things that do not come from the run itself:

* forces = central differences of the total pe (vertex/voronoi + soft +
  bonds + angles) for cells and beads touching each other, a crosslinked bead
  among them;
* the cells are the cells alone: their areas are those of tessera-tools'
  own finite Voronoi construction of the cells' centres without the beads,
  and their vertex energy is that of pair_style vertex/voronoi alone with
  the beads deleted; tessera-tools info and vtk --cell-types count the cells
  and the beads;
* write_restart / read_restart continues the run (the anchors' springs keep
  their rest positions), and 2 ranks run the trajectory of 1;
* what the README says: with fibres the cells are slower, and they align
  the fibres along their migration axis x, with the bonds near rest."""

import math
import os
import subprocess
import sys

import numpy as np

import lmptest
from lmptest import LammpsTestCase

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "..", "examples", "fibre_network")
sys.path.insert(0, EXAMPLE)
sys.path.insert(0, lmptest.TOOLS)

import make_network  # noqa: E402
import plot as fibre_plot  # noqa: E402

NC = 48


def example(noise=True):
    """The example's input with its dump and final run removed."""
    with open(os.path.join(EXAMPLE, "in.fibre_network")) as f:
        script = f.read()
    lines = [line for line in script.split("\n")
             if not line.startswith(("dump", "run "))]
    script = "\n".join(lines) + "\n"
    if not noise:
        script = script.replace(" noise 0.2 4821", "")
        assert " noise " not in script
    return script


def data_file(path):
    make_network.write(make_network.build(), path)


def printed(run, key):
    return [[float(w) for w in line.split()[1:]] for line in run.stdout.splitlines()
            if line.startswith(key + " ")]


# The interactions of the example, for a configuration read from a data file
# (write_data ... nocoeff keeps no coefficients of pair_style hybrid).
POTENTIALS = """pair_style hybrid/overlay vertex/voronoi 1.76 radius 0.8 soft 1.0
pair_coeff 1 1 vertex/voronoi quadratic 1.0 1.0 0.1 3.8 free 0.2
pair_coeff 1 1 soft 1.0 0.6
pair_coeff 1 2 soft 1.0 1.0
pair_coeff 2 2 none
bond_coeff 1 20.0 0.5
bond_coeff 2 20.0 0.0
angle_coeff 1 0.5
special_bonds lj 1.0 1.0 1.0
"""


class FibreNetwork(LammpsTestCase):

    def crawled(self, steps=600):
        """The example run for `steps` steps (cells now touch fibres): its
        configuration (write_data) and a dump of every atom at full precision."""
        d = self.new_dir()
        data_file(os.path.join(d, "fibres.data"))
        script = example() + f"""dump d all custom {steps} end.dump id type x y xu yu c_cell[1]
dump_modify d sort id format float %.17g
run {steps}
write_data cfg.data nocoeff
"""
        run = self.run_lmp(script, variables={"data": os.path.join(d, "fibres.data")})
        return run, d

    def test_forces_are_central_differences(self):
        run, d = self.crawled()
        frame = run.dump("end.dump")[-1]
        box = frame["box"][:2, 1] - frame["box"][:2, 0]
        pos = np.column_stack([frame["x"], frame["y"]])
        cell = frame["type"] == 1

        def dist(a, others):
            dd = pos[others] - pos[a]
            dd -= box * np.round(dd / box)
            return np.hypot(dd[:, 0], dd[:, 1])

        bonds = fibre_plot.read_bonds(run.path("cfg.data"))
        ends = set()
        ids = frame["id"]
        for f in range(30):
            ends.update((NC + f * 17 + 1, NC + f * 17 + 17))
        linked = set(bonds[bonds[:, 0] == 2][:, 1:].ravel())
        beads = np.nonzero(~cell)[0]
        cells = np.nonzero(cell)[0]
        # a cell touching beads and another cell; an interior bead touching a
        # cell; a crosslinked interior bead
        near_cell = [k for k in cells if dist(k, beads).min() < 0.98 and
                     np.sort(dist(k, cells))[1] < 1.5]
        near_bead = [k for k in beads if ids[k] not in ends and dist(k, cells).min() < 0.98]
        xlinked = [k for k in beads if ids[k] in linked and ids[k] not in ends]
        self.assertTrue(near_cell and near_bead and xlinked, (near_cell, near_bead, xlinked))
        chosen = [int(ids[near_cell[0]]), int(ids[near_bead[0]]), int(ids[xlinked[0]])]
        h = 1e-5
        script = f"""dimension 2
units lj
boundary p p p
atom_style hybrid dipole angle
atom_modify map array
bond_style harmonic
angle_style cosine
read_data {run.path('cfg.data')}
{POTENTIALS}
compute pv all pair vertex/voronoi
compute ps all pair soft
thermo_style custom step pe c_pv c_ps ebond eangle
thermo_modify norm no format float %.17g
run 0
"""
        for a in chosen:
            script += f'print "F {a} $(fx[{a}]:%.17g) $(fy[{a}]:%.17g)"\ngroup g{a} id {a}\n'
            for k, (dx, dy) in enumerate(((h, 0), (-2 * h, 0), (h, h), (0, -2 * h), (0, h))):
                script += f"displace_atoms g{a} move {dx} {dy} 0 units box\n"
                if k < 4:
                    script += f'run 0\nprint "E {a} $(pe:%.17g) $(c_ps:%.17g) $(ebond:%.17g)"\n'
        out = self.run_lmp(script)
        forces = {int(r[0]): r[1:] for r in printed(out, "F")}
        energies = printed(out, "E")
        for n, a in enumerate(chosen):
            e = [r[1] for r in energies[4 * n:4 * n + 4]]
            fd = (-(e[0] - e[1]) / (2 * h), -(e[2] - e[3]) / (2 * h))
            # the soft and bond terms act on the chosen atoms (not a check of zero forces)
            self.assertGreater(energies[4 * n][2] + energies[4 * n][3], 0.0)
            for k in range(2):
                self.assertAlmostEqual(forces[a][k], fd[k], delta=1e-6 * (abs(fd[k]) + 1),
                                       msg=f"atom {a} component {'xy'[k]}")
            self.assertGreater(math.hypot(*forces[a]), 1e-3)

    def test_cells_are_the_cells_alone(self):
        run, d = self.crawled()
        from tessera_tools.dump import parse_types, read_dump
        from tessera_tools.render import tessellate_frame

        frame = read_dump(run.path("end.dump"), cell_types=parse_types("1"))[-1]
        self.assertEqual(frame.timestep, 600)
        self.assertEqual((frame.natoms, frame.particles.natoms), (NC, 510))
        # tessera-tools' own finite Voronoi construction of the centres alone
        tess = tessellate_frame(frame, 0.8)
        np.testing.assert_allclose(frame["c_cell[1]"], tess.area, rtol=0, atol=1e-9)
        self.assertTrue(np.all(frame.particles["c_cell[1]"] == 0.0))
        # the vertex energy is that of the cells with the beads deleted
        base = f"""dimension 2
units lj
boundary p p p
atom_style hybrid dipole angle
bond_style harmonic
angle_style cosine
read_data {run.path('cfg.data')}
"""
        mixed = self.run_lmp(base + POTENTIALS + """compute pv all pair vertex/voronoi
thermo_style custom step pe c_pv
run 0
print "E $(c_pv:%.17g)"
""")
        alone = self.run_lmp(base + """group beads type 2
delete_atoms group beads bond yes
pair_style vertex/voronoi 1.76 radius 0.8
pair_coeff 1 1 quadratic 1.0 1.0 0.1 3.8 free 0.2
pair_coeff 2 2 quadratic 1.0 1.0 0.1 3.8 free 0.2
bond_coeff * 20.0 0.5
angle_coeff * 0.5
thermo_style custom step pe
thermo_modify norm no
run 0
print "E $(pe:%.17g)"
""")
        ev, ea = printed(mixed, "E")[0][0], printed(alone, "E")[0][0]
        self.assertAlmostEqual(ev, ea, delta=1e-10 * abs(ea))
        # the command-line tools count cells and beads; vtk writes the beads as points
        tools = os.path.join(lmptest.TOOLS, "tessera-tools")
        info = subprocess.run([sys.executable, tools, "info", run.path("end.dump"),
                               "--cell-types", "1"], capture_output=True, text=True, check=True)
        self.assertIn("48 cells, 510 particles (types 2)", info.stdout)
        render = subprocess.run([sys.executable, tools, "render", run.path("end.dump"), "-o",
                                 os.path.join(d, "cells.png"), "--cell-types", "1", "--radius",
                                 "0.8"], capture_output=True, text=True, check=True)
        self.assertIn("48 cells, mean area %.6g" % np.mean(tess.area), render.stdout)
        subprocess.run([sys.executable, tools, "vtk", run.path("end.dump"), "-o",
                        os.path.join(d, "vtk", "all"), "--cell-types", "1", "--radius", "0.8"],
                       capture_output=True, text=True, check=True)
        # (the file names' step numbers are padded to the widest one)
        with open(os.path.join(d, "vtk", "all_particles_600.vtu")) as f:
            self.assertIn('NumberOfPoints="510"', f.read())

    def test_restart_continues(self):
        d = self.new_dir()
        data_file(os.path.join(d, "fibres.data"))
        end = "write_dump all custom end.dump id xu yu mux muy modify sort id format float %.17g\n"
        script = example(noise=False)
        whole = self.run_lmp(script + "run 200\n" + end,
                             variables={"data": os.path.join(d, "fibres.data")}).dump("end.dump")[0]
        first = self.run_lmp(script + "run 100\nwrite_restart half.restart\n",
                             variables={"data": os.path.join(d, "fibres.data")})
        # the same script, from the restart file: groups, bonds, angles and
        # the anchors' rest positions (fix spring/self of the same ID) come back
        again = script.replace("read_data       ${data}",
                               "read_restart    " + first.path("half.restart"))
        self.assertNotEqual(again, script)
        second = self.run_lmp(again + "run 100\n" + end).dump("end.dump")[0]
        for col in ("xu", "yu", "mux", "muy"):
            np.testing.assert_allclose(second[col], whole[col], rtol=0, atol=1e-9, err_msg=col)

    @lmptest.nprocs(2)
    def test_two_ranks_agree(self):
        # bonds, angles and crosslinks across the ranks' boundary, ghosts of
        # cells and beads: the same trajectory on 1 and 2 ranks
        d = self.new_dir()
        data_file(os.path.join(d, "fibres.data"))
        end = "write_dump all custom end.dump id xu yu mux muy modify sort id format float %.17g\n"
        script = example(noise=False) + "run 400\n" + end
        runs = [self.run_lmp(script, nprocs=n, variables={"data": os.path.join(d, "fibres.data")})
                for n in (1, 2)]
        one, two = (r.dump("end.dump")[0] for r in runs)
        self.assertIn("2 by 1 by 1 MPI processor grid", runs[1].output)
        for col in ("xu", "yu", "mux", "muy"):
            np.testing.assert_allclose(two[col], one[col], rtol=0, atol=1e-9, err_msg=col)

    def test_fibres_slow_the_cells_and_align(self):
        d = self.new_dir()
        data_file(os.path.join(d, "fibres.data"))
        with open(os.path.join(EXAMPLE, "in.fibre_network")) as f:
            script = f.read()
        out = {}
        for fibres in (1, 0):
            out[fibres] = self.run_lmp(script, variables={"data": os.path.join(d, "fibres.data"),
                                                          "fibres": fibres, "tend": 40})
        m1 = np.loadtxt(out[1].path("msd.1.dat"))
        m0 = np.loadtxt(out[0].path("msd.0.dat"))
        self.assertEqual((m1[-1, 0], m0[-1, 0]), (40.0, 40.0))
        # the cells are slower with fibres (mean speed from t = 10 on), and
        # move mostly along x
        late1, late0 = m1[m1[:, 0] >= 10, 7], m0[m0[:, 0] >= 10, 7]
        self.assertLess(late1.mean(), 0.75 * late0.mean())
        self.assertGreater(m1[-1, 1], 3 * m1[-1, 2])
        # the fibres turn towards x: S = <cos 2 theta> of the bonds rises from ~0
        bonds = fibre_plot.read_bonds(os.path.join(d, "fibres.data"))
        net, _ = fibre_plot.measures(out[1].path("dump.fibre_network.1"), bonds)
        self.assertLess(abs(net[0, 1]), 0.02)
        self.assertGreater(net[-1, 1], 0.08)
        # the fibres move, but their bonds stay near their rest length
        self.assertGreater(net[-1, 2], 1.0)
        from tessera_tools.dump import read_dump
        last = read_dump(out[1].path("dump.fibre_network.1"))[-1]
        v, _ = fibre_plot.bond_vectors(last, bonds)
        length = np.linalg.norm(v, axis=1)
        self.assertLess(abs(np.mean(length) - 0.5), 0.015)
        self.assertLess(np.max(np.abs(length - 0.5)), 0.15)


if __name__ == "__main__":
    lmptest.main()
