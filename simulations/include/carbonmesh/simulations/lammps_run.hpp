#pragma once
// Running LAMMPS commands (md_deck.hpp) with the Debian LAMMPS.
//  - np == 1: in-process through liblammps (library.h: lammps_open_no_mpi, lammps_command, lammps_get_thermo,
//    lammps_gather_atoms, lammps_close). The Debian library is built without LAMMPS_EXCEPTIONS, so a LAMMPS
//    error ends the process with exit(1) instead of setting lammps_has_error; the library therefore runs in a
//    forked child of the calling process, which reports back through a JSON file. lammps_has_error is still
//    checked after every command (a library built with exceptions reports through it). The child loads the
//    library at run time (src/lammps_library.hpp); carbonmesh is not linked with it.
//  - np > 1: `mpirun [--allow-run-as-root] --oversubscribe -np N lmp -in in.simulate` in the work folder.
// Either way a LAMMPS error is an InputError of one line (the ERROR line of log.lammps), never a crash.
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct LammpsRunSettings {
  std::vector<std::string> commands;
  std::filesystem::path work_dir;  // log.lammps (and in.simulate for mpirun) go here; created if missing
  int np = 1;
  std::string lmp = "lmp", mpirun = "mpirun";  // for np > 1 (looked up on PATH)
  long steps = 0;              // NVT steps, for the progress log
  double timestep_fs = 1;      // for the progress log
  std::size_t atoms = 0;       // for the progress log (eV/atom)
};

struct LammpsRunResult {
  std::string mode;  // "liblammps (in-process)" or the mpirun command
  int np = 1;
  double seconds = 0;     // wall time of everything
  double md_seconds = 0;  // wall time from the end of the minimisation to the end of the NVT run
  double pe_minimized = std::numeric_limits<double>::quiet_NaN();  // eV, total
  double pe_final = std::numeric_limits<double>::quiet_NaN();      // eV, total
  double temperature_final = std::numeric_limits<double>::quiet_NaN();
  long steps = 0;
  std::vector<Vec3> final_positions;  // by atom id 1..N (in-process only; mpirun: read the dump)
  std::filesystem::path log;
};

// Throws InputError for a missing lmp/mpirun, a LAMMPS error or a crash of the run.
LammpsRunResult run_lammps(const LammpsRunSettings& settings);

// The lines of `file` starting with "ERROR" (the first), else its last non-empty line; "" if unreadable.
std::string lammps_error_line(const std::filesystem::path& file);

}  // namespace carbonmesh
