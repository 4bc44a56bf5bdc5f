// Self-intersection test of a triangle mesh with CGAL's box intersection and exact triangle predicates.
#include "carbonmesh/remesh/self_intersections.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

namespace carbonmesh {

SelfIntersections self_intersections(const TriMesh& mesh) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Surface = CGAL::Surface_mesh<Kernel::Point_3>;
  Surface surface;
  std::vector<Surface::Vertex_index> vertex(mesh.n_vertices());
  for (auto v : mesh.vertices()) {  // (not the deleted ones)
    const Vec3& p = mesh.point(v);
    vertex[static_cast<std::size_t>(v.idx())] = surface.add_vertex(Kernel::Point_3(p[0], p[1], p[2]));
  }
  std::vector<int> face_of;  // the mesh's index of each face of `surface`, in the order they were added
  face_of.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    std::array<Surface::Vertex_index, 3> corners;
    std::size_t i = 0;
    for (auto v : mesh.fv_range(f)) corners[i++] = vertex[static_cast<std::size_t>(v.idx())];
    // The mesh is manifold and oriented, so every face goes in; a face refused anyway is left out of the test.
    if (surface.add_face(corners[0], corners[1], corners[2]) != Surface::null_face()) face_of.push_back(f.idx());
  }
  std::vector<std::pair<Surface::Face_index, Surface::Face_index>> crossing;
  CGAL::Polygon_mesh_processing::self_intersections(surface, std::back_inserter(crossing));
  SelfIntersections result;
  result.pairs = crossing.size();
  std::vector<int> faces;
  faces.reserve(2 * crossing.size());
  for (const auto& [a, b] : crossing) {
    int i = face_of[static_cast<std::size_t>(a.idx())], j = face_of[static_cast<std::size_t>(b.idx())];
    if (i > j) std::swap(i, j);
    if (result.example[0] < 0 || std::make_pair(i, j) < std::make_pair(result.example[0], result.example[1]))
      result.example = {i, j};
    faces.push_back(i);
    faces.push_back(j);
  }
  std::sort(faces.begin(), faces.end());
  result.faces = static_cast<std::size_t>(std::unique(faces.begin(), faces.end()) - faces.begin());
  return result;
}

nlohmann::json to_json(const SelfIntersections& s) {
  nlohmann::json j;
  j["pairs"] = s.pairs;
  j["faces"] = s.faces;
  j["example"] = s.pairs > 0 ? nlohmann::json(s.example) : nlohmann::json(nullptr);
  j["searched"] = s.searched;
  return j;
}

std::string to_text(const SelfIntersections& s) {
  if (!s.searched) return "self-intersections none by construction (not searched)";
  if (s.pairs == 0) return "self-intersections none";
  return fmt::format("self-intersections {} face pair{} ({} faces; e.g. faces {} and {})", s.pairs,
                     s.pairs == 1 ? "" : "s", s.faces, s.example[0], s.example[1]);
}

}  // namespace carbonmesh
