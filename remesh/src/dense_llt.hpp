// The Cholesky factorization and solve of Eigen 3.4's LLT<MatrixXd> (lower triangle) in place, without what
// LLT::compute() adds around it: a copy of the matrix and its L1 norm (for rcond(), which the nonlinear optimizer
// does not ask for). The damped normal equations of a small Levenberg-Marquardt region (at most 48 unknowns) are
// factorized once for every damping a step tries (bunny: 20271 factorizations).
//  - Below 32 unknowns Eigen factorizes with llt_inplace::unblocked(); here its arithmetic runs in its order on plain
//    loops: for column k, the diagonal less the squared norm of row k (summed from its first term), the square root,
//    the column below less the product of the rows below and row k (each row's sum accumulated from zero, as Eigen's
//    matrix-vector kernel does, or from its first term as Eigen's dot product does where one row is left), and that
//    column divided by the root. From 32 unknowns on, Eigen's own blocked routine.
//  - The solve is LLT::solve()'s: the two triangular solves of Eigen on the factor.
// The results are Eigen's bit for bit (tests/test_dense_llt.cpp).
#pragma once

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace carbonmesh {

// Factorizes the symmetric positive definite `a` (its lower triangle is read) into L in its lower triangle. False
// where Eigen's LLT reports NumericalIssue (a pivot not above 0).
inline bool llt_in_place(Eigen::MatrixXd& a) {
  const Eigen::Index n = a.rows();
  if (n >= 32) return Eigen::internal::llt_inplace<double, Eigen::Lower>::blocked(a) == -1;
  double* m = a.data();
  const Eigen::Index ld = a.outerStride();
  auto at = [&](Eigen::Index i, Eigen::Index j) -> double& { return m[i + j * ld]; };
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index rs = n - k - 1;
    double x = at(k, k);
    if (k > 0) {
      double s = at(k, 0) * at(k, 0);
      for (Eigen::Index j = 1; j < k; ++j) s = s + at(k, j) * at(k, j);
      x -= s;
    }
    if (x <= 0.0) return false;
    x = std::sqrt(x);
    at(k, k) = x;
    if (k > 0 && rs > 0) {
      if (rs == 1) {  // Eigen's product falls back to a dot product for one row
        const Eigen::Index i = k + 1;
        double d = at(i, 0) * at(k, 0);
        for (Eigen::Index j = 1; j < k; ++j) d = d + at(i, j) * at(k, j);
        at(i, k) += -1.0 * d;
      } else {  // (column by column, each row's sum in its own slot: the loop over the rows vectorizes as Eigen's)
        double c[32];
        for (Eigen::Index i = 0; i < rs; ++i) c[i] = 0.0;
        for (Eigen::Index j = 0; j < k; ++j) {
          const double b = at(k, j);
          const double* column = m + (k + 1) + j * ld;
          for (Eigen::Index i = 0; i < rs; ++i) c[i] = column[i] * b + c[i];
        }
        double* below = m + (k + 1) + k * ld;
        for (Eigen::Index i = 0; i < rs; ++i) below[i] = c[i] * -1.0 + below[i];
      }
    }
    if (rs > 0)
      for (Eigen::Index i = k + 1; i < n; ++i) at(i, k) = at(i, k) / x;
  }
  return true;
}

// x = the solution of L L^T x = b, L the factor llt_in_place() left in the lower triangle of `l`.
inline void llt_solve(const Eigen::MatrixXd& l, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  x = b;
  l.triangularView<Eigen::Lower>().solveInPlace(x);
  l.adjoint().triangularView<Eigen::Upper>().solveInPlace(x);
}

}  // namespace carbonmesh
