// A flat surface cut from a triangular lattice (carbonmesh/remesh/lattice_sheet.hpp).
#include "carbonmesh/remesh/lattice_sheet.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "add_faces.hpp"
#include "carbonmesh/remesh/error.hpp"

namespace carbonmesh {
namespace {

struct Point2 {
  double x = 0, y = 0;
};

double cross(Point2 a, Point2 b, Point2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

using Triangle2 = std::array<Point2, 3>;

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

// The lattice: point (i, j) at origin + i e1 + j e2, e1 and e2 at 60 degrees. Up triangle (i, j): corners (i, j),
// (i + 1, j), (i, j + 1); down triangle (i, j): (i + 1, j), (i + 1, j + 1), (i, j + 1); both counter-clockwise.
struct Lattice {
  Point2 origin, e1, e2;
  Point2 at(double i, double j) const { return {origin.x + i * e1.x + j * e2.x, origin.y + i * e1.y + j * e2.y}; }
  // Lattice coordinates of p.
  std::pair<double, double> coordinates(Point2 p) const {
    const double det = e1.x * e2.y - e1.y * e2.x;
    const double dx = p.x - origin.x, dy = p.y - origin.y;
    return {(dx * e2.y - dy * e2.x) / det, (e1.x * dy - e1.y * dx) / det};
  }
};

using Corners = std::array<std::pair<long, long>, 3>;
Corners corners(long i, long j, int down) {
  if (down) return {{{i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
  return {{{i, j}, {i + 1, j}, {i, j + 1}}};
}

// The six triangles around lattice point (i, j) in counter-clockwise order: (i, j, down).
std::array<std::array<long, 3>, 6> around(long i, long j) {
  return {{{i, j, 0}, {i - 1, j, 1}, {i - 1, j, 0}, {i - 1, j - 1, 1}, {i, j - 1, 0}, {i, j - 1, 1}}};
}

// Border edges in one run turn by less than this (radians): a straight side tessellated into several edges.
constexpr double kStraight = 1e-4;  // (coordinates read as single precision bend a straight side by up to ~1e-5)

// The ends of the longest run of consecutive border edges in one direction (a straight side of the outline, however
// it is tessellated), in the plane; the first such run of the loops in order of their first border halfedge. Throws
// InputError if there is no border.
template <typename ToPlane>
std::pair<Point2, Point2> longest_straight_run(const TriMesh& flat, const ToPlane& to_plane) {
  std::vector<char> seen(flat.n_halfedges(), 0);
  double best = -1;
  std::pair<Point2, Point2> ends;
  for (auto start : flat.halfedges()) {
    if (!flat.is_boundary(start) || seen[static_cast<std::size_t>(start.idx())]) continue;
    std::vector<TriMesh::HalfedgeHandle> loop;
    for (auto h = start; !seen[static_cast<std::size_t>(h.idx())]; h = flat.next_halfedge_handle(h)) {
      seen[static_cast<std::size_t>(h.idx())] = 1;
      loop.push_back(h);
    }
    const std::size_t n = loop.size();
    std::vector<Point2> from(n), to(n);
    for (std::size_t k = 0; k < n; ++k) {
      from[k] = to_plane(flat.point(flat.from_vertex_handle(loop[k])));
      to[k] = to_plane(flat.point(flat.to_vertex_handle(loop[k])));
    }
    auto turns = [&](std::size_t k) {  // between edge k - 1 and edge k
      const std::size_t p = (k + n - 1) % n;
      const double ux = to[p].x - from[p].x, uy = to[p].y - from[p].y, vx = to[k].x - from[k].x,
                   vy = to[k].y - from[k].y;
      return std::abs(std::atan2(ux * vy - uy * vx, ux * vx + uy * vy)) >= kStraight;
    };
    std::size_t first = 0;  // a run starts where the border turns (a loop turns somewhere)
    while (first < n && !turns(first)) ++first;
    if (first == n) first = 0;
    for (std::size_t s = 0; s < n;) {
      const std::size_t k0 = (first + s) % n;
      double length = 0;
      std::size_t k = k0;
      do {
        length += std::hypot(to[k].x - from[k].x, to[k].y - from[k].y);
        k = (k + 1) % n, ++s;
      } while (s < n && !turns(k));
      if (length > best) best = length, ends = {from[k0], to[(k + n - 1) % n]};
    }
  }
  if (best < 0) throw InputError("the flat surface has no border (a flat surface is open)");
  return ends;
}

}  // namespace

Flatness flatness(const TriMesh& mesh) {
  Flatness out;
  std::size_t n = 0;
  Vec3 c(0, 0, 0);
  for (auto v : mesh.vertices()) c += mesh.point(v), ++n;
  if (n == 0) return out;
  c /= static_cast<double>(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (auto v : mesh.vertices()) {
    const Vec3 d = mesh.point(v) - c;
    const Eigen::Vector3d e(d[0], d[1], d[2]);
    cov += e * e.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);  // eigenvalues in increasing order
  const Eigen::Vector3d least = solver.eigenvectors().col(0), most = solver.eigenvectors().col(2);
  Vec3 normal(least[0], least[1], least[2]);
  Vec3 facing(0, 0, 0);  // the faces' area-weighted normal
  for (auto f : mesh.faces()) {
    const auto h = mesh.halfedge_handle(f);
    const Vec3 a = mesh.point(mesh.from_vertex_handle(h)), b = mesh.point(mesh.to_vertex_handle(h)),
               p = mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)));
    facing += OpenMesh::cross(b - a, p - a);
  }
  if (OpenMesh::dot(facing, normal) < 0) normal = -normal;
  out.centroid = c;
  out.normal = normal;
  out.u = Vec3(most[0], most[1], most[2]);
  out.v = OpenMesh::cross(normal, out.u);
  for (auto v : mesh.vertices())
    out.distance = std::max(out.distance, std::abs(OpenMesh::dot(mesh.point(v) - c, normal)));
  return out;
}

LatticeSheet lattice_sheet(const TriMesh& flat, const Flatness& plane, double edge, double turn_deg) {
  if (!(edge > 0) || !std::isfinite(edge)) throw InputError(fmt::format("lattice edge {} must be positive", edge));
  auto to_plane = [&](const Vec3& p) {
    const Vec3 d = p - plane.centroid;
    return Point2{OpenMesh::dot(d, plane.u), OpenMesh::dot(d, plane.v)};
  };
  // The lattice direction: the longest straight run of the border (ties: the first), one lattice line along it.
  const auto [a, b] = longest_straight_run(flat, to_plane);
  LatticeSheet out;
  if (!std::isfinite(turn_deg)) throw InputError(fmt::format("lattice turn {} must be a finite angle", turn_deg));
  const double pi = std::acos(-1.0);
  const double angle = std::atan2(b.y - a.y, b.x - a.x) + turn_deg * pi / 180;
  out.angle_deg = angle * 180 / pi;
  const double third = pi / 3;
  const Lattice lattice{a, {edge * std::cos(angle), edge * std::sin(angle)},
                        {edge * std::cos(angle + third), edge * std::sin(angle + third)}};

  std::vector<Triangle2> triangles;
  for (auto f : flat.faces()) {
    Triangle2 t;
    int k = 0;
    for (auto v : flat.fv_range(f)) t[static_cast<std::size_t>(k++)] = to_plane(flat.point(v));
    triangles.push_back(t);
  }

  // Triangles whose centroid (the atom of the dual) lies inside: those around each input triangle's bounding box in
  // lattice coordinates.
  std::unordered_set<std::uint64_t> kept[2];
  for (const Triangle2& t : triangles) {
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
          if (in_triangle(t, lattice.at(ci, cj))) kept[down].insert(pack(i, j));
        }
  }
  auto is_kept = [&](long i, long j, long down) {
    return kept[static_cast<std::size_t>(down)].count(pack(i, j)) > 0;
  };
  std::vector<std::pair<long, long>> points;  // (j, i) of every corner of a kept triangle, sorted (the fan test's)
  {
    std::unordered_set<std::uint64_t> seen;
    for (int down = 0; down < 2; ++down)
      for (const std::uint64_t key : kept[down]) {
        const long i = static_cast<std::int32_t>(key >> 32), j = static_cast<std::int32_t>(key & 0xffffffffu);
        for (const auto& [ci, cj] : corners(i, j, down))
          if (seen.insert(pack(ci, cj)).second) points.emplace_back(cj, ci);
      }
  }
  std::sort(points.begin(), points.end());

  // A point where the kept triangles around it form more than one fan keeps the largest fan (ties: the first
  // counter-clockwise from up triangle (i, j)); repeated until no point has two.
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& [j, i] : points) {
      const auto ring = around(i, j);
      std::array<bool, 6> on{};
      int count = 0;
      for (std::size_t k = 0; k < 6; ++k) count += (on[k] = is_kept(ring[k][0], ring[k][1], ring[k][2])) ? 1 : 0;
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
            kept[static_cast<std::size_t>(ring[k][2])].erase(pack(ring[k][0], ring[k][1]));
            ++out.dropped;
          }
      changed = true;
    }
  }

  // The mesh: the kept triangles in (j, i, down) order, their corners in (j, i) order.
  std::vector<std::array<long, 3>> triangles_kept;  // (j, i, down)
  for (int down = 0; down < 2; ++down)
    for (const std::uint64_t key : kept[down])
      triangles_kept.push_back(
          {static_cast<std::int32_t>(key & 0xffffffffu), static_cast<std::int32_t>(key >> 32), down});
  std::sort(triangles_kept.begin(), triangles_kept.end());
  std::vector<std::pair<long, long>> used;  // (j, i)
  for (const auto& [j, i, down] : triangles_kept)
    for (const auto& [ci, cj] : corners(i, j, static_cast<int>(down))) used.emplace_back(cj, ci);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::unordered_map<std::uint64_t, int> vertex;
  for (const auto& [j, i] : used) {
    vertex[pack(i, j)] = static_cast<int>(out.mesh.n_vertices());
    const Point2 p = lattice.at(static_cast<double>(i), static_cast<double>(j));
    out.mesh.add_vertex(plane.centroid + p.x * plane.u + p.y * plane.v);
  }
  std::vector<std::array<int, 3>> faces;
  for (const auto& [j, i, down] : triangles_kept) {
    std::array<int, 3> f{};
    const Corners c = corners(i, j, static_cast<int>(down));
    for (std::size_t k = 0; k < 3; ++k) f[k] = vertex.at(pack(c[k].first, c[k].second));
    faces.push_back(f);
  }
  if (!add_faces(out.mesh, faces))  // (every vertex has one fan and every edge at most two triangles)
    throw std::logic_error("lattice_sheet: the lattice triangles did not form a manifold mesh");
  return out;
}

}  // namespace carbonmesh
