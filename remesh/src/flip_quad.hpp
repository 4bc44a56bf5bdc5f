#pragma once
// The four vertices of an edge flip's quad: the valence flips, the data-dependent and the relaxed flips. Internal.
#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct FlipQuad {
  TriMesh::VertexHandle a, b, c, d;  // edge a-b, opposite vertices c (left of a->b) and d
};

inline FlipQuad quad(const TriMesh& mesh, TriMesh::EdgeHandle e) {
  const auto h = mesh.halfedge_handle(e, 0), o = mesh.halfedge_handle(e, 1);
  return {mesh.from_vertex_handle(h), mesh.to_vertex_handle(h),
          mesh.to_vertex_handle(mesh.next_halfedge_handle(h)), mesh.to_vertex_handle(mesh.next_halfedge_handle(o))};
}

}  // namespace carbonmesh
