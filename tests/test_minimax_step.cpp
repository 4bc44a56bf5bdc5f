// minimax_step (remesh/src/minimax_step.hpp), the linear program of the minimax fit's joint moves: the largest
// linearised distance made least within the box and the length bounds, on small programs whose optimum is known or can
// be bracketed by trying every point of a grid over the box.
#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "minimax_step.hpp"

namespace {

using carbonmesh::LinearRow;
using carbonmesh::minimax_step;
using carbonmesh::Vec3;

LinearRow row(double value, std::vector<std::pair<std::size_t, Vec3>> terms) {
  LinearRow r;
  r.value = value;
  r.terms = std::move(terms);
  return r;
}

double predicted(const LinearRow& r, const std::vector<Vec3>& d) {
  double x = r.value;
  for (const auto& [v, g] : r.terms) x += OpenMesh::dot(g, d[v]);
  return x;
}

double largest(const std::vector<LinearRow>& rows, const std::vector<Vec3>& d) {
  double t = -1e300;
  for (const auto& r : rows) t = std::max(t, predicted(r, d));
  return t;
}

TEST(MinimaxStep, BalancesTwoOpposedDistancesWithinTheBox) {
  // 1 + x and 0.5 - x: least largest at x = -0.25 (0.75), inside a box of 0.5; the box of 0.1 stops at x = -0.1.
  const std::vector<LinearRow> distances{row(1.0, {{0, Vec3(1, 0, 0)}}), row(0.5, {{0, Vec3(-1, 0, 0)}})};
  const auto wide = minimax_step(distances, {}, 0, 10, 1, 0.5);
  ASSERT_TRUE(wide.has_value());
  EXPECT_NEAR((*wide)[0][0], -0.25, 1e-12);
  EXPECT_NEAR(largest(distances, *wide), 0.75, 1e-12);
  const auto narrow = minimax_step(distances, {}, 0, 10, 1, 0.1);
  ASSERT_TRUE(narrow.has_value());
  EXPECT_NEAR((*narrow)[0][0], -0.1, 1e-12);
  for (int c = 1; c < 3; ++c) EXPECT_LE(std::abs((*narrow)[0][c]), 0.1 + 1e-12);
}

TEST(MinimaxStep, KeepsLengthsWithinTheirBounds) {
  // The distance falls as vertex 0 moves along x, which lengthens an edge of 1.0 to a vertex that stays and shortens
  // an edge of 1.3 to vertex 1 (which moves too): the length bounds [1.0, 1.05] stop it.
  const std::vector<LinearRow> distances{row(0.6, {{0, Vec3(-1, 0, 0)}})};
  const std::vector<LinearRow> lengths{row(1.0, {{0, Vec3(1, 0, 0)}}),
                                       row(1.3, {{0, Vec3(-1, 0, 0)}, {1, Vec3(1, 0, 0)}})};
  const auto d = minimax_step(distances, lengths, 1.0, 1.5, 2, 0.2);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR((*d)[0][0], 0.2, 1e-12);  // within [1.0, 1.5] the box stops it (lengths 1.2 and 1.1 + d_1)
  const auto tight = minimax_step(distances, lengths, 1.0, 1.05, 2, 0.2);
  ASSERT_TRUE(tight.has_value());
  EXPECT_NEAR((*tight)[0][0], 0.05, 1e-12);
  for (const auto& r : lengths) {
    EXPECT_GE(predicted(r, *tight), 1.0 - 1e-12);
    EXPECT_LE(predicted(r, *tight), 1.05 + 1e-12);
  }
}

TEST(MinimaxStep, RefusesALengthTheBoxCannotBringInside) {
  // A length of 2.0 with the upper bound 1.8 needs a move of 0.2 along the edge; the box allows 0.1.
  const std::vector<LinearRow> distances{row(0.5, {{0, Vec3(0, 0, 1)}})};
  const std::vector<LinearRow> lengths{row(2.0, {{0, Vec3(1, 0, 0)}})};
  EXPECT_FALSE(minimax_step(distances, lengths, 1.2, 1.8, 1, 0.1).has_value());
  EXPECT_TRUE(minimax_step(distances, lengths, 1.2, 1.8, 1, 0.25).has_value());
}

TEST(MinimaxStep, RefusesARowThatIsNotFinite) {
  // A degenerate face's gradient (NaN) or an infinite distance: no step, rather than a program GLPK solves as given.
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const std::vector<LinearRow> good{row(0.5, {{0, Vec3(0, 0, 1)}})};
  EXPECT_TRUE(minimax_step(good, {}, 1.2, 1.8, 1, 0.1).has_value());
  EXPECT_FALSE(minimax_step({row(0.5, {{0, Vec3(0, nan, 1)}})}, {}, 1.2, 1.8, 1, 0.1).has_value());
  EXPECT_FALSE(minimax_step({row(inf, {{0, Vec3(0, 0, 1)}})}, {}, 1.2, 1.8, 1, 0.1).has_value());
  EXPECT_FALSE(minimax_step(good, {row(1.5, {{0, Vec3(nan, 0, 0)}})}, 1.2, 1.8, 1, 0.1).has_value());
}

TEST(MinimaxStep, NoPointOfTheBoxHasASmallerLargestDistance) {
  // Many rows of one vertex, most far below the largest (the cutting planes start from the few near it): the step's
  // largest prediction is no larger than at any point of a grid over the box, and every row is counted.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), value(0.2, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<LinearRow> distances;
    for (int k = 0; k < 200; ++k) {
      Vec3 g(u(rng), u(rng), u(rng));
      distances.push_back(row(value(rng), {{0, g.normalized()}}));
    }
    const double radius = 0.3;
    const auto d = minimax_step(distances, {}, 0, 10, 1, radius);
    ASSERT_TRUE(d.has_value());
    for (int c = 0; c < 3; ++c) EXPECT_LE(std::abs((*d)[0][c]), radius + 1e-12);
    const double best = largest(distances, *d);
    constexpr int kSteps = 12;
    for (int i = 0; i <= kSteps; ++i)
      for (int j = 0; j <= kSteps; ++j)
        for (int k = 0; k <= kSteps; ++k) {
          const Vec3 p(-radius + 2 * radius * i / kSteps, -radius + 2 * radius * j / kSteps,
                       -radius + 2 * radius * k / kSteps);
          EXPECT_LE(best, largest(distances, {p}) + 1e-9);
        }
  }
}

}  // namespace
