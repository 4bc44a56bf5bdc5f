#pragma once
// A few rings of vertices around one vertex, and the flaws of that region (edges outside [emin, emax], faces
// with an angle under 3 degrees): the acceptance test of the local steps that run after convergence
// (remove_valence_defects, snap_to_features). Internal.
#include <cstddef>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"

namespace carbonmesh {

// Moves `v` onto the target, with the points of its one-ring as the projection's neighbours (`neighbors`: scratch
// space): the projection of the local steps after convergence.
void project_with_ring(TriMesh& mesh, const ProjectionTarget& target, TriMesh::VertexHandle v,
                       std::vector<Vec3>& neighbors);

class LocalRegion {
 public:
  LocalRegion(double emin, double emax) : emin_(emin), emax_(emax) {}
  // The vertices within `rings` of v (breadth first, v first).
  void collect(const TriMesh& mesh, TriMesh::VertexHandle v, int rings, std::vector<TriMesh::VertexHandle>& out);
  // Edges outside [emin, emax] and faces with an angle under 3 degrees at the (undeleted) vertices, each edge
  // and face counted once.
  std::size_t flaws(const TriMesh& mesh, const std::vector<TriMesh::VertexHandle>& vertices);
  // The faces at the (undeleted) vertices, each once.
  void faces(const TriMesh& mesh, const std::vector<TriMesh::VertexHandle>& vertices,
             std::vector<TriMesh::FaceHandle>& out);

 private:
  double emin_, emax_;
  std::vector<unsigned> vertex_mark_, edge_mark_, face_mark_;
  unsigned stamp_ = 0;
};

}  // namespace carbonmesh
