// Fan or ear-clipping triangulation of a polygon, in the plane of its Newell normal.
#include "triangulate_polygon.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace carbonmesh {

bool triangulate_polygon(const std::vector<Vec3>& points, const std::vector<int>& polygon,
                         std::vector<std::array<int, 3>>& out) {
  const std::size_t n = polygon.size();
  auto at = [&](std::size_t j) -> const Vec3& { return points[static_cast<std::size_t>(polygon[j])]; };
  auto fan = [&] {
    for (std::size_t k = 1; k + 1 < n; ++k) out.push_back({polygon[0], polygon[k], polygon[k + 1]});
  };
  // Newell's normal: the polygon's area vector, its turning sense included.
  Vec3 normal(0, 0, 0);
  for (std::size_t j = 0; j < n; ++j) normal += OpenMesh::cross(at(j), at((j + 1) % n));
  bool convex_fan = true;
  for (std::size_t k = 1; k + 1 < n && convex_fan; ++k)
    convex_fan = OpenMesh::dot(OpenMesh::cross(at(k) - at(0), at(k + 1) - at(0)), normal) > 0;
  if (convex_fan || !(normal.sqrnorm() > 0)) {  // (a degenerate polygon: its triangles are refused or removed later)
    fan();
    return false;
  }
  // Ear clipping in the plane across the normal's largest component, oriented so the polygon turns counter-clockwise.
  int axis = 0;
  for (int c = 1; c < 3; ++c)
    if (std::abs(normal[c]) > std::abs(normal[axis])) axis = c;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const double sense = normal[axis] > 0 ? 1.0 : -1.0;
  auto cross2 = [&](std::size_t a, std::size_t b, std::size_t c) {
    const Vec3 &pa = at(a), &pb = at(b), &pc = at(c);
    return sense * ((pb[u] - pa[u]) * (pc[v] - pa[v]) - (pb[v] - pa[v]) * (pc[u] - pa[u]));
  };
  std::vector<std::size_t> left(n);
  for (std::size_t j = 0; j < n; ++j) left[j] = j;
  std::size_t i = 0, tried = 0;
  while (left.size() > 3) {
    const std::size_t m = left.size();
    const std::size_t a = left[(i + m - 1) % m], b = left[i % m], c = left[(i + 1) % m];
    bool ear = cross2(a, b, c) > 0;
    for (std::size_t j = 0; j < m && ear; ++j) {
      const std::size_t p = left[j];
      if (p == a || p == b || p == c || at(p) == at(a) || at(p) == at(b) || at(p) == at(c)) continue;
      // Inside or on the candidate ear: it would overlap what is left.
      ear = !(cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0);
    }
    if (ear) {
      out.push_back({polygon[a], polygon[b], polygon[c]});
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(i % m));
      i = i % m == 0 ? 0 : i % m - 1;  // the ear's first corner may be an ear now
      tried = 0;
    } else if (++tried > m) {  // no ear: a polygon that crosses itself; the rest as a fan
      for (std::size_t k = 1; k + 1 < m; ++k) out.push_back({polygon[left[0]], polygon[left[k]], polygon[left[k + 1]]});
      return true;
    } else {
      i = (i + 1) % m;
    }
  }
  out.push_back({polygon[left[0]], polygon[left[1]], polygon[left[2]]});
  return true;
}

}  // namespace carbonmesh
