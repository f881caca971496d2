/* ----------------------------------------------------------------------
   TESSERA package for LAMMPS: vertex models of cell tissues
   LAMMPS: https://www.lammps.org/

   Copyright (2026) the Tessera developers.  This software is distributed
   under the GNU General Public License, version 2 or (at your option) any
   later version.
   SPDX-License-Identifier: GPL-2.0-or-later

   See the README file in the package's directory (src/TESSERA).
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing authors: the Tessera developers

   tesseraplugin.so: Tessera's styles for a LAMMPS built with its PLUGIN
   package, loaded with `plugin load /path/to/tesseraplugin.so` or found
   through LAMMPS_PLUGIN_PATH.  LAMMPS calls lammpsplugin_init() (its
   examples/plugins convention) with the instance, the dlopen handle and its
   registration function; we register every entry of the style table in
   tessera_styles.cpp.  Built only with -D TESSERA_PLUGIN=ON; the plugin must be
   compiled against the headers of the LAMMPS version that loads it.
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "tessera_styles.h"

#include "comm.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "lammps.h"
#include "modify.h"

#include <cstdio>
#include <string>

using namespace LAMMPS_NS;

namespace {

// LAMMPS's registration function, and how many styles it was handed in this
// lammpsplugin_init() call.
lammpsplugin_regfunc host_register = nullptr;
int handed = 0;

// True if the instance already serves this plugin entry's style name.
bool served(LAMMPS *lmp, const lammpsplugin_t *plugin)
{
  const std::string style = plugin->style;
  if (style == "pair") return lmp->force->pair_map->count(plugin->name) > 0;
  if (style == "fix") return lmp->modify->fix_map->count(plugin->name) > 0;
  if (style == "compute") return lmp->modify->compute_map->count(plugin->name) > 0;
  if (style == "command") return lmp->input->command_map->count(plugin->name) > 0;
  return false;
}

// Hands one style to LAMMPS.  LAMMPS prints "Loading plugin: <info> by <author>"
// for each, so the styles after the first are handed with the instance's screen
// and log file set aside: the banner appears once (and Tessera's own line lists
// every style).  LAMMPS's warning that a style overrides a built-in one is then
// given here.
void register_once_loud(lammpsplugin_t *plugin, void *ptr)
{
  auto *lmp = static_cast<LAMMPS *>(ptr);
  if (handed++ == 0) {
    host_register(plugin, ptr);
    return;
  }
  const bool overrides = served(lmp, plugin);
  FILE *screen = lmp->screen, *logfile = lmp->logfile;
  lmp->screen = nullptr;
  lmp->logfile = nullptr;
  try {
    host_register(plugin, ptr);
  } catch (...) {
    lmp->screen = screen;
    lmp->logfile = logfile;
    throw;
  }
  lmp->screen = screen;
  lmp->logfile = logfile;
  if (overrides && lmp->comm->me == 0)
    lmp->error->warning(FLERR, "Tessera's {} style {} (plugin) overrides the built-in one",
                        plugin->style, plugin->name);
}

}    // namespace

extern "C" TESSERA_LAMMPS_API void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  host_register = reinterpret_cast<lammpsplugin_regfunc>(regfunc);
  handed = 0;
  tessera_register_plugin(static_cast<LAMMPS *>(lmp), handle,
                          reinterpret_cast<void *>(&register_once_loud));
}
