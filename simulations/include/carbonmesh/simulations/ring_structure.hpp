#pragma once
// Rings of an sp2 carbon structure and their adjacency, from whichever input: a triangle mesh (one ring per
// primal vertex), a polygon mesh (one ring per face: a dual) or an atom graph with its SP rings.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "carbonmesh/remesh/io.hpp"
#include "carbonmesh/remesh/mesh.hpp"
#include "carbonmesh/simulations/atom_graph.hpp"

namespace carbonmesh {

struct RingStructure {
  AtomGraph atoms;                         // atom positions and bonds
  std::vector<std::vector<int>> rings;     // atoms of each ring in cyclic order (open rings: in fan order)
  std::vector<int> sizes;                  // ring size (for a mesh vertex: its valence)
  std::vector<bool> open;                  // ring on a border (not a closed cycle of atoms)
  std::vector<Vec3> centers;               // primal vertex, or the centroid of the ring's atoms
  std::vector<std::vector<int>> neighbors;  // rings sharing a bond (primal edges), sorted
  std::optional<long> euler;               // chi of the surface when known
  bool closed_surface = false;             // no border: every bond in exactly two rings
  std::string source;                      // "triangle mesh", "polygon mesh", "atom graph (SP rings)"

  std::size_t size() const { return rings.size(); }
};

// One ring per primal vertex (size = valence), atoms at face centroids, bonds across interior edges.
RingStructure rings_from_mesh(const TriMesh& mesh);

// One ring per polygon; atoms are the points, bonds the polygon edges. Throws InputError (naming `source`)
// for an index out of range or a repeated corner.
RingStructure rings_from_polygons(const PolygonSoup& soup, const std::string& source);

// Rings given by cycles of an atom graph (e.g. SP rings). Rings are adjacent when they share a bond.
// euler = atoms - bonds + rings; closed_surface when every bond lies on exactly two rings.
RingStructure rings_from_graph(AtomGraph graph, std::vector<std::vector<int>> rings);

}  // namespace carbonmesh
