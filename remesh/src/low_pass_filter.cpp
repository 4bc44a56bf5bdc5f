// Section 4.3: low-pass filter in a local parametrization (Algorithm 3) and the border optimizer.
#include <algorithm>
#include <cmath>
#include <vector>

#include "carbonmesh/remesh/remesh_steps.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {
namespace {

using geometry::kMaxNormalTurnCos;
using geometry::kMinAngle;

// Tangential Laplacian over the k-star, weights 1/star (Algorithm 3, else branch).
Vec3 tangential_laplacian(const TriMesh& mesh, const KStar& star) {
  const Vec3 p = mesh.point(star.vertices[0]);
  Vec3 sum(0, 0, 0);
  double fat = 0;
  for (std::size_t j = 1; j < star.vertices.size(); ++j) {
    const double w = 1.0 / star.ring[j];
    sum += w * mesh.point(star.vertices[j]);
    fat += w;
  }
  if (fat <= 0) return p;
  Vec3 d = sum / fat - p;
  const Vec3 n = geometry::vertex_normal(mesh, star.vertices[0]);
  d -= OpenMesh::dot(d, n) * n;
  return p + d;
}

// 3D position of the parametric point `x`: barycentric interpolation in the star face containing it
// (the one with the largest smallest barycentric coordinate).
Vec3 position_from_parameter(const TriMesh& mesh, const KStar& star, const StarScratch& s,
                             const std::vector<Eigen::Vector2d>& uv, const Eigen::Vector2d& x) {
  double best = -1e300;
  Vec3 result = mesh.point(star.vertices[0]);
  for (auto f : star.faces) {
    int idx[3], i = 0;
    TriMesh::VertexHandle vh[3];
    for (auto w : mesh.fv_range(f)) {
      vh[i] = w;
      idx[i++] = s.local[static_cast<std::size_t>(w.idx())];
    }
    const Eigen::Vector2d& a = uv[static_cast<std::size_t>(idx[0])];
    const Eigen::Vector2d& b = uv[static_cast<std::size_t>(idx[1])];
    const Eigen::Vector2d& c = uv[static_cast<std::size_t>(idx[2])];
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
    if (std::abs(det) < 1e-300) continue;
    const double lb = ((x.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (x.y() - a.y())) / det;
    const double lc = ((b.x() - a.x()) * (x.y() - a.y()) - (x.x() - a.x()) * (b.y() - a.y())) / det;
    const double la = 1 - lb - lc;
    const double worst = std::min({la, lb, lc});
    if (worst > best) {
      best = worst;
      const double l0 = std::max(la, 0.0), l1 = std::max(lb, 0.0), l2 = std::max(lc, 0.0), sum = l0 + l1 + l2;
      result = (l0 * mesh.point(vh[0]) + l1 * mesh.point(vh[1]) + l2 * mesh.point(vh[2])) / sum;
      if (worst >= 0) break;
    }
  }
  return result;
}

}  // namespace

Vec3 low_pass_position(const TriMesh& mesh, TriMesh::VertexHandle v, int kl, ParametrizationWeights weights,
                       StarScratch& scratch) {
  thread_local KStar star;  // reused buffers
  collect_k_star(mesh, v, kl, star, scratch);
  // Eq 4.4: kl_i = min Star(V_j) over the border vertices V_j of the kl-star.
  int kli = kl;
  for (std::size_t j = 0; j < star.vertices.size(); ++j)
    if (mesh.is_boundary(star.vertices[j])) kli = std::min(kli, star.ring[j]);
  if (kli <= 0) return mesh.point(v);
  if (kli < kl) collect_k_star(mesh, v, kli, star, scratch);
  thread_local std::vector<Eigen::Vector2d> uv;
  if (!compute_parametrization(mesh, star, weights, scratch, uv)) return tangential_laplacian(mesh, star);
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  double fat = 0;
  for (std::size_t j = 1; j < star.vertices.size(); ++j) {
    const double w = 2.0 / static_cast<double>(1u << star.ring[j]);  // 1 / 2^(star-1), exact
    x += w * uv[j];
    fat += w;
  }
  return position_from_parameter(mesh, star, scratch, uv, x / fat);
}

bool border_optimizer(TriMesh& mesh, TriMesh::VertexHandle v, double m) {
  if (!mesh.is_boundary(v)) return false;
  TriMesh::HalfedgeHandle out;
  for (auto h : mesh.voh_range(v))
    if (mesh.is_boundary(h)) out = h;
  if (!out.is_valid()) return false;
  const auto in = mesh.prev_halfedge_handle(out);
  const auto va = mesh.from_vertex_handle(in), vb = mesh.to_vertex_handle(out);
  if (va == vb) return false;
  geometry::BorderCurve curve;  // the quadratic through (ta, a), (0, p), (tb, b)
  curve.a = mesh.point(va), curve.p = mesh.point(v), curve.b = mesh.point(vb);
  const double ta = curve.ta = -(curve.p - curve.a).norm(), tb = curve.tb = (curve.b - curve.p).norm();
  if (ta >= 0 || tb <= 0) return false;
  std::vector<Vec3> nb;
  for (auto w : mesh.vv_range(v)) nb.push_back(mesh.point(w));
  auto energy = [&](double t) {  // Eq 4.1
    const Vec3 x = curve.at(t);
    double e = 0;
    for (const auto& q : nb) {
      const double r = (x - q).norm() - m;
      e += r * r;
    }
    return e;
  };
  // Sample the middle halves of the two border edges, then golden-section around the best sample.
  const int samples = 20;
  const double lo = 0.5 * ta, hi = 0.5 * tb;
  double best_t = 0, best_e = energy(0);
  for (int i = 0; i <= samples; ++i) {
    const double t = lo + (hi - lo) * i / samples;
    const double e = energy(t);
    if (e < best_e) best_e = e, best_t = t;
  }
  const double step = (hi - lo) / samples;
  double l = std::max(lo, best_t - step), r = std::min(hi, best_t + step);
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  for (int it = 0; it < 25; ++it) {
    const double c = r - g * (r - l), d = l + g * (r - l);
    if (energy(c) < energy(d)) r = d;
    else l = c;
  }
  const double t = 0.5 * (l + r);
  if (energy(t) < best_e) best_t = t;
  if (best_t == 0) return false;
  const Vec3 x = curve.at(best_t);
  for (auto f : mesh.vf_range(v)) {
    Vec3 q[3];
    int i = 0;
    for (auto w : mesh.fv_range(f)) q[i++] = w == v ? x : mesh.point(w);
    const Vec3 before = geometry::face_normal(mesh, f), after = geometry::triangle_normal(q[0], q[1], q[2]);
    if (OpenMesh::dot(before, after) < kMaxNormalTurnCos || geometry::min_angle(q[0], q[1], q[2]) < kMinAngle)
      return false;
  }
  mesh.set_point(v, x);
  return true;
}

void low_pass_filter(TriMesh& mesh, int kl, ParametrizationWeights weights, double m) {
  const int n = static_cast<int>(mesh.n_vertices());
  std::vector<Vec3> moved(static_cast<std::size_t>(n));
  const RingWeights cached = ring_weights(mesh, weights);
#pragma omp parallel
  {
    StarScratch scratch(mesh);
    scratch.weights = &cached;
#pragma omp for schedule(dynamic, 64)
    for (int i = 0; i < n; ++i) {
      const TriMesh::VertexHandle v(i);
      moved[static_cast<std::size_t>(i)] =
          mesh.status(v).deleted() || mesh.is_boundary(v) || mesh.is_isolated(v)
              ? mesh.point(v)
              : low_pass_position(mesh, v, kl, weights, scratch);
    }
  }
  for (int i = 0; i < n; ++i) {
    const TriMesh::VertexHandle v(i);
    if (!mesh.status(v).deleted() && !mesh.is_boundary(v)) mesh.set_point(v, moved[static_cast<std::size_t>(i)]);
  }
  for (int i = 0; i < n; ++i) {
    const TriMesh::VertexHandle v(i);
    if (!mesh.status(v).deleted() && mesh.is_boundary(v)) border_optimizer(mesh, v, m);
  }
}

}  // namespace carbonmesh
