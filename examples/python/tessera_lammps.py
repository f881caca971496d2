# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
"""Tessera's styles in a Python-driven LAMMPS (Debian's python3-lammps).

    from lammps import lammps
    import tessera_lammps
    lmp = lammps()
    tessera_lammps.register(lmp)      # now fix brownian, pair_style vertex/voronoi, ...

The packaged liblammps.so cannot load plugins, so libtessera_lammps.so inserts
its styles into the instance's style tables through the C function
tessera_register(void *lmp).  Run with /usr/bin/python3 (the interpreter that
has python3-lammps), serial or under mpirun.
"""

import ctypes
import os

_HERE = os.path.dirname(os.path.abspath(__file__))
_REPO = os.path.dirname(os.path.dirname(_HERE))


def find_library():
    """$TESSERA_LAMMPS_LIB, else libtessera_lammps.so in the build directory
    $TESSERA_BUILD or the repository's build/."""
    path = os.environ.get("TESSERA_LAMMPS_LIB")
    if path:
        return path
    build = os.environ.get("TESSERA_BUILD", os.path.join(_REPO, "build"))
    path = os.path.join(build, "lammps", "libtessera_lammps.so")
    if not os.path.exists(path):
        raise FileNotFoundError(
            "libtessera_lammps.so not found at %s: build Tessera (scripts/build) or set "
            "TESSERA_LAMMPS_LIB" % path)
    return path


def register(lmp, library=None):
    """Adds Tessera's styles to the lammps object `lmp`; returns how many
    styles Tessera provides in it."""
    # RTLD_GLOBAL as lammps.py loads liblammps.so: our dependency on
    # liblammps.so.0 then binds to that same, already loaded, library.
    lib = ctypes.CDLL(library or find_library(), mode=ctypes.RTLD_GLOBAL)
    lib.tessera_register.argtypes = [ctypes.c_void_p]
    lib.tessera_register.restype = ctypes.c_int
    provided = lib.tessera_register(lmp.lmp)
    if provided < 0:
        raise RuntimeError("tessera_register: no LAMMPS instance")
    return provided
