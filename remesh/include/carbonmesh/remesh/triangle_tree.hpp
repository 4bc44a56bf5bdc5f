#pragma once
// The CGAL AABB tree over a mesh's triangles, for closest-point and distance queries (Hausdorff distance,
// the dual's surface projection, the mirror-plane search): one definition of its types and of the triangle
// list it is built on. Needs CGAL (header-only) in the including target.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh::triangle_tree {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Triangles = std::vector<Triangle>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

inline Point to_point(const Vec3& p) { return Point(p[0], p[1], p[2]); }

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

}  // namespace carbonmesh::triangle_tree
