// libFuzzer target: the LAMMPS data-file readers (carbon's and the analysis one) must either return a
// structure or throw InputError.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "carbonmesh/carbon/lammps_data.hpp"
#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/simulations/lammps_atoms.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = "/tmp/carbonmesh-fuzz-" + std::to_string(::getpid()) + ".data";
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    (void)carbonmesh::read_lammps_data(path);
  } catch (const carbonmesh::InputError&) {
  }
  try {
    (void)carbonmesh::read_lammps_atoms(path);
  } catch (const carbonmesh::InputError&) {
  }
  std::remove(path.c_str());
  return 0;
}
