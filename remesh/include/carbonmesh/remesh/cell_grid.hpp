#pragma once
// Points bucketed into a uniform grid of cubic cells: the spatial index of the projection's k-nearest search
// (remesh/src/projection.cpp) and of the dual optimisation's contact pairs (dual/src/contact_term.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

class CellGrid {
 public:
  CellGrid() = default;
  // The points `points[id]` for the ids in `ids` (ascending), in cells of side `cell`, enlarged by a factor
  // 1.25 until the grid has at most `max_cells` cells. Within a cell the points keep the order of `ids`.
  CellGrid(const std::vector<Vec3>& points, const std::vector<int>& ids, double cell, double max_cells) {
    if (ids.empty()) return;
    Vec3 lo = points[static_cast<std::size_t>(ids[0])], hi = lo;
    for (int i : ids) lo.minimize(points[static_cast<std::size_t>(i)]), hi.maximize(points[static_cast<std::size_t>(i)]);
    const double largest = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300});
    cell_ = cell > largest * 1e-6 ? cell : largest * 1e-3;  // also for a NaN or zero cell
    for (;; cell_ *= 1.25) {
      double cells = 1;
      for (int a = 0; a < 3; ++a) cells *= size_[a] = static_cast<int>((hi[a] - lo[a]) / cell_) + 1;
      if (cells <= max_cells) break;
    }
    origin_ = lo;
    begin_.assign(static_cast<std::size_t>(size_[0]) * size_[1] * size_[2] + 1, 0);
    std::vector<std::size_t> cell_of(ids.size());
    for (std::size_t j = 0; j < ids.size(); ++j)
      ++begin_[(cell_of[j] = cell_index(points[static_cast<std::size_t>(ids[j])])) + 1];
    for (std::size_t c = 0; c + 1 < begin_.size(); ++c) begin_[c + 1] += begin_[c];
    ids_.resize(ids.size());
    points_.resize(ids.size());
    std::vector<int> fill(begin_.begin(), begin_.end() - 1);
    for (std::size_t j = 0; j < ids.size(); ++j) {
      const auto at = static_cast<std::size_t>(fill[cell_of[j]]++);
      ids_[at] = ids[j];
      points_[at] = points[static_cast<std::size_t>(ids[j])];
    }
  }

  bool empty() const { return ids_.empty(); }
  double cell() const { return cell_; }
  const Vec3& origin() const { return origin_; }
  const std::array<int, 3>& size() const { return size_; }

  // The cell coordinate of p along `axis`, clamped to the grid (0 for NaN).
  int coordinate(const Vec3& p, int axis) const {
    const double x = std::floor((p[axis] - origin_[axis]) / cell_);
    if (!(x > 0)) return 0;
    return x >= size_[axis] - 1 ? size_[axis] - 1 : static_cast<int>(x);
  }
  std::size_t cell_index(int x, int y, int z) const {
    return (static_cast<std::size_t>(x) * static_cast<std::size_t>(size_[1]) + static_cast<std::size_t>(y)) *
               static_cast<std::size_t>(size_[2]) + static_cast<std::size_t>(z);
  }
  std::size_t cell_index(const Vec3& p) const { return cell_index(coordinate(p, 0), coordinate(p, 1), coordinate(p, 2)); }

  // The entries of cell c are begin(c) .. begin(c + 1) - 1: id(j) and point(j).
  int begin(std::size_t c) const { return begin_[c]; }
  int id(int j) const { return ids_[static_cast<std::size_t>(j)]; }
  const Vec3& point(int j) const { return points_[static_cast<std::size_t>(j)]; }

 private:
  Vec3 origin_{0, 0, 0};
  double cell_ = 1;
  std::array<int, 3> size_{0, 0, 0};
  std::vector<int> begin_, ids_;  // CSR: the points of each cell
  std::vector<Vec3> points_;      // their positions, in the same order
};

}  // namespace carbonmesh
