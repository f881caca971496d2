# SPDX-License-Identifier: GPL-2.0-or-later
"""Tessera's styles in a Python-driven LAMMPS, whichever LAMMPS it is.

    from lammps import lammps
    from tessera_tools import host
    lmp = lammps()
    host.register(lmp)        # now pair_style vertex/voronoi, fix polarity, ...

Two hosts, one call:

* a LAMMPS with the PLUGIN package (a current release built with CMake):
  ``plugin load tesseraplugin.so``, unless the styles are already there (e.g.
  loaded through LAMMPS_PLUGIN_PATH).  The plugin is $TESSERA_PLUGIN, else
  build-plugin/lammps/tesseraplugin.so in this repository.  It must be built
  against that LAMMPS's headers (README, "Install into your LAMMPS").
* Debian's packaged LAMMPS (python3-lammps, no PLUGIN package):
  libtessera_lammps.so inserts the styles into the instance through its C
  function tessera_register(void *lmp), called with ctypes.  The library is
  $TESSERA_LAMMPS_LIB, else lammps/libtessera_lammps.so in $TESSERA_BUILD or
  this repository's build/.

Run serial or under mpirun; every rank calls register().
"""

import ctypes
import os

_REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _existing(path, what, hint):
    if not os.path.exists(path):
        raise FileNotFoundError("%s not found at %s: %s" % (what, path, hint))
    return path


def find_plugin():
    """$TESSERA_PLUGIN, else build-plugin/lammps/tesseraplugin.so of this repository."""
    path = os.environ.get("TESSERA_PLUGIN") or os.path.join(_REPO, "build-plugin", "lammps",
                                                            "tesseraplugin.so")
    return _existing(path, "tesseraplugin.so",
                     "build it against your LAMMPS (cmake -D TESSERA_PLUGIN=ON "
                     "-D TESSERA_LAMMPS_SRC=<lammps>/src) or set TESSERA_PLUGIN")


def find_library():
    """$TESSERA_LAMMPS_LIB, else libtessera_lammps.so in the build directory
    $TESSERA_BUILD or this repository's build/."""
    path = os.environ.get("TESSERA_LAMMPS_LIB")
    if not path:
        build = os.environ.get("TESSERA_BUILD", os.path.join(_REPO, "build"))
        path = os.path.join(build, "lammps", "libtessera_lammps.so")
    return _existing(path, "libtessera_lammps.so",
                     "build Tessera (scripts/build) or set TESSERA_LAMMPS_LIB")


def has_plugin_support(lmp):
    """True if the LAMMPS behind `lmp` has the PLUGIN package."""
    return "PLUGIN" in lmp.installed_packages


def register(lmp, plugin=None, library=None):
    """Adds Tessera's styles to the lammps object `lmp` and returns how:
    "plugin" (plugin load, or already loaded) or "ctypes" (tessera_register)."""
    if has_plugin_support(lmp):
        if not lmp.has_style("pair", "vertex/voronoi"):
            path = plugin or find_plugin()
            lmp.command('plugin load "%s"' % path)
            if not lmp.has_style("pair", "vertex/voronoi"):
                raise RuntimeError(
                    "plugin load %s did not add Tessera's styles (see the LAMMPS log: a plugin "
                    "built for another LAMMPS version, or a missing library)" % path)
        return "plugin"
    # RTLD_GLOBAL as lammps.py loads liblammps.so: our dependency on
    # liblammps.so.0 then binds to that same, already loaded, library.
    lib = ctypes.CDLL(library or find_library(), mode=ctypes.RTLD_GLOBAL)
    lib.tessera_register.argtypes = [ctypes.c_void_p]
    lib.tessera_register.restype = ctypes.c_int
    if lib.tessera_register(lmp.lmp) < 0:
        raise RuntimeError("tessera_register: no LAMMPS instance")
    return "ctypes"
