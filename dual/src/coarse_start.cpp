#include "carbonmesh/dual/coarse_start.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "carbonmesh/remesh/cell_grid.hpp"

namespace carbonmesh {

DisplacementTransfer transfer_displacements(Dual& fine, const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  if (from.size() != to.size()) throw std::invalid_argument("transfer_displacements: from and to differ in size");
  DisplacementTransfer r;
  if (from.empty() || fine.atoms() == 0) return r;
  constexpr int kNearest = 4;
  // Cells sized by the grid's cap of one cell per coarse atom over the bounding box (on a surface several atoms
  // share an occupied cell); the search below grows cube shells of cells until the nearest are certain.
  std::vector<int> ids(from.size());
  std::iota(ids.begin(), ids.end(), 0);
  const CellGrid grid(from, ids, 0.0, static_cast<double>(from.size()));
  const auto& size = grid.size();
  std::vector<Vec3> positions = fine.positions();
  const long n = static_cast<long>(positions.size());
  std::vector<double> shift(positions.size(), 0.0);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    Vec3& p = positions[static_cast<std::size_t>(i)];
    // The kNearest coarse atoms: grow a cube of cells around p until it holds them and the cube's inner reach is
    // beyond the farthest kept one.
    std::array<std::pair<double, int>, kNearest> best;
    best.fill({std::numeric_limits<double>::infinity(), -1});
    const int c[3] = {grid.coordinate(p, 0), grid.coordinate(p, 1), grid.coordinate(p, 2)};
    const int widest = std::max({size[0], size[1], size[2]});
    for (int radius = 0; radius <= widest; ++radius) {
      for (int x = std::max(c[0] - radius, 0); x <= std::min(c[0] + radius, size[0] - 1); ++x)
        for (int y = std::max(c[1] - radius, 0); y <= std::min(c[1] + radius, size[1] - 1); ++y)
          for (int z = std::max(c[2] - radius, 0); z <= std::min(c[2] + radius, size[2] - 1); ++z) {
            if (std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])}) != radius) continue;
            const std::size_t cell = grid.cell_index(x, y, z);
            for (int k = grid.begin(cell); k < grid.begin(cell + 1); ++k) {
              const std::pair<double, int> candidate{(p - grid.point(k)).sqrnorm(), grid.id(k)};
              if (candidate < best.back()) {
                best.back() = candidate;
                std::sort(best.begin(), best.end());
              }
            }
          }
      // Every point not yet seen lies farther than radius cells from p's cell.
      const double reach = radius * grid.cell();
      if (best.back().second >= 0 && best.back().first <= reach * reach) break;
    }
    Vec3 d(0, 0, 0);
    double weights = 0;
    for (const auto& [d2, j] : best) {
      if (j < 0) continue;
      const double w = 1.0 / (d2 + 1e-12);
      d += w * (to[static_cast<std::size_t>(j)] - from[static_cast<std::size_t>(j)]);
      weights += w;
    }
    if (weights > 0) d /= weights;
    p += d;
    shift[static_cast<std::size_t>(i)] = d.norm();
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
