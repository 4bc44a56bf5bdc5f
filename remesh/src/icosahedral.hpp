#pragma once
// The pieces the geodesic and the Goldberg-Coxeter spheres share (shapes.cpp, goldberg_coxeter.cpp): the unit
// icosahedron, points of its faces on the sphere, and the springs that even out the triangles.
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh::icosahedral {

// The unit icosahedron, faces counter-clockwise seen from outside.
inline std::pair<std::vector<Vec3>, std::vector<std::array<int, 3>>> icosahedron() {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> points = {{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                              {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<int, 3>> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                           {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                           {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                           {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : points) p.normalize();
  return {points, faces};
}

// Point along the great-circle arc from unit vector a to unit vector b, at the fraction t of its angle.
inline Vec3 slerp(const Vec3& a, const Vec3& b, double t) {
  const double angle = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
  if (angle < 1e-12) return a;
  return (a * std::sin((1 - t) * angle) + b * std::sin(t * angle)) / std::sin(angle);
}

// The point of the spherical triangle (a, b, c) (unit vectors) with the weights wa, wb, wc (summing to 1) on its
// corners. The edges are divided into equal arcs; an interior point is where the three great circles through the
// edge points of equal weight (wb on b, wc on c, wa on a) cross: the normalised mean of their three pairwise
// crossings. A weight of exactly 0 puts the point on the opposite edge.
inline Vec3 spherical_point(const Vec3& a, const Vec3& b, const Vec3& c, double wa, double wb, double wc) {
  if (wc == 0) return slerp(a, b, wb);
  if (wb == 0) return slerp(a, c, wc);
  if (wa == 0) return slerp(b, c, wc);
  // Normals of the great circles of constant weight on b, on c and on a.
  const Vec3 nb = slerp(a, b, wb).cross(slerp(c, b, wb));
  const Vec3 nc = slerp(a, c, wc).cross(slerp(b, c, wc));
  const Vec3 na = slerp(b, a, wa).cross(slerp(c, a, wa));
  const Vec3 centre = a + b + c;
  auto crossing = [&](const Vec3& n1, const Vec3& n2) {
    const Vec3 x = n1.cross(n2).normalized();
    return x.dot(centre) < 0 ? -x : x;
  };
  return (crossing(nb, nc) + crossing(nc, na) + crossing(na, nb)).normalized();
}

// The point of the capsule (radius r, straight part from -half to +half along z) nearest to p.
inline Vec3 onto_capsule(const Vec3& p, double r, double half) {
  const double z = std::clamp(p[2], -half, half);
  Vec3 d(p[0], p[1], p[2] - z);
  const double l = d.norm();
  if (!(l > 0)) d = Vec3(1, 0, 0);
  else d /= l;
  return Vec3(0, 0, z) + r * d;
}

constexpr int kSpringIterations = 50;

// Spring relaxation toward the mean edge, each step's points put back onto a surface by `onto` (a point -> its point
// on the surface). Each step reads the old positions only (in parallel, the same for any thread count).
template <typename Onto>
void even_out(TriMesh& mesh, const Onto& onto) {
  double mean = 0;
  for (auto e : mesh.edges()) mean += mesh.calc_edge_length(e);
  mean /= static_cast<double>(mesh.n_edges());
  std::vector<Vec3> next(mesh.n_vertices());
  const int n = static_cast<int>(mesh.n_vertices());
  for (int it = 0; it < kSpringIterations; ++it) {
#pragma omp parallel for schedule(static) if (n >= 20000)
    for (int i = 0; i < n; ++i) {
      const TriMesh::VertexHandle v(i);
      Vec3 force(0, 0, 0);
      for (auto w : mesh.vv_range(v)) {
        const Vec3 d = mesh.point(w) - mesh.point(v);
        const double l = d.norm();
        force += (l - mean) / l * d;
      }
      next[static_cast<std::size_t>(i)] = onto(mesh.point(v) + 0.3 * force);
    }
    for (auto v : mesh.vertices()) mesh.set_point(v, next[static_cast<std::size_t>(v.idx())]);
  }
}

// The springs on the sphere of `radius` about the origin: they even out the density within the icosahedron's faces,
// so the dual optimisation has less to flow (C998460: 225 L-BFGS iterations instead of 671), though the spread of the
// edges near the 12 corners grows (longest / shortest 1.34 instead of 1.25 at frequency 129 with sqrt(3)).
inline void even_out_on_sphere(TriMesh& mesh, double radius) {
  even_out(mesh, [radius](const Vec3& p) { return p.normalized() * radius; });
}

}  // namespace carbonmesh::icosahedral
