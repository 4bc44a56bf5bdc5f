#include "carbonmesh/dual/optimize.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "lbfgs.hpp"
#include "surface_projector.hpp"

namespace carbonmesh {
namespace {

struct DistanceFigures {
  double max = 0, rms = 0;
};

DistanceFigures surface_distances(const detail::SurfaceProjector& projector, const std::vector<Vec3>& points) {
  std::vector<Vec3> closest;
  projector.closest_points(points, closest);
  DistanceFigures out;
  double sum2 = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d2 = (points[i] - closest[i]).sqrnorm();
    out.max = std::max(out.max, std::sqrt(d2));
    sum2 += d2;
  }
  out.rms = points.empty() ? 0.0 : std::sqrt(sum2 / static_cast<double>(points.size()));
  return out;
}

// The energy of optimize.hpp over the 3n coordinates.
class DualEnergy {
 public:
  DualEnergy(const std::vector<AtomPair>& bonds, const std::vector<AtomTriple>& angles,
             const std::vector<double>& target_cosines, const detail::SurfaceProjector& projector,
             const DualOptimizeSettings& s)
      : bonds_(bonds), angles_(angles), target_cosines_(target_cosines), projector_(projector), s_(s) {}

  double operator()(const Eigen::VectorXd& x, Eigen::VectorXd& g) {
    const std::size_t n = static_cast<std::size_t>(x.size() / 3);
    g.setZero(x.size());
    auto p = [&](int i) { return Eigen::Vector3d(x.segment<3>(3 * i)); };
    double e = 0;
    const double b = s_.bond;
    for (const auto& bond : bonds_) {
      const Eigen::Vector3d r = p(bond[0]) - p(bond[1]);
      const double length = r.norm();
      if (length == 0) continue;
      const double diff = length - b;
      e += diff * diff;
      const Eigen::Vector3d d = (2 * diff / length) * r;
      g.segment<3>(3 * bond[0]) += d;
      g.segment<3>(3 * bond[1]) -= d;
    }
    const double wa = s_.angle_weight * b * b;
    if (wa > 0) {
      for (std::size_t a = 0; a < angles_.size(); ++a) {
        const AtomTriple& t = angles_[a];
        const Eigen::Vector3d c = p(t[1]);
        const Eigen::Vector3d u = p(t[0]) - c, v = p(t[2]) - c;
        const double lu = u.norm(), lv = v.norm();
        if (lu == 0 || lv == 0) continue;
        const double cosine = u.dot(v) / (lu * lv);
        const double diff = cosine - target_cosines_[a];
        e += wa * diff * diff;
        const double de = 2 * wa * diff;
        const Eigen::Vector3d du = de * (v / (lu * lv) - cosine * u / (lu * lu));
        const Eigen::Vector3d dv = de * (u / (lu * lv) - cosine * v / (lv * lv));
        g.segment<3>(3 * t[0]) += du;
        g.segment<3>(3 * t[2]) += dv;
        g.segment<3>(3 * t[1]) -= du + dv;
      }
    }
    if (s_.surface_weight > 0) {
      points_.resize(n);
      for (std::size_t i = 0; i < n; ++i) points_[i] = Vec3(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
      projector_.closest_points(points_, closest_);
      for (std::size_t i = 0; i < n; ++i) {
        const Vec3 d = points_[i] - closest_[i];
        e += s_.surface_weight * d.sqrnorm();
        for (int k = 0; k < 3; ++k) g[static_cast<Eigen::Index>(3 * i + k)] += 2 * s_.surface_weight * d[k];
      }
    }
    return e;
  }

 private:
  const std::vector<AtomPair>& bonds_;
  const std::vector<AtomTriple>& angles_;
  const std::vector<double>& target_cosines_;
  const detail::SurfaceProjector& projector_;
  const DualOptimizeSettings& s_;
  std::vector<Vec3> points_, closest_;
};

// The cosine of the target of every angle: the interior angle of a regular polygon of the size of the closed
// ring the angle lies in (108 degrees in a pentagon, 120 in a hexagon, ...), 120 degrees outside closed rings.
std::vector<double> target_cosines(const Dual& dual, const std::vector<AtomTriple>& angles) {
  std::map<AtomTriple, double> in_ring;
  for (std::size_t r = 0; r < dual.rings.size(); ++r) {
    const auto& ring = dual.rings[r];
    const std::size_t n = ring.size();
    if (!dual.ring_closed[r] || n < 3) continue;
    const double interior = std::numbers::pi * static_cast<double>(n - 2) / static_cast<double>(n);
    for (std::size_t k = 0; k < n; ++k) {
      const int j = ring[(k + n - 1) % n], c = ring[k], l = ring[(k + 1) % n];
      in_ring[{std::min(j, l), c, std::max(j, l)}] = std::cos(interior);
    }
  }
  std::vector<double> out;
  out.reserve(angles.size());
  for (const auto& t : angles) {
    const auto it = in_ring.find(t);
    out.push_back(it == in_ring.end() ? -0.5 : it->second);
  }
  return out;
}

}  // namespace

DualOptimizeResult optimize_dual(Dual& dual, const TriMesh& surface, const DualOptimizeSettings& settings) {
  if (!(settings.bond > 0)) throw std::invalid_argument("optimize_dual: the bond length must be positive");
  if (settings.angle_weight < 0 || settings.surface_weight < 0)
    throw std::invalid_argument("optimize_dual: weights must not be negative");
  const auto t0 = std::chrono::steady_clock::now();
  const detail::SurfaceProjector projector(surface);
  const auto angles = bond_angles(dual.atoms(), dual.bonds);
  DualOptimizeResult r;
  std::vector<Vec3> positions = dual.positions();
  r.bonds_before = sample_stats(bond_lengths(positions, dual.bonds));
  r.angles_before = sample_stats(angle_degrees(positions, angles));
  r.surface_max_before = surface_distances(projector, positions).max;

  Eigen::VectorXd x(static_cast<Eigen::Index>(3 * positions.size()));
  for (std::size_t i = 0; i < positions.size(); ++i)
    for (int k = 0; k < 3; ++k) x[static_cast<Eigen::Index>(3 * i + k)] = positions[i][k];
  const std::vector<double> targets = target_cosines(dual, angles);
  DualEnergy energy(dual.bonds, angles, targets, projector, settings);
  Eigen::VectorXd g;
  r.energy_before = energy(x, g);

  detail::LbfgsSettings ls;
  ls.max_iterations = settings.max_iterations;
  ls.memory = settings.memory;
  ls.gradient_tolerance = settings.gradient_tolerance;
  ls.max_step = 0.1 * settings.bond;
  const detail::LbfgsResult lr = detail::minimize_lbfgs(x, energy, ls);
  r.iterations = lr.iterations;
  r.converged = lr.converged;
  r.energy_after = lr.energy;

  for (std::size_t i = 0; i < positions.size(); ++i)
    positions[i] = Vec3(x[static_cast<Eigen::Index>(3 * i)], x[static_cast<Eigen::Index>(3 * i + 1)],
                        x[static_cast<Eigen::Index>(3 * i + 2)]);
  dual.set_positions(positions);
  dual.mesh.update_face_normals();
  r.bonds_after = sample_stats(bond_lengths(positions, dual.bonds));
  r.angles_after = sample_stats(angle_degrees(positions, angles));
  const DistanceFigures after = surface_distances(projector, positions);
  r.surface_max_after = after.max;
  r.surface_rms_after = after.rms;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  spdlog::info("dual optimisation: {} iterations ({}), bonds {:.4f}..{:.4f} (mean {:.4f}, std {:.4f}) -> "
               "{:.4f}..{:.4f} (mean {:.4f}, std {:.4f}), angles {:.2f}..{:.2f} -> {:.2f}..{:.2f} deg, "
               "surface distance max {:.4f}",
               r.iterations, r.converged ? "converged" : "not converged", r.bonds_before.min, r.bonds_before.max,
               r.bonds_before.mean, r.bonds_before.std, r.bonds_after.min, r.bonds_after.max, r.bonds_after.mean,
               r.bonds_after.std, r.angles_before.min, r.angles_before.max, r.angles_after.min, r.angles_after.max,
               r.surface_max_after);
  return r;
}

nlohmann::json to_json(const DualOptimizeResult& r) {
  return {{"bonds_before", to_json(r.bonds_before)},
          {"bonds_after", to_json(r.bonds_after)},
          {"angles_before_deg", to_json(r.angles_before)},
          {"angles_after_deg", to_json(r.angles_after)},
          {"surface_distance_max_before", r.surface_max_before},
          {"surface_distance_max_after", r.surface_max_after},
          {"surface_distance_rms_after", r.surface_rms_after},
          {"energy_before", r.energy_before},
          {"energy_after", r.energy_after},
          {"iterations", r.iterations},
          {"converged", r.converged},
          {"seconds", r.seconds}};
}

}  // namespace carbonmesh
