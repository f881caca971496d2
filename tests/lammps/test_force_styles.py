#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""LAMMPS's force-style test stages for pair_style vertex/voronoi in each model
(tests/lammps/force-styles/vertex_<model>.yaml, in LAMMPS's schema; the stages and
their commands are force_styles.py's): on this host's lmp, and on the plugin host
also on an lmp with the TESSERA package compiled in (--intree-lmp).

* stages: `run 0` (forces, pair energy, the six virial components) and 4 steps of
  fix nve (the tester's integrator: the cells have masses, so Newton's equations
  are as meaningful a check of the forces as any) against the stored references;
  the pair energy equal to the sum of compute pe/atom; write_restart/read_restart,
  `pair_modify nofdotr`, write_data/read_data and the style given again, each
  `run 0` giving the references of the first.
* derivatives: the stored references are the energy's derivatives, checked each
  time for three atoms and two strain components (the generator checked all).
* newton off: refused with an error that says why (forces go to ghost atoms).
* extract: every name of the YAML's extract list through fix adapt (which asks
  the style's extract() for a type-pair array of that name); a name the style does
  not know is refused; on a LAMMPS whose library interface has
  lammps_extract_pair (the current one), the names' dimensions and values through
  Python's lammps.extract_pair.
"""

import os
import re
import unittest

import numpy as np

import force_styles as fs
import lmptest
from lmptest import Config, LammpsTestCase

MODELS = fs.models()


def check_values(test, what, got, ref, eps):
    err = fs.fp_error(got, ref)
    worst = np.unravel_index(np.argmax(err), err.shape) if err.ndim else ()
    test.assertLessEqual(float(np.max(err)), eps,
                         "%s: largest error %.3g at %s (got %r, stored %r), epsilon %g"
                         % (what, float(np.max(err)), worst, np.asarray(got)[worst],
                            np.asarray(ref)[worst], eps))


class ForceStyle(LammpsTestCase):

    def config(self, model):
        cfg = fs.read_yaml(MODELS[model])
        return cfg, fs.dimension_of(cfg), float(cfg["epsilon"])

    def check_stages(self, model, lmp=None, host="host"):
        cfg, dim, eps = self.config(model)
        run = self.run_lmp(fs.stage_script(cfg), lmp=lmp)
        stages = fs.read_probes(run)
        ids, init_f = fs.parse_forces(cfg["init_forces"])
        _, run_f = fs.parse_forces(cfg["run_forces"])
        self.assertEqual(len(ids), int(cfg["natoms"]))
        init = {"vdwl": float(cfg["init_vdwl"]), "coul": float(cfg["init_coul"]),
                "stress": fs.parse_stress(cfg["init_stress"]), "forces": init_f}
        for stage in ("init", "restart", "nofdotr", "data", "reissue"):
            got = stages[stage]
            with self.subTest(host=host, stage=stage):
                np.testing.assert_array_equal(got["ids"], ids)
                check_values(self, "%s %s_forces" % (host, stage), got["forces"],
                             init["forces"], eps)
                check_values(self, "%s %s_stress" % (host, stage), got["stress"],
                             init["stress"], eps)
                check_values(self, "%s %s_vdwl" % (host, stage), got["vdwl"], init["vdwl"], eps)
                check_values(self, "%s %s_coul" % (host, stage), got["coul"], init["coul"], eps)
        # the data stage reads the data file that write_data wrote (a YAML file whose
        # pre_commands set data_file would keep the original)
        self.assertEqual(os.path.basename(stages["data"]["file"]), "tess.data")
        got = stages["run"]
        with self.subTest(host=host, stage="run"):
            check_values(self, host + " run_forces", got["forces"], run_f, 5 * eps)
            check_values(self, host + " run_stress", got["stress"],
                         fs.parse_stress(cfg["run_stress"]), eps)
            check_values(self, host + " run_vdwl", got["vdwl"], float(cfg["run_vdwl"]), eps)
            check_values(self, host + " run_coul", got["coul"], float(cfg["run_coul"]), eps)
            # the pair energy is the sum of the per-atom energies
            check_values(self, host + " run energy = sum of pe/atom", got["vdwl"] + got["coul"],
                         got["sum"], eps)
        # 4 steps of fix nve moved the cells (a stage that ran no steps would pass
        # the other checks)
        self.assertGreater(float(np.max(np.abs(stages["run"]["x"] - stages["init"]["x"]))), 1e-6)

    def check_derivatives(self, model):
        cfg, dim, _ = self.config(model)
        ids, forces = fs.parse_forces(cfg["init_forces"])
        stress = fs.parse_stress(cfg["init_stress"])
        # three atoms (the first, one in the middle, the last ID), every component;
        # a normal and a shear strain
        atoms = [int(ids[0]), int(ids[len(ids) // 2]), int(ids[-1])]
        strains = ["xx", "xy"] if dim == 2 else ["zz", "yz"]
        plan = fs.derivative_plan(atoms, range(dim), strains)
        probe = self.run_lmp(fs.setup_commands(cfg) + fs.thermo() + "run 0 post no\n" +
                             fs.probe("init"))
        lo, hi, tilt, periodic = fs.box_header(probe.path("tess_init.dump"))
        centre = fs.centre_of(cfg) or [0.5 * (a + b) for a, b in zip(lo, hi)]
        run = self.run_lmp(fs.fd_script(cfg, dim, (lo, hi, tilt), periodic, plan, centre))
        values, base = fs.fd_values(run, plan)
        self.assertEqual(len(values), len(atoms) * dim + len(strains))
        self.assertAlmostEqual(base, float(cfg["init_vdwl"]), delta=1e-9 * abs(base))
        bad = fs.check_derivatives(values, stress, ids, forces)
        self.assertFalse(bad, "the stored references are not the energy's derivatives:\n"
                         + "\n".join(bad))

    def check_newton_off(self, model):
        cfg, dim, _ = self.config(model)
        # the YAML's pre_commands force newton on (as LAMMPS's files of such styles);
        # without them the style must refuse newton off
        cfg["pre_commands"] = "\n".join(l for l in fs.lines(cfg["pre_commands"])
                                        if "newton_pair" not in l)
        run = self.run_lmp(fs.setup_commands(cfg, newton=False) + "run 0 post no\n", ok=False)
        self.assertLammpsError(run, "vertex/voronoi", "newton on")

    def check_extract(self, model):
        cfg, dim, eps = self.config(model)
        names = [l.split() for l in fs.lines(cfg["extract"])]
        self.assertTrue(names)
        # fix adapt stops with an error unless extract(name) is a type-pair array
        # (dim 2); scaling by 1 must leave the energy as it was
        script = fs.setup_commands(cfg) + "thermo_modify norm no\nvariable one equal 1.0\n"
        for name, d in names:
            self.assertEqual(d, "2", "fix adapt reaches type-pair arrays only")
            script += ("fix tess_a all adapt 1 pair vertex/voronoi %s * * v_one scale yes "
                       "reset yes\nrun 0 post no\nprint \"TESS_ADAPT %s $(pe:%%.17g)\"\n"
                       "unfix tess_a\n" % (name, name))
        run = self.run_lmp(script)
        got = dict(re.findall(r"^TESS_ADAPT (\w+) (\S+)$", run.stdout, re.M))
        self.assertEqual(sorted(got), sorted(n for n, _ in names))
        for name, value in got.items():
            check_values(self, "energy with fix adapt of %s" % name, float(value),
                         float(cfg["init_vdwl"]), eps)
        bad = self.run_lmp(fs.setup_commands(cfg) + "variable one equal 1.0\n"
                           "fix tess_a all adapt 1 pair vertex/voronoi does_not_exist * * v_one\n"
                           "run 0 post no\n", ok=False)
        self.assertNotEqual(bad.returncode, 0)
        self.assertRegex(bad.output, r"ERROR.*(adapt|does_not_exist)")
        if self.plugin_host:
            self.check_extract_python(cfg, names)

    def check_extract_python(self, cfg, names):
        """Through LAMMPS's library interface (lammps_extract_pair, 29 Aug 2024 on)."""
        code = ("import os\nfrom lammps import lammps\n"
                "lmp = lammps(cmdargs=['-log', 'none', '-screen', 'none', '-nocite'])\n"
                "lmp.commands_string(open('setup.in').read())\n"
                "lmp.command('run 0 post no')\n"
                "for name in %r:\n"
                "    print('DIM', name, lmp.extract_pair_dimension(name))\n"
                "    print('VAL', name, repr(lmp.extract_pair(name)))\n"
                "print('DIM does_not_exist', lmp.extract_pair_dimension('does_not_exist'))\n"
                "print('VAL does_not_exist', lmp.extract_pair('does_not_exist'))\n"
                % [n for n, _ in names])
        d = self.new_dir()
        with open(os.path.join(d, "setup.in"), "w") as f:
            f.write(fs.setup_commands(cfg))
        run = self.run_python(code.replace("open('setup.in')",
                                           "open(%r)" % os.path.join(d, "setup.in")))
        dims = dict(re.findall(r"^DIM (\w+) (\S+)$", run.stdout, re.M))
        for name, dim in names:
            self.assertEqual(dims.get(name), dim, "lammps.extract_pair_dimension(%r)" % name)
        self.assertEqual(dims.get("does_not_exist"), "None")
        values = {n: eval(v) for n, v in re.findall(r"^VAL (\w+) (.+)$", run.stdout, re.M)
                  if n != "does_not_exist"}
        # the values in use: for coefficients in the first form (K A0 Gamma Lambda,
        # and Lambda_IJ between types) the numbers given
        for line in fs.lines(cfg["pair_coeff"]):
            w = line.split()
            if "quadratic" in w:
                continue
            i, j = int(w[0]), int(w[1])
            if i == j:
                k, a0, g, lam = (float(v) for v in w[2:6])
                self.assertEqual(values["kappa"][i][i], k)
                self.assertEqual(values["area0"][i][i], a0)
                self.assertEqual(values["gamma"][i][i], g)
                self.assertEqual(values["lambda"][i][i], lam)
            else:
                self.assertEqual(values["lambda"][i][j], float(w[2]))
                self.assertEqual(values["lambda"][j][i], float(w[2]))


def _add(name, func):
    setattr(ForceStyle, name, func)


for _model in MODELS:
    _add("test_%s_stages" % _model, lambda self, m=_model: self.check_stages(m))
    _add("test_%s_derivatives" % _model, lambda self, m=_model: self.check_derivatives(m))
    _add("test_%s_newton_off" % _model, lambda self, m=_model: self.check_newton_off(m))
    _add("test_%s_extract" % _model, lambda self, m=_model: self.check_extract(m))


class NoFdotr(LammpsTestCase):
    """`pair_modify nofdotr`: the style sums its cells' own virials instead of LAMMPS's
    f dot r, the same virial (the stages check it in serial): on two ranks, where
    each rank sums its own cells; and inside pair_style hybrid/overlay, which then
    asks every sub-style for its virial (before the style honoured nofdotr, its
    share was missing there)."""

    def check(self, model, hybrid=False, nprocs=1):
        cfg, dim, eps = ForceStyle.config(self, model)
        if hybrid:
            cfg["pair_style"] = "hybrid/overlay %s zero 1.0" % cfg["pair_style"]
            cfg["pair_coeff"] = "\n".join(
                ["%s %s vertex/voronoi %s" % tuple(l.split(None, 2)) for l in
                 fs.lines(cfg["pair_coeff"])] + ["* * zero"])
        run = self.run_lmp(fs.setup_commands(cfg) + "pair_modify nofdotr\n" + fs.thermo() +
                           "run 0 post no\n" + fs.probe("nofdotr"), nprocs=nprocs)
        got = fs.read_probes(run)["nofdotr"]
        _, forces = fs.parse_forces(cfg["init_forces"])
        check_values(self, "nofdotr stress", got["stress"], fs.parse_stress(cfg["init_stress"]),
                     eps)
        # (on two ranks the ghost cells' forces are summed in another order: small
        # components differ by more than epsilon relative to themselves)
        np.testing.assert_allclose(got["forces"], forces, rtol=eps, atol=1e-14)
        check_values(self, "nofdotr vdwl", got["vdwl"], float(cfg["init_vdwl"]), eps)


for _model in MODELS:
    setattr(NoFdotr, "test_%s_two_ranks" % _model,
            lmptest.nprocs(2)(lambda self, m=_model: self.check(m, nprocs=2)))
    setattr(NoFdotr, "test_%s_hybrid_overlay" % _model,
            lambda self, m=_model: self.check(m, hybrid=True))


class InTree(LammpsTestCase):
    """The same stages on an lmp with the TESSERA package compiled in."""


def _intree(self, m):
    if not Config.intree_lmp:
        raise unittest.SkipTest("no lmp with the in-tree package (--intree-lmp)")
    ForceStyle.check_stages(self, m, lmp=Config.intree_lmp, host="in-tree")


for _model in MODELS:
    setattr(InTree, "test_%s_stages" % _model, lambda self, m=_model: _intree(self, m))
InTree.config = ForceStyle.config


class Files(unittest.TestCase):
    """The YAML files are LAMMPS's schema, complete and self-consistent."""

    def test_schema(self):
        self.assertEqual(sorted(MODELS), ["3d", "confluent", "finite", "sphere"])
        for model, path in MODELS.items():
            with self.subTest(model=model):
                with open(path) as f:
                    text = f.read()
                keys = re.findall(r"^(\w+):", text, re.M)
                self.assertEqual(tuple(keys), fs.KEYS)
                cfg = fs.read_yaml(path)
                self.assertTrue(os.path.exists(os.path.join(fs.FORCE_DIR, cfg["input_file"])))
                self.assertNotIn("data_file", cfg["pre_commands"])
                data = re.search(r"vertex_model index (\w+)", cfg["pre_commands"])
                self.assertTrue(data and os.path.exists(
                    os.path.join(fs.FORCE_DIR, "data.vertex_" + data.group(1))))
                n = int(cfg["natoms"])
                for key in ("init_forces", "run_forces"):
                    ids, f = fs.parse_forces(cfg[key])
                    np.testing.assert_array_equal(ids, np.arange(1, n + 1))
                for key in ("init_stress", "run_stress"):
                    self.assertEqual(len(fs.parse_stress(cfg[key])), 6)
                self.assertRegex(cfg["lammps_version"], r"^\d+ \w+ \d{4}$")
                self.assertGreater(float(cfg["epsilon"]), 0.0)
                try:
                    import yaml
                except ImportError:
                    continue
                # a YAML parser reads what LAMMPS's tester reads
                parsed = yaml.safe_load(text)
                self.assertEqual(list(parsed), list(fs.KEYS))
                self.assertAlmostEqual(float(parsed["init_vdwl"]), float(cfg["init_vdwl"]))
                self.assertEqual(len(parsed["init_forces"].strip().split("\n")), n)


if __name__ == "__main__":
    lmptest.main()
