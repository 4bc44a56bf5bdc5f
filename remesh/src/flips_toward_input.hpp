#pragma once
// What data_dependent_flips(), its relaxed flips (relaxed_flips.cpp) and the face caps (cap_tips.cpp) share. Internal.
#include <utility>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "carbonmesh/remesh/triangle_tree.hpp"
#include "flip_quad.hpp"

namespace carbonmesh {

// Whether the valences after the flip of the quad's edge a-b keep every vertex within one of its ideal valence (or
// no farther than it was) and E_val (Eq 4.2) within 2 of before.
bool flip_valence_ok(const TriMesh& mesh, const FlipQuad& q);

// Each face's distance to the input (`tree`), by face index: face_distance (seven samples), or its centroid's where
// that is within half the tolerance (its corners are on the input too, and most faces are such); 0 for a deleted face.
std::vector<double> face_distances(const TriMesh& mesh, const triangle_tree::Tree& tree, double tolerance);

// The interior edges with a face farther than `tolerance` (`distance`: by face index), as (-distance, edge index),
// farthest first (ties by index).
std::vector<std::pair<double, int>> far_edges(const TriMesh& mesh, const std::vector<double>& distance,
                                             double tolerance);

// The relaxed flips of data_dependent_flips() (see there), into result.relaxed_tries and result.relaxed_flips.
// `tree`: over `input`'s faces in order, from `first`; `distance`: by face index, each face's distance to the input
// in it (face_distance, or the centroid's where it is within half the tolerance), kept up to date. Vertices with
// (*fixed)[index] != 0 on a tip of the input stay.
void relaxed_flips(TriMesh& mesh, const TriMesh& input, const triangle_tree::Tree& tree,
                   triangle_tree::Triangles::const_iterator first, std::vector<double>& distance,
                   const ProjectionTarget& target, int kn, double emin, double emax, double tolerance,
                   const std::vector<char>* fixed, DataDependentFlips& result);

}  // namespace carbonmesh
