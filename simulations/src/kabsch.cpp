#include "carbonmesh/simulations/kabsch.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace carbonmesh {
namespace {

Eigen::Vector3d eig(const Vec3& v) { return {v[0], v[1], v[2]}; }

Eigen::Vector3d centroid(const std::vector<Vec3>& points) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : points) c += eig(p);
  return c / static_cast<double>(points.size());
}

}  // namespace

std::vector<Vec3> apply_alignment(const Alignment& a, const std::vector<Vec3>& moving) {
  std::vector<Vec3> out;
  out.reserve(moving.size());
  for (const auto& p : moving) {
    Vec3 q = a.translation;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) q[r] += a.rotation[r][c] * p[c];
    out.push_back(q);
  }
  return out;
}

Alignment kabsch_align(const std::vector<Vec3>& reference, const std::vector<Vec3>& moving) {
  if (reference.size() != moving.size() || reference.empty())
    throw std::invalid_argument("kabsch_align: the point sets must be non-empty and of equal size");
  const Eigen::Vector3d cr = centroid(reference), cm = centroid(moving);
  // Cross-covariance H = sum (m - cm)(r - cr)^T; R = V diag(1, 1, d) U^T with H = U S V^T.
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < moving.size(); ++i) h += (eig(moving[i]) - cm) * (eig(reference[i]) - cr).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  const Eigen::Matrix3d rot = svd.matrixV() * d * svd.matrixU().transpose();
  const Eigen::Vector3d t = cr - rot * cm;

  Alignment a;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a.rotation[r][c] = rot(r, c);
  a.translation = Vec3(t[0], t[1], t[2]);
  double sum = 0;
  for (std::size_t i = 0; i < moving.size(); ++i) {
    const double dist = (rot * eig(moving[i]) + t - eig(reference[i])).norm();
    sum += dist * dist;
    if (dist > a.max_displacement || a.max_atom < 0) a.max_displacement = dist, a.max_atom = static_cast<int>(i);
  }
  a.rmsd = std::sqrt(sum / static_cast<double>(moving.size()));
  return a;
}

}  // namespace carbonmesh
