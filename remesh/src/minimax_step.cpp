// The linear program of one joint move of the minimax fit (minimax_step.hpp), solved with GLPK's simplex.
#include "minimax_step.hpp"

#include <glpk.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace carbonmesh {

namespace {

using Program = std::unique_ptr<glp_prob, decltype(&glp_delete_prob)>;

// The program's variables: each coordinate of d as p - q, p and q in [0, radius] (columns 2k + 1 and 2k + 2 of
// coordinate k = 3 vertex + axis), then t (column 6n + 1). Minimised: t + kMoveWeight (p + q) summed, so that of the
// displacements with the least largest distance the shortest (L1) is taken: a coordinate no row needs stays at 0,
// not at a corner of the box where the simplex would leave it (which moved bunny's surface off its fit: the RMS of its
// rigid motions up to 0.0338).
constexpr double kMoveWeight = 1e-5;

int p_column(std::size_t k) { return static_cast<int>(2 * k) + 1; }
int t_column(std::size_t vertices) { return static_cast<int>(6 * vertices) + 1; }

Program make_program(std::size_t vertices, double radius) {
  Program lp(glp_create_prob(), &glp_delete_prob);
  glp_set_obj_dir(lp.get(), GLP_MIN);
  const int t = t_column(vertices);
  glp_add_cols(lp.get(), t);
  for (int j = 1; j < t; ++j) {
    glp_set_col_bnds(lp.get(), j, GLP_DB, 0, radius);
    glp_set_obj_coef(lp.get(), j, kMoveWeight);
  }
  glp_set_col_bnds(lp.get(), t, GLP_FR, 0, 0);
  glp_set_obj_coef(lp.get(), t, 1);
  return lp;
}

// Rows value + g.(p - q) - t <= 0 (a distance) or lower <= value + g.(p - q) <= upper (a length); a vertex's terms
// are summed.
class RowWriter {
 public:
  explicit RowWriter(std::size_t vertices) : sum_(vertices, Vec3(0, 0, 0)), used_(vertices, 0) {
    index_.reserve(6 * vertices + 2);
    value_.reserve(6 * vertices + 2);
  }

  void distance(glp_prob* lp, const LinearRow& r) {
    gather(r);
    index_.push_back(t_column(sum_.size()));
    value_.push_back(-1);
    write(lp, GLP_UP, 0, -r.value);
  }

  void length(glp_prob* lp, const LinearRow& r, double lower, double upper) {
    gather(r);
    write(lp, GLP_DB, lower - r.value, upper - r.value);
  }

 private:
  void gather(const LinearRow& r) {
    index_.assign(1, 0);  // GLPK reads from position 1
    value_.assign(1, 0);
    for (const auto& [v, g] : r.terms) {
      if (!used_[v]) touched_.push_back(v);
      sum_[v] += g;
      used_[v] = 1;
    }
    std::sort(touched_.begin(), touched_.end());
    for (const std::size_t v : touched_) {
      for (int c = 0; c < 3; ++c)
        if (sum_[v][c] != 0) {
          const int p = p_column(3 * v + static_cast<std::size_t>(c));
          index_.insert(index_.end(), {p, p + 1});
          value_.insert(value_.end(), {sum_[v][c], -sum_[v][c]});
        }
      sum_[v] = Vec3(0, 0, 0);
      used_[v] = 0;
    }
    touched_.clear();
  }

  void write(glp_prob* lp, int type, double lb, double ub) {
    const int row = glp_add_rows(lp, 1);
    glp_set_mat_row(lp, row, static_cast<int>(index_.size()) - 1, index_.data(), value_.data());
    glp_set_row_bnds(lp, row, type, lb, ub);
  }

  std::vector<Vec3> sum_;
  std::vector<char> used_;
  std::vector<std::size_t> touched_;
  std::vector<int> index_;
  std::vector<double> value_;
};

bool finite(const std::vector<LinearRow>& rows) {
  for (const LinearRow& r : rows) {
    if (!std::isfinite(r.value)) return false;
    for (const auto& term : r.terms)
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(term.second[c])) return false;
  }
  return true;
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
  if (distances.empty() || vertices == 0 || !std::isfinite(radius) || !finite(distances) || !finite(lengths))
    return std::nullopt;  // (GLPK takes a row with a NaN or an infinity as given)
  // Cutting planes: the rows near the largest first, then, while the solution's prediction puts rows above its
  // largest, the kAdded most violated of them, added to the same program and solved again from the last basis (the
  // result is that of the whole program; most rows never bind).
  constexpr double kNear = 0.1;       // of the radius
  constexpr std::size_t kAdded = 16;  // rows a round at most
  double largest = 0;
  for (const LinearRow& r : distances) largest = std::max(largest, r.value);
  const Program lp = make_program(vertices, radius);
  RowWriter writer(vertices);
  for (const LinearRow& r : lengths) writer.length(lp.get(), r, lower, upper);
  std::vector<char> in(distances.size(), 0);  // the rows in the program
  for (std::size_t k = 0; k < distances.size(); ++k)
    if (distances[k].value >= largest - kNear * radius) {
      in[k] = 1;
      writer.distance(lp.get(), distances[k]);
    }
  glp_smcp parameters;
  glp_init_smcp(&parameters);
  parameters.msg_lev = GLP_MSG_OFF;
  parameters.meth = GLP_DUALP;  // after added rows the last basis stays dual feasible
  std::vector<Vec3> d(vertices);
  std::vector<std::pair<double, std::size_t>> violated;
  for (;;) {
    if (glp_simplex(lp.get(), &parameters) != 0 || glp_get_status(lp.get()) != GLP_OPT) return std::nullopt;
    for (std::size_t v = 0; v < vertices; ++v)
      for (int c = 0; c < 3; ++c) {
        const int p = p_column(3 * v + static_cast<std::size_t>(c));
        d[v][c] = glp_get_col_prim(lp.get(), p) - glp_get_col_prim(lp.get(), p + 1);
      }
    double t = 0;
    for (std::size_t k = 0; k < distances.size(); ++k)
      if (in[k]) t = std::max(t, predicted(distances[k], d));
    violated.clear();
    for (std::size_t k = 0; k < distances.size(); ++k) {
      if (in[k]) continue;
      const double x = predicted(distances[k], d);
      if (x > t) violated.emplace_back(-x, k);
    }
    if (violated.empty()) return d;
    const std::size_t n = std::min(kAdded, violated.size());
    std::partial_sort(violated.begin(), violated.begin() + static_cast<std::ptrdiff_t>(n), violated.end());
    for (std::size_t i = 0; i < n; ++i) {
      in[violated[i].second] = 1;
      writer.distance(lp.get(), distances[violated[i].second]);
    }
  }
}

}  // namespace carbonmesh
