// Memory order of the mesh elements along a space-filling curve (not in the dissertation).
//
// Splits append vertices, edges and faces at the ends of OpenMesh's arrays and garbage_collection() fills the
// holes of collapses from the ends, so after a few remeshing iterations neighbours on the surface lie far
// apart in memory and every k-star walk misses the cache. Rebuilding the mesh with its vertices in Morton
// order of their positions and its faces in order of their first vertex restores locality.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "carbonmesh/remesh/remesh_steps.hpp"

namespace carbonmesh {
namespace {

// The 21 low bits of x spread to every third bit.
std::uint64_t spread(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

}  // namespace

bool spatial_order(TriMesh& mesh) {
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  std::vector<std::pair<std::uint64_t, int>> order;
  order.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    if (mesh.status(v).deleted()) continue;
    lo.minimize(mesh.point(v));
    hi.maximize(mesh.point(v));
  }
  const Vec3 extent = hi - lo;
  const double scale = 2097151.0 / std::max({extent[0], extent[1], extent[2], 1e-300});
  for (auto v : mesh.vertices()) {
    if (mesh.status(v).deleted()) continue;
    const Vec3 q = (mesh.point(v) - lo) * scale;
    const std::uint64_t code = spread(static_cast<std::uint64_t>(q[0])) |
                               spread(static_cast<std::uint64_t>(q[1])) << 1 |
                               spread(static_cast<std::uint64_t>(q[2])) << 2;
    order.emplace_back(code, v.idx());
  }
  std::sort(order.begin(), order.end());
  TriMesh out;
  out.reserve(order.size(), mesh.n_edges(), mesh.n_faces());
  std::vector<int> renumber(mesh.n_vertices(), -1);
  for (const auto& [code, i] : order) {
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
    for (const auto& [code, i] : order)
      out.property(last_out, TriMesh::VertexHandle(renumber[static_cast<std::size_t>(i)])) =
          mesh.property(last_in, TriMesh::VertexHandle(i));
  }
  mesh = std::move(out);
  return true;
}

}  // namespace carbonmesh
