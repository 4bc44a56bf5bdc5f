// PermutedLDLT (remesh/src/permuted_ldlt.hpp) against Eigen's SimplicialLDLT on the damped normal equations of a
// mesh-like pattern: the same solution bit for bit, for several damping factors on one analysis, and the same
// verdict on a zero pivot.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "permuted_ldlt.hpp"
#include "test_same_bits.hpp"

namespace {

using carbonmesh::PermutedLDLT;
using carbonmesh::testing::same_bits;
using Matrix = Eigen::SparseMatrix<double>;

// J^T J of random "edge" terms between 2x2 blocks of a grid of n x n nodes (each node joined to its right, upper
// and upper-right neighbours, as a triangulated grid), with both triangles stored and the upper one rounded
// differently (the lower one is the one read).
Matrix grid_normal_matrix(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> g(-1.0, 1.0);
  const int nodes = n * n, dim = 2 * nodes;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < dim; ++i) t.emplace_back(i, i, 1e-3);
  auto term = [&](int a, int b) {
    const int idx[4] = {2 * a, 2 * a + 1, 2 * b, 2 * b + 1};
    double v[4];
    for (double& x : v) x = g(rng);
    const double w = 1.0 + 0.5 * g(rng);
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q) t.emplace_back(idx[p], idx[q], w * v[p] * v[q] * (p < q ? 1 + 1e-15 : 1.0));
  };
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = y * n + x;
      if (x + 1 < n) term(a, a + 1);
      if (y + 1 < n) term(a, a + n);
      if (x + 1 < n && y + 1 < n) term(a, a + n + 1);
    }
  Matrix m(dim, dim);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

TEST(PermutedLDLT, SolvesBitForBitAsEigensSimplicialLDLT) {
  std::mt19937 rng(7);
  for (int n : {3, 6, 9}) {
    const Matrix jtj = grid_normal_matrix(n, rng);
    Eigen::VectorXd b(jtj.rows());
    std::uniform_real_distribution<double> g(-1.0, 1.0);
    for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = g(rng);
    PermutedLDLT permuted;
    permuted.analyze(jtj);
    Eigen::SimplicialLDLT<Matrix> eigen;
    Matrix h = jtj;
    eigen.analyzePattern(h);
    for (double mu : {1e-3, 0.25, 40.0}) {
      const double floor = 1e-12 * 3.25;
      for (int k = 0; k < h.outerSize(); ++k)
        for (Matrix::InnerIterator it(h, k); it; ++it)
          if (it.row() == it.col()) {
            const double jj = jtj.coeff(it.row(), it.col());
            it.valueRef() = jj + mu * (jj + floor);  // as optimize_region damps
          }
      eigen.factorize(h);
      ASSERT_EQ(eigen.info(), Eigen::Success);
      const Eigen::VectorXd expected = eigen.solve(b);
      ASSERT_TRUE(permuted.factorize(jtj, mu, floor));
      Eigen::VectorXd x;
      permuted.solve(b, x);
      EXPECT_TRUE(same_bits(x, expected)) << "n " << n << " mu " << mu << ": max difference "
                                          << (x - expected).cwiseAbs().maxCoeff();
      // And it solves the damped system.
      EXPECT_LT((h.selfadjointView<Eigen::Lower>() * x - b).norm(), 1e-9 * (1 + b.norm()));
    }
  }
}

// A zero pivot fails in both, and a factorization after the failed one is again Eigen's bit for bit.
TEST(PermutedLDLT, ReportsAZeroPivotAsEigenDoesAndRecovers) {
  std::mt19937 rng(11);
  const Matrix jtj = grid_normal_matrix(4, rng);
  Matrix zero = jtj;
  for (Eigen::Index k = 0; k < zero.nonZeros(); ++k) zero.valuePtr()[k] = 0.0;
  PermutedLDLT permuted;
  permuted.analyze(jtj);
  Eigen::SimplicialLDLT<Matrix> eigen;
  eigen.compute(zero);
  EXPECT_NE(eigen.info(), Eigen::Success);
  EXPECT_FALSE(permuted.factorize(zero, 0.0, 0.0));
  ASSERT_TRUE(permuted.factorize(jtj, 0.0, 0.0));
  eigen.compute(jtj);
  ASSERT_EQ(eigen.info(), Eigen::Success);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(jtj.rows(), -1.0, 1.0);
  Eigen::VectorXd x;
  permuted.solve(b, x);
  EXPECT_TRUE(same_bits(x, eigen.solve(b)));
}

}  // namespace
