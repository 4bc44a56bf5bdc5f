#pragma once
// Loading and saving triangle meshes (OFF, OBJ, PLY, STL in; OFF, OBJ, PLY, STL out) with validation.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// A mesh as a file gives it: points and polygons (indices into points), before any topology is built.
struct PolygonSoup {
  std::vector<Vec3> points;
  std::vector<std::vector<int>> polygons;
};

struct LoadSettings {
  // Merge duplicate and nearly coincident vertices, orient the faces alike, split non-manifold edges and vertices,
  // split faces at T-junctions, drop degenerate and duplicate faces instead of failing.
  bool repair = false;
};

// What loading found and did; every count is also logged.
struct LoadReport {
  std::size_t input_vertices = 0;
  std::size_t input_polygons = 0;
  std::size_t triangulated_polygons = 0;  // polygons with more than three corners, triangulated
  std::size_t nonconvex_polygons = 0;  // of those, the ones the fan from the first corner does not cover (ear clipping)
  std::size_t unreferenced_vertices = 0;  // removed
  std::size_t duplicate_vertices = 0;     // vertices at the same position as an earlier one
  std::size_t near_duplicate_vertices = 0;  // others within 4 float roundings of the largest coordinate of one
  std::size_t reversed_faces = 0;  // faces turned to agree with their neighbours (repair)
  std::size_t split_vertices = 0;  // copies added where edges or vertices were not manifold (repair)
  std::size_t t_junctions = 0;  // border vertices inside another border edge (within the same tolerance)
  std::size_t degenerate_faces = 0;       // zero area or a repeated corner
  std::size_t duplicate_faces = 0;        // same corner set as an earlier face
  bool repaired = false;
};

// Reads the raw points and polygons of a file (format from the extension), in double precision.
// Throws InputError naming the file and the problem.
PolygonSoup read_polygon_soup(const std::filesystem::path& file);

// Validates a soup and builds the half-edge mesh. `source` names the input in error messages.
// Throws InputError (NaN/Inf coordinates, out-of-range indices, no faces, and -- unless settings.repair --
// non-manifold edges or vertices, inconsistent orientation, duplicate or nearly coincident vertices, T-junctions and
// degenerate faces).
TriMesh build_mesh(const PolygonSoup& soup, const std::string& source, const LoadSettings& settings = {},
                   LoadReport* report = nullptr);

// read_polygon_soup + build_mesh.
TriMesh load_mesh(const std::filesystem::path& file, const LoadSettings& settings = {},
                  LoadReport* report = nullptr);

// Saves a mesh; the format follows the extension (.off, .obj, .ply, .stl). Written to a temporary name in
// the same folder and renamed into place. Throws InputError for an unknown extension or a failed write.
void save_mesh(const TriMesh& mesh, const std::filesystem::path& file);

}  // namespace carbonmesh
