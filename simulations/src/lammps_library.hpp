#pragma once
// The LAMMPS C library interface (lammps/library.h), loaded at run time with dlopen the first time a run needs it,
// as LAMMPS's own plugin loader (examples/COUPLE/plugin, not in the Debian packages) does. Linking liblammps into
// the carbonmesh program loaded it and its ~50 dependencies (MPI, Python, curl, Kerberos, ...) at every start,
// for every command: 40 ms of the 45 ms a `carbonmesh --version` took, twice with the huge-page restart.
#include <lammps/library.h>

#include <string>

namespace carbonmesh {

// The functions of library.h that a run calls, typed from its declarations.
struct LammpsLibrary {
  decltype(&::lammps_open_no_mpi) open_no_mpi = nullptr;
  decltype(&::lammps_close) close = nullptr;
  decltype(&::lammps_mpi_finalize) mpi_finalize = nullptr;
  decltype(&::lammps_version) version = nullptr;
  decltype(&::lammps_command) command = nullptr;
  decltype(&::lammps_has_error) has_error = nullptr;
  decltype(&::lammps_get_last_error_message) get_last_error_message = nullptr;
  decltype(&::lammps_get_thermo) get_thermo = nullptr;
  decltype(&::lammps_get_natoms) get_natoms = nullptr;
  decltype(&::lammps_gather_atoms) gather_atoms = nullptr;
};

// The LAMMPS shared library the build found: its soname (liblammps.so.0 on Debian), searched as the dynamic linker
// searches.
const char* lammps_library_file();

// Loads `file` and every function above; throws std::runtime_error naming the file and what is missing. The
// library stays loaded for the rest of the process.
LammpsLibrary load_lammps_library(const std::string& file = lammps_library_file());

}  // namespace carbonmesh
