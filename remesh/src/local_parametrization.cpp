// Sections 3.6 and 4.3.1: k-stars and their Floater parametrization onto a disk.
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/LU>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include "carbonmesh/remesh/remesh_steps.hpp"
#include "remesh_geometry.hpp"
#include "small_lu.hpp"

namespace carbonmesh {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kDenseLimit = 40;  // unknowns up to which the Floater system is solved with a dense LU

double angle_between(const Vec3& u, const Vec3& v) {
  const double lu = u.norm(), lv = v.norm();
  if (lu <= 0 || lv <= 0) return 0;
  return std::acos(std::clamp(OpenMesh::dot(u, v) / (lu * lv), -1.0, 1.0));
}

// Mean value weights (Eq 3.4-3.5): wp_ij = (tan(alpha_{j-1}/2) + tan(alpha_j/2)) / |v_j - v_i|.
void mean_value_weights(const Vec3& center, const std::vector<Vec3>& ring, std::vector<double>& lambda) {
  const std::size_t d = ring.size();
  // tan(alpha/2) = |u x v| / (|u| |v| + u . v), without trigonometric calls.
  double half_tan[64];
  double length[64];
  if (d > 64) return;
  for (std::size_t j = 0; j < d; ++j) length[j] = std::max((ring[j] - center).norm(), 1e-300);
  for (std::size_t j = 0; j < d; ++j) {
    const Vec3 u = ring[j] - center, v = ring[(j + 1) % d] - center;
    const double denominator = length[j] * length[(j + 1) % d] + OpenMesh::dot(u, v);
    half_tan[j] = OpenMesh::cross(u, v).norm() / std::max(denominator, 1e-300);
  }
  double sum = 0;
  for (std::size_t j = 0; j < d; ++j) {
    lambda[j] = (half_tan[(j + d - 1) % d] + half_tan[j]) / length[j];
    sum += lambda[j];
  }
  for (auto& l : lambda) l /= sum;  // Eq 3.4
}

// Barycentric coordinates of the origin in the 2D triangle (a, b, c).
bool origin_barycentric(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, double& la,
                        double& lb, double& lc) {
  const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
  if (std::abs(det) < 1e-300) return false;
  lb = ((-a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (-a.y())) / det;
  lc = ((b.x() - a.x()) * (-a.y()) - (-a.x()) * (b.y() - a.y())) / det;
  la = 1 - lb - lc;
  return true;
}

// Floater's shape-preserving weights (1997): the 1-ring is flattened by a polar map keeping lengths and
// angle proportions, then the barycentric coordinates of the centre in the triangles (q_l, q_r, q_r+1)
// containing it are averaged over l.
void shape_preserving_weights(const Vec3& center, const std::vector<Vec3>& ring, std::vector<double>& lambda) {
  const std::size_t d = ring.size();
  std::vector<double> theta(d);
  double total = 0;
  for (std::size_t j = 0; j < d; ++j) total += theta[j] = angle_between(ring[j] - center, ring[(j + 1) % d] - center);
  std::vector<Eigen::Vector2d> q(d);
  double phi = 0;
  for (std::size_t j = 0; j < d; ++j) {
    const double r = (ring[j] - center).norm();
    q[j] = Eigen::Vector2d(r * std::cos(phi), r * std::sin(phi));
    phi += 2 * kPi * theta[j] / (total > 0 ? total : 1);
  }
  std::fill(lambda.begin(), lambda.end(), 0.0);
  for (std::size_t l = 0; l < d; ++l) {
    double best = -1e300, bl = 0, br = 0, bs = 0;
    std::size_t best_r = d;
    for (std::size_t k = 1; k + 1 < d; ++k) {
      const std::size_t r = (l + k) % d, s = (l + k + 1) % d;
      double a, b, c;
      if (!origin_barycentric(q[l], q[r], q[s], a, b, c)) continue;
      const double worst = std::min({a, b, c});
      if (worst > best) best = worst, bl = a, br = b, bs = c, best_r = r;
    }
    if (best_r == d) continue;
    lambda[l] += bl;
    lambda[best_r] += br;
    lambda[(best_r + 1) % d] += bs;
  }
  double sum = 0;
  for (auto& x : lambda) sum += x = std::max(x, 0.0);
  if (sum <= 0) {
    std::fill(lambda.begin(), lambda.end(), 1.0 / static_cast<double>(d));
    return;
  }
  for (auto& x : lambda) x /= sum;
}

}  // namespace

RingWeights ring_weights(const TriMesh& mesh, ParametrizationWeights weights) {
  const std::size_t n = mesh.n_vertices();
  RingWeights r;
  r.begin.assign(n + 1, 0);
  r.valid.assign(n, 0);
  const int count = static_cast<int>(n);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < count; ++i) {  // each vertex's count, then their sums
    const TriMesh::VertexHandle v(i);
    const bool use = !mesh.status(v).deleted() && !mesh.is_isolated(v) && !mesh.is_boundary(v);
    r.begin[static_cast<std::size_t>(i) + 1] = use ? geometry::valence(mesh, v) : 0;
  }
  for (std::size_t i = 0; i < n; ++i) r.begin[i + 1] += r.begin[i];
  r.ring.resize(static_cast<std::size_t>(r.begin[n]));
  r.lambda.resize(r.ring.size());
#pragma omp parallel
  {
    std::vector<Vec3> ring;
    std::vector<double> lambda;
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < count; ++i) {
      const std::size_t b = static_cast<std::size_t>(r.begin[static_cast<std::size_t>(i)]);
      const std::size_t e = static_cast<std::size_t>(r.begin[static_cast<std::size_t>(i) + 1]);
      if (e == b) continue;
      const TriMesh::VertexHandle v(i);
      ring.clear();
      std::size_t k = b;
      for (auto w : mesh.vv_range(v)) {
        r.ring[k++] = w.idx();
        ring.push_back(mesh.point(w));
      }
      if (ring.size() < 3 || ring.size() > 64) continue;
      lambda.assign(ring.size(), 0.0);
      if (weights == ParametrizationWeights::MeanValue)
        mean_value_weights(mesh.point(v), ring, lambda);
      else
        shape_preserving_weights(mesh.point(v), ring, lambda);
      std::copy(lambda.begin(), lambda.end(), r.lambda.begin() + static_cast<std::ptrdiff_t>(b));
      r.valid[static_cast<std::size_t>(i)] = 1;
    }
  }
  return r;
}

StarScratch::StarScratch(const TriMesh& mesh)
    : vertex_mark(mesh.n_vertices(), 0), face_mark(mesh.n_faces(), 0), local(mesh.n_vertices(), -1) {}

void collect_k_star(const TriMesh& mesh, TriMesh::VertexHandle v, int k, KStar& star, StarScratch& s) {
  ++s.stamp;
  star.vertices.clear();
  star.ring.clear();
  star.faces.clear();
  auto visit = [&](TriMesh::VertexHandle w, int r) {
    s.vertex_mark[static_cast<std::size_t>(w.idx())] = s.stamp;
    s.local[static_cast<std::size_t>(w.idx())] = static_cast<int>(star.vertices.size());
    star.vertices.push_back(w);
    star.ring.push_back(r);
  };
  visit(v, 0);
  std::size_t begin = 0;
  for (int r = 1; r <= k; ++r) {
    const std::size_t end = star.vertices.size();
    for (std::size_t i = begin; i < end; ++i)
      geometry::for_each_outgoing(mesh, star.vertices[i], [&](TriMesh::HalfedgeHandle h) {
        const auto w = mesh.to_vertex_handle(h);
        if (s.vertex_mark[static_cast<std::size_t>(w.idx())] != s.stamp) visit(w, r);
      });
    begin = end;
  }
  for (std::size_t i = 0; i < star.vertices.size(); ++i) {
    if (star.ring[i] >= k) break;  // rings are appended in order
    geometry::for_each_outgoing(mesh, star.vertices[i], [&](TriMesh::HalfedgeHandle h) {
      const auto f = mesh.face_handle(h);
      if (!f.is_valid()) return;
      auto& mark = s.face_mark[static_cast<std::size_t>(f.idx())];
      if (mark != s.stamp) {
        mark = s.stamp;
        star.faces.push_back(f);
      }
    });
  }
}

bool compute_parametrization(const TriMesh& mesh, const KStar& star, ParametrizationWeights weights,
                             StarScratch& s, std::vector<Eigen::Vector2d>& uv) {
  const std::size_t n = star.vertices.size();
  if (n < 4 || star.faces.empty()) return false;
  auto local = [&](TriMesh::VertexHandle w) { return s.local[static_cast<std::size_t>(w.idx())]; };
  auto in_star_face = [&](TriMesh::FaceHandle f) {
    return f.is_valid() && s.face_mark[static_cast<std::size_t>(f.idx())] == s.stamp;
  };
  // Region border: half-edges of star faces whose opposite face is outside the star.
  thread_local std::vector<int> next_on_border;
  next_on_border.assign(n, -1);
  std::size_t border_edges = 0;
  for (auto f : star.faces) {
    for (auto h : mesh.fh_range(f)) {
      if (in_star_face(mesh.face_handle(mesh.opposite_halfedge_handle(h)))) continue;
      const int from = local(mesh.from_vertex_handle(h)), to = local(mesh.to_vertex_handle(h));
      if (from < 0 || to < 0 || next_on_border[static_cast<std::size_t>(from)] >= 0) return false;  // pinched
      next_on_border[static_cast<std::size_t>(from)] = to;
      ++border_edges;
    }
  }
  if (border_edges < 3 || next_on_border[0] >= 0) return false;  // the centre must be inside
  // A disk: one border loop and Euler characteristic 1 (V - E + F with E = (3F + B) / 2).
  const long faces = static_cast<long>(star.faces.size());
  if ((3 * faces + static_cast<long>(border_edges)) % 2 != 0) return false;
  const long edges = (3 * faces + static_cast<long>(border_edges)) / 2;
  if (static_cast<long>(n) - edges + faces != 1) return false;
  int first = -1;
  for (std::size_t i = 0; i < n && first < 0; ++i)
    if (next_on_border[i] >= 0) first = static_cast<int>(i);
  thread_local std::vector<int> loop;
  loop.clear();
  for (int i = first; loop.size() <= border_edges;) {
    loop.push_back(i);
    i = next_on_border[static_cast<std::size_t>(i)];
    if (i < 0) return false;
    if (i == first) break;
  }
  if (loop.size() != border_edges) return false;

  // Border onto a circle whose circumference is the border length, arc lengths kept.
  uv.assign(n, Eigen::Vector2d::Zero());
  thread_local std::vector<double> arc;
  arc.assign(loop.size() + 1, 0.0);
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const auto a = star.vertices[static_cast<std::size_t>(loop[i])];
    const auto b = star.vertices[static_cast<std::size_t>(loop[(i + 1) % loop.size()])];
    arc[i + 1] = arc[i] + (mesh.point(b) - mesh.point(a)).norm();
  }
  const double length = arc.back();
  if (!(length > 0)) return false;
  const double radius = length / (2 * kPi);
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const double t = 2 * kPi * arc[i] / length;
    uv[static_cast<std::size_t>(loop[i])] = Eigen::Vector2d(radius * std::cos(t), radius * std::sin(t));
  }

  // Interior vertices: U_i - sum_k lambda_ik U_k = sum_j lambda_ij U_j (Eq 3.3).
  thread_local std::vector<int> unknown;
  unknown.assign(n, -1);
  int count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (next_on_border[i] < 0) unknown[i] = count++;
  // The system: up to SmallLU::kMax unknowns (kl = 2) straight into a SmallLU, else as triplets and a right side.
  const bool small = count <= SmallLU::kMax;
  thread_local SmallLU lu;
  thread_local std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixX2d rhs;
  if (small) {
    lu.reset(count);
  } else {
    triplets.clear();
    rhs = Eigen::MatrixX2d::Zero(count, 2);
  }
  auto add = [&](int row, int col, double value) {
    if (small) lu.a[row][col] += value;
    else triplets.emplace_back(row, col, value);
  };
  thread_local std::vector<Vec3> ring;
  thread_local std::vector<int> ring_local;
  thread_local std::vector<double> lambda;
  for (std::size_t i = 0; i < n; ++i) {
    if (unknown[i] < 0) continue;
    const auto v = star.vertices[i];
    if (mesh.is_boundary(v)) return false;
    ring_local.clear();
    const double* weight = nullptr;  // lambda_ij of each neighbour, in ring_local's order
    if (s.weights && s.weights->valid[static_cast<std::size_t>(v.idx())]) {  // cached ring and weights
      const RingWeights& c = *s.weights;
      const int begin = c.begin[static_cast<std::size_t>(v.idx())], end = c.begin[static_cast<std::size_t>(v.idx()) + 1];
      for (int j = begin; j < end; ++j) {
        const std::size_t w = static_cast<std::size_t>(c.ring[static_cast<std::size_t>(j)]);
        if (s.local[w] < 0 || s.vertex_mark[w] != s.stamp) return false;
        ring_local.push_back(s.local[w]);
      }
      weight = c.lambda.data() + begin;
    } else {
      ring.clear();
      for (auto w : mesh.vv_range(v)) {
        const int l = local(w);
        if (l < 0 || s.vertex_mark[static_cast<std::size_t>(w.idx())] != s.stamp) return false;
        ring.push_back(mesh.point(w));
        ring_local.push_back(l);
      }
      if (ring.size() < 3 || ring.size() > 64) return false;
      lambda.assign(ring.size(), 0.0);
      if (weights == ParametrizationWeights::MeanValue)
        mean_value_weights(mesh.point(v), ring, lambda);
      else
        shape_preserving_weights(mesh.point(v), ring, lambda);
      weight = lambda.data();
    }
    const int row = unknown[i];
    add(row, row, 1.0);
    for (std::size_t j = 0; j < ring_local.size(); ++j) {
      if (!std::isfinite(weight[j])) return false;
      const int col = unknown[static_cast<std::size_t>(ring_local[j])];
      if (col >= 0) {
        add(row, col, -weight[j]);
      } else {
        const Eigen::Vector2d& u = uv[static_cast<std::size_t>(ring_local[j])];
        if (small) lu.b[row][0] += weight[j] * u.x(), lu.b[row][1] += weight[j] * u.y();
        else rhs.row(row) += weight[j] * u.transpose();
      }
    }
  }
  Eigen::MatrixX2d x;
  if (small) {  // Eigen's dense LU below, with the same arithmetic (small_lu.hpp)
    lu.solve(count);
    for (int i = 0; i < count; ++i)
      if (!std::isfinite(lu.b[i][0]) || !std::isfinite(lu.b[i][1])) return false;
    for (std::size_t i = 0; i < n; ++i)
      if (unknown[i] >= 0) uv[i] = Eigen::Vector2d(lu.b[unknown[i]][0], lu.b[unknown[i]][1]);
    return true;
  }
  if (count <= kDenseLimit) {
    // Medium stars (kl = 3): profiling showed SparseLU's symbolic analysis and allocations dominating the whole
    // filter, so the same system is solved densely, in fixed-capacity (stack) matrices.
    using Dense = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kDenseLimit, kDenseLimit>;
    using Rhs = Eigen::Matrix<double, Eigen::Dynamic, 2, 0, kDenseLimit, 2>;
    Dense a = Dense::Zero(count, count);
    for (const auto& t : triplets) a(t.row(), t.col()) += t.value();
    const Rhs b = rhs;
    const Rhs solved = Eigen::PartialPivLU<Dense>(a).solve(b);
    if (!solved.allFinite()) return false;
    for (std::size_t i = 0; i < n; ++i)
      if (unknown[i] >= 0) uv[i] = solved.row(unknown[i]).transpose();
    return true;
  } else {
    Eigen::SparseMatrix<double> a(count, count);
    a.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> solver;
    solver.compute(a);
    if (solver.info() != Eigen::Success) return false;
    x = solver.solve(rhs);
    if (solver.info() != Eigen::Success) return false;
  }
  if (!x.allFinite()) return false;
  for (std::size_t i = 0; i < n; ++i)
    if (unknown[i] >= 0) uv[i] = x.row(unknown[i]).transpose();
  return true;
}

}  // namespace carbonmesh
