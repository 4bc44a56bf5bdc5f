// SmallLU (remesh/src/small_lu.hpp) against Eigen's PartialPivLU on the dynamic fixed-capacity matrices the Floater
// parametrization used before: the same solution bit for bit, on Floater-like systems (unit diagonal, negative
// convex weights) and on general ones that need row swaps, for every size up to SmallLU::kMax.
#include <random>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "small_lu.hpp"
#include "test_same_bits.hpp"

namespace {

using carbonmesh::SmallLU;
using carbonmesh::testing::same_bits;
using Dense = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 40, 40>;
using Rhs = Eigen::Matrix<double, Eigen::Dynamic, 2, 0, 40, 2>;

// a x = b solved by SmallLU.
Rhs small_lu_solution(const Dense& a, const Rhs& b) {
  const int n = static_cast<int>(a.rows());
  SmallLU lu;
  lu.reset(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) lu.a[i][j] = a(i, j);
    lu.b[i][0] = b(i, 0), lu.b[i][1] = b(i, 1);
  }
  lu.solve(n);
  Rhs x(n, 2);
  for (int i = 0; i < n; ++i) x(i, 0) = lu.b[i][0], x(i, 1) = lu.b[i][1];
  return x;
}

// Solves a x = b both ways; true if the solutions have the same bits.
bool same_solution(const Dense& a, const Rhs& b) {
  const Rhs eigen = Eigen::PartialPivLU<Dense>(a).solve(b);
  return same_bits(small_lu_solution(a, b), eigen);
}

TEST(SmallLU, SolvesBitForBitAsEigensPartialPivLU) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> g(-1.0, 1.0), w(0.05, 1.0);
  int compared = 0, swapped = 0;
  for (int n = 1; n <= SmallLU::kMax; ++n)
    for (int trial = 0; trial < 50; ++trial) {
      Dense a(n, n);
      Rhs b(n, 2);
      if (trial % 2 == 0) {  // Floater: U_i - sum_k lambda_ik U_k, each row's weights summing to at most 1
        a.setZero();
        for (int i = 0; i < n; ++i) {
          a(i, i) = 1.0;
          double total = 0;
          for (int j = 0; j < n; ++j)
            if (j != i && rng() % 3 == 0) total += a(i, j) = -w(rng);
          for (int j = 0; j < n; ++j)
            if (j != i && total < 0) a(i, j) *= 0.9 / -total;
        }
      } else {  // general: partial pivoting swaps rows
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) a(i, j) = g(rng);
        swapped += Eigen::PartialPivLU<Dense>(a).permutationP().indices() !=
                   Eigen::VectorXi::LinSpaced(n, 0, n - 1).cast<int>();
      }
      for (int i = 0; i < n; ++i) b(i, 0) = 10 * g(rng), b(i, 1) = 10 * g(rng);
      EXPECT_TRUE(same_solution(a, b)) << n << " unknowns, trial " << trial;
      ++compared;
    }
  EXPECT_EQ(compared, 50 * SmallLU::kMax);
  EXPECT_GT(swapped, 250);  // the pivoting is exercised
}

TEST(SmallLU, ASingularSystemGivesANonFiniteSolutionAsEigens) {
  Dense a(3, 3);
  a << 1, 2, 3, 2, 4, 6, 0, 1, 1;  // rank 2
  Rhs b(3, 2);
  b << 1, 0, 0, 1, 1, 1;
  const Rhs eigen = Eigen::PartialPivLU<Dense>(a).solve(b);
  const bool finite = small_lu_solution(a, b).allFinite();
  EXPECT_EQ(finite, eigen.allFinite());
  EXPECT_FALSE(finite);
}

}  // namespace
