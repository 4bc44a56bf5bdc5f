#pragma once
// Extended XYZ: count, a comment line with Lattice (the vacuum box), Properties and pbc, then "El x y z".
#include <filesystem>

#include "carbonmesh/carbon/structure.hpp"

namespace carbonmesh {

void write_extended_xyz(const CarbonStructure& structure, const std::filesystem::path& file, double vacuum = 10.0);

}  // namespace carbonmesh
