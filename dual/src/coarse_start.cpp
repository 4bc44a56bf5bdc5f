#include "carbonmesh/dual/coarse_start.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "carbonmesh/remesh/point_grid.hpp"

namespace carbonmesh {

DisplacementTransfer transfer_displacements(Dual& fine, const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  if (from.size() != to.size()) throw std::invalid_argument("transfer_displacements: from and to differ in size");
  DisplacementTransfer r;
  if (from.empty() || fine.atoms() == 0) return r;
  constexpr std::size_t kNearest = 6;
  // Cells sized by the grid's cap of about one cell per coarse atom over the bounding box.
  std::vector<int> ids(from.size());
  std::iota(ids.begin(), ids.end(), 0);
  const PointGrid grid(from, ids, 0.0, static_cast<double>(from.size()));
  std::vector<Vec3> positions = fine.positions();
  const long n = static_cast<long>(positions.size());
  std::vector<double> shift(positions.size(), 0.0);
#pragma omp parallel
  {
    std::vector<std::pair<double, int>> best;
#pragma omp for schedule(static)
    for (long i = 0; i < n; ++i) {
      Vec3& p = positions[static_cast<std::size_t>(i)];
      grid.nearest(p, kNearest + 1, best);
      // Franke-Little weights ((R - d) / (R d))^2, R the distance of the (k+1)-th nearest: a coarse atom's weight
      // falls to 0 as it leaves the k nearest, so the moved atoms follow a continuous field (plain inverse
      // distance weights jump where the set of nearest atoms changes; fertility at 250000 atoms: shortest fine
      // bond at the start 0.89 A instead of 0.79, the fine optimisation's iterations about the same).
      const double r = best.size() > kNearest ? std::sqrt(best.back().first) : 0.0;
      if (best.size() > kNearest) best.pop_back();
      Vec3 d(0, 0, 0);
      double weights = 0;
      for (const auto& [d2, j] : best) {
        const double dist = std::sqrt(d2);
        const double w = r > 0 ? std::pow((r - dist) / (r * dist + 1e-12), 2) : 1.0 / (d2 + 1e-12);
        d += w * (to[static_cast<std::size_t>(j)] - from[static_cast<std::size_t>(j)]);
        weights += w;
      }
      if (weights > 0) d /= weights;
      p += d;
      shift[static_cast<std::size_t>(i)] = d.norm();
    }
  }
  fine.set_positions(positions);
  r.atoms = positions.size();
  for (double s : shift) r.mean_shift += s, r.max_shift = std::max(r.max_shift, s);
  r.mean_shift /= static_cast<double>(positions.size());
  return r;
}

namespace {

// Optimises `coarse` (a dual at coarse level `level`) at 2^level times the bond and window; returns where its atoms
// ended, in the unscaled frame (the optimisation put them at c + s (y - c)).
std::vector<Vec3> optimise_level(Dual& coarse, int level, const TriMesh& surface, const DualOptimizeSettings& settings,
                                 CoarseStartResult& r) {
  DualOptimizeSettings scaled = settings;
  const double factor = std::ldexp(1.0, level);
  scaled.bond = factor * settings.bond;
  scaled.bond_window = factor * settings.bond_window;
  r.level = level;
  r.coarse_atoms = coarse.atoms();
  r.coarse = optimize_dual(coarse, surface, scaled);
  std::vector<Vec3> to = coarse.positions();
  const Vec3 c = r.coarse.scale_centre;
  for (Vec3& p : to) p = c + (p - c) / r.coarse.surface_scale;
  return to;
}

}  // namespace

CoarseStartResult coarse_start(Dual& fine, const TriMesh& coarse_mesh, const TriMesh& surface,
                               const DualOptimizeSettings& settings) {
  Dual coarse = build_dual(coarse_mesh);
  const std::vector<Vec3> from = coarse.positions();
  CoarseStartResult r;
  const std::vector<Vec3> to = optimise_level(coarse, 1, surface, settings, r);
  r.transfer = transfer_displacements(fine, from, to);
  return r;
}

std::vector<CoarseStartResult> coarse_start(Dual& fine, const std::vector<CoarseLevel>& levels,
                                            const TriMesh& surface, const DualOptimizeSettings& settings) {
  std::vector<const CoarseLevel*> order;
  for (const CoarseLevel& l : levels) {
    if (l.level < 1) throw std::invalid_argument("coarse_start: coarse levels start at 1");
    order.push_back(&l);
  }
  std::sort(order.begin(), order.end(), [](const CoarseLevel* a, const CoarseLevel* b) { return a->level > b->level; });
  for (std::size_t i = 1; i < order.size(); ++i)
    if (order[i]->level == order[i - 1]->level) throw std::invalid_argument("coarse_start: a coarse level twice");
  std::vector<CoarseStartResult> results;
  std::vector<Vec3> from, to;  // the previous (coarser) level's centroids and where its atoms ended
  for (const CoarseLevel* l : order) {
    Dual coarse = build_dual(l->mesh);
    std::vector<Vec3> centroids = coarse.positions();
    if (!results.empty()) results.back().transfer = transfer_displacements(coarse, from, to);
    CoarseStartResult r;
    to = optimise_level(coarse, l->level, surface, settings, r);
    from = std::move(centroids);
    results.push_back(r);
  }
  if (!results.empty()) results.back().transfer = transfer_displacements(fine, from, to);
  return results;
}

nlohmann::json to_json(const CoarseStartResult& r) {
  nlohmann::json j = to_json(r.coarse);
  j["level"] = r.level;
  j["coarse_atoms"] = r.coarse_atoms;
  j["fine_atoms_moved"] = r.transfer.atoms;
  j["mean_shift"] = r.transfer.mean_shift;
  j["max_shift"] = r.transfer.max_shift;
  return j;
}

nlohmann::json to_json(const std::vector<CoarseStartResult>& levels) {
  if (levels.empty()) return nlohmann::json::object();
  nlohmann::json j = to_json(levels.back());
  j["levels"] = nlohmann::json::array();
  for (const CoarseStartResult& r : levels) j["levels"].push_back(to_json(r));
  return j;
}

}  // namespace carbonmesh
