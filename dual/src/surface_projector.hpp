#pragma once
// Closest points on a triangle mesh (a CGAL AABB tree). Internal to dual: CGAL stays a private dependency.
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

  // closest[i] = the point of the surface nearest to points[i] (OpenMP over points; deterministic). If `closest`
  // already holds one point per query, those points are used as search hints (the answer is the same).
  void closest_points(const std::vector<Vec3>& points, std::vector<Vec3>& closest) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace carbonmesh::detail
