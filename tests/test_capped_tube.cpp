// The capped nanotube (make_capped_tube: icosahedral caps for (5h, 5k), apex caps otherwise), the lattice folded
// onto a net of lattice triangles under it (remesh/src/lattice_net.hpp), and a capsule replaced by it
// (lattice_capsule.hpp: build --lattice).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/lattice_capsule.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "lattice_net.hpp"
#include "apex_capped_tube.hpp"

using namespace carbonmesh;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The signed volume the faces enclose (positive when they face out).
double volume(const TriMesh& m) {
  double v = 0;
  for (auto f : m.faces()) {
    std::vector<Vec3> p;
    for (auto w : m.fv_range(f)) p.push_back(m.point(w));
    v += OpenMesh::dot(p[0], OpenMesh::cross(p[1], p[2])) / 6;
  }
  return v;
}

std::vector<int> valence_counts(const TriMesh& m) {
  std::vector<int> out(12, 0);
  for (auto v : m.vertices()) ++out[std::min<std::size_t>(11, m.valence(v))];
  return out;
}

// A capped tube's triangulation: one closed genus-0 surface facing out, 12 vertices of valence 5 (the caps'
// pentagons) and the rest of valence 6, and unless `any_edges` every edge in [0.8, 1.2] times the lattice edge (so
// that `carbonmesh build` takes it as it is).
void expect_capped_tube(const CappedTube& tube, double edge, bool any_edges = false) {
  const Topology top = topology(tube.mesh);
  EXPECT_EQ(top.boundary_loops, 0);
  EXPECT_EQ(top.genus, 0);
  EXPECT_EQ(top.components, 1);
  const std::vector<int> valences = valence_counts(tube.mesh);
  EXPECT_EQ(valences[5], 12);
  EXPECT_EQ(valences[6], static_cast<int>(tube.mesh.n_vertices()) - 12);
  EXPECT_GT(volume(tube.mesh), 0);
  if (any_edges) return;
  const EdgeStats e = edge_stats(tube.mesh);
  EXPECT_GE(e.min, 0.8 * edge);
  EXPECT_LE(e.max, 1.2 * edge);
}

}  // namespace

// The icosahedron's net, each face the lattice triangle 0, w, w turned by 60 degrees, folds into the Goldberg-Coxeter
// sphere's triangulation: 10 T + 2 vertices, 20 T triangles, 12 of valence 5 and the rest of valence 6.
TEST(LatticeNet, TheIcosahedronsNetIsTheGoldbergCoxeterTriangulation) {
  using namespace lattice_net;
  for (const auto& [h, k] : std::vector<std::pair<long, long>>{{1, 0}, {1, 1}, {2, 1}, {3, 3}, {4, 1}, {2, 5}}) {
    SCOPED_TRACE(testing::Message() << "(" << h << ", " << k << ")");
    const LatticePoint w{h, k};
    const long t = squared_length(w);
    // The icosahedron as a pyramid, an antiprism and a pyramid: N = 0, U_i = 1 + i, L_i = 6 + i, S = 11.
    std::vector<NetFace> faces;
    for (int i = 0; i < 5; ++i) {
      const int u = 1 + i, u1 = 1 + (i + 1) % 5, lo = 6 + i, lo1 = 6 + (i + 1) % 5;
      const LatticePoint o{0, 0}, down = turned(w, -1);
      faces.push_back({{u, u1, 0}, {o, w, turned(w, 1)}});
      faces.push_back({{u, lo, u1}, {o, down, w}});
      faces.push_back({{lo, lo1, u1}, {down, down + w, w}});
      faces.push_back({{lo, 11, lo1}, {o, down, w}});
    }
    const Folded folded = fold_lattice(12, faces);
    EXPECT_EQ(static_cast<long>(folded.places.size()), 10 * t + 2);
    ASSERT_EQ(static_cast<long>(folded.triangles.size()), 20 * t);
    std::vector<int> valence(folded.places.size(), 0);
    for (const auto& tri : folded.triangles)
      for (int v : tri) ++valence[static_cast<std::size_t>(v)];
    for (std::size_t v = 0; v < valence.size(); ++v) EXPECT_EQ(valence[v], v < 12 ? 5 : 6) << v;
  }
}

// A net whose edge has lattice vectors of different lengths in its two faces does not fold.
TEST(LatticeNet, RefusesFacesThatDoNotFit) {
  using namespace lattice_net;
  // A tetrahedron of four lattice triangles, one of them larger than its neighbours.
  std::vector<NetFace> faces = {{{0, 2, 1}, {{{0, 0}, {1, 0}, {0, 1}}}},
                                {{0, 1, 3}, {{{0, 0}, {1, 0}, {0, 1}}}},
                                {{1, 2, 3}, {{{0, 0}, {1, 0}, {0, 1}}}},
                                {{0, 3, 2}, {{{0, 0}, {2, 0}, {0, 2}}}}};
  EXPECT_THROW(fold_lattice(4, faces), std::logic_error);
  faces[3].at = {{{0, 0}, {1, 0}, {0, 1}}};
  const Folded tetrahedron = fold_lattice(4, faces);  // four corners of 180 degrees: valence 3
  EXPECT_EQ(tetrahedron.places.size(), 4u);
  EXPECT_EQ(tetrahedron.triangles.size(), 4u);
}

// Every chirality (5h, 5k) at any length: a closed genus-0 surface facing out, 12 vertices of valence 5 (the caps'
// pentagons) and the rest of valence 6, 20 T + j P faces, and every edge in [0.8, 1.2] times the lattice edge (so that
// `carbonmesh build` takes it as it is).
TEST(CappedTube, HasTwelvePentagonsAndHexagonsOnly) {
  for (const auto& [n, m] : std::vector<std::pair<int, int>>{{5, 5}, {10, 0}, {0, 10}, {10, 5}, {15, 5}, {20, 20}}) {
    for (double length : {0.0, 12.0, 40.0}) {
      SCOPED_TRACE(testing::Message() << "(" << n << ", " << m << ") length " << length);
      const double edge = 2.0;
      const CappedTube tube = make_capped_tube({n, m, length, edge});
      expect_capped_tube(tube, edge);
      EXPECT_NEAR(tube.radius, edge * std::sqrt(n * n + n * m + m * m) / (2 * kPi), 1e-12);
      // The straight part is whole periods, within half a period of the length asked.
      EXPECT_NEAR(tube.straight_length, tube.periods * tube.period, 1e-9);
      EXPECT_LE(std::abs(tube.straight_length - length), 0.5 * tube.period + 1e-9);
      const long t = triangulation_number(n / 5, m / 5);
      EXPECT_EQ(static_cast<long>(tube.mesh.n_faces()) % 2, 0);
      EXPECT_GE(static_cast<long>(tube.mesh.n_faces()), 20 * t);
      EXPECT_EQ(tube.periods == 0, static_cast<long>(tube.mesh.n_faces()) == 20 * t);
    }
  }
}

// (5, 5) with no period added is C60's triangulation, on the sphere of the tube's radius; each period of the armchair tube adds 20 faces (a ring of 10
// hexagons and 20 atoms: C80, C100, ...), each of the (10, 0) tube 40.
TEST(CappedTube, PeriodsAddRingsOfTheTube) {
  // No period added: the Goldberg-Coxeter sphere of the tube's radius.
  for (const auto& [n, m] : std::vector<std::pair<int, int>>{{5, 5}, {15, 10}}) {
    const CappedTube sphere = make_capped_tube({n, m, 0.0, 1.0});
    EXPECT_EQ(static_cast<long>(sphere.mesh.n_faces()), 20 * triangulation_number(n / 5, m / 5));
    EXPECT_EQ(sphere.periods, 0);
    EXPECT_EQ(sphere.straight_length, 0.0);
    for (auto v : sphere.mesh.vertices()) EXPECT_NEAR(sphere.mesh.point(v).norm(), sphere.radius, 1e-9);
  }
  for (const auto& [n, m, per_period] : std::vector<std::tuple<int, int, std::size_t>>{{5, 5, 20}, {10, 0, 40}}) {
    const double period = capped_tube_period(n, m, 1.0);
    const CappedTube a = make_capped_tube({n, m, 20.0, 1.0}), b = make_capped_tube({n, m, 20.0 + 3 * period, 1.0});
    EXPECT_EQ(b.periods, a.periods + 3);
    EXPECT_EQ(b.mesh.n_faces(), a.mesh.n_faces() + 3 * per_period);
    EXPECT_NEAR(b.straight_length - a.straight_length, 3 * period, 1e-9);
  }
  EXPECT_NEAR(capped_tube_period(5, 5, 1.0), 1.0, 1e-12);                  // armchair: one lattice edge
  EXPECT_NEAR(capped_tube_period(10, 0, 1.0), std::sqrt(3.0), 1e-12);      // zigzag: sqrt(3) edges
}

// Away from the caps (more than 4 edges from the straight part's ends: the springs that even out an apex cap's
// triangles reach 3 edges past them) the vertices lie on the tube's cylinder and the edges run the lattice's three
// directions rolled with the chiral angle theta: at 90 - theta, 30 - theta and 30 + theta degrees to the axis.
TEST(CappedTube, MiddleIsTheLatticeRolledWithItsChirality) {
  for (const auto& [n, m] :
       std::vector<std::pair<int, int>>{{10, 0}, {10, 10}, {15, 5}, {5, 15}, {9, 0}, {12, 12}, {13, 4}, {4, 13}}) {
    SCOPED_TRACE(testing::Message() << "(" << n << ", " << m << ")");
    const double edge = 1.0;
    const CappedTube tube = make_capped_tube({n, m, 30.0, edge});
    const TriMesh& mesh = tube.mesh;
    const double theta = std::atan2(std::sqrt(3.0) * m, 2.0 * n + m) * 180 / kPi;
    const double middle = 0.5 * tube.straight_length - 4 * edge;
    ASSERT_GT(middle, 5 * edge);
    std::size_t edges = 0;
    for (auto e : mesh.edges()) {
      const Vec3 p = mesh.point(mesh.from_vertex_handle(mesh.halfedge_handle(e, 0)));
      const Vec3 q = mesh.point(mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)));
      if (std::abs(p[2]) > middle || std::abs(q[2]) > middle) continue;
      ++edges;
      EXPECT_NEAR(std::hypot(p[0], p[1]), tube.radius, 0.01 * edge);
      const double to_axis = std::acos(std::abs((q - p).normalized()[2])) * 180 / kPi;  // 0 .. 90 degrees
      double nearest = 180;
      for (double expected : {90 - theta, std::abs(30 - theta), 30 + theta})
        nearest = std::min(nearest, std::abs(to_axis - expected));
      EXPECT_LT(nearest, 2.0) << to_axis << " degrees to the axis";
    }
    EXPECT_GT(edges, 100u);
  }
}

// An apex cap's steps add up to the chiral vector, and for (5h, 5k) they are the icosahedral cap's five equal steps;
// every tube but the thinnest has one ((3, 3), (4, 2), (5, 1) and wider: n^2 + nm + m^2 >= 25).
TEST(ApexCap, StepsAddUpToTheChiralVectorForEveryTubeButTheThinnest) {
  using namespace lattice_net;
  for (int n = 0; n <= 24; ++n)
    for (int m = 0; m <= 24; ++m) {
      if (n == 0 && m == 0) continue;
      SCOPED_TRACE(testing::Message() << "(" << n << ", " << m << ")");
      const auto steps = apex_cap::apex_cap_steps(n, m);
      ASSERT_EQ(steps.has_value(), triangulation_number(n, m) >= 25);
      if (!steps) continue;
      LatticePoint sum{0, 0};
      for (const auto& f : *steps) sum = sum + f;
      EXPECT_EQ(sum, (LatticePoint{n, m}));
      if (n % 5 == 0 && m % 5 == 0) {
        for (const auto& f : *steps) EXPECT_EQ(f, (LatticePoint{n / 5, m / 5}));
      }
    }
}

// Indices that are not both multiples of 5 get apex caps, at any length: a closed genus-0 surface facing out, 12
// vertices of valence 5 (six per cap) and the rest of valence 6, every edge in [0.8, 1.2] times the lattice edge
// (but for the shortest cage, length 0), no two triangles crossing, and a straight part (the capsule with the
// triangles' area) within half a lattice row of the length asked.
TEST(CappedTube, ApexCapsCloseAnyOtherTube) {
  for (const auto& [n, m] : std::vector<std::pair<int, int>>{
           {3, 3}, {4, 2}, {6, 6}, {9, 0}, {0, 9}, {7, 3}, {3, 7}, {8, 4}, {12, 1}, {17, 3}, {11, 11}}) {
    for (double length : {0.0, 15.0, 40.0}) {
      SCOPED_TRACE(testing::Message() << "(" << n << ", " << m << ") length " << length);
      const double edge = 2.0;
      const CappedTube tube = make_capped_tube({n, m, length, edge});
      EXPECT_EQ(tube.caps, CapKind::apex);
      expect_capped_tube(tube, edge, length == 0);  // the shortest cages' edges may leave [0.8, 1.2] a by a little
      EXPECT_EQ(self_intersections(tube.mesh).pairs, 0);
      // The triangles' area is that of the capsule the points lie on.
      const double area = static_cast<double>(tube.mesh.n_faces()) * std::sqrt(3.0) / 4 * edge * edge;
      if (tube.straight_length > 0) {
        EXPECT_NEAR(area, 4 * kPi * tube.radius * tube.radius + 2 * kPi * tube.radius * tube.straight_length, 1e-6);
      }
      if (length > 0) {
        const double g = std::gcd(n, m), circumference = std::sqrt(static_cast<double>(triangulation_number(n, m)));
        EXPECT_LE(std::abs(tube.straight_length - length), g * std::sqrt(3.0) / 4 * edge / circumference + 1e-9);
      }
    }
  }
}

TEST(CappedTube, RefusesBadIndices) {
  EXPECT_THROW(make_capped_tube({2, 1, 10.0, 1.0}), InputError);  // too thin for a cap
  EXPECT_THROW(make_capped_tube({4, 1, 10.0, 1.0}), InputError);
  EXPECT_THROW(make_capped_tube({0, 0, 10.0, 1.0}), InputError);
  EXPECT_THROW(make_capped_tube({-5, 5, 10.0, 1.0}), InputError);
  EXPECT_THROW(make_capped_tube({5, 5, -1.0, 1.0}), InputError);
  EXPECT_THROW(make_capped_tube({6, 6, -1.0, 1.0}), InputError);
  EXPECT_THROW(make_capped_tube({5, 5, 10.0, 0.0}), InputError);
  EXPECT_THROW(make_capped_tube({5, 5, 1e12, 1.0}), InputError);
  EXPECT_THROW(make_capped_tube({6, 6, 1e12, 1.0}), InputError);
}

// The capsule through a capsule's vertices, turned and shifted: its radius, straight length, axis and centre, every
// vertex on it; a stretched one is no capsule.
TEST(CapsuleFit, FindsTheCapsuleThroughTheVertices) {
  TriMesh capsule = make_capsule({5.0, 20.0, 0.0});
  const Vec3 axis = Vec3(1, 2, 3).normalized(), shift(4, -7, 2);
  const Vec3 u = OpenMesh::cross(axis, Vec3(1, 0, 0)).normalized(), v = OpenMesh::cross(axis, u);
  for (auto w : capsule.vertices()) {
    const Vec3 p = capsule.point(w);
    capsule.set_point(w, shift + p[0] * u + p[1] * v + p[2] * axis);
  }
  const Capsule fit = capsule_fit(capsule);
  EXPECT_NEAR(fit.radius, 5.0, 1e-6);
  EXPECT_NEAR(fit.length, 20.0, 1e-6);
  EXPECT_LT(fit.distance, 1e-6);
  EXPECT_NEAR(std::abs(OpenMesh::dot(fit.axis, axis)), 1.0, 1e-9);
  EXPECT_LT((fit.centre - shift).norm(), 1e-6);
  EXPECT_NEAR(capsule_area(fit), 2 * kPi * 5 * 20 + 4 * kPi * 25, 1e-6);
  TriMesh flattened = make_capsule({5.0, 20.0, 0.0});
  for (auto w : flattened.vertices()) {
    Vec3 p = flattened.point(w);
    p[0] *= 1.05;
    flattened.set_point(w, p);
  }
  EXPECT_GT(capsule_fit(flattened).distance, 0.1);
}

// The capped tube nearest a radius: (10, 5) for 5 A at the lattice edge of graphene ((15, 0) has 5.87 A, (10, 0) 3.91
// A), (5, 5) for C60's tube; a larger radius gives a wider tube.
TEST(CapsuleFit, NearestCappedChirality) {
  const double a = std::sqrt(3.0) * 1.42;
  EXPECT_EQ(nearest_capped_chirality(5.0, a), (std::array<int, 2>{10, 5}));
  EXPECT_EQ(nearest_capped_chirality(3.39, a), (std::array<int, 2>{5, 5}));
  EXPECT_EQ(nearest_capped_chirality(capped_tube_radius(25, 10, a), a), (std::array<int, 2>{25, 10}));
  EXPECT_EQ(nearest_capped_chirality(0.1, a), (std::array<int, 2>{5, 0}));
}

// The capped tube on a capsule faces the side the capsule's faces face, and lies on the capsule's axis.
TEST(CapsuleFit, LatticeCappedTubeFollowsTheInput) {
  const double a = std::sqrt(3.0) * 1.42;
  TriMesh capsule = make_capsule({5.0, 20.0, 0.0});
  const Capsule fit = capsule_fit(capsule);
  const LatticeCappedTube out = lattice_capped_tube(capsule, fit, a, {10, 5});
  EXPECT_GT(volume(out.mesh), 0);
  EXPECT_EQ(valence_counts(out.mesh)[5], 12);
  for (auto v : out.mesh.vertices()) {
    const Vec3 p = out.mesh.point(v);
    const double along = std::clamp(OpenMesh::dot(p - fit.centre, fit.axis), -out.length / 2, out.length / 2);
    EXPECT_NEAR((p - fit.centre - along * fit.axis).norm(), out.radius, 1e-9);
  }
  TriMesh inward;
  std::vector<TriMesh::VertexHandle> handles;
  for (auto v : capsule.vertices()) handles.push_back(inward.add_vertex(capsule.point(v)));
  for (auto f : capsule.faces()) {
    std::vector<TriMesh::VertexHandle> c;
    for (auto v : capsule.fv_range(f)) c.push_back(handles[static_cast<std::size_t>(v.idx())]);
    inward.add_face(c[0], c[2], c[1]);
  }
  EXPECT_LT(volume(lattice_capped_tube(inward, fit, a, {10, 5}).mesh), 0);
  EXPECT_LT(volume(lattice_capped_tube(inward, fit, a, {11, 4}).mesh), 0);  // apex caps
  const LatticeCappedTube apex = lattice_capped_tube(capsule, fit, a, {11, 4});
  EXPECT_EQ(apex.caps, CapKind::apex);
  EXPECT_GT(volume(apex.mesh), 0);
  EXPECT_EQ(valence_counts(apex.mesh)[5], 12);
  EXPECT_THROW(lattice_capped_tube(capsule, fit, a, {2, 1}), InputError);
}
