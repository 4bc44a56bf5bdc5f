#pragma once
// Helpers shared by the remesher tests.
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh::test {

// Scales a mesh about the origin so that its mean edge length is `mean`.
inline TriMesh scaled(TriMesh mesh, double mean) {
  const double factor = mean / edge_stats(mesh).mean;
  for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * factor);
  return mesh;
}

}  // namespace carbonmesh::test
