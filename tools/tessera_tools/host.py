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
  this repository's build/, else next to (or in ../lib of) tessera-lmp on PATH.

Run serial or under mpirun; every rank calls register().
"""

import ctypes
import os
import shutil

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


def library_places():
    """Where :func:`find_library` looks, in order, as (description, path or None)."""
    name = "libtessera_lammps.so"
    places = [("$TESSERA_LAMMPS_LIB", os.environ.get("TESSERA_LAMMPS_LIB") or None)]
    if os.environ.get("TESSERA_BUILD"):
        places.append(("$TESSERA_BUILD/lammps", os.path.join(os.environ["TESSERA_BUILD"], "lammps", name)))
    places.append(("this repository's build/lammps", os.path.join(_REPO, "build", "lammps", name)))
    lmp = shutil.which("tessera-lmp")
    if lmp:
        bindir = os.path.dirname(os.path.realpath(lmp))
        # a build tree holds both in build/lammps/; 'cmake --install' puts them in bin/ and lib/
        places.append(("next to tessera-lmp on PATH", os.path.join(bindir, name)))
        places.append(("../lib of tessera-lmp on PATH", os.path.join(os.path.dirname(bindir), "lib", name)))
    else:
        places.append(("next to tessera-lmp on PATH", None))
    return places


def find_library():
    """libtessera_lammps.so: $TESSERA_LAMMPS_LIB, else in the build directory $TESSERA_BUILD or
    this repository's build/, else next to (or in ../lib of) the tessera-lmp found on PATH.
    A $TESSERA_LAMMPS_LIB that does not exist is an error, not a reason to look elsewhere."""
    env = os.environ.get("TESSERA_LAMMPS_LIB")
    if env:
        return _existing(env, "libtessera_lammps.so", "fix or unset TESSERA_LAMMPS_LIB")
    places = library_places()
    for _, path in places:
        if path and os.path.exists(path):
            return path
    looked = "; ".join(f"{what} ({path or 'not set' if what.startswith('$') else path or 'none'})"
                       for what, path in places)
    raise FileNotFoundError("libtessera_lammps.so not found. Looked in: " + looked + ". Build Tessera "
                            "(scripts/build) and set TESSERA_BUILD=<tessera>/build (or run "
                            "'eval \"$(<tessera>/tools/tessera-tools env)\"'), or set TESSERA_LAMMPS_LIB")


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
