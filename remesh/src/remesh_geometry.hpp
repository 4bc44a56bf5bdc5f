#pragma once
// Small geometric helpers shared by the remesher steps (internal).
#include <algorithm>
#include <array>
#include <cmath>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh::geometry {

// Below this smallest angle a triangle counts as degenerate; no step may turn a face by more than ~72 degrees.
inline constexpr double kMinAngle = 3.0 * 3.14159265358979 / 180;
inline constexpr double kMaxNormalTurnCos = 0.3;

inline Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  Vec3 n = OpenMesh::cross(b - a, c - a);
  const double l = n.norm();
  return l > 0 ? n / l : Vec3(0, 0, 0);
}

inline double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  return 0.5 * OpenMesh::cross(b - a, c - a).norm();
}

// Barycentric coordinates of p (on the triangle's plane) in the triangle a, b, c; the centroid's for a
// degenerate one.
inline std::array<double, 3> barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - a, w = p - a;
  const double uu = OpenMesh::dot(u, u), uv = OpenMesh::dot(u, v), vv = OpenMesh::dot(v, v);
  const double wu = OpenMesh::dot(w, u), wv = OpenMesh::dot(w, v);
  const double det = uu * vv - uv * uv;
  if (!(det > 1e-12 * uu * vv)) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const double beta = (vv * wu - uv * wv) / det, gamma = (uu * wv - uv * wu) / det;
  return {1 - beta - gamma, beta, gamma};
}

// Smallest interior angle (radians) of a triangle; 0 for a degenerate one.
inline double min_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  // The cosine of the angle at p; the smallest angle is the arccosine of the largest (one acos, not three).
  auto cosine = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = q - p, v = r - p;
    const double lu = u.norm(), lv = v.norm();
    if (lu <= 0 || lv <= 0) return 1.0;
    return std::clamp(OpenMesh::dot(u, v) / (lu * lv), -1.0, 1.0);
  };
  return std::acos(std::max({cosine(a, b, c), cosine(b, c, a), cosine(c, a, b)}));
}

// Whether flipping edge a-b of the faces (a, b, c) and (b, a, d) to c-d keeps their shape (section 3.5.3): the
// smallest angle of the new faces (a, d, c) and (b, c, d) is at least half of the old one, and neither new face
// turns against an old one (no fold).
inline bool flip_keeps_shape(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double pre = std::min(min_angle(a, b, c), min_angle(b, a, d));
  const double post = std::min(min_angle(a, d, c), min_angle(b, c, d));
  if (post < 0.5 * pre) return false;
  const Vec3 n1 = triangle_normal(a, b, c), n2 = triangle_normal(b, a, d);
  const Vec3 m1 = triangle_normal(a, d, c), m2 = triangle_normal(b, c, d);
  for (const Vec3& n : {n1, n2})
    for (const Vec3& m : {m1, m2})
      if (OpenMesh::dot(n, m) <= 0) return false;
  return true;
}

// The outgoing half-edges of `v` in the order of OpenMesh's vv_range / vf_range (clockwise from
// halfedge_handle(v)), by direct navigation: the circulators' lap bookkeeping cost more than a k-star walk itself.
template <class Visit>
inline void for_each_outgoing(const TriMesh& mesh, TriMesh::VertexHandle v, Visit&& visit) {
  const auto first = mesh.halfedge_handle(v);
  if (!first.is_valid()) return;
  auto h = first;
  do {
    visit(h);
    h = mesh.next_halfedge_handle(mesh.opposite_halfedge_handle(h));
  } while (h != first);
}

// The number of edges at `v`, as OpenMesh's valence() counts them (that one is a call into its library per vertex:
// 3.9 million calls on bunny, from the valence tables, statistics and ring weights of every iteration). Every step
// of the remesher counts valences with this one.
inline int valence(const TriMesh& mesh, TriMesh::VertexHandle v) {
  int count = 0;
  for_each_outgoing(mesh, v, [&](TriMesh::HalfedgeHandle) { ++count; });
  return count;
}

// Corner positions of a face.
inline void face_points(const TriMesh& mesh, TriMesh::FaceHandle f, Vec3& a, Vec3& b, Vec3& c) {
  auto h = mesh.halfedge_handle(f);
  a = mesh.point(mesh.to_vertex_handle(h));
  h = mesh.next_halfedge_handle(h);
  b = mesh.point(mesh.to_vertex_handle(h));
  h = mesh.next_halfedge_handle(h);
  c = mesh.point(mesh.to_vertex_handle(h));
}

inline Vec3 face_normal(const TriMesh& mesh, TriMesh::FaceHandle f) {
  Vec3 a, b, c;
  face_points(mesh, f, a, b, c);
  return triangle_normal(a, b, c);
}

// Area-weighted vertex normal computed from the current positions.
inline Vec3 vertex_normal(const TriMesh& mesh, TriMesh::VertexHandle v) {
  Vec3 n(0, 0, 0);
  for (auto f : mesh.vf_range(v)) {
    Vec3 a, b, c;
    face_points(mesh, f, a, b, c);
    n += OpenMesh::cross(b - a, c - a);
  }
  const double l = n.norm();
  return l > 0 ? n / l : Vec3(0, 0, 1);
}

// Two unit vectors spanning the plane orthogonal to the unit vector n.
inline void tangent_basis(const Vec3& n, Vec3& t1, Vec3& t2) {
  const Vec3 a = std::abs(n[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  t1 = OpenMesh::cross(n, a).normalized();
  t2 = OpenMesh::cross(n, t1);
}

inline double edge_length(const TriMesh& mesh, TriMesh::EdgeHandle e) {
  const auto h = mesh.halfedge_handle(e, 0);
  return (mesh.point(mesh.to_vertex_handle(h)) - mesh.point(mesh.from_vertex_handle(h))).norm();
}

// A border vertex moves along the quadratic through its two border neighbours (section 4.3.2), with the
// chord-length parameter t: curve(0) is its position, t in [ta/2, tb/2] (the middle halves of its border
// edges, as in border_optimizer and the nonlinear optimizer).
struct BorderCurve {
  Vec3 a, p, b;
  double ta = 0, tb = 0;
  Vec3 at(double t) const {
    const double la = t * (t - tb) / (ta * (ta - tb));
    const double lp = (t - ta) * (t - tb) / (ta * tb);
    const double lb = (t - ta) * t / (tb * (tb - ta));
    return la * a + lp * p + lb * b;
  }
  Vec3 derivative(double t) const {
    const double la = (2 * t - tb) / (ta * (ta - tb));
    const double lp = (2 * t - ta - tb) / (ta * tb);
    const double lb = (2 * t - ta) / (tb * (tb - ta));
    return la * a + lp * p + lb * b;
  }
  bool contains(double t) const { return t >= 0.5 * ta && t <= 0.5 * tb; }
};

// Every edge at `v` inside [emin, emax] and no face at `v` with an angle under 3 degrees.
inline bool star_inside(const TriMesh& mesh, TriMesh::VertexHandle v, double emin, double emax) {
  for (auto w : mesh.vv_range(v)) {
    const double l = (mesh.point(v) - mesh.point(w)).norm();
    if (!(l >= emin && l <= emax)) return false;
  }
  for (auto f : mesh.vf_range(v)) {
    Vec3 a, b, c;
    face_points(mesh, f, a, b, c);
    if (min_angle(a, b, c) < kMinAngle) return false;
  }
  return true;
}

}  // namespace carbonmesh::geometry
