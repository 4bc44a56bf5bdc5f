#include "carbonmesh/remesh/hausdorff.hpp"

#include "carbonmesh/remesh/triangle_tree.hpp"


#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

namespace carbonmesh {
namespace {

using namespace triangle_tree;

// Area-uniform samples on the triangles (fixed seed: deterministic).
std::vector<Point> sample(const Triangles& triangles, std::size_t n, std::uint64_t seed) {
  std::vector<double> cumulative(triangles.size());
  double total = 0;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    total += std::sqrt(std::max(0.0, triangles[i].squared_area()));
    cumulative[i] = total;
  }
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Point> points;
  points.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double pick = uniform(rng) * total;
    std::size_t i = static_cast<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), pick) -
                                             cumulative.begin());
    i = std::min(i, triangles.size() - 1);
    const double r1 = std::sqrt(uniform(rng)), r2 = uniform(rng);
    const auto& t = triangles[i];
    const double a = 1 - r1, b = r1 * (1 - r2), c = r1 * r2;
    points.emplace_back(a * t[0].x() + b * t[1].x() + c * t[2].x(), a * t[0].y() + b * t[1].y() + c * t[2].y(),
                        a * t[0].z() + b * t[1].z() + c * t[2].z());
  }
  return points;
}

// Max and RMS of the distances from the points to the tree's surface. Distances are computed in parallel
// and summed in order, so the figures do not depend on the thread count.
std::pair<double, double> one_sided(const std::vector<Point>& points, const Tree& tree) {
  std::vector<double> d2(points.size());
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < points.size(); ++i) d2[i] = tree.squared_distance(points[i]);
  double max2 = 0, sum2 = 0;
  for (double d : d2) {
    max2 = std::max(max2, d);
    sum2 += d;
  }
  return {std::sqrt(max2), points.empty() ? 0.0 : std::sqrt(sum2 / static_cast<double>(points.size()))};
}

// The vertices of the mesh's faces (isolated ones are no part of the surface).
std::vector<Point> face_vertices(const TriMesh& mesh) {
  std::vector<Point> points;
  for (auto v : mesh.vertices())
    if (!mesh.status(v).deleted() && !mesh.is_isolated(v)) points.push_back(to_point(mesh.point(v)));
  return points;
}

}  // namespace

HausdorffResult hausdorff_distance(const TriMesh& mesh, const TriMesh& reference, const HausdorffSettings& settings) {
  HausdorffResult r;
  const Triangles a = triangles_of(mesh), b = triangles_of(reference);
  if (a.empty() || b.empty()) return r;
  Tree tree_a(a.begin(), a.end()), tree_b(b.begin(), b.end());
  tree_a.build();
  tree_b.build();
  tree_a.accelerate_distance_queries();
  tree_b.accelerate_distance_queries();
  const auto samples_a = sample(a, settings.samples, settings.seed);
  const auto samples_b = sample(b, settings.samples, settings.seed + 1);
  std::tie(r.forward_max, r.forward_rms) = one_sided(samples_a, tree_b);
  std::tie(r.backward_max, r.backward_rms) = one_sided(samples_b, tree_a);
  if (settings.vertices) {
    r.forward_max = std::max(r.forward_max, one_sided(face_vertices(mesh), tree_b).first);
    r.backward_max = std::max(r.backward_max, one_sided(face_vertices(reference), tree_a).first);
    r.vertices = true;
  }
  r.max = std::max(r.forward_max, r.backward_max);
  r.rms = std::max(r.forward_rms, r.backward_rms);
  r.samples_per_side = settings.samples;
  return r;
}

nlohmann::json to_json(const HausdorffResult& h) {
  return {{"max", h.max},
          {"rms", h.rms},
          {"forward_max", h.forward_max},
          {"forward_rms", h.forward_rms},
          {"backward_max", h.backward_max},
          {"backward_rms", h.backward_rms},
          {"samples_per_side", h.samples_per_side},
          {"vertices", h.vertices}};
}

}  // namespace carbonmesh
