#pragma once
// Warnings about a surface the carbon net cannot be built on faithfully, shared by the commands.
#include <spdlog/spdlog.h>

#include <string>

#include "carbonmesh/remesh/self_intersections.hpp"

namespace carbonmesh::cli {

// The input passes through itself: the remesh follows it (or bridges the crossing), so its sheets may cross too.
inline SelfIntersections check_input_self_intersections(const TriMesh& mesh, const std::string& source) {
  const SelfIntersections found = self_intersections(mesh);
  if (found.pairs > 0)
    spdlog::warn("{}: the surface passes through itself: {} pair{} of faces intersect ({} faces; e.g. faces {} and "
                 "{}); the remesh may cross itself there too",
                 source, found.pairs, found.pairs == 1 ? "" : "s", found.faces, found.example[0], found.example[1]);
  return found;
}

// The remesh passes through itself (`output` names the file its face indices refer to): a carbon net built on it has
// sheets that cross, atoms of one inside the rings of the other.
inline SelfIntersections check_remesh_self_intersections(const SelfIntersections& found, const std::string& source,
                                                         const std::string& output) {
  if (found.pairs > 0)
    spdlog::warn("{}: the remeshed surface passes through itself: {} pair{} of faces intersect ({} faces; e.g. faces "
                 "{} and {} of {}): carbon sheets built on it cross there",
                 source, found.pairs, found.pairs == 1 ? "" : "s", found.faces, found.example[0], found.example[1],
                 output);
  return found;
}

}  // namespace carbonmesh::cli
