// Section 4.5: projection onto the projection mesh M_p (Algorithm 4) with a uniform-grid k-nearest search.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/closest_point.hpp"
#include "carbonmesh/remesh/point_grid.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {
namespace {

}  // namespace

struct ProjectionTarget::Impl {
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> faces;
  std::vector<std::array<double, 4>> spheres;  // per face: centroid and the largest corner distance
  std::vector<int> vertex_face_begin, vertex_faces;  // CSR: faces around each vertex
  std::unique_ptr<PointGrid> grid;
};

namespace {
// `mesh` with no edge longer than max_edge, or nothing when it has none.
std::optional<TriMesh> bisected(const TriMesh& mesh, double max_edge) {
  if (!(max_edge > 0)) return std::nullopt;
  bool long_edge = false;
  for (auto e : mesh.edges()) long_edge = long_edge || mesh.calc_edge_length(e) > max_edge;
  if (!long_edge) return std::nullopt;
  std::optional<TriMesh> out(mesh);
  longest_edge_bisection(*out, max_edge);
  return out;
}
}  // namespace

ProjectionTarget::ProjectionTarget(const TriMesh& input, double max_edge) : impl_(std::make_unique<Impl>()) {
  const std::optional<TriMesh> refined = bisected(input, max_edge);
  const TriMesh& target = refined ? *refined : input;
  Impl& t = *impl_;
  const std::size_t n = target.n_vertices();
  t.points.resize(n);
  for (std::size_t i = 0; i < n; ++i) t.points[i] = target.point(TriMesh::VertexHandle(static_cast<int>(i)));
  std::vector<int> count(n + 1, 0);
  for (auto f : target.faces()) {
    std::array<int, 3> tri{};
    int i = 0;
    for (auto v : target.fv_range(f)) tri[static_cast<std::size_t>(i++)] = v.idx();
    t.faces.push_back(tri);
    for (int v : tri) ++count[static_cast<std::size_t>(v) + 1];
  }
  for (const auto& tri : t.faces) {
    const Vec3 c = (t.points[static_cast<std::size_t>(tri[0])] + t.points[static_cast<std::size_t>(tri[1])] +
                    t.points[static_cast<std::size_t>(tri[2])]) / 3.0;
    double r = 0;
    for (int v : tri) r = std::max(r, (t.points[static_cast<std::size_t>(v)] - c).norm());
    t.spheres.push_back({c[0], c[1], c[2], r * (1 + 1e-12) + 1e-300});
  }
  for (std::size_t i = 0; i < n; ++i) count[i + 1] += count[i];
  t.vertex_face_begin = count;
  t.vertex_faces.resize(static_cast<std::size_t>(count[n]));
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (std::size_t f = 0; f < t.faces.size(); ++f)
    for (int v : t.faces[f]) t.vertex_faces[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = static_cast<int>(f);
  // Only vertices used by a face go into the grid.
  std::vector<int> used;
  for (std::size_t i = 0; i < n; ++i)
    if (count[i + 1] > count[i]) used.push_back(static_cast<int>(i));
  double edge_sum = 0;
  for (const auto& tri : t.faces)
    for (std::size_t j = 0; j < 3; ++j)
      edge_sum += (t.points[static_cast<std::size_t>(tri[j])] - t.points[static_cast<std::size_t>(tri[(j + 1) % 3])]).norm();
  const double mean_edge = t.faces.empty() ? 0.0 : edge_sum / (3.0 * static_cast<double>(t.faces.size()));
  t.grid = std::make_unique<PointGrid>(t.points, used, 2 * mean_edge, 8.0 * static_cast<double>(used.size()) + 1000);
}

ProjectionTarget::~ProjectionTarget() = default;

namespace {
// The k nearest target vertices of v into `ids`, nearest first: from `kept` when they hold for v
// (NearestTargetVertices), else searched, and then kept there with the next ones.
void nearest_vertices(const PointGrid& grid, const std::vector<Vec3>& points, const Vec3& v, std::size_t k,
                      NearestTargetVertices* kept, std::vector<int>& ids) {
  using Kept = NearestTargetVertices;
  ids.clear();
  if (k == 0) return;
  thread_local std::vector<std::pair<double, int>> nearest;
  if (kept != nullptr && k > Kept::kKept) kept = nullptr;
  if (kept != nullptr && kept->beyond >= 0) {
    nearest.clear();
    for (std::size_t j = 0; j < kept->count; ++j) {
      const int id = kept->ids[j];
      nearest.emplace_back(PointGrid::squared_distance(v, points[static_cast<std::size_t>(id)]), id);
    }
    std::sort(nearest.begin(), nearest.end(), PointGrid::before);
    const bool all = kept->beyond == std::numeric_limits<double>::infinity();
    if (all || nearest.size() >= k) {
      const Vec3 at(kept->at[0], kept->at[1], kept->at[2]);
      // With a margin far above the rounding of the squared distances.
      if (all || std::sqrt(nearest[k - 1].first) < kept->beyond - (v - at).norm() - 1e-9 * (kept->beyond + 1)) {
        for (std::size_t j = 0; j < std::min(k, nearest.size()); ++j) ids.push_back(nearest[j].second);
        return;
      }
    }
  }
  grid.nearest(v, kept != nullptr ? Kept::kKept + 1 : k, nearest);
  for (std::size_t j = 0; j < std::min(k, nearest.size()); ++j) ids.push_back(nearest[j].second);
  if (kept == nullptr) return;
  kept->at = {v[0], v[1], v[2]};
  kept->count = std::min(Kept::kKept, nearest.size());
  for (std::size_t j = 0; j < kept->count; ++j) kept->ids[j] = nearest[j].second;
  kept->beyond = nearest.size() > Kept::kKept ? std::sqrt(nearest[Kept::kKept].first)
                                              : std::numeric_limits<double>::infinity();
}
}  // namespace

Vec3 ProjectionTarget::project(const Vec3& v, const std::vector<Vec3>& neighbors, int k,
                               NearestTargetVertices* kept) const {
  const Impl& t = *impl_;
  thread_local std::vector<int> nearest;
  nearest_vertices(*t.grid, t.points, v, static_cast<std::size_t>(std::max(k, 0)), kept, nearest);
  // Candidate faces, each once: a per-thread stamp per target face instead of sort + unique.
  thread_local std::vector<unsigned> face_stamp;
  thread_local unsigned stamp = 0;
  if (face_stamp.size() < t.faces.size()) face_stamp.resize(t.faces.size(), 0);
  if (++stamp == 0) {  // wrapped: start over
    std::fill(face_stamp.begin(), face_stamp.end(), 0u);
    stamp = 1;
  }
  // Each candidate face with the squared distance of v to the centre of its bounding sphere (no square root: most
  // faces are ruled out by comparing it with the bound below).
  struct Candidate {
    double centre2;
    int face;
  };
  thread_local std::vector<Candidate> candidates;
  std::size_t fan = 0;
  for (const int index : nearest)
    fan += static_cast<std::size_t>(t.vertex_face_begin[static_cast<std::size_t>(index) + 1] -
                                    t.vertex_face_begin[static_cast<std::size_t>(index)]);
  if (candidates.size() < fan) candidates.resize(fan);
  Candidate* const listed = candidates.data();
  std::size_t count = 0;
  for (const int index : nearest) {
    const auto i = static_cast<std::size_t>(index);
    for (int j = t.vertex_face_begin[i]; j < t.vertex_face_begin[i + 1]; ++j) {
      const int f = t.vertex_faces[static_cast<std::size_t>(j)];
      auto& mark = face_stamp[static_cast<std::size_t>(f)];
      if (mark == stamp) continue;
      mark = stamp;
      const auto& sp = t.spheres[static_cast<std::size_t>(f)];
      const double dx = v[0] - sp[0], dy = v[1] - sp[1], dz = v[2] - sp[2];
      listed[count++] = {dx * dx + dy * dy + dz * dz, f};
    }
  }
  thread_local std::vector<double> neighbor_lengths;
  neighbor_lengths.resize(neighbors.size());
  for (std::size_t j = 0; j < neighbors.size(); ++j) neighbor_lengths[j] = (v - neighbors[j]).norm();
  auto closest = [&](int f) {
    const auto& tri = t.faces[static_cast<std::size_t>(f)];
    return closest_point_on_triangle(v, t.points[static_cast<std::size_t>(tri[0])],
                                     t.points[static_cast<std::size_t>(tri[1])],
                                     t.points[static_cast<std::size_t>(tri[2])]);
  };
  // The winner is the candidate with the smallest score, ties to the smaller |V - P|, then the smaller face
  // index: a strict order, so the faces may be scored in any order. A face whose bounding sphere lies farther than
  // the best score so far cannot win (|V - P| <= score; the radii are rounded up far beyond the rounding of these
  // comparisons) and is not projected onto. The face whose sphere's centre is nearest goes first (it usually wins, so
  // most others are ruled out by their sphere); sorting all of them cost more than the projections it saved.
  Vec3 best = v;
  double best_score = std::numeric_limits<double>::infinity(), best_distance = best_score;
  int best_face = -1;
  auto consider = [&](const Candidate& c) {
    const double radius = t.spheres[static_cast<std::size_t>(c.face)][3];
    if (c.centre2 > (best_score + radius) * (best_score + radius)) return;
    const int f = c.face;
    const Vec3 p = closest(f);
    const double distance = (v - p).norm();
    if (distance > best_score) return;
    // Neighbourhood-aware distance (section 4.5): |V - P| plus how much the edges to the neighbours change.
    double score = distance;
    for (std::size_t j = 0; j < neighbors.size() && score <= best_score; ++j)
      score += std::abs(neighbor_lengths[j] - (p - neighbors[j]).norm());
    if (score < best_score ||
        (score == best_score && (distance < best_distance || (distance == best_distance && f < best_face)))) {
      best_score = score;
      best_distance = distance;
      best_face = f;
      best = p;
    }
  };
  if (count == 0) return best;
  std::size_t first = 0;
  for (std::size_t j = 1; j < count; ++j)  // (on a tie any will do: the result does not depend on the order)
    if (listed[j].centre2 < listed[first].centre2) first = j;
  consider(listed[first]);
  for (std::size_t j = 0; j < count; ++j)
    if (j != first) consider(listed[j]);
  return best;
}

namespace {
// How many edges of v would lie outside `keep` with v at `at` (its neighbours where they are now).
int edges_outside(const TriMesh& mesh, TriMesh::VertexHandle v, const Vec3& at, const EdgeInterval& keep) {
  int outside = 0;
  for (auto w : mesh.vv_range(v)) {
    const double length = (mesh.point(w) - at).norm();
    outside += length < keep.emin || length > keep.emax ? 1 : 0;
  }
  return outside;
}
}  // namespace

void projection(const ProjectionTarget& target, TriMesh& mesh, bool only_moved, const EdgeInterval* keep) {
  const int n = static_cast<int>(mesh.n_vertices());
  // Where each vertex was put by the previous projection onto the same target ([3] = 1: valid). A vertex
  // still there lies on the target, and Algorithm 4 would return it in place: it is skipped.
  OpenMesh::VPropHandleT<std::array<double, 4>> last;
  if (!mesh.get_property_handle(last, kProjectedProperty)) mesh.add_property(last, kProjectedProperty);
  OpenMesh::VPropHandleT<NearestTargetVertices> kept;
  if (!mesh.get_property_handle(kept, kNearestTargetProperty)) mesh.add_property(kept, kNearestTargetProperty);
  OpenMesh::MPropHandleT<const ProjectionTarget*> owner;
  if (!mesh.get_property_handle(owner, kNearestTargetOwnerProperty))
    mesh.add_property(owner, kNearestTargetOwnerProperty);
  if (mesh.property(owner) != &target) {  // kept for another target, or nothing kept yet
    for (int i = 0; i < n; ++i) mesh.property(kept, TriMesh::VertexHandle(i)).beyond = -1;
    mesh.property(owner) = &target;
  }
  std::vector<Vec3> projected(static_cast<std::size_t>(n));
  std::vector<char> changed(static_cast<std::size_t>(n), 0);
#pragma omp parallel
  {
    std::vector<Vec3> neighbors;
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < n; ++i) {
      const TriMesh::VertexHandle v(i);
      if (mesh.status(v).deleted() || mesh.is_isolated(v)) continue;
      const Vec3& p = mesh.point(v);
      const auto& l = mesh.property(last, v);
      if (only_moved && l[3] == 1.0 && l[0] == p[0] && l[1] == p[1] && l[2] == p[2]) continue;
      neighbors.clear();
      for (auto w : mesh.vv_range(v)) neighbors.push_back(mesh.point(w));
      projected[static_cast<std::size_t>(i)] = target.project(p, neighbors, 10, &mesh.property(kept, v));
      changed[static_cast<std::size_t>(i)] = 1;
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!changed[static_cast<std::size_t>(i)]) continue;
    const TriMesh::VertexHandle v(i);
    const Vec3& q = projected[static_cast<std::size_t>(i)];
    // (In vertex order, each against its neighbours as projected so far: the same result on any thread count.)
    if (keep != nullptr) {
      const Vec3 p = mesh.point(v);
      const int before = edges_outside(mesh, v, p, *keep);
      if (edges_outside(mesh, v, q, *keep) > before) {
        for (const double t : {0.5, 0.25})
          if (const Vec3 r = p + t * (q - p); edges_outside(mesh, v, r, *keep) <= before) {
            mesh.set_point(v, r);
            break;
          }
        continue;
      }
    }
    mesh.set_point(v, q);
    mesh.property(last, v) = {q[0], q[1], q[2], 1.0};
  }
}

void forget_projection(TriMesh& mesh) {
  OpenMesh::VPropHandleT<std::array<double, 4>> last;
  if (mesh.get_property_handle(last, kProjectedProperty)) mesh.remove_property(last);
  forget_nearest_target_vertices(mesh);
}

void forget_nearest_target_vertices(TriMesh& mesh) {
  OpenMesh::VPropHandleT<NearestTargetVertices> kept;
  if (mesh.get_property_handle(kept, kNearestTargetProperty)) mesh.remove_property(kept);
  OpenMesh::MPropHandleT<const ProjectionTarget*> owner;
  if (mesh.get_property_handle(owner, kNearestTargetOwnerProperty)) mesh.remove_property(owner);
}

}  // namespace carbonmesh
