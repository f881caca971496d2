# SPDX-License-Identifier: GPL-2.0-or-later
"""Shared plumbing of the reproduction studies (studies/*/run).

Each study is one executable script that writes LAMMPS inputs, runs them with
tessera-lmp (several serial runs side by side), analyses the output with numpy
and tools/tessera_tools, and writes PNGs and a markdown report.  Full runs write
their raw output to studies/<name>/out/ (git-ignored) and the committed
REPORT.md and figures/*.png next to the script; ``--quick`` runs a tiny version
into studies/<name>/out/quick/ and leaves the committed files alone.
"""

import argparse
import concurrent.futures
import json
import os
import resource
import shutil
import subprocess
import sys
import time

import numpy as np

STUDIES = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(STUDIES)
sys.path.insert(0, os.path.join(ROOT, "tools"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401

from tessera_tools.logplot import parse_log  # noqa: E402,F401

#: committed PNGs should stay below this size (README gallery; the limit is 200 KB)
MAX_PNG_BYTES = 180 * 1024
#: resolution of the raster parts of the vector (PDF) copies
PRINT_DPI = 300

#: axis labels with the model's reduced units (doc/model.md, Units)
TIME = r"time $t$ ($\gamma_T/(K A_0)$)"
ENERGY_UNIT = r"($K A_0^2$)"
LENGTH_UNIT = r"($\sqrt{A_0}$)"
AREA_UNIT = r"($A_0$)"


def _data_axes(fig):
    """The axes that show data: not colour bars, not switched off."""
    return [ax for ax in fig.axes if ax.axison and ax.get_visible() and ax.get_label() != "<colorbar>"
            and not hasattr(ax, "_colorbar") and ax.get_navigate()]


def panel_letters(fig):
    """Bold a, b, c ... at the top left of each data panel of a figure with several panels."""
    axes = [ax for ax in _data_axes(fig) if getattr(ax, "get_subplotspec", lambda: None)() is not None]
    if len(axes) < 2:
        return
    for k, ax in enumerate(axes):
        ax.text(-0.02, 1.02, "abcdefghijklmnopqrstuvwxyz"[k], transform=ax.transAxes, fontweight="bold",
                fontsize=12, ha="right", va="bottom")


def _overlap(ax, legend, renderer):
    """How many sampled points of the axes' lines fall inside the legend's box."""
    box = legend.get_window_extent(renderer)
    count = 0
    for line in ax.get_lines():
        xy = line.get_transform().transform(np.column_stack([line.get_xdata(orig=False),
                                                             line.get_ydata(orig=False)]).astype(float))
        xy = xy[np.all(np.isfinite(xy), axis=1)]
        if len(xy) > 1:    # sample each segment, so lines crossing the box count
            t = np.linspace(0.0, 1.0, 12)[:, None, None]
            xy = (xy[:-1][None] * (1 - t) + xy[1:][None] * t).reshape(-1, 2)
        inside = ((xy[:, 0] > box.x0) & (xy[:, 0] < box.x1) & (xy[:, 1] > box.y0) & (xy[:, 1] < box.y1))
        count += int(np.count_nonzero(inside))
    return count


def place_legends(fig):
    """Each legend where it covers no line: matplotlib's 'best' spot inside the axes if that is
    free, otherwise outside, below the axes."""
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        legend = ax.get_legend()
        if legend is None:
            continue
        legend._loc = 0    # 'best' (matplotlib 3.6 has no Legend.set_loc)
        fig.canvas.draw()
        if _overlap(ax, legend, renderer) == 0:
            continue
        # below the axes' tick labels and x label
        legend.set_visible(False)
        bottom = ax.get_tightbbox(renderer).y0
        legend.set_visible(True)
        y = ax.transAxes.inverted().transform((0.0, bottom))[1]
        legend.set_bbox_to_anchor((0.5, y - 0.02), transform=ax.transAxes)
        legend._loc = 9    # 'upper center'
        moved = True
    if locals().get("moved"):
        # make room for the legends now below their axes
        fig.tight_layout()
    fig.canvas.draw()


def find_lmp(explicit=None):
    """The tessera-lmp executable: --lmp, $TESSERA_LMP, $TESSERA_BUILD/lammps, build/lammps."""
    candidates = [explicit, os.environ.get("TESSERA_LMP")]
    if os.environ.get("TESSERA_BUILD"):
        candidates.append(os.path.join(os.environ["TESSERA_BUILD"], "lammps", "tessera-lmp"))
    candidates.append(os.path.join(ROOT, "build", "lammps", "tessera-lmp"))
    for path in candidates:
        if path and os.path.isfile(path):
            return os.path.abspath(path)
    raise SystemExit("tessera-lmp not found: build it with scripts/build, or pass --lmp PATH "
                     "(or set TESSERA_LMP)")


class Study:
    """Command line, directories and LAMMPS runs of one study."""

    def __init__(self, name, description, argv=None, extra_args=None):
        parser = argparse.ArgumentParser(prog=f"studies/{name}/run", description=description)
        parser.add_argument("--quick", action="store_true",
                            help="tiny version (seconds) into out/quick/; committed files untouched")
        parser.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1),
                            help="serial LAMMPS runs side by side (default 2)")
        parser.add_argument("--lmp", help="tessera-lmp executable (default: build/lammps/tessera-lmp)")
        parser.add_argument("--out", help="write everything (runs, report, figures) under this directory "
                                              "instead of studies/<name>/out[/quick] (used by ctest)")
        parser.add_argument("--analyse-only", action="store_true",
                            help="reuse the LAMMPS output already in out/ (no runs)")
        parser.add_argument("--resume", action="store_true",
                            help="do not repeat a run whose input script in out/ is unchanged: reuse its "
                                 "log if it completed, report it as failed again if LAMMPS stopped on an "
                                 "error (interrupted runs are run again)")
        if extra_args:
            extra_args(parser)
        self.args = parser.parse_args(argv)
        self.name = name
        self.quick = self.args.quick
        self.here = os.path.join(STUDIES, name)
        self.out = os.path.join(self.here, "out", "quick") if self.quick else os.path.join(self.here, "out")
        if self.args.out:
            self.out = os.path.abspath(self.args.out)
        # in quick mode (or with --out) the "committed" files also go to the output directory
        separate = self.quick or self.args.out
        self.figures = os.path.join(self.out, "figures") if separate else os.path.join(self.here, "figures")
        self.report_path = os.path.join(self.out if separate else self.here, "REPORT.md")
        os.makedirs(self.out, exist_ok=True)
        os.makedirs(self.figures, exist_ok=True)
        self.lmp = None if self.args.analyse_only else find_lmp(self.args.lmp)
        self.started = time.time()
        self.machine = machine()

    # ----------------------------------------------------------------- runs
    def run_lammps(self, workdir, script, variables=None, log="log.lammps", timeout=3600):
        """Write ``script`` to workdir/in.lmp and run it serially; returns the log path.

        Raises RuntimeError with the tail of the log when LAMMPS fails.
        """
        os.makedirs(workdir, exist_ok=True)
        log_path = os.path.join(workdir, log)
        if self.args.analyse_only:
            return log_path
        in_path = os.path.join(workdir, "in.lmp")
        if getattr(self.args, "resume", False) and os.path.exists(in_path) and os.path.exists(log_path):
            with open(in_path) as f:
                same = f.read() == script
            if same:
                with open(log_path, errors="replace") as f:
                    lines = f.readlines()
                if any(line.startswith("Total wall time") for line in lines):
                    return log_path
                if any(line.startswith("ERROR") for line in lines):
                    raise RuntimeError(f"LAMMPS failed in {workdir} (earlier run, reused by --resume):\n"
                                       + "".join(lines[-15:]))
                # neither finished nor failed (interrupted): run it again
        with open(in_path, "w") as f:
            f.write(script)
        cmd = [self.lmp, "-in", "in.lmp", "-log", log, "-screen", "none", "-nocite"]
        for key, value in (variables or {}).items():
            cmd += ["-var", key, str(value)]
        # another developer may be relinking the shared build: retry a missing binary
        for attempt in range(20):
            if os.access(self.lmp, os.X_OK):
                break
            time.sleep(3)
        proc = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              timeout=timeout)
        if proc.returncode != 0:
            tail = ""
            if os.path.exists(log_path):
                with open(log_path, errors="replace") as f:
                    tail = "".join(f.readlines()[-15:])
            raise RuntimeError(f"LAMMPS failed in {workdir} (exit {proc.returncode}):\n"
                               f"{proc.stdout.decode(errors='replace')[-2000:]}\n{tail}")
        return log_path

    def run_all(self, jobs):
        """Run a list of (workdir, script, variables) side by side; returns the log paths
        (None and an entry in ``self.failures`` for runs that failed)."""
        self.failures = getattr(self, "failures", [])
        logs = [None] * len(jobs)
        progress = self.progress(len(jobs))
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, self.args.jobs)) as pool:
            futures = {pool.submit(self.run_lammps, *job): k for k, job in enumerate(jobs)}
            for fut in concurrent.futures.as_completed(futures):
                k = futures[fut]
                try:
                    logs[k] = fut.result()
                except RuntimeError as err:
                    self.failures.append((jobs[k][0], str(err)))
                    progress.write(f"[{self.name}] run failed: {jobs[k][0]}")
                progress.update(1)
        progress.close()
        return logs

    def progress(self, total):
        """A progress bar on stderr over ``total`` LAMMPS runs (done, elapsed, estimated time left):
        tqdm (Debian's python3-tqdm); without it, one line per finished run."""
        try:
            from tqdm import tqdm
        except ImportError:
            return _Lines(self.name, total)
        tty = sys.stderr.isatty()
        return tqdm(total=total, desc=f"[{self.name}] LAMMPS runs ({self.args.jobs} side by side)", unit="run",
                    file=sys.stderr, mininterval=1.0 if tty else 30.0, dynamic_ncols=tty, ascii=not tty)

    # -------------------------------------------------------------- output
    def savefig(self, fig, filename, dpi=150, commit=True, letters=True):
        """Save into figures/ (committed) or out/: the PNG at ``dpi`` (the gallery's picture;
        never lowered behind the caller's back: a PNG over the gallery's size limit is reported)
        and a vector PDF next to it for print (rasterised parts at PRINT_DPI).  Before saving,
        multi-panel figures get panel letters and legends are moved off the data."""
        path = os.path.join(self.figures if commit else self.out, filename)
        if letters:
            panel_letters(fig)
        place_legends(fig)
        fig.savefig(path, dpi=dpi, bbox_inches="tight", pad_inches=0.05)
        vector = os.path.splitext(path)[0] + ".pdf"
        fig.savefig(vector, dpi=PRINT_DPI, bbox_inches="tight", pad_inches=0.05)
        size = os.path.getsize(path)
        note = ""
        if commit and size > MAX_PNG_BYTES and path.endswith(".png"):
            # same pixels, fewer bytes: a 256-colour palette (plots have few colours)
            try:
                from PIL import Image

                with Image.open(path) as im:
                    small = im.convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT)
                small.save(path, optimize=True)
                size = os.path.getsize(path)
                note = " (256-colour palette)"
            except ImportError:
                pass
        if commit and size > MAX_PNG_BYTES:
            note += f" (over the gallery's {MAX_PNG_BYTES // 1024} KB: pass a lower dpi explicitly)"
        print(f"[{self.name}] {os.path.basename(path)}: {dpi} dpi, {size // 1024} KB{note}; "
              f"{os.path.basename(vector)}: {os.path.getsize(vector) // 1024} KB")
        plt.close(fig)
        return path

    def rel(self, path):
        """Path relative to the report (for links)."""
        return os.path.relpath(path, os.path.dirname(self.report_path))

    def elapsed(self):
        return time.time() - self.started

    def provenance(self):
        """Which source the executable was built from, when it lives in a git checkout's build tree."""
        if not self.lmp:
            return None
        d = os.path.dirname(self.lmp)
        while d != os.path.dirname(d):
            if os.path.exists(os.path.join(d, ".git")):
                try:
                    head = subprocess.run(["git", "-C", d, "log", "-1", "--format=%h %cd", "--date=short"],
                                          capture_output=True, text=True, check=True).stdout.strip()
                    dirty = subprocess.run(["git", "-C", d, "status", "--porcelain", "--", "core", "lammps"],
                                           capture_output=True, text=True, check=True).stdout.strip()
                except (OSError, subprocess.CalledProcessError):
                    return None
                return f"tessera-lmp built from commit {head}" + (
                    " with uncommitted changes in core/ or lammps/" if dirty else "")
            d = os.path.dirname(d)
        return None

    def runtime_text(self):
        """One line on how long the study took; an --analyse-only rerun quotes the last real run."""
        path = os.path.join(self.out, "runtime.json")
        if self.args.analyse_only:
            try:
                with open(path) as f:
                    info = json.load(f)
            except OSError:
                return "Runtime: unknown (report regenerated from existing output)."
        else:
            info = dict(wall=self.elapsed(), cpu=self.child_cpu(), jobs=self.args.jobs, source=self.provenance(),
                        machine=self.machine)
            with open(path, "w") as f:
                json.dump(info, f)
        source = f" ({info['source']})" if info.get("source") else ""
        machine = f" on {info['machine']}" if info.get("machine") else ""
        return (f"Runtime: {info['wall']:.0f} s wall with {info['jobs']} LAMMPS runs side by side{machine}, "
                f"{info['cpu']:.0f} s CPU in LAMMPS{source}.")

    def write_report(self, text):
        with open(self.report_path, "w") as f:
            f.write(text)
        print(f"[{self.name}] wrote {self.report_path} and {len(os.listdir(self.figures))} figures "
              f"in {self.elapsed():.0f} s wall, {self.child_cpu():.0f} s CPU in LAMMPS")

    @staticmethod
    def child_cpu():
        """CPU seconds used by finished child processes (the LAMMPS runs)."""
        ru = resource.getrusage(resource.RUSAGE_CHILDREN)
        return ru.ru_utime + ru.ru_stime


def machine():
    """The machine a study ran on, for its stated runtime: CPU model, core count and the load
    average when the study started (other jobs sharing the cores slow the runs down)."""
    model = ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    cores = os.cpu_count() or 1
    try:
        load = f", load average {os.getloadavg()[0]:.1f} at the start"
    except OSError:
        load = ""
    return f"{model + ', ' if model else ''}{cores} core{'s' if cores != 1 else ''}{load}"


class _Lines:
    """The part of tqdm's interface run_all uses, as one stderr line per finished run."""

    def __init__(self, name, total):
        self.name, self.total, self.done, self.start = name, total, 0, time.time()

    def write(self, text):
        print(text, file=sys.stderr, flush=True)

    def update(self, n):
        self.done += n
        took = time.time() - self.start
        left = took / self.done * (self.total - self.done)
        self.write(f"[{self.name}] {self.done}/{self.total} LAMMPS runs done, {took:.0f} s, about {left:.0f} s left")

    def close(self):
        pass


def md_table(header, rows):
    """A markdown table from a header list and rows of already formatted cells."""
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def fit_power(x, y):
    """Least-squares slope and prefactor of log y = log c + p log x; (nan, nan) if < 2 points."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = (x > 0) & (y > 0) & np.isfinite(y)
    if ok.sum() < 2:
        return float("nan"), float("nan")
    p, logc = np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)
    return float(p), float(np.exp(logc))


def copy_if_exists(src, dst):
    if os.path.exists(src):
        shutil.copy(src, dst)


# ------------------------------------------------------------ shared analysis
def msd_curve(pos, every, max_fraction=0.5):
    """Time-origin averaged mean squared displacement of unwrapped positions ``pos`` (frames x
    atoms x dims), centre-of-mass drift removed, at lags of 1 .. max_fraction * frames frames
    ``every`` time units apart; returns (lag times, MSD)."""
    pos = np.asarray(pos, float)
    pos = pos - pos.mean(axis=1, keepdims=True)
    f = len(pos)
    lags = np.arange(1, max(2, int(f * max_fraction)) + 1)
    lags = lags[lags < f]
    msd = np.array([np.mean(np.sum((pos[l:] - pos[:-l]) ** 2, axis=2)) for l in lags])
    return lags * every, msd


def fit_diffusivity(tau, msd, from_fraction=0.25):
    """D from a straight-line fit MSD = a + 2 d D tau (d = 2) over lags >= from_fraction * the
    longest lag."""
    tau, msd = np.asarray(tau, float), np.asarray(msd, float)
    sel = tau >= from_fraction * tau[-1]
    slope, _ = np.polyfit(tau[sel], msd[sel], 1)
    return float(slope / 4.0)


def msd_exponent(tau, msd, from_fraction=0.25):
    """Log-log slope of the MSD over lags >= from_fraction * the longest (1: diffusive, 0: caged)."""
    tau, msd = np.asarray(tau, float), np.asarray(msd, float)
    sel = tau >= from_fraction * tau[-1]
    slope, _ = np.polyfit(np.log(tau[sel]), np.log(np.maximum(msd[sel], 1e-300)), 1)
    return float(slope)


def rise_through(x, y, level, log_x=False, log_y=True):
    """x where y rises through ``level`` for good: the last upward crossing (y[i] < level <= y[j]
    for every j > i), interpolated linearly in (log) x and (log) y; nan when y never stays above
    ``level`` or is above it everywhere."""
    x, y = list(x), list(y)
    for i in range(len(y) - 2, -1, -1):
        if y[i] < level:
            if not all(v >= level for v in y[i + 1:]):
                return float("nan")
            fx = (lambda v: np.log(v)) if log_x else (lambda v: v)
            fy = (lambda v: np.log(max(v, 1e-300))) if log_y else (lambda v: v)
            a, b = fy(y[i]), fy(y[i + 1])
            t = (fy(level) - a) / (b - a)
            xi = fx(x[i]) + t * (fx(x[i + 1]) - fx(x[i]))
            return float(np.exp(xi)) if log_x else float(xi)
    return float("nan")
