#pragma once
// Whether a remeshed face turned against the input (a fold): its normal and the normal of the input face nearest its
// centroid are more than acos(-kMaxNormalTurnCos) apart. Internal (the feature snap and the tip caps).
#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/remesh/triangle_tree.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {

inline bool turned_against_input(const triangle_tree::Tree& input_tree, const TriMesh& mesh, TriMesh::FaceHandle f) {
  using triangle_tree::to_vec;
  Vec3 a, b, c;
  geometry::face_points(mesh, f, a, b, c);
  const auto nearest = input_tree.closest_point_and_primitive(triangle_tree::to_point((a + b + c) / 3.0));
  const triangle_tree::Triangle& t = *nearest.second;
  const Vec3 normal = geometry::triangle_normal(to_vec(t[0]), to_vec(t[1]), to_vec(t[2]));
  return OpenMesh::dot(normal, geometry::triangle_normal(a, b, c)) < -geometry::kMaxNormalTurnCos;
}

}  // namespace carbonmesh
