#include "carbonmesh/dual/coarse_start.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "carbonmesh/remesh/point_grid.hpp"

namespace carbonmesh {

DisplacementTransfer transfer_displacements(Dual& fine, const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  if (from.size() != to.size()) throw std::invalid_argument("transfer_displacements: from and to differ in size");
  DisplacementTransfer r;
  if (from.empty() || fine.atoms() == 0) return r;
  constexpr std::size_t kNearest = 4;
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
      grid.nearest(p, kNearest, best);
      Vec3 d(0, 0, 0);
      double weights = 0;
      for (const auto& [d2, j] : best) {
        const double w = 1.0 / (d2 + 1e-12);
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

CoarseStartResult coarse_start(Dual& fine, const TriMesh& coarse_mesh, const TriMesh& surface,
                               const DualOptimizeSettings& settings) {
  Dual coarse = build_dual(coarse_mesh);
  const std::vector<Vec3> from = coarse.positions();
  DualOptimizeSettings doubled = settings;
  doubled.bond = 2 * settings.bond;
  doubled.bond_window = 2 * settings.bond_window;
  CoarseStartResult r;
  r.coarse_atoms = coarse.atoms();
  r.coarse = optimize_dual(coarse, surface, doubled);
  // Back to the unscaled frame: the optimisation put the atoms at c + s (y - c).
  std::vector<Vec3> to = coarse.positions();
  const Vec3 c = r.coarse.scale_centre;
  for (Vec3& p : to) p = c + (p - c) / r.coarse.surface_scale;
  r.transfer = transfer_displacements(fine, from, to);
  return r;
}

nlohmann::json to_json(const CoarseStartResult& r) {
  nlohmann::json j = to_json(r.coarse);
  j["coarse_atoms"] = r.coarse_atoms;
  j["fine_atoms_moved"] = r.transfer.atoms;
  j["mean_shift"] = r.transfer.mean_shift;
  j["max_shift"] = r.transfer.max_shift;
  return j;
}

}  // namespace carbonmesh
