#pragma once
// Readers for PLY (ASCII and binary) and STL (ASCII and binary), in double precision. OpenMesh's readers pass
// coordinates through single precision and loop forever on some truncated PLY headers, so carbonmesh reads
// these formats itself; every problem is an InputError naming the file and the place.
#include <cstdio>
#include <filesystem>
#include <string>

#include "carbonmesh/remesh/io.hpp"

namespace carbonmesh::detail {

// A piece of file content quoted in a one-line error message: bytes outside printable ASCII as \xNN, at most
// 40 characters (binary garbage must not reach the terminal).
inline std::string printable(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (out.size() >= 40) return out + "...";
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte < 0x7f) {
      out += c;
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", byte);
      out += hex;
    }
  }
  return out;
}

PolygonSoup read_ply(const std::filesystem::path& file);
// STL stores every triangle with its own corners; corners at the same position are merged.
PolygonSoup read_stl(const std::filesystem::path& file);

// PLY with double-precision coordinates (binary little endian). Returns false on a failed write.
bool write_ply(const TriMesh& mesh, const std::filesystem::path& file);

}  // namespace carbonmesh::detail
