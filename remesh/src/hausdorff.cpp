#include "carbonmesh/remesh/hausdorff.hpp"

#include "carbonmesh/remesh/triangle_tree.hpp"
#include "farthest_point.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <queue>
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

namespace {

// What the branch and bound knows of the distance to the tree's surface over one (sub-)triangle.
struct Bounds {
  double lower = 0;  // attained: at a corner or the centroid
  double upper = 0;  // no point of the triangle is farther
  Point at;          // where `lower` is attained
};

// The distance to the surface is at most that to any one of its triangles t, which is convex (the distance to a convex
// set), so over the piece at most its largest value at the piece's corners: t is taken among the triangles nearest
// the centroid and the corners. The distance is also 1-Lipschitz: at most that of the centroid plus the farthest
// corner's distance from it.
Bounds bounds(const std::array<Point, 3>& piece, const Tree& tree) {
  const Point g = CGAL::centroid(piece[0], piece[1], piece[2]);
  const auto at_g = tree.closest_point_and_primitive(g);
  const double dg = std::sqrt(CGAL::squared_distance(g, at_g.first));
  std::array<const Triangle*, 4> nearest{&*at_g.second, nullptr, nullptr, nullptr};
  Bounds b{dg, 0, g};
  double reach = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto at_k = tree.closest_point_and_primitive(piece[k], at_g);
    const double dk = std::sqrt(CGAL::squared_distance(piece[k], at_k.first));
    if (dk > b.lower) b.lower = dk, b.at = piece[k];
    nearest[k + 1] = &*at_k.second;
    reach = std::max(reach, std::sqrt(CGAL::squared_distance(g, piece[k])));
  }
  b.upper = dg + reach;
  for (const Triangle* t : nearest) {
    double farthest2 = 0;
    for (const Point& p : piece) farthest2 = std::max(farthest2, CGAL::squared_distance(p, *t));
    b.upper = std::min(b.upper, std::sqrt(farthest2));
  }
  b.upper = std::max(b.upper, b.lower);
  return b;
}

}  // namespace

// The largest distance of the triangles' points to the tree's surface, bracketed: pieces (the faces first) whose
// upper bound exceeds the largest distance found so far by more than `tolerance` are split into four at their edge
// midpoints, those with the highest bounds first, kBatch at a time (each batch's pieces on every thread; the order is
// fixed by the bounds and the order of creation, so the result is the same for any thread count), until none is left
// or `max_pieces` more than the faces have been measured (a surface lying on the other one, where no bound falls to 0
// across the other's edges: then the bracket is what the pieces measured give).
Farthest farthest_point(const Triangles& triangles, const Tree& tree, double tolerance, std::size_t max_pieces) {
  constexpr std::size_t kBatch = 1024;
  struct Open {
    double upper;
    std::size_t id;  // order of creation (ties)
    std::array<Point, 3> piece;
    bool operator<(const Open& o) const { return upper != o.upper ? upper < o.upper : id > o.id; }
  };
  std::vector<std::array<Point, 3>> pieces;
  pieces.reserve(triangles.size());
  for (const Triangle& t : triangles) pieces.push_back({t[0], t[1], t[2]});
  std::vector<Bounds> b;
  auto measure = [&] {
    b.resize(pieces.size());
    const long n = static_cast<long>(pieces.size());
#pragma omp parallel for schedule(dynamic, 64)
    for (long i = 0; i < n; ++i) b[static_cast<std::size_t>(i)] = bounds(pieces[static_cast<std::size_t>(i)], tree);
  };
  measure();
  double lower = 0, upper = 0;  // upper: the largest bound of the pieces settled (not split further)
  Point at = triangles.empty() ? Point(0, 0, 0) : triangles.front()[0];
  auto raise = [&] {  // lower to the farthest of the pieces just measured (the first of equal ones)
    for (const Bounds& x : b)
      if (x.lower > lower) lower = x.lower, at = x.at;
  };
  raise();
  std::priority_queue<Open> open;
  std::size_t created = 0, measured = pieces.size();
  auto settle_or_open = [&] {
    for (std::size_t i = 0; i < pieces.size(); ++i, ++created) {
      if (b[i].upper <= lower + tolerance) upper = std::max(upper, b[i].upper);
      else open.push({b[i].upper, created, pieces[i]});
    }
  };
  settle_or_open();
  while (!open.empty() && measured < triangles.size() + max_pieces) {
    pieces.clear();
    while (!open.empty() && pieces.size() < 4 * kBatch) {
      const Open top = open.top();
      open.pop();
      if (top.upper <= lower + tolerance) {
        upper = std::max(upper, top.upper);
        continue;
      }
      const auto& [p, q, r] = top.piece;
      const Point pq = CGAL::midpoint(p, q), qr = CGAL::midpoint(q, r), rp = CGAL::midpoint(r, p);
      pieces.push_back({p, pq, rp});
      pieces.push_back({pq, q, qr});
      pieces.push_back({rp, qr, r});
      pieces.push_back({pq, qr, rp});
    }
    measure();
    measured += pieces.size();
    raise();
    settle_or_open();
  }
  for (; !open.empty(); open.pop()) upper = std::max(upper, open.top().upper);  // (the budget ran out)
  return {lower, std::max(lower, upper), at};
}

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
  if (settings.vertices && !(settings.max_tolerance > 0)) {  // (else every corner is measured below)
    r.forward_max = std::max(r.forward_max, one_sided(face_vertices(mesh), tree_b).first);
    r.backward_max = std::max(r.backward_max, one_sided(face_vertices(reference), tree_a).first);
    r.vertices = true;
  }
  if (settings.max_tolerance > 0) {
    auto budget = [&](const Triangles& t) {
      return std::max(settings.max_pieces, settings.pieces_per_face * t.size());
    };
    const Farthest forward = farthest_point(a, tree_b, settings.max_tolerance, budget(a));
    const Farthest backward = farthest_point(b, tree_a, settings.max_tolerance, budget(b));
    // (A sample is farther than the point found by at most the tolerance, unless the budget ran out.)
    r.forward_max = std::max(r.forward_max, forward.distance);
    r.backward_max = std::max(r.backward_max, backward.distance);
    r.forward_max_bound = std::max(r.forward_max, forward.bound);
    r.backward_max_bound = std::max(r.backward_max, backward.bound);
    r.forward_max_point = {forward.at.x(), forward.at.y(), forward.at.z()};
    r.backward_max_point = {backward.at.x(), backward.at.y(), backward.at.z()};
    r.max_bound = std::max(r.forward_max_bound, r.backward_max_bound);
    r.bracketed = true;
    r.vertices = true;  // (every corner is measured)
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
          {"vertices", h.vertices},
          {"bracketed", h.bracketed},
          {"forward_max_point", h.forward_max_point},
          {"backward_max_point", h.backward_max_point},
          {"max_bound", h.max_bound},
          {"forward_max_bound", h.forward_max_bound},
          {"backward_max_bound", h.backward_max_bound}};
}

}  // namespace carbonmesh
