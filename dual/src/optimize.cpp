#include "carbonmesh/dual/optimize.hpp"

#include <spdlog/spdlog.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <tuple>
#include <cmath>
#include <algorithm>
#include <numbers>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "carbonmesh/remesh/morton_order.hpp"
#include "dual_energy.hpp"
#include "lbfgs.hpp"
#include "surface_projector.hpp"

namespace carbonmesh {
namespace {

// The cosine of the target of every angle: the interior angle of a regular polygon of the size of the closed
// ring the angle lies in (108 degrees in a pentagon, 120 in a hexagon, ...), 120 degrees outside closed rings.
std::vector<double> target_cosines(const Dual& dual, const std::vector<AtomTriple>& angles) {
  // bond_angles orders the angles by centre atom: first[c] is the first angle centred on atom c.
  std::vector<int> first(dual.atoms() + 1, 0);
  for (const auto& t : angles) ++first[static_cast<std::size_t>(t[1]) + 1];
  for (std::size_t i = 0; i < dual.atoms(); ++i) first[i + 1] += first[i];
  std::vector<double> out(angles.size(), -0.5);
  for (std::size_t r = 0; r < dual.rings.size(); ++r) {
    const auto& ring = dual.rings[r];
    const std::size_t n = ring.size();
    if (!dual.ring_closed[r] || n < 3) continue;
    const double target = std::cos(std::numbers::pi * static_cast<double>(n - 2) / static_cast<double>(n));
    for (std::size_t k = 0; k < n; ++k) {
      const int j = ring[(k + n - 1) % n], c = ring[k], l = ring[(k + 1) % n];
      const AtomTriple key{std::min(j, l), c, std::max(j, l)};
      for (int a = first[static_cast<std::size_t>(c)]; a < first[static_cast<std::size_t>(c) + 1]; ++a)
        if (angles[static_cast<std::size_t>(a)] == key) out[static_cast<std::size_t>(a)] = target;
    }
  }
  return out;
}

// Area centroid of the surface and the area-weighted RMS distance of its face centroids from it.
void centre_and_radius(const TriMesh& surface, Vec3& centre, double& radius) {
  double area = 0;
  Vec3 sum(0, 0, 0);
  for (auto f : surface.faces()) {
    auto it = surface.cfv_iter(f);
    const Vec3 a = surface.point(*it++), b = surface.point(*it++), c = surface.point(*it);
    const double w = 0.5 * OpenMesh::cross(b - a, c - a).norm();
    area += w;
    sum += w * (a + b + c) / 3.0;
  }
  centre = area > 0 ? sum / area : Vec3(0, 0, 0);
  double r2 = 0;
  for (auto f : surface.faces()) {
    auto it = surface.cfv_iter(f);
    const Vec3 a = surface.point(*it++), b = surface.point(*it++), c = surface.point(*it);
    const double w = 0.5 * OpenMesh::cross(b - a, c - a).norm();
    r2 += w * ((a + b + c) / 3.0 - centre).sqrnorm();
  }
  radius = area > 0 && r2 > 0 ? std::sqrt(r2 / area) : 1.0;
}

// Atoms at the centre of an angle outside [90, 150] degrees.
std::size_t strained_atoms(std::size_t atoms, const std::vector<AtomTriple>& angles,
                           const std::vector<double>& degrees) {
  std::vector<char> strained(atoms, 0);
  for (std::size_t a = 0; a < angles.size(); ++a)
    if (degrees[a] < 90 || degrees[a] > 150) strained[static_cast<std::size_t>(angles[a][1])] = 1;
  return static_cast<std::size_t>(std::count(strained.begin(), strained.end(), 1));
}

}  // namespace

DualOptimizeResult optimize_dual(Dual& dual, const TriMesh& surface, const DualOptimizeSettings& settings) {
  if (!(settings.bond > 0)) throw std::invalid_argument("optimize_dual: the bond length must be positive");
  if (settings.angle_weight < 0 || settings.surface_weight < 0 || settings.bond_window_weight < 0 ||
      settings.contact_weight < 0 ||
      settings.bond_window < 0)
    throw std::invalid_argument("optimize_dual: weights must not be negative");
  const auto t0 = std::chrono::steady_clock::now();
  const detail::SurfaceProjector projector(surface);
  Vec3 centre;
  double radius = 1;
  centre_and_radius(surface, centre, radius);
  const auto angles = bond_angles(dual.atoms(), dual.bonds);
  DualOptimizeResult r;
  std::vector<Vec3> positions = dual.positions();
  r.bonds_before = sample_stats(bond_lengths(positions, dual.bonds));
  const std::vector<double> degrees_before = angle_degrees(positions, angles);
  r.angles_before = sample_stats(degrees_before);
  r.strained_before = strained_atoms(dual.atoms(), angles, degrees_before);
  // Seat every atom on its nearest face (the one global query per atom).
  std::vector<Vec3> closest;
  std::vector<int> faces;
  projector.closest_points(positions, closest, faces);
  for (std::size_t i = 0; i < positions.size(); ++i)
    r.surface_max_before = std::max(r.surface_max_before, (positions[i] - closest[i]).norm());

  const std::size_t n = positions.size();
  // The minimisation works on the atoms in spatial order: atom order[k] is unknown k (rank[order[k]] = k),
  // bonds sorted by their first atom and angles by their centre atom in that order.
  const std::vector<int> order = morton_order(positions);
  std::vector<int> rank(n);
  for (std::size_t k = 0; k < n; ++k) rank[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
  auto ranked = [&](int atom) { return rank[static_cast<std::size_t>(atom)]; };
  std::vector<AtomPair> bonds;
  bonds.reserve(dual.bonds.size());
  for (const auto& b : dual.bonds) {
    const int i = ranked(b[0]), j = ranked(b[1]);
    bonds.push_back({std::min(i, j), std::max(i, j)});
  }
  std::sort(bonds.begin(), bonds.end());
  const std::vector<double> targets = target_cosines(dual, angles);
  std::vector<std::size_t> by_centre(angles.size());
  std::vector<AtomTriple> ordered_angles(angles.size());
  for (std::size_t a = 0; a < angles.size(); ++a) {
    const int j = ranked(angles[a][0]), l = ranked(angles[a][2]);
    ordered_angles[a] = {std::min(j, l), ranked(angles[a][1]), std::max(j, l)};
    by_centre[a] = a;
  }
  std::sort(by_centre.begin(), by_centre.end(), [&](std::size_t a, std::size_t b) {
    const AtomTriple &p = ordered_angles[a], &q = ordered_angles[b];
    return std::tie(p[1], p[0], p[2]) < std::tie(q[1], q[0], q[2]);
  });
  std::vector<AtomTriple> sorted_angles(angles.size());
  std::vector<double> sorted_targets(angles.size());
  for (std::size_t a = 0; a < angles.size(); ++a)
    sorted_angles[a] = ordered_angles[by_centre[a]], sorted_targets[a] = targets[by_centre[a]];
  std::vector<int> sorted_faces(n);
  const Eigen::Index extra = settings.free_scale ? 1 : 0;
  Eigen::VectorXd x(static_cast<Eigen::Index>(3 * n) + extra);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = static_cast<std::size_t>(order[k]);
    for (int c = 0; c < 3; ++c) x[static_cast<Eigen::Index>(3 * k + c)] = positions[i][c];
    sorted_faces[k] = faces[i];
  }
  if (extra) x[x.size() - 1] = 0;
  detail::DualEnergy energy(bonds, sorted_angles, sorted_targets, projector, radius, std::move(sorted_faces), settings);

  detail::LbfgsSettings ls;
  ls.max_iterations = settings.max_iterations;
  ls.memory = settings.memory;
  ls.gradient_tolerance = settings.gradient_tolerance;
  ls.max_step = 0.1 * settings.bond;
  ls.energy_tolerance = settings.energy_tolerance;
  const detail::LbfgsResult lr = detail::minimize_lbfgs(x, energy, ls);
  r.energy_before = lr.initial_energy;
  r.iterations = lr.iterations;
  r.evaluations = lr.evaluations;
  r.converged = lr.converged;
  r.energy_after = lr.energy;
  r.surface_scale = energy.scale(x);
  r.scale_centre = centre;

  // Distances to s S (s times the distance of y to S) from the faces the optimiser ended on; then x.
  const double s = r.surface_scale;
  std::vector<int> last = energy.faces();
  double sum2 = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 y(x[static_cast<Eigen::Index>(3 * k)], x[static_cast<Eigen::Index>(3 * k + 1)],
                 x[static_cast<Eigen::Index>(3 * k + 2)]);
    const double d2 = s * s * (y - projector.closest_point_near(y, last[k])).sqrnorm();
    r.surface_max_after = std::max(r.surface_max_after, std::sqrt(d2));
    sum2 += d2;
    positions[static_cast<std::size_t>(order[k])] = centre + (y - centre) * s;
  }
  r.surface_rms_after = n ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0;
  dual.set_positions(positions);
  dual.mesh.update_face_normals();
  r.bonds_after = sample_stats(bond_lengths(positions, dual.bonds));
  const std::vector<double> degrees_after = angle_degrees(positions, angles);
  r.angles_after = sample_stats(degrees_after);
  r.strained_after = strained_atoms(dual.atoms(), angles, degrees_after);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  spdlog::debug("dual optimisation: contact pair list built {} times", energy.contact_rebuilds());
  spdlog::info("dual optimisation: {} iterations, {} evaluations ({}), bonds {:.4f}..{:.4f} (mean {:.4f}, std "
               "{:.4f}) -> {:.4f}..{:.4f} (mean {:.4f}, std {:.4f}), angles {:.2f}..{:.2f} -> {:.2f}..{:.2f} deg, "
               "surface scale {:.4f}, distance max {:.4f}, {:.2f} s",
               r.iterations, r.evaluations, r.converged ? "converged" : "not converged", r.bonds_before.min,
               r.bonds_before.max, r.bonds_before.mean, r.bonds_before.std, r.bonds_after.min, r.bonds_after.max,
               r.bonds_after.mean, r.bonds_after.std, r.angles_before.min, r.angles_before.max, r.angles_after.min,
               r.angles_after.max, r.surface_scale, r.surface_max_after, r.seconds);
  return r;
}

nlohmann::json to_json(const DualOptimizeResult& r) {
  return {{"bonds_before", to_json(r.bonds_before)},
          {"bonds_after", to_json(r.bonds_after)},
          {"angles_before_deg", to_json(r.angles_before)},
          {"angles_after_deg", to_json(r.angles_after)},
          {"strained_atoms_before", r.strained_before},
          {"strained_atoms_after", r.strained_after},
          {"surface_distance_max_before", r.surface_max_before},
          {"surface_distance_max_after", r.surface_max_after},
          {"surface_distance_rms_after", r.surface_rms_after},
          {"surface_scale", r.surface_scale},
          {"energy_before", r.energy_before},
          {"energy_after", r.energy_after},
          {"iterations", r.iterations},
          {"evaluations", r.evaluations},
          {"converged", r.converged},
          {"seconds", r.seconds}};
}

}  // namespace carbonmesh
