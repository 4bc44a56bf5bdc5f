// T-junctions: border vertices inside other border edges, found with a grid of the border vertices, and the faces
// split at them so the two sides of the seam share their vertices.
#include "t_junctions.hpp"

#include <algorithm>
#include <cmath>

#include "carbonmesh/remesh/cell_grid.hpp"

namespace carbonmesh {

TJunctions find_t_junctions(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& triangles,
                            const std::vector<std::pair<int, int>>& border, double tolerance) {
  TJunctions out;
  if (border.empty() || !(tolerance > 0)) return out;
  auto ends = [&](const std::pair<int, int>& e) {
    const auto& t = triangles[static_cast<std::size_t>(e.first)];
    const auto k = static_cast<std::size_t>(e.second);
    return std::pair<int, int>(t[k], t[(k + 1) % 3]);
  };
  std::vector<int> ids;
  double length = 0;
  for (const auto& e : border) {
    const auto [a, b] = ends(e);
    ids.push_back(a), ids.push_back(b);
    length += (points[static_cast<std::size_t>(a)] - points[static_cast<std::size_t>(b)]).norm();
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  const CellGrid grid(points, ids, length / static_cast<double>(border.size()),
                      8.0 * static_cast<double>(ids.size()) + 1000);
  std::vector<char> inside_some(points.size(), 0);
  std::vector<std::pair<double, int>> found;  // (parameter along the edge, vertex)
  for (const auto& e : border) {
    const std::pair<int, int> ab = ends(e);  // (not a structured binding: the lambda below captures them)
    const int a = ab.first, b = ab.second;
    const Vec3& pa = points[static_cast<std::size_t>(a)];
    const Vec3& pb = points[static_cast<std::size_t>(b)];
    const Vec3 d = pb - pa;
    const double length2 = d.sqrnorm();
    found.clear();
    auto test = [&](int v, const Vec3& p) {
      if (v == a || v == b) return;
      const double t = OpenMesh::dot(p - pa, d) / length2;
      const double distance = (p - (pa + t * d)).norm();
      if (!(distance <= tolerance) || t * t * length2 <= tolerance * tolerance ||
          (1 - t) * (1 - t) * length2 <= tolerance * tolerance || t <= 0 || t >= 1)
        return;
      found.emplace_back(t, v);
      if (!inside_some[static_cast<std::size_t>(v)]) {
        inside_some[static_cast<std::size_t>(v)] = 1;
        ++out.vertices;
      }
      if (out.example[0] < 0 || v < out.example[0]) {
        out.example = {v, std::min(a, b), std::max(a, b)};
        out.example_distance = distance;
      }
    };
    Vec3 lo = pa, hi = pa;
    lo.minimize(pb), hi.maximize(pb);
    std::array<int, 3> from{}, to{};
    double cells = 1;
    for (int c = 0; c < 3; ++c) {
      from[c] = grid.coordinate(lo - Vec3(tolerance, tolerance, tolerance), c);
      to[c] = grid.coordinate(hi + Vec3(tolerance, tolerance, tolerance), c);
      cells *= to[c] - from[c] + 1;
    }
    if (cells > static_cast<double>(ids.size())) {  // an edge far longer than the others: every border vertex
      for (int v : ids) test(v, points[static_cast<std::size_t>(v)]);
    } else {
      for (int x = from[0]; x <= to[0]; ++x)
        for (int y = from[1]; y <= to[1]; ++y)
          for (int z = from[2]; z <= to[2]; ++z) {
            const std::size_t c = grid.cell_index(x, y, z);
            for (int j = grid.begin(c); j < grid.begin(c + 1); ++j) test(grid.id(j), grid.point(j));
          }
    }
    if (found.empty()) continue;
    std::sort(found.begin(), found.end());
    std::vector<int>& list = out.inside[e];
    for (const auto& [t, v] : found) list.push_back(v);
  }
  return out;
}

std::vector<std::array<int, 3>> split_at_t_junctions(std::vector<Vec3>& points,
                                                     const std::vector<std::array<int, 3>>& triangles,
                                                     const TJunctions& found) {
  std::vector<std::array<int, 3>> out;
  out.reserve(triangles.size() + 2 * found.inside.size());
  auto on = [&](int f, int k) -> const std::vector<int>* {
    const auto it = found.inside.find({f, k});
    return it == found.inside.end() ? nullptr : &it->second;
  };
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    const int face = static_cast<int>(f);
    int split_edges = 0, edge = -1;
    for (int k = 0; k < 3; ++k)
      if (on(face, k) != nullptr) ++split_edges, edge = k;
    if (split_edges == 0) {
      out.push_back(t);
      continue;
    }
    // The face's boundary, corner by corner with the vertices inside each edge in order: a polygon whose points all
    // lie on the triangle, so a fan from the opposite corner (one edge split) or from the centroid covers it.
    std::vector<int> ring;
    for (int k = 0; k < 3; ++k) {
      ring.push_back(t[static_cast<std::size_t>(k)]);
      if (const std::vector<int>* inside = on(face, k)) ring.insert(ring.end(), inside->begin(), inside->end());
    }
    int apex = -1;
    std::size_t start = 0;
    if (split_edges == 1) {
      apex = t[static_cast<std::size_t>((edge + 2) % 3)];
      start = static_cast<std::size_t>(std::find(ring.begin(), ring.end(), apex) - ring.begin());
    } else {
      apex = static_cast<int>(points.size());
      points.push_back((points[static_cast<std::size_t>(t[0])] + points[static_cast<std::size_t>(t[1])] +
                        points[static_cast<std::size_t>(t[2])]) / 3.0);
    }
    const std::size_t n = ring.size();
    for (std::size_t j = 0; j < n; ++j) {
      const int p = ring[(start + j) % n], q = ring[(start + j + 1) % n];
      if (p == apex || q == apex) continue;
      out.push_back({p, q, apex});
    }
  }
  return out;
}

}  // namespace carbonmesh
