// A capsule replaced by a capped nanotube's triangulation (carbonmesh/remesh/lattice_capsule.hpp).
#include "carbonmesh/remesh/lattice_capsule.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "add_faces.hpp"
#include "least_squares_fit.hpp"

namespace carbonmesh {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kFitPoints = 4096;

// The residuals of the capsule fit: each point's distance to the axis segment less the radius. Parameters (alpha,
// beta, x, y, z, r, l): the axis axis0 + alpha u0 + beta v0 (normalised) through x u0 + y v0 + z axis0 (the points
// are relative to the first centre), the radius r, the straight part from -l to +l along the axis.
struct CapsuleResiduals : least_squares_fit::Residuals {

  const std::vector<Eigen::Vector3d>* points;
  Eigen::Vector3d axis0, u0, v0;

  int inputs() const { return 7; }
  int values() const { return static_cast<int>(points->size()); }
  Eigen::Vector3d axis(const Eigen::VectorXd& x) const { return (axis0 + x[0] * u0 + x[1] * v0).normalized(); }
  Eigen::Vector3d centre(const Eigen::VectorXd& x) const { return x[2] * u0 + x[3] * v0 + x[4] * axis0; }
  int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& f) const {
    const Eigen::Vector3d w = axis(x), c = centre(x);
    const double half = std::abs(x[6]);
    for (std::size_t i = 0; i < points->size(); ++i) {
      const Eigen::Vector3d d = (*points)[i] - c;
      const double s = std::clamp(d.dot(w), -half, half);
      f[static_cast<Eigen::Index>(i)] = (d - s * w).norm() - x[5];
    }
    return 0;
  }
};

Eigen::Vector3d eigen(const Vec3& v) { return {v[0], v[1], v[2]}; }
Vec3 vec3(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

// A unit vector square to the unit vector w.
Eigen::Vector3d square_to(const Eigen::Vector3d& w) {
  Eigen::Index k = 0;
  w.cwiseAbs().minCoeff(&k);
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  e[k] = 1;
  return (e - e.dot(w) * w).normalized();
}

}  // namespace

Capsule capsule_fit(const TriMesh& mesh) {
  Capsule out;
  std::vector<Eigen::Vector3d> all;
  for (auto v : mesh.vertices())
    if (!mesh.status(v).deleted() && !mesh.is_isolated(v)) all.push_back(eigen(mesh.point(v)));
  if (all.size() < 8) return out;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : all) mean += p;
  mean /= static_cast<double>(all.size());
  for (auto& p : all) p -= mean;
  // A first axis: the direction of the largest spread; a first radius and half length from the points' extent.
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const auto& p : all) spread += p * p.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(spread);
  CapsuleResiduals residuals;
  residuals.axis0 = solver.eigenvectors().col(2);
  residuals.u0 = square_to(residuals.axis0);
  residuals.v0 = residuals.axis0.cross(residuals.u0);
  double radius = 0, extent = 0;
  for (const auto& p : all) {
    const double s = p.dot(residuals.axis0);
    radius = std::max(radius, (p - s * residuals.axis0).norm());
    extent = std::max(extent, std::abs(s));
  }
  const std::size_t stride = (all.size() + kFitPoints - 1) / kFitPoints;
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < all.size(); i += stride) points.push_back(all[i]);
  residuals.points = &points;
  Eigen::VectorXd x(7);
  x << 0, 0, 0, 0, 0, radius, std::max(0.0, extent - radius);
  if (!x.allFinite() || !(radius > 0)) return out;
  if (!least_squares_fit::minimize(residuals, x, 4000)) return out;
  out.axis = vec3(least_squares_fit::canonical_axis(residuals.axis(x)));
  out.centre = vec3(mean + residuals.centre(x));
  out.radius = std::abs(x[5]);
  out.length = 2 * std::abs(x[6]);
  residuals.points = &all;
  Eigen::VectorXd f(static_cast<Eigen::Index>(all.size()));
  residuals(x, f);
  out.distance = f.cwiseAbs().maxCoeff();
  if (!(out.radius > 0) || !std::isfinite(out.distance)) out.distance = std::numeric_limits<double>::infinity();
  return out;
}

double capsule_area(const Capsule& capsule) {
  return 2 * kPi * capsule.radius * capsule.length + 4 * kPi * capsule.radius * capsule.radius;
}

std::array<int, 2> nearest_capped_chirality(double radius, double edge) {
  std::array<int, 2> best{5, 0};
  double best_error = std::abs(capped_tube_radius(5, 0, edge) - radius);
  long best_t = 1;
  for (int h = 1; triangulation_number(h, 0) <= kMaxTriangulationNumber; ++h) {
    if (capped_tube_radius(5 * h, 0, edge) - radius > best_error) break;  // T >= h^2 only grows from here
    for (int k = 0; k <= h; ++k) {
      const long t = triangulation_number(h, k);
      if (t > kMaxTriangulationNumber) break;
      const double error = std::abs(capped_tube_radius(5 * h, 5 * k, edge) - radius);
      if (error < best_error || (error == best_error && (t < best_t || (t == best_t && 5 * k < best[1]))))
        best = {5 * h, 5 * k}, best_error = error, best_t = t;
    }
  }
  return best;
}

LatticeCappedTube lattice_capped_tube(const TriMesh& input, const Capsule& capsule, double edge,
                                      std::array<int, 2> chirality) {
  if (!(edge > 0) || !std::isfinite(edge)) throw InputError(fmt::format("lattice edge {} must be positive", edge));
  CappedTube tube = make_capped_tube({chirality[0], chirality[1], capsule.length, edge});
  LatticeCappedTube out;
  out.chirality = chirality;
  out.periods = tube.periods;
  out.caps = tube.caps;
  out.radius = tube.radius;
  out.length = tube.straight_length;
  // Which side the input's faces face: the sign of its volume about the capsule's centre.
  const double volume = signed_volume(input, capsule.centre);
  // The tube's z axis onto the capsule's axis (the rotation about z x axis), centred on its centre.
  const Eigen::Vector3d z(0, 0, 1), to = eigen(capsule.axis).normalized();
  const Eigen::Matrix3d turn = Eigen::Quaterniond::FromTwoVectors(z, to).toRotationMatrix();
  for (auto v : tube.mesh.vertices()) out.mesh.add_vertex(capsule.centre + vec3(turn * eigen(tube.mesh.point(v))));
  if (!add_faces(out.mesh, face_corners(tube.mesh, volume < 0)))
    throw std::logic_error("lattice capped tube: a triangle that does not fit its neighbours");
  out.mesh.update_normals();
  return out;
}

}  // namespace carbonmesh
