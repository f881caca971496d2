# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
#
# LAMMPS CMake module of the TESSERA package (cmake/Modules/Packages/TESSERA.cmake in
# a LAMMPS source tree, put there by Tessera's scripts/install-lammps-package).  The
# styles (src/TESSERA/) are compiled by LAMMPS like any package's; Tessera's core
# library (lib/tessera/) is built here as its own static library, so CGAL and its
# -frounding-math reach only the core's sources, never LAMMPS's.

if(CMAKE_CXX_STANDARD LESS 17)
  message(FATAL_ERROR "The TESSERA package needs C++17 (CMAKE_CXX_STANDARD >= 17)")
endif()
if(NOT EXISTS ${LAMMPS_LIB_SOURCE_DIR}/tessera/CMakeLists.txt)
  message(FATAL_ERROR "PKG_TESSERA: ${LAMMPS_LIB_SOURCE_DIR}/tessera is missing; run Tessera's "
                      "scripts/install-lammps-package on this LAMMPS source tree again")
endif()
# (EXCLUDE_FROM_ALL: only what lammps links is built, not the core's tools)
add_subdirectory(${LAMMPS_LIB_SOURCE_DIR}/tessera ${CMAKE_BINARY_DIR}/tessera-core EXCLUDE_FROM_ALL)
set_target_properties(tessera_core PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_link_libraries(lammps PRIVATE tessera_core)
if(NOT PKG_BROWNIAN)
  message(WARNING "PKG_TESSERA: Tessera's input scripts integrate with 'fix brownian', which "
                  "in-tree comes from LAMMPS's BROWNIAN package: add -D PKG_BROWNIAN=on")
endif()
if(NOT PKG_DIPOLE)
  message(WARNING "PKG_TESSERA: Tessera's cells need 'atom_style dipole' (the polarity), from "
                  "LAMMPS's DIPOLE package: add -D PKG_DIPOLE=on")
endif()
