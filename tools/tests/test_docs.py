# SPDX-License-Identifier: GPL-2.0-or-later
"""The repository's documentation stands on its own: no doc (nor a study script that writes
a report) points outside the repository (a "SPEC" section, a seed path, ../shared, absolute
paths of the machine it was written on under /work), and every relative Markdown link resolves to a file
of the repository."""

import glob
import os
import re
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# what a doc must not mention: the external contract, the thesis's file, outside paths
# and the project's issue tracker, which a reader of the repository does not have ("issue 5")
OUTSIDE = re.compile(r"\bSPEC\b|SPEC\.md|\bseed/|shared/seed|\.\./shared|/work/|\b[Ii]ssues?[- ]?#?\d")


def doc_files():
    patterns = ["README.md", "doc/*", "examples/*/README.md", "studies/*.md", "studies/*/*.md",
                "studies/*/run", "studies/*/boundary", "studies/*.py", "tools/README.md",
                "lammps/README.md", "bench/*.md", "bench/run", "bench/run3d", "bench/disordered2d",
                "tools/pyproject.toml"]
    files = sorted({f for p in patterns for f in glob.glob(os.path.join(ROOT, p)) if os.path.isfile(f)})
    assert files, "no documentation found under " + ROOT
    return files


class SelfContained(unittest.TestCase):

    def test_no_reference_outside_the_repository(self):
        bad = []
        for path in doc_files():
            with open(path, errors="replace") as f:
                for n, line in enumerate(f, 1):
                    if OUTSIDE.search(line):
                        bad.append(f"{os.path.relpath(path, ROOT)}:{n}: {line.strip()[:100]}")
        self.assertEqual(bad, [], "docs point outside the repository:\n" + "\n".join(bad))

    def test_pattern_catches(self):
        for text in ("see SPEC section 4", "(SPEC 7)", "shared/seed/000.txt", "../shared/SPEC.md",
                     "(issue 14)", "Issue #5", "the issue-5 yardstick"):
            self.assertTrue(OUTSIDE.search(text), text)
        for text in ("fix polarity ... seed 12345", "random seed", "specification",
                     "a known issue of the model"):
            self.assertFalse(OUTSIDE.search(text), text)

    def test_relative_links_resolve(self):
        link = re.compile(r"\]\(([^)\s]+)\)")
        bad = []
        for path in doc_files():
            if not path.endswith(".md"):
                continue
            with open(path) as f:
                text = f.read()
            for target in link.findall(text):
                if re.match(r"[a-z]+:", target) or target.startswith("#"):
                    continue
                # studies/GALLERY.md is the README's gallery section, with the README's links
                base = ROOT if os.path.basename(path) == "GALLERY.md" else os.path.dirname(path)
                where = os.path.normpath(os.path.join(base, target.split("#")[0]))
                if not where.startswith(ROOT) or not os.path.exists(where):
                    bad.append(f"{os.path.relpath(path, ROOT)}: {target}")
        self.assertEqual(bad, [], "broken or outside links:\n" + "\n".join(bad))


if __name__ == "__main__":
    unittest.main()
