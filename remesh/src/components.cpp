// Removal of connected components below an area (components.hpp).
#include "carbonmesh/remesh/components.hpp"

#include <algorithm>
#include <vector>

#include <nlohmann/json.hpp>

#include "remesh_geometry.hpp"

namespace carbonmesh {

SmallComponents remove_small_components(TriMesh& mesh, double min_area) {
  SmallComponents result;
  // Components by flood fill over the faces around each vertex (vertex-connected, as topology() counts them).
  std::vector<int> component(mesh.n_faces(), -1);
  std::vector<double> area;
  std::vector<TriMesh::FaceHandle> stack;
  for (auto seed : mesh.faces()) {
    if (component[static_cast<std::size_t>(seed.idx())] >= 0) continue;
    const int c = static_cast<int>(area.size());
    area.push_back(0);
    component[static_cast<std::size_t>(seed.idx())] = c;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const auto f = stack.back();
      stack.pop_back();
      Vec3 a, b, d;
      geometry::face_points(mesh, f, a, b, d);
      area.back() += geometry::triangle_area(a, b, d);
      for (auto v : mesh.fv_range(f))
        for (auto g : mesh.vf_range(v))
          if (component[static_cast<std::size_t>(g.idx())] < 0) {
            component[static_cast<std::size_t>(g.idx())] = c;
            stack.push_back(g);
          }
    }
  }
  if (area.size() < 2) return result;
  const auto largest = static_cast<int>(std::max_element(area.begin(), area.end()) - area.begin());
  std::vector<char> drop(area.size(), 0);
  for (std::size_t c = 0; c < area.size(); ++c)
    if (static_cast<int>(c) != largest && area[c] < min_area) {
      drop[c] = 1;
      ++result.removed;
      result.area += area[c];
      result.largest = std::max(result.largest, area[c]);
    }
  if (result.removed == 0) return result;
  for (auto f : mesh.faces())
    if (drop[static_cast<std::size_t>(component[static_cast<std::size_t>(f.idx())])]) {
      mesh.delete_face(f, true);  // and its vertices once isolated
      ++result.faces;
    }
  mesh.garbage_collection();
  return result;
}

nlohmann::json to_json(const SmallComponents& s) {
  return {{"removed", s.removed}, {"faces", s.faces}, {"area", s.area}, {"largest", s.largest}};
}

}  // namespace carbonmesh
