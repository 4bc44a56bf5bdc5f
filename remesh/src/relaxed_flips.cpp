// Data-dependent flips whose new edge lies outside [emin, emax], with the vertices around relaxed until it is
// inside (not in the dissertation).
//
// data_dependent_flips() turns the diagonal of a quad that bridges a groove or cuts a ridge only where the other
// diagonal is already inside the interval. Where the pair's far corners are too near (a kite folded across a crease)
// or too far apart, the pair stays up to most of an edge from the input (bunny's two farthest spots, 0.598 and
// 0.549, are such pairs: the other diagonals are 0.80 and 2.28 long for [1.2, 1.8]). Here such an edge is flipped,
// and the interior vertices within kn + 2 rings of the new edge's ends are relaxed (Error_b with the interval hinge,
// Eq 4.7) and projected back onto the input, as in the feature snap. The result is kept only if
//  - the region has no more edges outside [emin, emax] or faces under 3 degrees than before, no face of it turns by
//    more than about 72 degrees, and neither new face turns that far from the pair it replaces;
//  - the two new faces end nearer the input than kGain of the pair's distance d (seven samples a face);
//  - every other face moved, and every input point near them (the corners, edge midpoints and centroids of the
//    input faces within emax of their box), ends no farther than the larger of d and its own distance before;
// else every position and the flip are undone. So no distance there grows past the pair's, and the vertices the
// snap put on input vertices may move too (those input vertices are among the points watched; both bunny pairs
// have snapped vertices in their rings), except those on a tip of the input (kTipDeficit). Farthest pairs first,
// one at a time, 32 at most.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/metrics.hpp"
#include "carbonmesh/remesh/remesh_steps.hpp"
#include "carbonmesh/remesh/triangle_tree.hpp"
#include "bounded_triangles.hpp"
#include "flips_toward_input.hpp"
#include "local_region.hpp"
#include "remesh_geometry.hpp"

namespace carbonmesh {
namespace {

using namespace triangle_tree;

constexpr double kGain = 0.9;      // the two new faces must end this factor nearer than the pair was, at least
constexpr int kRelaxRings = 2;     // interior vertices within kn + 2 rings of the new edge's ends are relaxed
constexpr int kPasses = 3;         // relax-and-project passes before the flip is given up
constexpr double kShortest = 0.5;  // new edges from this share of emin ...
constexpr double kLongest = 1.7;   // ... to this share of emax are tried (with 1.5 a diagonal 2.78 long across a
                                   // ridge of bunny's, 0.52 from the result, was not)
// A snapped vertex on an input vertex with a larger angle deficit stays (the cone tips of SnapToFeatures' test: 138
// degrees, one left its tip by 0.23 when they could move; bunny's snapped base rim vertices: 19-34; its largest: 68).
constexpr double kTipDeficit = M_PI / 3;
constexpr std::size_t kMaxTries = 32;  // pairs tried at most, farthest first (5-15 ms each; on a sphere with 8% noise
                                       // 87 were tried and none kept; bunny and armadillo try 20)

// Whether p is a vertex of the input (to within 1e-9 of its size) whose angle deficit (2 pi less the angles of
// the faces at it) is above kTipDeficit: a tip, around which the input turns as much as on a cone. `first`: the
// triangle of the input's first face in the tree.
bool on_tip(const TriMesh& input, const Tree& tree, Triangles::const_iterator first, const Vec3& p) {
  const auto hit = tree.closest_point_and_primitive(to_point(p));
  const TriMesh::FaceHandle f(static_cast<int>(hit.second - first));
  for (auto v : input.fv_range(f)) {
    const Vec3 corner = input.point(v);
    if ((corner - p).norm() > 1e-9 * (1 + corner.norm()) || input.is_boundary(v)) continue;
    double angles = 0;
    for (auto h : input.voh_range(v)) {
      const Vec3 u = input.point(input.to_vertex_handle(h)) - corner;
      const Vec3 w = input.point(input.to_vertex_handle(input.next_halfedge_handle(h))) - corner;
      angles += std::acos(std::clamp(OpenMesh::dot(u, w) / (u.norm() * w.norm()), -1.0, 1.0));
    }
    return std::abs(2 * M_PI - angles) > kTipDeficit;
  }
  return false;
}

// Whether one of the triangles is within `limit` of p.
bool within(const Vec3& p, const std::vector<BoundedTriangle>& triangles, double limit) {
  for (const auto& t : triangles) {
    const double reach = limit + t.radius;
    if ((p - t.centre).sqrnorm() <= reach * reach && point_triangle_distance(p, t.a, t.b, t.c) <= limit) return true;
  }
  return false;
}

}  // namespace

void relaxed_flips(TriMesh& mesh, const TriMesh& input, const Tree& tree, Triangles::const_iterator first,
                   std::vector<double>& distance, const ProjectionTarget& target, int kn, double emin, double emax,
                   double tolerance, const std::vector<char>* fixed, DataDependentFlips& result) {
  // The vertices the snap put on a tip of the input stay (see the top).
  std::vector<char> tip(mesh.n_vertices(), 0);
  if (fixed)
    for (std::size_t i = 0; i < std::min(fixed->size(), tip.size()); ++i)
      if ((*fixed)[i]) tip[i] = on_tip(input, tree, first, mesh.point(TriMesh::VertexHandle(static_cast<int>(i))));
  auto at = [&](TriMesh::FaceHandle f) -> double& { return distance[static_cast<std::size_t>(f.idx())]; };
  const std::vector<std::pair<double, int>> order = far_edges(mesh, distance, tolerance);
  LocalRegion local(emin, emax);
  std::vector<TriMesh::VertexHandle> region, around, variables;
  std::vector<TriMesh::FaceHandle> region_faces, moved_faces;
  std::vector<std::pair<TriMesh::VertexHandle, Vec3>> saved;
  std::vector<std::pair<TriMesh::FaceHandle, Vec3>> normals;
  std::vector<Vec3> neighbors, watched;
  std::vector<double> limits, watched_limits, moved_distances;
  std::vector<BoundedTriangle> balls, moved_balls, staying;
  std::vector<char> moved_mark;
  std::vector<Tree::Primitive_id> input_faces;
  for (const auto& [unused, index] : order) {
    const TriMesh::EdgeHandle e(index);
    if (mesh.status(e).deleted() || !mesh.is_flip_ok(e)) continue;
    const FlipQuad q = quad(mesh, e);
    const TriMesh::VertexHandle vc = q.c, vd = q.d;
    const Vec3 a = mesh.point(q.a), b = mesh.point(q.b), c = mesh.point(vc), d = mesh.point(vd);
    const double length = (c - d).norm();
    if (length >= emin && length <= emax) continue;  // (data_dependent_flips' case)
    if (length < kShortest * emin || length > kLongest * emax) continue;
    if (!flip_valence_ok(mesh, q)) continue;
    const auto f0 = mesh.face_handle(mesh.halfedge_handle(e, 0)), f1 = mesh.face_handle(mesh.halfedge_handle(e, 1));
    const double before = std::max(at(f0), at(f1)), goal = kGain * before;
    if (std::max(face_distance(tree, a, d, c), face_distance(tree, b, c, d)) >= goal) continue;
    if (result.relaxed_tries == kMaxTries) break;
    ++result.relaxed_tries;
    const Vec3 old_normal = geometry::face_normal(mesh, f0) + geometry::face_normal(mesh, f1);
    // The region: every vertex the relaxation moves, with their stars.
    region.clear();
    for (auto v : {vc, vd}) {
      local.collect(mesh, v, kn + kRelaxRings + 2, around);
      region.insert(region.end(), around.begin(), around.end());
    }
    std::sort(region.begin(), region.end());
    region.erase(std::unique(region.begin(), region.end()), region.end());
    const std::size_t flaws_before = local.flaws(mesh, region);
    local.faces(mesh, region, region_faces);
    // The interior vertices within kn + 2 rings of the new edge's ends (found with the edge flipped), and the faces
    // at them.
    mesh.flip(e);
    variables.clear();
    for (auto v : {vc, vd}) {
      local.collect(mesh, v, kn + kRelaxRings, around);
      for (auto w : around)
        if (!mesh.is_boundary(w) && !tip[static_cast<std::size_t>(w.idx())]) variables.push_back(w);
    }
    mesh.flip(e);
    std::sort(variables.begin(), variables.end());
    variables.erase(std::unique(variables.begin(), variables.end()), variables.end());
    moved_faces.clear();
    for (auto w : variables)
      for (auto f : mesh.vf_range(w)) moved_faces.push_back(f);
    moved_faces.push_back(f0);
    moved_faces.push_back(f1);
    std::sort(moved_faces.begin(), moved_faces.end());
    moved_faces.erase(std::unique(moved_faces.begin(), moved_faces.end()), moved_faces.end());
    // The input points watched: those of the input faces within emax of the moved faces' box (farther, a part of the
    // input was cut off: RemeshResult::farthest_input) that are nearest a moved face (only those can get farther)
    // and have no face that stays within their limit, the larger of the pair's distance and their own. They are
    // found from the faces as they are now, but only at the first pass that passes the other tests (on bunny 12 of
    // 20 tries never do; finding them takes about as long as a relaxation).
    CGAL::Bbox_3 box;
    for (auto f : moved_faces)
      for (auto v : mesh.fv_range(f)) box += to_point(mesh.point(v)).bbox();
    const double margin = std::max(before, emax);
    box = CGAL::Bbox_3(box.xmin() - margin, box.ymin() - margin, box.zmin() - margin, box.xmax() + margin,
                       box.ymax() + margin, box.zmax() + margin);
    balls = bounded(mesh, region_faces);
    moved_mark.assign(region_faces.size(), 0);
    staying.clear();
    for (std::size_t i = 0; i < region_faces.size(); ++i) {
      moved_mark[i] = std::binary_search(moved_faces.begin(), moved_faces.end(), region_faces[i]);
      if (!moved_mark[i]) staying.push_back(balls[i]);
    }
    bool watched_known = false;
    auto watch = [&] {  // (reads the positions before the move from balls and staying only)
      input_faces.clear();
      tree.all_intersected_primitives(box, std::back_inserter(input_faces));
      std::sort(input_faces.begin(), input_faces.end());
      watched.clear();
      watched_limits.clear();
      std::size_t hint = balls.size();  // (the points come in sevens, one input face's: the last one's nearest first)
      for (const auto& t : input_faces) {
        const Vec3 x = to_vec(t->vertex(0)), y = to_vec(t->vertex(1)), z = to_vec(t->vertex(2));
        for (const Vec3& p : {x, y, z, 0.5 * (x + y), 0.5 * (y + z), 0.5 * (z + x), (x + y + z) / 3.0}) {
          const double own = nearest_distance(p, balls, std::numeric_limits<double>::infinity(), hint);
          const double limit = std::max(before, own);
          if (hint < balls.size() && moved_mark[hint] && !within(p, staying, limit)) {
            watched.push_back(p);
            watched_limits.push_back(limit);
          }
        }
      }
      watched_known = true;
    };
    mesh.flip(e);
    normals.clear();
    for (auto f : region_faces) normals.emplace_back(f, geometry::face_normal(mesh, f));
    limits.clear();
    for (auto f : moved_faces) limits.push_back(f == f0 || f == f1 ? goal : std::max(before, at(f)));
    saved.clear();
    for (auto w : variables) saved.emplace_back(w, mesh.point(w));
    bool kept = false;
    std::size_t last_flaws = 0;
    for (int pass = 0; pass < kPasses && !kept; ++pass) {
      optimize_vertices(mesh, variables, emin, emax);
      for (auto w : variables) project_with_ring(mesh, target, w, neighbors);
      bool folded = false;
      for (const auto& [f, n] : normals)
        folded = folded || OpenMesh::dot(n, geometry::face_normal(mesh, f)) < geometry::kMaxNormalTurnCos;
      for (auto f : {f0, f1})  // (against the pair they replace)
        folded = folded || OpenMesh::dot(old_normal.normalized(), geometry::face_normal(mesh, f)) <
                               geometry::kMaxNormalTurnCos;
      const std::size_t flaws = local.flaws(mesh, region);
      if (!folded && flaws <= flaws_before) {
        kept = true;
        moved_distances.clear();
        for (std::size_t k = 0; k < moved_faces.size() && kept; ++k) {
          moved_distances.push_back(face_distance(tree, mesh, moved_faces[k]));
          kept = moved_distances.back() < limits[k];
        }
        if (kept) {
          if (!watched_known) watch();
          moved_balls = bounded(mesh, moved_faces);
          for (std::size_t k = 0; k < watched.size() && kept; ++k)
            kept = within(watched[k], moved_balls, watched_limits[k]);
        }
      }
      if (kept) break;
      if (pass > 0 && flaws >= last_flaws) break;  // no progress
      last_flaws = flaws;
    }
    if (!kept) {
      for (const auto& [w, p] : saved) mesh.set_point(w, p);
      mesh.flip(e);
      for (auto f : {f0, f1}) at(f) = face_distance(tree, mesh, f);  // (flipped back, the two may have swapped)
      continue;
    }
    ++result.relaxed_flips;
    for (std::size_t k = 0; k < moved_faces.size(); ++k) at(moved_faces[k]) = moved_distances[k];  // (as checked)
  }
}

}  // namespace carbonmesh
