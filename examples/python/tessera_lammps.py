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
    from tessera_tools import host
except ImportError:    # not installed: the repository's tools/
    sys.path.insert(0, _TOOLS)
    from tessera_tools import host

find_library = host.find_library
find_plugin = host.find_plugin


def register(lmp, library=None, plugin=None):
    """Adds Tessera's styles to the lammps object `lmp`; returns "plugin" or
    "ctypes" (the route taken)."""
    return host.register(lmp, plugin=plugin, library=library)
