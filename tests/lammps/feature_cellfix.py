#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The feature matrix's `particles_fixes` check (test_feature_matrix.py), for
every model: the cell-only fixes given group all with particles present
(atoms of a type without cell parameters) take the cells and leave the
particles alone.  fix cell/signal: the total of a species produced at rate 1
per cell grows by the number of cells times the time (not the atoms), the
particles' values stay, explicit and implicit; fix cell/adapt: a variable
that gives d_area0 = 0 on the particles is no error and leaves theirs; fix
cell/divide: no particle divides; fix cell/death: no particle dies and the
floor 'min' counts cells (on the sphere the default floor, 4 cells); each
fix says once in the log how many atoms it leaves out."""

import numpy as np

from feature_models import PARTICLE_IDS, is_polygon, model_script, printed
from feature_particles import check_polygon_particles_fixes

NOTE = "holds 3 atom(s) that are no cells (type 3"


def check_particles_fixes(self, model):
    if is_polygon(model):
        return check_polygon_particles_fixes(self, model)
    start = model_script(model, particles=True)
    ncells = None
    # Signals and adapted parameters over 3 steps of 0.1 (cells at rest).
    run = self.run_lmp(start + """fix sp all property/atom d_u d_w d_area0
variable u0 atom 1+((id*37)%11)
set group all d_u v_u0
set group all d_w v_u0
set group all d_area0 1.0
set group particles d_u 7.0
set group particles d_w 7.0
set group particles d_area0 5.0
variable one atom 1.0
fix s all cell/signal exchange d_u 2.0 produce d_u v_one
fix t all cell/signal exchange d_w 2.0 produce d_w v_one implicit yes
compute pu all property/atom d_u
variable a0 atom (type<3)*(0.9+0.01*c_pu)
fix ad all cell/adapt 1 d_area0 v_a0
variable ncell equal count(cells)
timestep 0.1
thermo_style custom step f_s[1] f_t[1]
run 0
print "T0 $(f_s[1]:%.17g) $(f_t[1]:%.17g) $(v_ncell)"
run 3
print "T1 $(f_s[1]:%.17g) $(f_t[1]:%.17g)"
dump d all custom 1 p.dump id type d_u d_w d_area0
dump_modify d format float %.17g
run 0
""")
    (s0, t0, ncells), (s1, t1) = printed(run, "T0")[0], printed(run, "T1")[0]
    self.assertEqual(ncells, run.dump("p.dump")[0]["id"].size - len(PARTICLE_IDS))
    for before, after in ((s0, s1), (t0, t1)):
        self.assertAlmostEqual(after - before, ncells * 0.3, delta=1e-12 * after)
    f = run.dump("p.dump")[0]
    part = f["type"] == 3
    self.assertEqual(sorted(f["id"][part]), sorted(PARTICLE_IDS))
    for col, want in (("d_u", 7.0), ("d_w", 7.0), ("d_area0", 5.0)):
        np.testing.assert_array_equal(f[col][part], want, err_msg=col)
    self.assertTrue(np.all(f["d_area0"][~part] > 0.9), "d_area0 of the cells")
    for fix in ("fix s cell/signal", "fix t cell/signal", "fix ad cell/adapt"):
        self.assertEqual(sum(line.startswith(fix + ": group 'all' " + NOTE)
                             for line in run.stdout.splitlines()), 1, fix)

    # Every cell decides to divide (rate dt = 2), the particles never.
    run = self.run_lmp(start + """fix div all cell/divide rate 20.0 seed 4821 separation 0.05
timestep 0.1
run 1
dump d all custom 1 d.dump id type f_div[2] f_div[5]
run 0
""")
    f = run.dump("d.dump")[0]
    part = f["type"] == 3
    self.assertEqual(part.sum(), len(PARTICLE_IDS))
    np.testing.assert_array_equal(f["f_div[2]"][part], 0.0)
    self.assertEqual(int((~part).sum()), 2 * int(ncells))
    self.assertFalse(set(f["f_div[5]"].astype(int)) & set(PARTICLE_IDS))
    self.assertIn("fix div cell/divide: group 'all' " + NOTE, run.stdout)

    # Every cell decides to die (rate dt = 2): the floor keeps cells, the
    # particles stay.  On the sphere the default floor (4 cells, the fewest
    # a tessellation of the sphere has); elsewhere 5 cells die (the few
    # cells left of a confluent tissue would need a larger cutoff).
    floor = 4 if model == "sphere" else int(ncells) - 5
    keyword = "" if model == "sphere" else f" min {floor}"
    run = self.run_lmp(start + f"""fix die all cell/death rate 20.0 seed 77{keyword}
timestep 0.1
run 3
dump d all custom 1 e.dump id type
run 0
""")
    f = run.dump("e.dump")[0]
    self.assertEqual(sorted(f["id"][f["type"] == 3]), sorted(PARTICLE_IDS))
    self.assertEqual(int((f["type"] != 3).sum()), floor)
    self.assertIn("fix die cell/death: group 'all' " + NOTE, run.stdout)
