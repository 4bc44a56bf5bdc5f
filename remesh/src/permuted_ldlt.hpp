// A sparse LDL^T for a symmetric pattern whose values change between factorizations (the damped normal equations
// of Levenberg-Marquardt). Eigen's SimplicialLDLT with its AMD ordering permutes the whole matrix on every
// factorize(); here the permutation is applied to the pattern once, in analyze(), and factorize() only gathers the
// values into place. The arithmetic is that of SimplicialLDLT<SparseMatrix<double>> (lower triangle, AMD ordering),
// so the solutions are the same bit for bit.
#pragma once

#include <vector>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

namespace carbonmesh {

class PermutedLDLT {
 public:
  using Matrix = Eigen::SparseMatrix<double>;

  // The pattern of `a` (compressed, square; the lower triangle and the diagonal are read).
  void analyze(const Matrix& a) {
    // The fill-reducing permutation as SimplicialLDLT's analyzePattern() computes it (AMD of the symmetric matrix).
    {
      Matrix symmetric;
      symmetric = a.selfadjointView<Eigen::Lower>();
      Eigen::AMDOrdering<int>()(symmetric, pinv_);
    }
    p_ = pinv_.inverse();
    // The permuted upper triangle Eigen's factorize() builds, with each value the index of its source entry.
    Matrix index = a;
    for (Eigen::Index k = 0; k < index.nonZeros(); ++k) index.valuePtr()[k] = static_cast<double>(k);
    permuted_.resize(a.rows(), a.cols());
    permuted_.selfadjointView<Eigen::Upper>() = index.selfadjointView<Eigen::Lower>().twistedBy(p_);
    std::vector<char> on_diagonal(static_cast<std::size_t>(a.nonZeros()), 0);
    for (Eigen::Index j = 0; j < a.outerSize(); ++j)
      for (int k = a.outerIndexPtr()[j]; k < a.outerIndexPtr()[j + 1]; ++k)
        on_diagonal[static_cast<std::size_t>(k)] = a.innerIndexPtr()[k] == j;
    source_.resize(static_cast<std::size_t>(permuted_.nonZeros()));
    diagonal_.resize(source_.size());
    for (std::size_t k = 0; k < source_.size(); ++k) {
      source_[k] = static_cast<int>(permuted_.valuePtr()[k]);
      diagonal_[k] = on_diagonal[static_cast<std::size_t>(source_[k])];
    }
    solver_.analyzePattern(permuted_);
  }

  // Factorizes a + mu (diag(a) + floor I), `a` with the pattern given to analyze(). False on a numerical failure.
  bool factorize(const Matrix& a, double mu, double floor) {
    const double* in = a.valuePtr();
    double* out = permuted_.valuePtr();
    for (std::size_t k = 0; k < source_.size(); ++k) {
      const double x = in[source_[k]];
      out[k] = diagonal_[k] ? x + mu * (x + floor) : x;
    }
    solver_.factorize(permuted_);
    return solver_.info() == Eigen::Success;
  }

  // x = the solution of the factorized system for b.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    work_ = p_ * b;
    work_ = solver_.solve(work_);
    x = pinv_ * work_;
  }

 private:
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p_, pinv_;
  Matrix permuted_;
  std::vector<int> source_;     // entry of `a` that each entry of permuted_ takes its value from
  std::vector<char> diagonal_;  // that entry is on the diagonal (damped)
  Eigen::VectorXd work_;
  Eigen::SimplicialLDLT<Matrix, Eigen::Upper, Eigen::NaturalOrdering<int>> solver_;
};

}  // namespace carbonmesh
