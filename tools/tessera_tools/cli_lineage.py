# SPDX-License-Identifier: GPL-2.0-or-later
"""tessera-tools lineage: the lineage tree of a tissue from the event logs of fix cell/divide and
fix cell/death."""

import csv


def cmd_lineage(args):
    from .lineage import Lineage, generation_stats, plot_tree, read_events, subtree

    events = read_events(args.logs)
    start_ids, start_step, start_time = None, 0, 0.0
    if args.start:
        from .dump import iter_dump

        first = next(iter_dump(args.start, args.cell_types), None)
        if first is None:
            raise SystemExit(f"tessera-tools lineage: {args.start}: no frame in the dump")
        start_ids, start_step = first.ids, first.timestep
        start_time = first.time if first.time is not None else (start_step * args.dt if args.dt else 0.0)
    tree = Lineage(events, start_ids, start_step, start_time)
    if args.root is not None:
        tree = subtree(tree, args.root)
    alive = tree.leaves()
    ndiv = sum(1 for c in tree.cells.values() if c.fate == "divide")
    ndeath = sum(1 for c in tree.cells.values() if c.fate == "death")
    print(f"{len(events)} events ({ndiv} divisions, {ndeath} deaths) from step {tree.start_step} to "
          f"{tree.last_step} (time {tree.last_time:.10g}); {len(tree.roots)} root cells, {len(tree.cells)} cells "
          f"in all, {len(alive)} living at the end (the tree's living leaves)")
    if not tree.complete:
        print("  without --start DUMP the roots are only the cells that have an event in the log: cells that "
              "never divided nor died are missing (give the first dump frame of the run)")
    gens = generation_stats(tree)
    if gens:
        print("  living cells per generation: " + ", ".join(f"{g}: {n}" for g, n in gens.items()))
    if args.ancestry:
        byid = tree.alive_by_id()
        for i in args.ancestry:
            if i not in byid:
                raise SystemExit(f"tessera-tools lineage: --ancestry {i}: no living cell has atom ID {i} at the end")
            chain = tree.ancestry(byid[i])
            print(f"  cell {i}: generation {tree.cells[chain[0]].generation}, ancestry "
                  + " <- ".join(chain))
    if args.table:
        rows = tree.table()
        with open(args.table, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]) if rows else ["cell"])
            w.writeheader()
            w.writerows(rows)
        print(f"wrote {args.table} ({len(rows)} cells: generation, mother, root, birth, end, fate)")
    if args.newick:
        with open(args.newick, "w") as f:
            f.write(tree.newick(args.end_time))
        print(f"wrote {args.newick} ({len(tree.roots)} tree(s) in Newick format; branch lengths in time units)")
    if args.output:
        plot_tree(tree, args.output, end_time=args.end_time, dpi=args.dpi, title=args.title)
        print(f"wrote {args.output}")


def add_commands(sub):
    """Add this module's commands to the subparsers ``sub`` of tessera-tools."""
    from .cli_frames import add_cell_types

    li = sub.add_parser("lineage", help="lineage tree from the event logs of fix cell/divide and fix cell/death",
                        description="Build the lineage tree (generations, ancestry, Newick, a drawing) from the "
                                    "event logs that fix cell/divide and fix cell/death write with their keyword "
                                    "'file'. The logs record every event, so cells that divide several times "
                                    "between two dumps keep their lineage.",
                        epilog="Cells are named ID for the cells of the start and ID@STEP for cells born at "
                               "STEP (the daughter that keeps her mother's atom ID is a new cell).")
    li.add_argument("logs", nargs="+", help="event log(s) (fix cell/divide ... file NAME, fix cell/death ... file NAME)")
    li.add_argument("--start", metavar="DUMP",
                    help="a dump whose first frame holds the cells at the start of the log (their IDs), so that "
                         "cells without events are in the tree too")
    add_cell_types(li, "; --start takes the IDs of the cells only (fix cell/divide and cell/death act on cells)")
    li.add_argument("--dt", type=float, help="timestep size, for the start's time when the dump has no TIME")
    li.add_argument("--root", type=int, metavar="ID", help="only the tree of this cell of the start")
    li.add_argument("--ancestry", type=int, nargs="+", metavar="ID",
                    help="print the ancestry of these living cells (atom IDs at the end)")
    li.add_argument("--table", metavar="CSV", help="one row per cell: generation, mother, root, birth, end, fate")
    li.add_argument("--newick", metavar="FILE", help="the tree(s) in Newick format")
    li.add_argument("--end-time", type=float, help="where the living cells' branches end (default: the last event)")
    li.add_argument("-o", "--output", help="drawing of the tree (.png, .pdf, .svg)")
    li.add_argument("--dpi", type=int, default=150)
    li.add_argument("--title")
    li.set_defaults(func=cmd_lineage)
