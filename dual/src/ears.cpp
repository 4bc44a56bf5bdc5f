// Ears off the primal mesh before the dual (carbonmesh/dual/ears.hpp).
#include "carbonmesh/dual/ears.hpp"

#include <vector>

namespace carbonmesh {
namespace {

// How many of the face's edges are on a border.
int border_edges(const TriMesh& mesh, TriMesh::FaceHandle f) {
  int n = 0;
  for (auto h : mesh.fh_range(f)) n += mesh.is_boundary(mesh.opposite_halfedge_handle(h)) ? 1 : 0;
  return n;
}

}  // namespace

EarRemoval remove_ears(TriMesh& primal) {
  EarRemoval result;
  std::vector<TriMesh::FaceHandle> queue;
  for (auto f : primal.faces())
    if (border_edges(primal, f) >= 2) queue.push_back(f);
  for (std::size_t k = 0; k < queue.size(); ++k) {
    const auto f = queue[k];
    if (primal.status(f).deleted()) continue;  // (listed twice: it became an ear from two sides)
    // The faces across its interior edges, which gain a border edge.
    std::vector<TriMesh::FaceHandle> across;
    for (auto h : primal.fh_range(f)) {
      const auto o = primal.opposite_halfedge_handle(h);
      if (!primal.is_boundary(o)) across.push_back(primal.face_handle(o));
    }
    const auto h = primal.halfedge_handle(f);
    const Vec3 a = primal.point(primal.from_vertex_handle(h));
    const Vec3 b = primal.point(primal.to_vertex_handle(h));
    const Vec3 c = primal.point(primal.to_vertex_handle(primal.next_halfedge_handle(h)));
    result.area += 0.5 * OpenMesh::cross(b - a, c - a).norm();
    ++result.faces;
    primal.delete_face(f, /*delete_isolated_vertices=*/true);
    for (auto g : across)
      if (border_edges(primal, g) >= 2) queue.push_back(g);
  }
  if (result.faces > 0) primal.garbage_collection();
  return result;
}

}  // namespace carbonmesh
