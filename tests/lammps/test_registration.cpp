// Tessera: active Voronoi vertex model in LAMMPS.  SPDX-License-Identifier: GPL-2.0-or-later
//
// tessera_register_styles() on a live LAMMPS instance: every table entry
// lands in its map, registering twice is harmless, and a host LAMMPS that
// already has an upstream style (here a stand-in `fix brownian`) keeps it.

#include "tessera_styles.h"

#include "force.h"
#include "input.h"
#include "lammps.h"
#include "lammpsplugin.h"
#include "modify.h"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

namespace {

LAMMPS *quiet_lammps()
{
  std::vector<std::string> words = {"test", "-log", "none", "-screen", "none", "-nocite"};
  std::vector<char *> args;
  for (std::string &word : words) args.push_back(&word[0]);
  args.push_back(nullptr);
  return new LAMMPS(static_cast<int>(words.size()), args.data(), MPI_COMM_WORLD);
}

Fix *host_brownian(LAMMPS *, int, char **)
{
  return nullptr;
}

bool in_map(LAMMPS *lmp, const TesseraStyle &style)
{
  if (style.command == "pair_style") return lmp->force->pair_map->count(style.name) == 1;
  if (style.command == "fix") return lmp->modify->fix_map->count(style.name) == 1;
  if (style.command == "compute") return lmp->modify->compute_map->count(style.name) == 1;
  if (style.command == "command") return lmp->input->command_map->count(style.name) == 1;
  return false;
}

}    // namespace

TEST(Registration, EveryStyleLandsInItsMap)
{
  LAMMPS *lmp = quiet_lammps();
  ASSERT_EQ(lmp->modify->fix_map->count("brownian"), 0u) << "packaged LAMMPS has no fix brownian";
  const std::vector<TesseraStyle> styles = tessera_register_styles(lmp);
  ASSERT_FALSE(styles.empty());
  bool brownian = false;
  for (const TesseraStyle &style : styles) {
    EXPECT_TRUE(style.provided) << style.command << " " << style.name;
    EXPECT_FALSE(style.replaced_host) << style.command << " " << style.name;
    EXPECT_TRUE(in_map(lmp, style)) << style.command << " " << style.name;
    if (style.command == "fix" && style.name == "brownian") brownian = true;
  }
  EXPECT_TRUE(brownian);
  EXPECT_EQ(tessera_register(lmp), static_cast<int>(styles.size()));
  delete lmp;
}

TEST(Registration, TwiceIsHarmless)
{
  LAMMPS *lmp = quiet_lammps();
  const std::vector<TesseraStyle> first = tessera_register_styles(lmp);
  const auto creator = (*lmp->modify->fix_map)["brownian"];
  const std::vector<TesseraStyle> second = tessera_register_styles(lmp);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); i++) {
    EXPECT_TRUE(second[i].provided);
    EXPECT_FALSE(second[i].replaced_host);
  }
  EXPECT_EQ((*lmp->modify->fix_map)["brownian"], creator);
  delete lmp;
}

TEST(Registration, HostBrownianIsKept)
{
  LAMMPS *lmp = quiet_lammps();
  (*lmp->modify->fix_map)["brownian"] = &host_brownian;
  for (const TesseraStyle &style : tessera_register_styles(lmp)) {
    if (style.command == "fix" && style.name == "brownian") {
      EXPECT_FALSE(style.provided);
    } else {
      EXPECT_TRUE(style.provided);
    }
  }
  EXPECT_EQ((*lmp->modify->fix_map)["brownian"], &host_brownian);
  delete lmp;
}

/* The plugin route (tessera_register_plugin, what lammpsplugin_init calls) with
   a stand-in for LAMMPS's plugin_register(): it records each lammpsplugin_t and
   inserts its creator the way LAMMPS does (cast back to the map's type). */

namespace {

std::vector<lammpsplugin_t> registered;

void fake_plugin_register(lammpsplugin_t *plugin, void *ptr)
{
  auto lmp = static_cast<LAMMPS *>(ptr);
  registered.push_back(*plugin);
  const std::string style = plugin->style;
  if (style == "pair")
    (*lmp->force->pair_map)[plugin->name] = (Force::PairCreator) plugin->creator.v1;
  else if (style == "fix")
    (*lmp->modify->fix_map)[plugin->name] = (Modify::FixCreator) plugin->creator.v2;
  else if (style == "compute")
    (*lmp->modify->compute_map)[plugin->name] = (Modify::ComputeCreator) plugin->creator.v2;
  else if (style == "command")
    (*lmp->input->command_map)[plugin->name] = (Input::CommandCreator) plugin->creator.v1;
}

std::vector<std::string> registered_names()
{
  std::vector<std::string> names;
  for (const lammpsplugin_t &p : registered) names.push_back(std::string(p.style) + " " + p.name);
  return names;
}

}    // namespace

TEST(PluginRegistration, EveryTableStyleWithTheLammpsVersion)
{
  LAMMPS *lmp = quiet_lammps();
  registered.clear();
  int handle = 0;
  const std::vector<TesseraStyle> styles =
      tessera_register_plugin(lmp, &handle, reinterpret_cast<void *>(&fake_plugin_register));
  ASSERT_EQ(registered.size(), styles.size());    // the packaged LAMMPS lacks fix brownian
  const std::vector<std::string> names = registered_names();
  for (const char *want : {"pair vertex/voronoi", "fix polarity", "fix brownian",
                           "compute vertex/atom", "pair vertex/polygon", "command create_vertices"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  for (const lammpsplugin_t &p : registered) {
    EXPECT_STREQ(p.version, lmp->version) << p.name;    // LAMMPS compares these
    EXPECT_EQ(p.handle, &handle);
    EXPECT_NE(p.creator.v1, nullptr);
  }
  for (const TesseraStyle &style : styles) EXPECT_TRUE(in_map(lmp, style)) << style.name;
  // a second `plugin load`: everything is ours already, nothing is registered again
  registered.clear();
  tessera_register_plugin(lmp, &handle, reinterpret_cast<void *>(&fake_plugin_register));
  EXPECT_TRUE(registered.empty());
  delete lmp;
}

TEST(PluginRegistration, HostBrownianIsKept)
{
  LAMMPS *lmp = quiet_lammps();
  (*lmp->modify->fix_map)["brownian"] = &host_brownian;
  registered.clear();
  for (const TesseraStyle &style :
       tessera_register_plugin(lmp, nullptr, reinterpret_cast<void *>(&fake_plugin_register)))
    EXPECT_EQ(style.provided, !(style.command == "fix" && style.name == "brownian")) << style.name;
  const std::vector<std::string> names = registered_names();
  EXPECT_EQ(std::find(names.begin(), names.end(), "fix brownian"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "fix polarity"), names.end());
  EXPECT_EQ((*lmp->modify->fix_map)["brownian"], &host_brownian);
  delete lmp;
}

TEST(Registration, NullHandle)
{
  EXPECT_EQ(tessera_register(nullptr), -1);
  EXPECT_STRNE(tessera_version(), "");
}

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  const int failed = RUN_ALL_TESTS();
  MPI_Finalize();
  return failed;
}
