#include "surface_projector.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

namespace carbonmesh::detail {
namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Triangles = std::vector<Triangle>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
}  // namespace

struct SurfaceProjector::Impl {
  Triangles triangles;
  Tree tree;
};

SurfaceProjector::SurfaceProjector(const TriMesh& surface) : impl_(std::make_unique<Impl>()) {
  auto to_point = [](const Vec3& p) { return Point(p[0], p[1], p[2]); };
  impl_->triangles.reserve(surface.n_faces());
  for (auto f : surface.faces()) {
    auto it = surface.cfv_iter(f);
    const Point a = to_point(surface.point(*it++));
    const Point b = to_point(surface.point(*it++));
    const Point c = to_point(surface.point(*it));
    impl_->triangles.emplace_back(a, b, c);
  }
  impl_->tree.insert(impl_->triangles.begin(), impl_->triangles.end());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

SurfaceProjector::~SurfaceProjector() = default;

void SurfaceProjector::closest_points(const std::vector<Vec3>& points, std::vector<Vec3>& closest) const {
  const bool hints = closest.size() == points.size();
  closest.resize(points.size());
  const Tree& tree = impl_->tree;
  const long n = static_cast<long>(points.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const Vec3& p = points[static_cast<std::size_t>(i)];
    Vec3& c = closest[static_cast<std::size_t>(i)];
    const Point q = hints ? tree.closest_point(Point(p[0], p[1], p[2]), Point(c[0], c[1], c[2]))
                          : tree.closest_point(Point(p[0], p[1], p[2]));
    c = Vec3(q.x(), q.y(), q.z());
  }
}

}  // namespace carbonmesh::detail
