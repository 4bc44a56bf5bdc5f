#pragma once
// Remeshed triangles with the balls around them, and the distance of a point to the nearest of a few of them: the
// local measures of the minimax fit and of the relaxed flips. Internal.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "carbonmesh/remesh/closest_point.hpp"
#include "carbonmesh/remesh/mesh.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {

inline double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return (closest_point_on_triangle(p, a, b, c) - p).norm();
}

// A triangle with the ball around it: a point farther from the centre than its distance bound plus the radius
// cannot be nearer than the bound, and its exact distance is not needed.
struct BoundedTriangle {
  Vec3 a, b, c, centre;
  double radius = 0;
};

inline BoundedTriangle bounded(const TriMesh& mesh, TriMesh::FaceHandle f) {
  BoundedTriangle t;
  geometry::face_points(mesh, f, t.a, t.b, t.c);
  t.centre = (t.a + t.b + t.c) / 3.0;
  t.radius = std::max({(t.a - t.centre).norm(), (t.b - t.centre).norm(), (t.c - t.centre).norm()});
  return t;
}

inline std::vector<BoundedTriangle> bounded(const TriMesh& mesh, const std::vector<TriMesh::FaceHandle>& faces) {
  std::vector<BoundedTriangle> out;
  out.reserve(faces.size());
  for (auto f : faces) out.push_back(bounded(mesh, f));
  return out;
}

// The distance of y to the nearest of the triangles, or `bound` if none is nearer; `hint` (a position in the list,
// or past its end) is tried first and left at the nearest.
inline double nearest_distance(const Vec3& y, const std::vector<BoundedTriangle>& triangles, double bound,
                               std::size_t& hint) {
  if (hint < triangles.size()) {
    const auto& t = triangles[hint];
    bound = std::min(bound, point_triangle_distance(y, t.a, t.b, t.c));
  }
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    const double reach = bound + t.radius;
    if (i == hint || (y - t.centre).sqrnorm() >= reach * reach) continue;
    const double d = point_triangle_distance(y, t.a, t.b, t.c);
    if (d < bound) {
      bound = d;
      hint = i;
    }
  }
  return bound;
}

inline double nearest_distance(const Vec3& y, const std::vector<BoundedTriangle>& triangles, double bound) {
  std::size_t hint = triangles.size();
  return nearest_distance(y, triangles, bound, hint);
}

}  // namespace carbonmesh
