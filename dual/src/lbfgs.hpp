#pragma once
// A small limited-memory BFGS minimiser with a backtracking (Armijo) line search. Internal to dual.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <deque>

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

// f(x, g) returns the energy at x and writes its gradient into g.
template <class Function>
LbfgsResult minimize_lbfgs(Eigen::VectorXd& x, Function&& f, const LbfgsSettings& settings) {
  LbfgsResult result;
  Eigen::VectorXd g(x.size()), g_new(x.size()), x_new(x.size()), d(x.size());
  double e = f(x, g);
  result.evaluations = 1;
  std::deque<Eigen::VectorXd> s_hist, y_hist;
  std::deque<double> rho_hist;
  std::deque<double> energies{e};  // the last energy_window + 1 energies
  for (int it = 0; it < settings.max_iterations; ++it) {
    result.gradient_max = x.size() ? g.cwiseAbs().maxCoeff() : 0.0;
    if (result.gradient_max < settings.gradient_tolerance) {
      result.converged = true;
      break;
    }
    // Two-loop recursion.
    d = -g;
    const std::size_t m = s_hist.size();
    std::vector<double> alpha(m);
    for (std::size_t k = m; k-- > 0;) {
      alpha[k] = rho_hist[k] * s_hist[k].dot(d);
      d -= alpha[k] * y_hist[k];
    }
    if (m > 0) d *= s_hist.back().dot(y_hist.back()) / y_hist.back().squaredNorm();
    for (std::size_t k = 0; k < m; ++k) {
      const double beta = rho_hist[k] * y_hist[k].dot(d);
      d += (alpha[k] - beta) * s_hist[k];
    }
    double slope = g.dot(d);
    if (!(slope < 0)) {  // not a descent direction: restart from steepest descent
      s_hist.clear(), y_hist.clear(), rho_hist.clear();
      d = -g;
      slope = g.dot(d);
    }
    double step = 1.0;
    const double largest = d.cwiseAbs().maxCoeff();
    if (largest * step > settings.max_step) step = settings.max_step / largest;
    bool accepted = false;
    double e_new = e;
    for (int trial = 0; trial < 50; ++trial) {
      x_new = x + step * d;
      e_new = f(x_new, g_new);
      ++result.evaluations;
      if (e_new <= e + 1e-4 * step * slope) {
        accepted = true;
        break;
      }
      step *= 0.5;
    }
    if (!accepted) {
      if (s_hist.empty()) break;  // even steepest descent fails: at the precision limit
      s_hist.clear(), y_hist.clear(), rho_hist.clear();
      continue;
    }
    Eigen::VectorXd s = x_new - x, y = g_new - g;
    const double sy = s.dot(y);
    if (sy > 1e-12 * y.squaredNorm()) {
      s_hist.push_back(std::move(s));
      y_hist.push_back(std::move(y));
      rho_hist.push_back(1.0 / sy);
      if (static_cast<int>(s_hist.size()) > settings.memory) {
        s_hist.pop_front(), y_hist.pop_front(), rho_hist.pop_front();
      }
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
  result.gradient_max = x.size() ? g.cwiseAbs().maxCoeff() : 0.0;
  if (result.gradient_max < settings.gradient_tolerance) result.converged = true;
  return result;
}

}  // namespace carbonmesh::detail
