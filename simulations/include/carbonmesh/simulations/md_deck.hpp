#pragma once
// The LAMMPS commands of `carbonmesh simulate`: the REBO2 deck of carbon/rebo_deck.hpp (what `carbonmesh build`
// writes) with absolute paths and the simulation's settings, plus the thermo CSV (fix print every thermo
// interval), the NVT run split into one run per picosecond, and marker lines ("carbonmesh: ...") that report
// the minimised and per-ps energies on the screen of a separate lmp process.
#include <filesystem>
#include <string>
#include <vector>

namespace carbonmesh {

struct MdDeckSettings {
  std::filesystem::path data_file;       // absolute
  std::filesystem::path potential_file;  // absolute path of CH.rebo
  std::filesystem::path dump_file, final_data_file, thermo_csv;  // outputs (absolute)
  bool hydrogen = false;  // type 2 is H
  bool topology = false;  // atom_style full
  double temperature = 300;  // K
  double timestep_fs = 1;    // fs
  double picoseconds = 10;   // NVT time
  long thermo_every = 100;   // steps
  long seed = 4928459;
};

// Steps of the NVT run: round(ps * 1000 / timestep_fs). Throws std::invalid_argument for non-positive input.
long md_steps(const MdDeckSettings& s);
// Steps per picosecond: round(1000 / timestep_fs), at least 1.
long steps_per_ps(const MdDeckSettings& s);

// One command per element (comments and blank lines dropped).
std::vector<std::string> md_commands(const MdDeckSettings& settings);

// The marker printed after the minimisation ("carbonmesh: minimized pe <eV>") and after every run segment
// ("carbonmesh: step <n> temp <K> pe <eV>").
inline constexpr const char* kMdMarker = "carbonmesh:";

// Searches `name` in the current folder, $LAMMPS_POTENTIALS and /usr/share/lammps/potentials; empty if none.
std::filesystem::path find_potential(const std::string& name = "CH.rebo");

}  // namespace carbonmesh
