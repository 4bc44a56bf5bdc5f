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

// `input` turned and shifted as tools/bench/remesh_motions.py moves it (its products summed in its order, so the
// coordinates are those of the file it writes).
void move_rigidly(TriMesh& input, const double (&rotation)[3][3], const double (&shift)[3]) {
  for (auto v : input.vertices()) {
    const Vec3 p = input.point(v);
    Vec3 q;
    for (int i = 0; i < 3; ++i) {
      double x = rotation[i][0] * p[0];
      x += rotation[i][1] * p[1];
      x += rotation[i][2] * p[2];
      q[i] = x + shift[i];
    }
    input.set_point(v, q);
  }
}

// A seed-protocol model moved rigidly, remeshed with the default settings, and its distance to the moved input.
struct MovedRun {
  TriMesh input, mesh;
  RemeshResult result;
  EdgeStats edges;
  HausdorffResult distance;
};

MovedRun remesh_moved(const std::filesystem::path& path, const double (&rotation)[3][3], const double (&shift)[3]) {
  MovedRun run;
  run.input = load_mesh(path);
  move_rigidly(run.input, rotation, shift);
  run.mesh = run.input;
  run.result = remesh(run.mesh, RemeshSettings{});
  run.edges = edge_stats(run.mesh, {1.2, 1.8});
  run.distance = hausdorff_distance(run.mesh, run.input);
  return run;
}

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

// The same surface in other coordinates meets the same bound: armadillo turned and shifted by the first rigid motion of
// tools/bench/remesh_motions.py (seed 1). A face across a saddle, with edges 1.798 and 1.202 long and a corner the snap
// put on an input vertex, stayed 0.5497 from the input (bound 0.5498) until the face caps (cap_far_faces) gave it a
// vertex of its own: 0.4637 (since the trees' closest point of session 44: 0.4673, and 0.5519 without the face caps).
TEST(SeedProtocol, ArmadilloUnderARigidMotionStaysWithinHalfAnEdgeOfItsInput) {
  const auto path = seed_model("armadillo");
  SKIP_WITHOUT(path);
  constexpr double rotation[3][3] = {{0.1615454267205496, -0.7910735180722196, 0.5900048848191999},
                                     {-0.8373576619467521, -0.4262580603619939, -0.3422516792588457},
                                     {0.5222405777845536, -0.43875591731767305, -0.7312715117751978}};
  constexpr double shift[3] = {-4.898619485211566, -0.09129825816118142, -1.010178704225238};
  const MovedRun run = remesh_moved(path, rotation, shift);
  EXPECT_EQ(run.edges.long_edges + run.edges.short_edges, 0u);
  EXPECT_TRUE(topology(run.input).same_type(topology(run.mesh)));
  EXPECT_LE(run.distance.rms, 0.035);
  EXPECT_TRUE(run.distance.bracketed);
  EXPECT_LE(run.distance.max_bound, 0.5) << "capped faces: " << run.result.capped_faces;
}

// Bunny turned and shifted by the 14th rigid motion of tools/bench/remesh_motions.py (seed 14): the region the minimax
// fit leaves farthest (0.5312 from the input) has its vertices held by edges at the ends of the interval; its second
// search, with the neighbours of those vertices movable too, brings it to 0.4924.
TEST(SeedProtocol, BunnyUnderARigidMotionStaysWithinHalfAnEdgeThroughTheWiderMinimaxSearch) {
  const auto path = seed_model("bunny");
  SKIP_WITHOUT(path);
  constexpr double rotation[3][3] = {{0.7036560768884348, 0.40052310434229377, 0.5868980902558717},
                                     {0.6019621275563524, -0.7748717057662471, -0.19291302856659845},
                                     {0.3775045992379523, 0.4890348479310238, -0.7863429245966891}};
  constexpr double shift[3] = {8.807047791322358, -4.577695468793537, -4.884489731339217};
  const MovedRun run = remesh_moved(path, rotation, shift);
  EXPECT_EQ(run.edges.long_edges + run.edges.short_edges, 0u);
  EXPECT_GT(run.result.minimax_wide_moves, 0u);
  EXPECT_LE(run.distance.rms, 0.035);
  EXPECT_TRUE(run.distance.bracketed);
  EXPECT_LE(run.distance.max_bound, 0.5) << "minimax fit " << run.result.minimax_max_before << " -> "
                                         << run.result.minimax_max_after;
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
