#pragma once
// Pairs of triangles of a mesh that cross or touch away from the corners and edge they share: a surface that passes
// through itself (two interpenetrating shells, a fold, a fin pushed through a wall). The carbon sheets built on such
// a surface cross there too, with atoms of one sheet inside the rings of the other.
#include <array>
#include <cstddef>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct SelfIntersections {
  std::size_t pairs = 0;  // pairs of faces that intersect (faces sharing a corner or an edge only if they overlap)
  std::size_t faces = 0;  // faces in at least one such pair
  std::array<int, 2> example{-1, -1};  // (lower, higher) face index of the pair first in that order; -1: none
  bool searched = true;  // false: not searched, the mesh cannot pass through itself by construction (then no pairs)
};

// CGAL::Polygon_mesh_processing::self_intersections on exact predicates (deleted faces left out; face indices are the
// mesh's own). Deterministic: the count and the example do not depend on the order CGAL reports the pairs in.
SelfIntersections self_intersections(const TriMesh& mesh);

nlohmann::json to_json(const SelfIntersections& s);
// "self-intersections none", or "self-intersections 228 face pairs (142 faces; e.g. faces 12 and 1530)".
std::string to_text(const SelfIntersections& s);

}  // namespace carbonmesh
