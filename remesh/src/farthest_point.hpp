#pragma once
// The farthest point of a set of triangles from a surface (an AABB tree over its triangles), bracketed by branch and
// bound: the Hausdorff maxima (hausdorff.cpp) and the minimax fit's check of a region. Internal.
#include <cstddef>

#include "carbonmesh/remesh/triangle_tree.hpp"

namespace carbonmesh {

struct Farthest {
  double distance = 0, bound = 0;  // attained at `at`; no point is farther than `bound`
  triangle_tree::Point at;
};

// The largest distance of the triangles' points to the tree's surface, bracketed: pieces (the faces first) whose
// upper bound exceeds the largest distance found so far by more than `tolerance` are split into four, highest bounds
// first, until none is left or `max_pieces` more than the faces have been measured. The same for any thread count.
Farthest farthest_point(const triangle_tree::Triangles& triangles, const triangle_tree::Tree& tree, double tolerance,
                        std::size_t max_pieces);

}  // namespace carbonmesh
