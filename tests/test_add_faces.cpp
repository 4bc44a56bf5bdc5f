// add_faces(): the mesh OpenMesh's add_face() builds face by face, element for element, on closed and bordered
// surfaces with the faces in any order, and the same refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <string>
#include <vector>

#include "add_faces.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "test_meshes.hpp"

namespace carbonmesh {
namespace {

using Faces = std::vector<std::array<int, 3>>;

TriMesh vertices_of(const TriMesh& mesh) {
  TriMesh out;
  for (auto v : mesh.vertices()) out.add_vertex(mesh.point(v));
  return out;
}

// Every connectivity handle and status of each kind of element, in element order.
std::vector<int> state_of(const TriMesh& mesh) {
  std::vector<int> s{static_cast<int>(mesh.n_vertices()), static_cast<int>(mesh.n_edges()),
                     static_cast<int>(mesh.n_faces())};
  for (auto v : mesh.all_vertices())
    s.insert(s.end(), {mesh.halfedge_handle(v).idx(), static_cast<int>(mesh.status(v).bits())});
  for (auto h : mesh.all_halfedges())
    s.insert(s.end(), {mesh.to_vertex_handle(h).idx(), mesh.next_halfedge_handle(h).idx(),
                       mesh.prev_halfedge_handle(h).idx(), mesh.face_handle(h).idx(),
                       static_cast<int>(mesh.status(h).bits())});
  for (auto e : mesh.all_edges()) s.push_back(static_cast<int>(mesh.status(e).bits()));
  for (auto f : mesh.all_faces())
    s.insert(s.end(), {mesh.halfedge_handle(f).idx(), static_cast<int>(mesh.status(f).bits())});
  return s;
}

// OpenMesh's add_face() on each face in turn; false at the first one it refuses.
bool openmesh_add_faces(TriMesh& mesh, const Faces& faces) {
  for (const auto& t : faces)
    if (!mesh.add_face(TriMesh::VertexHandle(t[0]), TriMesh::VertexHandle(t[1]), TriMesh::VertexHandle(t[2]))
             .is_valid())
      return false;
  return true;
}

void expect_same_as_openmesh(const TriMesh& shape, Faces faces, const std::string& what) {
  TriMesh expected = vertices_of(shape), built = vertices_of(shape);
  ASSERT_TRUE(openmesh_add_faces(expected, faces)) << what;
  ASSERT_TRUE(add_faces(built, faces)) << what;
  EXPECT_EQ(state_of(built), state_of(expected)) << what;
  EXPECT_EQ(built.n_faces(), faces.size()) << what;
}

// The faces in their order, sorted, and shuffled: a random order opens many boundary patches that later faces
// join (add_face()'s re-linking of patches and its adjusting of outgoing halfedges).
void expect_same_in_any_order(const TriMesh& shape, const std::string& what) {
  const Faces faces = test::triangles_of(shape);
  expect_same_as_openmesh(shape, faces, what + ", in order");
  Faces sorted = faces;
  std::sort(sorted.begin(), sorted.end());
  expect_same_as_openmesh(shape, sorted, what + ", sorted");
  for (unsigned seed : {1u, 2u, 3u}) {
    Faces shuffled = faces;
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(seed));
    expect_same_as_openmesh(shape, shuffled, what + ", shuffled with seed " + std::to_string(seed));
  }
}

TEST(AddFaces, SameMeshAsOpenMeshOnClosedSurfaces) {
  expect_same_in_any_order(make_icosphere({10.0, 3}), "icosphere");
  expect_same_in_any_order(make_torus({}), "torus");
}

TEST(AddFaces, SameMeshAsOpenMeshWithBorders) {
  TriMesh cut = make_icosphere({10.0, 3});
  // Two holes: the faces above one height and beyond another.
  for (auto f : cut.faces()) {
    const auto c = cut.calc_face_centroid(f);
    if (c[2] > 7.0 || c[0] > 8.0) cut.delete_face(f, false);
  }
  cut.garbage_collection();
  ASSERT_GT(cut.n_faces(), 0u);
  bool border = false;
  for (auto h : cut.halfedges()) border = border || cut.is_boundary(h);
  ASSERT_TRUE(border);
  expect_same_in_any_order(cut, "icosphere with two holes");
}

TEST(AddFaces, RefusesWhatOpenMeshRefuses) {
  // A second face on the halfedge 0 -> 1 (a complex edge), and a face at vertex 4 once the fan of four triangles
  // around it has closed (a complex vertex; the third face joins the bow tie of the first two, a re-linking).
  TriMesh points;
  for (int i = 0; i < 9; ++i) points.add_vertex(Vec3(i, i * i % 5, i % 3));
  const Faces complex_edge = {{0, 1, 2}, {0, 1, 3}};
  const Faces complex_vertex = {{4, 5, 6}, {4, 7, 8}, {4, 6, 7}, {4, 8, 5}, {4, 5, 7}};
  for (const Faces& faces : {complex_edge, complex_vertex}) {
    TriMesh expected = points, built = points;
    const bool openmesh = openmesh_add_faces(expected, faces);
    EXPECT_FALSE(openmesh);
    EXPECT_EQ(add_faces(built, faces), openmesh);
  }
}

}  // namespace
}  // namespace carbonmesh
