#pragma once
// Exact k-nearest-neighbour search over a point set: the projection's candidate vertices (remesh/src/projection.cpp)
// and the coarse atoms of the dual optimisation's coarse start (dual/src/coarse_start.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/cell_grid.hpp"

namespace carbonmesh {

// Exact k nearest neighbours among points in a uniform grid of cells (CellGrid), rings of cells around the
// query's cell searched until no unvisited cell can hold a nearer point. Squared distances are summed as in
// CGAL's Euclidean_distance (x, then y, then z), so the neighbours are the ones of the kd-tree used before
// (exact ties to the smaller index); the grid visits about 27 cells per query instead of a tree descent with
// a priority queue.
class PointGrid {
 public:
  // (distance, index) pairs in ascending order; cheaper than std::pair's synthesised three-way comparison.
  static bool before(const std::pair<double, int>& a, const std::pair<double, int>& b) {
    return a.first < b.first || (a.first == b.first && a.second < b.second);
  }

  // The squared distance the search orders by (the same sums wherever it is compared).
  static double squared_distance(const Vec3& q, const Vec3& p) {
    double d = (q[0] - p[0]) * (q[0] - p[0]);
    d += (q[1] - p[1]) * (q[1] - p[1]);
    d += (q[2] - p[2]) * (q[2] - p[2]);
    return d;
  }

  // The points `points[id]` for the ids in `used` (ascending), cells as in CellGrid (side `cell`, at most about
  // `max_cells`). The projection uses cells of two mean edges.
  PointGrid(const std::vector<Vec3>& points, const std::vector<int>& used, double cell, double max_cells)
      : grid_(points, used, cell, max_cells) {}

  // The min(k, points) nearest points to q as (squared distance, index), ascending.
  void nearest(const Vec3& q, std::size_t k, std::vector<std::pair<double, int>>& out) const {
    out.clear();
    if (grid_.empty() || k == 0) return;
    std::array<int, 3> c{};
    for (int a = 0; a < 3; ++a) c[a] = grid_.coordinate(q, a);
    for (int r = 0;; ++r) {
      visit_ring(q, c, r, k, out);
      const double bound = unvisited_distance(q, c, r);
      if (bound == std::numeric_limits<double>::infinity()) return;  // every cell visited
      if (out.size() == k && out.back().first < bound * bound) return;
    }
  }

 private:
  CellGrid grid_;

  // The points of cells at Chebyshev distance r from cell c into the ascending list `out` of at most k.
  void visit_ring(const Vec3& q, const std::array<int, 3>& c, int r, std::size_t k,
                  std::vector<std::pair<double, int>>& out) const {
    const auto& size = grid_.size();
    const int x0 = std::max(0, c[0] - r), x1 = std::min(size[0] - 1, c[0] + r);
    const int y0 = std::max(0, c[1] - r), y1 = std::min(size[1] - 1, c[1] + r);
    for (int x = x0; x <= x1; ++x)
      for (int y = y0; y <= y1; ++y) {
        const bool side = std::abs(x - c[0]) == r || std::abs(y - c[1]) == r;
        const int step = side || r == 0 ? 1 : 2 * r;
        for (int z = c[2] - r; z <= c[2] + r; z += step) {
          if (z < 0 || z >= size[2]) continue;
          const std::size_t id = grid_.cell_index(x, y, z);
          for (int j = grid_.begin(id); j < grid_.begin(id + 1); ++j) insert(q, j, k, out);
        }
      }
  }

  void insert(const Vec3& q, int j, std::size_t k, std::vector<std::pair<double, int>>& out) const {
    const std::pair<double, int> entry(squared_distance(q, grid_.point(j)), grid_.id(j));
    if (out.size() == k) {
      if (!before(entry, out.back())) return;
    } else {
      out.push_back(entry);
    }
    std::size_t i = out.size() - 1;  // insertion from the back (k is small)
    for (; i > 0 && before(entry, out[i - 1]); --i) out[i] = out[i - 1];
    out[i] = entry;
  }

  // A lower bound of the distance from q to the cells outside the block of rings 0..r around c (infinity when
  // the block covers the grid), slightly shrunk against rounding in the cell coordinates.
  double unvisited_distance(const Vec3& q, const std::array<int, 3>& c, int r) const {
    const auto& size = grid_.size();
    const Vec3& origin = grid_.origin();
    const double cell = grid_.cell();
    double bound = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (c[a] - r > 0) bound = std::min(bound, q[a] - (origin[a] + (c[a] - r) * cell));
      if (c[a] + r < size[a] - 1) bound = std::min(bound, origin[a] + (c[a] + r + 1) * cell - q[a]);
    }
    return bound == std::numeric_limits<double>::infinity() ? bound : std::max(0.0, bound - 1e-9 * cell);
  }
};

}  // namespace carbonmesh
