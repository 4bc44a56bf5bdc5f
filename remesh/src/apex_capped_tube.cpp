// Capped nanotubes of any chirality with apex caps (apex_capped_tube.hpp).
//
// Unrolled, the tube is the strip of the lattice between two polylines, each repeating with the chiral vector C. The
// upper one P_0, P_1 = P_0 + f_0, .., P_5 = P_0 + C runs through five of the upper cap's pentagons: at each the
// lattice below it keeps its angle, the cap above it has 60 degrees less (300 degrees around a pentagon). Going round
// the cap, each side therefore turns 60 degrees more than the rim does: side i is f_i turned by i * 60 degrees. The
// five sides are the far sides of five lattice triangles around the sixth pentagon, the apex, whose 300 degrees close
// them for any steps (the icosahedral caps are the case f_i = C / 5). The lower polyline Q_j = T - P_-j is the upper
// one turned by 180 degrees about T / 2, with the lower cap the upper one's image. The net folded (lattice_net) is
// each cap's 5 triangles and the 10 triangles of the belt between the polylines: a polyhedron with 12 corners of 300
// degrees (the icosahedron's combinatorics), whose folded lattice has 12 vertices of valence 5 (the dual's pentagons)
// and valence 6 otherwise.
#include "apex_capped_tube.hpp"

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

namespace carbonmesh::apex_cap {

namespace {

using lattice_net::det;
using lattice_net::LatticePoint;
using lattice_net::NetFace;
using lattice_net::squared_length;
using lattice_net::turned;
using lattice_net::operator+;
using lattice_net::operator*;
using lattice_net::operator-;
using Steps = std::array<LatticePoint, 5>;  // f_0 .. f_4

constexpr double kPi = 3.14159265358979323846;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr long kRim = 5;  // the pentagons on a cap's rim

// Twice the dot product of two lattice vectors (unit edges): exact in integers.
long dot2(LatticePoint a, LatticePoint b) { return 2 * a[0] * b[0] + 2 * a[1] * b[1] + a[0] * b[1] + a[1] * b[0]; }

// A lattice point in the plane, in unit edges (e1 along x).
std::array<double, 2> cartesian(double i, double j) { return {i + 0.5 * j, 0.5 * std::sqrt(3.0) * j}; }

double signed_turn(LatticePoint a, LatticePoint b) {  // the angle from a to b, in (-pi, pi]
  const auto x = cartesian(static_cast<double>(a[0]), static_cast<double>(a[1]));
  const auto y = cartesian(static_cast<double>(b[0]), static_cast<double>(b[1]));
  return std::atan2(x[0] * y[1] - x[1] * y[0], x[0] * y[0] + x[1] * y[1]);
}

// The polyline through five of the upper cap's pentagons, P_i for any i (P_i+5 = P_i + C).
struct Rim {
  LatticePoint chiral{};
  std::array<LatticePoint, 6> at{};  // P_0 = 0 .. P_5 = C
  LatticePoint point(long i) const {
    const long q = static_cast<long>(std::floor(static_cast<double>(i) / static_cast<double>(kRim)));
    return at[static_cast<std::size_t>(i - kRim * q)] + q * chiral;
  }
};

Rim make_rim(const Steps& f, LatticePoint chiral) {
  Rim r;
  r.chiral = chiral;
  r.at[0] = {0, 0};
  for (std::size_t i = 0; i < 5; ++i) r.at[i + 1] = r.at[i] + f[i];
  return r;
}

// Twice a lattice triangle's area in unit triangles: the unit triangles it holds.
long unit_triangles(const std::array<LatticePoint, 3>& at) { return det(at[1] - at[0], at[2] - at[0]); }

// The cap above the rim, in one lattice chart with the apex at 0: its 5 triangles (P_i, P_i+1, apex) over the ring's
// corners 0 .. 4 and the apex 5; triangle i's far side lies over the rim's step i.
struct Cap {
  std::vector<std::array<int, 3>> faces;
  std::vector<std::array<LatticePoint, 3>> at;
  long triangles = 0;
};

// The cap of the steps f: side i is f_i turned by i * 60 degrees, the far side of the triangle (P_i, P_i+1, apex). The
// apex's side to P_0, a_0, comes back after the 5 sides turned by -60 degrees, so a_0 is their sum turned by 120
// degrees. The triangles must be counter-clockwise with 300 degrees at the apex, and each ring corner must have 300
// degrees with the strip's angle below it. None if the steps give no such cap.
std::optional<Cap> make_cap(const Steps& f) {
  Cap cap;
  std::array<LatticePoint, 6> p{};
  LatticePoint sum{0, 0};
  for (std::size_t i = 0; i < 5; ++i) sum = sum + turned(f[i], static_cast<int>(i));
  p[0] = turned(sum, 2);
  for (std::size_t i = 0; i < 5; ++i) p[i + 1] = p[i] + turned(f[i], static_cast<int>(i));
  if (p[5] != turned(p[0], -1)) throw std::logic_error("apex cap: the sides do not close");
  double around = 0;
  for (std::size_t i = 0; i < 5; ++i) {
    if (det(p[i], p[i + 1]) <= 0) return std::nullopt;
    around += signed_turn(p[i], p[i + 1]);
    cap.faces.push_back({static_cast<int>(i), static_cast<int>((i + 1) % 5), 5});
    cap.at.push_back({p[i], p[i + 1], LatticePoint{0, 0}});
    cap.triangles += det(p[i], p[i + 1]);
  }
  if (std::abs(around - 5 * kPi / 3) > 1e-9) return std::nullopt;
  std::array<double, 5> angle{};
  for (std::size_t t = 0; t < 5; ++t)
    for (std::size_t c = 0; c < 2; ++c) {
      const LatticePoint o = cap.at[t][c], a = cap.at[t][(c + 1) % 3], b = cap.at[t][(c + 2) % 3];
      angle[static_cast<std::size_t>(cap.faces[t][c])] += signed_turn(a - o, b - o);
    }
  for (std::size_t i = 0; i < 5; ++i) {
    const double strip = kPi + signed_turn(f[(i + 4) % 5], f[i]);  // below the rim, between its two steps
    if (std::abs(angle[i] + strip - 5 * kPi / 3) > 1e-9) return std::nullopt;
  }
  return cap;
}

// The belt between P (upper) and Q_j = T - P_-j (lower): triangles (P_i, Q_j, P_i+1) and (Q_j, Q_j+1, P_i) in the
// order of the points along C, from the rung P_0 - Q_j0 to the rung P_k - Q_j0+k. Empty if a triangle is not
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
  for (long i = 0; i < kRim; ++i) {
    top_low = std::min(top_low, det(c, rim.point(i)));
    bottom_high = std::max(bottom_high, det(c, q(i)));
  }
  if (bottom_high >= top_low) return {};
  // Q_j0: the last lower point not ahead of P_0 along C.
  long j0 = 0;
  while (dot2(q(j0), c) > 0) --j0;
  while (dot2(q(j0 + 1), c) <= 0) ++j0;
  std::vector<BeltTriangle> out;
  long i = 0, j = j0;
  const long k = kRim;
  while (i < k || j < j0 + k) {
    const bool top = j == j0 + k || (i < k && dot2(rim.point(i + 1), c) < dot2(q(j + 1), c));
    BeltTriangle b;
    if (top) {
      b = {{false, true, false}, {i, j, i + 1}, {rim.point(i), q(j), rim.point(i + 1)}};
      ++i;
    } else {
      b = {{true, true, false}, {j, j + 1, i}, {q(j), q(j + 1), rim.point(i)}};
      ++j;
    }
    if (unit_triangles(b.at) <= 0) return {};
    out.push_back(b);
  }
  return out;
}

long smallest_triangle(const std::vector<BeltTriangle>& triangles) {
  long s = std::numeric_limits<long>::max();
  for (const auto& b : triangles) s = std::min(s, unit_triangles(b.at));
  return s;
}

long triangle_count(const std::vector<BeltTriangle>& triangles) {
  long count = 0;
  for (const auto& b : triangles) count += unit_triangles(b.at);
  return count;
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
  for (long i = 0; i < kRim; ++i) top_low = std::min(top_low, det(c, rim.point(i)));
  // The lower rim (heights det(C, T) - those of the upper) is wholly below the upper for det(C, T) < 2 top_low.
  const long highest = floor_div(2 * top_low - 1, g);
  const long start = std::isfinite(wanted) ? std::min(highest, std::lround(wanted / static_cast<double>(g))) : highest;
  const long period_height = -det(c, translation_vector(c[0], c[1]));
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

std::optional<std::array<LatticePoint, 5>> apex_cap_steps(int n, int m) {
  const LatticePoint c{n, m};
  // Steps near C / 5: f with |5 f - C| <= 15 (in unit edges), nearest first.
  std::vector<LatticePoint> near;
  const long ci = static_cast<long>(std::floor(n / 5.0)), cj = static_cast<long>(std::floor(m / 5.0));
  const auto cost = [&](LatticePoint x) { return squared_length(5 * x - c); };
  for (long i = ci - 4; i <= ci + 5; ++i)
    for (long j = cj - 4; j <= cj + 5; ++j)
      if (cost({i, j}) <= 225) near.push_back({i, j});
  std::sort(near.begin(), near.end(), [&](LatticePoint a, LatticePoint b) {
    const long da = cost(a), db = cost(b);
    return da != db ? da < db : a < b;
  });
  // f_0 .. f_3 from `near` (each loop nearest first, left once its sum so far cannot beat the best), f_4 = C - the
  // others.
  std::optional<Steps> best;
  long best_spread = std::numeric_limits<long>::max();
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
          f[4] = c - (f[0] + f[1] + f[2] + f[3]);
          const long s = s3 + cost(f[4]);
          if (s >= best_spread) continue;
          bool forward = true;
          for (const auto& x : f) forward = forward && dot2(x, c) > 0;
          if (!forward || !make_cap(f) || !rim_offset(make_rim(f, c), kInfinity)) continue;
          best_spread = s;
          best = f;
        }
      }
    }
  }
  return best;
}

CappedTube make_apex_capped_tube(const CappedTubeShape& shape) {
  const auto steps = apex_cap_steps(shape.n, shape.m);
  if (!steps)
    throw InputError(fmt::format("capped tube ({}, {}): no cap of six pentagons fits a tube this thin (n^2 + nm + m^2 "
                                 "< 25)",
                                 shape.n, shape.m));
  const LatticePoint c{shape.n, shape.m};
  const Rim rim = make_rim(*steps, c);
  const Cap cap = *make_cap(*steps);
  const double a = shape.edge, r = capped_tube_radius(shape.n, shape.m, a);
  const double length_c = std::sqrt(static_cast<double>(squared_length(c)));  // |C| in unit edges
  const double height_unit = 0.5 * std::sqrt(3.0) / length_c;                 // det(C, x) -> height in unit edges

  // The tube's triangles: the two caps' and the belt's. Lowering T by one height step (det(C, T) by g) adds a strip
  // of 2 g triangles to the belt. T is chosen for as many as cover the capsule asked (unit triangles of sqrt(3) / 4
  // a^2): its straight part then has the length asked.
  const double unit_triangle = 0.25 * std::sqrt(3.0) * a * a;
  const double capsule_triangles = (4 * kPi * r * r + 2 * kPi * r * shape.length) / unit_triangle;
  const LatticePoint highest = *rim_offset(rim, kInfinity);  // (the steps were chosen where some T fits)
  const double wanted = static_cast<double>(det(c, highest)) -
                        0.5 * (capsule_triangles - static_cast<double>(2 * cap.triangles + triangle_count(belt(rim, highest))));
  const long max_faces = 20 * kMaxTriangulationNumber;
  if (capsule_triangles > static_cast<double>(max_faces))
    throw InputError(fmt::format("capped tube ({}, {}): a length of {} needs more than {} triangles", shape.n, shape.m,
                                 shape.length, max_faces));
  const auto offset = rim_offset(rim, wanted);
  if (!offset) throw std::logic_error(fmt::format("capped tube ({}, {}): no belt fits", shape.n, shape.m));
  const LatticePoint t = *offset;
  const auto belt_triangles = belt(rim, t);
  const long expected = 2 * cap.triangles + triangle_count(belt_triangles);

  // The net: P_i = i mod 5, Q_j = 5 + (j mod 5), the apexes 10 and 11; the upper cap, the belt, the lower cap (the
  // upper turned by 180 degrees: P_i -> Q_-i, in the same chart).
  const auto id = [](bool lower, long i) { return static_cast<int>(((i % kRim) + kRim) % kRim + (lower ? kRim : 0)); };
  const auto cap_corner = [&](bool lower, int corner) {
    return corner == kRim ? static_cast<int>(2 * kRim + (lower ? 1 : 0)) : id(lower, lower ? -corner : corner);
  };
  std::vector<NetFace> faces;
  for (std::size_t f = 0; f < cap.faces.size(); ++f)
    faces.push_back({{cap_corner(false, cap.faces[f][0]), cap_corner(false, cap.faces[f][1]),
                      cap_corner(false, cap.faces[f][2])},
                     cap.at[f]});
  if (belt_triangles.empty()) throw std::logic_error("capped tube: the belt of a longer tube does not fit");
  for (const auto& b : belt_triangles)
    faces.push_back({{id(b.lower[0], b.index[0]), id(b.lower[1], b.index[1]), id(b.lower[2], b.index[2])}, b.at});
  for (std::size_t f = 0; f < cap.faces.size(); ++f)
    faces.push_back({{cap_corner(true, cap.faces[f][0]), cap_corner(true, cap.faces[f][1]),
                      cap_corner(true, cap.faces[f][2])},
                     cap.at[f]});
  const lattice_net::Folded folded = lattice_net::fold_lattice(12, faces);

  // Where the points go: the capsule of the tube's radius (or the sphere, for a cage too short for it) with the
  // area of the tube's triangles. The belt is the strip rolled onto it, from the middle between the rims (at half T's
  // height) up and down along its meridian; a cap point a fraction rho of the way from the apex to the cap's border
  // (1 - its weight on the apex) lies rho times as far from the pole as that border point on the rim, toward it.
  const double area = static_cast<double>(expected) * unit_triangle;
  const double straight = std::max(0.0, (area - 4 * kPi * r * r) / (2 * kPi * r));
  const double radius = straight > 0 ? r : std::sqrt(area / (4 * kPi)), half = 0.5 * straight;
  const double meridian = kPi * radius + straight;
  const auto east = [&](double i, double j) {  // along C, unit edges
    return (i * c[0] + j * c[1] + 0.5 * (i * c[1] + j * c[0])) / length_c;
  };
  const auto height = [&](double i, double j) { return (j * c[0] - i * c[1]) * height_unit; };  // unit edges
  const auto upper_rim = [&](double x) {  // the upper rim's height at x along C (its points P_0 .. P_k from 0 to |C|)
    x -= length_c * std::floor(x / length_c);
    for (std::size_t k = 0; k < static_cast<std::size_t>(kRim); ++k) {
      const LatticePoint p0 = rim.at[k], p1 = rim.at[k + 1];
      const double x0 = east(static_cast<double>(p0[0]), static_cast<double>(p0[1]));
      const double x1 = east(static_cast<double>(p1[0]), static_cast<double>(p1[1]));
      if (x <= x1 || k + 1 == static_cast<std::size_t>(kRim)) {
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
  const std::size_t cap_count = cap.faces.size(), belt_end = cap_count + belt_triangles.size();
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
    if (face >= cap_count && face < belt_end) {
      const double x = east(pi, pj);
      points[v] = on_capsule(0.5 * meridian - (height(pi, pj) - 0.5 * t_height) * a, x);
      continue;
    }
    // Cap triangle i is (P_i, P_i+1, apex): the ray from the apex through the point meets side i where the weights
    // of P_i and P_i+1 alone put it.
    const std::size_t i = face < cap_count ? face : face - belt_end;
    const double rho = 1 - place.weights[2], u = rho > 0 ? place.weights[1] / rho : 0;
    const LatticePoint from = rim.at[i], step = (*steps)[i];
    const double x = east(static_cast<double>(from[0]) + u * static_cast<double>(step[0]),
                          static_cast<double>(from[1]) + u * static_cast<double>(step[1]));
    if (face < cap_count) {
      points[v] = on_capsule(rho * rim_from_pole(x), x);
    } else {  // the lower cap: the upper turned by 180 degrees about T / 2
      points[v] = on_capsule(meridian - rho * rim_from_pole(x), t_east - x);
    }
  }

  CappedTube out;
  out.mesh = capsule_mesh(points, folded.triangles, expected, shape.n, shape.m, radius, half);
  out.periods = 0;
  out.caps = CapKind::apex;
  out.radius = r;
  out.straight_length = straight;
  out.period = capped_tube_period(shape.n, shape.m, a);
  return out;
}

}  // namespace carbonmesh::apex_cap
