// 1-to-4 midpoint subdivision, the refinement step of the coarse-to-fine remesh (not in the dissertation).
//
// Every triangle (a, b, c) becomes (a, m_ab, m_ca), (b, m_bc, m_ab), (c, m_ca, m_bc) and (m_ab, m_bc, m_ca), with
// m the edge midpoints: every new edge is exactly half of an old one, so a mesh with its edges in [2 emin, 2 emax]
// gets its edges in [emin, emax]; old vertices keep their valence and new ones have valence 6 (4 on a border).
#include <array>
#include <vector>

#include "carbonmesh/remesh/remesh_steps.hpp"
#include "spatial_order.hpp"

namespace carbonmesh {

bool midpoint_subdivision(TriMesh& mesh) {
  mesh.garbage_collection();
  const std::size_t nv = mesh.n_vertices();
  // Point nv + e is the midpoint of edge e.
  std::vector<Vec3> points;
  points.reserve(nv + mesh.n_edges());
  for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    points.push_back(0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h))));
  }
  auto middle = [&](TriMesh::HalfedgeHandle h) { return static_cast<int>(nv) + mesh.edge_handle(h).idx(); };
  std::vector<std::array<int, 3>> faces;
  faces.reserve(4 * mesh.n_faces());
  for (auto f : mesh.faces()) {
    const auto h0 = mesh.halfedge_handle(f), h1 = mesh.next_halfedge_handle(h0), h2 = mesh.next_halfedge_handle(h1);
    // h0 = a->b, h1 = b->c, h2 = c->a
    const int a = mesh.from_vertex_handle(h0).idx(), b = mesh.from_vertex_handle(h1).idx(),
              c = mesh.from_vertex_handle(h2).idx();
    const int ab = middle(h0), bc = middle(h1), ca = middle(h2);
    faces.insert(faces.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
  }
  // Built in spatial memory order at once (the remesher would reorder the appended midpoints anyway).
  TriMesh out;
  std::vector<int> renumber;
  // Each edge is halved and each face adds three inner edges.
  const std::size_t edges = 2 * mesh.n_edges() + 3 * mesh.n_faces();
  if (!build_in_spatial_order(points, faces, edges, out, renumber)) return false;  // not on a manifold mesh
  mesh = std::move(out);
  return true;
}

}  // namespace carbonmesh
