// Consistent orientation of a triangle soup with CGAL's orient_polygon_soup (Gueziec et al.'s cutting and stitching),
// keeping each component's majority orientation.
#include "orient_soup.hpp"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>

#include <algorithm>
#include <numeric>

namespace carbonmesh {
namespace {

// Records which faces the orienter reversed (it copies its visitor: the record is held by pointer).
struct ReversalVisitor : CGAL::Polygon_mesh_processing::Default_orientation_visitor {
  std::vector<char>* reversed = nullptr;
  void polygon_orientation_reversed(std::size_t face) { (*reversed)[face] ^= 1; }
};

}  // namespace

OrientedSoup orient_soup(std::vector<Vec3>& points, std::vector<std::array<int, 3>>& triangles) {
  OrientedSoup out;
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(triangles.size());
  for (const auto& t : triangles)
    polygons.push_back(
        {static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2])});
  std::vector<char> reversed(triangles.size(), 0);
  ReversalVisitor visitor;
  visitor.reversed = &reversed;
  const std::size_t before = points.size();
  CGAL::Polygon_mesh_processing::orient_polygon_soup(points, polygons, CGAL::parameters::visitor(visitor));
  out.duplicated_vertices = points.size() - before;

  // Components: faces joined at their edges (the soup is now manifold and consistently oriented).
  std::vector<std::size_t> component(polygons.size());
  std::iota(component.begin(), component.end(), 0);
  auto root = [&component](std::size_t i) {
    while (component[i] != i) i = component[i] = component[component[i]];
    return i;
  };
  std::vector<std::array<std::size_t, 3>> edges;  // (lower end, higher end, face)
  edges.reserve(3 * polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t a = polygons[f][k], b = polygons[f][(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), f});
    }
  std::sort(edges.begin(), edges.end());
  for (std::size_t j = 1; j < edges.size(); ++j)
    if (edges[j][0] == edges[j - 1][0] && edges[j][1] == edges[j - 1][1]) {
      const std::size_t ra = root(edges[j][2]), rb = root(edges[j - 1][2]);
      if (ra != rb) component[std::max(ra, rb)] = std::min(ra, rb);
    }
  // Each component back to the orientation most of its faces had (a tie keeps the orientation of its first face).
  std::vector<std::size_t> faces(polygons.size(), 0), turned(polygons.size(), 0);
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    ++faces[root(f)];
    turned[root(f)] += reversed[f] != 0;
  }
  std::vector<char> back(polygons.size(), 0);
  for (std::size_t c = 0; c < polygons.size(); ++c)  // (a root is its component's lowest face)
    if (root(c) == c) back[c] = 2 * turned[c] > faces[c] || (2 * turned[c] == faces[c] && reversed[c] != 0);
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    if (back[root(f)]) {
      std::reverse(polygons[f].begin(), polygons[f].end());
      reversed[f] ^= 1;
    }
    out.reversed_faces += reversed[f] != 0;
    triangles[f] = {static_cast<int>(polygons[f][0]), static_cast<int>(polygons[f][1]),
                    static_cast<int>(polygons[f][2])};
  }
  return out;
}

}  // namespace carbonmesh
