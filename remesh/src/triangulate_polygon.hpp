#pragma once
// Triangles of a polygon with more than three corners (a file's n-gon): the fan from its first corner where that fan
// covers it, else ear clipping in the polygon's plane, so a non-convex polygon (an L-shaped face) gives no triangle
// turned against the others.
#include <array>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// Appends the triangles of `polygon` (indices into `points`, in order around it) to `out`, each turning as the polygon
// does. Returns true when the fan from the first corner was not used (a non-convex polygon).
bool triangulate_polygon(const std::vector<Vec3>& points, const std::vector<int>& polygon,
                         std::vector<std::array<int, 3>>& out);

}  // namespace carbonmesh
