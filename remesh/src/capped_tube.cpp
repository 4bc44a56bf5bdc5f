// A capped nanotube (5h, 5k): the icosahedral fullerene C_20T (h, k) opened along a five-fold axis and lengthened
// by whole periods of the tube (carbonmesh/remesh/shapes.hpp).
//
// The icosahedron seen along a five-fold axis is a pentagonal pyramid (5 faces around the corner N), a pentagonal
// antiprism (10 faces between the corner rings U and L) and a second pyramid (around S). Unrolled, the antiprism is a
// strip of the lattice whose upper border U_0 .. U_5 = U_0 is the lattice vector C = 5 w, w = (h, k) the
// icosahedron's edge, and whose lower border is the upper one moved by t = w turned by -60 degrees: a cylinder of
// circumference C, the tube (5h, 5k). Adding to t the tube's translation vector p times j lengthens the strip by j
// periods and leaves the two pyramids, the caps, as they were: 12 pentagons (the corners), hexagons otherwise.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "carbonmesh/remesh/shapes.hpp"
#include "add_faces.hpp"
#include "icosahedral.hpp"
#include "lattice_net.hpp"
#include "apex_capped_tube.hpp"

namespace carbonmesh {

namespace {

using lattice_net::LatticePoint;
using lattice_net::NetFace;
using lattice_net::turned;
using lattice_net::operator+;
using lattice_net::operator*;
using lattice_net::operator-;

constexpr double kPi = 3.14159265358979323846;

struct Layout {
  LatticePoint w{}, period{};  // the icosahedron's edge and the tube's translation vector
  long T = 0, period_triangles = 0;
};

Layout layout(int n, int m) {
  Layout out;
  const long h = n / 5, k = m / 5;
  out.w = {h, k};
  out.T = h * h + h * k + k * k;
  out.period = translation_vector(h, k);  // square to w, pointing from the U ring to the L ring
  out.period_triangles = 10 * lattice_net::det(out.period, out.w);  // 5 parallelograms of 2 det triangles each
  return out;
}

}  // namespace

void check_capped_tube(int n, int m) {
  if (n < 0 || m < 0 || (n == 0 && m == 0))
    throw InputError(fmt::format("capped tube ({}, {}): the chiral indices must be >= 0, one > 0", n, m));
  if (!icosahedral_caps(n, m)) {
    if (triangulation_number(n, m) > 25 * kMaxTriangulationNumber)
      throw InputError(fmt::format("capped tube ({}, {}): n^2 + nm + m^2 is more than {}", n, m,
                                   25 * kMaxTriangulationNumber));
    return;
  }
  if (triangulation_number(n / 5, m / 5) > kMaxTriangulationNumber)
    throw InputError(fmt::format("capped tube ({}, {}): its caps' C_20T has T = {}, more than {}", n, m,
                                 triangulation_number(n / 5, m / 5), kMaxTriangulationNumber));
}

double capped_tube_radius(int n, int m, double edge) {
  const double nn = n, mm = m;
  return edge * std::sqrt(nn * nn + nn * mm + mm * mm) / (2 * kPi);
}

TriMesh capsule_mesh(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& triangles, long expected,
                     int n, int m, double radius, double half) {
  TriMesh mesh;
  for (const auto& p : points) mesh.add_vertex(p);
  if (!add_faces(mesh, triangles)) throw std::logic_error("capped tube: a triangle that does not fit its neighbours");
  if (static_cast<long>(mesh.n_faces()) != expected || static_cast<long>(mesh.n_vertices()) != expected / 2 + 2)
    throw std::logic_error(fmt::format("capped tube ({}, {}): {} vertices and {} triangles, not {} and {}", n, m,
                                       mesh.n_vertices(), mesh.n_faces(), expected / 2 + 2, expected));
  // The sphere's springs, each step back onto the capsule.
  icosahedral::even_out(mesh, [&](const Vec3& p) { return icosahedral::onto_capsule(p, radius, half); });
  mesh.update_normals();
  return mesh;
}

const char* cap_kind_name(CapKind kind) {
  switch (kind) {
    case CapKind::icosahedral: return "icosahedral";
    case CapKind::apex: return "apex";
  }
  return "";
}

const char* cap_kind_description(CapKind kind) {
  switch (kind) {
    case CapKind::icosahedral: return "the halves of an icosahedral fullerene C_20T";
    case CapKind::apex: return "apex caps (five lattice triangles around a pentagon, five more pentagons on their rim)";
  }
  return "";
}

bool icosahedral_caps(int n, int m) { return n % 5 == 0 && m % 5 == 0; }

LatticePoint translation_vector(long n, long m) {
  const long d = std::gcd(2 * m + n, 2 * n + m);
  return {(2 * m + n) / d, -(2 * n + m) / d};
}

double capped_tube_period(int n, int m, double edge) {
  check_capped_tube(n, m);
  return edge * std::sqrt(static_cast<double>(lattice_net::squared_length(translation_vector(n, m))));
}

CappedTube make_capped_tube(const CappedTubeShape& shape) {
  check_capped_tube(shape.n, shape.m);
  if (!(shape.edge > 0) || !std::isfinite(shape.edge)) throw InputError("capped tube: the edge must be a positive number");
  if (!(shape.length >= 0) || !std::isfinite(shape.length))
    throw InputError("capped tube: the length must be a number >= 0");
  if (!icosahedral_caps(shape.n, shape.m)) return apex_cap::make_apex_capped_tube(shape);
  const Layout l = layout(shape.n, shape.m);
  const double a = shape.edge, r = capped_tube_radius(shape.n, shape.m, a);
  const double period = capped_tube_period(shape.n, shape.m, a);
  const long max_periods = (20 * kMaxTriangulationNumber - 20 * l.T) / l.period_triangles;
  const double wanted = std::round(shape.length / period);
  if (wanted > static_cast<double>(max_periods))
    throw InputError(fmt::format("capped tube ({}, {}): a length of {} needs more than {} triangles", shape.n, shape.m,
                                 shape.length, 20 * kMaxTriangulationNumber));
  const long j = static_cast<long>(wanted);  // (the length is >= 0)

  // The net: N = 0, U_i = 1 + i, L_i = 6 + i, S = 11.
  const LatticePoint w = l.w, t0 = turned(w, -1), t = t0 + j * l.period, zero{0, 0};
  std::vector<NetFace> faces;
  for (int i = 0; i < 5; ++i) {
    const int u = 1 + i, u1 = 1 + (i + 1) % 5, lo = 6 + i, lo1 = 6 + (i + 1) % 5;
    faces.push_back({{u, u1, 0}, {zero, w, turned(w, 1)}});
    faces.push_back({{u, lo, u1}, {zero, t, w}});
    faces.push_back({{lo, lo1, u1}, {t, t + w, w}});
    faces.push_back({{lo, 11, lo1}, {zero, t0, w}});
  }
  const lattice_net::Folded folded = lattice_net::fold_lattice(12, faces);

  // Where the points go: the capsule of the tube's radius r whose straight part is the j periods, D = j |p| long.
  // The caps and the half-belts next to them are the Goldberg-Coxeter sphere's halves (the unit icosahedron with N
  // on the z axis, its points placed as that sphere's are), of radius r, moved by D / 2 up and down; the periods
  // between them are the strip rolled onto the cylinder. With no period added it is the Goldberg-Coxeter sphere.
  const double half_straight = 0.5 * static_cast<double>(j) * period;
  std::array<Vec3, 12> corners;
  const double c = 1 / std::sqrt(5.0), s = 2 / std::sqrt(5.0);  // the rings' height and radius on the unit sphere
  corners[0] = Vec3(0, 0, 1);
  corners[11] = Vec3(0, 0, -1);
  for (int i = 0; i < 5; ++i) {
    const double phi = 2 * kPi * i / 5, psi = phi + kPi / 5;
    corners[static_cast<std::size_t>(1 + i)] = Vec3(s * std::cos(phi), s * std::sin(phi), c);
    corners[static_cast<std::size_t>(6 + i)] = Vec3(s * std::cos(psi), s * std::sin(psi), -c);
  }
  const auto on_sphere = [&](const std::array<int, 3>& k, const std::array<double, 3>& b, double shift) {
    const Vec3 u = icosahedral::spherical_point(corners[static_cast<std::size_t>(k[0])],
                                                corners[static_cast<std::size_t>(k[1])],
                                                corners[static_cast<std::size_t>(k[2])], b[0], b[1], b[2]);
    return r * u + Vec3(0, 0, shift);
  };
  const long T = l.T, belt_period = lattice_net::det(l.period, w);  // det(x, w): how far below the U ring, in T / H
  std::vector<Vec3> points(folded.places.size());
  for (std::size_t v = 0; v < points.size(); ++v) {
    const auto& place = folded.places[v];
    const int kind = place.face % 4, i = place.face / 4;
    const NetFace& f = faces[static_cast<std::size_t>(place.face)];
    if (kind == 0 || kind == 3) {  // a cap
      points[v] = on_sphere(f.corners, place.weights, kind == 0 ? half_straight : -half_straight);
      continue;
    }
    // A point of the belt: its lattice point in the chart with U_i at the origin (exact: the weights' sum rounded).
    double pi = 0, pj = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      pi += place.weights[k] * static_cast<double>(f.at[k][0]);
      pj += place.weights[k] * static_cast<double>(f.at[k][1]);
    }
    LatticePoint q{std::lround(pi), std::lround(pj)};
    const long below = lattice_net::det(q, w);  // T at the L ring of the sphere's antiprism
    const bool upper = 2 * below <= T, lower = 2 * (below - j * belt_period) >= T;
    if (!upper && !lower) {  // the periods between: the cylinder
      const double along = static_cast<double>(2 * (q[0] * w[0] + q[1] * w[1]) + q[0] * w[1] + q[1] * w[0]) /
                           static_cast<double>(2 * T);  // in edges w
      const double angle = 2 * kPi * (i + along) / 5;
      const double depth = static_cast<double>(2 * below - T) / static_cast<double>(2 * T) * 0.5 * std::sqrt(3.0) *
                           std::sqrt(static_cast<double>(T)) * a;  // below the sphere's equator
      points[v] = Vec3(r * std::cos(angle), r * std::sin(angle), half_straight - depth);
      continue;
    }
    if (!upper) q = q - j * l.period;
    // The antiprism face of the sphere holding q: (U_k, L_k, U_k+1) or (L_k, L_k+1, U_k+1), k = i - 1 .. i + 1.
    bool found = false;
    for (int di : {0, 1, -1}) {
      const LatticePoint o = di * w;
      const int k = (i + di + 5) % 5, k1 = (k + 1) % 5;
      const std::array<std::array<LatticePoint, 3>, 2> triangles = {
          {{o, o + t0, o + w}, {o + t0, o + t0 + w, o + w}}};
      const std::array<std::array<int, 3>, 2> ids = {{{1 + k, 6 + k, 1 + k1}, {6 + k, 6 + k1, 1 + k1}}};
      for (std::size_t e = 0; e < 2 && !found; ++e) {
        const auto& x = triangles[e];
        const std::array<long, 3> weights = {lattice_net::det(x[1] - q, x[2] - q), lattice_net::det(x[2] - q, x[0] - q),
                                             lattice_net::det(x[0] - q, x[1] - q)};
        if (weights[0] < 0 || weights[1] < 0 || weights[2] < 0) continue;
        const double sum = static_cast<double>(weights[0] + weights[1] + weights[2]);
        points[v] = on_sphere(ids[e],
                              {static_cast<double>(weights[0]) / sum, static_cast<double>(weights[1]) / sum,
                               static_cast<double>(weights[2]) / sum},
                              upper ? half_straight : -half_straight);
        found = true;
      }
      if (found) break;
    }
    if (!found) throw std::logic_error("capped tube: a belt point outside the sphere's antiprism");
  }

  CappedTube out;
  out.mesh = capsule_mesh(points, folded.triangles, 20 * l.T + j * l.period_triangles, shape.n, shape.m, r,
                          half_straight);
  out.periods = static_cast<int>(j);
  out.radius = r;
  out.straight_length = 2 * half_straight;
  out.period = period;
  return out;
}

}  // namespace carbonmesh
