// Memory order of the mesh elements along a space-filling curve (not in the dissertation).
//
// Splits append vertices, edges and faces at the ends of OpenMesh's arrays and garbage_collection() fills the
// holes of collapses from the ends, so after a few remeshing iterations neighbours on the surface lie far
// apart in memory and every k-star walk misses the cache. Rebuilding the mesh with its vertices in Morton
// order of their positions and its faces in order of their first vertex restores locality.
#include <algorithm>
#include <array>
#include <vector>

#include "carbonmesh/remesh/morton_order.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"

namespace carbonmesh {

bool spatial_order(TriMesh& mesh) {
  std::vector<Vec3> points;
  std::vector<int> handle;  // vertex index of each point
  points.reserve(mesh.n_vertices());
  handle.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    if (mesh.status(v).deleted()) continue;
    points.push_back(mesh.point(v));
    handle.push_back(v.idx());
  }
  const std::vector<int> order = morton_order(points);
  TriMesh out;
  out.reserve(order.size(), mesh.n_edges(), mesh.n_faces());
  std::vector<int> renumber(mesh.n_vertices(), -1);
  for (int k : order) {
    const int i = handle[static_cast<std::size_t>(k)];
    renumber[static_cast<std::size_t>(i)] = out.add_vertex(mesh.point(TriMesh::VertexHandle(i))).idx();
  }
  // Faces by their smallest new vertex index, each starting at that vertex (orientation kept).
  std::vector<std::array<int, 3>> faces;
  faces.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    std::array<int, 3> t{};
    int k = 0;
    for (auto w : mesh.fv_range(f)) t[static_cast<std::size_t>(k++)] = renumber[static_cast<std::size_t>(w.idx())];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    faces.push_back(t);
  }
  std::sort(faces.begin(), faces.end());
  for (const auto& t : faces) {
    const auto f = out.add_face(TriMesh::VertexHandle(t[0]), TriMesh::VertexHandle(t[1]), TriMesh::VertexHandle(t[2]));
    if (!f.is_valid()) return false;  // cannot happen on a manifold mesh; keep the old order
  }
  // The projection's memory of where each vertex was put (projection.cpp) moves with its vertex.
  OpenMesh::VPropHandleT<std::array<double, 4>> last_in, last_out;
  if (mesh.get_property_handle(last_in, "carbonmesh:projected")) {
    out.add_property(last_out, "carbonmesh:projected");
    for (int i : handle)
      out.property(last_out, TriMesh::VertexHandle(renumber[static_cast<std::size_t>(i)])) =
          mesh.property(last_in, TriMesh::VertexHandle(i));
  }
  mesh = std::move(out);
  return true;
}

}  // namespace carbonmesh
