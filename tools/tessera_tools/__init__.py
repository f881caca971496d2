# SPDX-License-Identifier: GPL-2.0-or-later
"""Post-processing for Tessera (active Voronoi vertex model in LAMMPS).

Modules:
  dump          read LAMMPS ``dump custom`` text files (frames, box, columns)
  voronoi       periodic Voronoi tessellation of a frame (areas, perimeters, neighbours)
  render        pictures of the tessellation coloured by a per-cell field
  trajectories  trajectories coloured by coordination / orientation, angle histograms
  logplot       thermo blocks of LAMMPS log files, quantities against time
  junctions     cell polygons from a dump local of compute vertex/local
  vtk           VTK polygon files (.vtu per frame, .pvd time series) for ParaView / OVITO
  transport     flux through sections, velocity field, drift and MSD of atoms of any type
  holes         loops of free boundary of finite cells, the hole around each particle
  divisions     division events of fix cell/divide's log, latitude/longitude on a sphere
  segmented     a vertex tissue (rings of pair_style vertex/polygon) from a segmented image's labels
"""

__version__ = "0.1.0"
