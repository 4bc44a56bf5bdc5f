#pragma once
// Reading LAMMPS data files (the subset carbonmesh writes and reads back: atomic, full, molecular, bond and
// charge atom styles; header counts, box, Masses, Atoms; other sections are skipped, Bonds are kept).
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/simulations/atom_graph.hpp"

namespace carbonmesh {

struct LammpsAtoms {
  std::string title;       // first line
  std::string atom_style;  // as given after "Atoms #", or inferred from the column count
  std::array<double, 3> box_lo{0, 0, 0}, box_hi{0, 0, 0};
  std::array<double, 3> tilt{0, 0, 0};  // xy xz yz
  int atom_types = 0;
  std::vector<double> masses;  // index type-1; 0 when not given
  std::vector<long> ids;       // atom ids, in file order
  std::vector<int> types;      // 1-based types
  std::vector<Vec3> positions;
  std::vector<Bond> bonds;  // from a Bonds section (atom indices in file order), empty if none
};

// Throws InputError "file:line: problem" for anything malformed (missing header counts or box, truncated
// sections, non-numeric or non-finite values, duplicate or unknown atom ids, types out of range).
LammpsAtoms read_lammps_atoms(const std::filesystem::path& file);

}  // namespace carbonmesh
