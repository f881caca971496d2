// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// How error messages name a point (internal to the core).
#pragma once

#include <sstream>
#include <string>

namespace tessera {

// "id 17" when the caller gave ids (LAMMPS atom IDs), else "point 17".
inline std::string point_name(int i, const long *ids) {
  std::ostringstream s;
  if (ids)
    s << "id " << ids[i];
  else
    s << "point " << i;
  return s.str();
}

}  // namespace tessera
