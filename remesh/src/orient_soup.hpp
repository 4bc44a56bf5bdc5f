#pragma once
// The repair of a triangle soup whose faces disagree in orientation or whose edges or vertices are not manifold: the
// faces oriented alike and the vertices where the surface is not a disk duplicated (CGAL's orient_polygon_soup), then
// every connected component turned back to the orientation most of its faces had in the file.
#include <array>
#include <cstddef>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct OrientedSoup {
  std::size_t reversed_faces = 0;       // faces whose corner order was reversed
  std::size_t duplicated_vertices = 0;  // vertices added: copies of one where the surface was not a disk
};

// Changes `triangles` (and appends to `points`) only where the soup needs it: a consistently oriented manifold soup is
// left as it is.
OrientedSoup orient_soup(std::vector<Vec3>& points, std::vector<std::array<int, 3>>& triangles);

}  // namespace carbonmesh
