#pragma once
// One linearised step of a minimax problem over vertex displacements: the largest of a few distances, each linear in
// the displacements near where it was measured, made least subject to linearised edge lengths and a box trust
// region (a linear program, solved by GLPK's simplex in floating point: the minimax fit checks every step it keeps
// against the true lengths and distances). The minimax fit's joint moves. Internal.
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// value + sum over terms of gradient . d[vertex]: a distance, or an edge's length.
struct LinearRow {
  double value = 0;
  std::vector<std::pair<std::size_t, Vec3>> terms;  // (movable vertex, gradient)
};

// The displacements d (one a vertex, each coordinate within [-radius, radius]) that make the largest distance row
// least, with every length row within [lower, upper]; none if no displacement within the box keeps every length
// row there (or the solver failed).
std::optional<std::vector<Vec3>> minimax_step(const std::vector<LinearRow>& distances,
                                              const std::vector<LinearRow>& lengths, double lower, double upper,
                                              std::size_t vertices, double radius);

}  // namespace carbonmesh
