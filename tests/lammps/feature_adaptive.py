#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Feature-matrix check of fix brownian/heun's adaptive step (mixed into
test_feature_matrix.FeatureMatrix):

heun_adapt  with a tolerance no step reaches and dtmax = the timestep, the
            adaptive step is the fixed Heun step bit for bit (positions and
            polarities, no rejections); with tolerances 1e-4 and 1e-5 the
            end state's error against a fine fixed-step Heun run to the same
            time falls at least three times (it should fall about tenfold:
            the global error goes like the tolerance) and the finer tolerance
            takes more steps."""

import numpy as np

from feature_models import model_script, printed

COLUMNS = ("xu", "yu", "zu", "mux", "muy", "muz")
COUNTS = 'print "N $(f_b[3]) $(f_b[4]) $(time:%.17g)"\n'
END = "write_dump all custom end.dump id xu yu zu mux muy muz modify format float %.17g sort id\n"


class AdaptiveChecks:
    """Checks of the feature matrix; self is a FeatureMatrix."""

    def adaptive_end(self, script):
        run = self.run_lmp(script)
        f = run.dump("end.dump")[0]
        return np.concatenate([f[c] for c in COLUMNS]), run

    def check_heun_adapt(self, model):
        base = model_script(model) + "fix p all polarity 0.3 1.0 neighbor 0.5\n"
        fixed = "fix b all brownian/heun 1.0 1 gamma_t 1.0 rng none"
        plain, _ = self.adaptive_end(base + fixed + "\ntimestep 0.004\nthermo_style custom step pe\n"
                                     "run 10\n" + END)
        loose, run = self.adaptive_end(base + fixed + " adapt tol 1e9\ntimestep 0.004\n"
                                       "thermo_style custom step pe\nrun 10\n" + END + COUNTS)
        np.testing.assert_array_equal(loose, plain)
        self.assertEqual(printed(run, "N")[0][:2], [10, 0])
        errors, steps = ([], []) if model != "finite_per" else self.kinked_errors(base, fixed)
        for tol in (1e-4, 1e-5) if model != "finite_per" else ():
            state, run = self.adaptive_end(
                base + fixed + f" adapt tol {tol} dtmax 0.004\ntimestep 0.004\n"
                "variable t equal time\nfix stop all halt 1 v_t >= 0.04 error continue\n"
                "thermo_style custom step pe\nrun 100000\n" + END + COUNTS)
            accepted, _, t_end = printed(run, "N")[0]
            ref, _ = self.adaptive_end(base + fixed + f"\ntimestep {t_end / 200!r}\n"
                                       "thermo_style custom step pe\nrun 200\n" + END)
            errors.append(np.abs(state - ref).max())
            steps.append(accepted)
        self.assertGreater(errors[0], 0.0)
        self.assertGreater(errors[0] / errors[1], 3.0, f"errors {errors} at tol 1e-4, 1e-5")
        self.assertGreater(steps[1], steps[0])

    def kinked_errors(self, base, fixed):
        """finite_per: its cells leave gaps at three-cell corners that open
        and close, kinks of the energy where any step is first order (a
        fixed-step reference is not accurate enough) and the adaptive step
        goes like tol.  The reference is the adaptive step at tol 1e-6 over
        t = 0.01; each run's end state is taken back to t = 0.01 along its
        last step (dt is then below 1e-4, the chord's error far below the
        tolerances')."""
        ends = {}
        for tol in (1e-4, 1e-5, 1e-6):
            script = (base + fixed + f" adapt tol {tol} dtmax 0.004\ntimestep 0.004\n"
                      "variable t equal time\nfix stop all halt 1 v_t >= 0.01 error continue\n"
                      "thermo_style custom step pe\nrun 1000000\n" + COUNTS +
                      "write_dump all custom end.dump id xu yu zu mux muy muz vx vy vz "
                      "modify format float %.17g sort id\n")
            run = self.run_lmp(script)
            f = run.dump("end.dump")[0]
            accepted, _, t_end = printed(run, "N")[0]
            back = t_end - 0.01
            pos = np.concatenate([f[c] - back * f["v" + c[0]] for c in ("xu", "yu", "zu")])
            ends[tol] = (pos, accepted)
        ref = ends[1e-6][0]
        return ([np.abs(ends[t][0] - ref).max() for t in (1e-4, 1e-5)],
                [ends[t][1] for t in (1e-4, 1e-5)])
