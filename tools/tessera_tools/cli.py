# SPDX-License-Identifier: GPL-2.0-or-later
"""Command line: ``tessera-tools COMMAND ...`` (each has --help).  The commands live in one
module per group: cli_frames (info, render, vtk, traj), cli_log (log), cli_moduli (moduli),
cli_lineage (lineage), cli_plot (plot ...), cli_analyses (flux, velocity, msd, holes,
divisions); this module puts them together."""

import argparse
import sys

from . import cli_analyses, cli_frames, cli_lineage, cli_log, cli_moduli, cli_plot


def cmd_env(args):
    """Shell lines that let any python3 import tessera_tools and find Tessera's build."""
    import os
    import shlex

    tools = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    repo = os.path.dirname(tools)
    build = os.environ.get("TESSERA_BUILD") or os.path.join(repo, "build")
    lines = []
    if os.path.isfile(os.path.join(tools, "tessera-tools")):     # a source tree, not an installed copy
        lines.append(f'export PYTHONPATH={shlex.quote(tools)}"${{PYTHONPATH:+:$PYTHONPATH}}"')
        lines.append(f'export PATH={shlex.quote(tools)}":$PATH"')
    if os.path.isdir(os.path.join(build, "lammps")):
        lines.append(f"export TESSERA_BUILD={shlex.quote(build)}")
        lines.append(f'export PATH={shlex.quote(os.path.join(build, "lammps"))}":$PATH"')
    else:
        print(f"# no build found at {build}: run scripts/build in the repository, or set TESSERA_BUILD",
              file=sys.stderr)
    print("\n".join(lines))


def build_parser():
    p = argparse.ArgumentParser(
        prog="tessera-tools",
        description="Post-processing for Tessera (active Voronoi vertex model in LAMMPS): "
                    "tessellation pictures, VTK polygon files, trajectory plots, thermo plots.")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True

    cli_frames.add_commands(sub)
    cli_log.add_commands(sub)
    cli_moduli.add_commands(sub)
    en = sub.add_parser("env", help="shell settings for running from anywhere (eval \"$(tessera-tools env)\")",
                        description="Print export lines: PYTHONPATH (this tools/ directory, so any python3 can "
                                    "import tessera_tools, e.g. the Python examples copied elsewhere), "
                                    "TESSERA_BUILD (where libtessera_lammps.so and tessera-hessian are) and PATH "
                                    "(tessera-tools, tessera-lmp).")
    en.set_defaults(func=cmd_env)

    cli_lineage.add_commands(sub)
    cli_plot.add_commands(sub)
    cli_analyses.add_commands(sub)
    __import__(__package__ + ".cli_converge", fromlist=["add_commands"]).add_commands(sub)
    __import__(__package__ + ".cli_segmented", fromlist=["add_commands"]).add_commands(sub)
    return p


def main(argv=None):
    args = build_parser().parse_args(argv)
    try:
        args.func(args)
    except (OSError, KeyError, ValueError, RuntimeError) as err:
        msg = err.args[0] if isinstance(err, KeyError) and err.args else err
        what = args.command + (" " + args.what if getattr(args, "what", None) else "")
        print(f"tessera-tools {what}: {msg}", file=sys.stderr)
        return 1
    return 0
