#pragma once
// `carbonmesh simulate`: REBO2 molecular dynamics of a built structure (minimise, then NVT) with the Debian
// LAMMPS, and the stability analysis of the final frame against the structure as built (stability.hpp).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/simulations/lammps_run.hpp"
#include "carbonmesh/simulations/stability.hpp"

namespace carbonmesh {

struct SimulationSettings {
  std::filesystem::path structure_dir;  // a build folder: structure.data (as `carbonmesh build` writes it)
  std::filesystem::path output_dir;     // empty: structure_dir / "simulation"
  double picoseconds = 10, temperature = 300, timestep_fs = 1;
  int np = 1;  // 1: in-process liblammps; N > 1: mpirun -np N lmp
  long seed = 4928459;
  std::string lmp = "lmp", mpirun = "mpirun";
  std::filesystem::path potential;  // empty: find_potential("CH.rebo")
  StabilitySettings stability;
  bool report = true;  // the analysis report of the final frame (report.json, CSVs, PLY) in output_dir/report
};

struct SimulationResult {
  std::filesystem::path structure_dir, output_dir;
  std::size_t atoms = 0, carbon_atoms = 0, hydrogen_atoms = 0;
  double picoseconds = 0, temperature = 0, timestep_fs = 0;
  LammpsRunResult run;  // final_positions moved out
  double pe_minimized_per_atom = 0, pe_final_per_atom = 0;  // eV/atom (all atoms)
  double atom_steps_per_second = 0;                          // atoms * NVT steps / md_seconds
  FrameComparison comparison;                                // final frame vs structure.data
  std::vector<std::string> files;                            // written into output_dir
};

// Throws InputError for a missing/bad structure, a missing CH.rebo, a missing LAMMPS or a LAMMPS error.
SimulationResult simulate(const SimulationSettings& settings);

nlohmann::json to_json(const SimulationResult& r);
std::string to_text(const SimulationResult& r);

// REBO2 graphene cohesive energy per atom (eV), the reference the energies are compared with.
inline constexpr double kGrapheneReboEnergy = -7.4;

}  // namespace carbonmesh
