#pragma once
// The dual mesh as an ASCII PLY (double coordinates) with a colour per face by ring size: pentagons red,
// hexagons grey, heptagons blue, any other size yellow.
#include <array>
#include <filesystem>

#include "carbonmesh/dual/dual_mesh.hpp"

namespace carbonmesh {

std::array<unsigned char, 3> ring_colour(int ring_size);

void write_ring_ply(const DualMesh& mesh, const std::filesystem::path& file);

}  // namespace carbonmesh
