// The part of a triangular lattice inside a region of a plane (lattice_cut.hpp).
#include "lattice_cut.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "add_faces.hpp"

namespace carbonmesh::lattice {
namespace {

double cross(Point2 a, Point2 b, Point2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

constexpr double kOnBorder = 1e-9;  // barycentric coordinates down to -this count as inside (points on the border)

// Whether p lies in t (or on its border).
bool in_triangle(const Triangle2& t, Point2 p) {
  const double area = cross(t[0], t[1], t[2]);
  if (area == 0) return false;
  return cross(t[1], t[2], p) / area >= -kOnBorder && cross(t[2], t[0], p) / area >= -kOnBorder &&
         cross(t[0], t[1], p) / area >= -kOnBorder;
}

// Two integers in one key (each within +-2^31).
std::uint64_t pack(long i, long j) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) | static_cast<std::uint32_t>(j);
}
long first_of(std::uint64_t key) { return static_cast<std::int32_t>(key >> 32); }
long second_of(std::uint64_t key) { return static_cast<std::int32_t>(key & 0xffffffffu); }

// The six triangles around lattice point (i, j) in counter-clockwise order.
std::array<LatticeTriangle, 6> around(long i, long j) {
  return {{{i, j, 0}, {i - 1, j, 1}, {i - 1, j, 0}, {i - 1, j - 1, 1}, {i, j - 1, 0}, {i, j - 1, 1}}};
}

// floor(a / b) for b > 0.
long floor_div(long a, long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

}  // namespace

std::pair<double, double> Lattice::coordinates(Point2 p) const {
  const double det = e1.x * e2.y - e1.y * e2.x;
  const double dx = p.x - origin.x, dy = p.y - origin.y;
  return {(dx * e2.y - dy * e2.x) / det, (e1.x * dy - e1.y * dx) / det};
}

std::pair<long, long> reduce(long i, long j, Period period) {
  const long n = period.n, m = period.m;
  if (n == 0 && m == 0) return {i, j};
  // 2 (i e1 + j e2) . (n e1 + m e2) / |e1|^2 (e1 . e2 = |e1|^2 / 2), and the same for the chiral vector itself.
  const long along = 2 * i * n + 2 * j * m + i * m + j * n, period_along = 2 * (n * n + n * m + m * m);
  const long k = floor_div(along, period_along);
  return {i - k * n, j - k * m};
}

std::array<std::pair<long, long>, 3> corners(const LatticeTriangle& t) {
  const long i = t.i, j = t.j;
  if (t.down) return {{{i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
  return {{{i, j}, {i + 1, j}, {i, j + 1}}};
}

InsideTriangles triangles_inside(const std::vector<Triangle2>& region, const Lattice& lattice, Period period) {
  InsideTriangles out;
  std::unordered_set<std::uint64_t> kept[2];  // up and down triangles by their reduced (i, j)
  auto key = [&](long i, long j) {
    const auto [ri, rj] = reduce(i, j, period);
    return pack(ri, rj);
  };
  // The triangles around each region triangle's bounding box in lattice coordinates.
  for (const Triangle2& t : region) {
    double i0 = std::numeric_limits<double>::infinity(), i1 = -i0, j0 = i0, j1 = -i0;
    for (const Point2& p : t) {
      const auto [i, j] = lattice.coordinates(p);
      i0 = std::min(i0, i), i1 = std::max(i1, i), j0 = std::min(j0, j), j1 = std::max(j1, j);
    }
    for (long i = static_cast<long>(std::floor(i0)) - 1; i <= static_cast<long>(std::ceil(i1)); ++i)
      for (long j = static_cast<long>(std::floor(j0)) - 1; j <= static_cast<long>(std::ceil(j1)); ++j)
        for (int down = 0; down < 2; ++down) {
          const double offset = down ? 2.0 / 3 : 1.0 / 3;  // the centroid's lattice coordinates: (i, j) + offset
          const double ci = static_cast<double>(i) + offset, cj = static_cast<double>(j) + offset;
          if (in_triangle(t, lattice.at(ci, cj))) kept[down].insert(key(i, j));
        }
  }
  auto is_kept = [&](const LatticeTriangle& t) { return kept[t.down].count(key(t.i, t.j)) > 0; };
  std::vector<std::pair<long, long>> points;  // (j, i) of every corner of a kept triangle, reduced, sorted
  {
    std::unordered_set<std::uint64_t> seen;
    for (int down = 0; down < 2; ++down)
      for (const std::uint64_t k : kept[down])
        for (const auto& [ci, cj] : corners({first_of(k), second_of(k), down})) {
          const auto [ri, rj] = reduce(ci, cj, period);
          if (seen.insert(pack(ri, rj)).second) points.emplace_back(rj, ri);
        }
  }
  std::sort(points.begin(), points.end());

  // A point where the kept triangles around it form more than one fan keeps the largest fan; repeated until no
  // point has two.
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& [j, i] : points) {
      const auto ring = around(i, j);
      std::array<bool, 6> on{};
      int count = 0;
      for (std::size_t k = 0; k < 6; ++k) count += (on[k] = is_kept(ring[k])) ? 1 : 0;
      if (count == 0 || count == 6) continue;
      std::size_t start = 0;  // a fan starts after a gap
      while (!(on[start] && !on[(start + 5) % 6])) ++start;
      std::vector<std::vector<std::size_t>> fans;
      for (std::size_t s = 0; s < 6; ++s) {
        const std::size_t k = (start + s) % 6;
        if (!on[k]) continue;
        if (s == 0 || !on[(k + 5) % 6]) fans.emplace_back();
        fans.back().push_back(k);
      }
      if (fans.size() < 2) continue;
      std::size_t best = 0;
      for (std::size_t f = 1; f < fans.size(); ++f)
        if (fans[f].size() > fans[best].size()) best = f;
      for (std::size_t f = 0; f < fans.size(); ++f)
        if (f != best)
          for (std::size_t k : fans[f]) {
            kept[ring[k].down].erase(key(ring[k].i, ring[k].j));
            ++out.dropped;
          }
      changed = true;
    }
  }

  for (int down = 0; down < 2; ++down)
    for (const std::uint64_t k : kept[down]) out.triangles.push_back({first_of(k), second_of(k), down});
  std::sort(out.triangles.begin(), out.triangles.end(), [](const LatticeTriangle& a, const LatticeTriangle& b) {
    return std::tie(a.j, a.i, a.down) < std::tie(b.j, b.i, b.down);
  });
  return out;
}

TriMesh lattice_mesh(const InsideTriangles& inside, Period period, const std::function<Vec3(long, long)>& place,
                     bool reverse) {
  std::vector<std::pair<long, long>> used;  // (j, i), reduced
  for (const LatticeTriangle& t : inside.triangles)
    for (const auto& [ci, cj] : corners(t)) {
      const auto [ri, rj] = reduce(ci, cj, period);
      used.emplace_back(rj, ri);
    }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  TriMesh mesh;
  std::unordered_map<std::uint64_t, int> vertex;
  for (const auto& [j, i] : used) {
    vertex[pack(i, j)] = static_cast<int>(mesh.n_vertices());
    mesh.add_vertex(place(i, j));
  }
  std::vector<std::array<int, 3>> faces;
  for (const LatticeTriangle& t : inside.triangles) {
    std::array<int, 3> f{};
    const auto c = corners(t);
    for (std::size_t k = 0; k < 3; ++k) {
      const auto [ri, rj] = reduce(c[k].first, c[k].second, period);
      f[k] = vertex.at(pack(ri, rj));
    }
    if (reverse) std::swap(f[1], f[2]);
    faces.push_back(f);
  }
  if (!add_faces(mesh, faces))  // (every vertex has one fan and every edge at most two triangles)
    throw std::logic_error("lattice_mesh: the lattice triangles did not form a manifold mesh");
  return mesh;
}

}  // namespace carbonmesh::lattice
