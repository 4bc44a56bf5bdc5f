#pragma once
// Double-precision readers and writers for the text formats OFF and OBJ. OpenMesh's readers and writers pass
// coordinates through single precision, which would move edge lengths across a strict interval bound.
#include <filesystem>

#include "carbonmesh/remesh/io.hpp"

namespace carbonmesh::detail {

// Throw InputError naming the file, the problem and the line.
PolygonSoup read_off(const std::filesystem::path& file);
PolygonSoup read_obj(const std::filesystem::path& file);

// Write every coordinate with 17 significant digits (exact round trip). Return false on a failed write.
bool write_off(const TriMesh& mesh, const std::filesystem::path& file);
bool write_obj(const TriMesh& mesh, const std::filesystem::path& file);

}  // namespace carbonmesh::detail
