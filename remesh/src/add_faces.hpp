#pragma once
// Many triangles added to a mesh at once, with OpenMesh's result. Internal (build_in_spatial_order).
#include <array>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// Adds `faces` (vertex indices, in this order) to `mesh`, which has its vertices and no edges or faces. The result
// is that of OpenMesh's add_face() called on each face in turn, element for element: the same edges in the same
// order with the same halfedge orientations, the same next and previous links, outgoing halfedges and face
// halfedges. add_face() searches each new face's edges around its vertices, reorders the boundary links and grows
// every property array by one element per new edge and face; here the same steps run on plain arrays and the mesh's
// arrays are sized once (bunny's remesh rebuilds its mesh in spatial order seven times: 3.0% of its instructions,
// three quarters of them in add_face(); 1.4% with add_faces()). Returns false, leaving `mesh` unspecified, where
// add_face() would refuse a face (a complex vertex or edge, or a failed re-linking of a patch).
bool add_faces(TriMesh& mesh, const std::vector<std::array<int, 3>>& faces);

// The corners (vertex indices) of the faces of the triangle mesh `mesh`, in face order, each turned the other way
// (its last two corners swapped) if `reversed`: for add_faces() on a copy of its vertices.
std::vector<std::array<int, 3>> face_corners(const TriMesh& mesh, bool reversed = false);

}  // namespace carbonmesh
