# SPDX-License-Identifier: GPL-2.0-or-later
"""Lineage trees of a growing tissue from the event logs of fix cell/divide and fix cell/death.

The logs (keyword ``file`` of either fix) hold one line per event::

    step time event id daughter1 daughter2 x y z

``divide``: cell ``id`` divided; its daughters are ``daughter1`` (which keeps the
mother's atom ID) and ``daughter2`` (a new ID); they exist from ``step`` on (the
dump of that step shows them, the one before shows the mother at ``x y z``).
``death``: cell ``id`` was removed at ``step`` (daughters 0).

A *cell* here is one life of an atom ID: from its birth (a division, or the start)
to its division, death, or the end.  Since the daughter that keeps the mother's atom
ID is a new cell, cells are named ``ID`` for the cells of the start and
``ID@STEP`` for the cells born at STEP.  Every cell gets its generation (0 at the
start), its mother and its root (the cell of the start it descends from).
"""

import numpy as np


class LineageError(ValueError):
    pass


class Event:
    __slots__ = ("step", "time", "kind", "id", "d1", "d2", "pos", "where")

    def __init__(self, step, time, kind, cid, d1, d2, pos, where):
        self.step, self.time, self.kind, self.id, self.d1, self.d2 = step, time, kind, cid, d1, d2
        self.pos, self.where = pos, where


def read_events(paths):
    """The events of one or more logs, in the order they happened: by step; at one step the
    divisions first, then the deaths (a cell that both fixes picked at one step died after
    dividing if there is a division line: had the death come first, the division would not
    have happened, nor been logged, so the death is its daughter's that kept the atom ID);
    then by cell ID."""
    if isinstance(paths, str):
        paths = [paths]
    events = []
    for path in paths:
        with open(path) as f:
            for k, line in enumerate(f, start=1):
                w = line.split()
                if not w or w[0].startswith("#"):
                    continue
                where = f"{path}:{k}"
                if len(w) != 9 or w[2] not in ("divide", "death"):
                    raise LineageError(f"{where}: expected 'step time divide|death id daughter1 daughter2 x y z' "
                                       f"(an event log of fix cell/divide or cell/death, keyword file), got {line.strip()!r}")
                try:
                    ev = Event(int(w[0]), float(w[1]), w[2], int(w[3]), int(w[4]), int(w[5]),
                               tuple(float(v) for v in w[6:9]), where)
                except ValueError:
                    raise LineageError(f"{where}: unreadable number in {line.strip()!r}") from None
                events.append(ev)
    events.sort(key=lambda e: (e.step, 0 if e.kind == "divide" else 1, e.id))
    return events


class Cell:
    __slots__ = ("name", "id", "birth_step", "birth_time", "end_step", "end_time", "fate", "generation",
                 "mother", "daughters", "root", "position")

    def __init__(self, name, cid, step, time, generation, mother, root):
        self.name, self.id, self.birth_step, self.birth_time = name, cid, step, time
        self.end_step = self.end_time = None
        self.fate = "alive"
        self.generation, self.mother, self.daughters, self.root = generation, mother, [], root
        self.position = None


class Lineage:
    """The cells of a lineage, by name, with the roots in ID order.

    events: from read_events.  start_ids: the atom IDs of the cells at the start (e.g. the
    first frame of a dump); without them the roots are the cells whose first event is in the
    log, so cells with no event at all are missing (the tree's leaves are then not every cell).
    start_step, start_time: of the start (default: 0).
    """

    def __init__(self, events, start_ids=None, start_step=0, start_time=0.0):
        self.cells = {}
        self.roots = []
        self.complete = start_ids is not None
        self.start_step, self.start_time = start_step, start_time
        self.last_step, self.last_time = start_step, start_time
        alive = {}    # atom ID -> the cell living under it now
        for i in sorted(int(v) for v in (start_ids if start_ids is not None else ())):
            if i in alive:
                raise LineageError(f"atom ID {i} is twice among the cells of the start")
            alive[i] = self._root(i)
        for ev in events:
            if ev.step < start_step:
                continue
            if ev.id not in alive:
                if self.complete:
                    raise LineageError(f"{ev.where}: cell {ev.id} ({ev.kind} at step {ev.step}) is not alive "
                                       "then: neither among the cells of the start nor born in the log "
                                       "(a log of another run, or lines missing?)")
                alive[ev.id] = self._root(ev.id)
            cell = alive.pop(ev.id)
            cell.end_step, cell.end_time, cell.fate, cell.position = ev.step, ev.time, ev.kind, ev.pos
            if ev.kind == "divide":
                for d in (ev.d1, ev.d2):
                    if d in alive:
                        raise LineageError(f"{ev.where}: daughter ID {d} of cell {ev.id} belongs to a living "
                                           "cell already")
                    name = f"{d}@{ev.step}"
                    child = Cell(name, d, ev.step, ev.time, cell.generation + 1, cell.name, cell.root)
                    self.cells[name] = child
                    cell.daughters.append(name)
                    alive[d] = child
            self.last_step, self.last_time = max(self.last_step, ev.step), max(self.last_time, ev.time)
        self.alive = alive

    def _root(self, cid):
        cell = Cell(str(cid), cid, self.start_step, self.start_time, 0, None, str(cid))
        self.cells[cell.name] = cell
        self.roots.append(cell.name)
        return cell

    # ----------------------------------------------------------- queries
    def leaves(self, alive_only=True):
        """Names of the cells with no daughters (alive ones only, by default)."""
        return [c.name for c in self.cells.values() if not c.daughters and (c.fate == "alive" or not alive_only)]

    def ancestry(self, name):
        """The names from the cell up to its root, the cell first."""
        out = [name]
        while self.cells[out[-1]].mother is not None:
            out.append(self.cells[out[-1]].mother)
        return out

    def alive_by_id(self):
        """Atom ID -> the living cell's name."""
        return {i: c.name for i, c in self.alive.items()}

    def table(self):
        """One row (dict) per cell, in order of birth."""
        rows = []
        for c in sorted(self.cells.values(), key=lambda c: (c.birth_step, c.id)):
            rows.append(dict(cell=c.name, id=c.id, generation=c.generation, mother=c.mother or "",
                             root=c.root, birth_step=c.birth_step, birth_time=c.birth_time,
                             end_step="" if c.end_step is None else c.end_step,
                             end_time="" if c.end_time is None else c.end_time, fate=c.fate))
        return rows

    # ------------------------------------------------------------ output
    def newick(self, end_time=None):
        """The tree in Newick format, one tree per root (a forest: the trees one after another,
        each ending in ';').  Branch lengths are life times; living cells' lives end at
        ``end_time`` (default: the last event).  Dead cells are marked with a trailing '+'."""
        end = self.last_time if end_time is None else end_time

        def label(c):
            return c.name.replace("@", "_at_") + ("+" if c.fate == "death" else "")

        def sub(name):
            # iterative post-order: deep trees must not hit Python's recursion limit
            out = {}
            stack = [(name, False)]
            while stack:
                n, done = stack.pop()
                c = self.cells[n]
                if not done and c.daughters:
                    stack.append((n, True))
                    stack.extend((d, False) for d in reversed(c.daughters))
                    continue
                length = (c.end_time if c.end_time is not None else end) - c.birth_time
                inner = "(" + ",".join(out.pop(d) for d in c.daughters) + ")" if c.daughters else ""
                out[n] = f"{inner}{label(c)}:{length:.10g}"
            return out[name]

        return "\n".join(sub(r) + ";" for r in self.roots) + "\n"

    def layout(self, end_time=None):
        """Coordinates for a drawing: per cell (t0, t1, y), leaves at y = 0, 1, 2, ... in tree
        order, an inner cell at the mean y of its daughters."""
        end = self.last_time if end_time is None else end_time
        pos = {}
        y = 0
        for r in self.roots:
            order = []
            stack = [(r, False)]
            while stack:
                n, done = stack.pop()
                c = self.cells[n]
                if not done and c.daughters:
                    stack.append((n, True))
                    stack.extend((d, False) for d in reversed(c.daughters))
                    continue
                order.append(n)
            for n in order:
                c = self.cells[n]
                t1 = c.end_time if c.end_time is not None else end
                if c.daughters:
                    yy = float(np.mean([pos[d][2] for d in c.daughters]))
                else:
                    yy, y = float(y), y + 1
                pos[n] = (c.birth_time, t1, yy)
        return pos


def plot_tree(lineage, path, end_time=None, dpi=150, title=None, max_leaves=5000):
    """Draw the lineage forest: time to the right, one row per leaf; divisions are the vertical
    links, deaths end in a cross."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    pos = lineage.layout(end_time)
    nleaves = sum(1 for c in lineage.cells.values() if not c.daughters)
    if nleaves > max_leaves:
        raise LineageError(f"{nleaves} leaves are too many to draw legibly (limit {max_leaves}); "
                           "write --newick and draw it with a tree viewer, or use --root ID")
    fig, ax = plt.subplots(figsize=(8, min(60.0, max(3.0, 0.12 * nleaves + 1))))
    segs, links, dead = [], [], []
    for n, (t0, t1, y) in pos.items():
        c = lineage.cells[n]
        segs.append([(t0, y), (t1, y)])
        if c.daughters:
            ys = [pos[d][2] for d in c.daughters]
            links.append([(t1, min(ys)), (t1, max(ys))])
        if c.fate == "death":
            dead.append((t1, y))
    ax.add_collection(LineCollection(segs, colors="k", linewidths=0.8))
    ax.add_collection(LineCollection(links, colors="k", linewidths=0.8))
    if dead:
        d = np.array(dead)
        ax.plot(d[:, 0], d[:, 1], "x", color="tab:red", ms=4, label="death")
        ax.legend(loc="upper left", fontsize=8)
    ax.autoscale()
    ax.set_yticks([])
    ax.set_xlabel("time")
    alive = len(lineage.leaves())
    ax.set_title(title or f"{len(lineage.roots)} root(s), {alive} living cells, "
                          f"{sum(1 for c in lineage.cells.values() if c.fate == 'divide')} divisions, "
                          f"{len(dead)} deaths", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path


def subtree(lineage, root_id):
    """A Lineage of one root (atom ID of a cell of the start) and its descendants."""
    name = str(root_id)
    if name not in lineage.cells or lineage.cells[name].mother is not None:
        raise LineageError(f"no root cell with ID {root_id} (the roots are the cells of the start)")
    out = Lineage([], None, lineage.start_step, lineage.start_time)
    out.complete = lineage.complete
    out.last_step, out.last_time = lineage.last_step, lineage.last_time
    stack = [name]
    while stack:
        n = stack.pop()
        out.cells[n] = lineage.cells[n]
        stack.extend(lineage.cells[n].daughters)
    out.roots = [name]
    out.alive = {i: c for i, c in lineage.alive.items() if c.root == name}
    return out


def generation_stats(lineage):
    """Counts of living cells per generation, as {generation: count}."""
    out = {}
    for c in lineage.alive.values():
        out[c.generation] = out.get(c.generation, 0) + 1
    return dict(sorted(out.items()))
