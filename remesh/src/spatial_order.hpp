#pragma once
// The mesh of `points` and `faces` (vertex indices into points, consistently oriented) built in spatial memory
// order: vertices in Morton order of their positions, faces by their smallest new vertex index, each starting at
// that vertex. spatial_order and midpoint_subdivision build their meshes with it. Internal.
#include <array>
#include <cstddef>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// Returns false, leaving `out` unspecified, if a face cannot be added (a non-manifold face set). `renumber`
// receives the new index of every point. `edges`: how many edges the mesh will have (its arrays are reserved for
// them, so that none grows by copying while the faces are added).
bool build_in_spatial_order(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& faces,
                            std::size_t edges, TriMesh& out, std::vector<int>& renumber);

}  // namespace carbonmesh
