#pragma once
// The LAMMPS input deck for REBO2 (pair_style rebo, CH.rebo): read the data file, minimise, give 300 K
// velocities, run NVT, dump the trajectory. Runs as written with `lmp -in in.rebo` (Debian's lmp finds CH.rebo
// in its potentials folder) or `mpirun -np N lmp -in in.rebo`.
#include <filesystem>
#include <string>

namespace carbonmesh {

struct ReboDeckSettings {
  std::string data_file = "structure.data";  // relative to the folder lmp runs in
  std::string dump_file = "dump.rebo.lammpstrj";
  std::string final_data_file = "final.data";
  bool hydrogen = false;  // the data file has type 2 = H
  bool topology = false;  // the data file is atom_style full (bonds and angles are carried, not used by REBO)
  double temperature = 300.0;  // K
  double timestep = 0.001;     // ps
  long steps = 10000;          // 10 ps
  long thermo_every = 100;
  long dump_every = 1000;  // lowered to the largest divisor of steps not above it: the last step is dumped
  long minimize_iterations = 10000;
  long seed = 4928459;
  int mpi_ranks = 4;  // in the comment line only
};

// The deck text.
std::string rebo_deck(const ReboDeckSettings& settings);

// Writes rebo_deck(settings) atomically.
void write_rebo_deck(const ReboDeckSettings& settings, const std::filesystem::path& file);

}  // namespace carbonmesh
