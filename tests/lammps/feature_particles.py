#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The feature matrix's particle checks (test_feature_matrix.py): the probe
every model shares, and the vertex model's checks (pair_style hybrid/overlay
vertex/polygon ... soft): three cell centres made particles (type 4) before the vertices are created,
soft between the particles and the vertices.  The particles never enter a
polygon: the cells' energy and areas are those of the same tissue built
without them, their rows of compute vertex/atom are zero, no junction
names them; the cell-only fixes on group all take the cells alone."""

import numpy as np

from feature_models import PARTICLE_IDS, local_rows, model_script, polygon_death, printed
from vertex_check import check_tissue

PTYPE = 4    # the particles' type in the vertex model (3: the vertices)


def probe_particles(self, model, style, ptype):
    """One run 0 with the particles (either pair style, hybrid/overlay with
    soft): pe is the two sub-styles' sum, the particles touch something,
    their rows of compute vertex/atom are zero and no junction of compute
    vertex/local names them.  Returns (pv, vol, the per-atom dump, the
    particles' mask)."""
    cols = " ".join(f"c_c[{k}]" for k in range(1, 10))
    probe = f"""compute c all vertex/atom
compute pv all pair {style}
compute ps all pair soft
compute l all vertex/local
dump d all custom 1 cells.dump id type {cols}
dump_modify d format float %.17g sort id
dump n all local 1 nb.dump c_l[1] c_l[2]
thermo_style custom step pe c_pv c_ps vol
run 0
print "E $(pe:%.17g) $(c_pv:%.17g) $(c_ps:%.17g) $(vol:%.17g)"
"""
    run = self.run_lmp(model_script(model, particles=True) + probe)
    pe, pv, ps, vol = printed(run, "E")[0]
    self.assertAlmostEqual(pe, pv + ps, delta=1e-10 * abs(pe))
    self.assertGreater(ps, 0.0)    # the particles touch the cells (vertices)
    f = run.dump("cells.dump")[0]
    part = f["type"] == ptype
    self.assertEqual(sorted(f["id"][part].astype(int)), list(PARTICLE_IDS))
    for k in range(1, 10):
        self.assertTrue(np.all(f[f"c_c[{k}]"][part] == 0.0), f"c_c[{k}] of a particle")
    nb = local_rows(run, "nb.dump")[0]
    self.assertFalse(set(nb.ravel().astype(int)) & set(PARTICLE_IDS))
    return pv, vol, f, part


def check_polygon_particles(self, model):
    self.check_forces(model, particles=True)
    pv, vol, f, _ = probe_particles(self, model, "vertex/polygon", PTYPE)
    cell = f["type"] < 3
    self.assertTrue(np.all(f["c_c[1]"][cell] > 0.0))
    # The cells tile the box whatever lies among them.
    self.assertAlmostEqual(f["c_c[1]"][cell].sum(), vol, delta=1e-9 * vol)
    # The same tissue built without the particles, the pair style alone.
    ids = " ".join(str(i) for i in PARTICLE_IDS)
    alone = model_script(model).replace(
        "create_vertices all 3\n", f"group p id {ids}\ndelete_atoms group p compress no\n"
        "create_vertices all 3\n")
    ref = self.run_lmp(alone + """compute c all vertex/atom
dump d all custom 1 cells.dump id type c_c[1] c_c[2]
dump_modify d format float %.17g sort id
run 0
print "E $(pe:%.17g)"
""")
    self.assertAlmostEqual(pv, printed(ref, "E")[0][0], delta=1e-10 * abs(pv))
    g = ref.dump("cells.dump")[0]
    np.testing.assert_array_equal(g["id"][g["type"] < 3], f["id"][cell])
    for col in ("c_c[1]", "c_c[2]"):
        np.testing.assert_allclose(f[col][cell], g[col][g["type"] < 3], rtol=1e-12, err_msg=col)


def check_polygon_particles_fixes(self, model):
    """fix cell/signal and cell/adapt on group all: totals count the cells,
    the particles' values stay; cell/divide: cells divide, particles never,
    the tissue stays valid; cell/death: cells leave, particles stay.  Each
    fix says once how many atoms (vertices and particles) it leaves out."""
    start = model_script(model, particles=True)
    note = "holds {} atom(s) that are no cells (type 3 4"
    run = self.run_lmp(start + """fix sp all property/atom d_u d_area0
set group all d_u 1.0
set group all d_area0 1.0
set group particles d_u 7.0
set group particles d_area0 5.0
variable one atom 1.0
fix s all cell/signal exchange d_u 2.0 produce d_u v_one
compute pu all property/atom d_u
variable a0 atom (type<3)*(0.9+0.01*c_pu)
fix ad all cell/adapt 1 d_area0 v_a0
variable ncell equal count(cells)
variable nother equal count(all)-count(cells)
timestep 0.1
thermo_style custom step f_s[1]
run 0
print "T0 $(f_s[1]:%.17g) $(v_ncell) $(v_nother)"
run 3
print "T1 $(f_s[1]:%.17g)"
dump d all custom 1 p.dump id type d_u d_area0
dump_modify d format float %.17g
run 0
""")
    s0, ncells, nother = printed(run, "T0")[0]
    s1 = printed(run, "T1")[0][0]
    self.assertAlmostEqual(s1 - s0, ncells * 0.3, delta=1e-12 * s1)
    f = run.dump("p.dump")[0]
    part, cell = f["type"] == PTYPE, f["type"] < 3
    self.assertEqual(int(cell.sum()), ncells)
    self.assertEqual(sorted(f["id"][part]), sorted(PARTICLE_IDS))
    for col, want in (("d_u", 7.0), ("d_area0", 5.0)):
        np.testing.assert_array_equal(f[col][part], want, err_msg=col)
    self.assertTrue(np.all(f["d_area0"][cell] > 0.9), "d_area0 of the cells")
    for fix in ("fix s cell/signal", "fix ad cell/adapt"):
        self.assertEqual(sum(line.startswith(f"{fix}: group 'all' " + note.format(int(nother)))
                             for line in run.stdout.splitlines()), 1, fix)

    # Cells divide (by a new edge), the particles never.
    run = self.run_lmp(start + """fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix div all cell/divide rate 20.0 seed 4821 separation 0.05
timestep 0.005
run 4
dump d all custom 1 d.dump id type f_div[2]
run 0
write_data end.data
""")
    f = run.dump("d.dump")[0]
    part, cell = f["type"] == PTYPE, f["type"] < 3
    self.assertEqual(sorted(f["id"][part]), sorted(PARTICLE_IDS))
    np.testing.assert_array_equal(f["f_div[2]"][part], 0.0)
    self.assertGreater(int(cell.sum()), int(ncells))
    self.assertIn("fix div cell/divide: group 'all' " + note.format(int(nother)), run.stdout)
    check_tissue(self, run.text("end.data"), f"{model} particles divide")

    # Cells die (shrink, then T1s and a T2), the particles stay; min counts cells.
    floor = int(ncells) - 3
    run = self.run_lmp(polygon_death(start, "rate 0.5", floor) + """run 2000
dump d all custom 1 e.dump id type
run 0
write_data end.data
""")
    f = run.dump("e.dump")[0]
    self.assertEqual(sorted(f["id"][f["type"] == PTYPE]), sorted(PARTICLE_IDS))
    self.assertLess(int((f["type"] < 3).sum()), int(ncells))
    self.assertGreaterEqual(int((f["type"] < 3).sum()), floor)
    check_tissue(self, run.text("end.data"), f"{model} particles death")
