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

   pair_style vertex/polygon: the vertex model's energy, forces on the
   vertices and virial; its settings and coefficients are in
   pair_vertex_polygon_coeff.cpp, the topology in fix_vertex_polygon.cpp.
------------------------------------------------------------------------- */

#include "pair_vertex_polygon.h"

#include "cell_source.h"
#include "fix_vertex_polygon.h"

#include "tessera/vertex_model.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

struct PairVertexPolygon::Impl {
  tessera::TopologyParams topo;
  tessera::Model model;
  tessera::PolygonCells view, shown;
};

PairVertexPolygon::PairVertexPolygon(LAMMPS *lmp) :
    Pair(lmp), impl(new Impl), topo(impl->topo), model(impl->model), view(impl->view),
    shown(impl->shown)
{
  single_enable = 0;
  restartinfo = 1;
  one_coeff = 0;
  manybody_flag = 1;
  centroidstressflag = CENTROID_NOTAVAIL;
  nextra = 4;
  pvector = pvec;
  fix_id = std::string("VERTEX_POLYGON_") + std::to_string(instance_me);
}

PairVertexPolygon::~PairVertexPolygon()
{
  if (modify && modify->find_fix(fix_id) >= 0) modify->delete_fix(fix_id);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
  memory->destroy(adapt_kappa);
  memory->destroy(adapt_area0);
  memory->destroy(adapt_gamma);
  memory->destroy(adapt_lambda);
  memory->destroy(built_lambda);
}

int PairVertexPolygon::ring_length(int i) const
{
  const int *r = atom->iarray[ring_index][i];
  if (r[0] < 0) return 0;
  int n = 0;
  while (n < ring_width && r[n] != 0) n++;
  return n;
}

/* The rings: fix property/atom with ID vring and the integer array vring
   (defined again here after read_restart, which restores its values). */

void PairVertexPolygon::find_rings()
{
  int flag = -1, cols = -1;
  int index = atom->find_custom("vring", flag, cols);
  if (index < 0 && restart_ring_width > 0 && modify->find_fix(ring_fix_id()) < 0) {
    modify->add_fix(
        fmt::format("{} all property/atom i2_vring {}", ring_fix_id(), restart_ring_width));
    index = atom->find_custom("vring", flag, cols);
  }
  if (index < 0)
    error->all(FLERR,
               "pair_style vertex/polygon: no rings: the cells' polygons live in 'fix vring all "
               "property/atom i2_vring W' (W: the most sides a cell may have); make them with "
               "create_vertices, or define that fix before read_data and read them with "
               "'read_data FILE fix vring NULL vring'");
  if (flag != 0 || cols <= 0)
    error->all(FLERR,
               "pair_style vertex/polygon: the per-atom property 'vring' must be an integer array "
               "(fix vring all property/atom i2_vring W), not a vector or doubles");
  if (modify->find_fix(ring_fix_id()) < 0)
    error->all(FLERR,
               "pair_style vertex/polygon: the fix property/atom that defines i2_vring must have "
               "the ID 'vring' (so that restart files can restore it)");
  if (sizeof(tagint) > sizeof(int) && atom->map_tag_max > INT_MAX)
    error->all(FLERR,
               "pair_style vertex/polygon: atom IDs above {} do not fit the integer array i_vring",
               INT_MAX);
  ring_index = index;
  ring_width = cols;
}

void PairVertexPolygon::init_style()
{
  if (domain->dimension != 2)
    error->all(FLERR,
               "pair_style vertex/polygon: the vertex model is two-dimensional ('dimension 2')");
  if (!domain->xperiodic || !domain->yperiodic)
    error->all(FLERR,
               "pair_style vertex/polygon: the box must be periodic in x and y ('boundary p p p'); "
               "tissues with free edges are not supported yet");
  if (force->newton_pair == 0)
    error->all(FLERR,
               "pair_style vertex/polygon requires 'newton on' (forces go to ghost vertices)");
  if (atom->tag_enable == 0) error->all(FLERR, "pair_style vertex/polygon requires atom IDs");
  if (atom->map_style == 0)
    error->all(FLERR,
               "pair_style vertex/polygon needs an atom map (rings name their vertices by ID): "
               "add 'atom_modify map yes' before the box is created");
  // Fixes that add atoms during a run may add particles (types of other
  // styles under hybrid/overlay), not cells or vertices (no ring, in no
  // cell).  Their types are known from extract("radius", type), nonzero for
  // the types a fix adds (as granular styles ask it).
  for (int k = 0; k < modify->nfix; k++) {
    Fix *f = modify->fix[k];
    if (!utils::strmatch(f->style, "^deposit") && !utils::strmatch(f->style, "^pour")) continue;
    for (int t = 1; t <= atom->ntypes; t++) {
      int asked = t;
      const auto *radius = static_cast<const double *>(f->extract("radius", asked));
      if (radius && *radius > 0.0 && role(t) != NONE)
        error->all(FLERR,
                   "pair_style vertex/polygon: fix {} ({}) adds atoms during the run, but a cell "
                   "of the vertex model is a ring of vertex atoms that an added atom does not "
                   "have (new cells come from fix cell/divide, which cuts a cell in two), and an "
                   "added vertex would be in no cell: type {} is a {} type; add particles only "
                   "(types without a vertex/polygon pair_coeff, under pair_style hybrid/overlay)",
                   f->id, f->style, t, role(t) == CELL ? "cell" : "vertex");
    }
  }
  int ncell = 0, nvertex = 0;
  for (int t = 1; t <= atom->ntypes; t++) {
    if (role(t) == NONE && force->pair == this)
      error->all(FLERR,
                 "pair_style vertex/polygon: type {} has no pair_coeff: give it cell parameters "
                 "('pair_coeff {} {} quadratic KA A0 KP P0') or make it a vertex type "
                 "('pair_coeff {} {} vertex'); for atoms that are neither (particles, "
                 "obstacles) use 'pair_style hybrid/overlay vertex/polygon ... <style> ...'",
                 t, t, t, t, t);
    if (role(t) != NONE) (role(t) == CELL ? ncell : nvertex)++;
  }
  if (ncell == 0 || nvertex == 0)
    error->all(FLERR,
               "pair_style vertex/polygon needs at least one cell type and one vertex type "
               "(pair_coeff I I quadratic ... and pair_coeff J J vertex)");
  check_hybrid();
  find_rings();
  build_model();
  // Lengths against the cells' size: a T1 moves two vertices by about
  // l_new / 2, which must stay small against a cell.
  // (The largest preferred area: a type of cells meant to shrink away may
  // have a tiny one.)
  double a0max = 0.0;
  for (int t = 1; t <= atom->ntypes; t++)
    if (role(t) == CELL) a0max = MAX(a0max, area0[t]);
  const double size = std::sqrt(a0max);
  if (topo.t1_length > 0.0 && topo.t1_new > 0.5 * size)
    error->all(FLERR,
               "pair_style vertex/polygon: t1 new-edge length {} is comparable to the cells' size "
               "sqrt(A0) = {:.4g}; use lengths well below it (e.g. t1 {:.3g} {:.3g})",
               topo.t1_new, size, 0.02 * size, 0.03 * size);
  if (topo.t2_area > 0.0 && topo.t2_area > 0.25 * a0max)
    error->all(FLERR,
               "pair_style vertex/polygon: t2 area {} is comparable to the cells' preferred area "
               "{:.4g}; use an area well below it (e.g. t2 {:.3g})",
               topo.t2_area, a0max, 0.01 * a0max);
  if (cut_global < 2.0 * size && comm->me == 0)
    error->warning(FLERR,
                   "pair_style vertex/polygon: cutoff {} is less than two cell diameters ({:.3g}); "
                   "the topology needs about 3.5 (runs stop with an error naming the cutoff "
                   "when the ghost atoms do not hold what they need)",
                   cut_global, 2.0 * size);
  // The ghost shell is complete only if atoms moved less than half the skin
  // since the last re-neighbouring: check every step.
  if (neighbor->every != 1 || neighbor->dist_check == 0) {
    if (comm->me == 0)
      error->warning(FLERR,
                     "pair_style vertex/polygon: setting 'neigh_modify every 1 delay 0 check yes' "
                     "so that the ghost shell stays complete");
    neighbor->every = 1;
    neighbor->dist_check = 1;
  }
  neighbor->delay = 0;
  print_model();

  // The internal fix, kept last among the fixes with post_force (it hands
  // the cell atoms' forces to the vertices after every other fix added
  // them): defined again when a later fix came after it.
  const std::string style = FixVertexPolygon::style_name();
  if (modify->fix_map->find(style) == modify->fix_map->end())
    (*modify->fix_map)[style] = &FixVertexPolygon::creator;
  int ifix = modify->find_fix(fix_id);
  if (ifix >= 0) {
    for (int k = ifix + 1; k < modify->nfix; k++)
      if (modify->fmask[k] & FixConst::POST_FORCE) {
        modify->delete_fix(fix_id);
        ifix = -1;
        break;
      }
  }
  if (ifix < 0) modify->add_fix(fix_id + " all " + style);
  fix = dynamic_cast<FixVertexPolygon *>(modify->fix[modify->find_fix(fix_id)]);
  fix->pair = this;
  cache_epoch = -1;
}

double PairVertexPolygon::init_one(int i, int j)
{
  if (setflag[i][j] == 0) setflag[i][j] = 1;
  return cut_global;
}

/* Per-cell values from 'fix property/atom d_area0 d_ka d_kp d_perim0' (each
   when defined), read at the cell atom's local index, as
   pair_style vertex/voronoi reads them. */

void PairVertexPolygon::bind_cell_values()
{
  static const char *names[4] = {"area0", "ka", "kp", "perim0"};
  static const char *what[4] = {"preferred area A0", "area modulus KA", "perimeter modulus KP",
                                "preferred perimeter P0"};
  const double *v[4] = {nullptr, nullptr, nullptr, nullptr};
  const int nlocal = atom->nlocal;
  const int *type = atom->type;
  for (int k = 0; k < 4; k++) {
    int flag = -1, cols = -1;
    const int index = atom->find_custom(names[k], flag, cols);
    if (index < 0) continue;
    if (flag != 1 || cols != 0)
      error->all(FLERR,
                 "pair_style vertex/polygon: the per-atom property '{}' must be a double vector "
                 "(fix property/atom d_{})",
                 names[k], names[k]);
    v[k] = atom->dvector[index];
    for (int i = 0; i < nlocal; i++)
      if (role(type[i]) == CELL && (!(v[k][i] > 0.0) || !std::isfinite(v[k][i])))
        error->one(FLERR,
                   "pair_style vertex/polygon: per-atom {} d_{} of cell {} is {}; it must be > 0 "
                   "(set it for every cell, e.g. 'set type I d_{} value')",
                   what[k], names[k], atom->tag[i], v[k][i], names[k]);
  }
  model.cell_area0 = v[0];
  model.cell_KA = v[1];
  model.cell_KP = v[2];
  model.cell_P0 = v[3];
  if (v[2] && !v[3])
    for (int i = 0; i < nlocal; i++)
      if (role(type[i]) == CELL && !(gamma[type[i]] > 0.0))
        error->one(FLERR,
                   "pair_style vertex/polygon: cell {} has a per-atom d_kp, but its type {} has "
                   "perimeter modulus 0, which defines no preferred perimeter: also define and "
                   "set d_perim0",
                   atom->tag[i], type[i]);
}

/* ----------------------------------------------------------------------
   Cell atom i's polygon: its vertices' coordinates (the closest copies, as
   ring_local holds them) into xy and the 0-based types of the cells across
   its edges into nt.  Returns the vertex count.
------------------------------------------------------------------------- */

int PairVertexPolygon::gather_ring(int i, std::vector<double> &xy, std::vector<int> &nt) const
{
  double **x = atom->x;
  const int *type = atom->type;
  const int n = off[i + 1] - off[i];
  const int *loc = &ring_local[off[i]];
  xy.resize(2 * n);
  nt.resize(n);
  for (int k = 0; k < n; k++) {
    xy[2 * k] = x[loc[k]][0];
    xy[2 * k + 1] = x[loc[k]][1];
    nt[k] = type[nbr_local[off[i] + k]] - 1;
  }
  return n;
}

void PairVertexPolygon::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  if (!fix) error->all(FLERR, "pair_style vertex/polygon: compute before init");
  if (cache_epoch != epoch) refresh();
  bind_cell_values();
  const int nlocal = atom->nlocal;
  double **x = atom->x, **f = atom->f;
  const int *type = atom->type;
  const tagint *tag = atom->tag;
  int **ring = atom->iarray[ring_index];
  std::vector<double> xy, g;
  std::vector<int> nt;
  double energy = 0.0;
  // The Tessera values held in Impl, bound once per compute (not per cell).
  const tessera::Model &model = this->model;
  const tessera::TopologyParams &topo = this->topo;
  tessera::PolygonCells &view = this->view;
  const double l2 = topo.t1_length * topo.t1_length;
  const bool percell = model.has_cell_params();
  const bool vflag_cells = vflag_global && !vflag_fdotr;
  nforce++;
  show_shown = false;
  view.clear(nlocal, nlocal + atom->nghost, tessera::Points{&x[0][0], nlocal + atom->nghost, 3});
  // (the pieces' corners are made from these positions when a consumer reads them)
  view.set_rings(off.data(), ring_local.data(), nbr_local.data(),
                 tessera::Points{&x[0][0], nlocal + atom->nghost, 3});
  cell_energy.assign(nlocal, 0.0);
  for (int i = 0; i < nlocal; i++) {
    if (role(type[i]) != CELL || ring[i][0] < 0) continue;
    const int n = gather_ring(i, xy, nt);
    g.resize(2 * n);
    const int tc = type[i] - 1;
    tessera::PolygonMeasures m;
    double e = tessera::polygon_energy(xy.data(), n, model, i, tc, nt.data(), g.data(), &m);
    // (no vertex twice in a ring: checked by refresh())
    const tessera::PolygonDefect d = tessera::polygon_defect(xy.data(), n);
    if (d != tessera::PolygonDefect::None || !std::isfinite(e)) {
      std::string vs;
      for (int k = 0; k < n; k++) vs += fmt::format(" {}", ring[i][k]);
      // During minimize the topology is fixed: an edge that the minimum at
      // this topology shrinks to nothing goes through zero instead of a T1.
      const char *fix_it = update->whichflag == 2
          ? "minimize keeps the topology fixed (no T1s), and the minimum at this topology "
            "has an edge of zero length: relax with a run with T1s ('t1 l_T1 l_new') first"
          : "a smaller timestep, or T1s ('t1 l_T1 l_new') before its edges shrink to "
            "nothing, keep cells valid";
      error->one(
          FLERR, "pair_style vertex/polygon at step {}: cell {} {} (vertices{}; area {:.6g}); {}",
          update->ntimestep, tag[i],
          std::isfinite(e) ? tessera::describe(d) : "has a non-finite energy", vs, m.area, fix_it);
    }
    const int *loc = &ring_local[off[i]];
    for (int k = 0; k < n; k++) {
      f[loc[k]][0] -= g[2 * k];
      f[loc[k]][1] -= g[2 * k + 1];
    }
    if (quad[type[i]]) e += percell ? model.quadratic_constant(i, tc) : energy0[type[i]];
    energy += e;
    cell_energy[i] = e;
    if (eflag_atom) eatom[i] += e;
    if (vflag_atom) {
      // The cell's own virial, about its centroid, to the cell atom.
      for (int k = 0; k < n; k++) {
        const double rx = xy[2 * k] - m.centroid.x, ry = xy[2 * k + 1] - m.centroid.y;
        vatom[i][0] -= rx * g[2 * k];
        vatom[i][1] -= ry * g[2 * k + 1];
        vatom[i][3] -= 0.5 * (rx * g[2 * k + 1] + ry * g[2 * k]);
      }
    }
    if (vflag_cells) {
      // 'pair_modify nofdotr': the global virial is the sum of the cells' own
      // (the same as f dot r: the forces of a cell on its corners sum to zero).
      for (int k = 0; k < n; k++) {
        const double rx = xy[2 * k] - m.centroid.x, ry = xy[2 * k + 1] - m.centroid.y;
        virial[0] -= rx * g[2 * k];
        virial[1] -= ry * g[2 * k + 1];
        virial[3] -= 0.5 * (rx * g[2 * k + 1] + ry * g[2 * k]);
      }
    }
    view.set_measures(i, m.area, m.perimeter);
    x[i][0] = m.centroid.x;
    x[i][1] = m.centroid.y;
    // A topology candidate: ask for a topology step (end_of_step).
    if (!request) {
      // (and a cell of more sides below the T2 area loses its shortest edge)
      if (topo.t2_area > 0.0 && m.area < topo.t2_area && (n == 3 || topo.t1_length > 0.0))
        request = 1;
      // An edge shorter than l_T1, or folding onto the next one (the core's
      // size of an edge, from this cell's corners).
      // (edge k is u, edge k + 1 is w, which becomes the next u: each edge's
      // difference of corners and square length made once)
      double ux = xy[2] - xy[0], uy = xy[3] - xy[1];
      double lu2 = ux * ux + uy * uy;
      for (int k = 0; k < n && topo.t1_length > 0.0 && !request; k++) {
        const int k1 = k + 1 == n ? 0 : k + 1, k2 = k1 + 1 == n ? 0 : k1 + 1;
        const double wx = xy[2 * k2] - xy[2 * k1], wy = xy[2 * k2 + 1] - xy[2 * k1 + 1];
        const double lw2 = wx * wx + wy * wy;
        if (lu2 < l2) request = 1;
        // The corner at k1 sharper than 90 degrees: the distance of each far
        // end from the other edge's line.
        const double cr = ux * wy - uy * wx;
        if (ux * wx + uy * wy < 0.0 && (cr * cr < l2 * lw2 || cr * cr < l2 * lu2)) request = 1;
        ux = wx;
        uy = wy;
        lu2 = lw2;
      }
    }
  }
  view.energy = cell_energy.data();
  view_step = update->ntimestep;
  view_natoms = atom->natoms;
  for (int k = 0; k < 6; k++) view_box[k] = domain->h[k];
  view_box[6] = domain->boxlo[0];
  view_box[7] = domain->boxlo[1];
  if (eflag_global) eng_vdwl += energy;
  if (vflag_fdotr) virial_fdotr_compute();
  publish_stats();
}

/* fix deform (or change_box) changed the box after this step's forces: the
   cells of the positions and box shown, computed again (no forces) from the
   ghosts sent again in the changed box (collective), into a view of their
   own: the neighbours and junctions that the next step integrates (fix
   polarity) stay those of the force computation.  The cell atoms go to
   their polygons' centroids as at a force computation. */

void PairVertexPolygon::cells_of_changed_box()
{
  comm->forward_comm();
  const int nlocal = atom->nlocal;
  double **x = atom->x;
  const int *type = atom->type;
  int **ring = atom->iarray[ring_index];
  std::vector<double> xy, g;
  std::vector<int> nt;
  const bool percell = model.has_cell_params();
  shown.clear(nlocal, nlocal + atom->nghost, tessera::Points{&x[0][0], nlocal + atom->nghost, 3});
  shown_energy.assign(nlocal, 0.0);
  for (int i = 0; i < nlocal; i++) {
    if (role(type[i]) != CELL || ring[i][0] < 0) continue;
    const int n = gather_ring(i, xy, nt);
    g.resize(2 * n);
    const int tc = type[i] - 1;
    double e = tessera::polygon_energy(xy.data(), n, model, i, tc, nt.data(), g.data());
    if (quad[type[i]]) e += percell ? model.quadratic_constant(i, tc) : energy0[type[i]];
    shown_energy[i] = e;
    const tessera::PolygonMeasures m = tessera::polygon_measures(xy.data(), n);
    shown.add_cell(i, xy.data(), n, &nbr_local[off[i]], m.area, m.perimeter);
    x[i][0] = m.centroid.x;
    x[i][1] = m.centroid.y;
  }
  shown.finish();
  shown.energy = shown_energy.data();
  show_shown = true;
  for (int k = 0; k < 6; k++) view_box[k] = domain->h[k];
  view_box[6] = domain->boxlo[0];
  view_box[7] = domain->boxlo[1];
}

bool PairVertexPolygon::box_changed() const
{
  for (int k = 0; k < 6; k++)
    if (view_box[k] != domain->h[k]) return true;
  return view_box[6] != domain->boxlo[0] || view_box[7] != domain->boxlo[1];
}

/* fix adapt's arrays (type pairs, the values in use; build_model fills them). */

void *PairVertexPolygon::extract(const char *str, int &dim)
{
  dim = 2;
  if (strcmp(str, "kappa") == 0) return adapt_kappa;
  if (strcmp(str, "area0") == 0) return adapt_area0;
  if (strcmp(str, "gamma") == 0) return adapt_gamma;
  if (strcmp(str, "lambda") == 0) return adapt_lambda;
  if (strcmp(str, CellSource::extract_name) == 0) {
    dim = 0;
    if (!source) source = CellSource::of(*this);
    return source.get();
  }
  return nullptr;
}

const tessera::CellView &PairVertexPolygon::cells() const
{
  return show_shown ? static_cast<const tessera::CellView &>(shown) : view;
}

tessera::Contacts PairVertexPolygon::force_contacts() const
{
  return view.contacts();
}

double PairVertexPolygon::force_boundary(int c) const
{
  return view.boundary(c);
}

/* fix adapt changed extract()'s arrays: the per-type values from the
   diagonal, a junction tension it changed becomes given, and the model is
   built again for the next force computation. */

void PairVertexPolygon::reinit()
{
  Pair::reinit();
  if (!adapt_kappa) return;
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++) {
    if (roles[i] != CELL) continue;
    for (auto [name, v] : {std::pair<const char *, double>{"kappa", adapt_kappa[i][i]},
                           {"area0", adapt_area0[i][i]}})
      if (!(v > 0.0) || !std::isfinite(v))
        error->all(FLERR,
                   "pair_style vertex/polygon (fix adapt): {} of type {} must be > 0, got {}", name,
                   i, v);
    if (!(adapt_gamma[i][i] >= 0.0) || !std::isfinite(adapt_gamma[i][i]))
      error->all(FLERR,
                 "pair_style vertex/polygon (fix adapt): gamma of type {} must be >= 0, got {}", i,
                 adapt_gamma[i][i]);
    kappa[i] = adapt_kappa[i][i];
    area0[i] = adapt_area0[i][i];
    gamma[i] = adapt_gamma[i][i];
  }
  // fix adapt writes the upper triangle (j >= i).
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++)
      if (adapt_lambda[i][j] != built_lambda[i][j]) {
        lambda[i][j] = lambda[j][i] = adapt_lambda[i][j];
        if (i != j) lambda_set[i][j] = lambda_set[j][i] = 1;
      }
  build_model();
}

/* The cells are those of the last force computation: at this timestep, for
   these atoms (collective). */

void PairVertexPolygon::require_current_cells(const std::string &who)
{
  const char *why = nullptr;
  if (view_step < 0)
    why = "no force computation yet (the cells exist after a run, e.g. 'run 0')";
  else if (view_step != update->ntimestep)
    why = "its cells are those of another step";
  else if (view_natoms != atom->natoms || view.n_owned() != atom->nlocal)
    why = "the atoms changed since (atoms created or deleted)";
  int bad = why ? 1 : 0, any = 0, moved = box_changed() ? 1 : 0, box = 0;
  MPI_Allreduce(&bad, &any, 1, MPI_INT, MPI_MAX, world);
  MPI_Allreduce(&moved, &box, 1, MPI_INT, MPI_MAX, world);
  if (!any && box) cells_of_changed_box();
  if (any)
    error->all(FLERR,
               "{} reads the cells of pair_style vertex/polygon at step {}, but {}; invoke it on "
               "a timestep when pair vertex/polygon computed forces",
               who, update->ntimestep, why ? why : "on another rank they are not this step's");
}

void PairVertexPolygon::publish_stats()
{
  for (int k = 0; k < 4; k++) pvec[k] = comm->me == 0 ? stats[k] : 0.0;
}

double PairVertexPolygon::memory_usage()
{
  double bytes = Pair::memory_usage();
  bytes += (double) (off.capacity() + ring_local.capacity() + nbr_local.capacity()) * sizeof(int);
  bytes += (double) (edge_first.capacity() + edge_fill.capacity() + edge_to.capacity() +
                     edge_cell.capacity()) *
      sizeof(int);
  return bytes;
}

/* A cell atom's position is the cell's centroid, written at every force
   computation: an integrator that moves cell atoms is an error naming it. */

void PairVertexPolygon::check_integrators() const
{
  const int nlocal = atom->nlocal;
  const int *mask = atom->mask, *type = atom->type;
  for (int k = 0; k < modify->nfix; k++) {
    Fix *f = modify->fix[k];
    if (!f->time_integrate) continue;
    tagint first = MAXTAGINT, any = MAXTAGINT;
    for (int i = 0; i < nlocal; i++)
      if ((mask[i] & f->groupbit) && role(type[i]) == CELL) first = MIN(first, atom->tag[i]);
    MPI_Allreduce(&first, &any, 1, MPI_LMP_TAGINT, MPI_MIN, world);
    if (any != MAXTAGINT)
      error->all(FLERR,
                 "pair_style vertex/polygon: fix {} ({}) integrates cell atom {}; a cell atom sits "
                 "at its cell's centroid and is moved by its vertices: integrate the vertex atoms "
                 "only (e.g. 'group vertices type J' and 'fix {} vertices {} ...')",
                 f->id, f->style, any, f->id, f->style);
  }
}
