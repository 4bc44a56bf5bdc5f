#pragma once
// Closest points on a triangle mesh. Internal to dual: CGAL stays a private dependency.
//
// Two kinds of query: a global one (a CGAL AABB tree) that finds the nearest face anywhere, used once to seat
// every atom, and a local one that walks from a face hint across neighbouring faces to the nearest face in its
// neighbourhood. The optimiser calls the local query at every energy evaluation: it costs a few point-triangle
// tests instead of a tree descent, and an atom stays on its own sheet of the surface (the global closest point
// of an atom on a thin feature, between two fingers say, may lie on the other side).
#include <memory>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh::detail {

class SurfaceProjector {
 public:
  explicit SurfaceProjector(const TriMesh& surface);
  ~SurfaceProjector();
  SurfaceProjector(const SurfaceProjector&) = delete;
  SurfaceProjector& operator=(const SurfaceProjector&) = delete;

  // closest[i] = the point of the surface nearest to points[i], faces[i] its face (OpenMP over points;
  // deterministic).
  void closest_points(const std::vector<Vec3>& points, std::vector<Vec3>& closest, std::vector<int>& faces) const;

  // The point nearest to q among `face` and the faces around its corners, repeated from the better face until
  // no neighbour is nearer (at most 64 steps): a local minimum of the distance. Updates `face`.
  Vec3 closest_point_near(const Vec3& q, int& face) const;

  std::size_t faces() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace carbonmesh::detail
