#include "carbonmesh/simulations/mirror_plane.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <Eigen/Dense>
#include <algorithm>
#include <charconv>
#include <cmath>

#include "carbonmesh/remesh/triangle_tree.hpp"

#include <random>

#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh {
namespace {

Vec3 reflect(const Vec3& p, const Plane& plane) { return p - 2.0 * plane.signed_distance(p) * plane.normal; }

double bbox_diagonal(const TriMesh& mesh) {
  if (mesh.n_vertices() == 0) return 0;
  Vec3 lo = mesh.point(*mesh.vertices_begin()), hi = lo;
  for (auto v : mesh.vertices()) {
    lo.minimize(mesh.point(v));
    hi.maximize(mesh.point(v));
  }
  return (hi - lo).norm();
}

// Area-weighted centroid and covariance of the surface (triangle centroids, weighted by area).
void surface_moments(const TriMesh& mesh, Vec3& centroid, Eigen::Matrix3d& cov) {
  double total = 0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  std::vector<std::pair<Eigen::Vector3d, double>> tri;
  for (auto f : mesh.faces()) {
    auto it = mesh.cfv_iter(f);
    const Vec3 a = mesh.point(*it++), b = mesh.point(*it++), d = mesh.point(*it);
    const double area = 0.5 * OpenMesh::cross(b - a, d - a).norm();
    const Vec3 m = (a + b + d) / 3.0;
    tri.push_back({Eigen::Vector3d(m[0], m[1], m[2]), area});
    c += area * tri.back().first;
    total += area;
  }
  if (total <= 0) {  // fall back to vertices
    tri.clear();
    total = 0;
    c.setZero();
    for (auto v : mesh.vertices()) {
      const Vec3 p = mesh.point(v);
      tri.push_back({Eigen::Vector3d(p[0], p[1], p[2]), 1.0});
      c += tri.back().first;
      total += 1;
    }
  }
  c /= std::max(total, 1e-300);
  cov.setZero();
  for (const auto& [m, w] : tri) cov += w * (m - c) * (m - c).transpose();
  cov /= std::max(total, 1e-300);
  centroid = Vec3(c[0], c[1], c[2]);
}

// The search objective. Reflection is an isometry, so both one-sided Hausdorff distances between a surface S
// and its mirror image M(S) equal max over p in S of d(M(p), S): one AABB tree of S, built once, and samples
// of S reflected per candidate plane.
class MirrorObjective {
 public:
  using Point = triangle_tree::Point;
  using Triangles = triangle_tree::Triangles;
  using Tree = triangle_tree::Tree;

  MirrorObjective(const TriMesh& mesh, std::size_t samples) : triangles_(triangle_tree::triangles_of(mesh)) {
    std::vector<double> cumulative;
    double total = 0;
    for (auto f : mesh.faces()) {
      auto it = mesh.cfv_iter(f);
      const Vec3 a = mesh.point(*it++), b = mesh.point(*it++), c = mesh.point(*it);
      total += 0.5 * OpenMesh::cross(b - a, c - a).norm();
      cumulative.push_back(total);
    }
    tree_.insert(triangles_.begin(), triangles_.end());
    tree_.build();
    tree_.accelerate_distance_queries();
    std::mt19937_64 rng(20261123);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::size_t k = 0; k < samples && total > 0; ++k) {
      const std::size_t i = std::min<std::size_t>(
          std::lower_bound(cumulative.begin(), cumulative.end(), u(rng) * total) - cumulative.begin(),
          triangles_.size() - 1);
      const double r1 = std::sqrt(u(rng)), r2 = u(rng);
      const auto& t = triangles_[i];
      const double wa = 1 - r1, wb = r1 * (1 - r2), wc = r1 * r2;
      samples_.emplace_back(wa * t[0].x() + wb * t[1].x() + wc * t[2].x(), wa * t[0].y() + wb * t[1].y() + wc * t[2].y(),
                            wa * t[0].z() + wb * t[1].z() + wc * t[2].z());
    }
  }
  double operator()(const Plane& plane) const {
    std::vector<double> d2(samples_.size());
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < samples_.size(); ++i) {
      const Vec3 m = reflect(samples_[i], plane);
      d2[i] = tree_.squared_distance(triangle_tree::to_point(m));
    }
    double max2 = 0;
    for (double d : d2) max2 = std::max(max2, d);
    return std::sqrt(max2);
  }

 private:
  Triangles triangles_;
  Tree tree_;
  std::vector<Vec3> samples_;
};

Plane make_plane(const Vec3& n0, const Vec3& u, const Vec3& v, const Vec3& center, double a, double b, double t) {
  Plane p;
  p.normal = (n0 + a * u + b * v).normalized();
  p.offset = OpenMesh::dot(p.normal, center) + t;
  return p;
}

}  // namespace

Plane parse_plane(const std::string& text, const Vec3& center) {
  Plane p;
  if (text == "x" || text == "y" || text == "z") {
    p.normal = Vec3(0, 0, 0);
    p.normal[text[0] - 'x'] = 1;
    p.offset = center[text[0] - 'x'];
    return p;
  }
  double v[4];
  std::size_t start = 0;
  for (int k = 0; k < 4; ++k) {
    const std::size_t comma = k < 3 ? text.find(',', start) : text.size();
    if (comma == std::string::npos || (k == 3 && text.find(',', start) != std::string::npos))
      throw InputError(fmt::format("--plane '{}': expected x, y, z, auto or nx,ny,nz,d", text));
    const std::string tok = text.substr(start, comma - start);
    const char* first = tok.data();
    if (!tok.empty() && *first == '+') ++first;
    auto [ptr, ec] = std::from_chars(first, tok.data() + tok.size(), v[k]);
    if (ec != std::errc() || ptr != tok.data() + tok.size() || tok.empty() || !std::isfinite(v[k]))
      throw InputError(fmt::format("--plane '{}': '{}' is not a number", text, tok));
    start = comma + 1;
  }
  const Vec3 n(v[0], v[1], v[2]);
  const double len = n.norm();
  if (!(len > 0)) throw InputError(fmt::format("--plane '{}': the normal is zero", text));
  p.normal = n / len;
  p.offset = v[3] / len;
  return p;
}

TriMesh mirror_mesh(const TriMesh& mesh, const Plane& plane) {
  TriMesh out;
  std::vector<TriMesh::VertexHandle> map(mesh.n_vertices());
  for (auto v : mesh.vertices()) map[v.idx()] = out.add_vertex(reflect(mesh.point(v), plane));
  for (auto f : mesh.faces()) {
    std::vector<TriMesh::VertexHandle> c;
    for (auto v : mesh.fv_range(f)) c.push_back(map[v.idx()]);
    std::reverse(c.begin(), c.end());
    out.add_face(c);
  }
  return out;
}

HausdorffResult mirror_residual(const TriMesh& shape, const Plane& plane, std::size_t samples) {
  HausdorffSettings hs;
  hs.samples = samples;
  // The maxima of the samples and the vertices: a symmetric shape lies on its mirror image, where bracketing the
  // maximum would split pieces down to the tolerance across every edge (the whole budget, seconds) for a residual
  // that is reported, not decided on.
  hs.max_tolerance = 0;
  return hausdorff_distance(shape, mirror_mesh(shape, plane), hs);
}

MirrorResult find_mirror_plane(const TriMesh& shape, const MirrorSettings& settings) {
  MirrorResult result;
  result.diagonal = bbox_diagonal(shape);
  Vec3 center;
  Eigen::Matrix3d cov;
  surface_moments(shape, center, cov);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const double diag = std::max(result.diagonal, 1e-12);
  const MirrorObjective objective(shape, settings.search_samples);
  for (int axis = 2; axis >= 0; --axis) {
    const Eigen::Vector3d e = eig.eigenvectors().col(axis);
    const Vec3 n0 = Vec3(e[0], e[1], e[2]).normalized();
    // Two unit vectors orthogonal to n0.
    Vec3 helper = std::abs(n0[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    const Vec3 u = OpenMesh::cross(n0, helper).normalized();
    const Vec3 v = OpenMesh::cross(n0, u).normalized();
    MirrorCandidate cand;
    double x[3] = {0, 0, 0};
    auto eval = [&](const double* p) {
      ++cand.evaluations;
      return objective(make_plane(n0, u, v, center, p[0], p[1], p[2]));
    };
    double best = eval(x);
    cand.start = make_plane(n0, u, v, center, 0, 0, 0);
    cand.start_distance = best;
    // Pattern search: try +-step on each coordinate, move on improvement, halve the steps otherwise.
    double step[3] = {0.08, 0.08, 0.02 * diag};
    const double min_step[3] = {1e-3, 1e-3, 1e-4 * diag};
    while (cand.evaluations < settings.evaluations_per_candidate) {
      bool improved = false;
      for (int k = 0; k < 3 && cand.evaluations < settings.evaluations_per_candidate; ++k)
        for (double sign : {1.0, -1.0}) {
          double y[3] = {x[0], x[1], x[2]};
          y[k] += sign * step[k];
          const double f = eval(y);
          if (f < best) {
            best = f;
            std::copy(y, y + 3, x);
            improved = true;
            break;
          }
        }
      if (!improved) {
        bool done = true;
        for (int k = 0; k < 3; ++k) {
          step[k] *= 0.5;
          if (step[k] >= min_step[k]) done = false;
        }
        if (done) break;
      }
    }
    cand.refined = make_plane(n0, u, v, center, x[0], x[1], x[2]);
    cand.refined_distance = best;
    spdlog::debug("mirror candidate axis {}: {:.4g} -> {:.4g} in {} evaluations", axis, cand.start_distance,
                  cand.refined_distance, cand.evaluations);
    result.candidates.push_back(cand);
  }
  std::stable_sort(result.candidates.begin(), result.candidates.end(),
                   [](const MirrorCandidate& a, const MirrorCandidate& b) { return a.refined_distance < b.refined_distance; });
  result.plane = result.candidates.front().refined;
  result.residual = mirror_residual(shape, result.plane, settings.final_samples);
  return result;
}

TriMesh surface_of(const RingStructure& rs) {
  TriMesh mesh;
  // OpenMesh reports refused (non-manifold) faces on omerr; they are expected here and skipped.
  struct Quiet {
    Quiet() { omerr().disable(); }
    ~Quiet() { omerr().enable(); }
  } quiet;
  const auto& pos = rs.atoms.positions;
  std::vector<TriMesh::VertexHandle> atom(pos.size());
  for (std::size_t i = 0; i < pos.size(); ++i) atom[i] = mesh.add_vertex(pos[i]);
  for (std::size_t r = 0; r < rs.size(); ++r) {
    if (rs.open[r] || rs.rings[r].size() < 3) continue;
    const auto c = mesh.add_vertex(rs.centers[r]);
    const auto& ring = rs.rings[r];
    for (std::size_t k = 0; k < ring.size(); ++k) {
      auto f = mesh.add_face(c, atom[ring[k]], atom[ring[(k + 1) % ring.size()]]);
      if (!f.is_valid()) f = mesh.add_face(c, atom[ring[(k + 1) % ring.size()]], atom[ring[k]]);
    }
  }
  return mesh;
}

SideCounts count_sides(const RingStructure& rs, const Plane& plane, double tolerance) {
  SideCounts s;
  for (std::size_t r = 0; r < rs.size(); ++r) {
    if (rs.open[r] || rs.sizes[r] == 6) continue;
    const double d = plane.signed_distance(rs.centers[r]);
    if (std::abs(d) <= tolerance) {
      ++s.on_plane[rs.sizes[r]];
      ++s.on_plane_total;
    } else if (d > 0) {
      ++s.positive[rs.sizes[r]];
      ++s.positive_total;
    } else {
      ++s.negative[rs.sizes[r]];
      ++s.negative_total;
    }
  }
  return s;
}

}  // namespace carbonmesh
