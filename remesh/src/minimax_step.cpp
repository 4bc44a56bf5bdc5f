// The linear program of one joint move of the minimax fit (minimax_step.hpp).
#include "minimax_step.hpp"

#include <CGAL/Gmpzf.h>
#include <CGAL/QP_functions.h>
#include <CGAL/QP_models.h>

#include <algorithm>

namespace carbonmesh {

namespace {

// The linear program over the distance rows in `active` and every length row.
std::optional<std::vector<Vec3>> solve(const std::vector<LinearRow>& distances, const std::vector<std::size_t>& active,
                                       const std::vector<LinearRow>& lengths, double lower, double upper,
                                       std::size_t vertices, double radius) {
  // Variables: d (3 a vertex), then t. Rows: value + g.d - t <= 0; lower <= value + g.d <= upper.
  const int t = static_cast<int>(3 * vertices);
  CGAL::Quadratic_program<double> program(CGAL::SMALLER, true, -radius, true, radius);
  program.set_l(t, false);
  program.set_u(t, false);
  program.set_c(t, 1);
  int row = 0;
  std::vector<Vec3> sum(vertices);
  std::vector<char> used(vertices);
  auto add_terms = [&](const LinearRow& r) {  // (a vertex may have several terms: the solver keeps the last set)
    std::fill(sum.begin(), sum.end(), Vec3(0, 0, 0));
    std::fill(used.begin(), used.end(), 0);
    for (const auto& [v, g] : r.terms) {
      sum[v] += g;
      used[v] = 1;
    }
    for (std::size_t v = 0; v < vertices; ++v)
      if (used[v])
        for (int c = 0; c < 3; ++c)
          if (sum[v][c] != 0) program.set_a(static_cast<int>(3 * v) + c, row, sum[v][c]);
  };
  for (const std::size_t k : active) {
    add_terms(distances[k]);
    program.set_a(t, row, -1);
    program.set_b(row, -distances[k].value);
    ++row;
  }
  for (const LinearRow& r : lengths)
    for (const auto& [relation, bound] : {std::pair{CGAL::SMALLER, upper}, std::pair{CGAL::LARGER, lower}}) {
      add_terms(r);
      program.set_r(row, relation);
      program.set_b(row, bound - r.value);
      ++row;
    }
  const auto solution = CGAL::solve_linear_program(program, CGAL::Gmpzf());
  if (!solution.is_optimal()) return std::nullopt;
  std::vector<Vec3> d(vertices, Vec3(0, 0, 0));
  auto value = solution.variable_values_begin();
  for (std::size_t v = 0; v < vertices; ++v)
    for (int c = 0; c < 3; ++c, ++value) d[v][c] = CGAL::to_double(*value);
  return d;
}

double predicted(const LinearRow& r, const std::vector<Vec3>& d) {
  double x = r.value;
  for (const auto& [v, g] : r.terms) x += OpenMesh::dot(g, d[v]);
  return x;
}

}  // namespace

std::optional<std::vector<Vec3>> minimax_step(const std::vector<LinearRow>& distances,
                                              const std::vector<LinearRow>& lengths, double lower, double upper,
                                              std::size_t vertices, double radius) {
  if (distances.empty() || vertices == 0) return std::nullopt;
  // Cutting planes: the rows near the largest first, then, while the solution's prediction puts rows above its
  // largest, the kAdded most violated of them (the result is that of the whole program; most rows never bind).
  constexpr double kNear = 0.1;       // of the radius
  constexpr std::size_t kAdded = 16;  // rows a round at most
  double largest = 0;
  for (const LinearRow& r : distances) largest = std::max(largest, r.value);
  std::vector<std::size_t> active;
  std::vector<char> in(distances.size(), 0);
  for (std::size_t k = 0; k < distances.size(); ++k)
    if (distances[k].value >= largest - kNear * radius) {
      active.push_back(k);
      in[k] = 1;
    }
  std::vector<std::pair<double, std::size_t>> violated;
  for (;;) {
    auto d = solve(distances, active, lengths, lower, upper, vertices, radius);
    if (!d) return d;
    double t = 0;
    for (const std::size_t k : active) t = std::max(t, predicted(distances[k], *d));
    violated.clear();
    for (std::size_t k = 0; k < distances.size(); ++k) {
      if (in[k]) continue;
      const double x = predicted(distances[k], *d);
      if (x > t) violated.emplace_back(-x, k);
    }
    if (violated.empty()) return d;
    const std::size_t n = std::min(kAdded, violated.size());
    std::partial_sort(violated.begin(), violated.begin() + static_cast<std::ptrdiff_t>(n), violated.end());
    for (std::size_t i = 0; i < n; ++i) {
      active.push_back(violated[i].second);
      in[violated[i].second] = 1;
    }
  }
}

}  // namespace carbonmesh
