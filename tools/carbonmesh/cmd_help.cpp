// `carbonmesh help [TOPIC]`: a subcommand's full option list (every option with its default and unit), all of
// them, or a short topic page (units, exit codes, files, the stability verdict).
#include <fmt/format.h>

#include <iostream>
#include <map>
#include <string>

#include "carbonmesh/remesh/error.hpp"
#include "commands.hpp"

namespace carbonmesh::cli {
namespace {

const std::map<std::string, std::string>& topics() {
  static const std::map<std::string, std::string> pages{
      {"units",
       "Units\n"
       "  stats, shape, remesh: lengths are in the mesh's own units (the seed-protocol models: mean edge 2.25).\n"
       "  build: the input is scaled to Angstrom (--size L, --scale s or --atoms N; without them the input\n"
       "         coordinates are taken as Angstrom); --bond b in A (default 1.42), the primal edge is sqrt(3) b\n"
       "         and the remesh interval sqrt(3) b [0.8, 1.2] unless --emin/--emax (A) are given.\n"
       "  LAMMPS files: units metal (A, eV, ps, g/mol); the deck's timestep is 0.001 ps = 1 fs.\n"
       "  simulate: --ps picoseconds, --temp K, --timestep fs, --cutoff A; energies eV and eV/atom.\n"
       "  analyze: distances in A for structures, mesh units for meshes; angles in degrees.\n"},
      {"exit-codes",
       fmt::format("Exit codes\n"
                   "  0  success; remesh also exits 0 when long/short edges remain (it warns and says how many;\n"
                   "     --json has \"converged\": false); simulate exits 0 for either verdict (see \"verdict\")\n"
                   "  1  an unexpected internal error (a bug: please report it with the input)\n"
                   "  {}  bad input: a missing, unreadable or invalid file, a bad option or value; one line on stderr\n"
                   "     naming the file and the problem, no output file written or touched\n"
                   "  {}  the remesher's topology guard fired: the result had another genus, component or border\n"
                   "     count than the input; the best mesh with the input's topology was written instead\n"
                   "  Interrupted runs (SIGINT/SIGTERM) remove their temporary files and exit with the signal.\n",
                   kExitBadInput, kExitTopologyViolation)},
      {"files",
       "Files (details: docs/formats.md)\n"
       "  reads:  .off .obj .ply (ascii/binary) .stl (ascii/binary) meshes; LAMMPS data files (analyze)\n"
       "  remesh OUT: .off .obj .ply (double precision) or .stl; --log: CSV, one line per iteration\n"
       "  build -o DIR: structure.data (LAMMPS, atom_style atomic; --topology adds structure-full.data),\n"
       "         in.rebo (REBO2 deck), structure.xyz (extended XYZ), structure.pdb (CONECT), rings.ply (dual,\n"
       "         ring-size colours), remeshed.off, summary.json, analysis/ (defect report)\n"
       "  simulate DIR: DIR/simulation/ with simulation.json, summary.txt, thermo.csv, dumps, final frame\n"
       "  Every file is written to a temporary name in its folder and renamed into place.\n"},
      {"verdict",
       "Stability verdict of `carbonmesh simulate` (details: docs/simulate.md)\n"
       "  stable when at least 99% of the carbon atoms that had three carbon neighbours still have exactly\n"
       "  three (cutoff --cutoff, default 1.85 A) in the final frame and at most 1% of the rings changed;\n"
       "  otherwise unstable. The rule is printed with the verdict and stored in simulation.json.\n"},
  };
  return pages;
}

std::string topic_list(const CLI::App& app) {
  std::string list = "all";
  for (const CLI::App* sub : app.get_subcommands({}))
    if (sub->get_name() != "help") list += ", " + sub->get_name();
  for (const auto& [name, page] : topics()) list += ", " + name;
  return list;
}

}  // namespace

void add_help_command(CLI::App& app, Action& action) {
  auto topic = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("help", "help TOPIC: a command's options (defaults, units), all, units, "
                                         "exit-codes, files, verdict");
  cmd->add_option("topic", *topic, "a command name, all, units, exit-codes, files or verdict (default: the list)");
  cmd->callback([&app, &action, topic] {
    action = [&app, topic]() -> int {
      // app.help() would show this subcommand (the parsed one), so the overview is assembled here.
      if (topic->empty()) {
        std::cout << app.get_description() << "\nUsage: " << app.get_name() << " [OPTIONS] COMMAND\n\nCommands:\n";
        for (const CLI::App* sub : app.get_subcommands({}))
          std::cout << fmt::format("  {:<10} {}\n", sub->get_name(), sub->get_description());
        std::cout << "\nOptions (before COMMAND):\n  -v, -vv    more log output (debug, trace)\n"
                     "  -q         only warnings and errors\n  --version  print the version\n"
                     "\nTopics: carbonmesh help TOPIC with TOPIC one of " << topic_list(app) << "\n";
        return 0;
      }
      if (*topic == "all") {
        for (const CLI::App* sub : app.get_subcommands({}))
          if (sub->get_name() != "help") std::cout << sub->help(app.get_name()) << "\n";
        return 0;
      }
      if (const auto page = topics().find(*topic); page != topics().end()) {
        std::cout << page->second;
        return 0;
      }
      for (const CLI::App* sub : app.get_subcommands({}))
        if (sub->get_name() == *topic && sub->get_name() != "help") {
          std::cout << sub->help(app.get_name());
          return 0;
        }
      throw InputError(fmt::format("no help topic '{}'; topics: {}", *topic, topic_list(app)));
    };
  });
}

}  // namespace carbonmesh::cli
