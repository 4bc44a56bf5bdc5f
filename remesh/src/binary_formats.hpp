#pragma once
// Readers for PLY (ASCII and binary) and STL (ASCII and binary), in double precision. OpenMesh's readers pass
// coordinates through single precision and loop forever on some truncated PLY headers, so carbonmesh reads
// these formats itself; every problem is an InputError naming the file and the place.
#include <filesystem>

#include "carbonmesh/remesh/io.hpp"

namespace carbonmesh::detail {

PolygonSoup read_ply(const std::filesystem::path& file);
// STL stores every triangle with its own corners; corners at the same position are merged.
PolygonSoup read_stl(const std::filesystem::path& file);

// PLY with double-precision coordinates (binary little endian). Returns false on a failed write.
bool write_ply(const TriMesh& mesh, const std::filesystem::path& file);

}  // namespace carbonmesh::detail
