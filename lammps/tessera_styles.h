/* -*- c++ -*- ----------------------------------------------------------
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

   Registration of Tessera's styles into a LAMMPS instance.

   The packaged LAMMPS has no plugin support and no style_*.h of ours, so the
   styles are inserted into an existing instance's style maps (force->pair_map,
   modify->fix_map, modify->compute_map).  tessera-lmp does this right after
   constructing LAMMPS; Python does it through tessera_register() and ctypes.
   To add a style, add one line to the table in tessera_styles.cpp.
------------------------------------------------------------------------- */

#ifndef TESSERA_STYLES_H
#define TESSERA_STYLES_H

#include <string>
#include <vector>

// The only symbols libtessera_lammps.so exports; everything else is hidden.
#define TESSERA_LAMMPS_API __attribute__((visibility("default")))

namespace LAMMPS_NS {

class LAMMPS;

// What registration did with one entry of Tessera's style table.
struct TesseraStyle {
  std::string command;    // "pair_style", "fix" or "compute"
  std::string name;       // the style name an input script uses
  bool provided;          // true: Tessera's class serves this name in this instance
  bool replaced_host;     // Tessera's class replaced a host style of the same name
};

// Insert Tessera's styles into lmp's style maps and log one line naming them.
// Idempotent.  Call after constructing the instance, before any input uses
// the styles.
TESSERA_LAMMPS_API std::vector<TesseraStyle> tessera_register_styles(LAMMPS *lmp);

// The plugin route (LAMMPS's `plugin load`, tessera_plugin.cpp): hands every
// table entry to LAMMPS's plugin registration function regfunc (a
// lammpsplugin_regfunc) with the plugin's dlopen handle, except a
// Policy::IF_MISSING entry whose name the host already serves; logs the same
// line as tessera_register_styles().
TESSERA_LAMMPS_API std::vector<TesseraStyle> tessera_register_plugin(LAMMPS *lmp, void *handle,
                                                                     void *regfunc);

}    // namespace LAMMPS_NS

extern "C" {

// For ctypes: lmp_handle is a LAMMPS_NS::LAMMPS * (the `lmp` attribute of a
// Python `lammps` object).  Returns how many styles Tessera now provides in
// that instance, or -1 if lmp_handle is null.
TESSERA_LAMMPS_API int tessera_register(void *lmp_handle);

// Tessera's version, e.g. "0.1.0".
TESSERA_LAMMPS_API const char *tessera_version();
}

#endif
