# Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
#
# LAMMPS CMake module of the TESSERA package (cmake/Modules/Packages/TESSERA.cmake in a
# LAMMPS source tree; scripts/lammps-package puts it there).  The styles (src/TESSERA)
# are compiled by LAMMPS like any package's; the package's library (lib/tessera, a
# copy of Tessera's core/) is built here by its own CMakeLists.txt as a static library,
# so that its external libraries and compile options reach only its sources.

if(CMAKE_CXX_STANDARD LESS 17)
  message(FATAL_ERROR "The TESSERA package needs C++17 (CMAKE_CXX_STANDARD >= 17)")
endif()
set(TESSERA_LIB_DIR ${LAMMPS_LIB_SOURCE_DIR}/tessera)
if(NOT EXISTS ${TESSERA_LIB_DIR}/CMakeLists.txt)
  message(FATAL_ERROR "PKG_TESSERA: ${TESSERA_LIB_DIR} is missing; copy the package's "
                      "lib/tessera into this LAMMPS tree (Tessera's scripts/lammps-package)")
endif()
# (EXCLUDE_FROM_ALL: only what lammps links is built, not the library's tools)
add_subdirectory(${TESSERA_LIB_DIR} ${CMAKE_BINARY_DIR}/tessera-lib EXCLUDE_FROM_ALL)
set_target_properties(tessera_core PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_link_libraries(lammps PRIVATE tessera_core)
if(NOT PKG_BROWNIAN)
  message(WARNING "PKG_TESSERA: the package's example inputs integrate with 'fix brownian', "
                  "from LAMMPS's BROWNIAN package: add -D PKG_BROWNIAN=on")
endif()
if(NOT PKG_DIPOLE)
  message(WARNING "PKG_TESSERA: fix polarity keeps the cells' polarity in 'atom_style dipole', "
                  "from LAMMPS's DIPOLE package: add -D PKG_DIPOLE=on")
endif()
