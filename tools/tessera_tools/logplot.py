# SPDX-License-Identifier: GPL-2.0-or-later
"""Thermo output of LAMMPS log files: parse and plot against time.

A thermo block starts at a header line whose first word is ``Step`` and runs
until ``Loop time`` (or the end of the file, for a run that died).  Lines inside
a block that are not rows of numbers (warnings, messages) are skipped.  Each
block is one run; :meth:`Log.combined` concatenates the runs, dropping the row a
continuing run repeats (its first step equals the previous run's last step).
Time comes from a ``Time`` column if there is one, else from Step and the value
of the last ``timestep`` command echoed before the run.
"""

import math
import os
import re

import numpy as np

BOOKKEEPING = {"Step", "Time", "CPU", "Elapsed", "Elaplong", "Dt", "CPULeft", "TpCPU", "SpCPU",
               "Part", "Atoms", "Cella", "Cellb", "Cellc", "Lx", "Ly", "Lz", "Xlo", "Xhi",
               "Ylo", "Yhi", "Zlo", "Zhi", "Volume"}

LABELS = {"PotEng": "potential energy", "E_pair": "pair energy", "TotEng": "total energy",
          "KinEng": "kinetic energy", "Temp": "temperature", "Press": "pressure"}

_TIMESTEP = re.compile(r"^\s*timestep\s+(\S+)")


class Run:
    """One thermo block: ``run['Step']`` -> array, ``run.dt`` (None if unknown)."""

    def __init__(self, names, rows, dt, complete):
        self.names = names
        table = np.array(rows, dtype=float).reshape(len(rows), len(names))
        self.columns = {name: table[:, k] for k, name in enumerate(names)}
        self.dt = dt
        self.complete = complete

    def __getitem__(self, name):
        return self.columns[name]

    def __contains__(self, name):
        return name in self.columns

    def __len__(self):
        return len(self.columns["Step"])


class Log:
    def __init__(self, path, runs):
        self.path = path
        self.runs = runs

    @property
    def names(self):
        out = []
        for run in self.runs:
            out += [n for n in run.names if n not in out]
        return out

    def combined(self):
        """Columns over all runs (NaN where a run lacks a column) plus ``time`` (NaN if unknown)."""
        names = self.names
        parts = {name: [] for name in names}
        times = []
        last_step, last_time = None, None
        for run in self.runs:
            steps = run["Step"]
            start = 1 if (last_step is not None and len(steps) and steps[0] == last_step) else 0
            if "Time" in run:
                t = run["Time"]
            elif run.dt is not None:
                if last_step is not None and last_time is not None and steps[0] >= last_step:
                    t = last_time + (steps - last_step) * run.dt
                else:
                    t = steps * run.dt
            else:
                t = np.full(len(steps), np.nan)
            for name in names:
                col = run[name] if name in run else np.full(len(steps), np.nan)
                parts[name].append(col[start:])
            times.append(t[start:])
            if len(steps):
                last_step, last_time = steps[-1], t[-1]
                if np.isnan(last_time):
                    last_time = None
        out = {name: np.concatenate(parts[name]) if parts[name] else np.zeros(0) for name in names}
        out["time"] = np.concatenate(times) if times else np.zeros(0)
        return out


def _numbers(tokens):
    try:
        return [float(t) for t in tokens]
    except ValueError:
        return None


def parse_log(path):
    """Parse a LAMMPS log file into a :class:`Log` with one :class:`Run` per thermo block."""
    runs = []
    dt = None
    names, rows = None, []
    with open(path, "r", errors="replace") as f:
        for line in f:
            tokens = line.split()
            if names is None:
                m = _TIMESTEP.match(line)
                if m:
                    try:
                        dt = float(m.group(1))
                    except ValueError:
                        pass
                if tokens and tokens[0] == "Step" and _numbers(tokens) is None:
                    names, rows = tokens, []
                continue
            if line.startswith("Loop time"):
                runs.append(Run(names, rows, dt, True))
                names = None
                continue
            if len(tokens) == len(names):
                values = _numbers(tokens)
                if values is not None:
                    rows.append(values)
            elif tokens and tokens[0] == "Step" and _numbers(tokens) is None:
                # a new header without "Loop time": the previous run was cut short
                runs.append(Run(names, rows, dt, False))
                names, rows = tokens, []
    if names is not None:
        runs.append(Run(names, rows, dt, False))
    if not runs:
        raise ValueError(f"{path}: no thermo output (no header line starting with 'Step')")
    return Log(path, runs)


def default_columns(logs, limit=6):
    names = []
    for log in logs:
        names += [n for n in log.names if n not in BOOKKEEPING and n not in names]
    return names[:limit]


def plot_logs(logs, out, columns=None, labels=None, x="auto", refs=None, dpi=150, title=None,
              legend=None, logy=()):
    """One panel per column against time (or Step); each log is one line per panel.

    ``columns``: list of (name, axis label or None); ``refs``: dict name -> reference value
    drawn as a grey horizontal line (e.g. an analytical minimum, or 3.81 for the shape index).
    """
    import matplotlib.pyplot as plt

    columns = columns or [(name, None) for name in default_columns(logs)]
    if not columns:
        raise ValueError("no columns to plot (use --list to see what the log has)")
    data = [log.combined() for log in logs]
    use_time = x == "time" or (x == "auto" and all(np.isfinite(d["time"]).all() and len(d["time"]) for d in data))
    if x == "time" and not use_time:
        raise ValueError("time unknown: the log has no Time column and no 'timestep' command echo")
    fig, axes = plt.subplots(len(columns), 1, sharex=True, figsize=(7, 1.2 + 2.2 * len(columns)), squeeze=False)
    legend = legend or [os.path.basename(log.path) for log in logs]
    for ax, (name, label) in zip(axes[:, 0], columns):
        plotted = False
        for d, lab in zip(data, legend):
            if name not in d:
                continue
            xs = d["time"] if use_time else d["Step"]
            ax.plot(xs, d[name], lw=1.2, label=lab)
            plotted = True
        if not plotted:
            raise KeyError(f"column '{name}' is in none of the logs (columns: {' '.join(logs[0].names)})")
        if refs and name in refs:
            ax.axhline(refs[name], color="0.55", lw=1.5, zorder=0)
        if name in logy:
            ax.set_yscale("log")
        ax.set_ylabel(label or LABELS.get(name, name))
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("time" if use_time else "step")
    if len(logs) > 1:
        axes[0, 0].legend(fontsize=8)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=dpi)
    plt.close(fig)


def write_csv(log, out):
    d = log.combined()
    names = ["time"] + log.names
    with open(out, "w") as f:
        f.write(",".join(names) + "\n")
        for row in zip(*(d[n] for n in names)):
            f.write(",".join("" if (isinstance(v, float) and math.isnan(v)) else f"{v:.10g}" for v in row) + "\n")
