// Capped nanotubes of any chirality with ring caps (ring_capped_tube.hpp).
//
// Unrolled, the tube is the strip of the lattice between two polylines, each repeating with the chiral vector C. The
// upper one P_0, P_1 = P_0 + f_0, .., P_6 = P_0 + C runs through the upper cap's six pentagons: at each the lattice
// below it keeps its angle, the cap above it has 60 degrees less (300 degrees around a pentagon). Going round the cap,
// each side therefore turns 60 degrees more than the rim does: the cap is the flat lattice hexagon with sides f_i
// turned by i * 60 degrees, closed when their sum is 0. The lower polyline Q_j = T - P_-j is the upper one turned by
// 180 degrees about T / 2, with the lower cap the upper one's image. The net folded (lattice_net) is then 4 triangles
// of each hexagon and the 12 triangles of the belt between the polylines: a polyhedron with 12 corners of 300
// degrees, whose folded lattice has 12 vertices of valence 5 (the dual's pentagons) and valence 6 otherwise.
// Moving T by the tube's translation vector p lengthens the belt by one period.
#include "ring_capped_tube.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "carbonmesh/remesh/error.hpp"
#include "add_faces.hpp"
#include "icosahedral.hpp"

namespace carbonmesh::ring_cap {

namespace {

using lattice_net::det;
using lattice_net::squared_length;
using lattice_net::LatticePoint;
using lattice_net::NetFace;
using lattice_net::turned;
using lattice_net::operator+;
using lattice_net::operator*;
using lattice_net::operator-;
using Steps = std::array<LatticePoint, 6>;

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Twice the dot product of two lattice vectors (unit edges): exact in integers.
long dot2(LatticePoint a, LatticePoint b) { return 2 * a[0] * b[0] + 2 * a[1] * b[1] + a[0] * b[1] + a[1] * b[0]; }

// A lattice point in the plane, in unit edges (e1 along x).
std::array<double, 2> cartesian(double i, double j) { return {i + 0.5 * j, 0.5 * std::sqrt(3.0) * j}; }

// The polyline through the upper cap's pentagons, P_k for any k (P_k+6 = P_k + C).
struct Rim {
  Steps steps{};
  LatticePoint chiral{};
  std::array<LatticePoint, 7> at{};  // P_0 = 0 .. P_6 = C
  LatticePoint point(long k) const {
    const long q = static_cast<long>(std::floor(static_cast<double>(k) / 6.0));
    return at[static_cast<std::size_t>(k - 6 * q)] + q * chiral;
  }
};

Rim make_rim(const Steps& f, LatticePoint chiral) {
  Rim r;
  r.steps = f;
  r.chiral = chiral;
  r.at[0] = {0, 0};
  for (std::size_t i = 0; i < 6; ++i) r.at[i + 1] = r.at[i] + f[i];
  return r;
}

// The cap hexagon's corners: p_0 = 0, p_i+1 = p_i + f_i turned by i * 60 degrees.
std::array<LatticePoint, 6> hexagon(const Steps& f) {
  std::array<LatticePoint, 6> p{};
  for (int i = 0; i + 1 < 6; ++i)
    p[static_cast<std::size_t>(i + 1)] = p[static_cast<std::size_t>(i)] + turned(f[static_cast<std::size_t>(i)], i);
  return p;
}

bool segments_cross(LatticePoint a, LatticePoint b, LatticePoint c, LatticePoint d) {
  const auto side = [](LatticePoint o, LatticePoint x, LatticePoint y) {
    const long s = det(x - o, y - o);
    return (s > 0) - (s < 0);
  };
  const int s1 = side(a, b, c), s2 = side(a, b, d), s3 = side(c, d, a), s4 = side(c, d, b);
  if (s1 * s2 < 0 && s3 * s4 < 0) return true;
  const auto on = [](LatticePoint o, LatticePoint x, LatticePoint y) {  // y on the segment o-x (collinear)
    return std::min(o[0], x[0]) <= y[0] && y[0] <= std::max(o[0], x[0]) && std::min(o[1], x[1]) <= y[1] &&
           y[1] <= std::max(o[1], x[1]);
  };
  return (s1 == 0 && on(a, b, c)) || (s2 == 0 && on(a, b, d)) || (s3 == 0 && on(c, d, a)) || (s4 == 0 && on(c, d, b));
}

// The hexagon simple and counter-clockwise, each corner turning 60 degrees more than the rim there (not 300 less).
bool simple_hexagon(const Steps& f) {
  const auto p = hexagon(f);
  long area = 0;
  for (std::size_t i = 0; i < 6; ++i) area += det(p[i], p[(i + 1) % 6]);
  if (area <= 0) return false;
  for (std::size_t i = 0; i < 6; ++i)
    for (std::size_t j = i + 2; j < 6; ++j) {
      if (i == 0 && j == 5) continue;
      if (segments_cross(p[i], p[(i + 1) % 6], p[j], p[(j + 1) % 6])) return false;
    }
  const auto angle = [](LatticePoint a, LatticePoint b) {  // signed turn from a to b
    const auto x = cartesian(static_cast<double>(a[0]), static_cast<double>(a[1]));
    const auto y = cartesian(static_cast<double>(b[0]), static_cast<double>(b[1]));
    return std::atan2(x[0] * y[1] - x[1] * y[0], x[0] * y[0] + x[1] * y[1]);
  };
  for (int i = 0; i < 6; ++i) {
    const int k = (i + 5) % 6;
    const LatticePoint rim_in = f[static_cast<std::size_t>(k)], rim_out = f[static_cast<std::size_t>(i)];
    const LatticePoint side_in = turned(rim_in, k), side_out = turned(rim_out, i);
    if (std::abs(angle(side_in, side_out) - angle(rim_in, rim_out) - kPi / 3) > 1e-9) return false;
  }
  return true;
}

// The hexagon cut into 4 triangles: the fan from the corner whose smallest triangle is largest.
std::vector<std::array<int, 3>> fan(const std::array<LatticePoint, 6>& p) {
  long best = 0;
  int from = -1;
  for (int k = 0; k < 6; ++k) {
    long smallest = std::numeric_limits<long>::max();
    for (int i = 1; i < 5; ++i) {
      const LatticePoint a = p[static_cast<std::size_t>(k)], b = p[static_cast<std::size_t>((k + i) % 6)],
                         c = p[static_cast<std::size_t>((k + i + 1) % 6)];
      smallest = std::min(smallest, det(b - a, c - a));
    }
    if (smallest > best) best = smallest, from = k;
  }
  std::vector<std::array<int, 3>> out;
  if (from < 0) return out;
  for (int i = 1; i < 5; ++i) out.push_back({from, (from + i) % 6, (from + i + 1) % 6});
  return out;
}

// The belt between P (upper) and Q_j = T - P_-j (lower): triangles (P_i, Q_j, P_i+1) and (Q_j, Q_j+1, P_i) in the
// order of the points along C, from the rung P_0 - Q_j0 to the rung P_6 - Q_j0+6. Empty if a triangle is not
// counter-clockwise or the lower polyline is not wholly below the upper.
struct BeltTriangle {
  std::array<bool, 3> lower{};   // a corner on Q (else on P)
  std::array<long, 3> index{};   // its i or j
  std::array<LatticePoint, 3> at{};
};

std::vector<BeltTriangle> belt(const Rim& rim, LatticePoint t) {
  const LatticePoint c = rim.chiral;
  const auto q = [&](long j) { return t - rim.point(-j); };
  long top_low = std::numeric_limits<long>::max(), bottom_high = std::numeric_limits<long>::min();
  for (long k = 0; k < 6; ++k) {
    top_low = std::min(top_low, det(c, rim.point(k)));
    bottom_high = std::max(bottom_high, det(c, q(k)));
  }
  if (bottom_high >= top_low) return {};
  // Q_j0: the last lower point not ahead of P_0 along C.
  long j0 = 0;
  while (dot2(q(j0), c) > 0) --j0;
  while (dot2(q(j0 + 1), c) <= 0) ++j0;
  std::vector<BeltTriangle> out;
  long i = 0, j = j0;
  while (i < 6 || j < j0 + 6) {
    const bool top = j == j0 + 6 || (i < 6 && dot2(rim.point(i + 1), c) < dot2(q(j + 1), c));
    BeltTriangle b;
    if (top) {
      b = {{false, true, false}, {i, j, i + 1}, {rim.point(i), q(j), rim.point(i + 1)}};
      ++i;
    } else {
      b = {{true, true, false}, {j, j + 1, i}, {q(j), q(j + 1), rim.point(i)}};
      ++j;
    }
    if (det(b.at[1] - b.at[0], b.at[2] - b.at[0]) <= 0) return {};
    out.push_back(b);
  }
  return out;
}

long smallest_triangle(const std::vector<BeltTriangle>& triangles) {
  long s = std::numeric_limits<long>::max();
  for (const auto& b : triangles) s = std::min(s, det(b.at[1] - b.at[0], b.at[2] - b.at[0]));
  return s;
}

// The translation vector of the tube (n, m), pointing from the upper rim to the lower.
LatticePoint tube_period(int n, int m) {
  const long d = std::gcd(2L * m + n, 2L * n + m);
  return {(2L * m + n) / d, -(2L * n + m) / d};
}

long floor_div(long a, long b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0)) ? 1 : 0); }

// T, where the lower rim lies: a lattice vector whose height det(C, T) is the multiple of gcd(n, m) nearest `wanted`
// (heights in det(C, .)), or lower where the belt does not fit there, down to the highest for which it fits; of the
// vectors of that height (T + C gives the same tube), the one whose belt's smallest triangle is largest. None if the
// belt fits at no height within a period below.
std::optional<LatticePoint> rim_offset(const Rim& rim, double wanted) {
  const LatticePoint c = rim.chiral;
  const long g = std::gcd(std::labs(c[0]), std::labs(c[1]));
  const LatticePoint along{c[0] / g, c[1] / g};
  // A lattice vector `down` with det(along, down) = -1, so det(C, -h down) = h g: from the extended Euclid.
  LatticePoint down{};
  {
    long a = along[0], b = -along[1], s0 = 1, s1 = 0, t0 = 0, t1 = 1;  // s0 a0 + t0 b0 = a at the end, a = +-1
    while (b != 0) {
      const long qt = a / b;
      std::tie(a, b) = std::make_pair(b, a - qt * b);
      std::tie(s0, s1) = std::make_pair(s1, s0 - qt * s1);
      std::tie(t0, t1) = std::make_pair(t1, t0 - qt * t1);
    }
    down = {-a * t0, -a * s0};  // det(along, down) = -a (s0 along0 - t0 along1) = -a^2 = -1
  }
  long top_low = std::numeric_limits<long>::max();
  for (long k = 0; k < 6; ++k) top_low = std::min(top_low, det(c, rim.point(k)));
  // The lower rim (heights det(C, T) - those of the upper) is wholly below the upper for det(C, T) < 2 top_low.
  const long highest = floor_div(2 * top_low - 1, g);
  const long start = std::isfinite(wanted) ? std::min(highest, std::lround(wanted / static_cast<double>(g))) : highest;
  const long period_height = -det(c, tube_period(static_cast<int>(c[0]), static_cast<int>(c[1])));
  for (long h = start; h >= start - period_height / g - 1; --h) {
    std::optional<LatticePoint> best;
    long best_smallest = 0;
    const LatticePoint base = (-h) * down;
    const long k_mid = -static_cast<long>(std::floor(static_cast<double>(dot2(base, along)) /
                                                     static_cast<double>(dot2(along, along))));
    for (long k = k_mid - g; k <= k_mid + g; ++k) {
      const LatticePoint t = base + k * along;
      const auto triangles = belt(rim, t);
      if (triangles.empty()) continue;
      const long s = smallest_triangle(triangles);
      if (s > best_smallest) best_smallest = s, best = t;
    }
    if (best) return best;
  }
  return std::nullopt;
}

}  // namespace

std::optional<Steps> ring_cap_steps(int n, int m) {
  const LatticePoint c{n, m};
  // Steps near C / 6: f with |6 f - C| <= 3 * 6 (in unit edges), nearest first.
  std::vector<LatticePoint> near;
  const long ci = static_cast<long>(std::floor(n / 6.0)), cj = static_cast<long>(std::floor(m / 6.0));
  for (long i = ci - 4; i <= ci + 5; ++i)
    for (long j = cj - 4; j <= cj + 5; ++j) {
      const LatticePoint f{i, j};
      if (squared_length(6 * f - c) <= 36 * 9) near.push_back(f);
    }
  std::sort(near.begin(), near.end(), [&](LatticePoint a, LatticePoint b) {
    const long da = squared_length(6 * a - c), db = squared_length(6 * b - c);
    return da != db ? da < db : a < b;
  });
  std::optional<Steps> best;
  long best_spread = std::numeric_limits<long>::max();
  // f_0 .. f_3 from `near` (each loop nearest first, left once its sum so far cannot beat the best), f_4 and f_5 from
  // the two conditions: f_4 + f_5 = A and w^4 f_4 + w^5 f_5 = B (w: the 60 degree turn) give f_5 = B - w^4 A, as
  // w^5 - w^4 = 1.
  const auto cost = [&](LatticePoint x) { return squared_length(6 * x - c); };
  Steps f{};
  for (const auto& f0 : near) {
    const long s0 = cost(f0);
    if (s0 >= best_spread) break;
    f[0] = f0;
    for (const auto& f1 : near) {
      const long s1 = s0 + cost(f1);
      if (s1 >= best_spread) break;
      f[1] = f1;
      for (const auto& f2 : near) {
        const long s2 = s1 + cost(f2);
        if (s2 >= best_spread) break;
        f[2] = f2;
        for (const auto& f3 : near) {
          const long s3 = s2 + cost(f3);
          if (s3 >= best_spread) break;
          f[3] = f3;
          const LatticePoint sum = f[0] + f[1] + f[2] + f[3];
          const LatticePoint turned_sum = f[0] + turned(f[1], 1) + turned(f[2], 2) + turned(f[3], 3);
          const LatticePoint A = c - sum, B = LatticePoint{0, 0} - turned_sum;
          f[5] = B - turned(A, 4);
          f[4] = A - f[5];
          const long s = s3 + cost(f[4]) + cost(f[5]);
          if (s >= best_spread) continue;
          bool forward = true;
          for (const auto& x : f) forward = forward && dot2(x, c) > 0;
          if (!forward || !simple_hexagon(f) || fan(hexagon(f)).empty()) continue;
          if (!rim_offset(make_rim(f, c), kInfinity)) continue;
          best_spread = s;
          best = f;
        }
      }
    }
  }
  return best;
}

CappedTube make_ring_capped_tube(const CappedTubeShape& shape) {
  const auto steps = ring_cap_steps(shape.n, shape.m);
  if (!steps)
    throw InputError(fmt::format("capped tube ({}, {}): no cap with its six pentagons on a ring fits a tube this thin",
                                 shape.n, shape.m));
  const LatticePoint c{shape.n, shape.m};
  const Rim rim = make_rim(*steps, c);
  const double a = shape.edge, r = capped_tube_radius(shape.n, shape.m, a);
  const double length_c = std::sqrt(static_cast<double>(squared_length(c)));  // |C| in unit edges
  const double height_unit = 0.5 * std::sqrt(3.0) / length_c;                 // det(C, x) -> height in unit edges

  const std::array<LatticePoint, 6> hex = hexagon(*steps);
  const auto hex_faces = fan(hex);
  long hex_triangles = 0;
  for (const auto& h : hex_faces)
    hex_triangles += det(hex[static_cast<std::size_t>(h[1])] - hex[static_cast<std::size_t>(h[0])],
                         hex[static_cast<std::size_t>(h[2])] - hex[static_cast<std::size_t>(h[0])]);
  // The tube's triangles: the two hexagons' and the belt's. Lowering T by one height step (det(C, T) by g) adds a
  // strip of 2 g triangles to the belt. T is chosen for as many as cover the capsule asked (unit triangles of
  // sqrt(3) / 4 a^2): its straight part then has the length asked.
  const double unit_triangle = 0.25 * std::sqrt(3.0) * a * a;
  const double capsule_triangles = (4 * kPi * r * r + 2 * kPi * r * shape.length) / unit_triangle;
  const auto belt_count = [&](LatticePoint t) {
    long count = 0;
    for (const auto& b : belt(rim, t)) count += det(b.at[1] - b.at[0], b.at[2] - b.at[0]);
    return count;
  };
  const LatticePoint highest = *rim_offset(rim, kInfinity);  // (the rim's steps were chosen where some T fits)
  const double wanted = static_cast<double>(det(c, highest)) -
                        0.5 * (capsule_triangles - static_cast<double>(2 * hex_triangles + belt_count(highest)));
  const long max_faces = 20 * kMaxTriangulationNumber;
  if (capsule_triangles > static_cast<double>(max_faces))
    throw InputError(fmt::format("capped tube ({}, {}): a length of {} needs more than {} triangles", shape.n, shape.m,
                                 shape.length, max_faces));
  const auto offset = rim_offset(rim, wanted);
  if (!offset) throw std::logic_error(fmt::format("capped tube ({}, {}): no belt fits", shape.n, shape.m));
  const LatticePoint t = *offset;
  const auto belt_triangles = belt(rim, t);
  const long expected = 2 * hex_triangles + belt_count(t);

  // The net: P_i = i mod 6, Q_j = 6 + (j mod 6); the upper hexagon, the belt, the lower hexagon (the upper turned
  // by 180 degrees: P_i -> Q_-i, in the same chart).
  const auto id = [](bool lower, long i) { return static_cast<int>(((i % 6) + 6) % 6) + (lower ? 6 : 0); };
  std::vector<NetFace> faces;
  for (const auto& h : hex_faces)
    faces.push_back({{id(false, h[0]), id(false, h[1]), id(false, h[2])},
                     {hex[static_cast<std::size_t>(h[0])], hex[static_cast<std::size_t>(h[1])],
                      hex[static_cast<std::size_t>(h[2])]}});
  if (belt_triangles.empty()) throw std::logic_error("capped tube: the belt of a longer tube does not fit");
  for (const auto& b : belt_triangles)
    faces.push_back({{id(b.lower[0], b.index[0]), id(b.lower[1], b.index[1]), id(b.lower[2], b.index[2])}, b.at});
  for (const auto& h : hex_faces)
    faces.push_back({{id(true, -h[0]), id(true, -h[1]), id(true, -h[2])},
                     {hex[static_cast<std::size_t>(h[0])], hex[static_cast<std::size_t>(h[1])],
                      hex[static_cast<std::size_t>(h[2])]}});
  const lattice_net::Folded folded = lattice_net::fold_lattice(12, faces);

  // Where the points go: the capsule of the tube's radius (or the sphere, for a cage too short for it) with the
  // area of the tube's triangles. The belt is the strip rolled onto it, from the middle between the rims (at half T's
  // height) up and down along its meridian; a hexagon point a fraction rho of the way from the hexagon's centre to
  // its border lies rho times as far from the pole as that border point on the rim, toward it.
  const double area = static_cast<double>(expected) * unit_triangle;
  const double straight = std::max(0.0, (area - 4 * kPi * r * r) / (2 * kPi * r));
  const double radius = straight > 0 ? r : std::sqrt(area / (4 * kPi)), half = 0.5 * straight;
  const double meridian = kPi * radius + straight;
  const auto east = [&](double i, double j) {  // along C, unit edges
    return (i * c[0] + j * c[1] + 0.5 * (i * c[1] + j * c[0])) / length_c;
  };
  const auto height = [&](double i, double j) { return (j * c[0] - i * c[1]) * height_unit; };  // unit edges
  const auto upper_rim = [&](double x) {  // the upper rim's height at x along C (its points P_0 .. P_6 from 0 to |C|)
    x -= length_c * std::floor(x / length_c);
    for (std::size_t k = 0; k < 6; ++k) {
      const LatticePoint p0 = rim.at[k], p1 = rim.at[k + 1];
      const double x0 = east(static_cast<double>(p0[0]), static_cast<double>(p0[1]));
      const double x1 = east(static_cast<double>(p1[0]), static_cast<double>(p1[1]));
      if (x <= x1 || k == 5) {
        const double u = std::clamp((x - x0) / (x1 - x0), 0.0, 1.0);
        return (1 - u) * height(static_cast<double>(p0[0]), static_cast<double>(p0[1])) +
               u * height(static_cast<double>(p1[0]), static_cast<double>(p1[1]));
      }
    }
    return 0.0;
  };
  const double t_east = east(static_cast<double>(t[0]), static_cast<double>(t[1]));
  const double t_height = height(static_cast<double>(t[0]), static_cast<double>(t[1]));
  const auto rim_from_pole = [&](double x) {  // along the meridian, from the upper pole to the upper rim at x
    return std::max(0.0, 0.5 * meridian - (upper_rim(x) - 0.5 * t_height) * a);
  };
  const auto on_capsule = [&](double from_pole, double x) {  // the point this far down the meridian at x along C
    const double s = std::clamp(from_pole, 0.0, meridian), angle = 2 * kPi * x / length_c;
    double rho = radius, z = 0;
    if (s < 0.5 * kPi * radius) {
      rho = radius * std::sin(s / radius);
      z = half + radius * std::cos(s / radius);
    } else if (s <= 0.5 * kPi * radius + straight) {
      z = half - (s - 0.5 * kPi * radius);
    } else {
      const double from_bottom = meridian - s;
      rho = radius * std::sin(from_bottom / radius);
      z = -half - radius * std::cos(from_bottom / radius);
    }
    return Vec3(rho * std::cos(angle), rho * std::sin(angle), z);
  };
  std::array<std::array<double, 2>, 6> corner_xy{};
  std::array<double, 2> centre{0, 0};
  for (std::size_t k = 0; k < 6; ++k) {
    corner_xy[k] = cartesian(static_cast<double>(hex[k][0]), static_cast<double>(hex[k][1]));
    centre[0] += corner_xy[k][0] / 6;
    centre[1] += corner_xy[k][1] / 6;
  }
  const std::size_t hex_count = hex_faces.size(), belt_end = hex_count + belt_triangles.size();
  std::vector<Vec3> points(folded.places.size());
  for (std::size_t v = 0; v < points.size(); ++v) {
    const auto& place = folded.places[v];
    const NetFace& f = faces[static_cast<std::size_t>(place.face)];
    double pi = 0, pj = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      pi += place.weights[k] * static_cast<double>(f.at[k][0]);
      pj += place.weights[k] * static_cast<double>(f.at[k][1]);
    }
    const auto face = static_cast<std::size_t>(place.face);
    if (face >= hex_count && face < belt_end) {
      const double x = east(pi, pj);
      points[v] = on_capsule(0.5 * meridian - (height(pi, pj) - 0.5 * t_height) * a, x);
      continue;
    }
    const auto xy = cartesian(pi, pj);
    const double dx = xy[0] - centre[0], dy = xy[1] - centre[1];
    double rho = 0, x = 0;
    if (dx * dx + dy * dy > 1e-18) {
      // The ray from the centre through the point meets side k at u: centre + s d = p_k + u (p_k+1 - p_k).
      double best_s = kInfinity;
      for (std::size_t k = 0; k < 6; ++k) {
        const auto& p0 = corner_xy[k];
        const auto& p1 = corner_xy[(k + 1) % 6];
        const double ex = p1[0] - p0[0], ey = p1[1] - p0[1];
        const double den = dx * (-ey) - dy * (-ex);
        if (std::abs(den) < 1e-15) continue;
        const double bx = p0[0] - centre[0], by = p0[1] - centre[1];
        const double s = (bx * (-ey) - by * (-ex)) / den, u = (dx * by - dy * bx) / den;
        if (s <= 0 || u < -1e-12 || u > 1 + 1e-12 || s >= best_s) continue;
        best_s = s;
        const LatticePoint from = rim.at[k], step = (*steps)[k];
        x = east(static_cast<double>(from[0]) + u * static_cast<double>(step[0]),
                 static_cast<double>(from[1]) + u * static_cast<double>(step[1]));
      }
      rho = std::min(1.0, 1 / best_s);
    }
    if (face < hex_count) {
      points[v] = on_capsule(rho * rim_from_pole(x), x);
    } else {  // the lower cap: the upper turned by 180 degrees about T / 2
      points[v] = on_capsule(meridian - rho * rim_from_pole(x), t_east - x);
    }
  }

  CappedTube out;
  out.mesh = capsule_mesh(points, folded.triangles, expected, shape.n, shape.m, radius, half);
  out.periods = 0;
  out.ring_caps = true;
  out.radius = r;
  out.straight_length = straight;
  out.period = capped_tube_period(shape.n, shape.m, a);
  return out;
}

}  // namespace carbonmesh::ring_cap
