// The remesher on real models: issue 4's protocol on two of ../shared/models/seed-protocol (mean edge 2.25, remeshed
// into [1.2, 1.8] with the default settings, which are the dissertation's parameters 150, 2, 2, 0, 0.5, mean value).
// Fertility (genus 4, closed) and camelhead (one border, a slit narrower than emin at its mouth) are the two that the
// built-in shapes of test_remesher do not stand for. Skipped, with the path in the message, where the models are
// missing (the repository ships no model files).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "carbonmesh/remesh/hausdorff.hpp"
#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesher.hpp"
#include "test_paths.hpp"

namespace carbonmesh {
namespace {

// Where the seed-protocol model `name` is (the tests skip when it is not there).
std::filesystem::path seed_model(const std::string& name) {
  return std::filesystem::path(CARBONMESH_SHARED_DIR) / "models" / "seed-protocol" / (name + ".off");
}

#define SKIP_WITHOUT(path)                                                                                   \
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared model not found: " << (path).string()          \
                                                   << " (set CARBONMESH_SHARED_DIR at configure time)"

TEST(SeedProtocol, FertilityEndsWithEveryEdgeInsideItsGenusAndTheIssuesRegularityAndDistances) {
  const auto path = seed_model("fertility");
  SKIP_WITHOUT(path);
  const TriMesh input = load_mesh(path);
  TriMesh mesh = input;
  const RemeshResult result = remesh(mesh, RemeshSettings{});
  const EdgeStats edges = edge_stats(mesh, {1.2, 1.8});
  EXPECT_EQ(edges.long_edges, 0u);
  EXPECT_EQ(edges.short_edges, 0u);
  EXPECT_TRUE(result.converged);
  const Topology before = topology(input), after = topology(mesh);
  EXPECT_EQ(before.genus, 4);
  EXPECT_TRUE(before.same_type(after)) << "genus " << after.genus << ", components " << after.components
                                       << ", borders " << after.boundary_loops;
  const ValenceStats valence = valence_stats(mesh);
  EXPECT_GE(valence.percent_regular, 90.0);  // issue 4: >= 90% regular on every closed model
  EXPECT_EQ(valence.percent_eval_gt1, 0.0);  // and none off its ideal valence by more than one
  // Issue 4's bounds on bunny, fertility and armadillo: RMS <= 0.035, and the largest distance over every point
  // of both surfaces (bracketed; the certified bound) <= 0.5 since the minimax fit (0.5993 without it).
  const HausdorffResult distance = hausdorff_distance(mesh, input);
  EXPECT_LE(distance.rms, 0.035);
  EXPECT_TRUE(distance.bracketed);
  EXPECT_LE(distance.max_bound, 0.5);
}

TEST(SeedProtocol, CamelheadKeepsItsBorderAndAtMostTenEdgesOutside) {
  const auto path = seed_model("camelhead");
  SKIP_WITHOUT(path);
  const TriMesh input = load_mesh(path);
  TriMesh mesh = input;
  remesh(mesh, RemeshSettings{});
  const EdgeStats edges = edge_stats(mesh, {1.2, 1.8});
  EXPECT_LE(edges.long_edges + edges.short_edges, 10u);  // issue 4's allowance for the bordered model
  const Topology before = topology(input), after = topology(mesh);
  EXPECT_EQ(before.boundary_loops, 1u);
  EXPECT_TRUE(before.same_type(after)) << "genus " << after.genus << ", components " << after.components
                                       << ", borders " << after.boundary_loops;
  EXPECT_GE(valence_stats(mesh).percent_regular, 90.0);
}

}  // namespace
}  // namespace carbonmesh
