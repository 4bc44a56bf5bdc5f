// A flat surface cut from a triangular lattice (build --lattice): flatness and lattice_sheet.
#include <gtest/gtest.h>

#include <cmath>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/lattice_sheet.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "test_meshes.hpp"

using namespace carbonmesh;

namespace {

Vec3 face_normal(const TriMesh& mesh, TriMesh::FaceHandle f) {
  const auto h = mesh.halfedge_handle(f);
  const Vec3 a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h)),
             c = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
  return OpenMesh::cross(b - a, c - a).normalized();
}

}  // namespace

TEST(LatticeSheet, ATiltedFlakeIsCutIntoEqualTrianglesInItsPlane) {
  const TriMesh flake = test::tilted(test::triangle_sheet(6, 20.0));
  const Flatness plane = flatness(flake);
  EXPECT_LT(plane.distance, 1e-9);
  const Vec3 input_normal = face_normal(flake, *flake.faces().begin());
  EXPECT_NEAR(OpenMesh::dot(plane.normal, input_normal), 1.0, 1e-9);
  const LatticeSheet sheet = lattice_sheet(flake, plane, 1.0);
  const TriMesh& m = sheet.mesh;
  // About the flake's area in triangles of side 1 (the sites inside the outline).
  const double expected = surface_area(flake) / (std::sqrt(3.0) / 4);
  EXPECT_NEAR(static_cast<double>(m.n_faces()), expected, 0.1 * expected);
  for (auto e : m.edges()) EXPECT_NEAR(m.calc_edge_length(e), 1.0, 1e-9);
  for (auto v : m.vertices()) {
    EXPECT_LT(std::abs(OpenMesh::dot(m.point(v) - plane.centroid, plane.normal)), 1e-9);
    if (!m.is_boundary(v)) {
      EXPECT_EQ(m.valence(v), 6u);
    }
  }
  for (auto f : m.faces()) EXPECT_NEAR(OpenMesh::dot(face_normal(m, f), input_normal), 1.0, 1e-9);
  const Topology t = topology(m);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.boundary_loops, 1);
  EXPECT_EQ(t.genus, 0);
}

TEST(LatticeSheet, TheLongestSideIsALatticeLine) {
  // A 10.3 x 4.3 rectangle of two triangles: its long sides are the longest straight sides, the first one at y = 0 (no
  // lattice triangle has its centroid on its other sides).
  const TriMesh rectangle =
      test::mesh_from({{0, 0, 0}, {10.3, 0, 0}, {10.3, 4.3, 0}, {0, 4.3, 0}}, {{{0, 1, 2}}, {{0, 2, 3}}});
  const LatticeSheet sheet = lattice_sheet(rectangle, flatness(rectangle), 1.0);
  int on_side = 0;
  for (auto v : sheet.mesh.vertices()) {
    const Vec3 p = sheet.mesh.point(v);
    EXPECT_GT(p[1], -1e-9);  // nothing below the side: its row of triangles stands on it
    if (std::abs(p[1]) < 1e-9) ++on_side;
  }
  EXPECT_GE(on_side, 10);  // 0, 1, ..., 10 (the triangles whose centroid is inside)
  // Every lattice triangle whose centroid lies in the rectangle is in the mesh (but those left out where they touched
  // the rest at one corner only): counted here from the lattice points (i + j / 2, j sqrt(3) / 2).
  const double h = std::sqrt(3.0) / 2;
  std::size_t inside = 0;
  for (int j = -2; j < 8; ++j)
    for (int i = -10; i < 14; ++i)
      for (const double d : {1.0 / 3, 2.0 / 3}) {  // the up and the down triangle's centroid, (i + d, j + d)
        const double x = i + d + 0.5 * (j + d), y = (j + d) * h;
        const double e = 1e-9;  // on the border counts as inside (the left side passes through some centroids)
        if (x >= -e && x <= 10.3 + e && y >= -e && y <= 4.3 + e) ++inside;
      }
  EXPECT_EQ(sheet.mesh.n_faces() + sheet.dropped, inside);
  EXPECT_NEAR(std::fmod(std::abs(sheet.angle_deg), 180.0), 0.0, 1e-9);
}

TEST(LatticeSheet, AnAnnulusKeepsItsHole) {
  // A flat ring, radii 3 and 12, of 40 x 8 quads.
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;
  const int nu = 40, nv = 8;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const double r = 3 + 9.0 * j / nv, a = 2 * std::acos(-1.0) * i / nu;
      points.emplace_back(r * std::cos(a), r * std::sin(a), 0);
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = j * nu + i, b = j * nu + (i + 1) % nu, c = a + nu, d = b + nu;
      triangles.push_back({a, b, d});
      triangles.push_back({a, d, c});
    }
  const TriMesh ring = test::mesh_from(points, triangles);
  const LatticeSheet sheet = lattice_sheet(ring, flatness(ring), 1.0);
  const Topology t = topology(sheet.mesh);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.boundary_loops, 2);
  for (auto v : sheet.mesh.vertices()) EXPECT_GT(sheet.mesh.point(v).norm(), 3 - 1.0);  // within an edge of the hole
}

TEST(LatticeSheet, ASurfaceWithoutBorderIsRefused) {
  const TriMesh sphere = make_icosphere({10.0, 2});
  const Flatness plane = flatness(sphere);
  EXPECT_GT(plane.distance, 5.0);  // not flat
  EXPECT_THROW(lattice_sheet(sphere, plane, 1.0), InputError);
}

// A 30 x 6 ribbon whose long sides are cut into edges of 2 and whose ends are single edges of 6: the lattice follows
// the longest straight side (the long sides, 30), not the longest edge (an end). Along the long sides the lattice's
// border edges then lie on the side (a zigzag edge of the carbon net); turned 30 degrees, none does (armchair).
TEST(LatticeSheet, TheLatticeFollowsTheLongestStraightSideAndTurns) {
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;
  for (int i = 0; i <= 15; ++i) points.emplace_back(2.0 * i, 0, 0), points.emplace_back(2.0 * i, 6, 0);
  for (int i = 0; i < 15; ++i) {
    triangles.push_back({2 * i, 2 * i + 2, 2 * i + 3});
    triangles.push_back({2 * i, 2 * i + 3, 2 * i + 1});
  }
  const TriMesh ribbon = test::mesh_from(points, triangles);
  const Flatness plane = flatness(ribbon);
  for (const double turn : {0.0, 30.0}) {
    const LatticeSheet sheet = lattice_sheet(ribbon, plane, 1.0, turn);
    const TriMesh& m = sheet.mesh;
    // The lattice direction against the ribbon's axis (the plane's u axis is along the ribbon, either way).
    const double against_axis = std::fmod(std::abs(sheet.angle_deg) + 360.0, 60.0);
    EXPECT_NEAR(std::min(against_axis, 60.0 - against_axis), turn == 0 ? 0.0 : 30.0, 1e-9) << "turn " << turn;
    std::size_t along = 0, across = 0;  // border edges in the middle of the long sides
    for (auto e : m.edges()) {
      if (!m.is_boundary(e)) continue;
      const auto h = m.halfedge_handle(e, 0);
      const Vec3 p = m.point(m.from_vertex_handle(h)), q = m.point(m.to_vertex_handle(h));
      if (std::min(p[0], q[0]) < 5 || std::max(p[0], q[0]) > 25) continue;
      (std::abs(p[1] - q[1]) < 1e-9 ? along : across) += 1;
    }
    if (turn == 0) {
      EXPECT_GT(along, 30u);
      EXPECT_EQ(across, 0u);
    } else {
      EXPECT_EQ(along, 0u);
      EXPECT_GT(across, 30u);
    }
  }
}
