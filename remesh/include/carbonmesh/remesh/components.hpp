#pragma once
// Connected components of a mesh, and the removal of those too small to keep (debris of a scan, a stray
// triangle): a component whose edges cannot reach an interval keeps the remesher from converging.
#include <cstddef>

#include <nlohmann/json_fwd.hpp>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct SmallComponents {
  std::size_t removed = 0;  // components deleted
  std::size_t faces = 0;    // their faces
  double area = 0;          // their total area
  double largest = 0;       // the area of the largest of them
};

// Deletes every connected component (by shared edges and vertices) whose area is below `min_area`, and the
// vertices left isolated; the largest component is always kept. Garbage-collects the mesh if anything was
// removed.
SmallComponents remove_small_components(TriMesh& mesh, double min_area);

nlohmann::json to_json(const SmallComponents& s);

}  // namespace carbonmesh
