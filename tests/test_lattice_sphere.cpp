// A sphere replaced by the triangular lattice folded onto an icosahedron (build --lattice): the Goldberg-Coxeter
// sphere, sphere_fit, the indices nearest a radius and lattice_fullerene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/lattice_sphere.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "test_meshes.hpp"

using namespace carbonmesh;

namespace {

// The largest distance from a point of `a` to the nearest point of `b` (both small).
double farthest_unmatched(const TriMesh& a, const TriMesh& b) {
  double worst = 0;
  for (auto v : a.vertices()) {
    double nearest = std::numeric_limits<double>::infinity();
    for (auto w : b.vertices()) nearest = std::min(nearest, (a.point(v) - b.point(w)).norm());
    worst = std::max(worst, nearest);
  }
  return worst;
}

TriMesh mirrored_x(TriMesh mesh) {
  for (auto v : mesh.vertices()) {
    Vec3 p = mesh.point(v);
    p[0] = -p[0];
    mesh.set_point(v, p);
  }
  return mesh;
}

// +1 if every face faces away from `centre`, -1 if every face faces it, 0 if mixed.
int facing(const TriMesh& m, const Vec3& centre) {
  int out = 0, in = 0;
  for (auto f : m.faces()) {
    Vec3 centroid(0, 0, 0);
    for (auto v : m.fv_range(f)) centroid += m.point(v) / 3.0;
    ++(OpenMesh::dot(m.calc_face_normal(f), centroid - centre) > 0 ? out : in);
  }
  return in == 0 ? 1 : out == 0 ? -1 : 0;
}

}  // namespace

// Every (h, k) gives 10 T + 2 vertices and 20 T triangles on the sphere, closed, genus 0, every vertex of valence 6
// but 12 of valence 5, every face facing out, the edges within 1.4 of each other.
TEST(GoldbergCoxeter, IsTheIcosahedralTriangulationOfItsIndices) {
  for (const auto& [h, k] : std::vector<std::pair<int, int>>{
           {1, 0}, {1, 1}, {2, 1}, {1, 2}, {3, 0}, {4, 1}, {3, 3}, {5, 3}, {6, 2}, {9, 4}, {4, 7}}) {
    SCOPED_TRACE(testing::Message() << "(" << h << ", " << k << ")");
    const double radius = 3.5;
    const TriMesh m = make_goldberg_coxeter_sphere({radius, h, k});
    const long t = triangulation_number(h, k);
    EXPECT_EQ(static_cast<long>(m.n_vertices()), 10 * t + 2);
    EXPECT_EQ(static_cast<long>(m.n_faces()), 20 * t);
    const Topology top = topology(m);
    EXPECT_EQ(top.boundary_loops, 0);
    EXPECT_EQ(top.genus, 0);
    EXPECT_EQ(top.components, 1);
    int fives = 0;
    for (auto v : m.vertices()) {
      const int valence = static_cast<int>(m.valence(v));
      EXPECT_TRUE(valence == 5 || valence == 6) << valence;
      fives += valence == 5 ? 1 : 0;
      EXPECT_NEAR(m.point(v).norm(), radius, 1e-12 * radius);
    }
    EXPECT_EQ(fives, 12);
    EXPECT_EQ(facing(m, Vec3(0, 0, 0)), 1);
    const EdgeStats e = edge_stats(m);
    EXPECT_LT(e.max / e.min, 1.4);
  }
}

// (h, 0) is the geodesic sphere of frequency h, point for point.
TEST(GoldbergCoxeter, FrequencyIsTheGeodesicSphere) {
  for (int f : {2, 5}) {
    const TriMesh gc = make_goldberg_coxeter_sphere({2.0, f, 0});
    const TriMesh geodesic = make_geodesic_sphere({2.0, f, false});
    ASSERT_EQ(gc.n_vertices(), geodesic.n_vertices());
    EXPECT_LT(farthest_unmatched(gc, geodesic), 1e-12);
  }
}

// (k, h) is the mirror image of (h, k): the icosahedron's mirror x -> -x takes one onto the other, and a chiral cage
// onto no copy of itself; (h, 0) is its own mirror image.
TEST(GoldbergCoxeter, SwappedIndicesAreTheMirrorImage) {
  const TriMesh a = make_goldberg_coxeter_sphere({1.0, 3, 1}), b = make_goldberg_coxeter_sphere({1.0, 1, 3});
  EXPECT_LT(farthest_unmatched(mirrored_x(a), b), 1e-12);
  EXPECT_GT(farthest_unmatched(mirrored_x(a), a), 1e-3);
  const TriMesh c = make_goldberg_coxeter_sphere({1.0, 4, 0});
  EXPECT_LT(farthest_unmatched(mirrored_x(c), c), 1e-12);
}

TEST(GoldbergCoxeter, RefusesIndicesWithNoCage) {
  EXPECT_THROW(make_goldberg_coxeter_sphere({1.0, 0, 0}), InputError);
  EXPECT_THROW(make_goldberg_coxeter_sphere({1.0, -1, 2}), InputError);
  EXPECT_THROW(make_goldberg_coxeter_sphere({1.0, 2000, 2000}), InputError);  // T = 1.2e7 > kMaxTriangulationNumber
  EXPECT_THROW(make_goldberg_coxeter_sphere({0.0, 1, 1}), InputError);
  EXPECT_NO_THROW(check_goldberg_coxeter(0, 1));
}

// The sphere through a turned and shifted icosphere is found exactly; noise and stretching show in the distance.
TEST(SphereFit, FindsCentreAndRadius) {
  const TriMesh sphere = test::tilted(make_icosphere({7.0, 3}));
  const Sphere s = sphere_fit(sphere);
  EXPECT_NEAR(s.radius, 7.0, 1e-9);
  EXPECT_LT((s.centre - Vec3(5, -3, 2)).norm(), 1e-9);
  EXPECT_LT(s.distance, 1e-9);
  EXPECT_GT(sphere_fit(test::radial_noise(make_icosphere({7.0, 3}), 0.01, 3)).distance, 0.02);
  EXPECT_GT(sphere_fit(test::stretched(make_icosphere({7.0, 3}), 2, 1.05)).distance, 0.1);
  EXPECT_EQ(sphere_fit(test::mesh_from({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{{0, 1, 2}}})).distance,
            std::numeric_limits<double>::infinity());
}

// The indices nearest a fullerene's own radius are its own (the achiral ones first where two share T); between two
// radii, the nearer.
TEST(NearestGoldbergIndices, PicksTheNearestRadius) {
  const double a = 2.46;
  for (const auto& [h, k] : std::vector<std::pair<int, int>>{{1, 0}, {1, 1}, {2, 0}, {2, 1}, {3, 3}, {7, 0}, {10, 0}}) {
    const GoldbergIndices g = nearest_goldberg_indices(fullerene_radius({h, k}, a), a);
    EXPECT_EQ(g.h, h);
    EXPECT_EQ(g.k, k);
  }
  const GoldbergIndices tie = nearest_goldberg_indices(fullerene_radius({5, 3}, a), a);  // T = 49 as (7, 0)
  EXPECT_EQ(tie.h, 7);
  EXPECT_EQ(tie.k, 0);
  EXPECT_NEAR(fullerene_radius({1, 1}, 1.42 * std::sqrt(3.0)), 3.53, 0.02);  // C60's radius, 3.55 A
  const double r1 = fullerene_radius({1, 1}, a), r2 = fullerene_radius({2, 0}, a);  // T = 3 and 4
  EXPECT_EQ(nearest_goldberg_indices(0.9 * r1 + 0.1 * r2, a).k, 1);
  EXPECT_EQ(nearest_goldberg_indices(0.1 * r1 + 0.9 * r2, a).h, 2);
  EXPECT_EQ(nearest_goldberg_indices(0.01, a).h, 1);  // smaller than C20: C20
}

// On a turned and shifted icosphere: the fullerene's vertices on one sphere about the input's centre, its mean edge
// the lattice edge, its faces facing out, or in where the input's do.
TEST(LatticeFullerene, SitsOnTheInputsCentreWithTheLatticeEdge) {
  const TriMesh input = test::tilted(make_icosphere({20.0, 3}));
  const Sphere s = sphere_fit(input);
  const double a = 2.46;
  const GoldbergIndices g = nearest_goldberg_indices(s.radius, a);
  const LatticeFullerene f = lattice_fullerene(input, s, a, g);
  EXPECT_EQ(static_cast<long>(f.mesh.n_faces()), 20 * triangulation_number(g.h, g.k));
  EXPECT_NEAR(edge_stats(f.mesh).mean, a, 1e-9);
  EXPECT_NEAR(f.radius, s.radius, 0.05 * s.radius);
  for (auto v : f.mesh.vertices()) EXPECT_NEAR((f.mesh.point(v) - s.centre).norm(), f.radius, 1e-9);
  EXPECT_EQ(facing(f.mesh, s.centre), 1);
  std::vector<std::array<int, 3>> triangles = test::triangles_of(input);
  for (auto& t : triangles) std::swap(t[1], t[2]);
  std::vector<Vec3> points;
  for (auto v : input.vertices()) points.push_back(input.point(v));
  const TriMesh inward = test::mesh_from(points, triangles);
  EXPECT_EQ(facing(lattice_fullerene(inward, s, a, g).mesh, s.centre), -1);
  EXPECT_THROW(lattice_fullerene(input, s, 0.0, g), InputError);
  EXPECT_THROW(lattice_fullerene(input, s, a, {0, 0}), InputError);
}
