// A cylindrical surface cut from a triangular lattice rolled into a tube (build --lattice): cylinder_fit, the chiral
// indices and lattice_tube.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/lattice_tube.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "test_meshes.hpp"

using namespace carbonmesh;

namespace {

const double kPi = std::acos(-1.0);

// The direction test::tilted turns the z axis to.
Vec3 tilted_z() {
  const TriMesh m = test::tilted(test::mesh_from({{0, 0, 0}, {0, 0, 1}, {1, 0, 0}}, {{{0, 1, 2}}}));
  auto it = m.vertices().begin();
  const Vec3 a = m.point(*it++);
  return m.point(*it) - a;
}

// Distance of p from the axis of `c`.
double from_axis(const Cylinder& c, const Vec3& p) {
  const Vec3 d = p - c.point;
  return (d - OpenMesh::dot(d, c.axis) * c.axis).norm();
}

// The lattice mesh's faces against the radial direction at their centroids: +1 if all face out, -1 if all face in,
// 0 if mixed.
int facing(const TriMesh& m, const Cylinder& c) {
  int out = 0, in = 0;
  for (auto f : m.faces()) {
    Vec3 centroid(0, 0, 0);
    for (auto v : m.fv_range(f)) centroid += m.point(v) / 3.0;
    const Vec3 d = centroid - c.point;
    ++(OpenMesh::dot(m.calc_face_normal(f), d - OpenMesh::dot(d, c.axis) * c.axis) > 0 ? out : in);
  }
  return in == 0 ? 1 : out == 0 ? -1 : 0;
}

TriMesh reversed(const TriMesh& mesh) {
  std::vector<Vec3> points;
  for (auto v : mesh.vertices()) points.push_back(mesh.point(v));
  std::vector<std::array<int, 3>> triangles = test::triangles_of(mesh);
  for (auto& t : triangles) std::swap(t[1], t[2]);
  return test::mesh_from(points, triangles);
}

// The checks every lattice laid on a cylinder passes: every vertex on the cylinder of `radius` about c's axis, every
// interior vertex of valence 6, every edge a lattice edge of length a bent around the axis (between the chord
// 2 R sin(a / 2R) of an edge square to the axis and a), the faces facing out (in if `inward`).
void expect_lattice_on_cylinder(const TriMesh& m, const Cylinder& c, double radius, double a, bool inward) {
  for (auto v : m.vertices()) {
    EXPECT_NEAR(from_axis(c, m.point(v)), radius, 1e-9);
    if (!m.is_boundary(v)) {
      EXPECT_EQ(m.valence(v), 6u);
    }
  }
  const double shortest = 2 * radius * std::sin(a / (2 * radius));
  for (auto e : m.edges()) {
    EXPECT_LE(m.calc_edge_length(e), a + 1e-9);
    EXPECT_GE(m.calc_edge_length(e), shortest - 1e-9);
  }
  EXPECT_EQ(facing(m, c), inward ? -1 : 1);
}

}  // namespace

// The built-in open tube's rings are offset by half a step, so its triangles are not parallel to the axis: the
// faces' normals give only a first axis, the fit over the vertices finds the cylinder they lie on. With edges of 0.1
// the tube has about 58000 vertices, and the fit runs on every k-th of them.
TEST(CylinderFit, FindsATiltedTubesAxisAndRadius) {
  for (const double edge : {0.0, 0.1}) {
    const TriMesh tube = test::tilted(make_open_tube({4.0, 20.0, edge}));
    const Topology t = topology(tube);
    EXPECT_EQ(t.boundary_loops, 2u);
    EXPECT_EQ(t.genus, 0);
    const Cylinder c = cylinder_fit(tube);
    EXPECT_NEAR(c.radius, 4.0, 1e-9);
    EXPECT_LT(c.distance, 1e-9);
    EXPECT_NEAR(std::abs(OpenMesh::dot(c.axis, tilted_z())), 1.0, 1e-12);
    EXPECT_NEAR(c.axis.norm(), 1.0, 1e-12);
    // The point is on the axis (the tilt shifted it to (5, -3, 2)), level with the vertices' centroid (the origin).
    EXPECT_LT(((c.point - Vec3(5, -3, 2)) - OpenMesh::dot(c.point - Vec3(5, -3, 2), c.axis) * c.axis).norm(), 1e-9);
  }
  // One vertex off the cylinder by 0.01 (not among those the fit runs on): the distance names it.
  TriMesh bumped = make_open_tube({4.0, 20.0, 0.1});
  const auto v = *std::next(bumped.vertices().begin(), 1001);
  const Vec3 p = bumped.point(v);
  bumped.set_point(v, p + 0.01 * Vec3(p[0], p[1], 0).normalized());
  EXPECT_NEAR(cylinder_fit(bumped).distance, 0.01, 1e-6);
}

TEST(CylinderFit, ASpherePatchIsNoCylinder) {
  TriMesh sphere = make_icosphere({10.0, 3});
  for (auto f : sphere.faces())
    if (sphere.calc_face_centroid(f)[2] > 0) sphere.delete_face(f, true);
  sphere.garbage_collection();
  EXPECT_GT(cylinder_fit(sphere).distance, 0.1);
}

TEST(Chirality, TheNearestIndicesToARadius) {
  const double a = 2.46;
  EXPECT_NEAR(chiral_circumference({5, 5}, a), a * std::sqrt(75.0), 1e-12);
  for (const Chirality c : {Chirality{5, 5}, Chirality{10, 0}, Chirality{7, 3}, Chirality{12, 8}}) {
    const Chirality found = nearest_chirality(chiral_circumference(c, a) / (2 * kPi), a);
    EXPECT_EQ(found.n, c.n);
    EXPECT_EQ(found.m, c.m);
  }
  // (7, 0) and (5, 3) have one circumference (n^2 + nm + m^2 = 49): the zigzag one is taken.
  const Chirality tie = nearest_chirality(7 * a / (2 * kPi), a);
  EXPECT_EQ(tie.n, 7);
  EXPECT_EQ(tie.m, 0);
  // Thinner than the thinnest tube: (2, 1).
  const Chirality thin = nearest_chirality(0.1, a);
  EXPECT_EQ(thin.n, 2);
  EXPECT_EQ(thin.m, 1);
  EXPECT_NEAR(chiral_angle_deg({9, 0}), 0.0, 1e-12);
  EXPECT_NEAR(chiral_angle_deg({6, 6}), 30.0, 1e-12);
}

// An open tube rolled from the lattice: every interior vertex of valence 6, every vertex on the tube's cylinder, the
// edges the lattice's chords, two rims, the faces facing the input's way; a (n, 0) tube has rings of n points.
TEST(LatticeTube, AnOpenTubeIsRolledFromTheLatticeWithoutDefects) {
  const double a = 1.0;
  for (const Chirality chirality : {Chirality{12, 0}, Chirality{7, 7}, Chirality{9, 4}}) {
    SCOPED_TRACE(testing::Message() << "(" << chirality.n << ", " << chirality.m << ")");
    const double radius = chiral_circumference(chirality, a) / (2 * kPi);
    for (const bool inward : {false, true}) {
      const TriMesh open = test::tilted(make_open_tube({radius, 15.0, 0.0}));
      const TriMesh input = inward ? reversed(open) : open;
      const Cylinder c = cylinder_fit(input);
      const LatticeTube tube = lattice_tube(input, c, a, chirality);
      const TriMesh& m = tube.mesh;
      EXPECT_NEAR(tube.radius, radius, 1e-12);
      const Topology t = topology(m);
      EXPECT_EQ(t.components, 1u);
      EXPECT_EQ(t.boundary_loops, 2u);
      EXPECT_EQ(t.genus, 0);
      expect_lattice_on_cylinder(m, c, radius, a, inward);
      EXPECT_EQ(facing(tube.surface, c), inward ? -1 : 1);
      // About the input's area in lattice triangles (less a row or so at each rim).
      const double expected = surface_area(input) / (std::sqrt(3.0) / 4 * a * a);
      EXPECT_NEAR(static_cast<double>(m.n_faces()), expected, 0.1 * expected);
      if (chirality.m == 0) {
        EXPECT_EQ(m.n_vertices() % static_cast<std::size_t>(chirality.n), 0u);
      }
      // The surface: the tube's cylinder, beyond both rims.
      for (auto v : tube.surface.vertices()) EXPECT_NEAR(from_axis(c, tube.surface.point(v)), radius, 1e-9);
    }
  }
}

// Half a cylinder, its grid jittered along the surface: one border, no interior defect, the lattice on the cylinder
// of the nearest chirality.
TEST(LatticeTube, HalfACylinderIsCutFromTheTube) {
  const TriMesh half = test::tilted(test::half_cylinder(12.0, 40.0));
  const Cylinder c = cylinder_fit(half);
  EXPECT_NEAR(c.radius, 12.0, 1e-9);
  const double a = 2.46;
  const Chirality chirality = nearest_chirality(c.radius, a);
  const LatticeTube tube = lattice_tube(half, c, a, chirality);
  EXPECT_NEAR(tube.radius, 12.0, a / (2 * kPi));  // the circumferences of neighbouring indices are < a apart
  const Topology t = topology(tube.mesh);
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.boundary_loops, 1u);
  expect_lattice_on_cylinder(tube.mesh, c, tube.radius, a, false);
  const double expected = surface_area(half) / (std::sqrt(3.0) / 4 * a * a);
  EXPECT_NEAR(static_cast<double>(tube.mesh.n_faces()), expected, 0.15 * expected);
}

TEST(LatticeTube, IndicesThatMakeNoTubeAreRefused) {
  const TriMesh open = make_open_tube({4.0, 10.0, 0.0});
  const Cylinder c = cylinder_fit(open);
  EXPECT_THROW(lattice_tube(open, c, 1.0, {1, 1}), InputError);
  EXPECT_THROW(lattice_tube(open, c, 1.0, {2, 0}), InputError);
  EXPECT_THROW(lattice_tube(open, c, 1.0, {-3, 5}), InputError);
  EXPECT_THROW(lattice_tube(open, c, 0.0, {5, 5}), InputError);
  EXPECT_NO_THROW(lattice_tube(open, c, 1.0, {2, 1}));
}

// A tube goes around its axis; half a tube and a strip winding one and a half times around a cylinder (a ribbon
// coiled like a spring, its turns apart) do not: their angles unwrap along the edges.
TEST(AnglesAlongSurface, OnlyATubeGoesAroundItsAxis) {
  const TriMesh tube = test::tilted(make_open_tube({4.0, 20.0, 0.0}));
  EXPECT_FALSE(angles_along_surface(tube, cylinder_fit(tube)).has_value());
  const TriMesh half = test::tilted(test::half_cylinder(12.0, 40.0));
  const auto half_angles = angles_along_surface(half, cylinder_fit(half));
  ASSERT_TRUE(half_angles.has_value());
  EXPECT_NEAR(*std::max_element(half_angles->begin(), half_angles->end()) -
                  *std::min_element(half_angles->begin(), half_angles->end()),
              kPi, 1e-9);
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;
  const int n = 90;  // 60 degrees of the coil per 10 steps
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k < 2; ++k) {
      const double theta = 3 * kPi * i / n;
      points.emplace_back(6 * std::cos(theta), 6 * std::sin(theta), 4 * theta / kPi + 2.0 * k);  // pitch 8, width 2
    }
  for (int i = 0; i < n; ++i) {
    triangles.push_back({2 * i, 2 * i + 2, 2 * i + 3});
    triangles.push_back({2 * i, 2 * i + 3, 2 * i + 1});
  }
  const TriMesh coil = test::mesh_from(points, triangles);
  const Cylinder c = cylinder_fit(coil);
  EXPECT_NEAR(c.radius, 6.0, 1e-9);
  const auto coil_angles = angles_along_surface(coil, c);
  ASSERT_TRUE(coil_angles.has_value());
  EXPECT_NEAR(*std::max_element(coil_angles->begin(), coil_angles->end()) -
                  *std::min_element(coil_angles->begin(), coil_angles->end()),
              3 * kPi, 1e-9);
}

// Half a cylinder, unrolled, cut as a flat sheet is and rolled back: on the input's own cylinder (no chirality
// changes its radius), no interior defect, one lattice line along a straight side along the axis (40 long, longer
// than the curved sides' 12 pi), the faces facing the input's way.
TEST(CurvedSheet, HalfACylinderKeepsItsRadiusAndALatticeLineAlongItsSide) {
  const double a = 2.46;
  for (const bool inward : {false, true}) {
    const TriMesh half = inward ? reversed(test::half_cylinder(12.0, 40.0)) : test::half_cylinder(12.0, 40.0);
    const Cylinder c = cylinder_fit(half);
    const auto angles = angles_along_surface(half, c);
    ASSERT_TRUE(angles.has_value());
    const CurvedSheet sheet = curved_sheet(half, c, *angles, a);
    const TriMesh& m = sheet.mesh;
    const Topology t = topology(m);
    EXPECT_EQ(t.components, 1u);
    EXPECT_EQ(t.boundary_loops, 1u);
    expect_lattice_on_cylinder(m, c, 12.0, a, inward);
    std::size_t on_side = 0;  // on the side at angle 0 or at pi
    for (auto v : m.vertices()) on_side += std::abs(m.point(v)[1]) < 1e-9 ? 1 : 0;
    EXPECT_GE(on_side, 16u);  // a lattice line of edge 2.46 along a side 40 long: 17 points
    EXPECT_EQ(facing(sheet.surface, c), inward ? -1 : 1);
    const double expected = surface_area(half) / (std::sqrt(3.0) / 4 * a * a);
    EXPECT_NEAR(static_cast<double>(m.n_faces()), expected, 0.1 * expected);
  }
}
