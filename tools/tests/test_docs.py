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


def _minutes(text):
    """The largest time in a runtime cell such as '5 min idle, 11 min shared', '30 s', '1 h', in minutes."""
    unit = {"s": 1 / 60, "min": 1.0, "h": 60.0}
    found = [float(v.split("-")[-1]) * unit[u] for v, u in re.findall(r"([0-9.]+(?:-[0-9.]+)?) ?(s|min|h)\b", text)]
    return max(found) if found else None


def gallery_rows(path):
    with open(path) as f:
        text = f.read()
    rows = {}
    for line in text.splitlines():
        m = re.match(r"\| `(studies/[^`]+)` \| ([^|]+) \| (.+) \|$", line)
        if m:
            rows[m.group(1)] = (m.group(2).strip(), m.group(3).strip())
    return rows


class StatedRuntimes(unittest.TestCase):
    """The runtimes the README and the gallery state are the same, and none is below what the
    study's own report measured (its 'Runtime: N s wall', or for runs one at a time the sum of
    their wall times)."""

    def test_readme_table_is_the_gallery(self):
        self.assertEqual(gallery_rows(os.path.join(ROOT, "README.md")),
                         gallery_rows(os.path.join(ROOT, "studies", "GALLERY.md")))

    def test_not_below_the_reports(self):
        rows = gallery_rows(os.path.join(ROOT, "studies", "GALLERY.md"))
        self.assertGreater(len(rows), 5)
        low = []
        for command, (runtime, link) in rows.items():
            report = os.path.join(ROOT, re.search(r"\]\(([^)]+)\)", link).group(1))
            with open(report) as f:
                text = " ".join(f.read().split())
            measured = [float(v) / 60 for v in re.findall(r"Runtime: ([0-9.]+) s wall", text)]
            if re.search(r"with 1 LAMMPS runs side by side", text):
                measured += [float(v) for v in re.findall(r"took ([0-9.]+) min of wall time in all", text)]
            stated = _minutes(runtime)
            self.assertIsNotNone(stated, f"{command}: no time in '{runtime}'")
            if measured and stated < max(measured):
                low.append(f"{command}: states '{runtime}', its report measured {max(measured):.1f} min")
        self.assertEqual(low, [], "\n".join(low))

    def test_minutes(self):
        self.assertEqual(_minutes("5 min idle, 11 min shared"), 11)
        self.assertEqual(_minutes("30 s"), 0.5)
        self.assertEqual(_minutes("1.5-4 min"), 4)
        self.assertEqual(_minutes("10 min idle, 1 h shared"), 60)


if __name__ == "__main__":
    unittest.main()
