// Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
//
// tesseraplugin.so: Tessera's styles for a LAMMPS built with its PLUGIN
// package, loaded with `plugin load /path/to/tesseraplugin.so` or found
// through LAMMPS_PLUGIN_PATH.  LAMMPS calls lammpsplugin_init() (its
// examples/plugins convention) with the instance, the dlopen handle and its
// registration function; we register every entry of the style table in
// tessera_styles.cpp.  Built only with -D TESSERA_PLUGIN=ON; the plugin must be
// compiled against the headers of the LAMMPS version that loads it.

#include "lammpsplugin.h"
#include "tessera_styles.h"

#include "lammps.h"

extern "C" TESSERA_LAMMPS_API void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  LAMMPS_NS::tessera_register_plugin(static_cast<LAMMPS_NS::LAMMPS *>(lmp), handle, regfunc);
}
