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
  double initial_energy = 0;  // f at the start
  double energy = 0;
  double gradient_max = 0;
};

// Passes over the minimiser's long vectors, parallel (OpenMP) with results that do not depend on the thread
// count: a pass runs body(begin, size, sums) on fixed chunks, and the chunks' sums are added in chunk order
// (their maxima combined). Short vectors go in one chunk. Each pass fuses the updates and the dot products that
// follow them, so that an iteration reads the vectors about half as often as with one loop per operation (at a
// million atoms a vector is 24 MB and the passes are bound by memory).
namespace lbfgs_kernels {

constexpr Eigen::Index kChunk = 16384;
constexpr Eigen::Index kParallelSize = 60000;  // 20000 atoms

struct Sums {
  double sum = 0;
  double sum2 = 0;
  double max = 0;
};

template <class Body>
Sums pass(Eigen::Index n, Body&& body) {
  Sums total;
  if (n < kParallelSize) {
    body(Eigen::Index{0}, n, total);
    return total;
  }
  const Eigen::Index chunks = (n + kChunk - 1) / kChunk;
  std::vector<Sums> partial(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(static)
  for (Eigen::Index c = 0; c < chunks; ++c) {
    const Eigen::Index begin = c * kChunk;
    body(begin, std::min(kChunk, n - begin), partial[static_cast<std::size_t>(c)]);
  }
  for (const Sums& p : partial) {
    total.sum += p.sum;
    total.sum2 += p.sum2;
    total.max = std::max(total.max, p.max);
  }
  return total;
}

}  // namespace lbfgs_kernels

// f(x, g) returns the energy at x and writes its gradient into g.
template <class Function>
LbfgsResult minimize_lbfgs(Eigen::VectorXd& x, Function&& f, const LbfgsSettings& settings) {
  using lbfgs_kernels::pass;
  using lbfgs_kernels::Sums;
  using Index = Eigen::Index;
  LbfgsResult result;
  const Index n = x.size();
  Eigen::VectorXd g(n), g_new(n), x_new(n), d(n), s_new(n), y_new(n);
  double e = f(x, g);
  result.evaluations = 1;
  result.initial_energy = e;
  auto max_abs = [](const Eigen::VectorXd& a) {
    return pass(a.size(), [&](Index i, Index k, Sums& s) {
             if (k > 0) s.max = a.segment(i, k).cwiseAbs().maxCoeff();
           }).max;
  };
  // The last `memory` pairs s = x_k+1 - x_k, y = g_k+1 - g_k in a ring of preallocated vectors (no allocation per
  // iteration: at a million atoms a fresh pair is 2 x 24 MB of page faults); pair k (0 = oldest) is at
  // (first + k) % memory, with rho = 1 / s.y and y.y.
  const std::size_t capacity = static_cast<std::size_t>(std::max(settings.memory, 1));
  std::vector<Eigen::VectorXd> s_hist(capacity, Eigen::VectorXd(n)), y_hist(capacity, Eigen::VectorXd(n));
  std::vector<double> rho_hist(capacity), yy_hist(capacity), alpha(capacity);
  std::size_t first = 0, m = 0;
  auto slot = [&](std::size_t k) { return (first + k) % capacity; };
  std::deque<double> energies{e};  // the last energy_window + 1 energies
  result.gradient_max = max_abs(g);
  for (int it = 0; it < settings.max_iterations; ++it) {
    if (result.gradient_max < settings.gradient_tolerance) {
      result.converged = true;
      break;
    }
    // Two-loop recursion: d = -H g. Every pass updates d and takes the dot product the next step needs; the
    // last gives the slope g.d and the largest component of d.
    Sums last;
    if (m == 0) {
      last = pass(n, [&](Index i, Index k, Sums& s) {
        d.segment(i, k) = -g.segment(i, k);
        s.sum = g.segment(i, k).dot(d.segment(i, k));
        if (k > 0) s.max = d.segment(i, k).cwiseAbs().maxCoeff();
      });
    } else {
      std::size_t j = slot(m - 1);
      double dot = pass(n, [&](Index i, Index k, Sums& s) {
                     d.segment(i, k) = -g.segment(i, k);
                     s.sum = s_hist[j].segment(i, k).dot(d.segment(i, k));
                   }).sum;
      const double gamma = 1.0 / (rho_hist[slot(m - 1)] * yy_hist[slot(m - 1)]);  // s.y / y.y of the newest pair
      for (std::size_t k = m; k-- > 0;) {
        j = slot(k);
        alpha[k] = rho_hist[j] * dot;
        const double a = alpha[k];
        const Eigen::VectorXd& y = y_hist[j];
        // After the last pair of the first loop d is scaled by gamma and the second loop's first dot is taken.
        const Eigen::VectorXd& next = k > 0 ? s_hist[slot(k - 1)] : y_hist[slot(0)];
        dot = pass(n, [&](Index i, Index c, Sums& s) {
                d.segment(i, c) -= a * y.segment(i, c);
                if (k == 0) d.segment(i, c) *= gamma;
                s.sum = next.segment(i, c).dot(d.segment(i, c));
              }).sum;
      }
      for (std::size_t k = 0; k < m; ++k) {
        j = slot(k);
        const double factor = alpha[k] - rho_hist[j] * dot;
        const Eigen::VectorXd& sv = s_hist[j];
        const bool final = k + 1 == m;
        const Eigen::VectorXd& next = final ? g : y_hist[slot(k + 1)];
        last = pass(n, [&](Index i, Index c, Sums& s) {
          d.segment(i, c) += factor * sv.segment(i, c);
          s.sum = next.segment(i, c).dot(d.segment(i, c));
          if (final && c > 0) s.max = d.segment(i, c).cwiseAbs().maxCoeff();
        });
        dot = last.sum;
      }
    }
    double slope = last.sum, largest = last.max;
    if (!(slope < 0)) {  // not a descent direction: restart from steepest descent
      m = 0;
      last = pass(n, [&](Index i, Index k, Sums& s) {
        d.segment(i, k) = -g.segment(i, k);
        s.sum = g.segment(i, k).dot(d.segment(i, k));
        if (k > 0) s.max = d.segment(i, k).cwiseAbs().maxCoeff();
      });
      slope = last.sum, largest = last.max;
    }
    double step = 1.0;
    if (largest * step > settings.max_step) step = settings.max_step / largest;
    bool accepted = false;
    double e_new = e;
    for (int trial = 0; trial < 50; ++trial) {
      pass(n, [&](Index i, Index k, Sums&) { x_new.segment(i, k) = x.segment(i, k) + step * d.segment(i, k); });
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
    // The new pair with s.y, y.y and the largest component of the new gradient in one pass; kept when s.y > 0,
    // in the next free slot (over the oldest pair once the ring is full).
    const Sums pair = pass(n, [&](Index i, Index k, Sums& s) {
      s_new.segment(i, k) = x_new.segment(i, k) - x.segment(i, k);
      y_new.segment(i, k) = g_new.segment(i, k) - g.segment(i, k);
      s.sum = s_new.segment(i, k).dot(y_new.segment(i, k));
      s.sum2 = y_new.segment(i, k).squaredNorm();
      if (k > 0) s.max = g_new.segment(i, k).cwiseAbs().maxCoeff();
    });
    if (pair.sum > 1e-12 * pair.sum2) {
      const std::size_t j = m < capacity ? slot(m) : first;
      s_hist[j].swap(s_new);
      y_hist[j].swap(y_new);
      rho_hist[j] = 1.0 / pair.sum;
      yy_hist[j] = pair.sum2;
      if (m < capacity) ++m;
      else first = (first + 1) % capacity;
    }
    result.gradient_max = pair.max;
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
  result.gradient_max = max_abs(g);
  if (result.gradient_max < settings.gradient_tolerance) result.converged = true;
  return result;
}

}  // namespace carbonmesh::detail
