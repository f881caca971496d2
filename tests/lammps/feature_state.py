#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Feature-matrix checks of which state a step reads and shows (mixed into
test_feature_matrix.FeatureMatrix):

fix_order      the integrator defined before or after fix polarity (neighbour
               and velocity alignment, noise) gives the same trajectory, and
               1, 2 and 4 ranks agree to round-off (from a data file).
deform_output  at a step where fix deform changed the box after the forces,
               the dumped cells describe the dumped box and positions."""

import numpy as np

from feature_models import SPHERE_C, SPHERE_R, dim_of, model_script, printed


class StateChecks:
    """Checks of the feature matrix; self is a FeatureMatrix."""

    END_COLUMNS = ("xu", "yu", "zu", "mux", "muy", "muz")

    def ordered_dynamics(self, model, integrator, first, steps=6):
        pol = "fix p all polarity 0.3 1.0 neighbor 0.5 velocity 0.2 noise 0.2 77\n"
        integ = f"fix b all {integrator} 1.0 1 gamma_t 1.0 rng none\n"
        fixes = integ + pol if first == "integrator" else pol + integ
        return model_script(model, data="cfg.data") + fixes + f"""timestep 0.005
thermo_style custom step pe
run {steps}
write_dump all custom end.dump id xu yu zu mux muy muz modify format float %.17g sort id
"""

    def check_fix_order(self, model):
        data = self.run_lmp(model_script(model) + "write_data cfg.data\n").text("cfg.data")
        files = {"cfg.data": data}

        def end(integrator, first, n=1):
            run = self.run_lmp(self.ordered_dynamics(model, integrator, first), nprocs=n,
                               files=files)
            f = run.dump("end.dump")[0]
            return np.column_stack([f[c] for c in self.END_COLUMNS])

        for integrator in ("brownian", "brownian/heun"):
            after = end(integrator, "polarity")
            runs = {"integrator first": end(integrator, "integrator")}
            if integrator == "brownian":
                for n in (2, 4):
                    runs[f"integrator first, {n} ranks"] = end(integrator, "integrator", n)
            for what, got in runs.items():
                np.testing.assert_allclose(got, after, rtol=0, atol=1e-11,
                                           err_msg=f"{integrator}, {what}")

    def check_deform_output(self, model):
        d = dim_of(model)
        strain = "x erate 0.5 y erate -0.3" + (" z erate 0.2" if d == 3 and model != "sphere" else "")
        columns = ("c_c[1]", "c_c[2]", "c_c[5]")
        script = model_script(model) + f"""fix b all brownian 1.0 1 gamma_t 1.0 rng none
fix def all deform 1 {strain} remap x
compute c all vertex/atom
compute a all reduce sum c_c[1]
timestep 0.005
thermo_style custom step pe c_a vol
dump d all custom 5 cells.dump id {' '.join(columns)}
dump_modify d format float %.17g sort id
run 5
print "A $(c_a:%.17g) $(vol:%.17g)"
write_data end.data
"""
        run = self.run_lmp(script)
        area, vol = printed(run, "A")[0]
        if model == "sphere":
            self.assertAlmostEqual(area, 4 * np.pi * SPHERE_R ** 2, delta=1e-9 * area)
        elif not model.startswith("finite"):
            self.assertAlmostEqual(area, vol, delta=1e-9 * vol)    # the cells tile the box shown
        shown = run.dump("cells.dump")[-1]
        again = self.run_lmp(model_script(model, data="end.data") + f"""compute c all vertex/atom
dump d all custom 1 cells.dump id {' '.join(columns)}
dump_modify d format float %.17g sort id
run 0
""", files={"end.data": run.text("end.data")}).dump("cells.dump")[0]
        np.testing.assert_array_equal(shown["id"], again["id"])
        for col in columns:
            scale = np.abs(again[col]).max()
            np.testing.assert_allclose(shown[col], again[col], rtol=0, atol=1e-9 * scale,
                                       err_msg=col)
