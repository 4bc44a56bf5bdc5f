#pragma once
// A small limited-memory BFGS minimiser with a backtracking (Armijo) line search. Internal to dual.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <deque>
#include <vector>

namespace carbonmesh::detail {

struct LbfgsSettings {
  int max_iterations = 1000;
  int memory = 8;
  double gradient_tolerance = 1e-6;  // on the largest gradient component
  double max_step = 0.2;             // largest move of one coordinate in one line search trial
  // Also converged when the energy fell by less than energy_tolerance * |E| over the last energy_window
  // iterations (0: off): the tail of a stiff problem polishes little for many iterations.
  double energy_tolerance = 0;
  int energy_window = 10;
};

struct LbfgsResult {
  int iterations = 0;
  int evaluations = 0;  // calls of f
  bool converged = false;
  double energy = 0;
  double gradient_max = 0;
};

// Vector kernels of the minimiser, parallel (OpenMP) for long vectors with results that do not depend on the
// thread count: a dot product is the sum, in chunk order, of Eigen dot products over fixed chunks.
namespace lbfgs_kernels {

constexpr Eigen::Index kChunk = 16384;
constexpr Eigen::Index kParallelSize = 60000;  // 20000 atoms

inline double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::Index n = a.size();
  if (n < kParallelSize) return a.dot(b);
  const Eigen::Index chunks = (n + kChunk - 1) / kChunk;
  std::vector<double> partial(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(static)
  for (Eigen::Index c = 0; c < chunks; ++c) {
    const Eigen::Index begin = c * kChunk, size = std::min(kChunk, n - begin);
    partial[static_cast<std::size_t>(c)] = a.segment(begin, size).dot(b.segment(begin, size));
  }
  double sum = 0;
  for (double p : partial) sum += p;
  return sum;
}

// out = a + f * b (out may be a or b).
inline void axpy(Eigen::VectorXd& out, const Eigen::VectorXd& a, double f, const Eigen::VectorXd& b) {
  const Eigen::Index n = a.size();
  out.resize(n);
  if (n < kParallelSize) {
    out = a + f * b;
    return;
  }
  const Eigen::Index chunks = (n + kChunk - 1) / kChunk;
#pragma omp parallel for schedule(static)
  for (Eigen::Index c = 0; c < chunks; ++c) {
    const Eigen::Index begin = c * kChunk, size = std::min(kChunk, n - begin);
    out.segment(begin, size) = a.segment(begin, size) + f * b.segment(begin, size);
  }
}

inline double max_abs(const Eigen::VectorXd& a) {
  if (a.size() == 0) return 0.0;
  if (a.size() < kParallelSize) return a.cwiseAbs().maxCoeff();
  double m = 0;
#pragma omp parallel for schedule(static) reduction(max : m)
  for (Eigen::Index i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i]));
  return m;  // a maximum does not depend on the order
}

}  // namespace lbfgs_kernels

// f(x, g) returns the energy at x and writes its gradient into g.
template <class Function>
LbfgsResult minimize_lbfgs(Eigen::VectorXd& x, Function&& f, const LbfgsSettings& settings) {
  LbfgsResult result;
  Eigen::VectorXd g(x.size()), g_new(x.size()), x_new(x.size()), d(x.size());
  double e = f(x, g);
  result.evaluations = 1;
  // The last `memory` pairs s = x_k+1 - x_k, y = g_k+1 - g_k in a ring of preallocated vectors (no allocation per
  // iteration: at a million atoms a fresh pair is 2 x 24 MB of page faults); pair k (0 = oldest) is at
  // (first + k) % memory.
  const std::size_t capacity = static_cast<std::size_t>(std::max(settings.memory, 1));
  std::vector<Eigen::VectorXd> s_hist(capacity, Eigen::VectorXd(x.size())), y_hist(capacity, Eigen::VectorXd(x.size()));
  std::vector<double> rho_hist(capacity), alpha(capacity);
  std::size_t first = 0, m = 0;
  auto slot = [&](std::size_t k) { return (first + k) % capacity; };
  std::deque<double> energies{e};  // the last energy_window + 1 energies
  using namespace lbfgs_kernels;
  Eigen::VectorXd s_new(x.size()), y_new(x.size());
  for (int it = 0; it < settings.max_iterations; ++it) {
    result.gradient_max = max_abs(g);
    if (result.gradient_max < settings.gradient_tolerance) {
      result.converged = true;
      break;
    }
    // Two-loop recursion.
    d = -g;
    for (std::size_t k = m; k-- > 0;) {
      const std::size_t j = slot(k);
      alpha[k] = rho_hist[j] * dot(s_hist[j], d);
      axpy(d, d, -alpha[k], y_hist[j]);
    }
    if (m > 0) {
      const std::size_t j = slot(m - 1);
      d *= dot(s_hist[j], y_hist[j]) / dot(y_hist[j], y_hist[j]);
    }
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t j = slot(k);
      const double beta = rho_hist[j] * dot(y_hist[j], d);
      axpy(d, d, alpha[k] - beta, s_hist[j]);
    }
    double slope = dot(g, d);
    if (!(slope < 0)) {  // not a descent direction: restart from steepest descent
      m = 0;
      d = -g;
      slope = dot(g, d);
    }
    double step = 1.0;
    const double largest = max_abs(d);
    if (largest * step > settings.max_step) step = settings.max_step / largest;
    bool accepted = false;
    double e_new = e;
    for (int trial = 0; trial < 50; ++trial) {
      axpy(x_new, x, step, d);
      e_new = f(x_new, g_new);
      ++result.evaluations;
      if (e_new <= e + 1e-4 * step * slope) {
        accepted = true;
        break;
      }
      step *= 0.5;
    }
    if (!accepted) {
      if (m == 0) break;  // even steepest descent fails: at the precision limit
      m = 0;
      continue;
    }
    // The new pair, when s.y > 0, goes into the next free slot (over the oldest pair once the ring is full).
    axpy(s_new, x_new, -1.0, x);
    axpy(y_new, g_new, -1.0, g);
    const double sy = dot(s_new, y_new);
    if (sy > 1e-12 * dot(y_new, y_new)) {
      const std::size_t j = m < capacity ? slot(m) : first;
      s_hist[j].swap(s_new);
      y_hist[j].swap(y_new);
      rho_hist[j] = 1.0 / sy;
      if (m < capacity) ++m;
      else first = (first + 1) % capacity;
    }
    x.swap(x_new);
    g.swap(g_new);
    e = e_new;
    result.iterations = it + 1;
    if (settings.energy_tolerance > 0) {
      energies.push_back(e);
      if (static_cast<int>(energies.size()) > settings.energy_window + 1) energies.pop_front();
      if (static_cast<int>(energies.size()) == settings.energy_window + 1 &&
          energies.front() - e <= settings.energy_tolerance * std::abs(e)) {
        result.converged = true;
        break;
      }
    }
  }
  result.energy = e;
  result.gradient_max = lbfgs_kernels::max_abs(g);
  if (result.gradient_max < settings.gradient_tolerance) result.converged = true;
  return result;
}

}  // namespace carbonmesh::detail
