// Edge flips that bring the remeshed surface nearer the input (a data-dependent triangulation in the sense of
// Dyn, Levin and Rippa 1990; not in the dissertation). The flips that need the vertices around relaxed are in
// relaxed_flips.cpp.
//
// With every vertex on the input, the triangulation between them still decides how far the surface strays from
// it: a pair of triangles whose shared edge bridges a groove or cuts across a ridge lies up to most of an edge
// away, where the other diagonal of the same four vertices would follow the input. The valence flips (Eq 4.3)
// choose the diagonal by valence alone. Here the faces farther than `tolerance` from the input (the largest of
// seven sampled distances per face, one AABB tree), farthest first, have the diagonal of each of their edges'
// quads flipped where the two new faces are at least kGain nearer, the new edge lies in [emin, emax], no new
// angle falls under 3 degrees or half the old smallest one, no new face turns against an old one, no vertex
// gets more than one off its ideal valence (6 inside, 4 on a border) unless it already was, and E_val (Eq 4.2)
// rises by at most 2 (flip_valence_ok).
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "carbonmesh/remesh/triangle_tree.hpp"
#include "flips_toward_input.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {
namespace {

using namespace triangle_tree;

constexpr double kGain = 0.9;  // the flipped pair must be this factor nearer the input at least

// The valence flips' shape test, and no new angle under 3 degrees.
bool geometry_ok(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return geometry::flip_keeps_shape(a, b, c, d) &&
         std::min(geometry::min_angle(a, d, c), geometry::min_angle(b, c, d)) >= geometry::kMinAngle;
}

}  // namespace

// E_val may rise by 2 (one vertex pair 6,6 -> 5,7). Seed-protocol models, Hausdorff max at 2M samples: armadillo
// 0.589 -> 0.477 (6 flips), bunny 0.798 -> 0.647 (2); with 0: armadillo 0.528 (2), bunny no flip; with 4: 0.474
// (10), 0.647.
bool flip_valence_ok(const TriMesh& mesh, const FlipQuad& q) {
  int before = 0, after = 0;
  for (const auto& [v, change] : {std::pair{q.a, -1}, std::pair{q.b, -1}, std::pair{q.c, 1}, std::pair{q.d, 1}}) {
    const int off = geometry::valence(mesh, v) - ideal_valence(mesh, v);
    const int off_after = off + change;
    if (std::abs(off_after) > std::max(1, std::abs(off))) return false;  // (so no valence under 3 either)
    before += off * off;
    after += off_after * off_after;
  }
  return after <= before + 2;
}

std::vector<double> face_distances(const TriMesh& mesh, const Tree& tree, double tolerance) {
  std::vector<double> distance(mesh.n_faces(), 0.0);
  const int nf = static_cast<int>(mesh.n_faces());
#pragma omp parallel for schedule(dynamic, 256)
  for (int i = 0; i < nf; ++i) {
    const TriMesh::FaceHandle f(i);
    if (mesh.status(f).deleted()) continue;
    Vec3 a, b, c;
    geometry::face_points(mesh, f, a, b, c);
    // The centroid first: a face whose centroid lies within half the tolerance is no candidate.
    const double centroid = std::sqrt(tree.squared_distance(to_point((a + b + c) / 3.0)));
    distance[static_cast<std::size_t>(i)] = centroid < 0.5 * tolerance ? centroid : face_distance(tree, a, b, c);
  }
  return distance;
}

std::vector<std::pair<double, int>> far_edges(const TriMesh& mesh, const std::vector<double>& distance,
                                             double tolerance) {
  auto at = [&](TriMesh::HalfedgeHandle h) { return distance[static_cast<std::size_t>(mesh.face_handle(h).idx())]; };
  std::vector<std::pair<double, int>> order;
  for (auto e : mesh.edges()) {
    if (mesh.status(e).deleted() || mesh.is_boundary(e)) continue;
    const double d = std::max(at(mesh.halfedge_handle(e, 0)), at(mesh.halfedge_handle(e, 1)));
    if (d > tolerance) order.emplace_back(-d, e.idx());
  }
  std::sort(order.begin(), order.end());
  return order;
}

DataDependentFlips data_dependent_flips(TriMesh& mesh, const TriMesh& input, double emin, double emax,
                                        double tolerance, const ProjectionTarget* target, int kn,
                                        const std::vector<char>* fixed, const SurfaceTree* input_tree) {
  DataDependentFlips result;
  if (input.n_faces() == 0 || mesh.n_faces() == 0) return result;
  std::optional<SurfaceTree> own;
  const SurfaceTree& input_surface = input_tree ? *input_tree : own.emplace(input);
  const Tree& tree = input_surface.tree();
  std::vector<double> distance = face_distances(mesh, tree, tolerance);
  auto at = [&](TriMesh::FaceHandle f) -> double& { return distance[static_cast<std::size_t>(f.idx())]; };
  for (const double d : distance) result.max_before = std::max(result.max_before, d);
  // Edges of the faces farther than the tolerance, farthest first (ties by edge index).
  const std::vector<std::pair<double, int>> order = far_edges(mesh, distance, tolerance);
  result.candidates = order.size();
  for (const auto& [unused, index] : order) {
    const TriMesh::EdgeHandle e(index);
    if (!mesh.is_flip_ok(e)) continue;
    const FlipQuad q = quad(mesh, e);
    const Vec3 a = mesh.point(q.a), b = mesh.point(q.b), c = mesh.point(q.c), d = mesh.point(q.d);
    const double length = (c - d).norm();
    if (length < emin || length > emax) continue;
    if (!flip_valence_ok(mesh, q) || !geometry_ok(a, b, c, d)) continue;
    const auto f0 = mesh.face_handle(mesh.halfedge_handle(e, 0)), f1 = mesh.face_handle(mesh.halfedge_handle(e, 1));
    const double before = std::max(at(f0), at(f1));
    if (std::max(face_distance(tree, a, d, c), face_distance(tree, b, c, d)) >= kGain * before) continue;
    mesh.flip(e);
    ++result.flips;
    for (auto f : {f0, f1}) at(f) = face_distance(tree, mesh, f);
  }
  if (target)
    relaxed_flips(mesh, input, tree, input_surface.first(), distance, *target, kn, emin, emax, tolerance, fixed,
                  result);
  for (const double d : distance) result.max_after = std::max(result.max_after, d);
  return result;
}

}  // namespace carbonmesh
