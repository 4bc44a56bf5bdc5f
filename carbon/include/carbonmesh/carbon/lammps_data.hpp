#pragma once
// LAMMPS data files (units metal): atom_style atomic, or atom_style full with Bonds and Angles (--topology).
// Atom type 1 is C, type 2 is H (present only when the structure has hydrogen). Non-periodic box with vacuum.
#include <filesystem>
#include <string>
#include <vector>

#include "carbonmesh/carbon/structure.hpp"

namespace carbonmesh {

struct LammpsDataSettings {
  bool topology = false;  // atom_style full with Bonds (1 C-C, 2 C-H) and Angles (1 C-C-C, 2 with an H)
  double vacuum = 10.0;   // empty space around the atoms on every side (Angstrom)
};

// Writes atomically. Throws std::runtime_error if the file cannot be written.
void write_lammps_data(const CarbonStructure& structure, const std::filesystem::path& file,
                       const LammpsDataSettings& settings = {});

// LAMMPS atom type of an element (1 for C, 2 for H).
int lammps_type(Element e);

// What a data file holds, as read back.
struct LammpsData {
  std::string atom_style;  // "atomic" or "full" (from the "Atoms # style" comment or the column count)
  int atom_types = 0, bond_types = 0, angle_types = 0;
  Box box;
  std::vector<double> masses;    // by type - 1
  std::vector<int> ids, types;   // by line order
  std::vector<Vec3> positions;
  std::vector<std::array<int, 3>> bonds;   // type, atom id, atom id
  std::vector<std::array<int, 4>> angles;  // type, atom ids
};

// Reads the header counts and the Masses, Atoms, Bonds and Angles sections of a data file written by
// write_lammps_data (or a LAMMPS write_data in these styles). Throws InputError naming the line on bad content.
LammpsData read_lammps_data(const std::filesystem::path& file);

}  // namespace carbonmesh
