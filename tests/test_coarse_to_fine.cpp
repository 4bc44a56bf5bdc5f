// Coarse to fine: the 1-to-4 midpoint subdivision and the remesh that starts at twice the interval.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "carbonmesh/remesh/remesher.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "test_meshes.hpp"

namespace carbonmesh {
namespace {

using test::scaled;

// Four faces per face, a vertex per edge, every edge half of an old one, old valences kept and every new
// vertex of valence 6; on a torus (genus 1) and on an icosphere with one face removed (a border; new border
// vertices have valence 4).
TEST(MidpointSubdivision, HalvesEveryEdgeAndKeepsTheSurfaceType) {
  for (TriMesh mesh : {make_torus({10.0, 4.0, 0.0}), make_icosphere({10.0, 2})}) {
    const bool with_border = mesh.n_faces() == make_icosphere({10.0, 2}).n_faces();
    if (with_border) mesh.delete_face(*mesh.faces().begin(), true), mesh.garbage_collection();
    const TriMesh before = mesh;
    const Topology type = topology(mesh);
    const EdgeStats edges = edge_stats(mesh);
    ASSERT_TRUE(midpoint_subdivision(mesh));
    EXPECT_EQ(mesh.n_faces(), 4 * before.n_faces());
    EXPECT_EQ(mesh.n_vertices(), before.n_vertices() + before.n_edges());
    EXPECT_TRUE(topology(mesh).same_type(type));
    const EdgeStats halved = edge_stats(mesh);
    EXPECT_NEAR(halved.min, 0.5 * edges.min, 1e-12);
    EXPECT_NEAR(halved.max, 0.5 * edges.max, 1e-12);
    // The result is in spatial memory order: old vertices are found by their (unchanged) positions.
    std::map<std::array<double, 3>, unsigned> old_valence;
    for (auto v : before.vertices()) {
      const Vec3& p = before.point(v);
      old_valence[{p[0], p[1], p[2]}] = before.valence(v);
    }
    std::size_t old_found = 0;
    for (auto v : mesh.vertices()) {
      const Vec3& p = mesh.point(v);
      const auto it = old_valence.find({p[0], p[1], p[2]});
      if (it != old_valence.end()) {
        ++old_found;
        EXPECT_EQ(mesh.valence(v), it->second) << "old vertex at " << p;
      } else {
        EXPECT_EQ(mesh.valence(v), mesh.is_boundary(v) ? 4u : 6u) << "new vertex at " << p;
      }
    }
    EXPECT_EQ(old_found, before.n_vertices());
  }
}

// Springs after a subdivision: an icosphere stretched to an ellipsoid and then subdivided keeps the coarse
// triangles' shapes in each patch of four; springs of the mean edge even the edges out, a border (one face
// removed) stays where it was, and the result is the same for the same input.
TEST(SpringRelaxation, EvensOutTheEdgesOfASubdividedMeshAndKeepsItsBorder) {
  TriMesh mesh = test::stretched(make_icosphere({10.0, 2}), 0, 1.8);
  mesh.delete_face(*mesh.faces().begin(), true);
  mesh.garbage_collection();
  ASSERT_TRUE(midpoint_subdivision(mesh));
  const TriMesh before = mesh;
  const EdgeStats edges = edge_stats(mesh);
  spring_relaxation(mesh, edges.mean, 10);
  const EdgeStats after = edge_stats(mesh);
  EXPECT_LT(after.std, 0.95 * edges.std);
  EXPECT_LT(after.max / after.min, edges.max / edges.min);
  std::size_t border = 0;
  for (auto w : mesh.vertices())
    if (mesh.is_boundary(w)) {
      ++border;
      EXPECT_EQ(mesh.point(w), before.point(w));
    }
  EXPECT_GT(border, 0u);
  TriMesh again = before;
  spring_relaxation(again, edges.mean, 10);
  for (auto w : mesh.vertices()) EXPECT_EQ(mesh.point(w), again.point(w));
}

// A torus of mean edge 1.5 remeshed into [0.6, 0.9] with one coarse level: the coarse level converges at
// [1.2, 1.8], the subdivided mesh is finished at [0.6, 0.9] with every edge inside, the genus kept, and more
// regular vertices than the direct remesh (the subdivision adds only valence-6 vertices).
TEST(CoarseToFine, EveryEdgeInsideAndMoreRegularThanDirect) {
  const TriMesh input = scaled(make_torus({10.0, 4.0, 0.0}), 1.5);
  RemeshSettings settings;
  settings.emin = 0.6;
  settings.emax = 0.9;
  settings.fit_surface = settings.snap_features = false;
  TriMesh direct = input, staged = input;
  const RemeshResult d = remesh(direct, settings);
  settings.coarse_levels = 1;
  std::vector<int> levels;
  settings.on_iteration = [&](const IterationLog& l) { levels.push_back(l.level); };
  const RemeshResult c = remesh(staged, settings);
  ASSERT_TRUE(d.converged);
  ASSERT_TRUE(c.converged);
  EXPECT_EQ(c.coarse_levels, 1);
  EXPECT_GT(c.coarse_iterations, 0);
  ASSERT_FALSE(levels.empty());
  EXPECT_EQ(levels.front(), 1) << "the coarse level reports first";
  EXPECT_EQ(c.log.size(), static_cast<std::size_t>(c.coarse_iterations + c.iterations));
  const EdgeStats edges = edge_stats(staged, {0.6, 0.9});
  EXPECT_EQ(edges.long_edges + edges.short_edges, 0u);
  EXPECT_GE(edges.min, 0.6);
  EXPECT_LE(edges.max, 0.9);
  EXPECT_TRUE(topology(staged).same_type(topology(input)));
  EXPECT_GT(c.percent_regular, d.percent_regular + 2.0);
  // About as many faces as the direct remesh (the same interval on the same surface).
  EXPECT_NEAR(static_cast<double>(staged.n_faces()), static_cast<double>(direct.n_faces()),
              0.15 * static_cast<double>(direct.n_faces()));
}

// An input with every edge inside already (a geodesic sphere whose edges fit the interval) is left as it is:
// no coarse level, no iteration.
TEST(CoarseToFine, AnInputAlreadyInsideIsLeftAlone) {
  TriMesh mesh = make_geodesic_sphere({10.0, 4, false});
  const EdgeStats edges = edge_stats(mesh);
  RemeshSettings settings;
  settings.emin = 0.95 * edges.min;
  settings.emax = 1.05 * edges.max;
  settings.coarse_levels = 2;
  settings.fit_surface = settings.snap_features = false;
  const std::size_t faces = mesh.n_faces();
  const RemeshResult r = remesh(mesh, settings);
  EXPECT_EQ(r.coarse_levels, 0);
  EXPECT_EQ(r.coarse_iterations, 0);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(mesh.n_faces(), faces);
}

// A coarse level that cannot converge (at four times the interval about two edges would go around the tube of
// this torus, circumference 3.8) is given up and the level below starts from the input: every edge inside, the
// genus kept, fewer coarse levels counted than asked for.
TEST(CoarseToFine, FallsBackWhenTheCoarseLevelCannotConverge) {
  const TriMesh input = make_torus({4.0, 0.6, 0.3});
  RemeshSettings settings;
  settings.emin = 0.4;
  settings.emax = 0.6;
  settings.coarse_levels = 2;
  settings.fit_surface = settings.snap_features = false;
  TriMesh mesh = input;
  const RemeshResult r = remesh(mesh, settings);
  EXPECT_LT(r.coarse_levels, 2);
  EXPECT_GT(r.coarse_iterations, 0) << "a coarse level was tried";
  EXPECT_TRUE(r.converged);
  const EdgeStats edges = edge_stats(mesh, {0.4, 0.6});
  EXPECT_EQ(edges.long_edges + edges.short_edges, 0u);
  EXPECT_TRUE(topology(mesh).same_type(topology(input)));
}

}  // namespace
}  // namespace carbonmesh
