// collect_garbage(): the same mesh as OpenMesh's garbage_collection(), element for element, after collapses and
// splits on closed and bordered meshes.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "carbonmesh/remesh/garbage_collection.hpp"
#include "carbonmesh/remesh/shapes.hpp"

namespace carbonmesh {
namespace {

// An integer property on each kind of element, set to the element's index before the garbage collection.
struct Labels {
  OpenMesh::VPropHandleT<int> v;
  OpenMesh::EPropHandleT<int> e;
  OpenMesh::HPropHandleT<int> h;
  OpenMesh::FPropHandleT<int> f;

  void add(TriMesh& mesh) {
    mesh.add_property(v, "test:v");
    mesh.add_property(e, "test:e");
    mesh.add_property(h, "test:h");
    mesh.add_property(f, "test:f");
    for (auto x : mesh.all_vertices()) mesh.property(v, x) = x.idx();
    for (auto x : mesh.all_edges()) mesh.property(e, x) = x.idx();
    for (auto x : mesh.all_halfedges()) mesh.property(h, x) = x.idx();
    for (auto x : mesh.all_faces()) mesh.property(f, x) = x.idx();
  }
  void find(const TriMesh& mesh) {
    mesh.get_property_handle(v, "test:v");
    mesh.get_property_handle(e, "test:e");
    mesh.get_property_handle(h, "test:h");
    mesh.get_property_handle(f, "test:f");
  }
};

// Every handle, point, normal, status and label of each kind of element, in element order.
std::vector<long> state_of(const TriMesh& mesh) {
  Labels id;
  id.find(mesh);
  std::vector<long> s{static_cast<long>(mesh.n_vertices()), static_cast<long>(mesh.n_edges()),
                      static_cast<long>(mesh.n_faces())};
  auto bits = [](double x) { return static_cast<long>(std::hash<double>{}(x)); };
  for (auto v : mesh.all_vertices()) {
    s.insert(s.end(),
             {mesh.halfedge_handle(v).idx(), static_cast<long>(mesh.status(v).bits()), mesh.property(id.v, v)});
    for (int k = 0; k < 3; ++k) s.insert(s.end(), {bits(mesh.point(v)[k]), bits(mesh.normal(v)[k])});
  }
  for (auto h : mesh.all_halfedges())
    s.insert(s.end(), {mesh.to_vertex_handle(h).idx(), mesh.next_halfedge_handle(h).idx(),
                       mesh.prev_halfedge_handle(h).idx(), mesh.face_handle(h).idx(),
                       static_cast<long>(mesh.status(h).bits()), mesh.property(id.h, h)});
  for (auto e : mesh.all_edges())
    s.insert(s.end(), {static_cast<long>(mesh.status(e).bits()), mesh.property(id.e, e)});
  for (auto f : mesh.all_faces()) {
    s.insert(s.end(),
             {mesh.halfedge_handle(f).idx(), static_cast<long>(mesh.status(f).bits()), mesh.property(id.f, f)});
    for (int k = 0; k < 3; ++k) s.push_back(bits(mesh.normal(f)[k]));
  }
  return s;
}

// Random splits (new elements at the ends), then random collapses of about `share` of the edges.
void churn(TriMesh& mesh, double share, unsigned seed) {
  std::mt19937 random(seed);
  const int splits = static_cast<int>(mesh.n_edges() / 10);
  for (int i = 0; i < splits; ++i) {
    const TriMesh::EdgeHandle e(static_cast<int>(random() % mesh.n_edges()));
    const auto h = mesh.halfedge_handle(e, 0);
    const Vec3 mid = 0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h)));
    mesh.split(e, mesh.add_vertex(mid));
  }
  mesh.update_normals();
  const int collapses = static_cast<int>(share * static_cast<double>(mesh.n_edges()));
  for (int i = 0, done = 0; i < 20 * collapses && done < collapses; ++i) {
    const TriMesh::HalfedgeHandle h(static_cast<int>(random() % mesh.n_halfedges()));
    if (mesh.status(mesh.edge_handle(h)).deleted() || !mesh.is_collapse_ok(h)) continue;
    mesh.collapse(h);
    ++done;
  }
}

void expect_same_as_openmesh(TriMesh mesh, double share, unsigned seed, const std::string& what) {
  churn(mesh, share, seed);
  Labels().add(mesh);
  TriMesh expected = mesh;
  expected.garbage_collection();
  collect_garbage(mesh);
  EXPECT_EQ(state_of(mesh), state_of(expected)) << what << ", share " << share << ", seed " << seed;
}

TEST(GarbageCollection, SameMeshAsOpenMeshOnAClosedSurface) {
  const TriMesh sphere = make_icosphere({10.0, 3});
  for (double share : {0.0, 0.001, 0.02, 0.2})
    for (unsigned seed : {1u, 2u, 3u}) expect_same_as_openmesh(sphere, share, seed, "icosphere");
}

TEST(GarbageCollection, SameMeshAsOpenMeshWithBordersAndIsolatedVertices) {
  TriMesh cut = make_icosphere({10.0, 3});
  // Two holes (faces above and below two heights) and a vertex left without faces.
  for (auto f : cut.faces()) {
    const auto c = cut.calc_face_centroid(f);
    if (c[2] > 7.0 || c[0] > 8.0) cut.delete_face(f, false);
  }
  cut.add_vertex(Vec3(50, 0, 0));
  cut.garbage_collection();
  ASSERT_GT(cut.n_faces(), 0u);
  bool border = false;
  for (auto h : cut.halfedges()) border = border || cut.is_boundary(h);
  ASSERT_TRUE(border);
  for (double share : {0.005, 0.05, 0.3})
    for (unsigned seed : {4u, 5u}) expect_same_as_openmesh(cut, share, seed, "icosphere with holes");
}

TEST(GarbageCollection, NothingDeletedLeavesTheMeshAsItWas) {
  TriMesh mesh = make_icosphere({10.0, 2});
  Labels().add(mesh);
  const std::vector<long> before = state_of(mesh);
  collect_garbage(mesh);
  EXPECT_EQ(state_of(mesh), before);
}

}  // namespace
}  // namespace carbonmesh
