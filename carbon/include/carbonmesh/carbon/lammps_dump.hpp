#pragma once
// Reading the last frame of a LAMMPS text dump ("dump custom ... id type x y z").
#include <filesystem>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct DumpFrame {
  long timestep = 0;
  std::vector<int> ids, types;  // sorted by id
  std::vector<Vec3> positions;
};

// The last complete frame. Needs the columns id, type, x, y, z (any order; xu/yu/zu accepted).
// Throws InputError for a missing file, no frame, or missing columns.
DumpFrame read_last_dump_frame(const std::filesystem::path& file);

}  // namespace carbonmesh
