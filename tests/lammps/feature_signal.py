#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""The feature matrix's `signal` check (test_feature_matrix.py), for every
model: species exchanged across the junctions (fix cell/signal) keep their
total to round-off while the cells move; the junction-weighted neighbour
mean (compute cell/neighbor/mean) equals the one computed from compute
vertex/local's rows; a per-cell preferred area set by fix cell/adapt from a
variable gives the energy that the same values set with `set` give; the
forces are bit for bit those without species."""

import numpy as np

from feature_models import POLYGON_CELLS, dim_of, is_polygon, local_rows, model_script, printed

SPECIES = """fix sp all property/atom d_u d_area0
variable u0 atom 1+((id*37)%11)
set group all d_u v_u0
set group all d_area0 1.0
compute pu all property/atom d_u
"""


def junction_weights(model, rows):
    """{(cell ID, neighbour ID): total junction size} from vertex/local rows:
    2d and the sphere, one row per edge (size in the last column); 3d, one
    row per edge of a face, the face's area repeated on each (a face is a
    run of consecutive rows with the same pair)."""
    w = {}
    last = None
    for r in rows:
        key = (int(r[0]), int(r[1]))
        if key[1] == 0:    # a free arc (finite cells)
            last = None
            continue
        if dim_of(model) == 3 and model != "sphere":
            if key == last:
                continue
            last = key
        w[key] = w.get(key, 0.0) + r[-1]
    return w


def check_signal(self, model):
    d = dim_of(model)
    cols = " ".join(f"c_l[{k}]" for k in range(1, 10 if d == 3 else 8))
    # The neighbour mean at one step, against vertex/local's junctions.
    run = self.run_lmp(model_script(model) + SPECIES + f"""compute m all cell/neighbor/mean d_u
compute l all vertex/local
dump d all local 1 faces.dump {cols}
dump_modify d format float %.17g
dump e all custom 1 cells.dump id c_pu c_m
dump_modify e format float %.17g
run 0
""")
    rows = local_rows(run, "faces.dump")[0]
    cells = run.dump("cells.dump")[0]
    u = dict(zip(cells["id"], cells["c_pu"]))
    num, den = {}, {}
    for (i, j), s in junction_weights(model, rows).items():
        num[i] = num.get(i, 0.0) + s * u[j]
        den[i] = den.get(i, 0.0) + s
    got = dict(zip(cells["id"], cells["c_m"]))
    if is_polygon(model):    # vertex atoms are no cells: no junctions, mean 0
        self.assertTrue(all(got[i] == 0.0 for i in got if i > POLYGON_CELLS))
        got = {i: m for i, m in got.items() if i <= POLYGON_CELLS}
    self.assertEqual(set(num), set(got))
    for i in got:
        self.assertAlmostEqual(got[i], num[i] / den[i], delta=1e-12 * u[i])

    # Exchange alone, cells moving: the total stays to round-off.
    run = self.run_lmp(model_script(model) + SPECIES + """fix move all brownian 1.0 1 gamma_t 1.0 rng none
fix s all cell/signal exchange d_u 2.0
timestep 0.01
thermo_style custom step f_s[1] f_s[2]
thermo_modify format float %.17g
thermo 10
run 50
""")
    lines = run.stdout.splitlines()
    start = [k for k, line in enumerate(lines) if line.split()[:2] == ["Step", "f_s[1]"]][-1]
    totals = [float(line.split()[1]) for line in lines[start + 1:start + 7]]
    self.assertEqual(len(totals), 6)
    np.testing.assert_allclose(totals, totals[0], rtol=1e-13, atol=0)

    # fix cell/adapt sets d_area0 from a variable during a run; the energy
    # after one step is that of the same values set before the run; the
    # forces with species present are those without.
    area = "variable a0 atom 0.9+0.05*c_pu\n"
    adapt = self.run_lmp(model_script(model) + SPECIES + area + """fix ad all cell/adapt 1 d_area0 v_a0
thermo_style custom step pe
run 1
print "E $(pe:%.17g)"
""")
    plain = model_script(model) + SPECIES + """variable a0 atom 0.9+0.05*(1+((id*37)%11))
set group all d_area0 v_a0
thermo_style custom step pe
run 0
print "E $(pe:%.17g)"
group one id 5
print "F $(fx[5]:%.17g) $(fy[5]:%.17g) $(fz[5]:%.17g)"
"""
    with_set = self.run_lmp(plain)
    e_adapt, e_set = printed(adapt, "E")[0][0], printed(with_set, "E")[0][0]
    self.assertAlmostEqual(e_adapt, e_set, delta=1e-12 * abs(e_set))
    with_signal = self.run_lmp(plain.replace("run 0", "fix s all cell/signal exchange d_u 2.0\nrun 0"))
    self.assertEqual(printed(with_set, "F"), printed(with_signal, "F"))
