#pragma once
// T-junctions of a triangle soup: a border vertex lying inside another border edge. Two sides of a seam triangulated
// apart (a CAD export, a model stitched from parts) load as a crack: two borders lying on each other whose vertices do
// not pair up, so welding coincident vertices cannot close it.
#include <array>
#include <cstddef>
#include <map>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct TJunctions {
  std::size_t vertices = 0;  // border vertices inside another border edge
  // The lowest such vertex and the edge (lower end, higher end) it lies in, and its distance to the edge.
  std::array<int, 3> example{-1, -1, -1};
  double example_distance = 0;
  // Per border edge (face, corner k: the edge from corner k to corner k + 1): the vertices inside it, from corner k on.
  std::map<std::pair<int, int>, std::vector<int>> inside;
};

// `border`: the edges used by one face, as (face, corner k). A border vertex is inside a border edge that does not end
// at it when it lies within `tolerance` of the segment and farther than `tolerance` from both ends.
TJunctions find_t_junctions(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& triangles,
                            const std::vector<std::pair<int, int>>& border, double tolerance);

// The triangles with every face that has vertices inside its edges split there, orientation kept: fanned from the
// opposite corner when one edge has them, else from a new vertex at the face's centroid (appended to `points`).
std::vector<std::array<int, 3>> split_at_t_junctions(std::vector<Vec3>& points,
                                                     const std::vector<std::array<int, 3>>& triangles,
                                                     const TJunctions& found);

}  // namespace carbonmesh
