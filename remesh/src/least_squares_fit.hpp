#pragma once
// The pieces the cylinder and capsule fits share (lattice_tube.cpp, lattice_capsule.cpp): Levenberg-Marquardt with
// forward differences on a residual functor, and an axis made unique in sign.
#include <Eigen/Dense>
#include <unsupported/Eigen/NonLinearOptimization>
#include <unsupported/Eigen/NumericalDiff>

namespace carbonmesh::least_squares_fit {

// The types an Eigen residual functor declares (a fit's functor derives from it).
struct Residuals {
  using Scalar = double;
  using InputType = Eigen::VectorXd;
  using ValueType = Eigen::VectorXd;
  using JacobianType = Eigen::MatrixXd;
  enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };
};

// Minimises the sum of squares of `residuals` (an Eigen functor: inputs(), values(), operator()(x, f)) from x, to a
// relative change of 1e-14 or `max_evaluations` evaluations. False if x ends not finite.
template <typename Residuals>
bool minimize(const Residuals& residuals, Eigen::VectorXd& x, int max_evaluations) {
  Eigen::NumericalDiff<Residuals> differences(residuals);
  Eigen::LevenbergMarquardt<Eigen::NumericalDiff<Residuals>> solve(differences);
  solve.parameters.xtol = 1e-14;
  solve.parameters.ftol = 1e-14;
  solve.parameters.maxfev = max_evaluations;
  solve.minimize(x);
  return x.allFinite();
}

// `axis` with its largest component positive (an axis and its opposite are the same line).
inline Eigen::Vector3d canonical_axis(Eigen::Vector3d axis) {
  Eigen::Index largest = 0;
  axis.cwiseAbs().maxCoeff(&largest);
  if (axis[largest] < 0) axis = -axis;
  return axis;
}

}  // namespace carbonmesh::least_squares_fit
