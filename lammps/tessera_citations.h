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
------------------------------------------------------------------------- */

/* Citation reminders, registered through LAMMPS's CiteMe (lmp->citeme->add(),
   null under -nocite): the implementation's source, by the styles that
   implement it (constructors), and the publication of each model, by
   pair_style vertex/voronoi when a run uses that model (init_style).  The
   first line is what LAMMPS prints on the screen, the BibTeX entry goes to
   the log file (and to the -cite file).  Each text is here once: LAMMPS
   prints a text once per run however many styles register it. */

#ifndef LMP_TESSERA_CITATIONS_H
#define LMP_TESSERA_CITATIONS_H

namespace LAMMPS_NS {
namespace tessera_cite {

  // The thesis whose model and LAMMPS implementation Tessera reproduces.  (Its
  // author, institution and year are still to be added: a @Misc entry until then.)
  inline constexpr char thesis[] =
      "Tessera (pair_style vertex/voronoi, fix polarity): Vertex modeling of confluent cellular "
      "networks within a molecular dynamics framework in LAMMPS (thesis directed by "
      "F. Vernerey)\n\n"
      "@Misc{TesseraThesis,\n"
      " title = {Vertex Modeling of Confluent Cellular Networks Within a Molecular Dynamics "
      "Framework in {LAMMPS}},\n"
      " howpublished = {Thesis},\n"
      " note = {Thesis directed by Franck Vernerey}\n"
      "}\n\n";

  // The self-propelled Voronoi model: confluent cells in the plane (and on a sphere).
  inline constexpr char voronoi_2d[] =
      "pair_style vertex/voronoi (Voronoi model): doi:10.1103/PhysRevX.6.021011\n\n"
      "@Article{Bi16,\n"
      " author = {D. Bi and X. Yang and M. C. Marchetti and M. L. Manning},\n"
      " title = {Motility-Driven Glass and Jamming Transitions in Biological Tissues},\n"
      " journal = {Phys.\\ Rev.\\ X},\n"
      " year = 2016,\n"
      " volume = 6,\n"
      " pages = {021011}\n"
      "}\n\n";

  // dimension 3: Voronoi polyhedra with a volume and a surface term.
  inline constexpr char voronoi_3d[] =
      "pair_style vertex/voronoi (3d Voronoi model): doi:10.1088/1367-2630/aaaa13\n\n"
      "@Article{Merkel18,\n"
      " author = {M. Merkel and M. L. Manning},\n"
      " title = {A Geometrically Controlled Rigidity Transition in a Model for Confluent "
      "{3D} Tissues},\n"
      " journal = {New J.\\ Phys.},\n"
      " year = 2018,\n"
      " volume = 20,\n"
      " pages = {022002}\n"
      "}\n\n";

  // 'radius r': each cell its Voronoi cell cut by a disc, with free edges.
  inline constexpr char voronoi_finite[] =
      "pair_style vertex/voronoi (finite Voronoi model): doi:10.1103/PhysRevE.98.042418\n\n"
      "@Article{Teomy18,\n"
      " author = {E. Teomy and D. A. Kessler and H. Levine},\n"
      " title = {Confluent and Nonconfluent Phases in a Model of Cell Tissue},\n"
      " journal = {Phys.\\ Rev.\\ E},\n"
      " year = 2018,\n"
      " volume = 98,\n"
      " pages = {042418}\n"
      "}\n\n";

}    // namespace tessera_cite
}    // namespace LAMMPS_NS

#endif
