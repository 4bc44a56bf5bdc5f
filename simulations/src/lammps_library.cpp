#include "lammps_library.hpp"

#include <dlfcn.h>

#include <stdexcept>

namespace carbonmesh {
namespace {

template <typename Function>
void resolve(void* library, const char* name, Function& out) {
  out = reinterpret_cast<Function>(dlsym(library, name));
  if (out == nullptr)
    throw std::runtime_error(std::string("cannot load LAMMPS: ") + CARBONMESH_LAMMPS_LIBRARY + " has no " + name);
}

}  // namespace

LammpsLibrary load_lammps_library() {
  void* library = dlopen(CARBONMESH_LAMMPS_LIBRARY, RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    const char* why = dlerror();
    throw std::runtime_error(std::string("cannot load LAMMPS: ") + (why ? why : CARBONMESH_LAMMPS_LIBRARY));
  }
  LammpsLibrary l;
  resolve(library, "lammps_open_no_mpi", l.open_no_mpi);
  resolve(library, "lammps_close", l.close);
  resolve(library, "lammps_mpi_finalize", l.mpi_finalize);
  resolve(library, "lammps_version", l.version);
  resolve(library, "lammps_command", l.command);
  resolve(library, "lammps_has_error", l.has_error);
  resolve(library, "lammps_get_last_error_message", l.get_last_error_message);
  resolve(library, "lammps_get_thermo", l.get_thermo);
  resolve(library, "lammps_get_natoms", l.get_natoms);
  resolve(library, "lammps_gather_atoms", l.gather_atoms);
  return l;
}

}  // namespace carbonmesh
