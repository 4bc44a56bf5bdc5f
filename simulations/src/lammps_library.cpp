#include "lammps_library.hpp"

#include <dlfcn.h>

#include <stdexcept>

namespace carbonmesh {
namespace {

template <typename Function>
void resolve(void* library, const std::string& file, const char* name, Function& out) {
  out = reinterpret_cast<Function>(dlsym(library, name));
  if (out == nullptr) throw std::runtime_error("cannot load LAMMPS: " + file + " has no " + name);
}

}  // namespace

const char* lammps_library_file() { return CARBONMESH_LAMMPS_LIBRARY; }

LammpsLibrary load_lammps_library(const std::string& file) {
  void* library = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    const char* why = dlerror();  // names the file
    throw std::runtime_error("cannot load LAMMPS: " + (why ? std::string(why) : file));
  }
  LammpsLibrary l;
  resolve(library, file, "lammps_open_no_mpi", l.open_no_mpi);
  resolve(library, file, "lammps_close", l.close);
  resolve(library, file, "lammps_mpi_finalize", l.mpi_finalize);
  resolve(library, file, "lammps_version", l.version);
  resolve(library, file, "lammps_command", l.command);
  resolve(library, file, "lammps_has_error", l.has_error);
  resolve(library, file, "lammps_get_last_error_message", l.get_last_error_message);
  resolve(library, file, "lammps_get_thermo", l.get_thermo);
  resolve(library, file, "lammps_get_natoms", l.get_natoms);
  resolve(library, file, "lammps_gather_atoms", l.gather_atoms);
  return l;
}

}  // namespace carbonmesh
