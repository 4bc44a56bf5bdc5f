// The dual of triangle meshes (atoms, bonds, rings, maps) and the dual optimisation.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "carbonmesh/dual/coarse_start.hpp"
#include "carbonmesh/dual/dual_mesh.hpp"
#include "carbonmesh/dual/ears.hpp"
#include "carbonmesh/dual/graph_stats.hpp"
#include "carbonmesh/dual/optimize.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "test_meshes.hpp"

using namespace carbonmesh;

namespace {

// An icosphere scaled so that its area is faces * (3 sqrt(3) / 4) b^2: the area a graphene-like net of
// bond b needs for one atom per face.
TriMesh fullerene_surface(int subdivisions, double b) {
  TriMesh mesh = make_icosphere({1.0, subdivisions});
  const double wanted = static_cast<double>(mesh.n_faces()) * 3.0 * std::sqrt(3.0) / 4.0 * b * b;
  const double s = std::sqrt(wanted / surface_area(mesh));
  for (auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) * s);
  mesh.update_normals();
  return mesh;
}

// Six triangles around one vertex: a flat hexagonal fan with a border.
TriMesh hexagon_fan() {
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> v{mesh.add_vertex(Vec3(0, 0, 0))};
  for (int i = 0; i < 6; ++i) v.push_back(mesh.add_vertex(Vec3(std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), 0)));
  for (int i = 0; i < 6; ++i) mesh.add_face(v[0], v[1 + i], v[1 + (i + 1) % 6]);
  return mesh;
}

}  // namespace

TEST(Dual, IcosphereGivesFullereneWith12Pentagons) {
  for (int s = 0; s <= 3; ++s) {
    const TriMesh sphere = make_icosphere({5.0, s});
    const Dual dual = build_dual(sphere);
    EXPECT_EQ(dual.atoms(), sphere.n_faces());
    EXPECT_EQ(dual.bonds.size(), sphere.n_edges());
    EXPECT_EQ(dual.rings.size(), sphere.n_vertices());
    EXPECT_EQ(dual.mesh.n_faces(), sphere.n_vertices());
    EXPECT_EQ(dual.counts.ring_sizes.at(5), 12u) << "subdivisions " << s;
    const std::size_t hexagons = sphere.n_vertices() - 12;
    if (hexagons > 0) {
      EXPECT_EQ(dual.counts.ring_sizes.at(6), hexagons);
    }
    EXPECT_EQ(dual.counts.ring_sizes.size(), hexagons > 0 ? 2u : 1u);
    EXPECT_EQ(dual.counts.coordination.size(), 1u);
    EXPECT_EQ(dual.counts.coordination.at(3), dual.atoms());
    EXPECT_DOUBLE_EQ(dual.counts.percent_three_bonds, 100.0);
    EXPECT_EQ(dual.counts.open_rings, 0u);
    EXPECT_EQ(dual.counts.border_atoms, 0u);
  }
}

TEST(Dual, MapsAreInverseAndAtomsSitAtCentroids) {
  const TriMesh sphere = make_icosphere({3.0, 2});
  const Dual dual = build_dual(sphere);
  for (std::size_t a = 0; a < dual.atoms(); ++a) {
    const int f = dual.atom_face[a];
    EXPECT_EQ(dual.face_atom[static_cast<std::size_t>(f)], static_cast<int>(a));
    Vec3 c(0, 0, 0);
    for (auto v : sphere.fv_range(sphere.face_handle(static_cast<unsigned>(f)))) c += sphere.point(v);
    EXPECT_LT((dual.mesh.point(dual.mesh.vertex_handle(static_cast<unsigned>(a))) - c / 3.0).norm(), 1e-12);
  }
  for (std::size_t r = 0; r < dual.rings.size(); ++r) {
    const int v = dual.ring_vertex[r];
    EXPECT_EQ(dual.vertex_ring[static_cast<std::size_t>(v)], static_cast<int>(r));
    EXPECT_EQ(dual.rings[r].size(), sphere.valence(sphere.vertex_handle(static_cast<unsigned>(v))));
    // Every atom of the ring is a triangle around the vertex.
    for (int a : dual.rings[r]) {
      bool found = false;
      for (auto u : sphere.fv_range(sphere.face_handle(static_cast<unsigned>(dual.atom_face[static_cast<std::size_t>(a)]))))
        found = found || u.idx() == v;
      EXPECT_TRUE(found);
    }
  }
  // Each bond joins the two triangles of its primal edge.
  for (std::size_t i = 0; i < dual.bonds.size(); ++i) {
    const auto e = sphere.edge_handle(static_cast<unsigned>(dual.bond_edge[i]));
    const int f0 = sphere.face_handle(sphere.halfedge_handle(e, 0)).idx();
    const int f1 = sphere.face_handle(sphere.halfedge_handle(e, 1)).idx();
    EXPECT_EQ(std::minmax(dual.face_atom[static_cast<std::size_t>(f0)], dual.face_atom[static_cast<std::size_t>(f1)]),
              std::minmax(dual.bonds[i][0], dual.bonds[i][1]));
  }
}

TEST(Dual, RingsAreOrientedOutward) {
  const TriMesh sphere = make_icosphere({4.0, 2});
  const Dual dual = build_dual(sphere);
  for (auto f : dual.mesh.faces()) {
    Vec3 c(0, 0, 0);
    int n = 0;
    for (auto v : dual.mesh.fv_range(f)) c += dual.mesh.point(v), ++n;
    EXPECT_GT(OpenMesh::dot(dual.mesh.normal(f), c / n), 0.0);
  }
}

TEST(Dual, OpenBorderGivesTwoCoordinatedAtomsAndOpenRings) {
  const Dual dual = build_dual(hexagon_fan());
  EXPECT_EQ(dual.atoms(), 6u);
  EXPECT_EQ(dual.bonds.size(), 6u);
  EXPECT_EQ(dual.counts.closed_rings, 1u);
  EXPECT_EQ(dual.counts.ring_sizes.at(6), 1u);
  EXPECT_EQ(dual.counts.open_rings, 6u);
  EXPECT_EQ(dual.counts.coordination.at(2), 6u);
  EXPECT_EQ(dual.counts.border_atoms, 6u);
  EXPECT_DOUBLE_EQ(dual.counts.percent_three_bonds, 0.0);
  // Each open ring (border vertex) holds the two triangles at that vertex, in order.
  for (std::size_t r = 0; r < dual.rings.size(); ++r)
    if (!dual.ring_closed[r]) {
      EXPECT_EQ(dual.rings[r].size(), 2u);
    }
}

// Every face's count of border edges is at most one: no atom of the dual has fewer than two bonds.
static void expect_no_ears(const TriMesh& mesh) {
  for (auto f : mesh.faces()) {
    int border = 0;
    for (auto h : mesh.fh_range(f)) border += mesh.is_boundary(mesh.opposite_halfedge_handle(h)) ? 1 : 0;
    EXPECT_LE(border, 1) << "face " << f.idx();
  }
}

TEST(Ears, ATriangularSheetLosesItsThreeCornerTriangles) {
  TriMesh sheet = test::triangle_sheet(4, 8.0);  // 16 triangles of side 2
  ASSERT_EQ(build_dual(sheet).counts.coordination.at(1), 3u);  // the corners' atoms: one bond each
  const EarRemoval removed = remove_ears(sheet);
  EXPECT_EQ(removed.faces, 3u);
  EXPECT_NEAR(removed.area, 3 * std::sqrt(3.0), 1e-12);  // three triangles of side 2
  EXPECT_EQ(sheet.n_faces(), 13u);
  EXPECT_EQ(sheet.n_vertices(), 12u);  // the three corner vertices went with them
  expect_no_ears(sheet);
  const Dual dual = build_dual(sheet);
  EXPECT_EQ(dual.counts.coordination.count(0), 0u);
  EXPECT_EQ(dual.counts.coordination.count(1), 0u);
  EXPECT_EQ(dual.counts.coordination.at(2) + dual.counts.coordination.at(3), 13u);
}

TEST(Ears, AStripOneTriangleWideGoesWhole) {
  // Two rows of 6 vertices: 10 triangles, the two at the ends with two border edges, the others with one; each
  // removal leaves its neighbour with two.
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;
  for (int i = 0; i < 6; ++i) points.emplace_back(i, 0, 0), points.emplace_back(i + 0.5, 1, 0);
  for (int i = 0; i < 5; ++i) {
    triangles.push_back({2 * i, 2 * i + 2, 2 * i + 1});
    triangles.push_back({2 * i + 1, 2 * i + 2, 2 * i + 3});
  }
  TriMesh strip = test::mesh_from(points, triangles);
  const EarRemoval removed = remove_ears(strip);
  EXPECT_EQ(removed.faces, 10u);
  EXPECT_EQ(strip.n_faces(), 0u);
  EXPECT_EQ(strip.n_vertices(), 0u);
}

TEST(Ears, ClosedSurfacesAndFansKeepEveryFace) {
  TriMesh sphere = make_icosphere({10.0, 2});
  const std::size_t faces = sphere.n_faces();
  EXPECT_EQ(remove_ears(sphere).faces, 0u);
  EXPECT_EQ(sphere.n_faces(), faces);
  TriMesh fan = hexagon_fan();  // six triangles, each with one border edge
  EXPECT_EQ(remove_ears(fan).faces, 0u);
  EXPECT_EQ(fan.n_faces(), 6u);
}

TEST(GraphStats, AnglesOfAHexagonFanAre120) {
  const Dual dual = build_dual(hexagon_fan());
  const auto angles = bond_angles(dual.atoms(), dual.bonds);
  ASSERT_EQ(angles.size(), 6u);
  const SampleStats s = sample_stats(angle_degrees(dual.positions(), angles));
  EXPECT_NEAR(s.min, 120.0, 1e-9);
  EXPECT_NEAR(s.max, 120.0, 1e-9);
  const SampleStats b = sample_stats(bond_lengths(dual.positions(), dual.bonds));
  EXPECT_NEAR(b.mean, 1.0 / std::sqrt(3.0), 1e-12);  // centroid distance of unit equilateral triangles
  EXPECT_NEAR(b.std, 0.0, 1e-12);
}

TEST(DualOptimize, SubdividedIcosahedronFullereneBondsWithinTolerance) {
  const double b = 1.42;
  for (int s : {1, 2, 3}) {
    const TriMesh surface = fullerene_surface(s, b);
    Dual dual = build_dual(surface);
    DualOptimizeSettings settings;
    settings.bond = b;
    const DualOptimizeResult r = optimize_dual(dual, surface, settings);
    EXPECT_GT(r.bonds_after.min, b - 0.05) << "C" << dual.atoms();
    EXPECT_LT(r.bonds_after.max, b + 0.05) << "C" << dual.atoms();
    EXPECT_LT(r.bonds_after.std, r.bonds_before.std) << "C" << dual.atoms();
    EXPECT_LT(r.energy_after, r.energy_before);
    EXPECT_LT(r.surface_max_after, 0.1);
    const SampleStats check = sample_stats(bond_lengths(dual.positions(), dual.bonds));
    EXPECT_DOUBLE_EQ(check.max, r.bonds_after.max);  // the atoms were moved
  }
}

TEST(DualOptimize, IsDeterministic) {
  const TriMesh surface = fullerene_surface(2, 1.42);
  Dual a = build_dual(surface), b = build_dual(surface);
  optimize_dual(a, surface);
  optimize_dual(b, surface);
  const auto pa = a.positions(), pb = b.positions();
  for (std::size_t i = 0; i < pa.size(); ++i) EXPECT_EQ(pa[i], pb[i]);
}

TEST(DualOptimize, WithoutIterationsOnlyMeasures) {
  const TriMesh surface = fullerene_surface(1, 1.42);
  Dual dual = build_dual(surface);
  const auto before = dual.positions();
  DualOptimizeSettings settings;
  settings.max_iterations = 0;
  const DualOptimizeResult r = optimize_dual(dual, surface, settings);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(dual.positions(), before);
  EXPECT_DOUBLE_EQ(r.bonds_before.mean, r.bonds_after.mean);
  EXPECT_NEAR(r.surface_max_before, 0.0, 1e-9);  // centroids lie on their triangles
}

// The surface is 6% too large for its atom count (as when the remesher makes fewer, larger triangles than
// area / 2.62 A^2): with the free scale the structure shrinks to bond b, held on s S with s ~ 1/1.06.
TEST(DualOptimize, FreeScaleFitsTheSizeToTheAtomCount) {
  const double b = 1.42;
  TriMesh surface = fullerene_surface(2, b);
  for (auto v : surface.vertices()) surface.set_point(v, surface.point(v) * 1.06);
  surface.update_normals();
  Dual free = build_dual(surface), fixed = build_dual(surface);
  const DualOptimizeResult r = optimize_dual(free, surface);
  EXPECT_NEAR(r.bonds_after.mean, b, 0.005);
  EXPECT_GT(r.bonds_after.min, b - 0.05);
  EXPECT_LT(r.bonds_after.max, b + 0.05);
  EXPECT_NEAR(r.surface_scale, 1 / 1.06, 0.02);
  EXPECT_LT(r.surface_max_after, 0.05);  // distance to s S
  DualOptimizeSettings keep;
  keep.free_scale = false;
  const DualOptimizeResult k = optimize_dual(fixed, surface, keep);
  EXPECT_EQ(k.surface_scale, 1.0);
  EXPECT_GT(k.bonds_after.mean, b + 0.03);  // pinned to S, every bond takes the misfit
}

// The energy criterion stops the tail: C5120 converges in a few hundred iterations with bonds in the window.
TEST(DualOptimize, LargerFullereneConvergesInFewIterations) {
  const TriMesh surface = fullerene_surface(4, 1.42);  // C5120
  Dual dual = build_dual(surface);
  const DualOptimizeResult r = optimize_dual(dual, surface);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.iterations, 600);
  EXPECT_GT(r.bonds_after.min, 1.42 - 0.05);
  EXPECT_LT(r.bonds_after.max, 1.42 + 0.05);
  EXPECT_GE(r.evaluations, r.iterations);
}

namespace {

// The smallest distance between two atoms that are not bonded (brute force: small structures only).
double closest_non_bonded(const Dual& dual) {
  const auto p = dual.positions();
  std::vector<std::vector<int>> bonded(p.size());
  for (const auto& b : dual.bonds) bonded[static_cast<std::size_t>(b[0])].push_back(b[1]);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const auto& n = bonded[i];
      if (std::find(n.begin(), n.end(), static_cast<int>(j)) != n.end()) continue;
      best = std::min(best, (p[i] - p[j]).norm());
    }
  return best;
}

}  // namespace

// A tube thinner than the bond scale (torus of radii 3 and 1.2 A, triangles of edge ~sqrt(3) 1.42): the bond
// term alone crushes the net on the inner side (non-bonded atoms 1.09 A apart); the contact term keeps every
// non-bonded pair apart.
TEST(DualOptimize, ContactTermKeepsAThinTubeFromFolding) {
  const TriMesh surface = make_torus({3.0, 1.2, std::sqrt(3.0) * 1.42});
  Dual with = build_dual(surface), without = build_dual(surface);
  optimize_dual(with, surface);
  DualOptimizeSettings off;
  off.contact_weight = 0;
  optimize_dual(without, surface, off);
  const double a = closest_non_bonded(with), b = closest_non_bonded(without);
  EXPECT_GT(a, 1.5) << "without the term: " << b;  // measured: 1.86 with, 1.09 without
  EXPECT_LT(b, a);
}

// The coarse start moves every fine atom by the displacement of the coarse atoms around it: a uniform
// displacement is passed on exactly, and one coarse atom's displacement goes mostly to the fine atoms nearest it.
TEST(CoarseStart, TransferPassesOnTheCoarseDisplacements) {
  Dual fine = build_dual(make_icosphere({10.0, 3}));
  const Dual coarse = build_dual(make_icosphere({10.0, 2}));
  const std::vector<Vec3> from = coarse.positions(), before = fine.positions();
  std::vector<Vec3> to = from;
  const Vec3 t(0.3, -0.2, 0.1);
  for (Vec3& p : to) p += t;
  const DisplacementTransfer r = transfer_displacements(fine, from, to);
  EXPECT_EQ(r.atoms, fine.atoms());
  EXPECT_NEAR(r.mean_shift, t.norm(), 1e-12);
  EXPECT_NEAR(r.max_shift, t.norm(), 1e-12);
  const std::vector<Vec3> after = fine.positions();
  for (std::size_t i = 0; i < after.size(); ++i) EXPECT_NEAR((after[i] - before[i] - t).norm(), 0.0, 1e-12) << i;

  // Only coarse atom 0 moves: the fine atom nearest it moves most, the far side of the sphere not at all.
  Dual again = build_dual(make_icosphere({10.0, 3}));
  to = from;
  to[0] += Vec3(1, 0, 0);
  transfer_displacements(again, from, to);
  const std::vector<Vec3> moved = again.positions();
  std::size_t nearest = 0, farthest = 0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    if ((before[i] - from[0]).norm() < (before[nearest] - from[0]).norm()) nearest = i;
    if ((before[i] - from[0]).norm() > (before[farthest] - from[0]).norm()) farthest = i;
  }
  double largest = 0;
  for (std::size_t i = 0; i < before.size(); ++i) largest = std::max(largest, (moved[i] - before[i]).norm());
  EXPECT_DOUBLE_EQ((moved[nearest] - before[nearest]).norm(), largest);
  EXPECT_GT(largest, 0.5);
  EXPECT_EQ((moved[farthest] - before[farthest]).norm(), 0.0);
  EXPECT_THROW(transfer_displacements(again, from, std::vector<Vec3>(1)), std::invalid_argument);
}

// The whole coarse start: the coarse dual (icosphere one subdivision coarser, on the same sphere) is optimised at
// bond 2 b, its bonds end near 2 b, and every fine atom is moved by what it did.
TEST(CoarseStart, OptimisesTheCoarseDualAtTwiceTheBond) {
  const TriMesh surface = fullerene_surface(3, 1.42);
  const double radius = surface.point(*surface.vertices().begin()).norm();
  TriMesh coarse_mesh = make_icosphere({radius, 2});
  Dual fine = build_dual(surface);
  const std::vector<Vec3> before = fine.positions();
  DualOptimizeSettings settings;
  const CoarseStartResult r = coarse_start(fine, coarse_mesh, surface, settings);
  EXPECT_EQ(r.coarse_atoms, coarse_mesh.n_faces());
  EXPECT_TRUE(r.coarse.converged);
  EXPECT_NEAR(r.coarse.bonds_after.mean, 2 * 1.42, 0.02 * 2 * 1.42);
  EXPECT_EQ(r.transfer.atoms, fine.atoms());
  EXPECT_GT(r.transfer.max_shift, 0.0);
  const std::vector<Vec3> after = fine.positions();
  double largest = 0;
  for (std::size_t i = 0; i < after.size(); ++i) largest = std::max(largest, (after[i] - before[i]).norm());
  EXPECT_NEAR(largest, r.transfer.max_shift, 1e-12);
}

// Several levels: the coarsest (level 2, bond 4 b) is optimised first, its displacements move the level-1 atoms,
// which are optimised from there at bond 2 b, and the level-1 displacements (from its centroids) move the fine
// atoms. Levels may come in any order; one level gives what the one-level overload gives.
TEST(CoarseStart, OptimisesTheLevelsCoarsestFirst) {
  const double b = 1.42;
  const TriMesh surface = fullerene_surface(4, b);
  const double radius = surface.point(*surface.vertices().begin()).norm();
  std::vector<CoarseLevel> levels{{1, make_icosphere({radius, 3})}, {2, make_icosphere({radius, 2})}};
  Dual fine = build_dual(surface);
  DualOptimizeSettings settings;
  settings.bond = b;
  const std::vector<CoarseStartResult> r = coarse_start(fine, levels, surface, settings);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].level, 2);
  EXPECT_EQ(r[1].level, 1);
  EXPECT_EQ(r[0].coarse_atoms, levels[1].mesh.n_faces());
  EXPECT_EQ(r[1].coarse_atoms, levels[0].mesh.n_faces());
  EXPECT_NEAR(r[0].coarse.bonds_after.mean, 4 * b, 0.02 * 4 * b);
  EXPECT_NEAR(r[1].coarse.bonds_after.mean, 2 * b, 0.02 * 2 * b);
  EXPECT_EQ(r[0].transfer.atoms, levels[0].mesh.n_faces());  // level 2 moved the level-1 atoms
  EXPECT_GT(r[0].transfer.max_shift, 0.0);
  EXPECT_EQ(r[1].transfer.atoms, fine.atoms());
  const nlohmann::json j = to_json(r);
  EXPECT_EQ(j["level"], 1);
  EXPECT_EQ(j["levels"].size(), 2u);

  Dual one = build_dual(surface), overload = build_dual(surface);
  coarse_start(one, std::vector<CoarseLevel>{levels[0]}, surface, settings);
  coarse_start(overload, levels[0].mesh, surface, settings);
  EXPECT_EQ(one.positions(), overload.positions());
  levels.push_back({1, make_icosphere({radius, 1})});
  EXPECT_THROW(coarse_start(one, levels, surface, settings), std::invalid_argument);
}
