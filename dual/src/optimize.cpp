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
#include "contact_term.hpp"
#include "lbfgs.hpp"
#include "surface_projector.hpp"

namespace carbonmesh {
namespace {

// Classes of terms no two of which share an atom (greedy colouring in term order): the terms of one class can
// add to the gradient in parallel without two threads writing the same atom, and the classes run in a fixed
// order, so every atom's gradient is summed in the same order for any thread count.
template <std::size_t K>
std::vector<std::vector<std::uint32_t>> conflict_free_classes(const std::vector<std::array<int, K>>& terms,
                                                               std::size_t atoms) {
  std::vector<std::uint64_t> used(atoms, 0);
  std::vector<std::vector<std::uint32_t>> classes;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    std::uint64_t taken = 0;
    for (int a : terms[t]) taken |= used[static_cast<std::size_t>(a)];
    int c = 0;
    while (c < 64 && (taken >> c & 1u)) ++c;
    if (c == 64) return {};  // not for a net of degree <= 3: the caller then sums in one pass
    if (static_cast<std::size_t>(c) >= classes.size()) classes.resize(static_cast<std::size_t>(c) + 1);
    classes[static_cast<std::size_t>(c)].push_back(static_cast<std::uint32_t>(t));
    for (int a : terms[t]) used[static_cast<std::size_t>(a)] |= std::uint64_t{1} << c;
  }
  return classes;
}

// Sums term(i, e, gs) over i in [0, n) in parallel with a result that does not depend on the thread count:
// fixed chunks, their partial sums added in chunk order.
template <class Term>
void chunked_sum(std::size_t n, std::vector<std::array<double, 2>>& partial, double& e, double& gs, Term&& term) {
  constexpr std::size_t kChunk = 4096;
  const long chunks = static_cast<long>((n + kChunk - 1) / kChunk);
  partial.assign(static_cast<std::size_t>(chunks), {0.0, 0.0});
#pragma omp parallel for schedule(static)
  for (long c = 0; c < chunks; ++c) {
    double ce = 0, cg = 0;
    const std::size_t end = std::min(n, static_cast<std::size_t>(c + 1) * kChunk);
    for (std::size_t i = static_cast<std::size_t>(c) * kChunk; i < end; ++i) term(i, ce, cg);
    partial[static_cast<std::size_t>(c)] = {ce, cg};
  }
  for (const auto& [pe, pg] : partial) e += pe, gs += pg;
}

// The unknowns are y (3n coordinates) and, with a free scale, u: the atoms sit at x = c + s (y - c) with
// s = 1 + u / radius, c the area centroid of S and radius the RMS distance of S from c. Bond lengths are s |y_i - y_j|,
// angles do not depend on s, and the distance of x to s S is s d(y, S). So a change of u moves every atom and
// the surface together, and the size of the structure is one well-conditioned direction of the minimisation
// (holding atoms on a moving surface through the surface springs instead converges very slowly).
class DualEnergy {
 public:
  DualEnergy(const std::vector<AtomPair>& bonds, const std::vector<AtomTriple>& angles,
             const std::vector<double>& target_cosines, const detail::SurfaceProjector& projector, double radius,
             std::vector<int> faces, const DualOptimizeSettings& s)
      : bonds_(bonds), angles_(angles), target_cosines_(target_cosines), projector_(projector), radius_(radius),
        faces_(std::move(faces)), s_(s),
        contacts_(faces_.size(), bonds, std::numbers::sqrt2 * s.bond, s.contact_weight),
        bond_classes_(parallel() ? conflict_free_classes(bonds, faces_.size()) : Classes{}),
        angle_classes_(parallel() ? conflict_free_classes(angles, faces_.size()) : Classes{}) {}

  double scale(const Eigen::VectorXd& x) const {
    return s_.free_scale ? 1.0 + x[x.size() - 1] / radius_ : 1.0;
  }
  const std::vector<int>& faces() const { return faces_; }

  double operator()(const Eigen::VectorXd& x, Eigen::VectorXd& g) {
    const std::size_t n = faces_.size();
    g.setZero(x.size());
    const double* px = x.data();
    double* pg = g.data();
    double e = 0, gs = 0;  // gs = dE/ds
    const double b = s_.bond;
    const double s = scale(x);
    const double window = s_.bond_window, window_weight = s_.bond_window_weight;
    // Large structures sum their bond and angle terms class by class in parallel; small ones (where a parallel
    // region per class costs more than the loop) and a class list that could not be built go in one pass in
    // term order, the memory order of the atoms.
    auto sum_terms = [&](const Classes& classes, std::size_t count, auto&& term) {
      if (classes.empty()) {
        for (std::size_t i = 0; i < count; ++i) term(i, e, gs);
        return;
      }
      for (const auto& members : classes)
        chunked_sum(members.size(), partial_sums_, e, gs,
                    [&](std::size_t m, double& ce, double& cg) { term(members[m], ce, cg); });
    };
    auto bond_term = [&](std::size_t index, double& ce, double& cg) {
      const auto& bond = bonds_[index];
      const double* p = px + 3 * bond[0];
      const double* q = px + 3 * bond[1];
      const double r0 = p[0] - q[0], r1 = p[1] - q[1], r2 = p[2] - q[2];
      const double length = std::sqrt(r0 * r0 + r1 * r1 + r2 * r2);
      if (length == 0) return;
      const double diff = s * length - b;
      // (diff)^2 plus the window hinge w_h (|diff| - delta)^2 outside b +- delta: dE/d(diff) = de.
      double de = 2 * diff;
      ce += diff * diff;
      const double over = std::abs(diff) - window;
      if (over > 0) {
        ce += window_weight * over * over;
        de += 2 * window_weight * over * (diff > 0 ? 1 : -1);
      }
      cg += de * length;
      const double k = de * s / length;
      double* gp = pg + 3 * bond[0];
      double* gq = pg + 3 * bond[1];
      gp[0] += k * r0, gp[1] += k * r1, gp[2] += k * r2;
      gq[0] -= k * r0, gq[1] -= k * r1, gq[2] -= k * r2;
    };
    sum_terms(bond_classes_, bonds_.size(), bond_term);
    const double wa = s_.angle_weight * b * b;
    if (wa > 0) {
      auto angle_term = [&](std::size_t a, double& ce, double&) {
        const AtomTriple& t = angles_[a];
        const Eigen::Map<const Eigen::Vector3d> c(px + 3 * t[1]);
        const Eigen::Vector3d u = Eigen::Map<const Eigen::Vector3d>(px + 3 * t[0]) - c;
        const Eigen::Vector3d v = Eigen::Map<const Eigen::Vector3d>(px + 3 * t[2]) - c;
        const double lu2 = u.squaredNorm(), lv2 = v.squaredNorm();
        if (lu2 == 0 || lv2 == 0) return;
        const double inv = 1.0 / std::sqrt(lu2 * lv2);
        const double cosine = u.dot(v) * inv;
        const double diff = cosine - target_cosines_[a];
        ce += wa * diff * diff;
        const double de = 2 * wa * diff;
        const Eigen::Vector3d du = de * (v * inv - (cosine / lu2) * u);
        const Eigen::Vector3d dv = de * (u * inv - (cosine / lv2) * v);
        Eigen::Map<Eigen::Vector3d>(pg + 3 * t[0]) += du;
        Eigen::Map<Eigen::Vector3d>(pg + 3 * t[2]) += dv;
        Eigen::Map<Eigen::Vector3d>(pg + 3 * t[1]) -= du + dv;
      };
      sum_terms(angle_classes_, angles_.size(), angle_term);
    }
    if (s_.surface_weight > 0) {
      const double w = s_.surface_weight * s * s;
      const long count = static_cast<long>(n);
      // Per atom independent (the walk starts at that atom's own face): deterministic in parallel; the sum is
      // reduced in a fixed order below. Parallel only for large structures: on a loaded machine a parallel
      // region per evaluation costs more than a small loop.
      partial_.resize(n);
#pragma omp parallel for schedule(static) if (parallel())
      for (long i = 0; i < count; ++i) {
        const std::size_t k = static_cast<std::size_t>(i);
        const Vec3 p(px[3 * i], px[3 * i + 1], px[3 * i + 2]);
        const Vec3 d = p - projector_.closest_point_near(p, faces_[k]);
        partial_[k] = d.sqrnorm();
        for (int j = 0; j < 3; ++j) pg[3 * i + j] += 2 * w * d[j];
      }
      double d2 = 0;
      for (std::size_t k = 0; k < n; ++k) d2 += partial_[k];
      e += w * d2;
      gs += 2 * s_.surface_weight * s * d2;
    }
    e += contacts_.add(px, s, pg, gs);
    if (s_.free_scale) pg[x.size() - 1] = gs / radius_;
    return e;
  }
  std::size_t contact_rebuilds() const { return contacts_.rebuilds(); }

 private:
  using Classes = std::vector<std::vector<std::uint32_t>>;  // conflict_free_classes; empty: one pass
  static constexpr std::size_t kParallelAtoms = 20000;
  bool parallel() const { return faces_.size() >= kParallelAtoms; }

  const std::vector<AtomPair>& bonds_;
  const std::vector<AtomTriple>& angles_;
  const std::vector<double>& target_cosines_;
  const detail::SurfaceProjector& projector_;
  double radius_;
  std::vector<int> faces_;  // the surface face each atom was last projected to (the walk's start)
  const DualOptimizeSettings& s_;
  std::vector<double> partial_;
  detail::ContactTerm contacts_;
  Classes bond_classes_, angle_classes_;
  std::vector<std::array<double, 2>> partial_sums_;
};

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
  DualEnergy energy(bonds, sorted_angles, sorted_targets, projector, radius, std::move(sorted_faces), settings);
  Eigen::VectorXd g;
  r.energy_before = energy(x, g);

  detail::LbfgsSettings ls;
  ls.max_iterations = settings.max_iterations;
  ls.memory = settings.memory;
  ls.gradient_tolerance = settings.gradient_tolerance;
  ls.max_step = 0.1 * settings.bond;
  ls.energy_tolerance = settings.energy_tolerance;
  const detail::LbfgsResult lr = detail::minimize_lbfgs(x, energy, ls);
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
