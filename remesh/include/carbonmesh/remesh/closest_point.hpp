#pragma once
// The closest point of a triangle to a point: one definition for the remesher's projection and the AABB trees.
#include <array>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection 5.1.5), on plain coordinates:
// the same point as CGAL's projection, in a fraction of its time (no orientation predicates).
inline std::array<double, 3> closest_point_on_triangle(const std::array<double, 3>& p, const std::array<double, 3>& a,
                                                       const std::array<double, 3>& b,
                                                       const std::array<double, 3>& c) {
  const auto dot = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  };
  const auto minus = [](const std::array<double, 3>& u, const std::array<double, 3>& v) {
    return std::array<double, 3>{u[0] - v[0], u[1] - v[1], u[2] - v[2]};
  };
  const auto along = [](const std::array<double, 3>& o, double t, const std::array<double, 3>& d) {  // o + t d
    return std::array<double, 3>{o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
  };
  const std::array<double, 3> ab = minus(b, a), ac = minus(c, a), ap = minus(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const std::array<double, 3> bp = minus(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return along(a, d1 / (d1 - d3), ab);
  const std::array<double, 3> cp = minus(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return along(a, d2 / (d2 - d6), ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return along(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), minus(c, b));
  const double denom = 1.0 / (va + vb + vc);
  return along(along(a, vb * denom, ab), vc * denom, ac);
}

// The same on the mesh's points.
inline Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const auto in = [](const Vec3& v) { return std::array<double, 3>{v[0], v[1], v[2]}; };
  const std::array<double, 3> q = closest_point_on_triangle(in(p), in(a), in(b), in(c));
  return Vec3(q[0], q[1], q[2]);
}

}  // namespace carbonmesh
