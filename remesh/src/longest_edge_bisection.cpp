// Longest-edge bisection (OpenMesh's LongestEdgeT): the coarse-input step of the remesher and the refinement of
// the projection target. New vertices lie at edge midpoints, so the surface stays the same.
#include "carbonmesh/remesh/remesh_steps.hpp"

#include <OpenMesh/Tools/Subdivider/Uniform/LongestEdgeT.hh>

namespace carbonmesh {

void longest_edge_bisection(TriMesh& mesh, double max_edge) {
  OpenMesh::Subdivider::Uniform::LongestEdgeT<TriMesh, double> bisection;
  bisection.attach(mesh);
  bisection.set_max_edge_length(max_edge);
  bisection(1);
  bisection.detach();
}

}  // namespace carbonmesh
