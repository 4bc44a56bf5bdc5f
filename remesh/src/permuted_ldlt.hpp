// A sparse LDL^T for a symmetric pattern whose values change between factorizations (the damped normal equations
// of Levenberg-Marquardt). The arithmetic is that of Eigen's SimplicialLDLT<SparseMatrix<double>> (lower triangle,
// AMD ordering), so the solutions are the same bit for bit; what depends on the pattern only is done once, in
// analyze():
//  - the fill-reducing permutation is applied to the pattern once (SimplicialLDLT permutes the whole matrix on every
//    factorize()), and factorize() only gathers the values into place;
//  - the elimination tree, the structure of L and the nonzero pattern of each row of L, in the order Eigen 3.4's
//    factorize_preordered() finds it by walking the tree on every factorization, are kept; factorize() does that
//    routine's arithmetic in that order, and solve() that of SimplicialLDLT::solve() (L, then D^-1, then L^T).
#pragma once

#include <cstddef>
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
    Matrix permuted(a.rows(), a.cols());
    permuted.selfadjointView<Eigen::Upper>() = index.selfadjointView<Eigen::Lower>().twistedBy(p_);
    permuted.makeCompressed();
    std::vector<char> on_diagonal(static_cast<std::size_t>(a.nonZeros()), 0);
    for (Eigen::Index j = 0; j < a.outerSize(); ++j)
      for (int k = a.outerIndexPtr()[j]; k < a.outerIndexPtr()[j + 1]; ++k)
        on_diagonal[static_cast<std::size_t>(k)] = a.innerIndexPtr()[k] == j;
    source_.resize(static_cast<std::size_t>(permuted.nonZeros()));
    diagonal_.resize(source_.size());
    values_.resize(source_.size());
    for (std::size_t k = 0; k < source_.size(); ++k) {
      source_[k] = static_cast<int>(permuted.valuePtr()[k]);
      diagonal_[k] = on_diagonal[static_cast<std::size_t>(source_[k])];
    }
    symbolic(permuted);
  }

  // Factorizes a + mu (diag(a) + floor I), `a` with the pattern given to analyze(). False on a numerical failure
  // (a zero pivot, where SimplicialLDLT reports NumericalIssue).
  bool factorize(const Matrix& a, double mu, double floor) {
    const double* in = a.valuePtr();
    for (std::size_t k = 0; k < source_.size(); ++k) {
      const double x = in[source_[k]];
      values_[k] = diagonal_[k] ? x + mu * (x + floor) : x;
    }
    // SimplicialCholeskyBase::factorize_preordered<true> with its patterns known (its shift: scale 1, offset 0).
    const std::size_t n = d_.size();
    y_.assign(n, 0.0);  // (each row leaves the entries it used at zero; a failed factorization may not)
    for (std::size_t k = 0; k < n; ++k) {
      for (int s = scatter_begin_[k]; s < scatter_begin_[k + 1]; ++s)
        y_[static_cast<std::size_t>(scatter_row_[static_cast<std::size_t>(s)])] +=
            values_[static_cast<std::size_t>(scatter_entry_[static_cast<std::size_t>(s)])];
      double d = y_[k] * 1.0 + 0.0;
      y_[k] = 0.0;
      for (int t = row_begin_[k]; t < row_begin_[k + 1]; ++t) {
        const auto i = static_cast<std::size_t>(row_column_[static_cast<std::size_t>(t)]);
        const double yi = y_[i];
        y_[i] = 0.0;
        const double l_ki = yi / d_[i];
        const int p2 = row_slot_[static_cast<std::size_t>(t)];
        for (int p = column_begin_[i]; p < p2; ++p)
          y_[static_cast<std::size_t>(l_row_[static_cast<std::size_t>(p)])] -= l_[static_cast<std::size_t>(p)] * yi;
        d -= l_ki * yi;
        l_[static_cast<std::size_t>(p2)] = l_ki;
      }
      d_[k] = d;
      if (d == 0.0) return false;
    }
    return true;
  }

  // x = the solution of the factorized system for b.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    work_ = p_ * b;
    double* w = work_.data();
    const std::size_t n = d_.size();
    // L (unit lower, column-major), as Eigen's sparse_solve_triangular_selector<Lower, ColMajor>.
    for (std::size_t i = 0; i < n; ++i) {
      const double t = w[i];
      if (t != 0.0)
        for (int p = column_begin_[i]; p < column_begin_[i + 1]; ++p)
          w[l_row_[static_cast<std::size_t>(p)]] -= t * l_[static_cast<std::size_t>(p)];
    }
    // D^-1 (the inverse of the diagonal times the vector).
    for (std::size_t i = 0; i < n; ++i) w[i] = (1.0 / d_[i]) * w[i];
    // L^T (unit upper, row-major), as sparse_solve_triangular_selector<Upper, RowMajor>.
    for (std::size_t i = n; i-- > 0;) {
      double t = w[i];
      for (int p = column_begin_[i]; p < column_begin_[i + 1]; ++p)
        t -= l_[static_cast<std::size_t>(p)] * w[l_row_[static_cast<std::size_t>(p)]];
      w[i] = t;
    }
    x = pinv_ * work_;
  }

 private:
  // The elimination tree and the structure of L as SimplicialCholeskyBase::analyzePattern_preordered() computes
  // them, and each row's scatter of the matrix and pattern of L as factorize_preordered() walks them.
  void symbolic(const Matrix& ap) {
    const int n = static_cast<int>(ap.rows());
    const auto un = static_cast<std::size_t>(n);
    std::vector<int> parent(un, -1), count(un, 0), tags(un, -1);
    for (int k = 0; k < n; ++k) {
      tags[static_cast<std::size_t>(k)] = k;
      for (Matrix::InnerIterator it(ap, k); it; ++it) {
        int i = static_cast<int>(it.index());
        if (i >= k) continue;
        for (; tags[static_cast<std::size_t>(i)] != k; i = parent[static_cast<std::size_t>(i)]) {
          if (parent[static_cast<std::size_t>(i)] == -1) parent[static_cast<std::size_t>(i)] = k;
          ++count[static_cast<std::size_t>(i)];
          tags[static_cast<std::size_t>(i)] = k;
        }
      }
    }
    column_begin_.assign(un + 1, 0);
    for (std::size_t k = 0; k < un; ++k) column_begin_[k + 1] = column_begin_[k] + count[k];
    l_row_.assign(static_cast<std::size_t>(column_begin_[un]), 0);
    l_.assign(l_row_.size(), 0.0);
    d_.assign(un, 0.0);
    scatter_begin_.assign(un + 1, 0);
    scatter_entry_.clear();
    scatter_row_.clear();
    row_begin_.assign(un + 1, 0);
    row_column_.clear();
    row_slot_.clear();
    std::vector<int> filled(un, 0), path(un), stack(un);
    std::fill(tags.begin(), tags.end(), -1);
    const double* base = ap.valuePtr();
    for (int k = 0; k < n; ++k) {
      tags[static_cast<std::size_t>(k)] = k;
      int top = n;
      for (Matrix::InnerIterator it(ap, k); it; ++it) {
        int i = static_cast<int>(it.index());
        if (i > k) continue;
        scatter_entry_.push_back(static_cast<int>(&it.value() - base));
        scatter_row_.push_back(i);
        int len = 0;
        for (; tags[static_cast<std::size_t>(i)] != k; i = parent[static_cast<std::size_t>(i)]) {
          path[static_cast<std::size_t>(len++)] = i;
          tags[static_cast<std::size_t>(i)] = k;
        }
        while (len > 0) stack[static_cast<std::size_t>(--top)] = path[static_cast<std::size_t>(--len)];
      }
      for (; top < n; ++top) {
        const auto i = static_cast<std::size_t>(stack[static_cast<std::size_t>(top)]);
        const int slot = column_begin_[i] + filled[i]++;
        l_row_[static_cast<std::size_t>(slot)] = k;
        row_column_.push_back(static_cast<int>(i));
        row_slot_.push_back(slot);
      }
      scatter_begin_[static_cast<std::size_t>(k) + 1] = static_cast<int>(scatter_entry_.size());
      row_begin_[static_cast<std::size_t>(k) + 1] = static_cast<int>(row_column_.size());
    }
  }

  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p_, pinv_;
  std::vector<int> source_;     // entry of `a` that each entry of the permuted upper triangle takes its value from
  std::vector<char> diagonal_;  // that entry is on the diagonal (damped)
  std::vector<double> values_;  // the permuted upper triangle's values
  // Row k of the factorization: the entries it scatters (scatter_entry_ into values_, at rows scatter_row_) and the
  // columns i of its pattern (row_column_, in Eigen's order) with the slot of L(k, i) (row_slot_).
  std::vector<int> scatter_begin_, scatter_entry_, scatter_row_;
  std::vector<int> row_begin_, row_column_, row_slot_;
  std::vector<int> column_begin_, l_row_;  // L's strictly lower part by column (rows increasing)
  std::vector<double> l_, d_, y_;
  Eigen::VectorXd work_;
};

}  // namespace carbonmesh
