// Memory order of the mesh elements along a space-filling curve (not in the dissertation).
//
// Splits append vertices, edges and faces at the ends of OpenMesh's arrays and garbage_collection() fills the
// holes of collapses from the ends, so after a few remeshing iterations neighbours on the surface lie far
// apart in memory and every k-star walk misses the cache. Rebuilding the mesh with its vertices in Morton
// order of their positions and its faces in order of their first vertex restores locality.
#include <algorithm>
#include <array>
#include <vector>

#include "add_faces.hpp"
#include "carbonmesh/remesh/morton_order.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "spatial_order.hpp"

namespace carbonmesh {

bool build_in_spatial_order(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& faces,
                            std::size_t edges, TriMesh& out, std::vector<int>& renumber) {
  const std::vector<int> order = morton_order(points);
  out = TriMesh();
  out.reserve(points.size(), edges, faces.size());
  renumber.assign(points.size(), -1);
  for (int k : order)
    renumber[static_cast<std::size_t>(k)] = out.add_vertex(points[static_cast<std::size_t>(k)]).idx();
  // Faces by their smallest new vertex index, each starting at that vertex (orientation kept).
  std::vector<std::array<int, 3>> ordered;
  ordered.reserve(faces.size());
  for (const auto& f : faces) {
    std::array<int, 3> t{};
    for (std::size_t k = 0; k < 3; ++k) t[k] = renumber[static_cast<std::size_t>(f[k])];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    ordered.push_back(t);
  }
  std::sort(ordered.begin(), ordered.end());
  return add_faces(out, ordered);  // (OpenMesh's add_face() on each in turn, element for element)
}

bool spatial_order(TriMesh& mesh) {
  std::vector<Vec3> points;
  std::vector<int> handle;                      // vertex index of each point
  std::vector<int> point_of(mesh.n_vertices(), -1);  // point index of each vertex
  points.reserve(mesh.n_vertices());
  handle.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    if (mesh.status(v).deleted()) continue;
    point_of[static_cast<std::size_t>(v.idx())] = static_cast<int>(points.size());
    points.push_back(mesh.point(v));
    handle.push_back(v.idx());
  }
  std::vector<std::array<int, 3>> faces;
  faces.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    if (mesh.status(f).deleted()) continue;
    std::array<int, 3> t{};
    int k = 0;
    for (auto w : mesh.fv_range(f)) t[static_cast<std::size_t>(k++)] = point_of[static_cast<std::size_t>(w.idx())];
    faces.push_back(t);
  }
  std::size_t edges = 0;
  for (auto e : mesh.edges()) edges += !mesh.status(e).deleted();
  TriMesh out;
  std::vector<int> renumber;
  if (!build_in_spatial_order(points, faces, edges, out, renumber)) return false;  // not on a manifold mesh: old order
  // The projection's memory of where each vertex was put and of its nearest target vertices (projection.cpp)
  // moves with its vertex (and the target those were searched on with the mesh).
  auto carry = [&](auto prototype, const char* name) {
    OpenMesh::VPropHandleT<decltype(prototype)> in, out_handle;
    if (!mesh.get_property_handle(in, name)) return;
    out.add_property(out_handle, name);
    for (std::size_t k = 0; k < handle.size(); ++k)
      out.property(out_handle, TriMesh::VertexHandle(renumber[k])) =
          mesh.property(in, TriMesh::VertexHandle(handle[k]));
  };
  carry(std::array<double, 4>{}, kProjectedProperty);
  carry(NearestTargetVertices{}, kNearestTargetProperty);
  OpenMesh::MPropHandleT<const ProjectionTarget*> owner_in, owner_out;
  if (mesh.get_property_handle(owner_in, kNearestTargetOwnerProperty)) {
    out.add_property(owner_out, kNearestTargetOwnerProperty);
    out.property(owner_out) = mesh.property(owner_in);
  }
  mesh = std::move(out);
  return true;
}

}  // namespace carbonmesh
