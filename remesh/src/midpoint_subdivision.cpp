// 1-to-4 midpoint subdivision, the refinement step of the coarse-to-fine remesh (not in the dissertation).
//
// Every triangle (a, b, c) becomes (a, m_ab, m_ca), (b, m_bc, m_ab), (c, m_ca, m_bc) and (m_ab, m_bc, m_ca), with
// m the edge midpoints: every new edge is exactly half of an old one, so a mesh with its edges in [2 emin, 2 emax]
// gets its edges in [emin, emax]; old vertices keep their valence and new ones have valence 6 (4 on a border).
#include <array>
#include <vector>

#include "carbonmesh/remesh/remesh_steps.hpp"

namespace carbonmesh {

bool midpoint_subdivision(TriMesh& mesh) {
  mesh.garbage_collection();
  TriMesh out;
  const std::size_t nv = mesh.n_vertices(), ne = mesh.n_edges();
  out.reserve(nv + ne, 2 * ne + 3 * mesh.n_faces(), 4 * mesh.n_faces());
  for (auto v : mesh.vertices()) out.add_vertex(mesh.point(v));
  // Vertex nv + e is the midpoint of edge e.
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    out.add_vertex(0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h))));
  }
  auto corner = [&](TriMesh::HalfedgeHandle h) { return TriMesh::VertexHandle(mesh.from_vertex_handle(h).idx()); };
  auto middle = [&](TriMesh::HalfedgeHandle h) {
    return TriMesh::VertexHandle(static_cast<int>(nv) + mesh.edge_handle(h).idx());
  };
  for (auto f : mesh.faces()) {
    const auto h0 = mesh.halfedge_handle(f), h1 = mesh.next_halfedge_handle(h0), h2 = mesh.next_halfedge_handle(h1);
    const auto a = corner(h0), b = corner(h1), c = corner(h2);  // h0 = a->b, h1 = b->c, h2 = c->a
    const auto ab = middle(h0), bc = middle(h1), ca = middle(h2);
    for (const std::array<TriMesh::VertexHandle, 3>& t :
         {std::array{a, ab, ca}, std::array{b, bc, ab}, std::array{c, ca, bc}, std::array{ab, bc, ca}})
      if (!out.add_face(t[0], t[1], t[2]).is_valid()) return false;  // not on a manifold mesh
  }
  mesh = std::move(out);
  return true;
}

}  // namespace carbonmesh
