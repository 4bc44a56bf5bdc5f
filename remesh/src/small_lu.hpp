// A dense n x n system with two right sides (n <= SmallLU::kMax), solved with the arithmetic of Eigen 3.4's
// PartialPivLU(a).solve(b) on a dynamic matrix, operation for operation, without its machinery: below 17 unknowns
// Eigen factorizes unblocked, but its triangular solves still pack panels for its matrix-product kernel, and on the
// 5-16 unknowns of a Floater system (kl = 2) that took as long as the arithmetic (7 unknowns: 1.8x faster here).
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

namespace carbonmesh {

struct SmallLU {
  static constexpr int kMax = 16;  // Eigen's unblocked bound: larger systems go to Eigen's blocked LU
  double a[kMax][kMax];  // the matrix, row by row, then its L and U (only i, j < n are used)
  double b[kMax][2];     // the right sides, then the solution

  // Zeroes the n x n matrix and the n right sides.
  void reset(int n) {
    for (int i = 0; i < n; ++i) {
      std::fill(a[i], a[i] + n, 0.0);
      b[i][0] = b[i][1] = 0;
    }
  }

  // Factorizes a and overwrites b with the solution. The results equal Eigen's bit for bit (the tests compare).
  // Each n has its own copy of the arithmetic, with n known to the compiler: the same operations in the same order,
  // with less loop control (bunny's low-pass filter solves, one thread: 0.43 -> 0.32 G instructions).
  void solve(int n) { solve_from<1>(n); }

 private:
  template <int n>
  void solve_fixed() {
    int transposition[kMax];
    // Eigen's partial_lu_impl::unblocked_lu: the first largest pivot of the column, the whole rows swapped, the
    // column below divided by it (a division each, as Eigen's), and the rank-one update.
    for (int k = 0; k < n; ++k) {
      int pivot = k;
      double biggest = std::abs(a[k][k]);
      for (int i = k + 1; i < n; ++i)
        if (std::abs(a[i][k]) > biggest) biggest = std::abs(a[i][k]), pivot = i;
      transposition[k] = pivot;
      if (biggest != 0) {
        if (pivot != k) std::swap(a[k], a[pivot]);
        for (int i = k + 1; i < n; ++i) a[i][k] /= a[k][k];
      }
      for (int i = k + 1; i < n; ++i) {  // (row by row; Eigen goes column by column: each entry gets the same update)
        const double l = a[i][k];
        for (int j = k + 1; j < n; ++j) a[i][j] -= a[k][j] * l;
      }
    }
    for (int k = 0; k < n; ++k) std::swap(b[k], b[transposition[k]]);  // b = P b
    // Eigen's triangular_solve_matrix (OnTheLeft): panels of kPanel rows solved one row at a time, and each row
    // beyond a panel reduced by one dot product over the panel, accumulated in panel order from zero (its gebp kernel).
    for (int k1 = 0; k1 < n; k1 += kPanel) {  // L y = P b, L unit lower: panels from the top
      const int width = std::min(kPanel, n - k1);
      for (int i = k1; i < k1 + width; ++i)
        for (int c = 0; c < 2; ++c)
          for (int r = i + 1; r < k1 + width; ++r) b[r][c] -= b[i][c] * a[r][i];
      for (int t = k1 + width; t < n; ++t)
        for (int c = 0; c < 2; ++c) {
          double sum = 0;
          for (int d = k1; d < k1 + width; ++d) sum += a[t][d] * b[d][c];
          b[t][c] -= sum;
        }
    }
    for (int k1 = 0; k1 < n; k1 += kPanel) {  // U x = y: panels from the bottom
      const int width = std::min(kPanel, n - k1), first = n - k1 - width;
      for (int i = n - k1 - 1; i >= first; --i) {
        const double inverse = 1.0 / a[i][i];  // (Eigen multiplies by the reciprocal)
        for (int c = 0; c < 2; ++c) {
          b[i][c] *= inverse;
          for (int r = first; r < i; ++r) b[r][c] -= b[i][c] * a[r][i];
        }
      }
      for (int t = 0; t < first; ++t)
        for (int c = 0; c < 2; ++c) {
          double sum = 0;
          for (int d = first; d < first + width; ++d) sum += a[t][d] * b[d][c];
          b[t][c] -= sum;
        }
    }
  }

  // solve_fixed<n>() for the n given, 1 <= n <= kMax.
  template <int m>
  void solve_from(int n) {
    if (n == m) solve_fixed<m>();
    else if constexpr (m < kMax) solve_from<m + 1>(n);
  }

  // Eigen's SmallPanelWidth: the larger of its kernel's register block sizes (4 for doubles with SSE2).
  static constexpr int kPanel = std::max<int>(Eigen::internal::gebp_traits<double, double>::mr,
                                              Eigen::internal::gebp_traits<double, double>::nr);
};

}  // namespace carbonmesh
