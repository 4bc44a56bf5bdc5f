#pragma once
// A spatially coherent order of points: indices sorted by the Morton (Z-order) code of the points in their
// bounding box (21 bits per axis), ties by index. Used to put mesh elements (remesh spatial_order) and atoms
// (the dual optimisation) that are near in space near in memory.
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// order[k] is the index of the k-th point along the curve.
std::vector<int> morton_order(const std::vector<Vec3>& points);

}  // namespace carbonmesh
