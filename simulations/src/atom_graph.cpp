#include "carbonmesh/simulations/atom_graph.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>

namespace carbonmesh {

AtomGraph make_atom_graph(std::size_t atoms, std::vector<Bond> bonds, std::vector<Vec3> positions) {
  if (!positions.empty() && positions.size() != atoms)
    throw std::invalid_argument("make_atom_graph: positions and atom count differ");
  const long n = static_cast<long>(atoms);
  for (auto& b : bonds) {
    if (b[0] < 0 || b[1] < 0 || b[0] >= n || b[1] >= n)
      throw std::invalid_argument("make_atom_graph: bond " + std::to_string(b[0]) + "-" + std::to_string(b[1]) +
                                  " out of range");
    if (b[0] > b[1]) std::swap(b[0], b[1]);
  }
  bonds.erase(std::remove_if(bonds.begin(), bonds.end(), [](const Bond& b) { return b[0] == b[1]; }), bonds.end());
  std::sort(bonds.begin(), bonds.end());
  bonds.erase(std::unique(bonds.begin(), bonds.end()), bonds.end());

  AtomGraph g;
  g.positions = std::move(positions);
  g.offsets.assign(atoms + 1, 0);
  for (const auto& b : bonds) {
    ++g.offsets[b[0] + 1];
    ++g.offsets[b[1] + 1];
  }
  std::partial_sum(g.offsets.begin(), g.offsets.end(), g.offsets.begin());
  g.adjacency.resize(2 * bonds.size());
  std::vector<int> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (const auto& b : bonds) {
    g.adjacency[fill[b[0]]++] = b[1];
    g.adjacency[fill[b[1]]++] = b[0];
  }
  for (std::size_t i = 0; i < atoms; ++i)
    std::sort(g.adjacency.begin() + g.offsets[i], g.adjacency.begin() + g.offsets[i + 1]);
  g.bonds = std::move(bonds);
  return g;
}

std::vector<Bond> bonds_by_cutoff(const std::vector<Vec3>& positions, double cutoff) {
  if (!(cutoff > 0) || !std::isfinite(cutoff)) throw std::invalid_argument("bonds_by_cutoff: cutoff must be positive");
  const std::size_t n = positions.size();
  if (n == 0) return {};
  Vec3 lo = positions[0];
  for (const auto& p : positions)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]);
  // Cells of side `cutoff`; atoms sorted by cell so that each cell is a contiguous range.
  using Cell = std::tuple<std::int64_t, std::int64_t, std::int64_t>;
  auto cell_of = [&](const Vec3& p) {
    return Cell{static_cast<std::int64_t>(std::floor((p[0] - lo[0]) / cutoff)),
                static_cast<std::int64_t>(std::floor((p[1] - lo[1]) / cutoff)),
                static_cast<std::int64_t>(std::floor((p[2] - lo[2]) / cutoff))};
  };
  std::vector<std::pair<Cell, int>> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = {cell_of(positions[i]), static_cast<int>(i)};
  std::sort(order.begin(), order.end());
  auto range_of = [&](const Cell& c) {
    auto first = std::lower_bound(order.begin(), order.end(), std::pair<Cell, int>{c, -1});
    auto last = first;
    while (last != order.end() && last->first == c) ++last;
    return std::pair{first, last};
  };
  const double cut2 = cutoff * cutoff;
  std::vector<Bond> bonds;
  std::size_t i = 0;
  while (i < n) {
    std::size_t j = i;
    while (j < n && order[j].first == order[i].first) ++j;
    const auto [cx, cy, cz] = order[i].first;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const Cell other{cx + dx, cy + dy, cz + dz};
          if (other < order[i].first) continue;  // each pair of cells once
          const bool same = (dx == 0 && dy == 0 && dz == 0);
          auto [first, last] = same ? std::pair{order.begin() + i, order.begin() + j} : range_of(other);
          for (std::size_t a = i; a < j; ++a)
            for (auto it = first; it != last; ++it) {
              const int u = order[a].second, v = it->second;
              if (same && u >= v) continue;
              if ((positions[u] - positions[v]).sqrnorm() < cut2) bonds.push_back({std::min(u, v), std::max(u, v)});
            }
        }
    i = j;
  }
  std::sort(bonds.begin(), bonds.end());
  return bonds;
}

}  // namespace carbonmesh
