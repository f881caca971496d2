#!/usr/bin/python3
# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Citation reminders through LAMMPS's CiteMe (lammps/tessera_citations.h): a run of
pair_style vertex/voronoi names the thesis and the publication of the model it uses,
and no other model's: the first line of each on the screen, the BibTeX entry in the
log file and in the file of `-cite FILE`.  fix polarity registers the thesis too,
which LAMMPS prints once.  `-nocite` runs without any (LAMMPS has no CiteMe then).
The systems are those of the force-style tests (tests/lammps/force-styles)."""

import force_styles as fs
import lmptest
from lmptest import LammpsTestCase

THESIS = ("Vertex modeling of confluent cellular networks within a molecular dynamics "
          "framework in LAMMPS", "@Misc{TesseraThesis,")
PAPERS = {"voronoi_2d": ("doi:10.1103/PhysRevX.6.021011", "@Article{Bi16,"),
          "voronoi_3d": ("doi:10.1088/1367-2630/aaaa13", "@Article{Merkel18,"),
          "voronoi_finite": ("doi:10.1103/PhysRevE.98.042418", "@Article{Teomy18,")}
# model (force-style YAML) -> its publication
MODEL_PAPER = {"confluent": "voronoi_2d", "sphere": "voronoi_2d", "3d": "voronoi_3d",
               "finite": "voronoi_finite"}


class Citations(LammpsTestCase):

    def script(self, model, extra=""):
        cfg = fs.read_yaml(fs.models()[model])
        return fs.setup_commands(cfg) + extra + "run 0 post no\nrun 0 post no\n"

    def check_model(self, model):
        run = self.run_lmp(self.script(model), args=["-cite", "cite.bib"])
        log, bib = run.text("log.lammps"), run.text("cite.bib")
        for name, (line, entry) in [("thesis", THESIS)] + list(PAPERS.items()):
            wanted = name == "thesis" or name == MODEL_PAPER[model]
            with self.subTest(citation=name):
                # LAMMPS prints a citation once, however often it is registered
                # (two runs, and pair_style's init at each)
                self.assertEqual(run.stdout.count(line), 1 if wanted else 0, run.stdout[-3000:])
                self.assertEqual(bib.count(entry), 1 if wanted else 0, bib)
                self.assertEqual(log.count(line), 1 if wanted else 0)

    def test_confluent(self):
        self.check_model("confluent")

    def test_finite(self):
        self.check_model("finite")

    def test_3d(self):
        self.check_model("3d")

    def test_sphere(self):
        self.check_model("sphere")

    def test_log_has_bibtex(self):
        # without -cite, LAMMPS writes the BibTeX entries to the log file
        run = self.run_lmp(self.script("confluent"))
        log = run.text("log.lammps")
        self.assertIn(THESIS[1], log)
        self.assertIn(PAPERS["voronoi_2d"][1], log)
        self.assertNotIn(THESIS[1], run.stdout)

    def test_fix_polarity_once(self):
        # fix polarity registers the thesis as well; it is printed once
        run = self.run_lmp(lmptest.tissue(4, 3) + """
displace_atoms all random 0.1 0.1 0 4821 units box
set group all dipole/random 331 1.0
pair_style vertex/voronoi 3.0
pair_coeff * * 1.0 1.0 0.1 -0.5
fix p all polarity 0.2 1.0
run 0 post no
""")
        self.assertEqual(run.stdout.count(THESIS[0]), 1, run.stdout[-3000:])

    def test_nocite(self):
        run = self.run_lmp(self.script("finite"), args=["-nocite"])
        self.assertNotIn("CITE-CITE", run.stdout)
        self.assertNotIn(THESIS[0], run.stdout + run.text("log.lammps"))


if __name__ == "__main__":
    lmptest.main()
