// llt_in_place() and llt_solve() (remesh/src/dense_llt.hpp) against Eigen's LLT<MatrixXd>: the same factor and the
// same solution bit for bit on damped normal equations of 1 to 48 unknowns, and the same verdict where a pivot is
// not positive.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "dense_llt.hpp"
#include "test_same_bits.hpp"

namespace {

using carbonmesh::llt_in_place;
using carbonmesh::llt_solve;
using carbonmesh::testing::same_bits;

// J^T J of random terms joining 2x2 blocks (as the nonlinear optimizer's), damped as it damps.
Eigen::MatrixXd damped_normal_matrix(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  const int blocks = (n + 1) / 2;
  for (int t = 0; t < 3 * blocks; ++t) {
    const auto pick = [&] { return static_cast<int>(rng() % static_cast<unsigned>(blocks)); };
    const int p = pick(), q = pick();
    Eigen::VectorXd row = Eigen::VectorXd::Zero(n);
    for (int k : {2 * p, 2 * p + 1, 2 * q, 2 * q + 1})
      if (k < n) row[k] = g(rng);
    a += (1.0 + 0.5 * g(rng)) * row * row.transpose();
  }
  const double mu = std::pow(10.0, 3 * g(rng));
  for (int i = 0; i < n; ++i) a(i, i) += mu * (a(i, i) + 1e-12 * 3.25);
  return a;
}

TEST(DenseLLT, FactorsAndSolvesBitForBitAsEigensLLT) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  int compared = 0;
  for (int n = 1; n <= 48; ++n)
    for (int trial = 0; trial < 12; ++trial) {
      const Eigen::MatrixXd a = damped_normal_matrix(n, rng);
      Eigen::VectorXd b(n);
      for (int i = 0; i < n; ++i) b[i] = g(rng);
      const Eigen::LLT<Eigen::MatrixXd> eigen(a);
      ASSERT_EQ(eigen.info(), Eigen::Success) << "n " << n;
      Eigen::MatrixXd l = a;
      ASSERT_TRUE(llt_in_place(l)) << "n " << n;
      const Eigen::MatrixXd expected_l = eigen.matrixL();
      const Eigen::MatrixXd got_l = l.triangularView<Eigen::Lower>();
      EXPECT_TRUE(same_bits(got_l, expected_l)) << "n " << n << " trial " << trial;
      const Eigen::VectorXd expected = eigen.solve(b);
      Eigen::VectorXd x;
      llt_solve(l, b, x);
      EXPECT_TRUE(same_bits(x, expected)) << "n " << n << " trial " << trial;
      ++compared;
    }
  EXPECT_EQ(compared, 48 * 12);
}

TEST(DenseLLT, ReportsANonPositivePivotAsEigenDoes) {
  for (int n : {5, 40}) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
    a(n - 2, n - 2) = 0.25;
    a(n - 1, n - 2) = a(n - 2, n - 1) = 0.5;  // the last 2x2 block is singular
    a(n - 1, n - 1) = 1.0;
    const Eigen::LLT<Eigen::MatrixXd> eigen(a);
    EXPECT_NE(eigen.info(), Eigen::Success) << "n " << n;
    Eigen::MatrixXd l = a;
    EXPECT_FALSE(llt_in_place(l)) << "n " << n;
  }
}

}  // namespace
