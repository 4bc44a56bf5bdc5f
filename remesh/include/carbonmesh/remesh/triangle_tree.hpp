#pragma once
// The CGAL AABB tree over a mesh's triangles, for closest-point and distance queries (Hausdorff distance,
// the dual's surface projection, the mirror-plane search): one definition of its types and of the triangle
// list it is built on. Needs CGAL (header-only) in the including target.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <vector>

#include "carbonmesh/remesh/closest_point.hpp"
#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh::triangle_tree {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Triangles = std::vector<Triangle>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;

inline Point to_point(const Vec3& p) { return Point(p[0], p[1], p[2]); }
inline Vec3 to_vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

// The closest point of triangle t to p (closest_point_on_triangle: CGAL's projection with its orientation
// predicates took 10% of bunny's remesh).
inline Point closest_point_on(const Triangle& t, const Point& p) {
  const auto in = [](const Point& q) { return std::array<double, 3>{q.x(), q.y(), q.z()}; };
  const std::array<double, 3> c = closest_point_on_triangle(in(p), in(t[0]), in(t[1]), in(t[2]));
  return Point(c[0], c[1], c[2]);
}

// CGAL's AABB traits with closest_point_on() for the primitives' projection (the tree's closest-point and distance
// queries; the traversal and the box tests are CGAL's).
class Traits : public CGAL::AABB_traits<Kernel, Primitive> {
 public:
  class Closest_point {
   public:
    explicit Closest_point(const Traits&) {}
    // The closest point of the primitive, or `bound` where that is nearer (as CGAL's).
    Point operator()(const Point& p, const Primitive& primitive, const Point& bound) const {
      const Point c = closest_point_on(primitive.datum(), p);
      return CGAL::squared_distance(p, c) > CGAL::squared_distance(p, bound) ? bound : c;
    }
  };
  Closest_point closest_point_object() const { return Closest_point(*this); }
};

using Tree = CGAL::AABB_tree<Traits>;

// The mesh's triangles in face order (the tree keeps iterators into this list: keep it alive and unchanged).
inline Triangles triangles_of(const TriMesh& mesh) {
  Triangles out;
  out.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    auto it = mesh.cfv_iter(f);
    const Point a = to_point(mesh.point(*it++));
    const Point b = to_point(mesh.point(*it++));
    const Point c = to_point(mesh.point(*it));
    out.emplace_back(a, b, c);
  }
  return out;
}

// A surface's triangles and their tree, built once for closest-point queries (from any thread): the remesher's
// steps after Algorithm 1 share the input's.
class SurfaceTree {
 public:
  explicit SurfaceTree(const TriMesh& surface)
      : triangles_(triangles_of(surface)), tree_(triangles_.begin(), triangles_.end()) {
    if (!triangles_.empty()) {
      tree_.build();
      tree_.accelerate_distance_queries();
    }
  }
  SurfaceTree(const SurfaceTree&) = delete;
  SurfaceTree& operator=(const SurfaceTree&) = delete;

  const Tree& tree() const { return tree_; }
  const Triangles& triangles() const { return triangles_; }
  // The face index of a primitive: the triangles are in face order.
  Triangles::const_iterator first() const { return triangles_.begin(); }

 private:
  Triangles triangles_;  // (before tree_, which keeps iterators into it)
  Tree tree_;
};

// CGAL's closest_point_and_primitive(query, hint) for n queries near each other, each from its own hint, with one
// box search instead of n traversals: the primitives that meet the queries' box grown by the largest hint distance
// are listed in the tree's traversal order, and each query takes them in that order under the traversal's rule (a
// primitive whose closest point is no farther than the current one and differs from it replaces it). A primitive
// off the list is farther than the hint; one the traversal prunes is farther than its current point, or exactly as
// far in a box exactly as far (only then may the two name different primitives, at the same distance). The surface
// fit's samples: 12 queries a face.
inline void closest_points_from_hints(const Tree& tree, const Point* queries, Tree::Point_and_primitive_id* hints,
                                      std::size_t n, std::vector<Tree::Primitive_id>& listed) {
  if (n == 0 || tree.empty()) return;
  double r2 = 0, lo[3], hi[3], scale = 1;
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = queries[0][k];
  for (std::size_t i = 0; i < n; ++i) {
    r2 = std::max(r2, CGAL::squared_distance(queries[i], hints[i].first));
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], queries[i][k]);
      hi[k] = std::max(hi[k], queries[i][k]);
      scale = std::max(scale, std::abs(queries[i][k]));
    }
  }
  const double pad = std::sqrt(r2) * (1 + 1e-9) + 1e-12 * scale;  // (rounding in the box's bounds)
  listed.clear();
  tree.all_intersected_primitives(CGAL::Bbox_3(lo[0] - pad, lo[1] - pad, lo[2] - pad, hi[0] + pad, hi[1] + pad,
                                               hi[2] + pad),
                                  std::back_inserter(listed));
  for (std::size_t i = 0; i < n; ++i) {
    const Point& q = queries[i];
    Point best = hints[i].first;
    double best2 = CGAL::squared_distance(q, best);
    for (const auto& id : listed) {
      const Point c = closest_point_on(*id, q);
      const double d2 = CGAL::squared_distance(q, c);
      if (d2 > best2 || c == best) continue;
      best = c;
      best2 = d2;
      hints[i] = {c, id};
    }
  }
}

// The largest distance to the tree's surface of seven points of the triangle a, b, c: its centroid, its edge
// midpoints and the points a third of the way from the centroid to each corner. Each point's search starts from
// the closest point of the one before (the first from the tree's own hint): the nearest distance is the same
// from any start, and the points are close together.
inline double face_distance(const Tree& tree, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 g = (a + b + c) / 3.0;
  double worst = 0;
  Point closest;
  bool first = true;
  for (const Vec3& p : {g, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a), (2.0 * g + a) / 3.0, (2.0 * g + b) / 3.0,
                        (2.0 * g + c) / 3.0}) {
    const Point q = to_point(p);
    closest = first ? tree.closest_point(q) : tree.closest_point(q, closest);
    first = false;
    worst = std::max(worst, Traits().squared_distance_object()(q, closest));  // (as Tree::squared_distance)
  }
  return std::sqrt(worst);
}

// The same for a face of `mesh` (its corners from its halfedge on, as geometry::face_points lists them).
inline double face_distance(const Tree& tree, const TriMesh& mesh, TriMesh::FaceHandle f) {
  const auto h0 = mesh.halfedge_handle(f), h1 = mesh.next_halfedge_handle(h0), h2 = mesh.next_halfedge_handle(h1);
  return face_distance(tree, mesh.point(mesh.to_vertex_handle(h0)), mesh.point(mesh.to_vertex_handle(h1)),
                       mesh.point(mesh.to_vertex_handle(h2)));
}

}  // namespace carbonmesh::triangle_tree
