#pragma once
// Ears: a triangle with two border edges has one interior edge, so its atom in the dual has a single bond (a carbon
// hanging off the net, which no sp2 structure has; REBO2 leaves it dangling); one with three border edges has none.
// The remesher makes them where a border turns more sharply than its triangles can follow (a corner of a
// triangular flake, 60 degrees: keeping it takes a triangle with both border edges at the corner, and two triangles
// there would have sides under emin). They are taken off the primal mesh before the dual is built.
#include <cstddef>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

struct EarRemoval {
  std::size_t faces = 0;  // triangles removed
  double area = 0;        // their area (mesh units squared)
};

// Deletes every face of `primal` with two or three border edges, and then those that this leaves with two or three,
// until none is left (a strip one triangle wide goes whole); vertices left without a face go too. The mesh is
// garbage collected if anything was removed. Deterministic: faces in index order, then in the order they became
// ears.
EarRemoval remove_ears(TriMesh& primal);

}  // namespace carbonmesh
