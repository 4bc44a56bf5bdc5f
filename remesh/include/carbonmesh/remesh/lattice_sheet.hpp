#pragma once
// A flat surface cut from a triangular lattice (`carbonmesh build --lattice`). The dual of the triangular lattice is
// graphene's honeycomb, so a flat outline (a flake, a ribbon, a sheet with holes) gets a carbon net of hexagons only.
// The remesher cannot give that: its 6-9% irregular vertices are 5-7 pairs in the net (a flat triangle at 3000
// atoms: 51 pentagons, 47 heptagons), and a flat sheet needs none.
#include <cstddef>

#include "carbonmesh/remesh/mesh.hpp"

namespace carbonmesh {

// The plane through the vertices (least squares: the centroid and the direction of least spread) and how far the
// farthest vertex is from it; u, v span the plane and u x v = normal, which points to the side most faces face.
struct Flatness {
  Vec3 centroid{0, 0, 0}, normal{0, 0, 1}, u{1, 0, 0}, v{0, 1, 0};
  double distance = 0;  // mesh units
};

Flatness flatness(const TriMesh& mesh);

struct LatticeSheet {
  TriMesh mesh;           // the lattice triangles inside the outline, every edge `edge` long
  double angle_deg = 0;   // the lattice direction, from the plane's u axis (the longest side's, turned)
  std::size_t dropped = 0;  // triangles inside that were left out where they touched the rest at one vertex only
};

// The triangles of a triangular lattice of edge `edge` in the plane of `flat` whose centroid (the atom of the dual)
// lies in the region its faces cover: the honeycomb sites inside the outline (a notch or hole narrower than about
// one edge is bridged). One lattice line runs along the longest straight side of the outline (consecutive border
// edges in one direction), through its first vertex, so that side is a zigzag edge of the carbon net in its place. Where the kept triangles meet at a vertex only, the
// smaller fans there are left out (the mesh is manifold). The lattice mesh is in the input's units, facing the
// input's side. Throws InputError if `flat` has no border (a flat surface is open) or if `edge` is not positive.
// `turn_deg` turns the lattice about that vertex from the side's direction (counter-clockwise seen from the
// normal): 0 makes that border a zigzag edge, 30 an armchair edge; the lattice repeats every 60 degrees.
LatticeSheet lattice_sheet(const TriMesh& flat, const Flatness& plane, double edge, double turn_deg = 0);

}  // namespace carbonmesh
